"""What a controller or driver claims on the model: the joints it uses (with the hardware interfaces) and the
odometry transform it broadcasts; the helpers that read them, shared by the controller reader (`controllers`)
and the controller catalogue (`catalog`)."""
from __future__ import annotations

from collections.abc import Mapping

from urdfcheck.consumers.common import Value, as_bool
from urdfcheck.core.findings import Location
from urdfcheck.core.records import TupleRecord


class JointUse(TupleRecord):
    """A joint a controller or driver commands, and the hardware interfaces it needs on it."""

    joint: str
    loc: Location
    owner: str
    command: tuple[str, ...] = ()
    state: tuple[str, ...] = ()
    role: str = "joint"  # joint, left_wheel, right_wheel
    via: str = ""  # upstream controller when chained (no interface claims then)
    written: str = ""  # the name as written, when it differs (chained)


class OdomTF(TupleRecord):
    """An odom -> base transform a controller or driver broadcasts."""

    parent: str
    child: str
    owner: str
    loc: Location
    enabled: bool = True


def _norm_frame(s: str) -> str:
    return s.strip().lstrip("/")


def _tf_prefix(params: Mapping[str, Value], namespace: str) -> str:
    """diff_drive_controller's frame prefix (Humble..Kilted `tf_frame_prefix_enable`; Lyrical `~`)."""
    enable_v = params.get("tf_frame_prefix_enable")
    prefix_v = params.get("tf_frame_prefix")
    enable = as_bool(enable_v.value) if enable_v is not None else None
    prefix = str(prefix_v.value) if prefix_v is not None and prefix_v.value is not None else ""
    if enable is False:
        return ""
    if "~" in prefix:
        prefix = prefix.replace("~", namespace)
    elif not prefix and enable is True:
        prefix = namespace
    prefix = prefix.strip("/")
    return prefix + "/" if prefix else ""


def _resolve_chain(name: str, controller_names: set[str]) -> tuple[str, str]:
    """'pid_left/left_wheel_joint' -> ('left_wheel_joint', 'pid_left') when pid_left is a controller."""
    via = ""
    parts = name.split("/")
    while len(parts) > 1 and parts[0] in controller_names:
        via = via or parts[0]
        parts = parts[1:]
    return ("/".join(parts), via) if via else (name, "")


def _joint_uses(names: list[str], src: Value | Location, owner: str, names_set: set[str], command=(), state=(),
                role="joint") -> tuple[JointUse, ...]:
    out = []
    for i, n in enumerate(names):
        loc = src.item_loc(i) if isinstance(src, Value) else src
        joint, via = _resolve_chain(n, names_set)
        if via:
            out.append(JointUse(joint, loc, owner, (), (), role, via, n))
        else:
            out.append(JointUse(n, loc, owner, tuple(command), tuple(state), role))
    return tuple(out)
