"""Deployments: how the launch files of a workspace run each robot.

A deployment is one robot_state_publisher started by a launch file, and what runs beside it: the model it
publishes (file and xacro arguments, read from `Command(['xacro ', path, ' a:=', v])`, `ParameterValue`,
`$(command xacro ...)`, `<param command=...>`, `xacro.process_file`, `open(path).read()`), its namespace and
frame_prefix, the controller manager's parameter files and the spawned controllers, joint state publishers,
static transforms and localization nodes (robot_localization, AMCL, slam_toolbox, Nav2) with their parameter
files. Launch files are read, never run (`consumers.launch.xml`, `consumers.launch.python`).

`find_deployments(root)` reads every launch file below `root` (ROS 2 Python, XML, YAML; ROS 1 XML). Launch
files that no other file includes are the roots; each root is followed into its includes with the arguments it
passes (packages resolve among the workspace's package.xml files first). A robot_state_publisher that no root
reaches makes its own file a root. Launch arguments declared with `choices` (and, for a model path chosen at
launch time, the files that match it) give variants, one deployment each; identical deployments are kept once.
`Deployment.consumers()` (`consumers.consumers.deployment_consumers`) builds the `Consumers` the C and T checks read.
This module only reads launch files: which targets a request lints, deployments included, is decided by
`plan.plan` alone.
"""
from __future__ import annotations

import glob
import os
import re
from collections.abc import Iterable, Mapping
from pathlib import Path

from urdfcheck.consumers.openworld import KNOWN_PACKAGES, LOCALIZATION_PACKAGES, known_kind  # noqa: F401
from urdfcheck.core import lazyre
from urdfcheck.core.findings import Location
from urdfcheck.core.records import Record
from urdfcheck.core.walk import real as realpath  # remembered for the run

MAX_VARIANTS = 24  # launch-argument assignments tried per root launch file
MAX_MODEL_FILES = 8  # files one model path chosen at launch time may match
MAX_TREE_FILES = 60
MAX_DEPTH = 8


def _show(path: str) -> str:
    from urdfcheck.core.paths import shown

    return shown(path)


class Deployment(Record):
    # model: the model file (None: the launch file's model was not understood; see notes)
    # how: "xacro" (expanded with args) or "file" (read as is)
    # args: xacro arguments the launch file passes (literal ones); dropped_args: those decided at launch time
    # variant: the launch-argument choice this deployment comes from ("" for the defaults)
    # launch: the launch file that defines the deployment (the root of its include chain); rsp: the node
    # chain: the include sites from the root down to the file that starts robot_state_publisher
    # controller_files / localization_files: parameter files (source paths); spawned: (controller, Location)
    # joint_state: (what, Location); static_tfs: launch.StaticTF; infos: every LaunchInfo of the chain
    # driver_nodes: (LaunchNode, [parameter files]) of nodes of no known kind: custom drivers, read by key shape
    _fields = ('model', 'how', 'args', 'variant', 'namespace', 'frame_prefix', 'launch', 'rsp', 'chain',
               'controller_files', 'localization_files', 'spawned', 'joint_state', 'static_tfs', 'infos',
               'notes', 'dropped_args', 'driver_nodes')

    # package_files: parameter files of the model's package that no deployment reads (checked against the
    # model too, `consumers.openworld`); package_single: the package holds one model
    package_files: tuple = ()
    package_single = True
    # controller files taken from the model's Gazebo ros2_control plugin, read as text: kept only when the
    # expanded model has that plugin (`Consumers.settle`; it may sit in a branch these arguments do not take)
    plugin_files: tuple = ()
    workspace: str | None = None
    included_elsewhere = False
    # a literal model path into a package of the checkout that names no file (`_Workspace.missing`): the launch
    # file itself is broken (plan.understood: C025), not merely not understood; the package folder
    missing: str = ""

    def __init__(self, model, how="xacro", args=None, variant="", namespace="/", frame_prefix=None,
                 launch: Location | None = None, rsp: Location | None = None, chain=(), controller_files=(),
                 localization_files=(), spawned=(), joint_state=(), static_tfs=(), infos=(), notes=(),
                 dropped_args=(), driver_nodes=()):
        self.model = model
        self.driver_nodes = list(driver_nodes)
        self.how = how
        self.args = dict(args or {})
        self.variant = variant
        self.namespace = namespace
        self.frame_prefix = frame_prefix
        self.launch = launch
        self.rsp = rsp
        self.chain = tuple(chain)
        self.controller_files = list(controller_files)
        self.localization_files = list(localization_files)
        self.spawned = list(spawned)
        self.joint_state = list(joint_state)
        self.static_tfs = list(static_tfs)
        self.infos = list(infos)
        self.notes = list(notes)
        self.dropped_args = list(dropped_args)

    @property
    def label(self) -> str:
        """How findings name the deployment: the defining launch file, and the variant."""
        where = _show(self.launch.file) if self.launch is not None else "?"
        return where + (f" [{self.variant}]" if self.variant else "")

    def chosen_args(self) -> dict:
        """The xacro arguments a reader needs to tell this deployment apart: those whose value is not the
        default a launch file of the chain declares for a launch argument of that name (the variant's choice,
        what an including file passes, literals written into the command)."""
        defaults: dict[str, set] = {}
        for info in self.infos:
            for name, d in getattr(info, "declared", {}).items():
                defaults.setdefault(name, set()).add(d.default)
        return {k: v for k, v in self.args.items() if v not in defaults.get(k, ())}

    def key(self) -> tuple:
        """Identity: the same model with the same arguments, started the same way by the same launch file
        (variants that change nothing collapse; another launch file is another deployment: what runs
        beside the robot differs, as between a bringup and a simulation launch file)."""
        return (self.launch.file if self.launch is not None else None, self.model,
                tuple(sorted(self.args.items())), self.namespace, self.frame_prefix)

    def consumers(self):
        """The contract checks' view of this deployment (`consumers.consumers.deployment_consumers`)."""
        from urdfcheck.consumers.consumers import deployment_consumers

        return deployment_consumers(self)

def _model_like(path: str) -> bool:
    """A file a launch-time pattern may pick as the robot: a `.urdf`/`.xacro` (the loader says what is wrong
    with it), or any other whose root element is <robot>; never an SDFormat file, a text or a YAML."""
    low = path.lower()
    if low.endswith((".urdf", ".xacro")):
        return True
    if low.endswith(_NOT_URDF):
        return False
    from urdfcheck.load.discover import _read_head, _root_tag

    tag = _root_tag(_read_head(path))
    return tag is not None and tag.split(":")[-1] == "robot"


_NOT_URDF = (".sdf", ".world", ".yaml", ".yml", ".json", ".py", ".md", ".txt", ".rst", ".srdf", ".launch",
             ".stl", ".dae", ".obj", ".png", ".jpg", ".xml")


def sdformat(path: str) -> bool:
    """An SDFormat model (`.sdf`, or root <sdf>): robot_state_publisher reads it through sdformat_urdf, but it
    is no URDF, and linting it as one reports its every element."""
    if path.lower().endswith((".sdf", ".world")):
        return True
    from urdfcheck.load.discover import _read_head, _root_tag

    tag = _root_tag(_read_head(path))
    return tag is not None and tag.split(":")[-1] == "sdf"


# --- the workspace's launch files --------------------------------------------------------------------------
def _is_launch(name: str) -> bool:
    from urdfcheck.load.discover import LAUNCH_SUFFIXES

    low = name.lower()
    return low.endswith(LAUNCH_SUFFIXES)


class _Workspace:
    def __init__(self, root: str, resolver=None, packages: Mapping[str, str] | None = None):
        from urdfcheck.load.packages import workspace_packages

        self.root = os.path.abspath(root)
        self.resolver = resolver
        self.explicit = {k: os.path.abspath(v) for k, v in (packages or {}).items()}
        self.packages = workspace_packages(self.root)
        self.folders = sorted({str(p) for dirs in self.packages.values() for p in dirs} | set(self.explicit.values()),
                              key=len, reverse=True)
        self._parsed: dict[str, object] = {}
        self._single: dict[str, str] | None = None  # package_map: the packages with one copy
        self.raw: dict[str, bytes] = {}  # launch file bytes, as read
        self.found: list[str] = []  # package folders the resolver found outside the root
        self.notes: list[tuple[str, Location]] = []

    def find(self, name: str, near: str) -> str | None:
        from urdfcheck.load.packages import nearest

        if name in self.explicit:
            return self.explicit[name]
        dirs = self.packages.get(name)
        if dirs:
            return str(nearest(dirs, Path(near)))
        if self.resolver is not None:
            hit = self.resolver.find(name)
            if hit is None:
                return None
            if str(hit) not in self.found:  # a package found outside the root: its files may be read too
                self.found.append(str(hit))
                self.folders = sorted(set(self.folders) | {str(hit)}, key=len, reverse=True)
            return str(hit)
        return None

    def package_map(self, near: str) -> dict[str, str]:
        from urdfcheck.load.packages import nearest

        # a package with one copy maps to it from anywhere: only those with several depend on `near` (this is
        # asked for every launch file read, and a corpus root holds ~120 packages)
        if self._single is None:
            self._single = {k: str(v[0]) for k, v in self.packages.items() if len(v) == 1}
        near_path = Path(near)
        single = self._single
        out = {k: single[k] if k in single else str(nearest(v, near_path)) for k, v in self.packages.items()}
        out.update(self.explicit)
        return out

    def inside(self, path: str) -> bool:
        from urdfcheck.load.packages import real

        where = real(path)
        roots = [real(p) for p in (self.root, *self.explicit.values(), *self.found)]
        return any(where == r or where.startswith(r.rstrip(os.sep) + os.sep) for r in roots)

    def locate(self, path: str | None) -> str | None:
        """`path` if it is a file; else the source-layout file an install-layout path names
        (`share/P/urdf/x` written as `$(find P)/urdf/x` may be `P/description/urdf/x`), when unique."""
        if not path or "\x00" in path:
            return None
        path = os.path.normpath(path)
        if os.path.isfile(path):
            return path if self.inside(path) else None
        for folder in self.folders:
            if path.startswith(folder.rstrip(os.sep) + os.sep):
                rel = os.path.relpath(path, folder)
                for pat in (os.path.join(folder, "*", rel), os.path.join(folder, "*", "*", rel)):
                    hits = [h for h in glob.glob(glob.escape(folder) + pat[len(folder):]) if os.path.isfile(h)]
                    if len(hits) == 1:
                        return hits[0]
                    if hits:
                        return None
                return None
        return None

    def missing(self, path: str | None) -> str:
        """The package folder of the checkout that a literal model path points into, when no file is there (nor
        in the source layout): the launch file fails at this line (issue 37). "" when the path is not literal, lies
        outside the checkout's packages (a dependency's, the author's machine), or names a URDF the package makes
        at build time from a xacro file (CMake's xacro macros: the URDF is in the install space only)."""
        if not path or "\x00" in path or not os.path.isabs(path):
            return ""
        path = os.path.normpath(path)
        if os.path.lexists(path) or not self.inside(path):
            return ""
        pkg = next((str(d) for dirs in self.packages.values() for d in dirs
                    if path.startswith(str(d).rstrip(os.sep) + os.sep)), "")
        if not pkg or not _below_root(pkg, self.root) or _built(pkg, path) or _elsewhere(pkg, path):
            return ""
        return pkg

    def match(self, pattern: str) -> list[str]:
        """Model files matching a path with pieces decided at launch time (UNKNOWN), in the source layout too.
        A path that is nothing but launch-time pieces (`robot_xacro_file` with no default), or is relative (to a
        working directory the launch file never had), names no file: matching it would take a LICENSE or a
        README of the checkout for the robot. Only files that may be URDF robots are matched (`_model_like`)."""
        if not os.path.isabs(pattern):
            return []
        pat = glob.escape(pattern).replace("\x00", "*")
        hits = [h for h in sorted(glob.glob(pat)) if os.path.isfile(h)]
        if not hits:
            for folder in self.folders:
                if pattern.startswith(folder.rstrip(os.sep) + os.sep):
                    rel = pat[len(glob.escape(folder)):].lstrip(os.sep) if pat.startswith(glob.escape(folder)) else None
                    if rel is None:
                        break
                    base = glob.escape(folder)
                    for extra in ("*", os.path.join("*", "*")):
                        hits = [h for h in sorted(glob.glob(os.path.join(base, extra, rel))) if os.path.isfile(h)]
                        if hits:
                            break
                    break
        return [h for h in hits if self.inside(h) and _model_like(h)][:MAX_MODEL_FILES]

    def inactive_includes(self, path: str) -> list[str]:
        """Files a Python launch file includes under a condition that is false with its defaults."""
        import ast

        tree = self._parsed.get(path)
        if not isinstance(tree, ast.AST):
            return []
        from urdfcheck.consumers.launch import python as pylaunch

        return pylaunch.inactive_include_files(path, tree, lambda name: self.find(name, path))

    def read(self, path: str, args: Mapping[str, str | None] | None):
        """LaunchInfo for `path` with `args`, or a ConsumerError; read and parsed once, through the launch door
        (consumers.launch.xml.parse_launch), the Python tree kept for `inactive_includes`."""
        from urdfcheck.consumers.common import ConsumerError
        from urdfcheck.consumers.launch.xml import launch_format, parse_launch, python_tree, read_source

        got = self._parsed.get(path)
        if got is None:
            try:
                data = read_source(path)
                self.raw[path] = data
                got = python_tree(data, path) if launch_format(path) == "py" else data
            except ConsumerError as e:
                got = e
            self._parsed[path] = got
        if isinstance(got, ConsumerError):
            return got
        try:
            return parse_launch(got, path, args=args, packages=self.package_map(path),
                                find_package=lambda name: self.find(name, path))
        except ConsumerError as e:
            return e


def _below_root(path: str, root: str) -> bool:
    return path == root or path.startswith(root.rstrip(os.sep) + os.sep)


def _elsewhere(pkg: str, path: str) -> bool:
    """A file of that name somewhere else in the package: the build may install it where the launch file looks
    (`install(FILES models/robot.urdf DESTINATION share/pkg/urdf)`, setup.py's data_files)."""
    from urdfcheck.core.walk import folders

    name = os.path.basename(path)
    return any(e.name == name for _d, entries in folders(pkg, max_dirs=2000) for e in entries)


def _built(pkg: str, path: str) -> bool:
    """A URDF the package generates at build time: its CMakeLists.txt runs xacro and the package holds a xacro
    file of the same name (`robot.urdf` from `robot.urdf.xacro` or `robot.xacro`)."""
    from urdfcheck.core import door

    name = os.path.basename(path)
    stem = name[:-5] if name.endswith(".urdf") else name
    try:
        cmake = door.read_bytes(os.path.join(pkg, "CMakeLists.txt"), limit=1024 * 1024)
    except OSError:
        return False
    if b"xacro" not in cmake:
        return False
    wanted = {name + ".xacro", stem + ".xacro", stem + ".urdf.xacro"}
    from urdfcheck.core.walk import folders

    return any(e.name in wanted for _d, entries in folders(pkg, max_dirs=2000) for e in entries)


def launch_files(root: str) -> list[str]:
    from urdfcheck.load.discover import _walk

    return [os.path.join(d, f) for d, f in _walk(os.path.abspath(root), 20_000) if _is_launch(f)]


# --- trees of included launch files -------------------------------------------------------------------------
class _Tree:
    def __init__(self):
        self.infos: list = []  # LaunchInfo
        self.chains: dict[int, tuple] = {}  # id(info) -> include Locations from the root
        self.notes: list[tuple[str, Location]] = []
        self.files: set[str] = set()


def _walk_tree(ws: _Workspace, root: str, args: Mapping[str, str | None]) -> _Tree:
    from urdfcheck.consumers.common import ConsumerError

    tree = _Tree()
    queue = [(root, dict(args), (), 0)]
    while queue and len(tree.files) < MAX_TREE_FILES:
        path, a, chain, depth = queue.pop(0)
        real = realpath(path)
        if real in tree.files:
            continue
        tree.files.add(real)
        info = ws.read(path, a)
        if isinstance(info, ConsumerError):
            tree.notes.append((f"launch file not read: {info.message}", info.location))
            continue
        tree.infos.append(info)
        tree.chains[id(info)] = chain
        for inc in info.includes:
            target = ws.locate(inc.file) if inc.file else None
            if target is None:
                why = "its file name is decided at launch time" if not inc.file else \
                    f"{_show(inc.file)} is not in the workspace"
                tree.notes.append((f"include not followed: {why}", inc.loc))
                continue
            if depth + 1 > MAX_DEPTH:
                tree.notes.append(("include not followed: too deeply nested", inc.loc))
                continue
            if inc.condition:
                tree.notes.append((f"include followed although it runs only under a condition ({inc.condition})",
                                   inc.loc))
            queue.append((target, dict(inc.args), chain + (inc.loc,), depth + 1))
    return tree


def _choice_dims(tree: _Tree, overrides: Mapping[str, str | None]) -> dict[str, tuple]:
    """Launch arguments declared with `choices` that no including file sets, in the order seen."""
    passed: set[str] = set()
    for info in tree.infos:
        for inc in info.includes:
            passed.update(k for k, v in inc.args.items())
    dims: dict[str, tuple] = {}
    for info in tree.infos:
        is_root = not tree.chains.get(id(info))
        for name, d in getattr(info, "declared", {}).items():
            if d.choices and name not in overrides and (is_root or name not in passed) and name not in dims:
                dims[name] = d.choices
    return dims


_FLIP = {"true": "false", "false": "true", "True": "False", "False": "True"}
MAX_BOOL_DIMS = 8


def _bool_dims(tree: _Tree, dims: Mapping[str, tuple]) -> dict[str, str]:
    """Boolean launch arguments (default true/false, no choices) that no including file sets: name -> the value
    other than the default. A launch argument is as free as a xacro argument (issue 37): where it reaches the
    model's xacro arguments (`use_camera:=$(arg use_camera)`), its other value is another deployment; where it
    does not, that deployment is the same and collapses (`Deployment.key`)."""
    passed: set[str] = set()
    for info in tree.infos:
        for inc in info.includes:
            passed.update(inc.args)
    out: dict[str, str] = {}
    for info in tree.infos:
        is_root = not tree.chains.get(id(info))
        for name, d in getattr(info, "declared", {}).items():
            if d.choices or d.default not in _FLIP or name in dims or name in out:
                continue
            if is_root or name not in passed:
                out[name] = _FLIP[d.default]
            if len(out) >= MAX_BOOL_DIMS:
                return out
    return out


def _reaches_model(base: list, flipped: list) -> bool:
    """A flipped launch argument changed what robot_state_publisher is given (model or xacro arguments)."""
    return {(d.model, tuple(sorted(d.args.items()))) for d in flipped} != \
        {(d.model, tuple(sorted(d.args.items()))) for d in base}


def _required(tree: _Tree) -> set[str]:
    return {n for info in tree.infos for n, d in getattr(info, "declared", {}).items() if d.default is None}


# --- deployments of one tree --------------------------------------------------------------------------------
def _deployments(ws: _Workspace, root: str, tree: _Tree, variant: str) -> list[Deployment]:
    from urdfcheck.consumers.launch.info import UNKNOWN

    rsps = [(info, sp) for info in tree.infos for sp in info.state_publishers]
    out = []
    for info, sp in rsps:
        # several robot_state_publishers in one tree (a robot and its dock, two robots): each takes the nodes
        # of its own namespace; spawned controllers, joint state publishers and static transforms are shared
        ctrl, loc_files, spawned, js, tfs, notes, drivers = _beside(ws, tree.infos,
                                                                    sp.namespace if len(rsps) > 1 else None)
        notes = list(tree.notes) + notes
        chain = tree.chains.get(id(info), ())
        common = dict(namespace=sp.namespace, frame_prefix=sp.frame_prefix, launch=Location(root), rsp=sp.loc,
                      chain=chain, controller_files=ctrl, localization_files=loc_files, spawned=spawned,
                      joint_state=js, static_tfs=tfs, infos=tree.infos, variant=variant, driver_nodes=drivers)
        ref = sp.description
        if ref is None and sp.description_key:  # ROS 1: the parameter an included launch file writes
            ref = next((i.descriptions[sp.description_key] for i in tree.infos
                        if sp.description_key in getattr(i, "descriptions", {})), None)
        if ref is None:
            why = getattr(sp, "unread", "")
            out.append(Deployment(None, notes=notes + [("the model robot_state_publisher gets is not understood"
                                                         + (f": {why}" if why else ""), sp.loc)],
                                  **common))
            continue
        missing = ""
        if UNKNOWN in (ref.path or ""):
            files = ws.match(ref.path)
            picked = [(f, f"model={os.path.basename(f)}") for f in files]
            if not picked:
                notes.append((f"model path {_show(ref.path).replace(UNKNOWN, '*')} is decided at launch time and "
                               "matches no file", ref.loc))
        else:
            f = ws.locate(ref.path)
            picked = [(f, "")] if f else []
            if not picked:
                notes.append((f"model file {_show(ref.path)} not found in the workspace", ref.loc))
                missing = ws.missing(ref.path)
            elif sdformat(f):
                notes.append((f"{_show(f)} is an SDFormat model (read through sdformat_urdf), not a URDF: "
                              "not checked", ref.loc))
                picked = []
        if not picked:
            out.append(Deployment(None, notes=notes, **common))
            out[-1].missing = missing if UNKNOWN not in (ref.path or "") else ""
            continue
        args, dropped = {}, []
        for k, v in ref.args:
            if UNKNOWN in v:
                dropped.append(k)
                continue
            if os.path.isabs(v) and not os.path.exists(v) and ws.inside(v):
                v = ws.locate(v) or v  # a parameter file named in the install layout
            args[k] = v
        if dropped:
            notes.append((f"xacro argument(s) {', '.join(dropped)} are decided at launch time; the model's "
                          "defaults are used", ref.loc))
        ctrl_launched = bool(ctrl)
        if not ctrl and picked:
            # the controller manager is the simulator's plugin: its parameter file is named in the model
            files, unknown = plugin_parameter_files(ws, picked[0][0])
            if len(files) == 1:
                ctrl = [files[0]]
                common["controller_files"] = ctrl
                notes.append((f"controllers read from {_show(files[0])}, which the model's Gazebo ros2_control "
                              "plugin loads", sp.loc))
            elif files or unknown:
                notes.append(("the model's Gazebo ros2_control plugins load "
                              f"{', '.join([_show(f) for f in files] + unknown)}: which one runs is decided by "
                              "xacro arguments; not read", sp.loc))
        from_plugin = tuple(common["controller_files"]) if not ctrl_launched else ()
        for f, label in picked:
            c = dict(common)
            c["variant"] = ",".join(x for x in (variant, label) if x)
            out.append(Deployment(f, ref.how, args, notes=list(notes), dropped_args=dropped, **c))
            out[-1].plugin_files = from_plugin
    return out


def _beside(ws: _Workspace, infos, namespace: str | None):
    """Controller and localization parameter files, spawned controllers, joint state sources and static
    transforms of the nodes in `infos` (in `namespace` when given)."""
    from urdfcheck.consumers.localization import owner_packages

    ctrl, loc_files, spawned, js, tfs, notes, drivers = [], [], [], [], [], [], []
    owned = owner_packages()  # TF owners of the table: read by `localization`, not as custom drivers

    def add(files, path, where):
        got = ws.locate(path)
        if got is None:
            notes.append((f"parameter file {_show(path) if path else '?'} not found in the workspace", where))
        elif got not in files:
            files.append(got)

    from urdfcheck.consumers.controllers import CONTROLLER_EXES

    for info in infos:
        spawner_locs = set()
        for n in info.nodes:
            if namespace is not None and n.namespace != namespace:
                continue
            if n.package == "controller_manager" and n.executable in CONTROLLER_EXES:
                spawner_locs.add(n.loc)
                for f in n.param_files:
                    add(ctrl, f, n.loc)
            elif n.package in LOCALIZATION_PACKAGES or n.package.startswith("nav2_") or n.package in owned:
                for f in n.param_files:
                    add(loc_files, f, n.loc)
            elif n.package and not known_kind(n.package):
                files: list = []
                for f in n.param_files:
                    add(files, f, n.loc)
                if files or n.params:
                    drivers.append((n, files))
        for f, where in info.param_files:
            if where in spawner_locs:
                add(ctrl, f, where)
        for item in info.param_sets:
            f = getattr(item, "file", None)
            if f:
                add(ctrl, f, item.loc)
        spawned.extend(info.spawned)
        js.extend((j.package, j.loc) for j in info.joint_state_publishers)
        js.extend((name, where) for name, where in info.spawned if "joint_state" in name)
        tfs.extend(info.static_tfs)
    return ctrl, loc_files, spawned, js, tfs, notes, drivers


_PLUGIN = lazyre.compile(r"""<plugin\b[^>]*filename\s*=\s*["'][^"']*ros2_control[^"']*["'][^>]*>(.*?)</plugin>""", re.S)
_PARAMS = lazyre.compile(r"<parameters>\s*([^<]+?)\s*</parameters>")
_FIND = lazyre.compile(r"^\$\(\s*find(?:-pkg-share)?\s+([A-Za-z0-9_]+)\s*\)(/[^$]*)$")


def plugin_parameter_files(ws: _Workspace, model: str, max_files: int = 200) -> tuple[list[str], list[str]]:
    """Parameter files the model's Gazebo ros2_control plugins load (`<parameters>$(find pkg)/x.yaml`), read
    as text through the model's literal includes: (files found, references not literal)."""
    from urdfcheck.load.packages import literal_includes

    found, unknown = [], []
    for _path, text in literal_includes([model], lambda n: ws.find(n, model), max_files):
        for block in _PLUGIN.finditer(text):
            for m in _PARAMS.finditer(block.group(1)):
                ref = m.group(1).strip()
                hit = _FIND.match(ref)
                root = ws.find(hit.group(1), model) if hit else None
                got = ws.locate(root + hit.group(2)) if root else None
                if got is None:
                    unknown.append(ref)
                elif got not in found:
                    found.append(got)
    return found, unknown


# --- entry point --------------------------------------------------------------------------------------------
def find_deployments(root: str | os.PathLike, resolver=None, *, packages: Mapping[str, str] | None = None,
                     files: Iterable[str] | None = None) -> list[Deployment]:
    """Every deployment the launch files below `root` define (see the module docstring). `resolver` (a
    `load.packages.Resolver`) finds packages outside the workspace; `packages` maps names explicitly;
    `files` limits the launch files read (default: all below `root`). Never raises on bad input."""
    ws = _Workspace(str(root), resolver, packages)
    paths = sorted(files) if files is not None else launch_files(ws.root)
    # roots: launch files that no other launch file of the workspace includes, or names in an include that
    # runs only under a condition (bringup's custom_robot.launch.py: an alternative, not a deployment)
    included: set[str] = set()
    starts_rsp: set[str] = set()
    infos = {p: ws.read(p, {}) for p in paths}
    for p, info in infos.items():
        if getattr(info, "state_publishers", None):
            starts_rsp.add(realpath(p))
        for inc in getattr(info, "includes", ()):
            target = ws.locate(inc.file) if inc.file else None
            if target is not None:
                included.add(realpath(target))
        for f in ws.inactive_includes(p):
            target = ws.locate(f)
            if target is not None:
                included.add(realpath(target))
    roots = [p for p in paths if realpath(p) not in included]
    out: list[Deployment] = []
    seen: dict[tuple, Deployment] = {}
    reached: set[str] = set()
    # then an included file that starts robot_state_publisher itself, when no root reaches it (an include
    # hidden in an OpaqueFunction loop, a file name decided at launch time)
    later = [p for p in paths if realpath(p) in included and realpath(p) in starts_rsp]
    for rootfile in roots + later:
        if realpath(rootfile) in reached:
            continue
        for dep, tree in _root_deployments(ws, rootfile):
            reached.update(f for f in tree.files)
            k = dep.key()
            if dep.model is not None and k in seen:
                continue
            seen[k] = dep
            out.append(dep)
    from urdfcheck.plan.unread import mark_unread

    mark_unread(out, ws.root, included)
    return out


def _root_deployments(ws: _Workspace, rootfile: str):
    base = _walk_tree(ws, rootfile, {})
    if not any(info.state_publishers for info in base.infos):
        return
    dims = _choice_dims(base, {})
    required = _required(base) & set(dims)
    assignments: list[tuple[str, dict]] = []
    if not required:
        assignments.append(("", {}))
    fixed = {n: dims[n][0] for n in required}
    for name, choices in dims.items():
        for c in dict.fromkeys(choices, None) if len({x.lower() for x in choices}) == len(choices) else \
                {x.lower(): x for x in reversed(choices)}.values():  # True/true/False/false: two variants
            a = {**fixed, name: c}
            label = ",".join(f"{k}={v}" for k, v in a.items())
            if label not in [x for x, _ in assignments]:
                assignments.append((label, a))
    done = 0
    first = None
    for label, a in assignments[:MAX_VARIANTS]:
        tree = base if not a else _walk_tree(ws, rootfile, a)
        deps = _deployments(ws, rootfile, tree, label)
        first = deps if first is None else first
        done += 1
        for dep in deps:
            yield dep, tree
    if first is None or required:
        return
    for name, value in _bool_dims(base, dims).items():  # each boolean flipped alone, where it reaches the model
        if done >= MAX_VARIANTS:
            return
        tree = _walk_tree(ws, rootfile, {name: value})
        deps = _deployments(ws, rootfile, tree, f"{name}={value}")
        done += 1
        if _reaches_model(first, deps):
            for dep in deps:
                yield dep, tree


def describe(deployments: list[Deployment], show=None) -> str:
    """The deployments as `urdfcheck lint --list` shows them. `show`: how a path is printed (default:
    relative to the working directory when below it); xacro arguments equal to a launch default are counted,
    not listed (`Deployment.chosen_args`)."""
    if show is None:
        show = _show

    def at(loc) -> str:
        return str(loc._replace(file=show(loc.file))) if loc is not None and loc.file else str(loc)

    if not deployments:
        return "no deployments found (no launch file starts robot_state_publisher)\n"
    lines = []
    for d in deployments:
        where = show(d.launch.file) if d.launch is not None else "?"
        lines.append(where + (f" [{d.variant}]" if d.variant else ""))
        if d.model is None:
            lines.append("  model: not understood")
        else:
            chosen = d.chosen_args()
            hidden = len(d.args) - len(chosen)
            lines.append(f"  model: {show(d.model)}" + (f" (+{hidden} xacro argument(s) equal to launch defaults)"
                                                          if hidden else ""))
            lines.extend(f"    {k}:={show(v) if os.path.isabs(v) else v}" for k, v in sorted(chosen.items()))
        if d.dropped_args:
            lines.append(f"  arguments decided at launch time: {', '.join(d.dropped_args)}")
        lines.append(f"  robot_state_publisher: {at(d.rsp)}  namespace {d.namespace}"
                     + (f"  frame_prefix {d.frame_prefix!r}" if d.frame_prefix else ""))
        for loc in d.chain:
            lines.append(f"  via include at {at(loc)}")
        types, nodes = _read_back(d)
        if d.controller_files:
            lines.append("  controller files: " + ", ".join(show(f) for f in d.controller_files))
        if d.spawned:
            lines.append("  spawned: " + ", ".join(
                n + (f" ({types[n]})" if types.get(n) else " (type not found)")
                for n in dict.fromkeys(n for n, _ in d.spawned)))
        declared = [n for n in types if n not in {x for x, _ in d.spawned}]
        if declared:
            lines.append("  declared, not spawned here: " + ", ".join(f"{n} ({types[n]})" for n in declared))
        lines.append("  publishers: robot_state_publisher" + "".join(
            f", {n}" for n in dict.fromkeys(n for n, _ in d.joint_state)))
        if d.static_tfs:
            lines.append("  static transforms: " + ", ".join(f"{t.parent}->{t.child}" for t in d.static_tfs))
        if d.localization_files or nodes:
            # each node with the file it was read from: a file is never listed under another node's kind
            named = {realpath(f) for _, _, f in nodes if f}
            rest = [show(f) for f in d.localization_files if realpath(f) not in named]
            lines.append("  localization: " + ", ".join(
                [f"{kind} {node}" + (f" ({show(f)})" if f else "") for kind, node, f in nodes]
                + ([f"no TF owner in {', '.join(rest)}"] if rest else [])))
        for msg, loc in dict.fromkeys(d.notes):
            lines.append(f"  note: {msg} ({at(loc)})")
    n = sum(1 for d in deployments if d.model is not None)
    lines.append(f"{len(deployments)} deployment(s), {n} with a model")
    return "\n".join(lines) + "\n"


def show_args(args: Mapping[str, str], show, total: int | None = None, files: bool = True) -> str:
    """` a:=1 b:=path` (absolute paths printed with `show`; left out with files=False), then how many of
    `total` arguments were left out."""
    shown = {k: (show(v) if os.path.isabs(v) else v) for k, v in sorted(args.items())
             if files or not os.path.isabs(v)}
    text = "".join(f" {k}:={v}" for k, v in shown.items())
    hidden = (len(args) if total is None else total) - len(shown)
    return text + (f" (+{hidden} more)" if hidden > 0 else "")


def _read_back(d: Deployment) -> tuple[dict[str, str], list[tuple[str, str, str]]]:
    """The controllers (name -> type) and localization nodes (kind, node, file) the deployment's files declare,
    for `describe` (an unreadable file is reported by the lint run, not here)."""
    try:
        c = d.consumers()
    except Exception:  # noqa: BLE001 - a listing never fails on a file the lint run reports
        return {}, []
    types = {ctl.name: ctl.type or "" for ctl in c.controllers}
    return types, [(n.kind, n.node, n.file if n.file and os.path.isfile(n.file) else "") for n in c.localization]
