"""Controllers (ros2_control / ros_control) and custom drivers, read from parameter files.

ROS 2 (`controller_manager` parameter files)::

    controller_manager:
      ros__parameters:
        update_rate: 100
        diffbot_base_controller:
          type: diff_drive_controller/DiffDriveController      # declared here ...
    diffbot_base_controller:
      ros__parameters:
        type: diff_drive_controller/DiffDriveController        # ... and/or here (Jazzy and later)
        left_wheel_names: [left_wheel_joint]

ROS 1 (`rosparam load`): any mapping with a `type: pkg/Class` entry is a controller named by its key path
("diffbot_controller", "ns/arm_controller").

Several files for the same controller are merged in order (a later file wins), as the controller manager
does with several `--param-file`s or `rosparam load`s; so `diffbot_controllers.yaml` followed by
`diffbot_multipliers.yaml` gives one controller with the multipliers.

Chained controllers (`left_wheel_names: [pid_left/left_wheel_joint]`, where `pid_left` is a declared
controller) resolve to the last joint name; such uses are marked `via` and carry no interface claims
(the interfaces they use are the upstream controller's references).

A *custom driver* (a vendor node that is not a ros2_control controller) is described by key paths in
the config (`DriverSpec`) and read with `read_driver`.
"""
from __future__ import annotations

import os
from collections.abc import Iterable, Mapping, Sequence

from urdfcheck.consumers.common import ConsumerError, Value, as_bool, as_float, as_str_list
from urdfcheck.consumers.params import NodeParams, ParamFile, lookup, merge_nodes, node_key_matches, read_params
from urdfcheck.consumers.uses import JointUse, OdomTF, _joint_uses, _norm_frame, _tf_prefix  # noqa: F401
from urdfcheck.core import lazyre
from urdfcheck.core.findings import Location
from urdfcheck.core.records import Record, TupleRecord

# --- controller kinds --------------------------------------------------------------------------------
# the controller_manager executables that read controller parameter files (a launch node running one)
CONTROLLER_EXES = ("ros2_control_node", "spawner", "spawner.py", "controller_manager")
DIFF_DRIVE = "diff_drive"
JTC = "joint_trajectory"
JSB = "joint_state_broadcaster"
FORWARD = "forward_command"
GROUP = "joint_group"
JSC = "joint_state_controller"  # ROS 1
OTHER = "other"

_ROS2_TYPES = {
    "diff_drive_controller/DiffDriveController": DIFF_DRIVE,
    "joint_trajectory_controller/JointTrajectoryController": JTC,
    "joint_state_broadcaster/JointStateBroadcaster": JSB,
    "forward_command_controller/ForwardCommandController": FORWARD,
    "forward_command_controller/MultiInterfaceForwardCommandController": FORWARD,
    "position_controllers/JointGroupPositionController": GROUP,
    "velocity_controllers/JointGroupVelocityController": GROUP,
    "effort_controllers/JointGroupEffortController": GROUP,
}
_GROUP_INTERFACE = {
    "position_controllers": "position", "velocity_controllers": "velocity", "effort_controllers": "effort",
}
_ROS1_JOINT_PACKAGES = ("position_controllers", "velocity_controllers", "effort_controllers", "pos_vel_controllers",
                        "pos_vel_acc_controllers", "joint_trajectory_controller", "forward_command_controller")
_FRAME_PARAMS = ("frame_id", "sensor_frame_id")  # broadcasters (force/torque, IMU) stamp their messages with these


def kind_of(type_name: str, ros: int) -> str:
    if ros == 2:
        kind = _ROS2_TYPES.get(type_name)
        return kind or _catalogue_kind(type_name, 2) or OTHER
    kind = _catalogue_kind(type_name, 1)
    if kind:
        return kind
    if type_name == "diff_drive_controller/DiffDriveController":
        return DIFF_DRIVE
    if type_name == "joint_state_controller/JointStateController":
        return JSC
    pkg, _, cls = type_name.partition("/")
    if pkg in _ROS1_JOINT_PACKAGES:
        return JTC if "Trajectory" in cls else GROUP
    return OTHER


def _catalogue_kind(type_name: str, ros: int) -> str | None:
    """A family with a reader of its own named by the catalogue (ur_controllers' scaled JTC is a JTC)."""
    from urdfcheck.consumers.catalog import kind_of as catalogue_kind

    kind = catalogue_kind(type_name, ros)
    return None if kind == "catalogue" else kind


class DriveSpec(TupleRecord):
    """What a differential drive (controller or driver) believes about the wheels."""

    owner: str
    loc: Location
    left: tuple[JointUse, ...]
    right: tuple[JointUse, ...]
    left_loc: Location
    right_loc: Location
    wheel_separation: Value | None
    wheel_radius: Value | None
    separation_multiplier: Value | None = None
    left_radius_multiplier: Value | None = None
    right_radius_multiplier: Value | None = None
    wheels_per_side: Value | None = None
    from_urdf: bool = False  # ROS 1: separation/radius not set are computed from the URDF by the controller
    # sided: the configuration names which wheels are left and right (diff drive, Gazebo's diff-drive plugins);
    # False: the sides were taken from the model (steering controllers' traction wheels, mecanum), so wheel
    # counts and swapped sides are not compared, and neither are geometry parameters left unset
    sided: bool = True
    separation_key: str = "wheel_separation"
    radius_key: str = "wheel_radius"

    @staticmethod
    def _num(v: Value | None, default: float = 1.0) -> float | None:
        """A multiplier: `default` when not set, None when set to something that is not a number."""
        return default if v is None else number(v)

    @property
    def separation(self) -> float | None:
        """wheel_separation x wheel_separation_multiplier (None when not set / not a number)."""
        s = number(self.wheel_separation)
        m = self._num(self.separation_multiplier)
        return None if s is None or m is None else s * m

    def radius(self, side: str) -> float | None:
        r = number(self.wheel_radius)
        m = self._num(self.left_radius_multiplier if side == "left" else self.right_radius_multiplier)
        return None if r is None or m is None else r * m

    def multiplier(self, which: str) -> float | None:
        """A multiplier the file sets to a number other than 1 (a declared correction), else None.
        `which`: "separation", "left" or "right"."""
        v = {"separation": self.separation_multiplier, "left": self.left_radius_multiplier,
             "right": self.right_radius_multiplier}[which]
        if v is None or v.default:
            return None
        m = number(v)
        return None if m is None or m == 1.0 else m


# a ROS 1 parameter written `$(optenv NAME default)` (rosparam subst_value, <param value=...>): the default
# is what the controller gets unless the environment sets NAME
_OPTENV = lazyre.compile(r"^\s*\$\(optenv\s+(\S+)\s+([^()\s]+)\s*\)\s*$")


def number(v: Value | None) -> float | None:
    """The number a parameter holds: plain, or the default of `$(optenv NAME default)`; else None."""
    if v is None:
        return None
    f = as_float(v.value)
    if f is None and isinstance(v.value, str):
        m = _OPTENV.match(v.value)
        if m:
            f = as_float(m.group(2))
    return f


def number_text(v: Value | None) -> str:
    """How to print a parameter's number in a message: '0.05', or '0.05 (the default of $(optenv R))'."""
    f = number(v)
    if f is None:
        return "?" if v is None else repr(v.value)
    text = f"{f:.6g}"
    if v is not None and isinstance(v.value, str) and as_float(v.value) is None:
        name = _OPTENV.match(v.value).group(1)
        text += f" (the default of $(optenv {name}))"
    return text


class Controller(Record):
    # name: controller name (node basename)
    # node: fully qualified node key ("/ns/name"), "/name" when not namespaced
    # joints: commanded joints (and, for JSB with a list, the broadcast joints)
    # broadcasts_all: a state broadcaster for every hardware joint
    # state_joints: explicit state-source joints (JSB `joints`)
    # frames: frame ids the controller stamps data with / expects in the tree
    # notes: (message, Location)
    # components: catalog.Component (<ros2_control> sensors/GPIOs it names); wheels: catalog.WheelSet
    # inferred: its type is not in the catalogue; joints and frames were read by key shape
    _fields = ('name', 'node', 'type', 'type_loc', 'loc', 'kind', 'ros', 'file', 'params', 'joints', 'broadcasts_all',
               'state_joints', 'drive', 'odom_tf', 'frames', 'notes', 'components', 'wheels')
    inferred = False
    # configured in a file the deployment loads, while the deployment's spawners (all read) start others: a
    # controller for another launch-argument choice (schunk_svh's left_hand when `control` is right_hand)
    idle = False

    def __init__(self, name: str,
                 node: str,
                 type: str,
                 type_loc: Location,
                 loc: Location,
                 kind: str,
                 ros: int,
                 file: str,
                 params: dict[str, Value] | None = None,
                 joints: tuple[JointUse, ...] = (),
                 broadcasts_all: bool = False,
                 state_joints: tuple[JointUse, ...] = (),
                 drive: DriveSpec | None = None,
                 odom_tf: OdomTF | None = None,
                 frames: tuple[Value, ...] = (),
                 notes: list | None = None,
                 components: tuple = (),
                 wheels=None):
        self.components = components
        self.wheels = wheels
        self.name = name
        self.node = node
        self.type = type
        self.type_loc = type_loc
        self.loc = loc
        self.kind = kind
        self.ros = ros
        self.file = file
        self.params = {} if params is None else params
        self.joints = joints
        self.broadcasts_all = broadcasts_all
        self.state_joints = state_joints
        self.drive = drive
        self.odom_tf = odom_tf
        self.frames = frames
        self.notes = [] if notes is None else notes

    @property
    def namespace(self) -> str:
        ns = self.node.rsplit("/", 1)[0]
        return ns or "/"


class ControllerSet(Record):
    # controllers: by node key
    _fields = ('controllers', 'files', 'notes')

    def __init__(self, controllers: dict[str, Controller], files: tuple[str, ...], notes: list | None = None):
        self.controllers = controllers
        self.files = files
        self.notes = [] if notes is None else notes

    def by_name(self, name: str) -> Controller | None:
        for c in self.controllers.values():
            if c.name == name or c.node == name:
                return c
        return None

    def __iter__(self):
        return iter(self.controllers.values())

    def __len__(self):
        return len(self.controllers)


# --- helpers -----------------------------------------------------------------------------------------
def _is_type_string(v) -> bool:
    return isinstance(v, str) and "/" in v and " " not in v.strip() and not v.strip().startswith("/")


def _str_list(params: Mapping[str, Value], key: str, notes: list) -> tuple[list[str], Value] | None:
    v = params.get(key)
    if v is None:
        return None
    lst = as_str_list(v.value)
    if lst is None:
        if v.value is None:
            return [], v
        notes.append((f"'{key}' should be a list of strings, got {type(v.value).__name__}", v.loc))
        return None
    return lst, v


class _Reader:
    def __init__(self, files: Sequence[ParamFile], launch_types: Mapping[str, Value] | None = None):
        self.files = list(files)
        self.notes: list = []
        self.launch_types = dict(launch_types or {})

    # ROS 2 ---------------------------------------------------------------------------------------
    def ros2(self) -> dict[str, Controller]:
        files = [f for f in self.files if f.dialect == "ros2"]
        nodes = merge_nodes(files)
        declared: dict[str, tuple[str, Value]] = {}  # node key -> (type, type Value)
        for node in nodes.values():
            manager_like = "controller_manager" in node.basename or "update_rate" in node.params
            for pname, v in node.params.items():
                head, dot, tail = pname.rpartition(".")
                if tail != "type" or not head or "." in head or not _is_type_string(v.value):
                    continue
                if not manager_like and v.value not in _ROS2_TYPES:
                    continue
                ckey = (node.namespace.rstrip("/") + "/" + head) if node.namespace != "/" else "/" + head
                declared[ckey] = (str(v.value).strip(), v)
        own: dict[str, tuple[str, Value]] = {}
        for key, node in nodes.items():
            tv = node.params.get("type")
            if tv is None or not _is_type_string(tv.value):
                continue
            t = str(tv.value).strip()
            if key in declared:
                prev_key = key
            else:
                same = [k for k in declared if k.rsplit("/", 1)[-1] == node.basename]
                prev_key = same[0] if len(same) == 1 else None
            if prev_key is not None:
                prev = declared.pop(prev_key)
                if prev[0] != t:
                    self.notes.append((f"controller {node.basename} is declared as {prev[0]} in the controller "
                                       f"manager but as {t} in its own parameters", tv.loc))
            own[key] = (t, tv)
        declared.update(own)
        # a type given by a launch file (spawner -t) declares a controller its parameter file only configures
        for cname, tv in self.launch_types.items():
            if not _is_type_string(tv.value) or any(k.rsplit("/", 1)[-1] == cname for k in declared):
                continue
            keys = [key for key, node in nodes.items() if node.basename == cname and "*" not in key]
            for key in keys or ["/" + cname]:  # a controller with no parameters at all still runs
                declared[key] = (str(tv.value).strip(), tv)
        # a wildcard declaration ("/**/ctrl") applies to every concrete node it matches ("/robot1/ctrl")
        instances: dict[str, tuple[str, Value]] = {}
        for ckey, tv in declared.items():
            if "*" in ckey:
                hits = [k for k in nodes if "*" not in k and k not in declared and node_key_matches(ckey, k)]
                for k in hits:
                    instances.setdefault(k, tv)
                if hits:
                    continue
            instances[ckey] = tv
        wild = [k for k in nodes if "*" in k]
        out: dict[str, Controller] = {}
        for ckey, (tname, tv) in instances.items():
            node = nodes.get(ckey) or self._match_node(nodes, ckey)
            params: dict[str, Value] = {}
            for w in wild:  # rclcpp applies wildcard entries first, the node's own entry last
                if w != ckey and node_key_matches(w, ckey):
                    params.update(nodes[w].params)
            if node is not None:
                params.update(node.params)
            name = ckey.rsplit("/", 1)[-1]
            out[ckey] = Controller(
                name=name, node=ckey, type=tname, type_loc=tv.loc, loc=node.loc if node else tv.loc,
                kind=kind_of(tname, 2), ros=2, file=(node.file if node else tv.loc.file), params=params,
            )
        return out

    @staticmethod
    def _match_node(nodes: dict[str, NodeParams], ckey: str) -> NodeParams | None:
        base = ckey.rsplit("/", 1)[-1]
        for k, n in nodes.items():
            if n.basename == base and k != ckey and "*" not in k:
                return n
        return None

    # ROS 1 ---------------------------------------------------------------------------------------
    def ros1(self) -> dict[str, Controller]:
        files = [f for f in self.files if f.dialect == "ros1"]
        nodes = merge_nodes(files)
        out: dict[str, Controller] = {}
        for key, node in nodes.items():
            for pname, v in node.params.items():
                head, _, tail = pname.rpartition(".")
                if pname != "type" and tail != "type":
                    continue
                if not _is_type_string(v.value):
                    continue
                prefix = head
                ckey = key if not prefix else (key.rstrip("/") + "/" + prefix.replace(".", "/"))
                params = node.sub(prefix) if prefix else {k: x for k, x in node.params.items()}
                name = ckey.rsplit("/", 1)[-1]
                tname = str(v.value).strip()
                out[ckey] = Controller(
                    name=name, node=ckey, type=tname, type_loc=v.loc, loc=node.loc if not prefix else v.loc,
                    kind=kind_of(tname, 1), ros=1, file=v.loc.file, params=params,
                )
        return out


def _finish(c: Controller, names_set: set[str]) -> None:
    p = c.params
    notes = c.notes
    if c.kind == DIFF_DRIVE:
        _finish_diff_drive(c, names_set)
    elif c.kind == JTC:
        joints = _str_list(p, "joints", notes)
        if c.ros == 2:
            cmd = _str_list(p, "command_interfaces", notes)
            st = _str_list(p, "state_interfaces", notes)
            cmd_l = cmd[0] if cmd else []
            st_l = st[0] if st else []
        else:
            pkg = c.type.partition("/")[0]
            cmd_l = ([] if pkg == "joint_trajectory_controller"
                     else [_GROUP_INTERFACE.get(pkg, "")] if pkg in _GROUP_INTERFACE else [])
            st_l = []
        command_joints = _str_list(p, "command_joints", notes) if c.ros == 2 else None
        if command_joints and command_joints[0]:
            # JTC with command_joints (chained after another controller): it reads the states of `joints`
            # and writes its commands to `command_joints`
            c.joints = _joint_uses(command_joints[0], command_joints[1], c.name, names_set, cmd_l, ())
            if joints:
                c.joints += _joint_uses(joints[0], joints[1], c.name, names_set, (), st_l, role="state")
        elif joints:
            c.joints = _joint_uses(joints[0], joints[1], c.name, names_set, cmd_l, st_l)
        else:
            notes.append((f"{c.name}: no 'joints' list", c.loc))
    elif c.kind == FORWARD:
        iface = p.get("interface_name")
        joints = _str_list(p, "joints", notes)
        if joints is None and "joint" in p and isinstance(p["joint"].value, str):  # MultiInterface
            ifaces = _str_list(p, "interface_names", notes)
            c.joints = _joint_uses([p["joint"].value], p["joint"], c.name, names_set, ifaces[0] if ifaces else ())
        elif joints:
            cmd = [str(iface.value)] if iface is not None and iface.value else []
            c.joints = _joint_uses(joints[0], joints[1], c.name, names_set, cmd)
    elif c.kind == GROUP:
        pkg = c.type.partition("/")[0]
        iface = _GROUP_INTERFACE.get(pkg, "")
        joints = _str_list(p, "joints", notes)
        if joints is None and "joint" in p and isinstance(p["joint"].value, str):
            joints = ([p["joint"].value], p["joint"])
        if joints:
            c.joints = _joint_uses(joints[0], joints[1], c.name, names_set, [iface] if iface and c.ros == 2 else [])
    elif c.kind == JSB:
        joints = _str_list(p, "joints", notes)
        ifaces = _str_list(p, "interfaces", notes)
        if joints and joints[0]:
            c.state_joints = _joint_uses(joints[0], joints[1], c.name, names_set, (), ifaces[0] if ifaces else ())
        else:
            c.broadcasts_all = True
        # extra_joints are published with a zero state (joint_state_broadcaster userdoc) and need no hardware
        # interface: a state source for those joints, with no interface claims
        extra = _str_list(p, "extra_joints", notes)
        if extra and extra[0]:
            c.state_joints += _joint_uses(extra[0], extra[1], c.name, set(), (), (), role="extra")
    elif c.kind == JSC:
        c.broadcasts_all = True
        # ROS 1 joint_state_controller's extra_joints: [{name:, position:, ...}] published with those values
        # (a passive caster's joints): state sources, with no interface claims
        v = p.get("extra_joints")
        items = v.value if v is not None and isinstance(v.value, list) else []
        names = [i if isinstance(i, str) else i.get("name") for i in items[:1000] if isinstance(i, (str, dict))]
        names = [n for n in names if isinstance(n, str) and n]
        if names:
            c.state_joints += _joint_uses(names, v, c.name, set(), (), (), role="extra")
    elif c.kind == OTHER:
        from urdfcheck.consumers import catalog

        if catalog.entry(c.type, c.ros) is not None:
            catalog.apply(c, names_set)
        else:
            catalog.read_by_shape(c, names_set)
    # any controller: odometry of other drive types, and stamped frames
    if c.kind != DIFF_DRIVE and c.odom_tf is None:
        en = p.get("enable_odom_tf")
        if en is not None and as_bool(en.value) and ("odom_frame_id" in p or "base_frame_id" in p):
            prefix = _tf_prefix(p, c.namespace) if c.ros == 2 else ""
            odom = p.get("odom_frame_id")
            base = p.get("base_frame_id")
            c.odom_tf = OdomTF(prefix + _norm_frame(str(odom.value) if odom else "odom"),
                               prefix + _norm_frame(str(base.value) if base else "base_link"), c.name, en.loc)
            if base is not None:
                c.frames += (Value(c.odom_tf.child, base.loc),)
    for fp in _FRAME_PARAMS:
        v = p.get(fp)
        if v is not None and isinstance(v.value, str) and v.value.strip():
            c.frames += (Value(_norm_frame(v.value), v.loc),)


def finish_controller(c: Controller, controller_names: set[str]) -> None:
    """Derive joints, drive, odometry and frames of a controller from its `params` (after they changed)."""
    _finish(c, controller_names)


def _finish_diff_drive(c: Controller, names_set: set[str]) -> None:
    p = c.params
    notes = c.notes
    if c.ros == 2:
        lk, rk = "left_wheel_names", "right_wheel_names"
        feedback = as_bool(p["position_feedback"].value) if "position_feedback" in p else True
        cmd, st = ("velocity",), ("position" if feedback is not False else "velocity",)
    else:
        lk, rk = "left_wheel", "right_wheel"
        cmd, st = (), ()
    sides = {}
    for side, key in (("left", lk), ("right", rk)):
        got = _str_list(p, key, notes)
        if got is None:
            if key not in p:
                notes.append((f"{c.name}: '{key}' is not set", c.loc))
            sides[side] = ((), c.loc)
        else:
            sides[side] = (_joint_uses(got[0], got[1], c.name, names_set, cmd, st, role=f"{side}_wheel"), got[1].loc)
    c.joints = sides["left"][0] + sides["right"][0]

    def val(key: str, default=None) -> Value | None:
        if key in p:
            return p[key]
        return None if default is None else Value(default, c.loc, default=True)

    if c.ros == 1:
        base_mult = val("wheel_radius_multiplier", 1.0)
        lmult = p.get("left_wheel_radius_multiplier", base_mult)
        rmult = p.get("right_wheel_radius_multiplier", base_mult)
    else:
        lmult = val("left_wheel_radius_multiplier", 1.0)
        rmult = val("right_wheel_radius_multiplier", 1.0)
    c.drive = DriveSpec(
        owner=c.name, loc=c.loc, left=sides["left"][0], right=sides["right"][0],
        left_loc=sides["left"][1], right_loc=sides["right"][1],
        wheel_separation=val("wheel_separation"), wheel_radius=val("wheel_radius"),
        separation_multiplier=val("wheel_separation_multiplier", 1.0),
        left_radius_multiplier=lmult, right_radius_multiplier=rmult,
        wheels_per_side=val("wheels_per_side"), from_urdf=(c.ros == 1),
    )
    prefix = _tf_prefix(p, c.namespace) if c.ros == 2 else ""
    odom_v = val("odom_frame_id", "odom")
    base_v = val("base_frame_id", "base_link")
    en_v = val("enable_odom_tf", True)
    enabled = as_bool(en_v.value)
    if enabled is None:
        notes.append((f"{c.name}: enable_odom_tf is not a boolean: {en_v.value!r}", en_v.loc))
        enabled = True
    odom = prefix + _norm_frame(str(odom_v.value))
    base = prefix + _norm_frame(str(base_v.value))
    c.odom_tf = OdomTF(odom, base, c.name, en_v.loc, enabled)
    c.frames += (Value(base, base_v.loc, base_v.default),)


def read_controllers(files: Iterable[ParamFile | str | os.PathLike],
                     launch_types: Mapping[str, Value] | None = None) -> ControllerSet:
    """Controllers declared in parameter files (merged in order). Paths are read; ConsumerError propagates.

    `launch_types`: controller name -> its type given by a launch file (`spawner NAME -t TYPE`,
    `spawner_types`); it declares the controller the parameter files configure without a `type`."""
    pfs = [f if isinstance(f, ParamFile) else read_params(f) for f in files]
    r = _Reader(pfs, launch_types)
    ctrls = {**r.ros1(), **r.ros2()}
    names = {c.name for c in ctrls.values()}
    for c in ctrls.values():
        _finish(c, names)
    notes = list(r.notes)
    for pf in pfs:
        notes.extend(pf.notes)
    return ControllerSet(ctrls, tuple(pf.path for pf in pfs), notes)


_SPAWNERS = ("spawner", "spawner.py")
_SPAWNER_VALUE_FLAGS = ("-c", "--controller-manager", "-p", "--param-file", "-n", "--namespace",
                        "--controller-manager-timeout", "--switch-timeout", "--service-call-timeout",
                        "--controller-ros-args", "--ns", "--timeout", "--shutdown-timeout")


def spawner_types(launch_infos) -> dict[str, Value]:
    """Controller name -> type given on a ROS 2 spawner's command line (`spawner NAME -t TYPE`; "if not
    provided it should exist in the controller manager namespace", controller_manager userdoc), from the
    launch files read (`launch.LaunchInfo.nodes`; arguments not literal are skipped)."""
    out: dict[str, Value] = {}
    for li in launch_infos:
        for node in getattr(li, "nodes", ()):
            if node.package != "controller_manager" or node.executable not in _SPAWNERS or not node.args:
                continue
            toks, names, ctype = list(node.args), [], None
            i = 0
            while i < len(toks):
                t = toks[i]
                if t in ("-t", "--controller-type") and i + 1 < len(toks):
                    ctype = toks[i + 1]
                    i += 2
                elif t in _SPAWNER_VALUE_FLAGS:
                    i += 2
                elif t.startswith("-") or "\x00" in t:
                    i += 1
                else:
                    names.append(t)
                    i += 1
            if ctype and "\x00" not in ctype:
                for n in names:
                    out.setdefault(n, Value(ctype, node.loc))
    return out


# --- custom drivers ----------------------------------------------------------------------------------
class DriverSpec(TupleRecord):
    """How to read a custom driver's parameter file: key paths (dotted) into the node's parameters."""

    file: str
    node: str = ""
    name: str = ""
    joints: tuple[str, ...] = ()
    left_wheels: tuple[str, ...] = ()
    right_wheels: tuple[str, ...] = ()
    wheel_separation: str | None = None
    wheel_radius: str | None = None
    frames: tuple[str, ...] = ()
    odom_tf: str | None = None
    odom_frame: str | None = None
    base_frame: str | None = None
    loc: Location | None = None  # where the spec was written (the config)


class Driver(Record):
    # missing: (key path, Location of the spec): described but not in the file
    _fields = ('name', 'file', 'loc', 'joints', 'drive', 'frames', 'odom_tf', 'missing', 'notes')

    def __init__(self, name: str,
                 file: str,
                 loc: Location,
                 joints: tuple[JointUse, ...] = (),
                 drive: DriveSpec | None = None,
                 frames: tuple[Value, ...] = (),
                 odom_tf: OdomTF | None = None,
                 missing: list | None = None,
                 notes: list | None = None):
        self.name = name
        self.file = file
        self.loc = loc
        self.joints = joints
        self.drive = drive
        self.frames = frames
        self.odom_tf = odom_tf
        self.missing = [] if missing is None else missing
        self.notes = [] if notes is None else notes


def read_driver(spec: DriverSpec, files: Sequence[ParamFile] | None = None) -> Driver:
    """Read a custom driver described by `spec`. Raises ConsumerError when its file cannot be read."""
    pfs = list(files) if files is not None else [read_params(spec.file)]
    name = spec.name or spec.node or os.path.splitext(os.path.basename(spec.file))[0]
    drv = Driver(name, spec.file, Location(spec.file))
    spec_loc = spec.loc or Location(spec.file)

    def get(key: str | None) -> Value | None:
        if not key:
            return None
        v = lookup(pfs, key, spec.node)
        if v is None:
            drv.missing.append((key, spec_loc))
        return v

    def names(keys: Sequence[str], role: str) -> tuple[JointUse, ...]:
        out = []
        for k in keys:
            v = get(k)
            if v is None:
                continue
            lst = as_str_list(v.value)
            if lst is None:
                drv.notes.append((f"driver key '{k}' should name joints, got {v.value!r}", v.loc))
                continue
            out.extend(JointUse(n, v.item_loc(i) if isinstance(v.value, list) else v.loc, name, role=role)
                       for i, n in enumerate(lst))
        return tuple(out)

    left = names(spec.left_wheels, "left_wheel")
    right = names(spec.right_wheels, "right_wheel")
    others = names(spec.joints, "joint")
    seen = {(j.joint, j.loc) for j in left + right}
    drv.joints = left + right + tuple(j for j in others if (j.joint, j.loc) not in seen)
    if spec.wheel_separation or spec.wheel_radius or left or right:
        drv.drive = DriveSpec(
            owner=name, loc=drv.loc, left=left, right=right,
            left_loc=left[0].loc if left else spec_loc, right_loc=right[0].loc if right else spec_loc,
            wheel_separation=get(spec.wheel_separation), wheel_radius=get(spec.wheel_radius),
        )
    for k in spec.frames:
        v = get(k)
        if v is not None:
            if isinstance(v.value, str) and v.value.strip():
                drv.frames += (Value(_norm_frame(v.value), v.loc),)
            else:
                drv.notes.append((f"driver key '{k}' should be a frame id, got {v.value!r}", v.loc))
    if spec.odom_tf:
        v = get(spec.odom_tf)
        if v is not None:
            on = as_bool(v.value)
            if on is None:
                drv.notes.append((f"driver key '{spec.odom_tf}' should be a boolean, got {v.value!r}", v.loc))
            odom = get(spec.odom_frame) if spec.odom_frame else None
            base = get(spec.base_frame) if spec.base_frame else None
            drv.odom_tf = OdomTF(
                _norm_frame(str(odom.value)) if odom is not None else "odom",
                _norm_frame(str(base.value)) if base is not None else "",  # "": the configured base frame
                name, v.loc, bool(on),
            )
            if base is not None:
                drv.frames += (Value(drv.odom_tf.child, base.loc),)
    return drv


def load_controllers(paths: Iterable[str | os.PathLike]) -> tuple[ControllerSet, list[ConsumerError]]:
    """Read what can be read; unreadable files come back as errors (reported as C007)."""
    pfs, errors = [], []
    for p in paths:
        try:
            pfs.append(read_params(p))
        except ConsumerError as e:
            errors.append(e)
    return read_controllers(pfs), errors
