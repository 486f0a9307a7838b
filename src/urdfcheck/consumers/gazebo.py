"""Gazebo classic plugins and gz-sim systems in the model's <gazebo> blocks, read as the catalogue's `plugins:`
section says (`controller_types.yaml`): the odometry transforms they broadcast (TF owners, with the element
that turns the transform on and its default), the wheel geometry they are told (compared with the model like a
diff drive controller's), and the joint states they publish (C003).

A plugin runs only where the simulator runs. Its transforms are counted together with the controllers' only
when the controllers run in the simulator too (`controllers_in_sim`: the model loads gazebo_ros2_control,
gz_ros2_control or gazebo_ros_control); a real robot's controller YAML in the same package is not a second owner
of the plugin's edge.
"""
from __future__ import annotations

import os
import re

from urdfcheck.consumers.catalog import catalogue
from urdfcheck.consumers.common import Value, as_bool, as_float
from urdfcheck.consumers.controllers import DriveSpec, JointUse, OdomTF
from urdfcheck.core import lazyre
from urdfcheck.core.records import TupleRecord

SOURCE = "gazebo"  # TFClaim.source of a plugin's transform
_CONTROL_PLUGINS = ("gazebo_ros2_control", "gz_ros2_control", "ign_ros2_control", "gazebo_ros_control")


class PluginOwner(TupleRecord):
    plugin: object  # model.robot.GazeboPlugin
    key: str
    label: str
    odom: OdomTF | None = None
    drive: DriveSpec | None = None
    state_joints: tuple[str, ...] | None = None  # None: publishes none; (): all joints
    wheel_tf: bool = False  # broadcasts each wheel joint's parent -> child link itself
    wheel_states: bool = False  # publishes the wheel joints' states itself (ROS 1 publishWheelJointState)


def _key(p) -> str | None:
    table = catalogue().get("plugins") or {}
    aliases = catalogue().get("aliases") or {}
    for raw in (p.filename, p.name):
        name = os.path.basename(raw.strip())
        name = re.sub(r"^lib", "", name)
        name = re.sub(r"\.so$", "", name)
        name = re.sub(r"^(?:gz-sim|ignition-gazebo)\d*-", "gz-sim-", name)
        name = aliases.get(name, name)
        if name in table:
            return name
    return None


def _names(p, names) -> tuple[str, ...]:
    """The element names a plugin reads: a gazebo_ros plugin with a <ros> element is the ROS 2 build, which reads
    only the snake_case names (ROS 1's camelCase ones are ignored there, and their defaults apply)."""
    if p.get("ros") is not None:
        return tuple(n for n in names if n == n.lower())
    return tuple(names)


def _param(p, names):
    names = _names(p, names or ())
    return p.get(*names) if names else None


def _label(p) -> str:
    return f"Gazebo plugin {os.path.basename(p.filename) or p.name}" + (f" ({p.name})" if p.name else "")


def read_plugins(model) -> list[PluginOwner]:
    table = catalogue().get("plugins") or {}
    out = []
    for p in model.plugins:
        key = _key(p)
        if key is None:
            continue
        spec = table[key] or {}
        label = _label(p)
        odom = _odom(p, spec.get("odom_tf"), label)
        drive = _drive(p, spec.get("drive"), label)
        states = _states(p, spec.get("joint_states"), drive)
        wheel_tf, wheel_states = _wheel_tf(p, spec.get("wheel_tf"))
        out.append(PluginOwner(p, key, label, odom, drive, states, wheel_tf and drive is not None, wheel_states))
    return out


def _odom(p, spec, label: str) -> OdomTF | None:
    if not spec:
        return None
    (pnames, pdefault), (cnames, cdefault) = spec["parent"], spec["child"]
    parent, child = _param(p, pnames), _param(p, cnames)
    if spec.get("explicit") and (parent is None or child is None or not parent.text or not child.text):
        return None
    en = _param(p, spec.get("enable"))
    on = as_bool(en.text) if en is not None else None
    on = bool(spec.get("default", True)) if on is None else on
    for g in p.all(*_names(p, spec.get("gate", ()))):
        on = on and as_bool(g.text) is not False
    loc = en.loc if en is not None else p.loc
    return OdomTF((parent.text if parent is not None and parent.text else pdefault).strip("/"),
                  (child.text if child is not None and child.text else cdefault).strip("/"), label, loc, on)


def _flag(p, names, default: bool) -> bool:
    el = _param(p, names)
    on = as_bool(el.text) if el is not None else None
    return default if on is None else on


def _wheel_tf(p, spec) -> tuple[bool, bool]:
    if not spec:
        return False, False
    return _flag(p, spec.get("enable"), bool(spec.get("default"))), _flag(p, spec.get("states"), False)


def _drive(p, spec, label: str) -> DriveSpec | None:
    if not spec:
        return None
    left = tuple(JointUse(x.text, x.loc, label, role="left_wheel") for x in p.all(*_names(p, spec["left"])) if x.text)
    right = tuple(JointUse(x.text, x.loc, label, role="right_wheel")
                  for x in p.all(*_names(p, spec["right"])) if x.text)
    if not left and not right:
        return None
    sep = _param(p, spec.get("separation"))
    rad = _param(p, spec.get("radius"))
    skey = sep.tag if sep is not None else f"{spec['separation'][0]} (not set: the plugin's default)"
    sep_v = Value(sep.text, sep.loc) if sep is not None else Value(spec.get("separation_default"), p.loc, True)
    if rad is not None:
        r = as_float(rad.text)
        rkey = rad.tag + ("/2" if spec.get("diameter") else "")
        rad_v = Value(r / 2 if r is not None and spec.get("diameter") else rad.text, rad.loc)
    else:
        d = spec.get("radius_default")
        rkey = f"{spec['radius'][0]}{'/2' if spec.get('diameter') else ''} (not set: the plugin's default)"
        rad_v = Value(d / 2 if spec.get("diameter") else d, p.loc, True)
    return DriveSpec(owner=label, loc=p.loc, left=left, right=right,
                     left_loc=left[0].loc if left else p.loc, right_loc=right[0].loc if right else p.loc,
                     wheel_separation=sep_v, wheel_radius=rad_v, separation_key=skey, radius_key=rkey)


def _states(p, spec, drive: DriveSpec | None) -> tuple[str, ...] | None:
    if not spec:
        return None
    if "enable" in spec:
        en = _param(p, spec["enable"])
        on = as_bool(en.text) if en is not None else None
        if not (bool(spec.get("default")) if on is None else on):
            return None
    if spec.get("joints") == "drive":
        return tuple(u.joint for u in (drive.left + drive.right)) if drive is not None else None
    names = []
    for x in p.all(*_names(p, spec["joints"])):
        names.extend(n.strip() for n in x.text.split(",") if n.strip())  # ROS 1 jointName: "a, b, c"
    return tuple(names)


# --- what the checks use ---------------------------------------------------------------------------------------
def plugin_drives(model):
    for o in read_plugins(model):
        if o.drive is not None:
            yield o.drive, (o.odom.child if o.odom is not None else None)


def plugin_claims(model) -> list:
    from urdfcheck.consumers.tfclaims import DYNAMIC, TFClaim

    plugins = read_plugins(model)
    out = [TFClaim(o.odom.parent, o.odom.child, o.label, DYNAMIC, o.odom.loc, SOURCE)
           for o in plugins if o.odom is not None and o.odom.enabled]
    for o in plugins:
        if not o.wheel_tf:
            continue
        # the wheel edges are robot_state_publisher's too once the wheel joints' states reach it: from another
        # plugin of the model (gazebo_ros_joint_state_publisher) or this one's own joint states. Without a state
        # supplier, the plugin's wheel transforms are the only ones and nothing is duplicated.
        stated = set()
        for other in plugins:
            if other is not o and other.state_joints is not None:
                stated.update(other.state_joints or (j.name for j in model.joint_list))
        for u in o.drive.left + o.drive.right:
            j = model.joints.get(u.joint)
            if j is None or j.parent is None or j.child is None or not (o.wheel_states or u.joint in stated):
                continue
            out.append(TFClaim(j.parent, j.child, o.label, DYNAMIC, u.loc, SOURCE))
    return out


def state_joints(model) -> tuple[bool, set[str]]:
    """(every joint covered, joints named) by the joint-state publishing plugins."""
    every, named = False, set()
    for o in read_plugins(model):
        if o.state_joints is None:
            continue
        if not o.state_joints and o.key != "gazebo_ros_diff_drive":
            every = True
        named.update(o.state_joints)
    return every, named


def controllers_in_sim(model) -> bool:
    """The model loads ros2_control (or ROS 1 ros_control) into the simulator: its controllers run there."""
    return any(any(k in (p.filename + " " + p.name) for k in _CONTROL_PLUGINS) for p in model.plugins)


_SIM_PACKAGES = ("gazebo_ros", "ros_gz_sim", "ros_ign_gazebo", "gazebo_ros2_control")
_SIM_INCLUDE = lazyre.compile(r"(gazebo|gz_sim|ign_gazebo)[^/]*\.launch", re.I)


def launch_starts_sim(launch_infos) -> bool:
    """A launch file read starts the simulator or spawns the model into it (gazebo_ros spawn_entity.py, ros_gz_sim
    create, an include of gazebo.launch.py / gz_sim.launch.py)."""
    for li in launch_infos:
        if any(n.package in _SIM_PACKAGES for n in getattr(li, "nodes", ())):
            return True
        if any(inc.file and _SIM_INCLUDE.search(os.path.basename(inc.file)) for inc in getattr(li, "includes", ())):
            return True
    return False
