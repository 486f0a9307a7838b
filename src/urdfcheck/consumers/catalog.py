"""The controller catalogue (`controller_types.yaml`, read lazily): what each controller type's parameters mean.

`entry(type, ros)` gives the merged catalogue entry of a type; `apply(controller, names)` reads a controller's
joints, interfaces, <ros2_control> components, frames, odometry transform and wheel set from its parameters
as its entry says. A controller whose type is not in the catalogue is read by the shape of its keys
(`read_by_shape`: *_joint(s), *_joint_name(s), *_frame_id), marked `inferred`: the checks report what that
reading finds as warnings and say that the meaning was inferred.
"""
from __future__ import annotations

import functools
import os

from urdfcheck.consumers.common import Value, as_bool, as_str_list
from urdfcheck.core import lazyre
from urdfcheck.core.findings import Location
from urdfcheck.core.records import TupleRecord


class Component(TupleRecord):
    """A <ros2_control> <sensor>/<gpio> (or any hardware item: kind "any") a controller names."""

    name: str
    loc: Location
    kind: str
    owner: str


class WheelSet(TupleRecord):
    """The wheels of a drive other than diff_drive (steering controllers, tricycle, mecanum), as configured."""

    owner: str
    kind: str  # "steering", "tricycle", "mecanum"
    loc: Location
    traction: tuple  # JointUse
    steering: tuple
    wheelbase: Value | None = None
    track: Value | None = None
    radius: Value | None = None
    projection: Value | None = None  # mecanum: lx + ly
    wheelbase_key: str = "wheelbase"
    track_key: str = ""
    radius_key: str = ""
    projection_key: str = ""
    from_urdf: bool = False  # ROS 1: a wheelbase not set is computed from the URDF by the controller


@functools.lru_cache(maxsize=1)
def catalogue() -> dict:
    import json

    # the JSON twin of controller_types.yaml (tools/catalogues.py writes it): no PyYAML import for our own data
    with open(os.path.join(os.path.dirname(__file__), "controller_types.json"), encoding="utf-8") as f:
        return json.load(f)


def entry(type_name: str, ros: int) -> dict | None:
    """The catalogue entry of a controller type (its base merged in), None when the type is not known."""
    types = catalogue().get("types") or {}
    e = types.get(f"{type_name}@1") if ros == 1 else types.get(type_name)
    if e is None or int(e.get("ros", ros)) != ros:
        return None
    base = e.get("base")
    if base:
        merged = dict((catalogue().get("bases") or {}).get(base) or {})
        for k, v in e.items():
            merged[k] = (merged.get(k) or []) + v if k == "joints" and isinstance(v, list) else v
        e = merged
    return e


def kind_of(type_name: str, ros: int) -> str | None:
    e = entry(type_name, ros)
    return None if e is None else e.get("kind") or "catalogue"


def _strings(v: Value | None) -> list[str] | None:
    if v is None:
        return None
    if isinstance(v.value, str):
        return [v.value] if v.value.strip() else []
    return as_str_list(v.value)


def _interfaces(spec, params: dict) -> tuple[str, ...]:
    if spec is None:
        return ()
    if isinstance(spec, list):
        return tuple(str(x) for x in spec)
    if "switch" in spec:
        v = params.get(spec["switch"])
        on = as_bool(v.value) if v is not None else None
        on = bool(spec.get("default")) if on is None else on
        return tuple(spec.get("true" if on else "false") or ())
    v = params.get(spec.get("param", ""))
    if v is None:
        return tuple(spec.get("default") or ())
    got = _strings(v)
    return tuple(got) if got else ()


def _uses(c, names_set: set, param: str, command=(), state=(), role="joint") -> tuple:
    from urdfcheck.consumers.uses import _joint_uses

    v = c.params.get(param)
    names = _strings(v)
    if not names:
        if v is not None and names is None:
            c.notes.append((f"'{param}' should name joints, got {v.value!r}", v.loc))
        return ()
    return _joint_uses(names, v, c.name, names_set, command, state, role=role)


def apply(c, names_set: set) -> None:
    """Joints, components, frames, odometry and wheels of a controller, as its catalogue entry says."""
    e = entry(c.type, c.ros)
    if e is None:
        return
    p = c.params
    wheel_uses: dict[str, tuple] = {}
    for spec in e.get("joints") or ():
        param = spec["param"]
        command = _interfaces(spec.get("command"), p) if c.ros == 2 else ()
        state = _interfaces(spec.get("state"), p) if c.ros == 2 else ()
        role = "dof" if spec.get("dof") else spec.get("role", "joint")
        uses = _uses(c, names_set, param, command, state, role)
        wheel_uses[param] = uses
        c.joints += uses
    for spec in e.get("components") or ():
        v = p.get(spec["param"])
        for i, name in enumerate(_strings(v) or ()):
            c.components += (Component(name, v.item_loc(i) if isinstance(v.value, list) else v.loc,
                                       spec.get("kind", "any"), c.name),)
    for fp in e.get("frames") or ():
        v = p.get(fp)
        if v is not None and isinstance(v.value, str) and v.value.strip():
            c.frames += (Value(v.value.strip().lstrip("/"), v.loc),)
    odom = e.get("odom_tf")
    if odom and c.odom_tf is None:
        _odom(c, odom)
    drive = e.get("drive")
    if drive:
        c.wheels = _wheelset(c, drive, wheel_uses)


def _odom(c, spec: dict) -> None:
    from urdfcheck.consumers.uses import OdomTF, _norm_frame, _tf_prefix

    p = c.params
    en = p.get(spec["enable"])
    enabled = as_bool(en.value) if en is not None else None
    if enabled is None:
        enabled = bool(spec.get("default"))
    parent_key, parent_default = spec["parent"]
    child_key, child_default = spec["child"]
    pv, cv = p.get(parent_key), p.get(child_key)
    prefix = _tf_prefix(p, c.namespace) if c.ros == 2 else ""
    parent = prefix + _norm_frame(str(pv.value) if pv is not None else parent_default)
    child = prefix + _norm_frame(str(cv.value) if cv is not None else child_default)
    c.odom_tf = OdomTF(parent, child, c.name, en.loc if en is not None else c.loc, enabled)
    c.frames += (Value(child, cv.loc if cv is not None else c.loc, cv is None),)


def _first(p: dict, keys) -> tuple[str, Value | None]:
    for k in ([keys] if isinstance(keys, str) else keys or ()):
        v = p.get(k)
        if v is not None:
            return k, v
    return "", None


def _wheelset(c, spec: dict, uses: dict) -> WheelSet:
    p = c.params

    def joints(keys) -> tuple:
        if spec.get("kind") == "mecanum":  # one parameter per wheel
            return tuple(u for k in keys or () for u in uses.get(k, ()))
        for k in keys or ():  # alternatives: the current name first, then the deprecated one
            if uses.get(k):
                return uses[k]
        return ()

    traction = joints(spec.get("traction"))
    steering = joints(spec.get("steering"))
    if spec.get("kind") == "steering" and "front_steering" in p and not p.get("traction_joints_names"):
        # before Jazzy: front_steering says whether the front or the rear wheels steer
        front = as_bool(p["front_steering"].value)
        rear, fr = uses.get("rear_wheels_names", ()), uses.get("front_wheels_names", ())
        traction, steering = (rear, fr) if front is not False else (fr, rear)
    wk, wb = _first(p, spec.get("wheelbase"))
    tk, tr = _first(p, spec.get("track"))
    rk, rad = _first(p, spec.get("radius"))
    pk, proj = _first(p, spec.get("projection"))
    return WheelSet(c.name, spec.get("kind", ""), c.loc, traction, steering, wb, tr, rad, proj,
                    wk or "wheelbase", tk, rk, pk, bool(spec.get("from_urdf")))


# --- controllers of no known type --------------------------------------------------------------------------
_JOINT_KEY = lazyre.compile(r"(^|_)joints?$|_joint_names?$|_wheel_names$|^joint_names$")
_FRAME_KEY = lazyre.compile(r"_frame_id$|^frame_id$")
_REP105 = ("map", "odom", "earth", "world")  # published by localization and odometry, not by the model


def read_by_shape(c, names_set: set) -> None:
    """A controller type the catalogue does not know: joints and frames from the shape of its keys."""
    from urdfcheck.consumers.uses import _joint_uses

    found = False
    for key, v in sorted(c.params.items()):
        leaf = key.split(".")[-1]
        if key == "type" or "." in key:
            continue
        vals = _strings(v)
        if not vals or not all(x and "$(" not in x and "\x00" not in x for x in vals):
            continue
        if _JOINT_KEY.search(leaf):
            c.joints += _joint_uses(vals, v, c.name, names_set, role="joint")
            found = True
        elif _FRAME_KEY.search(leaf) and isinstance(v.value, str) and v.value.strip("/ ") not in _REP105:
            c.frames += (Value(v.value.strip().lstrip("/"), v.loc),)
            found = True
    if found:
        c.inferred = True
        c.notes.append((f"controller {c.name}: type {c.type} is not in urdfcheck's controller catalogue; its joints "
                        f"and frames were read by the shape of its keys", c.type_loc))
