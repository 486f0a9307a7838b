"""What a launch file says, as every launch reader (XML/YAML in `launch`, Python in `pylaunch`) records it: the
result records, the model a robot_state_publisher is given, static transform arguments, and how one node is filed
into a `LaunchInfo`. The readers import this module; it imports none of them (no import cycle between the
readers).
"""
from __future__ import annotations

import math
import os
from collections.abc import Mapping

from urdfcheck.consumers.common import Value
from urdfcheck.core import geometry
from urdfcheck.core.findings import Location
from urdfcheck.core.records import TYPE_CHECKING, FrozenRecord, Record, TupleRecord

if TYPE_CHECKING:
    from typing import Any

UNKNOWN = "\x00"  # a piece of a string decided at launch time


class Declared(TupleRecord):
    """A launch argument as the deployment finder reads it: its default and, where declared, its choices."""
    default: str | None  # None: no default
    choices: tuple | None
    loc: Location


class ModelRef(TupleRecord):
    """The model a robot_state_publisher gets: `path` (may hold UNKNOWN pieces), xacro `args` (values may hold
    UNKNOWN), `how`: "xacro" (expanded) or "file" (read as is)."""
    path: str
    args: tuple  # ((name, value), ...)
    how: str
    loc: Location



def _xacro_at(toks: list) -> int | None:
    """The index of the xacro executable among a command's tokens (the last of a run of them), or None."""
    names = ("xacro", "xacro.py")
    first = next((i for i, t in enumerate(toks[:8]) if os.path.basename(t) in names), None)
    if first is None:
        return None
    while first + 1 < len(toks) and os.path.basename(toks[first + 1]) in names:
        first += 1
    return first


def command_model(text: str, loc: Location) -> ModelRef | None:
    """`xacro FILE a:=b ...` (or `cat FILE`) -> ModelRef. Tokens are split on whitespace (launch joins the
    pieces and the shell splits them; quoting in robot descriptions is rare)."""
    toks = text.replace("'", " ").replace('"', " ").split()
    if not toks:
        return None
    exe = os.path.basename(toks[0])
    at = _xacro_at(toks)
    if at is not None:  # xacro itself, or run by a wrapper (`env_run CONFIG xacro FILE`, `ros2 run xacro xacro FILE`)
        path, args = None, []
        for t in toks[at + 1:]:
            if ":=" in t:
                k, _, v = t.partition(":=")
                if k and not k.startswith("_"):
                    args.append((k, v))
            elif t.startswith("-"):
                continue
            elif path is None:
                path = t
        return ModelRef(path, tuple(args), "xacro", loc) if path else None
    if exe == "cat" and len(toks) == 2:
        return ModelRef(toks[1], (), "file", loc)
    return None


# --- results -----------------------------------------------------------------------------------------
class StaticTF(TupleRecord):
    parent: str
    child: str
    xyz: tuple[float, float, float]
    rpy: tuple[float, float, float]
    loc: Location
    source_file: str
    condition: str | None = None  # an if/unless we could not decide
    node_name: str = ""


class StatePublisher(TupleRecord):
    """A robot_state_publisher node."""

    name: str
    namespace: str
    frame_prefix: str | None  # None: set but not literal; "" when not set
    loc: Location
    source_file: str
    prefix_loc: Location | None = None
    condition: str | None = None
    description: Any = None  # pylaunch.ModelRef: the model it publishes, when the launch file says
    description_key: str | None = None  # ROS 1: the global parameter it reads the model from, when not found
    unread: str = ""  # when `description` is None: the construct the model comes from, which is not read (C021)


class JointStatePublisher(TupleRecord):
    name: str
    package: str
    loc: Location
    source_file: str
    condition: str | None = None


class LaunchNode(FrozenRecord):
    # args: None: not literal
    # params: literal inline parameters
    _fields = ('package', 'executable', 'name', 'namespace', 'args', 'loc', 'params', 'param_files', 'condition')

    def __init__(self, package: str,
                 executable: str,
                 name: str,
                 namespace: str,
                 args: tuple[str, ...] | None,
                 loc: Location,
                 params: Mapping[str, Value] | None = None,
                 param_files: tuple[str, ...] = (),
                 condition: str | None = None):
        d = self.__dict__  # FrozenRecord forbids setattr
        d["package"] = package
        d["executable"] = executable
        d["name"] = name
        d["namespace"] = namespace
        d["args"] = args
        d["loc"] = loc
        d["params"] = {} if params is None else params
        d["param_files"] = param_files
        d["condition"] = condition


class ParamSet(TupleRecord):
    """A literal parameter written by a ROS 1 launch file: `name` is global ("/ns/ctrl/wheel_separation")."""

    name: str
    value: Value
    order: int


class RosparamLoad(TupleRecord):
    """`<rosparam command="load" file=... ns=...>` in a ROS 1 launch file; `ns` is global ("/" at the top)."""

    file: str
    ns: str
    loc: Location
    order: int
    subst: tuple | None = None  # subst_value="true": ((arg, value), ...) its $(arg ...) take


class Include(TupleRecord):
    """An <include> of another launch file. `file`: None when not literal. `args`: what the included file sees
    (value None: not literal). `condition`: an if/unless, its own or a group's, that could not be decided.
    `package` and `name`: where a file outside the workspace would be (a known driver's launch file)."""

    file: str | None
    loc: Location
    args: Mapping[str, str | None]
    condition: str | None = None
    package: str | None = None  # file not known: the package it is in, when named (not in the workspace)
    name: str = ""  # file not known: its base name, when literal
    namespace: str = ""  # the namespace pushed around it ("" or "/": none; "?" when not literal)


class LaunchInfo(Record):
    # format: "ros1-xml", "ros2-xml", "ros2-yaml", "ros2-py"
    # spawned: controller names given to spawners
    # param_sets: ROS 1: ParamSet / RosparamLoad, in document order
    # declared: launch argument name -> Declared (default, choices)
    _fields = ('path', 'format', 'nodes', 'static_tfs', 'state_publishers', 'joint_state_publishers', 'spawned',
               'param_files', 'includes', 'notes', 'param_sets', 'declared')

    unread_spawners = False  # a spawner argument decided at launch time: what it starts is unknown

    def __init__(self, path: str,
                 format: str,
                 nodes: list[LaunchNode] | None = None,
                 static_tfs: list[StaticTF] | None = None,
                 state_publishers: list[StatePublisher] | None = None,
                 joint_state_publishers: list[JointStatePublisher] | None = None,
                 spawned: list[tuple[str, Location]] | None = None,
                 param_files: list[tuple[str, Location]] | None = None,
                 includes: list[Include] | None = None,
                 notes: list[tuple[str, Location]] | None = None,
                 param_sets: list | None = None,
                 declared: dict | None = None):
        self.path = path
        self.format = format
        self.nodes = [] if nodes is None else nodes
        self.static_tfs = [] if static_tfs is None else static_tfs
        self.state_publishers = [] if state_publishers is None else state_publishers
        self.joint_state_publishers = [] if joint_state_publishers is None else joint_state_publishers
        self.spawned = [] if spawned is None else spawned
        self.param_files = [] if param_files is None else param_files
        self.includes = [] if includes is None else includes
        self.notes = [] if notes is None else notes
        self.param_sets = [] if param_sets is None else param_sets
        self.declared = {} if declared is None else declared


# --- the model robot_state_publisher is given ---------------------------------------------------
_CMD_START, _CMD_END, _CMD_UNKNOWN = "\x02", "\x03", "\x01"
_DESCRIPTION_KEY = "\x00description_key"  # LaunchNode.params entry: where a ROS 1 rsp reads its model
_DESCRIPTION_WHY = "\x00description_unread"  # LaunchNode.params entry: what the model comes from, not read


def description_of(value, loc: Location):
    """A robot_description parameter value -> pylaunch.ModelRef (None: no model named)."""
    if isinstance(value, ModelRef):
        return value
    if isinstance(value, str) and _CMD_START in value:
        inner = value[value.index(_CMD_START) + 1:].split(_CMD_END)[0].replace(_CMD_UNKNOWN, UNKNOWN)
        return command_model(inner, loc)
    return None


# --- static_transform_publisher arguments ------------------------------------------------------------
def _num(tok: str) -> float:
    f = float(tok)
    if not math.isfinite(f):
        raise ValueError(f"not a finite number: {tok!r}")
    return f


def _quat_rpy(qx: float, qy: float, qz: float, qw: float) -> tuple[float, float, float]:
    n = math.sqrt(qx * qx + qy * qy + qz * qz + qw * qw)
    if n < 1e-9:
        raise ValueError("quaternion has zero length")
    x, y, z, w = qx / n, qy / n, qz / n, qw / n
    rot = (
        (1 - 2 * (y * y + z * z), 2 * (x * y - z * w), 2 * (x * z + y * w)),
        (2 * (x * y + z * w), 1 - 2 * (x * x + z * z), 2 * (y * z - x * w)),
        (2 * (x * z - y * w), 2 * (y * z + x * w), 1 - 2 * (x * x + y * y)),
    )
    return tuple(geometry.rpy(geometry.from_rt(rot, (0, 0, 0))))


_FLAG_KEYS = {"--x", "--y", "--z", "--qx", "--qy", "--qz", "--qw", "--roll", "--pitch", "--yaw",
              "--frame-id", "--child-frame-id"}


def parse_static_tf_args(tokens: list[str], ros: int, package: str = "tf2_ros"):
    """Parse static_transform_publisher arguments -> (parent, child, xyz, rpy). Raises ValueError."""
    toks = list(tokens)
    if "--ros-args" in toks:
        toks = toks[: toks.index("--ros-args")]
    toks = [t for t in toks if ":=" not in t]  # ROS 1 remappings such as __name:=x
    if any(t in _FLAG_KEYS for t in toks):
        vals: dict[str, str] = {}
        i = 0
        while i < len(toks):
            t = toks[i]
            if t in _FLAG_KEYS and i + 1 < len(toks):
                vals[t] = toks[i + 1]
                i += 2
            else:
                raise ValueError(f"unexpected argument {t!r}")
        if "--frame-id" not in vals or "--child-frame-id" not in vals:
            raise ValueError("--frame-id and --child-frame-id are required")
        xyz = tuple(_num(vals.get(k, "0")) for k in ("--x", "--y", "--z"))
        if any(k in vals for k in ("--qx", "--qy", "--qz", "--qw")):
            rpy = _quat_rpy(*(_num(vals.get(k, "1" if k == "--qw" else "0")) for k in ("--qx", "--qy", "--qz", "--qw")))
        else:
            rpy = tuple(_num(vals.get(k, "0")) for k in ("--roll", "--pitch", "--yaw"))
        return vals["--frame-id"], vals["--child-frame-id"], xyz, rpy
    n = len(toks)
    if ros == 1 and package == "tf":
        shapes = {9: "ypr", 10: "quat"}  # tf always takes the period (ms) last
    elif ros == 1:
        shapes = {8: "ypr", 9: "quat", 10: "quat"}
    else:
        shapes = {8: "ypr", 9: "quat"}
    shape = shapes.get(n)
    if shape is None:
        raise ValueError(f"{n} arguments; expected x y z yaw pitch roll parent child or x y z qx qy qz qw parent child")
    xyz = (_num(toks[0]), _num(toks[1]), _num(toks[2]))
    if shape == "ypr":
        yaw, pitch, roll = _num(toks[3]), _num(toks[4]), _num(toks[5])
        rpy = (roll, pitch, yaw)
        parent, child = toks[6], toks[7]
    else:
        rpy = _quat_rpy(_num(toks[3]), _num(toks[4]), _num(toks[5]), _num(toks[6]))
        parent, child = toks[7], toks[8]
    return parent, child, xyz, rpy


def _frame(s: str) -> str:
    return s.strip().lstrip("/")


# --- shared node handling ----------------------------------------------------------------------------
_STATIC_PKGS = ("tf", "tf2_ros")
_JSP_PKGS = ("joint_state_publisher", "joint_state_publisher_gui")


def _unrooted(s):
    """A name or argument built from `__file__` (a node named after its launch file) holds the runner's absolute
    path: shown relative to the run's root, like every path in a report."""
    if not isinstance(s, str) or os.sep not in s:
        return s
    from urdfcheck.core import paths

    root = paths.root().rstrip(os.sep) + os.sep
    return s.replace(root, "") if root in s else s


def record_node(info: LaunchInfo, node: LaunchNode, ros: int) -> None:
    if any(isinstance(x, str) and os.sep in x for x in (node.name, node.namespace)):
        node = LaunchNode(node.package, node.executable, _unrooted(node.name), _unrooted(node.namespace),
                          node.args, node.loc, node.params, node.param_files, node.condition)
    info.nodes.append(node)
    pkg, exe = node.package, node.executable
    if pkg in _STATIC_PKGS and exe in ("static_transform_publisher", "static_transform_publisher_node"):
        if node.args is None or any("\x00" in a for a in node.args):
            info.notes.append(("static_transform_publisher arguments are not literal; skipped", node.loc))
            return
        try:
            parent, child, xyz, rpy = parse_static_tf_args(list(node.args), ros, pkg)
        except ValueError as e:
            info.notes.append((f"static_transform_publisher arguments not understood ({e}); skipped", node.loc))
            return
        xyz = tuple(float(v) + 0.0 for v in xyz)  # no -0.0
        rpy = tuple(float(v) + 0.0 for v in rpy)
        info.static_tfs.append(StaticTF(_frame(_unrooted(parent)), _frame(_unrooted(child)), xyz, rpy, node.loc,
                                        info.path, node.condition, node.name))
    elif pkg == "robot_state_publisher" and exe in ("robot_state_publisher", "state_publisher"):
        key = "frame_prefix" if ros == 2 else "tf_prefix"
        v = node.params.get(key)
        if v is None:
            prefix, ploc = "", None
        elif isinstance(v.value, str) and "$(" not in v.value:
            prefix, ploc = v.value, v.loc
            if ros == 1 and prefix.strip("/"):  # ROS 1 tf_prefix "r1" makes frames "r1/base_link"
                prefix = prefix.strip("/") + "/"
        else:
            prefix, ploc = None, v.loc
        d = node.params.get("robot_description")
        desc = description_of(d.value, d.loc) if d is not None else None
        key = node.params.get(_DESCRIPTION_KEY)
        why = node.params.get(_DESCRIPTION_WHY)
        info.state_publishers.append(StatePublisher(node.name or "robot_state_publisher", node.namespace, prefix,
                                                    node.loc, info.path, ploc, node.condition, desc,
                                                    key.value if key is not None and desc is None else None,
                                                    why.value if why is not None and desc is None else ""))
    elif pkg in _JSP_PKGS:
        info.joint_state_publishers.append(JointStatePublisher(node.name or pkg, pkg, node.loc, info.path,
                                                               node.condition))
    elif pkg == "controller_manager" and exe in ("spawner", "spawner.py", "controller_manager"):
        if node.args is None:
            info.notes.append(("spawner arguments are not literal; the controllers it starts are unknown", node.loc))
        if node.args:
            toks = list(node.args)
            i = 0
            while i < len(toks):
                t = toks[i]
                if t in ("-c", "--controller-manager", "-p", "--param-file", "-n", "--namespace", "-t",
                         "--controller-type", "--controller-manager-timeout", "--switch-timeout",
                         "--service-call-timeout", "--controller-ros-args", "--ns", "--timeout",
                         "--shutdown-timeout"):
                    if t in ("-p", "--param-file") and i + 1 < len(toks):
                        info.param_files.append((toks[i + 1], node.loc))
                    i += 2
                    continue
                if "\x00" in t:  # a controller name decided at launch time: what this spawner starts is unknown
                    info.unread_spawners = True
                if t.startswith("-") or t in ("spawn", "load", "start", "stop") or "\x00" in t:
                    i += 1
                    continue
                info.spawned.append((t, node.loc))
                i += 1
    for pf in node.param_files:
        info.param_files.append((pf, node.loc))
