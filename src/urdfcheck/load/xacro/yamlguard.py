"""Refuse YAML files that would blow up when xacro loads them (size, nesting, alias bombs): the refusal worded for
xacro's `load_yaml`, a recording and rosbag2's metadata (X012); the guard and its limits are `core.yamldoor`'s."""
from __future__ import annotations

from urdfcheck.core import yamldoor

LIMITS = yamldoor.XACRO
MAX_BYTES = LIMITS.max_bytes


class YamlRefused(Exception):
    def __init__(self, message: str):
        super().__init__(message)
        self.code = "X012"
        self.message = message


def check_yaml_text(text: str, name: str = "YAML") -> None:
    try:
        yamldoor.check(text, LIMITS)
    except yamldoor.Refused as e:
        if e.what == "size":
            raise YamlRefused(f"{name} is larger than {e.limit} bytes") from None
        if e.what == "depth":
            raise YamlRefused(f"{name} nests deeper than {e.limit} levels") from None
        raise YamlRefused(f"{name} expands to more than {e.limit} nodes through aliases (a YAML bomb)") from None
