"""core.bytescan answers exactly what bytes.find answers, whatever the anchor and however often it occurs."""
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from urdfcheck.core import bytescan

# a small alphabet makes anchors, near misses and overlaps common
_DATA = st.binary(max_size=300).map(lambda b: bytes(c % 4 + 0x3c for c in b))
_NEEDLE = st.binary(min_size=1, max_size=4).map(lambda b: bytes(c % 4 + 0x3c for c in b))


@settings(max_examples=400, deadline=None)
@given(data=_DATA, needle=_NEEDLE, start=st.integers(-5, 320), anchor=st.integers(0, 3))
def test_find_is_bytes_find(data, needle, start, anchor):
    anchor %= len(needle)
    assert bytescan.find(data, needle, start, anchor) == data.find(needle, max(start, 0))
    assert bytescan.has(data, needle, anchor) == (needle in data)


@settings(max_examples=200, deadline=None)
@given(data=_DATA, needle=_NEEDLE, start=st.integers(0, 320), anchor=st.integers(0, 3))
def test_find_after_the_hop_limit(data, needle, start, anchor):
    anchor %= len(needle)
    saved, bytescan.MAX_HOPS = bytescan.MAX_HOPS, 2  # the general search takes over after two anchor hits
    try:
        assert bytescan.find(data, needle, start, anchor) == data.find(needle, start)
    finally:
        bytescan.MAX_HOPS = saved


def test_a_document_full_of_the_anchor_is_searched_once():
    data = b"&" * 1_000_000 + b"&#"
    hops = []
    real = bytes.find

    class Counting(bytes):
        def find(self, *a):
            hops.append(a)
            return real(self, *a)

    assert bytescan.find(Counting(data), b"&#") == 1_000_000
    assert len(hops) <= bytescan.MAX_HOPS + 2


def test_anchor_outside_the_needle():
    with pytest.raises(ValueError):
        bytescan.find(b"abc", b"b", 0, 1)
