"""Planning: a `LintRequest` becomes the list of `Target`s to lint (model + xacro args + its consumers).

Which config applies where: the nearest config file at or above a path (like ruff), and inside a folder
each sub-folder holding its own config (a package's urdfcheck.yaml) is planned with that config, exactly as
`urdfcheck lint` run from inside it would: `urdfcheck lint src` from a workspace gives the union of linting
each package from inside it. A folder without config is planned package by package (each folder with a
package.xml discovered on its own), for the same reason.

A config with `models:` names the entry models and their consumers; each model's consumers are read once,
on first use (`Later`), and shared by its variants. Without config, each package's launch files that start
robot_state_publisher give deployments (`pipeline.deployments`: the model with the launch file's xacro
arguments and the consumers beside it); the package's other entry models are discovered and linted with their
boolean variants.
"""
from __future__ import annotations

import os
from pathlib import Path

from urdfcheck.core.records import Record
from urdfcheck.pipeline.request import LintRequest, Settings, UsageError

CONFIG_NAMES = ("urdfcheck.yaml", ".urdfcheck.yaml")  # config.CONFIG_NAMES (not imported: start-up)
SKIP_DIRS = {"build", "install", "log", "devel", "node_modules", "__pycache__", "venv"}  # discover.SKIP_DIRS
MAX_DIRS = 20_000  # folders a workspace walk looks at
LAUNCH_SUFFIXES = (".launch", ".launch.xml", ".launch.py", ".launch.yaml", ".launch.yml", "_launch.py")
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

    contracts: the consumers (contracts.consumers.Consumers) of this model, a `Later`, or None (the contract
    checks then look next to the model). settings: the request as it applies here (its config file);
    None for targets made by hand (tests), which `run.lint_targets` lints with its own arguments.
    deployment: the launch file that starts this model (label and defining Location), when planned from one."""

    _fields = ('path', 'args', 'variant', 'contracts', 'packages', 'settings', 'deployment')

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


class Planner:
    """Plans one request; reads each config file once."""

    def __init__(self, request: LintRequest, here: str | None = None):
        self.request = request
        self.here = here or "."  # the folder a request without paths names (`urdfcheck lint` run there)
        self._configs: dict[str, object] = {}
        self._settings: dict[str | None, Settings] = {}

    # --- configs ----------------------------------------------------------------------------------
    def config(self, path: str | None):
        if path is None:
            return None
        if path not in self._configs:
            from urdfcheck.pipeline import config as cfgmod

            try:
                self._configs[path] = cfgmod.load_config(path)
            except cfgmod.ConfigError as e:
                where = e.location or cfgmod.Location(path)
                shown = self.request.shown(where.file) + "".join(
                    f":{n}" for n in (where.line, where.column) if n)
                raise UsageError(f"invalid config {shown}: {e}") from None
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
        from urdfcheck.pipeline.config import find_config

        return self.config(find_config(path))

    # --- planning ---------------------------------------------------------------------------------
    def plan(self) -> list[Target]:
        req = self.request
        paths = list(req.paths)
        if not paths:
            cfg = self.nearest(os.path.abspath(self.here))
            if cfg is not None and cfg.models:
                return _unique(self.declared(cfg, None))
            paths = [self.here]  # the package here (a workspace config above it applies to it, not all of it)
        out: list[Target] = []
        for raw in paths:
            out.extend(self.path_targets(raw))
        return _unique(out)

    def path_targets(self, raw: str) -> list[Target]:
        cfg = self.nearest(raw)
        settings = self.settings(cfg)
        from urdfcheck.load.packages import leaves_cwd

        if not settings.trusted and leaves_cwd(Path(raw), settings.packages.values()):
            return [self.target(Path(raw), {}, "", None, settings)]  # refused by the loader (X014)
        if not os.path.isdir(raw):
            if cfg is not None and cfg.model_for(raw) is not None:
                return self.declared(cfg, [raw])
            if _is_launch(raw):
                return self.launch_targets(raw, settings)
            if raw.lower().endswith(NOT_MODELS):
                raise UsageError(f"{raw} is not a URDF or xacro model (name the model, its package, or a "
                                 "launch file that starts robot_state_publisher)")
            return self.file_targets(Path(raw), settings)
        # a folder: nested configs (when not given one explicitly) take their sub-trees
        walk = _walk(raw)
        nested = [] if (self.request.config is not None or not self.request.use_config) else \
            [c for c in walk.configs if cfg is None or os.path.dirname(c) != cfg.root]
        nested_roots = [os.path.dirname(c) for c in nested]
        out = self.scope(cfg, raw, walk, exclude=nested_roots)
        for c in nested:
            sub = self.config(c)
            deeper = [r for r in nested_roots if _below(r, sub.root) and r != sub.root]
            if sub.models:
                out.extend(t for t in self.declared(sub, None) if not _under_any(str(t.path), deeper))
            else:
                out.extend(self.scope(sub, sub.root, _walk(sub.root), exclude=deeper))
        return out

    def scope(self, cfg, folder: str, walk, exclude: list[str]) -> list[Target]:
        """The models of `folder` under one config (or none): declared ones, else discovered."""
        settings = self.settings(cfg)
        if cfg is not None and _models_at(cfg, folder):
            return [t for t in self.declared(cfg, [folder]) if not _under_any(str(t.path), exclude)]
        return [t for t in self.discovered(folder, walk, settings, exclude) if not _under_any(str(t.path), exclude)]

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
        for raw in rest:
            out.extend(self.file_targets(Path(raw), settings) if not os.path.isdir(raw)
                       else self.discovered(raw, _walk(raw), settings))
        return out

    def discovered(self, folder: str, walk, settings: Settings, exclude=()) -> list[Target]:
        """Zero-config: the entry models of each package below `folder`, each package discovered on its own
        (as from inside it); `folder` itself when it is inside a package or holds none."""
        from urdfcheck.contracts.discover import discover
        from urdfcheck.load.packages import enclosing_package

        inside = enclosing_package(Path(os.path.abspath(folder))) is not None
        roots = [folder] if inside or not walk.packages else \
            [p for p in walk.packages if not _under_any(p, exclude)]  # a package with its own config: its own
        out: list[Target] = []
        for root in roots:
            deployed = self.deployments(root, settings)
            out.extend(deployed)
            covered = {os.path.realpath(t.path) for t in deployed}
            for entry in discover(root, trusted=settings.trusted).models:
                if os.path.realpath(entry) not in covered:  # a deployment gives the args it needs
                    out.extend(self.variants(Path(entry), settings))
        if not inside and walk.packages and walk.loose:  # model files outside every package
            pk = walk.packages
            for entry in discover(folder, trusted=settings.trusted).models:
                if not _under_any(entry, pk):
                    out.extend(self.variants(Path(entry), settings))
        return out

    def deployments(self, root: str, settings: Settings, files=None) -> list[Target]:
        """The models the launch files of one package start robot_state_publisher with
        (pipeline/deployments.py): the launch file's xacro arguments, its controllers and localization as
        the consumers. Per package, so a workspace run is the union of its packages' runs."""
        try:
            from urdfcheck.pipeline.deployments import find_deployments
        except ImportError:  # pragma: no cover - the module is part of the package
            return []
        from urdfcheck.load.packages import Resolver

        resolver = Resolver(dict(settings.packages), near=Path(os.path.abspath(root)))
        out = []
        for d in find_deployments(root, resolver, packages=dict(settings.packages), files=files):
            if d.model is None:
                continue
            t = self.target(Path(d.model), dict(d.args), d.label, Later(d.consumers), settings)
            t.deployment = d
            out.append(t)
        return out

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
        package) is no robot by itself: lint the package's entry models instead, which expand it (what a
        per-file pre-commit hook needs)."""
        if path.name.endswith(".xacro"):
            from urdfcheck.contracts.discover import discover
            from urdfcheck.load.packages import enclosing_package

            pkg = enclosing_package(Path(os.path.abspath(path)).parent)
            if pkg is not None:
                found = discover(pkg)
                if os.path.realpath(path) in {os.path.realpath(x) for x in found.libraries} and found.models:
                    return [self.target(Path(m), {}, "", None, settings) for m in found.models]
        return [self.target(path, {}, "", None, settings)]

    def variants(self, entry: Path, settings: Settings) -> list[Target]:
        """Each combination of the boolean xacro:args the request does not fix (bounded; named)."""
        if not entry.name.endswith(".xacro"):
            return [self.target(entry, {}, "", None, settings)]
        from urdfcheck.pipeline.config import auto_variants

        return [self.target(entry, vargs, name, None, settings)
                for name, vargs in auto_variants(str(entry), dict(self.request.args))]

    def target(self, path: Path, args: dict, variant: str, consumers, settings: Settings) -> Target:
        return Target(path, {**args, **dict(self.request.args)}, variant, consumers, dict(settings.packages),
                      settings)


def plan(request: LintRequest, here: str | None = None) -> list[Target]:
    """`here`: the folder a request without paths lints, as if run there (default: the working directory)."""
    return Planner(request, here).plan()


def _is_launch(path: str) -> bool:
    return path.lower().endswith(LAUNCH_SUFFIXES)


def _models_at(cfg, path: str) -> list:
    """The config's models at or below `path`."""
    real = os.path.realpath(path)
    return [m for m in cfg.models if os.path.realpath(m.path) == real
            or os.path.realpath(m.path).startswith(real.rstrip(os.sep) + os.sep)]


def _consumers(mc, cfg, packages: dict):
    from urdfcheck.contracts.consumers import consumers_for_model

    return consumers_for_model(mc, cfg, packages=packages)


def _unique(targets: list[Target]) -> list[Target]:
    """Several library files of one package lead to the same entry models: each (file, args) once, and once
    per launch file that deploys it (each deployment brings its own consumers)."""
    seen, out = set(), []
    for t in targets:
        launch = getattr(getattr(t.deployment, "launch", None), "file", None)
        key = (os.path.realpath(t.path), tuple(sorted(t.args.items())), launch)  # realpath: no stat of a link's target
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

    def __init__(self, configs: list[str], packages: list[str], loose: bool):
        self.configs, self.packages, self.loose = configs, packages, loose


def _walk(folder: str) -> _Walk:
    """One pass over a folder tree: nested config files and packages (hidden and build folders skipped)."""
    from urdfcheck.pipeline.config import PYPROJECT, _pyproject_has_table

    top = os.path.abspath(folder)
    configs, packages, loose, seen = [], [], False, 0
    for here, dirs, files in os.walk(top):
        seen += 1
        if seen > MAX_DIRS:
            break
        dirs[:] = sorted(d for d in dirs if not d.startswith(".") and d not in SKIP_DIRS)
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
    return _Walk(configs, packages, loose)
