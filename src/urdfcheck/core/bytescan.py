"""Searching large documents for markers that are rare in robot descriptions ("&#", "<?", "<!DOCTYPE").

CPython finds one byte with memchr (about 15 GB/s here) but a longer needle with its general search (about
1 GB/s): on a 9 MB URDF, `b"&#" in data` costs 10 ms and finding "&" then checking the next byte 0.6 ms. The
pre-checks of a large plain URDF ask a handful of such questions before the model is built.
"""
from __future__ import annotations

# anchor hits checked one by one before the general search takes over: a document full of the anchor byte
# (hostile or odd) then costs what `bytes.find` costs, never a Python loop per byte
MAX_HOPS = 256


def find(data: bytes, needle: bytes, start: int = 0, anchor: int = 0) -> int:
    """`data.find(needle, start)`, looking first for `needle[anchor]`: choose the needle's rarest byte."""
    if not 0 <= anchor < len(needle):
        raise ValueError("anchor must index the needle")
    start = max(start, 0)
    key = needle[anchor:anchor + 1]
    i = data.find(key, start + anchor)
    for _ in range(MAX_HOPS):
        if i < 0:
            return -1
        if data.startswith(needle, i - anchor):
            return i - anchor
        i = data.find(key, i + 1)
    return data.find(needle, i - anchor) if i >= 0 else -1


def has(data: bytes, needle: bytes, anchor: int = 0) -> bool:
    """`needle in data` (see `find`)."""
    return find(data, needle, 0, anchor) >= 0
