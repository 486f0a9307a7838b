"""The consumers of one model, read once: what the contract (C) and TF (T) checks look at.

`consumers_for_model(model_config, config)` reads what the config declares for a model;
`discover_consumers(entry_path, model)` is the zero-config fallback: parameter files and launch files of the
package enclosing the model (see `discover`), associated with the model when the package has only one
entry model, or when they name one of its joints (parameter files) / its file name (launch files).

Reading never raises: unreadable files become `errors` (`ConsumerError`, reported as C007).
"""
from __future__ import annotations

import os
from collections.abc import Mapping
from pathlib import Path

from urdfcheck.consumers.common import ConsumerError
from urdfcheck.consumers.controllers import ControllerSet, Driver, read_controllers, read_driver
from urdfcheck.consumers.launch.xml import LaunchInfo, read_launch
from urdfcheck.consumers.localization import LocalizationNode, localization_from_launch, localization_from_params
from urdfcheck.consumers.openworld import names_a_joint as _names_a_joint
from urdfcheck.consumers.params import ParamFile, read_params
from urdfcheck.consumers.tfclaims import TFClaim, claims_from_owners
from urdfcheck.core.findings import Location
from urdfcheck.core.records import Record
from urdfcheck.core.walk import real as realpath  # remembered for the run

DEFAULT_FRAMES = {"map": "map", "odom": "odom", "base": "base_link"}


class Consumers(Record):
    # tf_owners: declared in the config
    # frames: REP-105 names: map, odom, base
    # frame_prefix: the config's robot_state_publisher frame_prefix for this model
    # notes: (message, Location)
    # origin: "config" or "discovered"
    # files: kind -> [paths read]
    _fields = ('controllers', 'drivers', 'launch', 'localization', 'tf_owners', 'frames', 'frame_prefix', 'errors',
               'notes', 'origin', 'files')
    # issue 20 (consumers.openworld), set after reading: unknown: (what, Location) not understood, which makes
    # absence claims infos; package_files: parameter files no deployment reads, checked against the model
    # (`settle`); elsewhere_localization: localization nodes of those files
    unknown: list = ()
    package_files: tuple = ()
    package_single = True
    elsewhere_localization: list = ()
    workspace: str | None = None  # the folder whose joint state broadcasters may run beside this deployment
    moveit: list = ()  # consumers.moveit.MoveItConfig: the MoveIt configs paired with the model (issue 41)

    plugin_files: tuple = ()
    # for a config the runner did not vouch for (`run_with`, issue 36): the files whose transforms count as published
    # (real paths), and a folder whose every file does; None: every file read counts
    run_files: frozenset | None = None
    run_root: str | None = None

    def runs(self, path: str) -> bool:
        """Does a transform read from `path` count as published (not only claimed)?"""
        if self.run_files is None:
            return True
        real = realpath(path)
        root = self.run_root
        return real in self.run_files or bool(root and (real == root or real.startswith(root.rstrip(os.sep) + os.sep)))

    def settle(self, model) -> Consumers:
        """Add the package's unread parameter files, once, now that the model is known; and, for a deployment or
        a config's model, the MoveIt configs beside the model (discovery looks for them itself)."""
        if self.origin != "discovered" and not self.__dict__.get("_moveit_looked"):
            self._moveit_looked = True
            entry = getattr(model, "source", None)
            root = _package_root(entry) if entry else None
            if root is not None and not self.moveit:
                self.moveit = _moveit(entry, model, root, {}, self.notes)
        plugin, self.plugin_files = self.plugin_files, ()
        if plugin:
            from urdfcheck.consumers.pairing import drop_unloaded

            drop_unloaded(self, plugin, model)
        files, self.package_files = self.package_files, ()
        if files:
            from urdfcheck.consumers.openworld import add_package_files

            add_package_files(self, files, model, _Reader(), single=self.package_single,
                              why="no launch file of this deployment reads its file")
        return self

    def __init__(self, controllers: ControllerSet | None = None,
                 drivers: list[Driver] | None = None,
                 launch: list[LaunchInfo] | None = None,
                 localization: list[LocalizationNode] | None = None,
                 tf_owners: list[TFClaim] | None = None,
                 frames: dict | None = None,
                 frame_prefix: str = "",
                 errors: list[ConsumerError] | None = None,
                 notes: list | None = None,
                 origin: str = "config",
                 files: dict | None = None):
        self.controllers = ControllerSet({}, ()) if controllers is None else controllers
        self.drivers = [] if drivers is None else drivers
        self.launch = [] if launch is None else launch
        self.localization = [] if localization is None else localization
        self.tf_owners = [] if tf_owners is None else tf_owners
        self.frames = dict(DEFAULT_FRAMES) if frames is None else frames
        self.frame_prefix = frame_prefix
        self.errors = [] if errors is None else errors
        self.notes = [] if notes is None else notes
        self.origin = origin
        self.files = {} if files is None else files
        # realpath of a consumer file -> the core.evidence.Step saying how it was paired with the model (issue
        # 37); the engine adds the steps of the files a finding points at
        self.pairing: dict = {}

    def pair(self, paths, how: str, model: str = "") -> None:
        """Record how `paths` were paired with the model (a file keeps its first, strongest pairing)."""
        from urdfcheck.consumers.pairing import step

        for p in paths:
            real = realpath(p)
            old = self.pairing.get(real)
            if old is None or (not old.strong and step(p, how).strong):
                self.pairing[real] = step(p, how, model)

    @property
    def empty(self) -> bool:
        return not (len(self.controllers) or self.drivers or self.launch or self.localization or self.tf_owners
                    or self.errors)

    def joint_uses(self):
        """Every (JointUse, owner kind) a controller or driver names."""
        for c in self.controllers:
            for u in c.joints + c.state_joints:
                yield u, "controller", c
        for d in self.drivers:
            for u in d.joints:
                yield u, "driver", d

    def launch_frame_prefix(self) -> str | None:
        """The frame_prefix of the one robot_state_publisher in the launch files, if exactly one (literal)."""
        rsps = [s for li in self.launch for s in li.state_publishers if not s.condition]
        if len(rsps) == 1 and rsps[0].frame_prefix is not None:
            return rsps[0].frame_prefix
        return None

    @property
    def rsp_prefix(self) -> str:
        if self.frame_prefix:
            return self.frame_prefix
        return self.launch_frame_prefix() or ""


class _Reader:
    def __init__(self):
        self.cache: dict[str, ParamFile | ConsumerError] = {}

    def params(self, path: str, errors: list) -> ParamFile | None:
        got = self.cache.get(path)
        if got is None:
            try:
                got = read_params(path)
            except ConsumerError as e:
                got = e
            self.cache[path] = got
        if isinstance(got, ConsumerError):
            if got not in errors:
                errors.append(got)
            return None
        return got


MAX_INCLUDE_DEPTH = 8
MAX_LAUNCH_FILES = 100


def _read_launch(paths, out: Consumers, args=None, packages=None, reader: _Reader | None = None,
                 follow: bool = False) -> None:
    """Read the launch files `paths`; with `follow`, also the files they include (the files a config names
    run together, so what they include runs too). Each file is read once, with the arguments of its first
    appearance; an include is not followed when its file or condition is not literal, or when it lies
    outside the including file's package and the known packages."""
    from urdfcheck.consumers.launch.params import _allowed_roots, _inside

    queue = [(str(p), args, 0) for p in paths]
    seen: set[str] = set()
    while queue:
        p, a, depth = queue.pop(0)
        real = realpath(p)
        if real in seen:
            continue
        seen.add(real)
        try:
            li = read_launch(p, args=a, packages=packages)
        except ConsumerError as e:
            out.errors.append(e)
            continue
        out.launch.append(li)
        if not follow:
            continue
        for inc in li.includes:
            why = None
            if inc.file is None:
                why = "its file name is not literal"
            elif inc.condition is not None:
                why = f"it runs only under a condition that cannot be decided ({inc.condition})"
            elif depth + 1 > MAX_INCLUDE_DEPTH or len(seen) + len(queue) >= MAX_LAUNCH_FILES:
                why = "too many nested launch files"
            elif not _inside(inc.file, _allowed_roots(li, packages or {})):
                why = "it is outside the including file's package and the known packages"
            elif not os.path.isfile(inc.file):
                why = "no such file"
            if why is not None:
                out.notes.append((f"include {inc.file or '?'} not followed: {why}", inc.loc))
                continue
            queue.append((inc.file, dict(inc.args), depth + 1))
    for li in out.launch:
        out.notes.extend(li.notes)
    if len(out.controllers) and any(li.param_sets for li in out.launch):
        from urdfcheck.consumers.launch.params import apply_launch_params

        r = reader or _Reader()
        out.notes.extend(apply_launch_params(out.controllers, out.launch, lambda f: r.params(f, []), packages or {}))


def _parsed(r: _Reader, paths, errors: list) -> list:
    """The parameter files among `paths` that parse (what does not is an error of the consumers)."""
    return [pf for pf in (r.params(p, errors) for p in paths) if pf is not None]


def _controllers(out: Consumers, pfs: list, types=None) -> None:
    """The controllers the parameter files declare (`types`: those a launch file's spawner sets), with their notes."""
    out.controllers = read_controllers(pfs, types)
    out.notes.extend(out.controllers.notes)
    for c in out.controllers:
        out.notes.extend(c.notes)


def consumers_for_model(mc, config=None, *, packages: Mapping[str, str] | None = None,
                        reader: _Reader | None = None) -> Consumers:
    """Consumers declared in the config for one model (`config.ModelConfig`)."""
    r = reader or _Reader()
    out = Consumers(origin="config")
    if config is not None:
        out.frames = {**DEFAULT_FRAMES, **dict(config.frames)}
        out.tf_owners = claims_from_owners(dict(config.tf_owners), dict(config.tf_owner_locs), Location(config.path),
                                           _owner_source(config))
    out.frame_prefix = mc.frame_prefix
    pfs = _parsed(r, mc.controllers, out.errors)
    _controllers(out, pfs)
    for d in mc.drivers:
        pf = r.params(d.file, out.errors)
        if pf is None:
            continue
        drv = read_driver(d, [pf])
        out.drivers.append(drv)
    loc_pfs = _parsed(r, mc.localization, out.errors)
    pk = dict(packages or (config.packages if config is not None else {}))
    _read_launch(mc.launch, out, dict(mc.launch_args), pk, r, follow=True)
    tf_owners(out, loc_pfs, r)
    _launch_typed(out, pfs)
    out.files = {"controllers": list(mc.controllers), "drivers": [d.file for d in mc.drivers],
                 "launch": list(mc.launch), "localization": list(mc.localization)}
    out.pair([f for fs in out.files.values() for f in fs], "config")
    out.pair([li.path for li in out.launch], "config")  # what the named launch files include runs with them
    if config is not None and not getattr(config, "vouched", True):
        out.run_files, out.run_root = run_with(mc, out)
    from urdfcheck.consumers.openworld import launch_unknowns

    # the config declares the world, but for what its launch files run that was not understood (issue 20)
    out.unknown = launch_unknowns(out, [d.file for d in mc.drivers])
    return out


# --- a deployment (plan.deployments) -------------------------------------------------------------------------
def deployment_consumers(dep) -> Consumers:
    """The contract checks' view of one deployment (`plan.deployments.Deployment`): read on each call (cheap,
    files are small)."""
    from urdfcheck.consumers.controllers import spawner_types
    from urdfcheck.consumers.openworld import infer_drivers

    out = Consumers(origin="deployment")
    r = _Reader()
    _refused_controller_files(dep, out)
    pfs = _parsed(r, dep.controller_files, out.errors)
    _controllers(out, pfs, spawner_types(dep.infos))  # types set in launch files too
    _spawned_broadcasters(dep, out)
    _idle(dep, out)
    lpfs = _parsed(r, dep.localization_files, out.errors)
    out.drivers = infer_drivers(dep.driver_nodes, r)
    out.launch = list(dep.infos)
    several = len({s.namespace for li in dep.infos for s in li.state_publishers}) > 1  # each robot its own
    tf_owners(out, lpfs, r, lambda f: _same_file(f, dep.localization_files), dep.namespace if several else None)
    out.frame_prefix = dep.frame_prefix or ""
    out.notes.extend(dep.notes)
    if len(out.controllers) and any(li.param_sets for li in out.launch):
        from urdfcheck.consumers.launch.params import apply_launch_params

        out.notes.extend(apply_launch_params(out.controllers, out.launch, lambda f: r.params(f, []), {}))
    out.files = {"controllers": list(dep.controller_files), "localization": list(dep.localization_files),
                 "launch": [li.path for li in dep.infos],
                 "drivers": sorted({f for _, files in dep.driver_nodes for f in files})}
    # what this deployment's launch files name or load runs with the model (issue 37: evidence)
    out.pair([f for fs in out.files.values() for f in fs], "launched", dep.model or "")
    from urdfcheck.consumers.openworld import deployment_unknowns

    out.unknown = deployment_unknowns(dep, out.drivers)
    out.package_files, out.package_single = list(dep.package_files), dep.package_single
    out.plugin_files = tuple(dep.plugin_files)
    out.workspace = dep.workspace
    return out


def _refused_controller_files(dep, out) -> None:
    """A controller_manager parameter file the door refuses (an absolute path or `../..` out of the checkout,
    a link out of it): C007 at the launch line that names it, as for a TF owner's file (issue 36), not a note
    that the workspace has no such file."""
    from urdfcheck.consumers.controllers import CONTROLLER_EXES
    from urdfcheck.consumers.localization import refused_file

    several = len({s.namespace for li in dep.infos for s in li.state_publishers}) > 1
    for info in dep.infos:
        for n in info.nodes:
            if n.package != "controller_manager" or n.executable not in CONTROLLER_EXES:
                continue
            if several and n.namespace != dep.namespace:
                continue
            for f in n.param_files:
                refused_file(f, f"controller_manager {n.name or n.executable}: parameter file", n.loc, out.errors,
                             "its controllers are not checked")


def _spawned_broadcasters(dep, out) -> None:
    """A spawned joint_state_broadcaster that no parameter file read here declares (its type is then set
    where the launch files cannot see: a Gazebo ros2_control plugin's <parameters>) is still a joint
    state source for every hardware joint: typed from its name, noted as inferred."""
    from urdfcheck.consumers.controllers import JSB, Controller, finish_controller

    names = {c.name for c in out.controllers}
    for name, loc in dep.spawned:
        if name in names or name.split("/")[-1] != "joint_state_broadcaster":
            continue
        names.add(name)
        c = Controller(name=name, node="/" + name, type="joint_state_broadcaster/JointStateBroadcaster",
                       type_loc=loc, loc=loc, kind=JSB, ros=2, file=loc.file, params={})
        finish_controller(c, names)
        out.controllers.controllers[c.node] = c
        out.notes.append((f"controller {name} is spawned here and taken to be a joint_state_broadcaster "
                          "(its parameter file is not among the files read)", loc))


def _idle(dep, out) -> None:
    """Mark the controllers this deployment configures but does not spawn, when its spawners were all read
    (every argument literal or resolved): what names them rests on a guess (rules.checks.contracts, issue 37)."""
    if not dep.spawned or any(getattr(li, "unread_spawners", False) for li in dep.infos):
        return
    started = {n.strip("/").split("/")[-1] for n, _ in dep.spawned}
    for c in out.controllers:
        if c.name not in started and "joint_state" not in (c.type or ""):
            c.idle = True


def _same_file(path: str, files) -> str | None:
    """`path` as read (a source file), or the file of `files` it names in the install layout."""
    if os.path.isfile(path):
        return path
    tail = os.sep.join(path.split(os.sep)[-2:])
    return next((f for f in files if f.endswith(os.sep + tail)), None)


# --- zero-config -----------------------------------------------------------------------------------------
def _package_root(entry: str) -> Path | None:
    p = Path(os.path.abspath(entry)).parent
    for d in (p, *p.parents):
        if (d / "package.xml").is_file():
            return d
    return None


def discover_consumers(entry: str, model=None, *, packages: Mapping[str, str] | None = None) -> Consumers | None:
    """Consumers found next to a model without a config; None when the model is in no ROS package."""
    from urdfcheck.load.discover import several_models

    root = _package_root(entry)
    if root is None:
        return None
    several, found_params, found_launch = several_models(root)
    single = not several
    joints = set(model.joints) if model is not None else set()
    out = Consumers(origin="discovered")
    r = _Reader()
    pfs = []
    from urdfcheck.consumers.prefilter import worth_parsing

    mine, others = _references(entry, root, several, found_params, found_launch, packages)
    skipped = []
    for p in found_params:
        real = realpath(p)
        if real in others:  # another model of the package names it: its file, not this model's
            skipped.append(p)
            continue
        if not single and real not in mine and not worth_parsing(p, joints):  # names none of the joints
            continue
        errs: list = []
        pf = r.params(p, errs)
        if pf is None:
            if single or real in mine:
                from urdfcheck.consumers.params import foreign

                out.errors.extend(e for e in errs if real in mine or not foreign(p, e))
            continue
        if single or real in mine or _names_a_joint(pf, joints):
            pfs.append(pf)
            out.pair([p], "referenced" if real in mine else "only" if single else "overlap", entry)
    out.controllers = read_controllers(pfs)
    for c in out.controllers:
        out.notes.extend(c.notes)
    from urdfcheck.consumers.openworld import package_drivers, package_unknowns

    base = os.path.basename(entry)
    launches = []
    # a file name that several models of the package share (robots/*/model.urdf) names none of them
    shared = not single and _shared_name(root, base)
    tail = "/".join(Path(entry).parts[-2:])
    for p in found_launch:
        if single or _mentions(p, base):
            launches.append(p)
            how = "only" if single else "guess" if shared and not _mentions(p, tail) else "referenced"
            out.pair([p], how, entry)
    pk = dict(packages or {})
    _read_launch(launches, out, None, pk, r)
    tf_owners(out, pfs, r)
    out.drivers = package_drivers(pfs, out.controllers, out.localization)  # the base driver's YAML (issue 20)
    _launch_typed(out, pfs)
    # every launch file of the package, associated with this model or not: when none starts a
    # robot_state_publisher, nothing in the package needs joint states (C003)
    out.files = {"params": [pf.path for pf in pfs], "launch": launches, "package_launch": list(found_launch)}
    from urdfcheck.consumers.pairing import others_files

    out.unknown = package_unknowns(out) + others_files(skipped)
    out.moveit = _moveit(entry, model, root, pk, out.notes)
    return out


def _moveit(entry: str, model, package: Path, packages: dict, notes: list) -> list:
    """The MoveIt configs in the model's package and beside it (issue 41); best effort, like discovery."""
    from urdfcheck.consumers.moveit import moveit_configs

    try:
        return moveit_configs(entry, model, package, packages=packages, notes=notes)
    except Exception:  # noqa: BLE001 - a MoveIt config that cannot be read leaves the model's other checks alone
        return []


def _references(entry: str, root, several: bool, params, launches, packages) -> tuple[set, set]:
    """In a package of several models: (the parameter files named for this model, those named for another
    model only), `consumers.pairing`. One model: nothing to tell apart."""
    if not several:
        return set(), set()
    from urdfcheck.consumers.pairing import finder, references
    from urdfcheck.load.discover import discover

    try:
        models = discover(str(root)).models
        return references(entry, str(root), models, params, launches, finder(str(root), packages))
    except OSError:
        return set(), set()


def consumers_near(entry: str, model=None, *, packages: Mapping[str, str] | None = None, config=None) -> Consumers:
    """Zero config (or a config with no entry for this model): the consumers beside the model
    (`discover_consumers`; none outside a ROS package), with the config's frames and TF owners, which a
    config names for every model. Discovery is best effort: a failure gives no consumers, never an error."""
    try:
        found = discover_consumers(entry, model, packages=packages)
    except Exception:  # noqa: BLE001 - discovery is best effort; never break the checks
        found = None
    c = found or Consumers(origin="none")
    if config is not None:
        c.frames = {**c.frames, **dict(getattr(config, "frames", {}) or {})}
        owners = dict(getattr(config, "tf_owners", {}) or {})
        if owners and not c.tf_owners:
            c.tf_owners = claims_from_owners(owners, dict(getattr(config, "tf_owner_locs", {}) or {}),
                                             Location(getattr(config, "path", "<config>")), _owner_source(config))
    return c


def consumers_of(model, ctx) -> Consumers:
    """The consumers the planner gave this target (`plan.plan.Target.consumers`). A context made by hand
    without them (tests, scripts calling the engine directly) gets those beside the model, computed here
    each time and never written back: a check context is not changed by the checks."""
    c = getattr(ctx, "contracts", None)
    if isinstance(c, Consumers):
        return c
    exp = getattr(ctx, "expanded", None)
    resolver = getattr(exp, "resolver", None)
    packages = {k: str(v) for k, v in getattr(resolver, "explicit", {}).items()} if resolver is not None else {}
    return consumers_near(getattr(exp, "entry", None) or model.source, model, packages=packages,
                          config=getattr(ctx, "config", None))


def run_with(mc, out: Consumers) -> tuple[frozenset, str | None]:
    """What runs with the model by the files alone, for a config the runner did not vouch for (issue 36): the
    (real paths of the) files whose transforms count as published, and a folder whose every file counts.

    Such a config declares which files run together; zero config counts only a launch file that starts
    robot_state_publisher with the model (or includes one that does), what it includes and the parameter files
    they load, each such launch file a deployment of its own. So: the files every declared launch file that
    reaches a robot_state_publisher runs; with none, the model's package (zero config reads the files beside the
    model). The `localization:` files too: they make the twin "consumers found beside it" (plan.plan). A file the
    config merely names may claim a transform (a conflict), never publish one (rules.checks.tf.graph.claim_only).
    """
    by_path = {realpath(li.path): li for li in out.launch}
    chains = []
    for top in mc.launch:
        todo, seen = [realpath(top)], set()
        while todo:
            real = todo.pop()
            if real in seen or real not in by_path:
                continue
            seen.add(real)
            todo.extend(realpath(inc.file) for inc in by_path[real].includes if inc.file)
        if any(by_path[r].state_publishers for r in seen):
            chains.append(seen | {realpath(f) for r in seen for f, _ in by_path[r].param_files})
    declared = {realpath(p) for p in mc.localization}
    if chains:
        return frozenset(set.intersection(*chains) | declared), None
    from urdfcheck.load.packages import enclosing_package

    pkg = enclosing_package(Path(os.path.abspath(mc.path)).parent)
    return frozenset(declared), (realpath(pkg) if pkg is not None else None)


def _owner_source(config) -> str:
    """The claims' source of the config's `tf_owners`: a config the runner did not vouch for declares publishers
    that may conflict, never publish (consumers.tfclaims.UNTRUSTED; issue 36)."""
    from urdfcheck.consumers.tfclaims import UNTRUSTED

    return "config" if getattr(config, "vouched", True) else UNTRUSTED


def tf_owners(out: Consumers, pfs: list, reader: _Reader, locate=None, namespace: str | None = None) -> None:
    """The localization, SLAM and driver nodes that broadcast transforms: those the launch files start (inline
    parameters over the files each node is given), then those of parameter files no such node has read.
    Discovered launch files of a package are often alternatives (sim/real): their nodes count only when one
    launch file starts them all."""
    nodes, used, notes = localization_from_launch(out.launch, lambda f: reader.params(f, []), locate, namespace,
                                                  refused=out.errors)  # C007 at the launch line, as controllers
    starters = {n.loc.file for n in nodes}
    if out.origin == "discovered" and len(starters) > 1:
        out.notes.append((f"TF-owning nodes are started by {len(starters)} launch files of the package, which may "
                          "be alternatives; only their parameter files are read", Location(sorted(starters)[0])))
        nodes, used = [], set()
    from_files = localization_from_params(pfs, skip=used)
    if out.origin == "discovered":
        from_files = _one_map_owner(from_files, out.notes)
    out.localization = nodes + from_files
    out.notes.extend(notes)


_MAP_OWNERS = ("amcl", "slam_toolbox", "cartographer")


def _one_map_owner(nodes: list, notes: list) -> list:
    """A package's parameter files for localization (AMCL) and for mapping (slam_toolbox, cartographer) are
    alternatives: without a launch file that starts them together, the first one read owns map -> odom."""
    seen: dict[tuple, LocalizationNode] = {}
    out = []
    for n in nodes:
        if n.kind in _MAP_OWNERS:
            edges = tuple((e.parent, e.child) for e in n.edges())
            first = next((seen[e] for e in edges if e in seen and seen[e].kind != n.kind), None)
            if first is not None:
                notes.append((f"{n.kind} {n.node} ({os.path.basename(n.file)}) and {first.kind} {first.node} "
                              f"({os.path.basename(first.file)}) are read as alternatives (mapping or localization): "
                              "no launch file starts them together", n.loc))
                continue
            for e in edges:
                seen.setdefault(e, n)
        out.append(n)
    return out


def _launch_typed(out: Consumers, pfs: list) -> None:
    """Controllers whose type a launch file gives (`spawner NAME -t TYPE`) and whose parameter file does not:
    read the parameter files again with those types (issue 15: such a diff drive was never checked)."""
    from urdfcheck.consumers.controllers import spawner_types

    types = spawner_types(out.launch)
    if not pfs or not types or all(out.controllers.by_name(n) is not None for n in types) \
            or any(li.param_sets for li in out.launch):  # (ROS 1 launch parameters were applied already)
        return
    out.controllers = read_controllers(pfs, launch_types=types)
    for c in out.controllers:
        if out.controllers.by_name(c.name) is c and c.name in types:
            out.notes.extend(c.notes)


def _shared_name(root, base: str) -> bool:
    from urdfcheck.load.discover import discover

    try:
        return sum(os.path.basename(m) == base for m in discover(str(root)).models) > 1
    except OSError:
        return False


def _mentions(path: str, name: str) -> bool:
    from urdfcheck.load.packages import leaves_cwd

    if leaves_cwd(path):
        return False
    try:
        from urdfcheck.consumers.pairing import named_in
        from urdfcheck.core import door

        return named_in(door.read_bytes(path, limit=2 * 1024 * 1024), name)  # agv.urdf is not named by agv.urdf.xacro
    except OSError:
        return False
