"""`lint`: load each entry model (and each variant), build it, run the checks, collect findings."""
from __future__ import annotations

import os
from pathlib import Path

from urdfcheck.rules import engine
from urdfcheck.load import loader as load
from urdfcheck.core.findings import Finding, Location, Severity
from urdfcheck.core.records import Record


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
    """One model to lint: an entry file with one xacro argument set."""

    # contracts: consumers declared or discovered for this model (may be given as a `Later`)
    _fields = ('path', 'args', 'variant', 'contracts', 'packages')

    def __init__(self, path: Path,
                 args: dict | None = None,
                 variant: str = "",
                 contracts: object = None,
                 packages: dict | None = None):
        self.path = path
        self.args = {} if args is None else args
        self.variant = variant
        self.contracts = contracts
        self.packages = {} if packages is None else packages

    @property
    def contracts(self):
        c = self._contracts
        return c.get() if isinstance(c, Later) else c

    @contracts.setter
    def contracts(self, value) -> None:
        self._contracts = value


class Result(Record):
    # models: (entry, variant) -> Model (None when it failed to load)
    _fields = ('findings', 'targets', 'models')

    def __init__(self, findings: list[Finding], targets: list[Target], models: dict | None = None):
        self.findings = findings
        self.targets = targets
        self.models = {} if models is None else models

    def worst(self) -> Severity | None:
        return max((f.severity for f in self.findings), default=None)

    def failed(self, fail_on: Severity) -> bool:
        return any(f.severity >= fail_on for f in self.findings)


def entry_models(folder: Path, trusted: bool = False) -> list[Path]:
    """Entry models of a package: URDF files, and xacro robots that no other file includes."""
    from urdfcheck.contracts.discover import discover

    return [Path(m) for m in discover(folder, trusted=trusted).models]


def lint_target(t: Target, selection: engine.Selection, *, trusted=False, allow_env=(), timeout=load.XACRO_TIMEOUT,
                config=None, max_elements=None) -> tuple[list[Finding], object]:
    pending = _begin(t, trusted=trusted, allow_env=allow_env, timeout=timeout, max_elements=max_elements)
    return _check(t, pending.result(), selection, config)


def _begin(t: Target, **kw) -> load.Pending:
    return load.begin(t.path, t.args, packages=t.packages, **kw)


def _check(t: Target, exp, selection: engine.Selection, config, yaml: _YamlUse | None = None
           ) -> tuple[list[Finding], object]:
    findings = list(exp.findings)
    model = load.build_model(exp)
    if model is not None:
        ctx = engine.Context(selection=selection, expanded=exp, config=config, contracts=t.contracts,
                             variant=t.variant)
        findings.extend(engine.run_checks(model, ctx))
        if yaml is not None:
            yaml.read(getattr(ctx, "contracts", None))
    shown = exp.entry
    return engine.finish(findings, selection, exp.suppressions, model=shown, variant=t.variant,
                         yaml_used=yaml.used if yaml is not None else None), model


class _YamlUse:
    """The YAML files the contract checks read, and which of their suppressions hid a finding."""

    def __init__(self):
        self.files: set[str] = set()
        self.used: set[tuple[str, int]] = set()

    def read(self, consumers) -> None:
        from urdfcheck.core.suppress import is_yaml

        for paths in (getattr(consumers, "files", None) or {}).values():
            self.files.update(os.path.abspath(p) for p in paths if is_yaml(str(p)))


def lint_targets(targets: list[Target], selection: engine.Selection | None = None, *, config=None,
                 retain: list | None = None, **kw) -> Result:
    """Lint every target. Xacro expansions run ahead in their workers (a few at a time), so this process
    imports the rules and builds the previous model while the next ones expand.

    `retain`: a list that keeps each parsed document alive. A process that exits right after (the console
    command) passes one: freeing a large libxml2 tree costs time, and the allocator's clean-up of its
    million small blocks on the next large request costs more (~0.1 s for 10,000 links)."""
    selection = selection or engine.Selection()
    all_findings: list[Finding] = []
    models = {}
    ahead = max(1, min(4, os.cpu_count() or 1))
    pending: dict[int, load.Pending] = {}
    yaml = _YamlUse()
    try:
        for i in range(min(ahead, len(targets))):
            pending[i] = _begin(targets[i], **kw)
        _warm_up(targets, config)
        for i, t in enumerate(targets):
            if i + ahead < len(targets):
                pending[i + ahead] = _begin(targets[i + ahead], **kw)
            exp = pending.pop(i).result()
            found, model = _check(t, exp, selection, config, yaml)
            if retain is not None:
                retain.append(exp)
            models[(str(t.path), t.variant)] = model
            all_findings.extend(found)
    finally:
        for p in pending.values():
            p.cancel()
    all_findings.extend(engine.unused_yaml(yaml.files, yaml.used, selection))
    return Result(_dedupe(all_findings), targets, models)


def _warm_up(targets: list[Target], config) -> None:
    """What the run needs after loading (model builders, rule modules, the catalogue, the contract readers
    when there can be consumers), done while the first expansions run in their workers, not after them."""
    from urdfcheck.model import build
    from urdfcheck.rules import catalogue as rulebook  # noqa: F401

    if not targets:
        return
    rulebook.load_checks()
    rulebook.catalogue()
    if config is not None or any(t.contracts is not None for t in targets) or _in_package(targets[0].path):
        from urdfcheck.contracts import rules_impl  # noqa: F401


def _in_package(path) -> bool:
    from urdfcheck.load.packages import enclosing_package

    # the folder the path names, not where a symlink points: nothing outside the tree is looked at
    return enclosing_package(Path(os.path.abspath(path)).parent) is not None


def _dedupe(findings: list[Finding]) -> list[Finding]:
    """The same problem seen in several variants is reported once, naming the variants."""
    seen: dict = {}
    for f in findings:
        key = (f.code, f.message, f.location, f.model)
        if key in seen:
            prev = seen[key]
            if f.variant and f.variant not in prev.variant.split(","):
                seen[key] = Finding(prev.code, prev.severity, prev.message, prev.location, prev.name,
                                    prev.related, prev.model, ",".join(filter(None, [prev.variant, f.variant])))
            continue
        seen[key] = f
    return sorted(seen.values(), key=Finding.sort_key)


def targets_for(paths: list[str], args: dict | None = None, packages: dict | None = None, *,
                trusted: bool = False) -> list[Target]:
    """Targets for plain paths (files or package folders), no config."""
    from urdfcheck.load.packages import leaves_cwd

    out = []
    for raw in paths:
        p = Path(raw)
        if not trusted and leaves_cwd(p, (packages or {}).values()):
            out.append(Target(p, dict(args or {}), packages=dict(packages or {})))  # refused by the loader (X014)
            continue
        if p.is_dir():
            out.extend(package_targets(p, args or {}, packages or {}, trusted=trusted))
        else:
            out.extend(file_targets(p, args or {}, packages or {}))
    seen, uniq = set(), []
    for t in out:  # several library files of one package lead to the same entry models
        key = (os.path.realpath(t.path), tuple(sorted(t.args.items())))  # realpath: no stat of a link's target
        if key not in seen:
            seen.add(key)
            uniq.append(t)
    return uniq


def file_targets(path: Path, args: dict, packages: dict) -> list[Target]:
    """An explicitly named file. A xacro library (macros only, or included by another file of its
    package) is no robot by itself: lint the package's entry models instead, which expand it
    (this is what a per-file pre-commit hook needs)."""
    if path.name.endswith(".xacro"):
        from urdfcheck.contracts.discover import discover
        from urdfcheck.load.packages import enclosing_package

        pkg = enclosing_package(Path(os.path.abspath(path)).parent)  # the package the file appears in
        if pkg is not None:
            found = discover(pkg)
            if os.path.realpath(path) in {os.path.realpath(x) for x in found.libraries} and found.models:
                return [Target(Path(m), dict(args), packages=dict(packages)) for m in found.models]
    return [Target(path, dict(args), packages=dict(packages))]


def package_targets(folder: Path, args: dict, packages: dict, trusted: bool = False) -> list[Target]:
    """Zero-config: each entry model of a package, and for xacro each combination of its boolean
    xacro:args that the command line does not fix (bounded; the variant names the values)."""
    from urdfcheck.pipeline.config import auto_variants

    out = []
    for entry in entry_models(folder, trusted):
        variants = auto_variants(str(entry), args) if entry.name.endswith(".xacro") else [("", {})]
        for name, vargs in variants:
            out.append(Target(entry, {**vargs, **args}, variant=name, packages=dict(packages)))
    return out


def missing_paths(paths: list[str]) -> list[str]:
    return [p for p in paths if not os.path.exists(p)]


def no_models_finding(folder: str) -> Finding:
    return Finding("X001", Severity.WARNING, "no URDF or xacro entry model found in this folder",
                   Location(folder), name="xml-syntax")
