"""Nodes that broadcast transforms of their own (localization, SLAM, camera drivers) and the edges each one
publishes, from the data in `tfowners.yaml` (per node: the parameters naming its frames with their defaults,
the parameter that turns the broadcast on, and the edges).

Where a node's parameters come from:

* parameter files (`localization_from_params`): a file's node is recognised by its keys (robot_localization:
  `world_frame`/`base_link_frame` or a sensor input such as `odom0`/`imu0`; AMCL: `global_frame_id` with
  `odom_frame_id`, or a node called `amcl`; slam_toolbox: `transform_publish_period`, `solver_plugin`, ...);
* launch files (`localization_from_launch`): a node of a known package (`Node(package="robot_localization")`,
  `<node pkg="slam_toolbox">`) with its inline parameters (a ROS 2 dict, ROS 1 `<param>`) over the
  parameter files it is given; cartographer's options from the `.lua` file its arguments name (read as text,
  never run); an include of a known driver's launch file (realsense2_camera's `rs_launch.py`) with the
  arguments it passes.
"""
from __future__ import annotations

import functools
import os
import re
from collections.abc import Callable, Iterable

from urdfcheck.consumers.common import Value, as_bool
from urdfcheck.consumers.params import NodeParams, ParamFile
from urdfcheck.core import lazyre
from urdfcheck.core.findings import Location
from urdfcheck.core.paths import shown
from urdfcheck.core.records import TYPE_CHECKING, TupleRecord

if TYPE_CHECKING:
    from typing import Any

_RL_INPUT = lazyre.compile(r"^(odom|imu|pose|twist)\d+$")


@functools.lru_cache(maxsize=1)
def owners() -> dict[str, dict]:
    """The TF owner table (`tfowners.yaml`)."""
    import json

    # the JSON twin of tfowners.yaml (tools/catalogues.py writes it): no PyYAML import for our own data
    with open(os.path.join(os.path.dirname(__file__), "tfowners.json"), encoding="utf-8") as f:
        return json.load(f)


def owner_packages() -> set[str]:
    """The packages whose nodes are TF owners of the table (read here, never as custom drivers)."""
    return {p for spec in owners().values() for p in spec.get("packages") or ()}


class Edge(TupleRecord):
    parent: str
    child: str
    kind: str  # "static" or "dynamic"
    loc: Location


class LocalizationNode(TupleRecord):
    node: str
    kind: str  # "ekf", "ukf", "amcl", "slam_toolbox", "cartographer", "realsense2_camera"
    file: str
    loc: Location
    values: dict  # parameter -> Value (defaults filled in, `default=True`)
    owner: str = ""  # the table entry

    def _spec(self) -> dict:
        return owners().get(self.owner or self.kind, {})

    def get(self, name: str) -> Value:
        v = self.values.get(name)
        return v if v is not None else Value(None, self.loc, default=True)

    @property
    def publishes(self) -> bool:
        spec = self._spec()
        return _on(self.get(spec.get("enable", ""))) if spec.get("enable") else True

    @property
    def base_frame(self) -> Value:
        spec = self._spec()
        return self.get(spec["base"]) if spec.get("base") else Value("", self.loc, default=True)

    def edges(self) -> list[Edge]:
        """The transforms it broadcasts (none when its enable parameter is off)."""
        spec = self._spec()
        if not self.publishes:
            return []
        out = []
        for e in spec.get("edges") or ():
            when = e.get("when")
            if when is not None and not self._holds(str(when)):
                continue
            parent, child = self._frame(str(e["parent"])), self._frame(str(e["child"]))
            if parent and child and parent != child:
                out.append(Edge(parent, child, e.get("kind", "dynamic"), self._edge_loc(e)))
        return out

    def edge(self) -> tuple[str, str] | None:
        """(parent, child) of the first transform it broadcasts; None when it broadcasts none."""
        es = self.edges()
        return (es[0].parent, es[0].child) if es else None

    @property
    def edge_loc(self) -> Location:
        es = self.edges()
        return es[0].loc if es else self.loc

    # --- helpers ---------------------------------------------------------------------------------------
    def _frame(self, ref: str) -> str:
        if "{" in ref:
            def sub(m):
                return str(self.get(m.group(1)).value or "")
            text = re.sub(r"\{([\w.]+)\}", sub, ref)  # nested parameters by their dotted name
        else:
            text = str(self.get(ref).value if self.get(ref).value is not None else "")
        return "" if "$(" in text else text.strip().lstrip("/")  # decided at launch time: not a known frame

    def _holds(self, when: str) -> bool:
        w = when.strip()
        if " == " in w:
            a, b = (x.strip() for x in w.split(" == ", 1))
            return self._frame(a) == self._frame(b)
        if w.startswith("not "):
            return not _on(self.get(w[4:].strip()))
        return _on(self.get(w))

    def _edge_loc(self, e: dict) -> Location:
        """Where the decision was written: the parameters of its condition, the enable parameter, the node."""
        spec = self._spec()
        names = re.findall(r"[\w.]+", str(e.get("when") or "").replace("not ", " ")) + [spec.get("enable", "")]
        for n in names:
            v = self.values.get(n)
            if v is not None and not v.default:
                return v.loc
        return self.loc


def _on(v: Value) -> bool:
    x = v.value
    if isinstance(x, (int, float)) and not isinstance(x, bool):
        return x != 0
    b = as_bool(x)
    if b is not None:
        return b
    try:
        return float(str(x)) != 0
    except ValueError:
        return True  # not literal: the node's default behaviour (publishing) is the safer reading


def _values(spec: dict, given: dict[str, Value], loc: Location, ros1: bool = False) -> dict[str, Value]:
    defaults = dict(spec.get("params") or {})
    if ros1:
        defaults.update(spec.get("ros1") or {})
    out: dict[str, Value] = {k: v for k, v in given.items()}
    for k, d in defaults.items():
        if k in out:
            continue
        if isinstance(d, str) and d.startswith("="):
            ref = out.get(d[1:])
            out[k] = Value(ref.value if ref is not None else defaults.get(d[1:]), loc, default=True)
        else:
            out[k] = Value(d, loc, default=True)
    return out


def _recognise(node: NodeParams) -> str | None:
    p = node.params
    table = owners()
    if "world_frame" in p or "base_link_frame" in p:
        return "robot_localization"
    if any(_RL_INPUT.match(k) for k in p) and ("frequency" in p or "two_d_mode" in p):
        return "robot_localization"
    if ("global_frame_id" in p and "odom_frame_id" in p) or (node.basename == "amcl" and bool(p)):
        return "amcl"
    for name, spec in table.items():
        keys = spec.get("recognise") or ()
        if keys and any(k in p for k in keys) and not any(k in p for k in spec.get("unless") or ()):
            return name
    return None


def _kind(owner: str, node_name: str, params: dict, executable: str = "") -> str:
    if owner == "robot_localization":
        return "ukf" if "ukf" in (node_name + executable).lower() or "alpha" in params else "ekf"
    return owner


def make_node(owner: str, node_name: str, file: str, loc: Location, given: dict[str, Value],
              ros1: bool = False, executable: str = "") -> LocalizationNode:
    spec = owners()[owner]
    return LocalizationNode(node_name, _kind(owner, node_name, given, executable), file, loc,
                            _values(spec, given, loc, ros1), owner)


def localization_from_params(files: Iterable[ParamFile], skip: set | None = None) -> list[LocalizationNode]:
    """The TF-owning nodes of parameter files, recognised by their keys (`skip`: (file, node key) pairs a
    launch file's node has read already)."""
    out: list[LocalizationNode] = []
    for pf in files:
        for key, node in pf.nodes.items():
            if skip and (os.path.realpath(pf.path), key) in skip:
                continue
            owner = _recognise(node)
            if owner is None:
                continue
            out.append(make_node(owner, key, pf.path, node.loc, dict(node.params), pf.dialect == "ros1"))
    return out


# --- launch files --------------------------------------------------------------------------------------
def _owner_of(package: str, executable: str) -> str | None:
    for name, spec in owners().items():
        if package in (spec.get("packages") or ()):
            exes = spec.get("executables")
            if not exes or executable in exes or not executable:
                return name
    return None


def _matching(pf: ParamFile, node_name: str, executable: str) -> list[tuple[str, NodeParams]]:
    """The nodes of a parameter file a launch node reads: its own name, a wildcard, or the only node."""
    names = {n for n in (node_name, executable) if n}
    hits = [(k, n) for k, n in pf.nodes.items() if n.basename in names or n.basename == "**"]
    if not hits and len(pf.nodes) == 1:
        hits = list(pf.nodes.items())
    return hits


def localization_from_launch(infos: Iterable, read: Callable[[str], ParamFile | None],
                             locate: Callable[[str], str | None] | None = None, namespace: str | None = None,
                             refused: list | None = None) -> tuple[list[LocalizationNode], set, list]:
    """TF-owning nodes started by the launch files `infos` (in `namespace` when given): (nodes, (file, node
    key) pairs read for them, notes). `read(path)` reads a parameter file (None: unreadable); `locate` maps a
    path to a workspace file. A file the door refuses (outside the run's roots: an absolute path, `../..`, a link
    out of the checkout) is a `ConsumerError` at the launch line that names it, appended to `refused` (C007, as
    the controller readers report the same refusal); without `refused`, a note."""
    out: list[LocalizationNode] = []
    used: set = set()
    notes: list = []
    for info in infos:
        ros1 = getattr(info, "format", "") == "ros1-xml"
        for n in info.nodes:
            owner = _owner_of(n.package, n.executable)
            if owner is None or n.condition or (namespace is not None and n.namespace != namespace):
                continue
            given: dict[str, Value] = {}
            files = []
            for f in n.param_files:
                path = locate(f) if locate is not None else f
                pf = read(path) if path else None
                if pf is None:
                    if not refused_file(path or f, f"{owner} {n.name or n.executable}: parameter file", n.loc, refused):
                        notes.append((f"{owner}: parameter file {f} not read; its frames are the defaults", n.loc))
                    continue
                files.append(pf.path)
                for key, node in _matching(pf, n.name, n.executable):
                    used.add((os.path.realpath(pf.path), key))
                    given.update(_substituted(node.params, n, f))
            if ros1:
                given.update(_ros1_server(info, n, read, locate, used, refused))
            given.update({k: v for k, v in n.params.items() if v.value is not None and not k.startswith("\x00")})
            if owners()[owner].get("lua"):
                got = _lua_options(n, locate, notes, refused)
                if got is None:
                    continue
                given.update(got)
            name = n.name or n.executable or n.package
            out.append(make_node(owner, name, files[0] if files else n.loc.file, n.loc, given, ros1, n.executable))
        for inc in getattr(info, "includes", ()):
            got = _driver_include(inc)
            if got is not None:
                out.append(got)
    return out, used, notes


def refused_file(path: str, what: str, where: Location, refused: list | None,
                 lost: str = "the node's frames cannot be checked") -> bool:
    """Whether the door refuses `path` (then one ConsumerError at `where`, the launch line naming it, goes to
    `refused`). The file is named by its base name only: the launch line says how it was written, and its
    resolved path may be the runner's."""
    if refused is None or not path:
        return False
    from urdfcheck.consumers.common import ConsumerError
    from urdfcheck.core import door

    try:
        door.confine(path)
        return False
    except door.Refused as e:
        why = e.why.removeprefix("refused: ")
    except (OSError, ValueError):
        return False
    err = ConsumerError(f"{what} {os.path.basename(os.path.normpath(str(path)))!r} is refused: {why}; {lost}", where)
    if err not in refused:
        refused.append(err)
    return True


def _ros1_server(info, n, read, locate, used: set, refused: list | None = None) -> dict[str, Value]:
    """A ROS 1 node's private parameters written outside it, in document order: `<rosparam command="load"
    file=... ns=...>` (with `subst_value="true"` its `$(arg ...)` substituted) and `<param name="node/x">`."""
    from urdfcheck.consumers.launch.info import ParamSet, RosparamLoad
    from urdfcheck.consumers.launch.xml import substitute_args

    name = n.name or n.executable
    if not name:
        return {}
    home = "/" + "/".join(x for x in (n.namespace.strip("/"), name.strip("/")) if x)
    out: dict[str, Value] = {}
    for item in info.param_sets:
        if isinstance(item, ParamSet) and item.name.startswith(home + "/"):
            out[item.name[len(home) + 1:].replace("/", ".")] = item.value
        elif isinstance(item, RosparamLoad):
            path = (locate(item.file) if locate is not None else item.file) or item.file
            pf = read(path)
            if pf is None:
                refused_file(path, f"{n.package} {name}: rosparam file", item.loc, refused)
                continue
            args = dict(item.subst or ())
            for key, node in pf.nodes.items():
                full = "/" + "/".join(x for x in (item.ns.strip("/"), key.strip("/")) if x)
                if full != home:
                    continue
                used.add((os.path.realpath(pf.path), key))
                for k, v in node.params.items():
                    if item.subst is not None and isinstance(v.value, str) and "$(" in v.value:
                        v = Value(substitute_args(v.value, args), v.loc, v.default, v.items)
                    out[k] = v
    return out


def _substituted(params: dict[str, Value], n, file: str) -> dict[str, Value]:
    """The parameters of a file the node loads with `subst_value="true"`, its `$(arg ...)` substituted."""
    from urdfcheck.consumers.launch.xml import SUBST_KEY, substitute_args

    got = n.params.get(SUBST_KEY)
    if got is None or file not in got.value[0]:
        return params
    args = got.value[1]
    return {k: (Value(substitute_args(v.value, args), v.loc, v.default, v.items)
                if isinstance(v.value, str) and "$(" in v.value else v) for k, v in params.items()}


def _driver_include(inc) -> LocalizationNode | None:
    """An include of a known driver's own launch file (`realsense2_camera/launch/rs_launch.py`): the node it
    starts, its parameters the arguments passed (the launch file's defaults otherwise)."""
    if inc.condition or (inc.file and os.path.isfile(inc.file)):
        return None  # a launch file of the workspace is read itself, with the node it starts
    file = inc.file or ""
    base = os.path.basename(file) if file else getattr(inc, "name", "")
    for name, spec in owners().items():
        packages = spec.get("packages") or ()
        if base in (spec.get("launch_files") or ()) and (getattr(inc, "package", None) in packages or any(
                f"{os.sep}{p}{os.sep}" in file for p in packages)):
            given = {k: Value(v, inc.loc) for k, v in inc.args.items() if v is not None and k in spec["params"]}
            return make_node(name, name, inc.loc.file, inc.loc, given)
    return None


# --- cartographer's .lua options, read as text --------------------------------------------------------------
_LUA_PAIR = lazyre.compile(r"""^\s*(\w+)\s*=\s*("([^"\\]*)"|'([^'\\]*)'|true|false|-?[\d.]+(?:[eE][-+]?\d+)?)\s*,?""",
                       re.M)
MAX_LUA_BYTES = 256 * 1024


def _arg_after(args, flag: str) -> str | None:
    toks = list(args or ())
    for i, t in enumerate(toks):
        if t in (flag, "-" + flag.lstrip("-"), "--" + flag.lstrip("-")) and i + 1 < len(toks):
            return toks[i + 1]
        if t.startswith(flag + "="):
            return t.split("=", 1)[1]
    return None


def _lua_options(n, locate, notes: list, refused: list | None = None) -> dict[str, Value] | None:
    """The top-level `options = {...}` keys of the .lua file a cartographer_node is given (None: not found)."""
    folder = _arg_after(n.args, "-configuration_directory")
    base = _arg_after(n.args, "-configuration_basename")
    if not folder or not base or "\x00" in folder + base or "$(" in folder + base:
        notes.append(("cartographer: its .lua configuration is not literal; its transforms are not known", n.loc))
        return None
    path = os.path.join(folder, base)
    path = (locate(path) if locate is not None else path) or path
    if refused_file(path, f"cartographer {n.name or n.executable}: configuration", n.loc, refused):
        return None
    return read_lua_options(path, notes, n.loc)


def read_lua_options(path: str, notes: list | None = None, where: Location | None = None) -> dict[str, Value] | None:
    from urdfcheck.consumers.common import ConsumerError, read_capped

    try:
        text = read_capped(path, MAX_LUA_BYTES, "lua file").decode("utf-8", "replace")
    except (ConsumerError, OSError):
        if notes is not None:
            notes.append((f"cartographer: configuration {shown(path)} not read; its transforms are not known",
                          where or Location(path)))
        return None
    start = re.search(r"^\s*options\s*=\s*\{", text, re.M)
    if start is None:
        return {}
    out: dict[str, Value] = {}
    depth, i = 1, start.end()
    end = len(text)
    for j in range(i, len(text)):  # the options table's own level only
        c = text[j]
        if c == "{":
            depth += 1
        elif c == "}":
            depth -= 1
            if depth == 0:
                end = j
                break
    body = text[i:end]
    for m in _LUA_PAIR.finditer(body):
        key, raw = m.group(1), m.group(2)
        value: Any
        if raw in ("true", "false"):
            value = raw == "true"
        elif m.group(3) is not None or m.group(4) is not None:
            value = m.group(3) if m.group(3) is not None else m.group(4)
        else:
            try:
                value = float(raw)
            except ValueError:
                continue
        line = text.count("\n", 0, i + m.start(1)) + 1
        out[key] = Value(value, Location(path, line))
    return out
