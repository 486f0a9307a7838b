"""MoveIt configuration as a consumer of the model (issue 41): the SRDF and the YAML files of a MoveIt config package.

A MoveIt config (one SRDF, plain or `.srdf.xacro`, with the `joint_limits.yaml`, `kinematics.yaml`,
`moveit_controllers.yaml` and `initial_positions.yaml` beside it) names the model's links and joints. It is found
zero-config in the model's own package and in the packages beside it (the folder that holds the model's package),
and paired with the model by evidence when it has some: the package's `.setup_assistant` names the model's file
(package and path), or one of its launch or xacro files names the model's file and package. Otherwise a config whose
SRDF gives the model's robot name is paired as a guess (`core.evidence`: findings resting on it are infos).

Every file is read through the door (`core.door.read_bytes`: confined to the run's roots, regular files only,
capped); an SRDF written as xacro is expanded by the project's sandboxed xacro (`load.loader.expand`). Reading never
raises.
"""
from __future__ import annotations

import os
from pathlib import Path

from urdfcheck.core.evidence import Step
from urdfcheck.core.findings import Location
from urdfcheck.core.records import Record

SRDF_SUFFIXES = (".srdf", ".srdf.xacro")
YAML_KINDS = {
    "joint_limits": ("joint_limits.yaml",),
    "kinematics": ("kinematics.yaml", "moveit_kinematics.yaml"),
    "controllers": ("moveit_controllers.yaml", "simple_moveit_controllers.yaml", "ros_controllers.yaml",
                    "controllers.yaml"),
    "initial_positions": ("initial_positions.yaml",),
}
ROS2_CONTROLLERS = ("ros2_controllers.yaml",)
LAUNCH_SUFFIXES = (".launch.py", ".launch", ".launch.xml", ".launch.yaml", ".launch.yml")
MAX_LAUNCHERS = 300
MAX_BYTES = 2 * 1024 * 1024
MAX_DIRS = 400  # folders looked at for config packages beside the model's package
SKIP_DIRS = {"build", "install", "log", "node_modules", "__pycache__"}


class Named(Record):
    """A name an SRDF or YAML file gives, with where."""

    _fields = ('name', 'loc')

    def __init__(self, name: str, loc: Location):
        self.name = name
        self.loc = loc


class Group(Record):
    _fields = ('name', 'loc', 'links', 'joints', 'chains', 'subgroups')

    def __init__(self, name: str, loc: Location):
        self.name = name
        self.loc = loc
        self.links: list[Named] = []
        self.joints: list[Named] = []
        self.chains: list[tuple[Named, Named]] = []  # (base_link, tip_link)
        self.subgroups: list[Named] = []


class Srdf(Record):
    # states: (name, group, loc, [(joint Named, value text)]); virtual: (name, parent_frame, child Named, loc)
    # disabled: (link Named, ...) per <disable_collisions>/<disable_default_collisions>/<enable_collisions>
    # end_effectors: (name, parent_link Named, loc)
    _fields = ('file', 'robot', 'groups', 'states', 'virtual', 'passive', 'disabled', 'end_effectors')

    def __init__(self, file: str, robot: str = ""):
        self.file = file
        self.robot = robot
        self.groups: dict[str, Group] = {}
        self.states: list = []
        self.virtual: list = []
        self.passive: list[Named] = []
        self.disabled: list = []
        self.end_effectors: list = []
        self.declared: tuple = ()  # the xacro arguments a `.srdf.xacro` declares (none for a plain SRDF)

    def group_joints(self, model) -> set[str] | None:
        """Every joint some group holds: named, on a chain, or between two of its links (a link group's
        parent joints), through subgroups. None when a chain does not resolve in the model (M001 says so; what the
        group was meant to hold is then unknown)."""
        out: set[str] = set()
        for g in self.groups.values():
            out |= {j.name for j in g.joints}
            for base, tip in g.chains:
                p = model.path(base.name, tip.name) if base.name in model.links and tip.name in model.links else None
                if p is None:
                    return None
                out |= {j.name for j in p[0] + p[1]}
            for ln in g.links:
                j = model.parent_joint.get(ln.name)
                if j is not None:
                    out.add(j.name)
        return out


class MoveItConfig(Record):
    """One SRDF with the MoveIt YAML files beside it, paired with a model by `step`."""

    # controllers: (controller name, [joint Named], Location of the controller)
    _fields = ('package', 'srdf', 'joint_limits', 'kinematics', 'controllers', 'initial_positions', 'step', 'files',
               'notes')

    def __init__(self, package: str, srdf: Srdf, step: Step):
        self.package = package
        self.srdf = srdf
        self.step = step
        self.joint_limits = None  # YamlDoc
        self.kinematics = None  # YamlDoc
        self.controllers: list = []
        self.initial_positions = None  # YamlDoc
        self.ros2_controllers = ()  # the config package's ros2_control controllers (consumers.controllers.Controller)
        self.files: list[str] = [srdf.file]
        self.notes: list = []


def _read(path: str, what: str = "file") -> bytes:
    """The bytes of `path` through the door; ConsumerError (reported located, never raised to the user) otherwise."""
    from urdfcheck.consumers.common import ConsumerError
    from urdfcheck.core import door
    from urdfcheck.load.packages import leaves_cwd

    if leaves_cwd(path):
        raise ConsumerError(f"{what} is, or lies in, a symbolic link that leads out of the working directory; "
                            "not read", Location(path))
    try:
        data = door.read_bytes(path, limit=MAX_BYTES)
    except OSError as e:
        raise ConsumerError(f"cannot read {what}: {getattr(e, 'strerror', None) or e}", Location(path)) from None
    if len(data) > MAX_BYTES:
        raise ConsumerError(f"{what} is larger than {MAX_BYTES} bytes; refused", Location(path))
    return data


_TEXTS: dict = {}  # small files read for the words they name, by file state (every model asks again)


def _cached(path: str) -> bytes:
    try:
        st = os.stat(path)
        key = (path, st.st_mtime_ns, st.st_size, st.st_ino)
    except OSError:
        key = None
    got = _TEXTS.get(key) if key is not None else None
    if got is None:
        got = _read(path)
        if key is not None and len(got) <= 256 * 1024:
            if len(_TEXTS) >= 2 * MAX_CACHED:
                _TEXTS.clear()
            _TEXTS[key] = got
    return got


def _yaml(path: str):
    """The YamlDoc of `path`. Raises ConsumerError."""
    from urdfcheck.consumers.yamlsrc import parse_yaml

    return parse_yaml(_read(path, "YAML file"), path, max_bytes=MAX_BYTES)


# --- SRDF ------------------------------------------------------------------------------------------------
# SRDFs read in this process, by file state and arguments: every model of a package asks for the same configs,
# and an SRDF written as xacro is one sandboxed expansion (a worker) each time
_SRDFS: dict = {}
MAX_CACHED = 256


def read_srdf(path: str, packages=None, args=None) -> Srdf:
    """The SRDF at `path`; a `.srdf.xacro` is expanded in the sandbox with its default arguments (or `args`).
    Raises ConsumerError when it cannot be read, parsed or expanded."""
    from urdfcheck.consumers.common import ConsumerError

    try:
        st = os.stat(path)
        key = (os.path.realpath(path), st.st_mtime_ns, st.st_size, tuple(sorted((args or {}).items())),
               tuple(sorted((packages or {}).items())))
    except OSError:
        key = None
    got = _SRDFS.get(key) if key is not None else None
    if got is None:
        try:
            got = _read_srdf(path, packages, args)
        except ConsumerError as e:
            got = e
        if key is not None:
            if len(_SRDFS) >= MAX_CACHED:
                _SRDFS.clear()
            _SRDFS[key] = got
    if isinstance(got, ConsumerError):
        raise got
    return got


def _read_srdf(path: str, packages=None, args=None) -> Srdf:
    from urdfcheck.consumers.common import ConsumerError

    if path.endswith(".xacro"):
        from urdfcheck.load.loader import expand

        try:
            exp = expand(path, dict(args or {}), packages=dict(packages or {}))
        except Exception as e:  # noqa: BLE001 - never a traceback: an unexpandable SRDF is not read
            raise ConsumerError(f"SRDF could not be expanded: {type(e).__name__}", Location(path)) from None
        if exp.root is None:
            why = exp.findings[0].message if exp.findings else "not expanded"
            raise ConsumerError(f"SRDF could not be expanded: {why}", Location(path))
        out = _srdf_from(exp.root, exp.locate, path)
        from urdfcheck.load.variants import defaulted_args

        try:
            out.declared = tuple(dict.fromkeys([*(exp.declared_args or ()), *defaulted_args(path, packages)]))
        except Exception:  # noqa: BLE001 - arguments not told: the SRDF follows none
            out.declared = tuple(exp.declared_args or ())
        return out
    from urdfcheck.core import xmlfront

    data = _read(path, "SRDF")
    try:
        root, _ = xmlfront.parse(data)
    except Exception as e:  # noqa: BLE001 - syntax errors, refused constructs
        raise ConsumerError(f"SRDF is not well-formed XML: {e}", Location(path)) from None
    return _srdf_from(root, lambda el: Location(path, el.sourceline), path)


def _srdf_from(root, locate, path: str) -> Srdf:
    out = Srdf(path, root.get("name") or "")

    def named(el, attr: str) -> Named | None:
        v = (el.get(attr) or "").strip()
        return Named(v, locate(el)) if v else None

    for el in root:
        if not isinstance(el.tag, str):
            continue
        tag = el.tag
        if tag == "group":
            g = Group(el.get("name") or "", locate(el))
            for c in el:
                if not isinstance(c.tag, str):
                    continue
                if c.tag == "link" and named(c, "name"):
                    g.links.append(named(c, "name"))
                elif c.tag == "joint" and named(c, "name"):
                    g.joints.append(named(c, "name"))
                elif c.tag == "chain":
                    base, tip = named(c, "base_link"), named(c, "tip_link")
                    if base and tip:
                        g.chains.append((base, tip))
                elif c.tag == "group" and named(c, "name"):
                    g.subgroups.append(named(c, "name"))
            out.groups.setdefault(g.name, g)
        elif tag == "group_state":
            joints = [(named(c, "name"), c.get("value") or "") for c in el
                      if isinstance(c.tag, str) and c.tag == "joint" and named(c, "name")]
            out.states.append((el.get("name") or "", el.get("group") or "", locate(el), joints))
        elif tag == "virtual_joint":
            out.virtual.append((el.get("name") or "", el.get("parent_frame") or "", named(el, "child_link"),
                                locate(el)))
        elif tag == "passive_joint" and named(el, "name"):
            out.passive.append(named(el, "name"))
        elif tag in ("disable_collisions", "enable_collisions"):
            out.disabled.append(tuple(n for n in (named(el, "link1"), named(el, "link2")) if n))
        elif tag == "disable_default_collisions" and named(el, "link"):
            out.disabled.append((named(el, "link"),))
        elif tag == "end_effector":
            out.end_effectors.append((el.get("name") or "", named(el, "parent_link"), locate(el)))
    return out


# --- YAML ------------------------------------------------------------------------------------------------
def _controllers(doc) -> list:
    """MoveIt's controller list: `moveit_simple_controller_manager: {controller_names, NAME: {joints}}` (ROS 2)
    or `controller_list: [{name, joints}]` (ROS 1). A ros2_control parameter file has neither."""
    out = []
    data = doc.data if isinstance(doc.data, dict) else {}
    msc = data.get("moveit_simple_controller_manager")
    if isinstance(msc, dict):
        names = msc.get("controller_names")
        for name, body in msc.items():
            if isinstance(body, dict) and isinstance(body.get("joints"), list) and \
                    (not isinstance(names, list) or name in names):
                joints = [Named(j, doc.loc("moveit_simple_controller_manager", name, "joints", i))
                          for i, j in enumerate(body["joints"]) if isinstance(j, str)]
                out.append((name, joints, doc.key_loc("moveit_simple_controller_manager", name)))
    lst = data.get("controller_list")
    if isinstance(lst, list):
        for i, body in enumerate(lst):
            if isinstance(body, dict) and isinstance(body.get("joints"), list):
                joints = [Named(j, doc.loc("controller_list", i, "joints", k))
                          for k, j in enumerate(body["joints"]) if isinstance(j, str)]
                out.append((str(body.get("name") or ""), joints, doc.loc("controller_list", i)))
    return out


# --- finding the configs of a model ------------------------------------------------------------------------
def _files_in(pkg: Path, max_depth: int = 4, max_files: int = 2000) -> list[str]:
    out: list[str] = []
    for top, dirs, files in os.walk(pkg):
        depth = len(Path(top).relative_to(pkg).parts)
        dirs[:] = sorted(d for d in dirs if not d.startswith(".") and d not in SKIP_DIRS
                         and (depth == 0 or not (Path(top) / d / "package.xml").exists()))
        if depth >= max_depth:
            dirs[:] = []
        out.extend(os.path.join(top, f) for f in sorted(files))
        if len(out) > max_files:
            break
    return out[:max_files]


def _config_packages(model_pkg: Path) -> list[Path]:
    """The model's package and the ROS packages beside it that hold an SRDF, below the working directory."""
    from urdfcheck.load.packages import enclosing_package

    cwd = os.getcwd()
    found = [model_pkg]
    here = enclosing_package(Path(cwd))  # run inside a config package whose model lies elsewhere
    if here is not None and here != model_pkg:
        found.append(here)
    parent = model_pkg.parent
    if not str(parent).startswith(cwd.rstrip(os.sep) + os.sep) and str(parent) != cwd:
        return found
    seen = 0
    for top, dirs, files in os.walk(parent):
        seen += 1
        if seen > MAX_DIRS:
            break
        depth = len(Path(top).relative_to(parent).parts)
        if "package.xml" in files and Path(top) not in found and depth > 0:
            found.append(Path(top))
            dirs[:] = []
            continue
        dirs[:] = sorted(d for d in dirs if not d.startswith(".") and d not in SKIP_DIRS)
        if depth >= 3:
            dirs[:] = []
    return found


def _mentions(path: str, *words: str) -> bool:
    try:
        data = _cached(path)
    except Exception:  # noqa: BLE001 - an unreadable file names nothing
        return False
    return all(_names(data, w) for w in words)


def _names(data: bytes, word: str) -> bool:
    """`word` stands in `data` as a whole name: `panda.urdf` is not named by `panda.urdf.xacro`, nor
    `arm_description` by `arm_description_extra`."""
    import re

    w = word.encode()
    if w not in data:
        return False
    return re.search(rb"(?<![\w.-])" + re.escape(w) + rb"(?![\w.-])", data) is not None


def _setup_assistant_names(pkg: Path, entry: str, model_pkg_name: str | None, srdf_file: str = "") -> bool:
    """The package's `.setup_assistant` names the model's file (URDF package and relative_path) and, when it names
    one, this SRDF (SRDF relative_path)."""
    sa = pkg / ".setup_assistant"
    if not sa.is_file():
        return False
    try:
        doc = _yaml(str(sa))
    except Exception:  # noqa: BLE001
        return False
    urdf = doc.get("moveit_setup_assistant_config", "URDF") or doc.get("moveit_setup_assistant_config", "urdf")
    if not isinstance(urdf, dict):
        return False
    rel = str(urdf.get("relative_path") or "").strip("/")
    package = str(urdf.get("package") or "")
    if not rel:
        return False
    same_pkg = not package or package == model_pkg_name
    if not (same_pkg and os.path.abspath(entry).endswith(os.sep + rel.replace("/", os.sep))):
        return False
    srdf = doc.get("moveit_setup_assistant_config", "SRDF") or doc.get("moveit_setup_assistant_config", "srdf")
    named = str(srdf.get("relative_path") or "").strip("/") if isinstance(srdf, dict) else ""
    return not named or not srdf_file or \
        os.path.abspath(srdf_file) == os.path.abspath(os.path.join(pkg, named.replace("/", os.sep)))


def _fits(srdf: Srdf, model) -> bool:
    """Most links and joints the SRDF's groups and states name are the model's: the SRDF is about this model.
    A config of another robot or another variant (a dual-arm config beside the single arm) names mostly others."""
    links, joints = set(model.links), set(model.joints) | {v[0] for v in srdf.virtual}
    hits = total = 0
    for g in srdf.groups.values():
        for base, tip in g.chains:
            hits += (base.name in links) + (tip.name in links)
            total += 2
        hits += sum(n.name in links for n in g.links) + sum(n.name in joints for n in g.joints)
        total += len(g.links) + len(g.joints)
    for _, _, _, values in srdf.states:
        hits += sum(n.name in joints for n, _ in values)
        total += len(values)
    for pair in srdf.disabled:
        hits += sum(n.name in links for n in pair)
        total += len(pair)
    return total > 0 and hits * 2 >= total


def named_model(pkg: str, packages=None) -> str | None:
    """The model a MoveIt config package names in its `.setup_assistant` (URDF package and relative_path), as a
    path, when that file exists; None otherwise. `urdfcheck lint <moveit_config_pkg>` lints it."""
    sa = Path(pkg) / ".setup_assistant"
    if not sa.is_file():
        return None
    from urdfcheck.load.packages import Resolver

    try:
        doc = _yaml(str(sa))
    except Exception:  # noqa: BLE001 - an unreadable .setup_assistant names nothing
        return None
    urdf = doc.get("moveit_setup_assistant_config", "URDF") or doc.get("moveit_setup_assistant_config", "urdf")
    if not isinstance(urdf, dict) or not urdf.get("package") or not urdf.get("relative_path"):
        return None
    rel = str(urdf["relative_path"]).strip("/")
    if rel.startswith("..") or "/../" in rel or os.path.isabs(rel):
        return None
    root = Resolver(dict(packages or {}), near=Path(os.path.abspath(pkg))).find(str(urdf["package"]))
    if root is None:
        return None
    path = Path(root) / rel
    return str(path) if path.is_file() else None


def _named_srdf(path: str, packages, model) -> Srdf | None:
    """A xacro SRDF expanded with the model's name as `name` and `robot_name`; None when that fails too. Its robot
    name then says nothing, so it is dropped."""
    import copy

    from urdfcheck.consumers.common import ConsumerError

    name = getattr(model, "name", "")
    if not path.endswith(".xacro") or not name:
        return None
    try:
        srdf = copy.copy(read_srdf(path, packages, {"name": name, "robot_name": name}))
    except ConsumerError:
        return None
    srdf.robot = ""
    return srdf


def _pairing(pkg: Path, files: list[str], entry: str, model, model_pkg: Path, model_pkg_name: str | None,
             srdf: Srdf, launchers=()) -> Step | None:
    base = os.path.basename(entry)
    subject = f"{_shown(srdf.file)} for {_shown(entry)}"
    if _setup_assistant_names(pkg, entry, model_pkg_name, srdf.file):
        return Step("moveit", subject, "referenced")
    for f in launchers:  # a launch file beside them that starts MoveIt with this SRDF and this model
        if _mentions(f, base, os.path.basename(srdf.file)):
            return Step("moveit", subject, "launched")
    words = (base,) if pkg == model_pkg or not model_pkg_name else (base, model_pkg_name)
    for f in files:
        if f.endswith((".py", ".launch", ".xml", ".xacro")) and not f.endswith(SRDF_SUFFIXES) \
                and os.path.abspath(f) != os.path.abspath(entry) and _mentions(f, *words):
            return Step("moveit", subject, "referenced")
    stem = base.split(".", 1)[0]
    if pkg == model_pkg and stem and os.path.basename(srdf.file).split(".", 1)[0] == stem:
        # MoveItConfigsBuilder("NAME") reads config/NAME.urdf.xacro and config/NAME.srdf of its package
        for f in files:
            if f.endswith(".py") and (_mentions(f, "MoveItConfigsBuilder", f'"{stem}"')
                                      or _mentions(f, "MoveItConfigsBuilder", f"'{stem}'")):
                return Step("moveit", subject, "referenced")
    if model is not None and srdf.robot and srdf.robot == getattr(model, "name", None):
        return Step("moveit", subject, "package" if pkg == model_pkg else "shape",
                    "name the model in the config package's .setup_assistant or a launch file")
    return None


def _shown(path: str) -> str:
    try:
        return os.path.relpath(path)
    except ValueError:
        return path


def _pick(files: list[str], names: tuple, near: str) -> str | None:
    """The file of one kind for an SRDF: the one in its folder, else the package's only one."""
    hits = [f for f in files if os.path.basename(f) in names]
    here = [f for f in hits if os.path.dirname(f) == near]
    if here:
        return here[0]
    return hits[0] if len(hits) == 1 else None


def moveit_configs(entry: str, model, model_pkg: Path, *, packages=None, notes=None) -> list:
    """The MoveIt configs that consume the model at `entry` (in package `model_pkg`), each with its pairing."""
    from urdfcheck.consumers.common import ConsumerError
    from urdfcheck.load.packages import package_name

    out = []
    model_pkg_name = package_name(model_pkg / "package.xml")
    listed = [(pkg, _files_in(pkg)) for pkg in _config_packages(model_pkg)]
    launchers = [f for _, files in listed for f in files if f.endswith(LAUNCH_SUFFIXES)][:MAX_LAUNCHERS]
    for pkg, files in listed:
        srdfs = [f for f in files if f.endswith(SRDF_SUFFIXES)]
        if not srdfs:
            continue
        for path in srdfs:
            step = None
            try:
                srdf = read_srdf(path, packages)
            except ConsumerError as e:
                # a xacro SRDF that needs the robot's name (`name`, `robot_name`, which MoveIt launch files pass):
                # when a reference pairs it with this model, expanded with the model's name
                step = _pairing(pkg, files, entry, model, model_pkg, model_pkg_name, Srdf(path), launchers)
                srdf = _named_srdf(path, packages, model) if step is not None else None
                if srdf is None:
                    if notes is not None:
                        notes.append((f"MoveIt SRDF not read: {e.message}", e.location))
                    continue
            if not srdf.groups and not srdf.virtual and not srdf.disabled:
                continue  # a macro file (its content comes in through the SRDF that includes it)
            if model is not None and not _fits(srdf, model):
                continue  # most of what it names is not in this model: the config of another robot (or variant)
            step = step or _pairing(pkg, files, entry, model, model_pkg, model_pkg_name, srdf, launchers)
            if step is None:
                continue
            cfg = MoveItConfig(str(pkg), srdf, step)
            near = os.path.dirname(path)
            for kind, names in YAML_KINDS.items():
                f = _pick(files, names, near)
                if f is None:
                    continue
                try:
                    doc = _yaml(f)
                except ConsumerError as e:
                    if notes is not None:
                        notes.append((f"MoveIt file not read: {e.message}", e.location))
                    continue
                if kind == "controllers":
                    cfg.controllers = _controllers(doc)
                    if not cfg.controllers:
                        continue
                else:
                    setattr(cfg, kind, doc)
                cfg.files.append(f)
            f = _pick(files, ROS2_CONTROLLERS, near)
            if f is not None:
                from urdfcheck.consumers.controllers import read_controllers
                from urdfcheck.consumers.params import parse_params

                try:
                    cfg.ros2_controllers = tuple(read_controllers([parse_params(_read(f, "YAML file"), f)]))
                except ConsumerError as e:
                    if notes is not None:
                        notes.append((f"MoveIt file not read: {e.message}", e.location))
            out.append(cfg)
    return out
