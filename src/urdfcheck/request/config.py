"""The urdfcheck configuration file.

Found from a start folder upward (first hit wins, stopping at the filesystem root); in each folder
`urdfcheck.yaml`, then `.urdfcheck.yaml`, then `pyproject.toml` if it has a `[tool.urdfcheck]` table.
Validated against `schemas/config.schema.json`; paths are relative to the config file's folder and must stay in its
repository or the working directory unless the config is trusted (`--config FILE --trust-config`; request/trust.py).
A bad config raises `ConfigError(message, location)` naming the offending key (file:line for YAML).

```yaml
models:                                   # the entry models to lint, each with its consumers
  - path: urdf/agv.urdf.xacro
    args: {use_sim: "false"}              # base xacro arguments
    variants:                             # lint once per argument set (merged over args) ...
      camera: {use_camera: "true"}
      no_camera: {use_camera: "false"}
    # variants: auto                      # ... or every combination of the boolean xacro:args
    controllers: [config/agv_controllers.yaml]     # controller_manager / ros_control parameter files, in load order
    drivers:                              # custom drivers: key paths (dotted) into their parameter files
      - file: config/agv_driver_ros1.yaml
        node: ""                          # ROS 2 node name, or ROS 1 key prefix (optional)
        joints: [left_wheel_joint, right_wheel_joint]   # keys whose values are joint names
        left_wheels: [left_wheel_joint]
        right_wheels: [right_wheel_joint]
        wheel_separation: wheel_separation
        wheel_radius: wheel_radius
        frames: [imu_frame_id, laser_frame_id]          # keys whose values are frame ids
        odom_tf: publish_odom_tf                        # key of the "publish odom -> base TF" switch
        odom_frame: odom_frame_id                       # optional (default odom)
        base_frame: base_frame_id                       # optional (default frames.base)
    launch: [launch/agv.launch.xml]       # launch files (read, never run)
    launch_args: {}                       # launch arguments for $(arg)/$(var)
    localization: [config/ekf.yaml]       # robot_localization / AMCL parameter files
    frame_prefix: ""                      # robot_state_publisher frame_prefix for this model
frames: {map: map, odom: odom, base: base_link}        # REP-105 names used by the TF rules
tf_owners: {"map->odom": amcl}            # TF edges published by nodes urdfcheck cannot read
packages: {agv_description: .}            # where ROS packages live ($(find), package://)
select: [ALL]                             # rule codes or prefixes, ruff-style
ignore: [I005]
fail_on: warning                          # error | warning | info
severity: {F002: warning}                 # per code or prefix
rules: {C010: {tolerance: 0.002}, F002: {expected: [base_link, base_footprint]}}   # rule options
trusted: false                            # stock xacro evaluation (only for your own files)
allow_env: [HOME]                         # environment variables $(env)/$(optenv) may read
max_elements: 20000                       # xacro elements one expansion may evaluate (--max-elements)
# trusted, allow_env and max_elements above the default count only in a config named with
# --config FILE --trust-config; elsewhere they are an X018 finding and ignored (request/trust.py), as are the keys
# that lower the gate: ignore, a narrower select, lower severities, fail_on above warning, looser rule options,
# packages remapping the checkout's own package, frames renaming a REP-105 frame, target. There, tf_owners may add a
# publisher but never publish a frame, and launch_args/frame_prefix add the launch files' own defaults (a variant)
target: humble                            # ROS distribution whose urdfdom must read the model (--target)
profiles: [mujoco, gazebo]                # consumer profiles (--profile): what each consumer rejects or changes
cache: false                              # never store these runs in the lint cache (where it is: not here)
```

`[tool.urdfcheck]` in pyproject.toml takes the same keys (`[[tool.urdfcheck.models]]` for the list).
"""
from __future__ import annotations

import json
import os
import re
from collections.abc import Mapping
from pathlib import Path
from types import MappingProxyType

from urdfcheck.core.findings import Location, Severity
from urdfcheck.core.records import TYPE_CHECKING, FrozenRecord
from urdfcheck.core.walk import real as realpath  # remembered for the run

if TYPE_CHECKING:
    from typing import Any

CONFIG_NAMES = ("urdfcheck.yaml", ".urdfcheck.yaml")
PYPROJECT = "pyproject.toml"
MAX_AUTO_ARGS = 4  # `variants: auto` enumerates at most 2**4 combinations; beyond, pairwise (load.variants)
SCHEMA_PATH = Path(__file__).resolve().parent.parent / "schemas" / "config.schema.json"
DEFAULT_FRAMES = MappingProxyType({"map": "map", "odom": "odom", "base": "base_link"})


class ConfigError(Exception):
    def __init__(self, message: str, location: Location | None = None):
        super().__init__(message)
        self.message = message
        self.location = location

    def __str__(self) -> str:
        return self.message


def _ro(d: Mapping | None) -> Mapping:
    return MappingProxyType(dict(d or {}))


class ModelConfig(FrozenRecord):
    # path: absolute
    # variants: "auto", a mapping, or None
    # drivers: consumers.controllers.DriverSpec, one per declared custom driver
    _fields = ('path', 'loc', 'args', 'variants', 'controllers', 'drivers', 'launch', 'launch_args', 'localization',
               'frame_prefix', 'bags', 'defaults')

    def __init__(self, path: str,
                 loc: Location,
                 args: Mapping[str, str] | None = None,
                 variants: Mapping[str, Mapping[str, str]] | str | None = None,
                 controllers: tuple[str, ...] = (),
                 drivers: tuple = (),
                 launch: tuple[str, ...] = (),
                 launch_args: Mapping[str, str] | None = None,
                 localization: tuple[str, ...] = (),
                 frame_prefix: str = "",
                 bags: tuple[str, ...] = (),
                 defaults: Mapping[str, str] | None = None):
        d = self.__dict__  # FrozenRecord forbids setattr
        d["path"] = path
        d["loc"] = loc
        d["args"] = _ro({}) if args is None else args
        d["variants"] = variants
        d["controllers"] = controllers
        d["drivers"] = drivers
        d["launch"] = launch
        d["launch_args"] = _ro({}) if launch_args is None else launch_args
        d["localization"] = localization
        d["frame_prefix"] = frame_prefix
        d["bags"] = bags  # recordings checked against this model (urdfcheck.bag)
        # xacro args whose default an untrusted config replaces: the defaults are linted too (issue 36)
        d["defaults"] = _ro({}) if defaults is None else defaults

    def launch_defaults(self) -> ModelConfig:
        """This model with its launch files read as they are: no `launch_args`, no `frame_prefix` (the launch
        defaults twin of a config the runner did not trust; plan.plan)."""
        return ModelConfig(**{**{f: getattr(self, f) for f in self._fields}, "launch_args": None, "frame_prefix": ""})

    def variant_args(self) -> list[tuple[str, dict]]:
        """(variant name, xacro args) pairs: one ("", args) when there are no variants."""
        base = dict(self.args)
        if self.variants == "auto":
            out = [(n, {**base, **a}) for n, a in auto_variants(self.path, base)]
        elif isinstance(self.variants, Mapping) and self.variants:
            out = [(n, {**base, **dict(a)}) for n, a in self.variants.items()]
        else:
            out = [("", base)]
        if self.defaults:  # an untrusted config's args may add variants, never replace the defaults
            d = self.defaults
            if not any(all(a.get(k, v) == v for k, v in d.items()) for _, a in out):
                out.append(("xacro defaults", {k: v for k, v in base.items() if k not in d}))
        return out


class Config(FrozenRecord):
    # path: the config file
    # root: its folder; relative paths start here
    _fields = ('path', 'root', 'models', 'frames', 'tf_owners', 'tf_owner_locs', 'packages', 'select', 'ignore',
               'fail_on', 'severity', 'rules', 'trusted', 'allow_env', 'max_elements', 'locs', 'target',
               'profiles', 'notes', 'vouched')

    def __init__(self, path: str,
                 root: str,
                 models: tuple[ModelConfig, ...] = (),
                 frames: Mapping[str, str] | None = None,
                 tf_owners: Mapping[str, str] | None = None,
                 tf_owner_locs: Mapping[str, Location] | None = None,
                 packages: Mapping[str, str] | None = None,
                 select: tuple[str, ...] | None = None,
                 ignore: tuple[str, ...] = (),
                 fail_on: Severity | None = None,
                 severity: Mapping[str, Severity] | None = None,
                 rules: Mapping[str, Mapping[str, Any]] | None = None,
                 trusted: bool = False,
                 allow_env: tuple[str, ...] = (),
                 max_elements: int | None = None,
                 locs: Mapping[tuple, Location] | None = None,
                 target: str | None = None,
                 profiles: tuple[str, ...] = (),
                 notes: tuple = (),
                 vouched: bool = True):
        d = self.__dict__  # FrozenRecord forbids setattr
        d["path"] = path
        d["root"] = root
        d["models"] = models
        d["frames"] = DEFAULT_FRAMES if frames is None else frames
        d["tf_owners"] = _ro({}) if tf_owners is None else tf_owners
        d["tf_owner_locs"] = _ro({}) if tf_owner_locs is None else tf_owner_locs
        d["packages"] = _ro({}) if packages is None else packages
        d["select"] = select
        d["ignore"] = ignore
        d["fail_on"] = fail_on
        d["severity"] = _ro({}) if severity is None else severity
        d["rules"] = _ro({}) if rules is None else rules
        d = self.__dict__  # FrozenRecord forbids setattr
        d["trusted"] = trusted
        d["allow_env"] = allow_env
        d["max_elements"] = max_elements
        d["locs"] = _ro({}) if locs is None else locs
        d["profiles"] = profiles  # issue 25: rules/checks/profiles/common.PROFILES
        d["target"] = target  # issue 14: noetic | humble | jazzy | kilted | rolling (model.grammar.TARGETS)
        d["notes"] = notes  # findings about the config itself (request.trust: keys it may not set)
        # the runner named it with --config FILE --trust-config: it may lower the gate, and its `models:` are all
        # that is linted; otherwise they add to discovery (plan.plan; issue 36)
        d["vouched"] = vouched

    def loc(self, *path) -> Location:
        """Where a key was written (the file when unknown)."""
        p = tuple(path)
        while p:
            if p in self.locs:
                return self.locs[p]
            p = p[:-1]
        return Location(self.path)

    def model_for(self, path: str | os.PathLike) -> ModelConfig | None:
        real = realpath(str(path))
        for m in self.models:
            if realpath(m.path) == real:
                return m
        return None


# --- finding and reading -------------------------------------------------------------------------------
def _pyproject_has_table(path: Path) -> bool:
    try:
        from urdfcheck.core import door

        text = door.read_bytes(path, limit=1024 * 1024, runner=True).decode("utf-8", "replace")
    except OSError:
        return False
    return re.search(r"^\s*\[\[?\s*tool\.urdfcheck(\s*\]|\.)", text, re.M) is not None


def find_config(start: str | os.PathLike) -> str | None:
    """The config that applies to `start` (a folder or file): nearest first, stopping at the filesystem root."""
    p = Path(os.path.abspath(str(start)))
    if p.is_file():
        p = p.parent
    for d in (p, *p.parents):
        for name in CONFIG_NAMES:
            f = d / name
            if f.is_file():
                return str(f)
        f = d / PYPROJECT
        if f.is_file() and _pyproject_has_table(f):
            return str(f)
    return None


def _read_yaml(path: str):
    from urdfcheck.consumers.common import ConsumerError
    from urdfcheck.consumers.yamlsrc import load_yaml

    try:
        doc = load_yaml(path, max_bytes=1024 * 1024, runner=True)  # the runner's: see `_read_pyproject`
    except ConsumerError as e:
        raise ConfigError(e.message, e.location) from None
    data = {} if doc.data is None else doc.data
    return data, doc.key_loc, doc.loc


def _toml_locator(path: str, text: str):
    """Best-effort line numbers for [tool.urdfcheck] keys (tomllib gives none)."""
    lines = text.splitlines()
    header = next((i for i, line in enumerate(lines) if re.match(r"^\s*\[\s*tool\.urdfcheck\s*\]", line)), None)

    def find(*keypath) -> Location:
        if not keypath:
            return Location(path, (header + 1) if header is not None else None)
        key = str(keypath[0])
        pat_table = re.compile(r"^\s*\[\[?\s*tool\.urdfcheck\." + re.escape(key) + r"\b")
        pat_key = re.compile(r"^\s*[\"']?" + re.escape(key) + r"[\"']?\s*=")
        for i, line in enumerate(lines):
            if pat_table.match(line):
                return Location(path, i + 1)
        start = header if header is not None else 0
        for i in range(start, len(lines)):
            if i > start and lines[i].lstrip().startswith("[") and not pat_table.match(lines[i]):
                break
            if pat_key.match(lines[i]):
                return Location(path, i + 1)
        return Location(path, (header + 1) if header is not None else None)

    return find


def _read_pyproject(path: str):
    import tomllib

    try:
        from urdfcheck.core import door

        # `runner`: a config named by --config, or found above the checkout, is the runner's; one inside the
        # checkout that links out of it is refused all the same (core.door.confine)
        raw = door.read_bytes(path, limit=1024 * 1024, runner=True)
        text = raw.decode("utf-8")
        data = tomllib.loads(text)
    except OSError as e:
        raise ConfigError(f"cannot read config: {e.strerror}", Location(path)) from None
    except RecursionError:  # tomllib recurses per nesting level: a hostile file is an error, not a crash
        raise ConfigError("invalid TOML: nested too deeply", Location(path)) from None
    except (UnicodeDecodeError, tomllib.TOMLDecodeError) as e:
        m = re.search(r"line (\d+)", str(e))
        raise ConfigError(f"invalid TOML: {e}", Location(path, int(m.group(1)) if m else None)) from None
    table = data.get("tool", {}).get("urdfcheck")
    if table is None:
        raise ConfigError("pyproject.toml has no [tool.urdfcheck] table", Location(path))
    find = _toml_locator(path, text)
    return table, find, find


def _validate(data, path: str, key_loc, val_loc) -> None:
    from urdfcheck.request.schemagate import verdict

    # `rules:`'s schema is built from every catalogue entry's options: only when the config has that key (the
    # schema of a key the data lacks cannot change the verdict nor the error named)
    schema = config_schema(rules=not isinstance(data, dict) or "rules" in data)
    if verdict(data, schema) is True:  # the usual case: skip importing jsonschema (~60 ms)
        _check_codes(data, key_loc, val_loc)
        return
    try:
        import jsonschema
    except ImportError:  # pragma: no cover - jsonschema is a dependency
        return
    validator = jsonschema.Draft202012Validator(schema)
    errors = sorted(validator.iter_errors(data), key=lambda e: (list(e.absolute_path), e.message))
    if not errors:
        _check_codes(data, key_loc, val_loc)
        return
    err = jsonschema.exceptions.best_match(errors)
    where = tuple(err.absolute_path)
    key = ".".join(str(p) for p in where) or "(top level)"
    if err.validator == "additionalProperties":
        m = re.search(r"'([^']+)' (?:was|were) unexpected", err.message)
        bad = m.group(1) if m else None
        if bad is not None:
            loc = key_loc(*where, bad)
            dotted = ".".join(str(p) for p in (*where, bad))
            raise ConfigError(f"unknown key '{dotted}'" + _suggest(bad, err.schema.get("properties", {})), loc)
    if "propertyNames" in err.schema_path:
        bad = err.instance
        loc = key_loc(*where, bad)
        dotted = ".".join(str(p) for p in (*where, bad))
        raise ConfigError(f"bad key '{dotted}': {_short_message(err)}", loc)
    loc = val_loc(*where) if where else Location(path)
    raise ConfigError(f"'{key}': {_short_message(err)}", loc)


def config_schema(rules: bool = True) -> dict:
    """schemas/config.schema.json, with `rules:` built from the options the catalogue entries declare (`rules`
    false: any mapping, for data without that key)."""
    with open(SCHEMA_PATH, encoding="utf-8") as f:
        schema = json.load(f)
    if rules:
        from urdfcheck.rules.catalogue import options_schema

        schema["properties"]["rules"] = options_schema()
    else:
        schema["properties"]["rules"] = {"type": "object"}
    return schema


def _check_codes(data: dict, key_loc, val_loc) -> None:
    """select/ignore/severity name rules that exist (the schema only checks their shape)."""
    from urdfcheck.rules.catalogue import unknown_codes

    for key in ("select", "ignore"):
        for i, code in enumerate(data.get(key) or ()):
            for problem in unknown_codes([code]):
                raise ConfigError(f"'{key}': {problem}", val_loc(key, i))
    for code in data.get("severity") or {}:
        for problem in unknown_codes([code]):
            raise ConfigError(f"'severity': {problem}", key_loc("severity", code))


_CODE_PATTERNS = ("^(ALL|[A-Z][0-9]{0,3})$", "^[A-Z][0-9]{3}$")


def _short_message(err) -> str:
    if err.validator == "pattern" and err.validator_value in _CODE_PATTERNS:
        return f"{err.instance!r} is not a rule code" + (" or prefix (e.g. S001, J, ALL)"
                                                        if err.validator_value == _CODE_PATTERNS[0] else " (e.g. C010)")
    if err.validator == "pattern" and "->" in str(err.validator_value):
        return f"{err.instance!r} is not a TF edge written 'parent->child'"
    msg = err.message
    if err.validator == "oneOf" and err.context:
        msg = min((e.message for e in err.context), key=len)
    return msg if len(msg) < 300 else msg[:297] + "..."


def _suggest(word: str, options) -> str:
    import difflib

    close = difflib.get_close_matches(word, list(options), n=1)
    return f" (did you mean '{close[0]}'?)" if close else ""


def _as_tuple(v) -> tuple[str, ...]:
    if v is None:
        return ()
    if isinstance(v, str):
        return (v,)
    return tuple(str(x) for x in v)


def _str_args(d) -> dict[str, str]:
    out = {}
    for k, v in (d or {}).items():
        out[str(k)] = ("true" if v else "false") if isinstance(v, bool) else str(v)
    return out


def load_config(path: str | os.PathLike, trusted: bool = False, root: str | None = None) -> Config:
    """`trusted`: the person running the tool named this config (--config FILE --trust-config); otherwise
    what lowers the guard is ignored, with a finding, and its paths stay in the checkout (request.trust).
    `root`: the folder its relative paths start at (default: its own folder; a trusted config kept in a private
    temp file, such as the base revision's, names the checkout folder it belongs to)."""
    from urdfcheck.request import trust

    path = os.path.abspath(str(path))
    if not os.path.isfile(path):
        raise ConfigError(f"no such config file: {path}", Location(path))
    if os.path.basename(path) == PYPROJECT or path.endswith(".toml"):
        data, key_loc, val_loc = _read_pyproject(path)
    else:
        data, key_loc, val_loc = _read_yaml(path)
    if not isinstance(data, dict):
        raise ConfigError("the config must be a mapping of keys (models, frames, select, ...)", val_loc())
    try:
        _validate(data, path, key_loc, val_loc)
    except RecursionError:
        raise ConfigError("the config is nested too deeply", Location(path)) from None
    notes = tuple(trust.screen(data, path, key_loc, trusted))
    root = os.path.abspath(root) if root else os.path.dirname(path)
    locs: dict[tuple, Location] = {}

    def resolve(p: str, *keypath, must_exist=True, kind="file") -> str:
        if "\x00" in str(p):  # no file system takes it (os.path.realpath raises ValueError)
            raise ConfigError(f"'{'.'.join(str(k) for k in keypath)}': a path holding a NUL character",
                              val_loc(*keypath))
        full = os.path.normpath(os.path.join(root, os.path.expanduser(p) if trusted else p))
        why = trust.confine(full, root, trusted)
        if why is not None:
            raise ConfigError(f"'{'.'.join(str(k) for k in keypath)}': {p}: {why}", val_loc(*keypath))
        if must_exist and not os.path.exists(full):
            raise ConfigError(f"'{'.'.join(str(k) for k in keypath)}': no such {kind}: {p}", val_loc(*keypath))
        locs[tuple(keypath)] = val_loc(*keypath)
        return full

    models = []
    for i, m in enumerate(data.get("models") or []):
        mp = resolve(m["path"], "models", i, "path")
        if not os.path.isfile(mp):
            raise ConfigError(f"'models.{i}.path': not a file: {m['path']}", val_loc("models", i, "path"))
        variants = m.get("variants")
        if isinstance(variants, dict):
            variants = _ro({str(k): _ro(_str_args(v)) for k, v in variants.items()})
            if not variants:
                variants = None
        from urdfcheck.consumers.controllers import DriverSpec

        drivers = []
        for j, d in enumerate(m.get("drivers") or []):
            drivers.append(DriverSpec(
                file=resolve(d["file"], "models", i, "drivers", j, "file"),
                loc=key_loc("models", i, "drivers", j, "file"),
                name=str(d.get("name") or ""), node=str(d.get("node") or ""),
                joints=_as_tuple(d.get("joints")), left_wheels=_as_tuple(d.get("left_wheels")),
                right_wheels=_as_tuple(d.get("right_wheels")),
                wheel_separation=d.get("wheel_separation"), wheel_radius=d.get("wheel_radius"),
                frames=_as_tuple(d.get("frames")), odom_tf=d.get("odom_tf"),
                odom_frame=d.get("odom_frame"), base_frame=d.get("base_frame"),
            ))
        replaced = _ro({}) if trusted else _replaced_defaults(mp, m)
        models.append(ModelConfig(
            defaults=replaced, path=mp, loc=val_loc("models", i, "path"), args=_ro(_str_args(m.get("args"))),
            variants=variants,
            controllers=tuple(resolve(p, "models", i, "controllers", k)
                              for k, p in enumerate(m.get("controllers") or [])),
            drivers=tuple(drivers),
            launch=tuple(resolve(p, "models", i, "launch", k) for k, p in enumerate(m.get("launch") or [])),
            launch_args=_ro(_str_args(m.get("launch_args"))),
            localization=tuple(resolve(p, "models", i, "localization", k)
                               for k, p in enumerate(m.get("localization") or [])),
            frame_prefix=str(m.get("frame_prefix") or ""),
            bags=tuple(resolve(p, "models", i, "bags", k, kind="recording") for k, p in enumerate(m.get("bags") or [])),
        ))
        if replaced and any(n == "xacro defaults" for n, _ in models[-1].variant_args()):
            key = "args" if m.get("args") else "variants"
            notes += (trust.defaults_kept(str(m["path"]), replaced, key_loc("models", i, key)),)
        if not trusted and (models[-1].launch_args or models[-1].frame_prefix):
            key = "launch_args" if models[-1].launch_args else "frame_prefix"
            notes += (trust.launch_defaults_kept(str(m["path"]), key, key_loc("models", i, key)),)
    packages = {str(k): resolve(v, "packages", k, kind="folder") for k, v in (data.get("packages") or {}).items()}
    for k, p in packages.items():
        if not os.path.isdir(p):
            raise ConfigError(f"'packages.{k}': not a folder: {data['packages'][k]}", val_loc("packages", k))
    if not trusted and packages:
        notes += tuple(_own_packages(packages, data, root, key_loc, [path] + [m.path for m in models]))
    tf_owners = {str(k): str(v) for k, v in (data.get("tf_owners") or {}).items()}
    tf_owner_locs = {k: key_loc("tf_owners", k) for k in tf_owners}
    severity = {str(k): Severity.parse(v) for k, v in (data.get("severity") or {}).items()}
    fail_on = Severity.parse(data["fail_on"]) if data.get("fail_on") else None
    rules = {str(k): _ro(v) for k, v in (data.get("rules") or {}).items()}
    for key in ("models", "frames", "tf_owners", "packages", "select", "ignore", "fail_on", "severity", "rules"):
        if key in data:
            locs[(key,)] = key_loc(key)
    if data.get("cache") is False:  # a config can turn the lint cache off, never point it somewhere (cli/cache.py)
        from urdfcheck.core import observe

        observe.taint("the config says cache: false")
    return Config(
        path=path, root=root, models=tuple(models),
        frames=_ro({**DEFAULT_FRAMES, **{str(k): str(v) for k, v in (data.get("frames") or {}).items()}}),
        tf_owners=_ro(tf_owners), tf_owner_locs=_ro(tf_owner_locs), packages=_ro(packages),
        select=tuple(data["select"]) if data.get("select") else None,
        ignore=tuple(data.get("ignore") or ()), fail_on=fail_on, severity=_ro(severity), rules=_ro(rules),
        trusted=bool(data.get("trusted", False)), allow_env=tuple(data.get("allow_env") or ()),
        max_elements=int(data["max_elements"]) if data.get("max_elements") is not None else None, locs=_ro(locs),
        target=str(data["target"]) if data.get("target") else None,
        profiles=tuple(dict.fromkeys(str(p) for p in data.get("profiles") or ())),
        notes=notes, vouched=trusted,
    )


def _replaced_defaults(model: str, m: dict) -> Mapping:
    """The xacro args with a default in `model` (name -> default) that the config's `args` or `variants` set."""
    given = {str(k) for k in m.get("args") or {}}
    if isinstance(m.get("variants"), dict):
        for v in m["variants"].values():
            given |= {str(k) for k in v or {}}
    if not given or not model.endswith(".xacro"):
        return _ro({})
    from urdfcheck.load.variants import defaulted_args

    return _ro({k: v for k, v in defaulted_args(model).items() if k in given})


def _own_packages(packages: dict, data: dict, root: str, key_loc, files: list[str]) -> list:
    """Refuse (X018, and drop) `packages:` entries that point a package the checkout defines (a package.xml of
    that name in the config's repository) at another folder, or choose among two copies of it: the pull request
    would lint a clean copy. An entry naming the package that holds the config and its models (`files`) is what
    zero config resolves for them anyway (the copy nearest each model) and needs no scan of the repository."""
    from urdfcheck.load.packages import workspace_packages
    from urdfcheck.request import trust

    pending = [name for name in packages if not _holds_as(packages[name], name, files)]
    if not pending:
        return []
    top = trust.repo_root(root)
    own = workspace_packages(top)
    out = []
    for name in pending:
        homes = own.get(name)
        # two copies of one package in the checkout: choosing one is the runner's (the pull request could commit a
        # clean copy under the same name); zero config resolves the copy nearest each model
        if homes and (len(homes) > 1 or realpath(packages[name]) != realpath(homes[0])):
            shown = [os.path.relpath(h, top) for h in homes]  # no absolute runner path in a message
            out.append(trust.refuse_package(name, str(data["packages"][name]), shown, key_loc("packages", name)))
            del packages[name]
    return out


def _holds_as(folder: str, name: str, files: list[str]) -> bool:
    """Is `folder` package `name` (its package.xml says so), holding every one of `files`? Then each of them is
    nearer to it than to any other copy of the package, which zero config would resolve instead."""
    from urdfcheck.load.packages import package_name

    home = realpath(folder)
    if not all(realpath(f).startswith(home.rstrip(os.sep) + os.sep) for f in files):
        return False
    return package_name(Path(home, "package.xml")) == name


# --- variants: auto (load.variants; imported from here too) ----------------------------------------------
def boolean_args(path: str) -> dict[str, str]:
    """The entry file's own boolean xacro:args (name -> default)."""
    from urdfcheck.load.variants import boolean_args as args_of

    return args_of(path, included=False)


def auto_variants(path: str, base: Mapping[str, str], packages: Mapping[str, str] | None = None
                  ) -> list[tuple[str, dict]]:
    from urdfcheck.load.variants import auto_variants as variants_of

    return variants_of(path, base, packages)
