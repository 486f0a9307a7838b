"""Mutated recordings (issue 36): a real ROS 1 bag and its rosbag2 sqlite3 and MCAP conversions, bytes flipped,
inserted, deleted, lengths set to 0 or 2^32-1, truncated. Every one is a list of findings (B014 when it cannot be
read), never an exception, and no message holds the runner's absolute path. Bounded: ~300 inputs, in process."""
from __future__ import annotations

import os
import shutil
import subprocess
import sys
import tempfile
from pathlib import Path

import pytest

hypothesis = pytest.importorskip("hypothesis")
pytest.importorskip("rosbags")
from hypothesis import HealthCheck, given, settings  # noqa: E402
from hypothesis import strategies as st  # noqa: E402

FIXTURES = Path(__file__).parent.parent / "fixtures" / "ros1"
_SEEDS: dict[str, bytes] = {}


def seeds() -> dict[str, bytes]:
    """suffix -> bytes of the clean recording in that container (converted once per session)."""
    if not _SEEDS:
        if not (FIXTURES / "clean.bag").exists():
            pytest.skip("tests/fixtures/ros1 is absent")
        tmp = Path(tempfile.mkdtemp(prefix="urdfcheck-bagfuzz-"))
        _SEEDS[".bag"] = (FIXTURES / "clean.bag").read_bytes()
        for fmt, suffix in (("sqlite3", ".db3"), ("mcap", ".mcap")):
            subprocess.run([sys.executable, "-m", "rosbags.convert", "--src", str(FIXTURES / "clean.bag"), "--dst",
                            str(tmp / fmt), "--dst-storage", fmt], check=True, capture_output=True)
            (f,) = [p for p in (tmp / fmt).iterdir() if p.suffix == suffix]
            _SEEDS[suffix] = f.read_bytes()
        shutil.rmtree(tmp)
    return _SEEDS


def _model():
    from urdfcheck.model.build import model_from_string

    return model_from_string((FIXTURES / "robot.urdf").read_text())


OPS = st.lists(st.tuples(st.sampled_from(["flip", "insert", "delete", "u32max", "zero", "truncate"]),
                         st.floats(0, 1), st.binary(min_size=1, max_size=16)), min_size=1, max_size=6)


def mutate(data: bytes, ops) -> bytes:
    b = bytearray(data)
    for op, where, blob in ops:
        p = int(where * max(len(b) - 1, 0))
        if op == "flip" and b:
            b[p] ^= blob[0] or 1
        elif op == "insert":
            b[p:p] = blob
        elif op == "delete":
            del b[p:p + len(blob) * 4]
        elif op == "u32max":
            b[p:p + 4] = b"\xff\xff\xff\xff"
        elif op == "zero":
            b[p:p + 8] = bytes(8)
        elif op == "truncate":
            del b[max(p, 8):]
    return bytes(b)


@settings(max_examples=300, deadline=None, suppress_health_check=list(HealthCheck), derandomize=True)
@given(suffix=st.sampled_from([".bag", ".db3", ".mcap"]), ops=OPS)
def test_mutated_recordings_are_findings(suffix, ops):
    from urdfcheck.bag import check_recording

    data = mutate(seeds()[suffix], ops)
    folder = Path(tempfile.mkdtemp(prefix="urdfcheck-bagfuzz-"))
    try:
        path = folder / f"rec{suffix}"
        path.write_bytes(data)
        found = check_recording(_model(), str(path))
        for f in found:
            assert f.code.startswith("B"), f
            assert str(folder) not in f.message and os.path.realpath(str(folder)) not in f.message, f.message
    finally:
        shutil.rmtree(folder)
