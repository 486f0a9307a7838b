"""The lint request: the one place where command-line flags, API arguments and config files are merged.

    make_request(paths, **options) -> LintRequest     # flags / API arguments, checked (UsageError)
    request.settings(config) -> Settings                # the request applied to one config file (or none)

Every front end (CLI, `urdfcheck.lint`, the pytest plugin, the pre-commit hooks) builds a `LintRequest`
with `make_request` and hands it to `run.run`. A workspace run has one `Settings` per config file
found (each package with its own urdfcheck.yaml), all made by `LintRequest.settings`: what the caller set
explicitly wins over the config, lists of ignored codes and allowed variables add up.
"""
from __future__ import annotations

import os
from collections.abc import Mapping
from types import MappingProxyType

from urdfcheck.core.findings import Severity
from urdfcheck.core.records import TYPE_CHECKING, Record
from urdfcheck.load.xacro import XACRO_TIMEOUT  # one xacro expansion (a light module: xacro is not imported)

if TYPE_CHECKING:
    from typing import Any


class UsageError(ValueError):
    """An unusable request (missing path, unknown rule code, invalid config): exit 2 on the command line."""


def _ro(d) -> Mapping:
    return MappingProxyType(dict(d or {}))


_EMPTY: Mapping = MappingProxyType({})


class LintRequest(Record):
    """What to lint and how, as the caller asked. `None` means "not given": the config decides.
    (A plain record, not a dataclass: `dataclasses` costs start-up time; see core/records.py.)"""

    _defaults: dict[str, Any] = {
        "paths": (),             # files or folders; () = what the config declares, else "."
        "args": _EMPTY,          # xacro arguments
        "packages": _EMPTY,      # ROS package name -> folder
        "select": None,          # rule codes or prefixes
        "ignore": (),
        "severity": _EMPTY,      # code or prefix -> Severity
        "rules": _EMPTY,         # rule options {code: {option: value}}, over the config's
        "fail_on": None,         # Severity
        "trusted": None,
        "allow_env": (),
        "timeout": XACRO_TIMEOUT,  # one xacro expansion
        "max_elements": None,
        "config": None,          # an explicit config file (else found upward from each path)
        "use_config": True,      # False: ignore config files (--no-config)
        "trust_config": False,   # the explicit `config` may lower the guard (--trust-config; request.trust)
        # the folder the explicit config's relative paths start at (None: its own folder). A config kept outside
        # the checkout (the base revision's, read through git into a private temp file: --config-from) names the
        # checkout folder it came from here
        "config_root": None,
        "max_files": None,       # files one package walk looks at (None: load.discover.MAX_FILES)
        "root": "",              # reports show paths relative to this folder (default: working directory)
        "baseline": None,        # only findings not in this baseline file
        "budget": None,          # seconds for the whole run (issue 11: run-wide limits); None = load.budget's default
        "target": None,          # ROS distribution the description is meant for (issue 14)
        "bags": (),              # recordings checked against every model linted (urdfcheck.bag)
        "joint_states": None,    # their JointState topic (None: /joint_states, else the only one)
        "profiles": None,        # consumer profiles (issue 25): mujoco, gazebo, isaac, kdl, pinocchio, pybullet, moveit
    }
    _fields = tuple(_defaults)

    def __init__(self, **kw):
        unknown = set(kw) - set(self._defaults)
        if unknown:
            raise TypeError(f"unknown request field {sorted(unknown)[0]!r}")
        for name, default in self._defaults.items():
            setattr(self, name, kw.get(name, default))

    def settings(self, cfg) -> Settings:
        """This request applied to one config (None: no config): the only merge of flags and config."""
        get = (lambda k, d=None: getattr(cfg, k, d)) if cfg is not None else (lambda k, d=None: d)
        from urdfcheck.rules.engine import Selection

        severity = {k: Severity.parse(v) if isinstance(v, str) else v for k, v in (get("severity") or {}).items()}
        severity.update(self.severity)
        options = {code: dict(opts) for code, opts in (get("rules") or {}).items()}
        for code, opts in self.rules.items():
            options[code] = {**options.get(code, {}), **dict(opts)}
        selection = Selection(tuple(self.select or get("select") or ("ALL",)),
                              tuple(get("ignore") or ()) + tuple(self.ignore), severity, options)
        trusted = bool(self.trusted) if self.trusted is not None else bool(get("trusted", False))
        cfg_fail = get("fail_on")
        return Settings(
            config=cfg, selection=selection,
            fail_on=self.fail_on or (Severity.parse(cfg_fail) if isinstance(cfg_fail, str) else cfg_fail)
            or Severity.WARNING,
            packages=_ro({**dict(get("packages") or {}), **dict(self.packages)}),
            trusted=trusted, allow_env=tuple(dict.fromkeys(tuple(self.allow_env) + tuple(get("allow_env") or ()))),
            timeout=self.timeout, max_elements=self.max_elements or get("max_elements"),
            target=self.target or get("target"),
            profiles=tuple(self.profiles if self.profiles is not None else get("profiles") or ()),
        )


class Settings(Record):
    """The request as it applies to the models of one config file (made by `LintRequest.settings`)."""

    # config: request.config.Config or None; selection: rules.engine.Selection
    _fields = ('config', 'selection', 'fail_on', 'packages', 'trusted', 'allow_env', 'timeout', 'max_elements',
               'target', 'profiles')

    def __init__(self, config, selection, fail_on: Severity = Severity.WARNING, packages: Mapping = _EMPTY,
                 trusted: bool = False, allow_env: tuple = (), timeout: float = XACRO_TIMEOUT,
                 max_elements: int | None = None, target: str | None = None, profiles: tuple = ()):
        self.config, self.selection, self.fail_on, self.packages = config, selection, fail_on, packages
        self.trusted, self.allow_env, self.timeout, self.max_elements = trusted, allow_env, timeout, max_elements
        self.target = target
        self.profiles = profiles

    def load_options(self) -> dict:
        """Keyword arguments of `load.loader.begin`."""
        return dict(trusted=self.trusted, allow_env=self.allow_env, timeout=self.timeout,
                    max_elements=self.max_elements)


def make_request(paths=(), **options) -> LintRequest:
    """A checked `LintRequest` from API keyword arguments or parsed flags (the same names as the
    `LintRequest` fields; `no_config=True` is `use_config=False`). Raises UsageError."""
    _FIELDS = set(LintRequest._fields)
    if "no_config" in options:
        options["use_config"] = not options.pop("no_config")
    unknown = sorted(set(options) - _FIELDS - {"paths"})
    if unknown:
        from urdfcheck.core.findings import closest

        hint = closest(unknown[0], sorted(_FIELDS), cutoff=0.6)
        raise UsageError(f"unknown option {unknown[0]!r}" + (f" (did you mean {hint!r}?)" if hint else ""))
    if isinstance(paths, (str, bytes)) or hasattr(paths, "__fspath__"):
        paths = [paths]
    kw: dict[str, Any] = {"paths": tuple(os.fsdecode(p) for p in (paths or ()))}
    for key in ("args", "packages"):
        if options.get(key) is not None:
            kw[key] = _ro({str(k): str(v) for k, v in dict(options[key]).items()})
    for key in ("select", "ignore"):
        value = options.get(key)
        if value is not None:
            codes = tuple(c.strip().upper() for c in ([value] if isinstance(value, str) else value) if c.strip())
            _check_codes(codes)
            kw[key] = codes if key == "ignore" or codes else None
    if options.get("severity") is not None:
        _check_codes(list(options["severity"]))
        kw["severity"] = _ro({str(k).upper(): _severity(v) for k, v in dict(options["severity"]).items()})
    if options.get("rules") is not None:
        kw["rules"] = _ro({str(k): _ro(v) for k, v in _check_rule_options(options["rules"]).items()})
    if options.get("fail_on") is not None:
        kw["fail_on"] = _severity(options["fail_on"])
    if options.get("allow_env") is not None:
        kw["allow_env"] = tuple(options["allow_env"])
    if options.get("bags"):
        kw["bags"] = tuple(os.fsdecode(b) for b in ([options["bags"]] if isinstance(options["bags"], str)
                                                     else options["bags"]))
    for key in ("trusted", "timeout", "max_elements", "config", "use_config", "root", "baseline", "budget",
                "target", "joint_states", "trust_config", "max_files", "config_root"):
        if options.get(key) is not None:
            kw[key] = options[key]
    if options.get("profiles") is not None:
        kw["profiles"] = _profiles(options["profiles"])
    if kw.get("target") is not None:
        from urdfcheck.model.grammar import TARGETS

        if kw["target"] not in TARGETS:
            raise UsageError(f"unknown target {kw['target']!r} (use one of {', '.join(TARGETS)})")
    if kw.get("root"):
        if not os.path.isdir(kw["root"]):
            raise UsageError(f"--root: no such folder: {kw['root']}")
        kw["root"] = os.path.abspath(kw["root"])
    missing = [p for p in kw["paths"] + kw.get("bags", ()) if not os.path.exists(p)]
    if missing:
        raise UsageError(f"no such file or folder: {', '.join(missing)}")
    if kw.get("config") is not None and not os.path.isfile(kw["config"]):
        raise UsageError(f"no such config file: {kw['config']}")
    if kw.get("config_root") is not None:
        if kw.get("config") is None:
            raise UsageError("config_root needs an explicit config file")
        if not os.path.isdir(kw["config_root"]):
            raise UsageError(f"no such folder: {kw['config_root']}")
        kw["config_root"] = os.path.abspath(kw["config_root"])
    if kw.get("trust_config") and kw.get("config") is None:
        raise UsageError("--trust-config needs --config FILE (a config found in the checkout is never trusted)")
    return LintRequest(**kw)


def _profiles(value) -> tuple[str, ...]:
    from urdfcheck.rules.checks.profiles.common import PROFILES

    names = [p.strip().lower() for p in ([value] if isinstance(value, str) else value) for p in str(p).split(",")]
    names = [p for p in names if p]
    for p in names:
        if p not in PROFILES:
            raise UsageError(f"unknown profile {p!r} (use one of {', '.join(PROFILES)})")
    return tuple(dict.fromkeys(names))


def _severity(v) -> Severity:
    if isinstance(v, Severity):
        return v
    try:
        return Severity.parse(str(v))
    except ValueError as e:
        raise UsageError(str(e)) from None


def _check_codes(codes) -> None:
    if not codes:  # the rules are imported after the first expansions are sent
        return
    from urdfcheck.rules.catalogue import unknown_codes

    problems = unknown_codes(codes)
    if problems:
        raise UsageError("; ".join(problems))


def _check_rule_options(rules) -> dict:
    """Rule options given in Python or on the command line: known rules and options, declared types."""
    from urdfcheck.core.findings import closest
    from urdfcheck.rules.catalogue import catalogue, option_ok

    cat = catalogue()
    out = {}
    for code, opts in dict(rules).items():
        info = cat.get(str(code))
        if info is None:
            raise UsageError(f"rules: {code!r} is not a rule code")
        for name, value in dict(opts).items():
            spec = info.option_specs.get(name)
            if spec is None:
                hint = closest(str(name), list(info.option_specs), cutoff=0.6)
                raise UsageError(f"rules: {code} has no option {name!r}"
                                 + (f" (did you mean {hint!r}?)" if hint else
                                    f" (options: {', '.join(info.option_specs) or 'none'})"))
            if not option_ok(spec, value):
                raise UsageError(f"rules: {code}.{name} must be {spec.type}"
                                 + (f" >= {spec.minimum}" if spec.minimum is not None else "") + f", got {value!r}")
        out[str(code)] = dict(opts)
    return out
