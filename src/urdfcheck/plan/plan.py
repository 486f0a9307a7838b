"""Planning: a `LintRequest` becomes the list of `Target`s to lint (model + xacro args + its consumers).

Which config applies where: the nearest config file at or above a path (like ruff), and inside a folder
each sub-folder holding its own config (a package's urdfcheck.yaml) is planned with that config, exactly as
`urdfcheck lint` run from inside it would: `urdfcheck lint src` from a workspace gives the union of linting
each package from inside it. A folder without config is planned package by package (each folder with a
package.xml discovered on its own), for the same reason.

A config with `models:` names the entry models and their consumers; each model's consumers are read once,
on first use (`Later`), and shared by its variants. Without config, the launch files that start
robot_state_publisher give deployments (`plan.deployments`: the model with the launch file's xacro
arguments and the consumers beside it). They are found once per folder the user names, not per package: a
bringup package's launch file that loads another package's model is a deployment of that model, and a model
that any deployment of the named tree loads is linted through its deployments only (its launch files give the
arguments it needs). The one exception to "the union of per-package runs": such a model, linted from inside
its own package, is linted alone. Other entry models are discovered and linted with their boolean variants;
a package of xacro libraries only is an info line (`TargetList.infos`), and a library is linted through the
robots that include it, never alone.
"""
from __future__ import annotations

import os
from pathlib import Path

from urdfcheck.core.paths import shown
from urdfcheck.core.records import Record
from urdfcheck.core.walk import real as realpath  # remembered for the run
from urdfcheck.plan.named import Named as _Named
from urdfcheck.request.request import LintRequest, Settings, UsageError

CONFIG_NAMES = ("urdfcheck.yaml", ".urdfcheck.yaml")  # config.CONFIG_NAMES (not imported: start-up)
MAX_DIRS = 20_000  # folders a workspace walk looks at
# files named on the command line that are certainly no robot description (a .xml or odd suffix may be one)
NOT_MODELS = (".yaml", ".yml", ".py", ".json", ".toml", ".txt", ".md", ".rst", ".cfg", ".ini", ".srdf", ".stl",
              ".dae", ".obj", ".png", ".jpg")


class Later:
    """A value computed on first use, once: a model's consumers, shared by its variants, are read while
    its first expansion runs rather than before it starts."""

    __slots__ = ("_fn", "_value")

    def __init__(self, fn):
        self._fn, self._value = fn, None

    def get(self):
        if self._fn is not None:
            fn, self._fn = self._fn, None
            self._value = fn()
        return self._value


class Target(Record):
    """One model to lint: an entry file with one xacro argument set.

    contracts: the consumers (consumers.consumers.Consumers) of this model, a `Later`, or None: zero config,
    found beside the model by `consumers()` once the model is built, and kept here (the checks never look
    for them, nor change their context). settings: the request as it applies here (its config file);
    None for targets made by hand (tests), which `run.lint_targets` lints with its own arguments.
    deployment: the launch file that starts this model (label and defining Location), when planned from one."""

    _fields = ('path', 'args', 'variant', 'contracts', 'packages', 'settings', 'deployment')
    bags: tuple = ()  # recordings a config declares for this model (urdfcheck.bag)
    joint_states: str | None = None  # their JointState topic (None: /joint_states, else the only one)
    probe = False    # may be a library: the expansion decides (plan.robots); the run sets `library`
    includers: tuple = ()  # files that may include this one (a probe): a symbol they define is no defect here
    # how the model and its deployment were chosen (core.evidence.Step), which every finding of it rests on
    evidence: tuple = ()
    library = False  # a probe whose expansion has no link: not a robot, not checked as one
    combination = False  # an automatic variant of a discovered model flipping several options (run._combinations)
    twin = False  # a declared model linted again with the consumers found beside it (an unvouched config's)

    def __init__(self, path: Path,
                 args: dict | None = None,
                 variant: str = "",
                 contracts: object = None,
                 packages: dict | None = None,
                 settings: Settings | None = None,
                 deployment: object = None):
        self.path = path
        self.args = {} if args is None else args
        self.variant = variant
        self.contracts = contracts
        self.packages = {} if packages is None else packages
        self.settings = settings
        self.deployment = deployment

    @property
    def contracts(self):
        c = self._contracts
        return c.get() if isinstance(c, Later) else c

    @contracts.setter
    def contracts(self, value) -> None:
        self._contracts = value

    def consumers(self, model, exp=None, config=None):
        """The consumers the checks of this target read, computed once. Planned ones (a config's models, a
        launch file's deployment) as planned; otherwise, inside a ROS package or under a config, those beside
        the model (`consumers.consumers.consumers_near`: the package's config/ and launch/ files; in a
        package of several models, the parameter files that name one of this model's joints, which is why
        they wait for the model), kept on the target. None: the model has no consumers to compare with."""
        c = self.contracts
        if c is not None:
            return c.settle(model) if hasattr(c, "settle") else c
        entry = getattr(exp, "entry", None) or getattr(model, "source", None) or str(self.path)
        from urdfcheck.consumers.reach import in_package

        if config is None and not in_package(entry):
            return None  # (the contract readers are not even imported)
        from urdfcheck.consumers.consumers import consumers_near

        resolver = getattr(exp, "resolver", None)
        packages = {k: str(v) for k, v in getattr(resolver, "explicit", {}).items()} if resolver is not None \
            else dict(self.packages)
        self._contracts = consumers_near(entry, model, packages=packages, config=config)
        return self._contracts


class TargetList(list):
    """The planned targets, and the planner's info lines (a package of xacro libraries only, a library file
    that no robot includes): said once, not findings, and not a reason to fail."""

    def __init__(self, targets=(), infos=()):
        super().__init__(targets)
        self.infos = list(infos)
        self.not_understood = []  # deployments whose model was not understood (no target; `--list`)
        self.findings = []  # about the plan itself: a config's ignored keys, a file walk cut short (issue 19)
        self.libraries = 0  # xacro libraries seen: "no robot found: N xacro libraries"
        self.included = []  # libraries by inclusion that may hold links (plan.robots.missed)
        self.library_files = []  # xacro libraries seen (macros only): a robot may include them under an argument


class Planner:
    """Plans one request; reads each config file once."""

    def __init__(self, request: LintRequest, here: str | None = None):
        self.request = request
        self.here = here or "."  # the folder a request without paths names (`urdfcheck lint` run there)
        self._configs: dict[str, object] = {}
        self._settings: dict[str | None, Settings] = {}
        self._named: dict[str, _Named] = {}
        self._robots: dict[str, list[Target]] = {}  # workspace folder -> its robots (a library's includers)
        self._closures: dict[tuple, set] = {}  # (model, packages) -> the files it includes literally
        self.infos: list[str] = []
        self.not_understood: list = []  # deployments whose model was not understood (`--list` shows them)
        self.truncated: list = []  # X019 findings: a file walk that stopped at its limit
        self.libraries: set = set()  # xacro libraries seen (a run that checked no robot counts them)
        self.included: list = []  # libraries by inclusion that may hold links: a model must read them (robots)

    # --- configs ----------------------------------------------------------------------------------
    def config(self, path: str | None):
        if path is None:
            return None
        if path not in self._configs:
            from urdfcheck.request import config as cfgmod

            try:
                named = self.request.config is not None and os.path.abspath(self.request.config) == path
                self._configs[path] = cfgmod.load_config(path, trusted=bool(named and self.request.trust_config),
                                                         root=self.request.config_root if named else None)
            except cfgmod.ConfigError as e:
                where = e.location or cfgmod.Location(path)
                at = shown(where.file) + "".join(f":{n}" for n in (where.line, where.column) if n)
                raise UsageError(f"invalid config {at}: {e}") from None
        return self._configs[path]

    def settings(self, cfg) -> Settings:
        key = getattr(cfg, "path", None)
        if key not in self._settings:
            self._settings[key] = self.request.settings(cfg)
        return self._settings[key]

    def nearest(self, path: str):
        if not self.request.use_config:
            return None
        if self.request.config is not None:
            return self.config(os.path.abspath(self.request.config))
        from urdfcheck.request.config import find_config

        return self.config(find_config(path))

    # --- walks: one that stops at its limit says so (X019), never a silent subset -------------------
    def walk(self, folder: str) -> _Walk:
        w = _walk(folder)
        if w.truncated:
            self.truncated.append(_cut_short(shown(folder), f"{MAX_DIRS} folders"))
        return w

    def discover(self, folder, settings: Settings):
        from urdfcheck.load.discover import MAX_FILES, discover

        limit = self.request.max_files or MAX_FILES
        found = discover(folder, trusted=settings.trusted, max_files=limit)
        self.libraries.update(realpath(p) for p in found.libraries)
        self.included.extend(getattr(found, "included", ()))
        if getattr(found, "truncated", False):
            self.truncated.append(_cut_short(shown(folder), f"{limit} files"))
        return found

    # --- planning ---------------------------------------------------------------------------------
    def plan(self) -> TargetList:
        req = self.request
        paths = list(req.paths)
        if not paths:
            cfg = self.nearest(os.path.abspath(self.here))
            if cfg is not None and cfg.models:
                found = self.declared(cfg, None)
                if not _vouched(cfg):  # its models add to the tree it governs, planned as a path (nested configs)
                    here = os.path.abspath(self.here)
                    near = _below(here, cfg.root) or _below(cfg.root, here)  # not a config kept elsewhere
                    found += self.path_targets(cfg.root if near else here)
                got = TargetList(_unique(found), dict.fromkeys(self.infos))
                got.not_understood = list(self.not_understood)
                got.findings, got.libraries = self.plan_findings(), len(self.libraries)
                got.library_files = sorted(self.libraries)
                got.included = list(dict.fromkeys(self.included))
                return got
            paths = [self.here]  # the package here (a workspace config above it applies to it, not all of it)
        out: list[Target] = []
        for raw in paths:
            out.extend(self.path_targets(raw))
        got = TargetList(_unique(out), dict.fromkeys(self.infos))
        got.not_understood = list(self.not_understood)
        got.findings, got.libraries = self.plan_findings(), len(self.libraries)
        got.library_files = sorted(self.libraries)
        got.included = list(dict.fromkeys(self.included))
        return got

    def plan_findings(self) -> list:
        """The configs' own findings (keys a config found in the checkout may not set), then the walks cut
        short: said in every report, never silently."""
        out = [f for c in self._configs.values() if c is not None for f in getattr(c, "notes", ())]
        return out + [f for f in dict.fromkeys(self.truncated)]

    def path_targets(self, raw: str) -> list[Target]:
        cfg = self.nearest(raw)
        settings = self.settings(cfg)
        from urdfcheck.load.packages import leaves_cwd

        if not settings.trusted and leaves_cwd(Path(raw), settings.packages.values()):
            return [self.target(Path(raw), {}, "", None, settings)]  # refused by the loader (X014)
        if not os.path.isdir(raw):
            if cfg is not None and cfg.model_for(raw) is not None:
                return self.declared(cfg, [raw])
            from urdfcheck.plan import dependents

            if _is_launch(raw):  # the per-file hook names a launch file: its robots, else what reads it
                return dependents.launch_or_readers(self, raw, settings)
            srdf = raw.lower().endswith((".srdf", ".srdf.xacro"))
            if dependents.is_dependent(raw) and (not srdf or _srdf_text(raw)):
                # a parameter, .lua or SRDF file (by its text: a robot in robot.srdf.xacro is a model): the
                # robots that read it
                return dependents.targets_reading(self, raw, settings)
            if raw.lower().endswith(NOT_MODELS):
                raise UsageError(f"{raw} is not a URDF or xacro model (name the model, its package, or a "
                                 "launch file that starts robot_state_publisher)")
            return self.file_targets(Path(raw), settings)
        # a folder: nested configs (when not given one explicitly) take their sub-trees
        walk = self.walk(raw)
        nested = [] if (self.request.config is not None or not self.request.use_config) else \
            [c for c in walk.configs if cfg is None or os.path.dirname(c) != cfg.root]
        nested_roots = [os.path.dirname(c) for c in nested]
        # the deployments of the whole named tree, once; a folder whose config declares its models keeps them
        declaring = [self.config(c).root for c in nested if self.config(c).models and _vouched(self.config(c))]
        if cfg is not None and _models_at(cfg, raw) and _vouched(cfg):
            declaring.append(os.path.abspath(raw))
        named = self.named(raw, settings, skip=declaring)
        out = self.scope(cfg, raw, walk, exclude=nested_roots, named=named)
        for c in nested:
            sub = self.config(c)
            deeper = [r for r in nested_roots if _below(r, sub.root) and r != sub.root]
            if sub.models:
                out.extend(t for t in self.declared(sub, None) if not _under_any(str(t.path), deeper))
                out.extend(self.added(sub, sub.root, self.walk(sub.root), exclude=deeper, named=named))
            else:
                out.extend(self.scope(sub, sub.root, self.walk(sub.root), exclude=deeper, named=named))
        return out

    def scope(self, cfg, folder: str, walk, exclude: list[str], named: _Named | None = None) -> list[Target]:
        """The models of `folder` under one config (or none): declared ones, else discovered."""
        settings = self.settings(cfg)
        if cfg is not None and _models_at(cfg, folder):
            return [t for t in self.declared(cfg, [folder]) if not _under_any(str(t.path), exclude)] \
                + self.added(cfg, folder, walk, exclude, named)
        return self.discovered(folder, walk, settings, exclude, named)

    def added(self, cfg, folder: str, walk=None, exclude=(), named: _Named | None = None) -> list[Target]:
        """What a config the runner did not vouch for cannot hide (issue 36): its `models:` add to discovery, so
        the robots of `folder` it does not declare are linted zero-config beside them (a clean decoy declared
        there does not hide the broken robot next to it). A vouched config's models are all that is linted."""
        if _vouched(cfg) or not os.path.isdir(folder):
            return []
        declared = {realpath(m.path) for m in cfg.models}
        got = self.discovered(folder, walk if walk is not None else self.walk(folder), self.settings(cfg),
                              exclude, named)
        return [t for t in got if not _covered(t, cfg) if t.deployment is not None
                or realpath(t.path) not in declared]

    def declared(self, cfg, paths) -> list[Target]:
        """The config's models (at or below `paths` when given); paths no model covers: discovered."""
        settings = self.settings(cfg)
        chosen, rest = [], []
        if paths:
            for raw in paths:
                hits = _models_at(cfg, raw)
                chosen.extend(m for m in hits if m not in chosen)
                if not hits:
                    rest.append(raw)
        else:
            chosen = list(cfg.models)
        out = []
        for m in chosen:
            consumers = Later(lambda m=m: _consumers(m, cfg, dict(settings.packages)))  # read in the warm-up
            for vname, vargs in m.variant_args():
                out.append(self.target(Path(m.path), vargs, vname, consumers, settings))
                out[-1].bags = m.bags
                out[-1].evidence = (_step("model", str(m.path), "config"),)
            if not _vouched(cfg) and (_undeclared_consumers(m) or _declares_localization(m)):
                # declared consumers add to those found beside the model, never replace them (issue 36): the
                # package's parameter and launch files the config leaves out are checked as zero config would
                twin = self.target(Path(m.path), m.variant_args()[0][1], "consumers found beside it", None, settings)
                twin.twin = True
                twin.evidence = (_step("model", str(m.path), "config"),)
                out.append(twin)
            if not _vouched(cfg) and (m.launch_args or m.frame_prefix):
                # launch arguments and a frame prefix choose what the declared launch files run and which frames
                # the model publishes: from an untrusted config they add a reading, never replace the one the
                # launch files give by themselves (issue 36): the same files, their own defaults and prefix
                plain = m.launch_defaults()
                twin = self.target(Path(m.path), m.variant_args()[0][1], "launch defaults",
                                   Later(lambda m=plain: _consumers(m, cfg, dict(settings.packages))), settings)
                twin.twin = "launch defaults"
                twin.evidence = (_step("model", str(m.path), "config"),)
                out.append(twin)
        for raw in rest:
            out.extend(self.file_targets(Path(raw), settings) if not os.path.isdir(raw)
                       else self.discovered(raw, self.walk(raw), settings))
        return out

    def discovered(self, folder: str, walk, settings: Settings, exclude=(), named: _Named | None = None
                   ) -> list[Target]:
        """Zero-config: the deployments whose launch file is below `folder` (found once for the named
        tree, `named`), then the entry models of each package below `folder` that no deployment of the named
        tree loads, each package discovered on its own; `folder` itself when it is inside a package or holds
        none. A package of xacro libraries only gives an info line."""
        from urdfcheck.load.packages import enclosing_package

        if named is None:
            named = self.named(folder, settings)
        out: list[Target] = []
        for d in named.deployments:
            if _below(d.launch.file, folder) and not _under_any(d.launch.file, exclude):
                out.append(self.deployed(d, named.root, settings))
        inside = enclosing_package(Path(os.path.abspath(folder))) is not None
        roots = [folder] if inside or not walk.packages else \
            [p for p in walk.packages if not _under_any(p, exclude)]  # a package with its own config: its own
        for root in roots:
            found = self.discover(root, settings)
            hinted: dict[str, list] = {}
            for f, by in getattr(found, "hints", ()):
                hinted.setdefault(realpath(f), []).append(by)
            for entry in found.probes:  # no link by its text: the expansion decides (plan.robots)
                if realpath(entry) not in named.covered:
                    out.append(self.probe(Path(entry), settings, named.root))
                    # whole, if it has links; one that another file may include is a fragment where it fails
                    # only on what that file provides (run: plan.robots.provided)
                    out[-1].evidence = (_step("model", entry, "complete"),)
                    out[-1].includers = tuple(hinted.get(realpath(entry), ()))
            if not found.models and not found.probes and found.libraries \
                    and not any(_below(t.path, root) for t in out):
                self.infos.append(f"{shown(root)}: xacro libraries only (macros, properties): "
                                  "linted through the robots that include them")
            for entry in found.models:
                if realpath(entry) not in named.covered:  # a deployment gives the args it needs
                    out.extend(_mark(self.variants(Path(entry), settings, named.root, found=True), "complete"))
        if not out:
            out.extend(self.moveit_model(folder, settings))
        if not inside and walk.packages and walk.loose:  # model files outside every package
            pk = walk.packages
            for entry in self.discover(folder, settings).models:
                if not _under_any(entry, pk) and realpath(entry) not in named.covered:
                    out.extend(_mark(self.variants(Path(entry), settings, named.root, found=True), "complete"))
        return [t for t in out if t.deployment is not None or not _under_any(str(t.path), exclude)]

    def moveit_model(self, folder: str, settings: Settings) -> list[Target]:
        """A MoveIt config package with no model of its own: the model its `.setup_assistant` names, whose
        checks then read this config (consumers.moveit) as one beside the model's package (issue 41)."""
        from urdfcheck.load.packages import enclosing_package

        pkg = enclosing_package(Path(os.path.abspath(folder)))
        if pkg is None:
            return []
        from urdfcheck.consumers.moveit import named_model

        model = named_model(str(pkg), dict(settings.packages))
        if model is None:
            return []
        from urdfcheck.load.packages import workspace_root

        real = realpath(model)
        inside = _below(real, realpath(os.getcwd()))
        if not inside and not _below(real, str(workspace_root(pkg))) \
                and not any(_below(real, realpath(p)) for p in settings.packages.values()):
            # a file of the checkout names it: a package of its workspace (as a launch file's $(find) resolves
            # one) or one the runner named, never an installed package elsewhere on the machine
            return []
        from urdfcheck.core.evidence import Step

        out = self.variants(Path(os.path.relpath(model)) if inside else Path(model), settings)
        for t in out:
            t.evidence = (Step("model", shown(model), "referenced",
                               f"named by {shown(str(pkg / '.setup_assistant'))}"),)
        return out

    def named(self, root: str, settings: Settings, skip=()) -> _Named:
        """The deployments of a named folder, found once (`skip`: folders whose config declares the models)."""
        key = os.path.abspath(root)
        if key not in self._named:
            deps = [d for d in self.find(key, settings) if not _under_any(d.launch.file, skip)]
            self._named[key] = _Named(key, deps, {realpath(d.model) for d in deps})
        return self._named[key]

    def find(self, root: str, settings: Settings, files=None) -> list:
        """The deployments with a model that the launch files below `root` (or `files`) define."""
        from urdfcheck.load.packages import Resolver
        from urdfcheck.plan.deployments import find_deployments

        resolver = Resolver(dict(settings.packages), near=Path(root), workspace=root)
        found = find_deployments(root, resolver, packages=dict(settings.packages), files=files)
        self.not_understood.extend(d for d in found if d.model is None and d not in self.not_understood)
        # what robot_state_publisher is given is a robot, whatever its name (issue 36: a robot.srdf.xacro
        # loaded as robot_description is not skipped); only a file whose text is MoveIt's semantic description
        # (groups, no link) is none
        return [d for d in found if d.model is not None and d.launch is not None and not _srdf_text(d.model)]

    def deployed(self, d, root: str, settings: Settings) -> Target:
        """A deployment's target: the launch file's xacro arguments, its controllers and localization as the
        consumers, every package of the named tree resolvable (a sibling repository's description)."""
        label = shown(d.launch.file) + (f" [{d.variant}]" if d.variant else "")  # like every path
        t = self.target(Path(d.model), dict(d.args), label, Later(d.consumers), settings,
                        _packages(root, d.model, settings))
        t.deployment = d
        t.evidence = (_step("deployment", label, "launched"),)
        return t

    def deployments(self, root: str, settings: Settings, files=None) -> list[Target]:
        """The deployments the launch files below `root` (or just `files`) define, as targets."""
        root = os.path.abspath(root)
        return [self.deployed(d, root, settings) for d in self.find(root, settings, files)]

    def launch_targets(self, path: str, settings: Settings) -> list[Target]:
        """A launch file named explicitly: the models it starts robot_state_publisher with."""
        from urdfcheck.load.packages import enclosing_package

        pkg = enclosing_package(Path(os.path.abspath(path)).parent)
        out = self.deployments(str(pkg or Path(path).parent), settings, files=[os.path.abspath(path)])
        if not out:
            raise UsageError(f"{path}: no robot_state_publisher with a model urdfcheck can read is started "
                             "there (name the model or its package)")
        return out

    def file_targets(self, path: Path, settings: Settings) -> list[Target]:
        """An explicitly named file. A xacro library (macros only, or included by another file of its
        package) is no robot by itself: lint the robots of its workspace (the working directory when the
        file is below it, else its package) that include it, as they are planned from there (deployments
        too): what the per-file pre-commit hook needs. A library no robot includes is an info line."""
        if path.name.endswith(".xacro"):
            from urdfcheck.load.packages import enclosing_package

            folder = Path(os.path.abspath(path)).parent
            pkg = enclosing_package(folder)
            found = self.discover(pkg or folder, settings)
            if realpath(path) in {realpath(x) for x in found.libraries} and _robot_file(path):
                robots = self.robots_including(str(path), str(pkg or folder), settings)
                real = realpath(path)
                for by in (b for f, b in getattr(found, "hints", ()) if realpath(f) == real):
                    if not robots:  # a computed, legacy or commented include: the robots that include its includer
                        robots = [t for t in self.robots_including(by, str(pkg or folder), settings)
                                  if realpath(t.path) != real]
                        ws = self.library_ws(by, str(pkg or folder))
                        robots = robots or [t for t in self.workspace_targets(ws)
                                            if realpath(t.path) == realpath(by)]
                maybe = {realpath(x) for x in (*found.probes, *found.included)}
                if not robots and realpath(path) in maybe:  # named: never skipped when it may be a robot
                    return _mark([self.probe(path, settings)], "named", force=True)
                if not robots:  # macros and properties only: certainly no link
                    self.infos.append(f"{shown(str(path))}: a xacro library that no robot of "
                                      "its workspace includes: not linted alone")
                self.included.append(str(path))  # the run checks that one of them did read it
                return robots + self.reaching(path, robots)
            if _robot_file(path):  # a robot named by itself (the per-file hook): its variants too
                return _mark(self.variants(path, settings), "named")
        return _mark([self.target(path, {}, "", None, settings)], "named")

    def reaching(self, fragment: Path, robots: list[Target]) -> list[Target]:
        """A fragment named on the command line that its robots include only under a xacro argument other than the
        one they are linted with: `reaching_targets`, with evidence `reaching` (the runner named the fragment)."""
        return reaching_targets(fragment, robots, self.infos, named=True)

    def probe(self, path: Path, settings: Settings, root: str | None = None) -> Target:
        """A file that may be a library: expanded with its defaults; a library when the expansion has no link."""
        t = self.target(path, {}, "", None, settings, _packages(root, str(path), settings) if root else None)
        t.probe = True
        t.evidence = (_step("model", str(path), "probe", f"lint {shown(str(path))} by name, or name it under "
                            "models: in urdfcheck.yaml, if it is a whole robot"),)
        return t

    def robots_including(self, library: str, pkg: str, settings: Settings) -> list[Target]:
        """The targets of the library's workspace whose model includes it (literal includes, read as text)."""
        from urdfcheck.load.packages import included_files

        ws = self.library_ws(library, pkg)
        real, out = realpath(library), []
        for t in self.workspace_targets(ws):
            key = (realpath(t.path), tuple(sorted(t.packages.items())))
            if key not in self._closures:
                self._closures[key] = included_files(t.path, lambda n, pk=t.packages: pk.get(n))
            if real in self._closures[key] and realpath(t.path) != real:
                out.append(t)
        return out

    def library_ws(self, library: str, pkg: str) -> str:
        """Where the robots including a library are looked for: the checkout around it (where the door lets the run
        read), never a folder above it (the working directory may hold the runner's other files), so the same from
        a folder of repositories as from the repository's root."""
        from urdfcheck.core.checkout import run_roots

        here = os.path.abspath(self.here)
        ws = next((r for r in run_roots((library,), cwd=here) if _below(library, r)), os.path.abspath(pkg))
        return _unskipped(ws, os.path.dirname(os.path.abspath(library)))

    def workspace_targets(self, ws: str) -> list[Target]:
        """The targets of a workspace folder as `urdfcheck lint` run there plans them (once per run)."""
        if ws not in self._robots:
            sub = Planner(self.request, self.here)
            sub._configs, sub._settings = self._configs, self._settings
            self._robots[ws] = list(sub.path_targets(ws))
        return self._robots[ws]

    def variants(self, entry: Path, settings: Settings, root: str | None = None, found: bool = False
                 ) -> list[Target]:
        """Each combination of the boolean xacro:args the request does not fix (bounded; named). `found`: the
        model was discovered (no one named it), so a combination of several options rests on a guess."""
        packages = _packages(root, str(entry), settings) if root is not None else None
        if not entry.name.endswith(".xacro"):
            return [self.target(entry, {}, "", None, settings, packages)]
        from urdfcheck.load.variants import auto_variants  # not the config module: a run without one never imports it

        out = []
        for name, vargs in auto_variants(str(entry), dict(self.request.args),
                                         dict(settings.packages) if packages is None else packages):
            out.append(self.target(entry, vargs, name, None, settings, packages))
            # several options flipped together on a discovered model: a combination no launch file or config
            # was seen to use, so what only it shows rests on a guess (issue 37; run._combinations); each option
            # alone is a variant of its own
            out[-1].combination = found and name.count(",") >= 1
        return out

    def target(self, path: Path, args: dict, variant: str, consumers, settings: Settings,
               packages: dict | None = None) -> Target:
        return Target(path, {**args, **dict(self.request.args)}, variant, consumers,
                      dict(settings.packages) if packages is None else packages, settings)


def reaching_targets(fragment, robots: list[Target], infos: list, named: bool = False) -> list[Target]:
    """Robots that include `fragment` only under a xacro argument other than the one they are linted with
    (`<xacro:if value="$(arg use_arm)">`, default false; a literal comparison): one more target per robot file,
    with the values that make the include happen, named by them (load.reach). `named`: the runner named the
    fragment (evidence `reaching`); otherwise the variant is one option of a discovered model, like the automatic
    boolean variants. A condition urdfcheck does not decide is said as an info line in `infos`."""
    from urdfcheck.load.reach import _same, reaching

    fragment = Path(fragment)
    out, done = [], set()
    for t in robots:
        entry = realpath(t.path)
        if entry in done or not str(t.path).endswith(".xacro"):
            continue
        done.add(entry)
        mine = [r for r in robots if realpath(r.path) == entry]
        r = reaching(str(t.path), str(fragment), lambda n, pk=t.packages: pk.get(n))
        if r is None:
            continue
        if r.undecided:
            infos.append(f"{shown(str(fragment))}: {shown(str(t.path))} includes it only when {r.undecided}, a "
                         "condition urdfcheck does not decide: not linted through it (pass the arguments that "
                         "include it with --arg NAME:=VALUE)")
            continue
        if not r.args or any(all(k in m.args and _same(str(m.args[k]), v) for k, v in r.args.items()) for m in mine):
            continue  # the defaults, a launch file's or the runner's arguments already include it
        given = ",".join(f"{k}={v}" for k, v in r.args.items())
        v = Target(Path(t.path), {**t.args, **r.args}, f"{given} (includes {fragment.name})", None,
                   dict(t.packages), t.settings)
        if named:
            v.evidence = (_step("variant", f"{shown(str(t.path))} with {given}", "reaching",
                                f"lint {shown(str(t.path))} with --arg for a deployment that uses it"),)
        else:
            # one option alone of a robot that is one by evidence (as the automatic boolean variants)
            v.evidence = tuple(s for s in t.evidence if s.what == "model") or \
                (_step("model", str(t.path), "launched" if t.deployment is not None else "complete"),)
        out.append(v)
    return out


def plan(request: LintRequest, here: str | None = None) -> TargetList:
    """`here`: the folder a request without paths lints, as if run there (default: the working directory)."""
    return Planner(request, here).plan()


def _packages(root: str, model: str, settings: Settings) -> dict:
    """Every package of the named tree (the copy nearest the model on a duplicate name), then the explicit
    ones: a model resolves its sibling repositories' packages whatever the working directory."""
    from urdfcheck.load.packages import workspace_map

    return {**workspace_map(root, near=model), **dict(settings.packages)}


def _unskipped(ws: str, folder: str) -> str:
    """`ws`, or the deepest folder between it and `folder` (the library's) that a walk from `ws` skips (a
    COLCON_IGNORE, a hidden folder: core.walk): the library was named, so the robots beside it are planned as if
    that folder had been named (this repository's examples/ holds COLCON_IGNORE; from its root, a macro file of
    examples/agv had "no robot that includes it")."""
    from urdfcheck.core import walk

    ws, d = os.path.abspath(ws), os.path.abspath(folder)
    if not _below(d, ws):
        return ws
    while d != ws:
        try:
            entries = list(os.scandir(d))
        except OSError:
            entries = []
        if os.path.basename(d).startswith(".") or walk.skipped(d, entries):
            return d
        d = os.path.dirname(d)
    return ws


def _step(what: str, subject: str, how: str, confirm: str = ""):
    from urdfcheck.core.evidence import Step

    return Step(what, shown(subject) if what == "model" else subject, how, confirm)


def _mark(targets: list[Target], how: str, force: bool = False) -> list[Target]:
    """Record how these targets' model was chosen (core.evidence), unless a step already says so."""
    for t in targets:
        if force or not any(s.what == "model" for s in t.evidence):
            t.evidence = (_step("model", str(t.path), how),) + tuple(s for s in t.evidence if s.what != "model")
    return targets


def _robot_file(path) -> bool:
    """A regular file whose root element is <robot>: a library only then (an empty file, a FIFO or a file of
    another root is linted, and the loader says what is wrong with it)."""
    from urdfcheck.load.discover import _read_head, _root_tag

    if not os.path.isfile(path):
        return False
    tag = _root_tag(_read_head(str(path)))
    return tag is not None and tag.split(":")[-1] == "robot"


def _cut_short(folder: str, limit: str):
    from urdfcheck.core.findings import Finding, Location, Severity

    return Finding("X019", Severity.ERROR, f"the file walk stopped after {limit}: what lies beyond was not looked "
                   "at (lint the packages one by one, or remove generated files from the checkout)",
                   Location(folder), name="walk-truncated")


def _covered(t: Target, cfg) -> bool:
    """A deployment the config already lints as planned: its model declared with that launch file among the
    model's `launch:`, and the launch file's xacro arguments one of the model's variants (or none at all)."""
    d = t.deployment
    if d is None:
        return False
    m = cfg.model_for(t.path)
    if m is None or realpath(d.launch.file) not in {realpath(x) for x in m.launch}:
        return False
    return not d.args or any(dict(d.args) == a for _, a in m.variant_args())


def _undeclared_consumers(m) -> bool:
    """Does the declared model's package hold parameter or launch files (as zero config finds them) that the
    config does not name for it?"""
    from urdfcheck.load.discover import discover
    from urdfcheck.load.packages import enclosing_package

    pkg = enclosing_package(Path(os.path.abspath(m.path)).parent)
    if pkg is None:
        return False
    named = {realpath(p) for p in (*m.controllers, *m.launch, *m.localization, *(d.file for d in m.drivers))}
    found = discover(str(pkg))
    return any(realpath(p) not in named for p in (*found.params, *found.launch))


def _declares_localization(m) -> bool:
    """Does the declared model name localization files? Each counts as a node run with the model, publishing its
    transforms, which zero config grants only to a node a launch file starts: from an untrusted config they add a
    reading, so the model is linted as zero config finds it too (a declared EKF file that publishes a frame does
    not hide the driver that uses it unpublished; issue 36)."""
    return bool(m.localization)


def _vouched(cfg) -> bool:
    """The runner named this config with --config FILE --trust-config (request.config.Config.vouched)."""
    return bool(getattr(cfg, "vouched", True))


def _srdf_text(path: str) -> bool:
    """MoveIt's semantic description by its text (SRDF elements, no <link>), whatever the file's name."""
    from urdfcheck.load.discover import _is_srdf, _read_head

    return os.path.isfile(path) and _is_srdf(_read_head(str(path)))


def _is_launch(path: str) -> bool:
    from urdfcheck.load.discover import LAUNCH_SUFFIXES

    return path.lower().endswith(LAUNCH_SUFFIXES)


def _models_at(cfg, path: str) -> list:
    """The config's models at or below `path`."""
    real = realpath(path)
    return [m for m in cfg.models if realpath(m.path) == real
            or realpath(m.path).startswith(real.rstrip(os.sep) + os.sep)]


def _consumers(mc, cfg, packages: dict):
    from urdfcheck.consumers.consumers import consumers_for_model

    return consumers_for_model(mc, cfg, packages=packages)


def _unique(targets: list[Target]) -> list[Target]:
    """Several library files of one package lead to the same entry models: each (file, args) once, and once
    per launch file that deploys it (each deployment brings its own consumers)."""
    seen, out = set(), []
    for t in targets:
        launch = getattr(getattr(t.deployment, "launch", None), "file", None)
        key = (realpath(t.path), tuple(sorted(t.args.items())), launch,  # realpath: no stat of a link's target
               getattr(t, "twin", False))
        if key not in seen:
            seen.add(key)
            out.append(t)
    return out


def _below(path: str, base: str) -> bool:
    p, b = os.path.abspath(path), os.path.abspath(base)
    return p == b or p.startswith(b.rstrip(os.sep) + os.sep)


def _under_any(path: str, folders) -> bool:
    return any(_below(path, f) for f in folders)


class _Walk(Record):
    # configs: config files strictly below the walked folder; packages: folders holding a package.xml
    # (outermost only); loose: a .urdf/.xacro file outside every package
    _fields = ('configs', 'packages', 'loose')
    truncated = False  # stopped at MAX_DIRS

    def __init__(self, configs: list[str], packages: list[str], loose: bool):
        self.configs, self.packages, self.loose = configs, packages, loose


def _walk(folder: str) -> _Walk:
    """One pass over a folder tree: nested config files and packages (what core.walk skips skipped)."""
    from urdfcheck.core import walk
    from urdfcheck.request.config import PYPROJECT, _pyproject_has_table

    top = os.path.abspath(folder)
    configs, packages, loose, seen, truncated = [], [], False, 0, False
    for here, entries in walk.folders(top, max_dirs=MAX_DIRS + 1):
        seen += 1
        if seen > MAX_DIRS:  # a tree larger than the walk looks at: said (X019), never a silent partial plan
            truncated = True
            break
        files = walk.files(entries)
        if here != top:
            name = next((n for n in CONFIG_NAMES if n in files), None)
            if name is None and PYPROJECT in files and _pyproject_has_table(Path(here, PYPROJECT)):
                name = PYPROJECT
            if name is not None:
                configs.append(os.path.join(here, name))
        in_pkg = any(_below(here, p) for p in packages)
        if "package.xml" in files and not in_pkg:
            packages.append(here)
            in_pkg = True
        if not in_pkg and not loose:
            loose = any(f.endswith((".urdf", ".xacro")) for f in files)
    w = _Walk(configs, packages, loose)
    w.truncated = truncated
    return w
