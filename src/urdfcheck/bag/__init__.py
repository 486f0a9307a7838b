"""Recorded data against the model: JointState and TF messages of a recording checked against the URDF.

    from urdfcheck.bag import check_recording
    findings = check_recording(model, "run1.mcap")      # list[Finding], located in the recording

A stage of its own above the publisher (it replays the recording's joint states through the built-in
robot_state_publisher): `urdfcheck bag` and a model's `bags:` in urdfcheck.yaml both call `check_recording`.
Recordings are read by urdfcheck's own readers (bag.containers, bag.decode) through core.door; lz4 and zstd
are imported only when a chunk needs them.
"""
from __future__ import annotations

from urdfcheck.bag.check import CODES, BagOptions, check_recording

__all__ = ["check_recording", "BagOptions", "CODES"]
