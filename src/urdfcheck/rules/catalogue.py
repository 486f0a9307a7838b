"""Rule registry: check functions (code) and their catalogue entries (top-level `rules/*.yaml`).

The catalogue is the single source for a rule's name, default severity, summary, rationale, fix and
examples: the engine, `urdfcheck rules`, the generated docs and SARIF metadata all read it.
"""
from __future__ import annotations

import functools
import importlib
import os
from pathlib import Path

from urdfcheck.core.findings import Severity
from urdfcheck.core.records import TupleRecord

TYPE_CHECKING = False  # typing.TYPE_CHECKING without importing typing at start-up
if TYPE_CHECKING:
    from collections.abc import Iterable
    from typing import Protocol

    from urdfcheck.core.findings import Problem
    from urdfcheck.model.robot import Model

    class Check(Protocol):
        """What `@check(codes)` registers: `fn(model, ctx) -> Iterable[Problem] | None`, with its codes."""

        codes: tuple[str, ...]
        needs: str
        __name__: str

        def __call__(self, model: Model, ctx) -> Iterable[Problem] | None: ...

CHECKS: dict[str, Check] = {}  # code -> check function (one function may serve several codes)
# every module of rules/checks, named here so that a run imports them without walking the folder (pkgutil: ~4 ms of
# imports); tests/rules/test_catalogue.py fails when a module of the folder is missing from the list
MODEL_MODULES = tuple(f"urdfcheck.rules.checks.{m}" for m in (
    "frames", "geometry", "inertial", "joints", "moveit", "profiles", "references", "structure", "units", "values"))
# the rules over a model's consumers (contracts C, TF ownership T) and the readers behind them: imported when a
# model can have consumers or has <ros2_control> blocks (`load_checks(consumers=True)`), never for a lone URDF
# outside any ROS package linted without a config (this keeps `urdfcheck lint robot.urdf` fast)
CONSUMER_MODULES = tuple(f"urdfcheck.rules.checks.{m}" for m in ("claims", "contracts", "navframes", "tf"))
CHECK_MODULES = CONSUMER_MODULES + MODEL_MODULES
# what a check needs to run (`@check(..., needs=)`): the model alone, consumers it may have, its <ros2_control>
NEEDS = ("model", "consumers", "ros2_control")


def check(*codes: str, needs: str = "model"):
    """Register `fn(model, ctx) -> Iterable[Problem]` for the given codes. `needs="consumers"`: the engine runs
    it only for a model that can have consumers (`consumers.reach`); `needs="ros2_control"`: only for a model
    with <ros2_control> blocks (a rule that reads nothing but them)."""
    if needs not in NEEDS:
        raise ValueError(f"needs must be one of {NEEDS}: {needs!r}")

    def deco(fn):  # a function becomes a `Check` here (its codes attached)
        fn.codes = codes
        fn.needs = needs
        for c in codes:
            if c in CHECKS and CHECKS[c] is not fn:
                raise RuntimeError(f"rule {c} registered twice ({CHECKS[c].__name__}, {fn.__name__})")
            CHECKS[c] = fn
        return fn

    return deco


# option types a catalogue entry may declare -> the JSON Schema a config value must satisfy
OPTION_TYPES: dict[str, dict] = {
    "number": {"type": "number"},
    "integer": {"type": "integer"},
    "boolean": {"type": "boolean"},
    "string": {"type": "string"},
    "strings": {"type": "array", "items": {"type": "string"}},
}


class OptionSpec(TupleRecord):
    """One rule option, declared once in the catalogue entry: `options: {name: {type, default, doc}}`."""

    name: str
    type: str
    default: object
    doc: str
    minimum: float | None = None

    def schema(self) -> dict:
        out = dict(OPTION_TYPES[self.type], description=self.doc)
        if self.minimum is not None:
            out["minimum"] = self.minimum
        return out


def option_ok(spec: OptionSpec, value) -> bool:
    """Does `value` satisfy the option's declared type (and minimum)? The config file is checked by its
    schema, which `options_schema` builds from the same declarations; this is for values given in Python."""
    def number(v):
        return isinstance(v, (int, float)) and not isinstance(v, bool)

    ok = {
        "number": number,
        "integer": lambda v: isinstance(v, int) and not isinstance(v, bool),
        "boolean": lambda v: isinstance(v, bool),
        "string": lambda v: isinstance(v, str),
        "strings": lambda v: isinstance(v, (list, tuple)) and all(isinstance(x, str) for x in v),
    }[spec.type](value)
    return ok and (spec.minimum is None or not number(value) or value >= spec.minimum)


def options_for(codes, given=None, cat=None) -> dict:
    """A check's options: every option its codes declare in the catalogue (rules/*.yaml `options:`), at
    its declared default, then the values `given` (code -> {option: value}, a Selection's options) sets for
    those codes, checked against the declared type. The one place defaults come from: a check reads
    `ctx.options[name]` and never has its own fallback. A value of the wrong type or an undeclared option
    raises ValueError (R001 for that rule; configs and requests are checked earlier, this catches a
    hand-made Selection)."""
    cat = catalogue() if cat is None else cat
    out: dict = {}
    specs: dict = {}
    for code in codes:
        info = cat.get(code)
        for name, default in (info.options if info else {}).items():
            if name not in out:
                out[name] = list(default) if isinstance(default, list) else default  # a check may not share it
                specs[name] = info.option_specs.get(name)
    for code in codes:
        for name, value in dict((given or {}).get(code, {})).items():
            spec = specs.get(name)
            if spec is None:
                raise ValueError(f"{code} has no option {name!r} (options: {', '.join(specs) or 'none'})")
            if not option_ok(spec, value):
                raise ValueError(f"option {code}.{name} must be {spec.type}"
                                 + (f" >= {spec.minimum}" if spec.minimum is not None else "") + f", got {value!r}")
            out[name] = value
    return out


class RuleInfo(TupleRecord):
    """A rule's catalogue entry. What a lint run needs is read with the catalogue (`index.json`); the long
    texts and the examples (nine tenths of the catalogue's bytes) only when asked for (`details.json`), by
    the docs, SARIF's rule metadata, `urdfcheck rules` and the tests."""

    code: str
    name: str
    severity: Severity
    family: str
    summary: str
    options: dict = {}  # name -> default (what a check gets when the config sets nothing)
    path: str = ""
    option_specs: dict = {}  # name -> OptionSpec
    # the upstream sources the rule relies on: ({"url": ..., "what": ...}, ...); the first is SARIF's helpUri
    references: tuple = ()

    @property
    def rationale(self) -> str:
        return str(self._details()["rationale"]).strip()

    @property
    def fix(self) -> str:
        return str(self._details()["fix"]).strip()

    @property
    def examples(self) -> dict:
        return dict(self._details()["examples"] or {})

    @property
    def cases(self) -> tuple:
        """More examples than `examples: {fail:, pass:}`: each {expect: fail|pass, config: {...}, urdf:/files:/...}"""
        return tuple(self._details().get("cases") or ())

    def _details(self) -> dict:
        return _details(os.path.dirname(self.path))[self.code]

    def all_examples(self) -> list[tuple[str, dict]]:
        """(expect, example) for the failing and passing example, then the further cases."""
        examples, cases = self.examples, self.cases
        out = [(k, examples[k]) for k in ("fail", "pass") if examples.get(k)]
        return out + [(str(c["expect"]), c) for c in cases]


class CatalogueError(Exception):
    pass


def catalogue_dir() -> Path:
    """Installed wheels carry the catalogue inside the package; a source checkout reads `rules/`."""
    package = Path(__file__).resolve().parent.parent
    inside = package / "catalogue"
    if inside.is_dir():
        return inside
    return package.parent.parent / "rules"


_REQUIRED = ("code", "name", "severity", "family", "summary", "rationale", "fix", "examples")


INDEX = "index.json"
DETAILS = "details.json"
DETAIL_KEYS = ("rationale", "fix", "examples", "cases")


def read_entries(folder: Path | None = None) -> dict[str, dict]:
    """Parse every rules/*.yaml (the source of truth)."""
    from urdfcheck.core.yamlimport import yaml

    loader = getattr(yaml, "CSafeLoader", yaml.SafeLoader)
    folder = folder or catalogue_dir()
    out: dict[str, dict] = {}
    for path in sorted(folder.glob("*.yaml")):
        with open(path, encoding="utf-8") as f:
            data = yaml.load(f, Loader=loader)
        missing = [k for k in _REQUIRED if k not in (data or {})]
        if missing:
            raise CatalogueError(f"{path.name}: missing {', '.join(missing)}")
        if path.stem != str(data["code"]):
            raise CatalogueError(f"{path.name}: file name must be the code {data['code']}")
        _check_extras(path.name, data)
        out[str(data["code"])] = data
    return out


def write_index(folder: Path | None = None) -> Path:
    """rules/index.json and rules/details.json: the parsed catalogue, so a lint run reads one small JSON file
    instead of ~80 YAML files. Generated; tests/rules/test_catalogue.py fails when they are stale. Returns the
    index's path."""
    import json

    folder = folder or catalogue_dir()
    index, details = split_entries(read_entries(folder))
    for name, data in ((INDEX, index), (DETAILS, details)):
        (folder / name).write_text(json.dumps(data, indent=1, sort_keys=True, ensure_ascii=False) + "\n",
                                   encoding="utf-8")
    return folder / INDEX


def split_entries(entries: dict[str, dict]) -> tuple[dict, dict]:
    """(index, details): each entry without and with only the fields a lint run does not read."""
    index = {code: {k: v for k, v in data.items() if k not in DETAIL_KEYS} for code, data in entries.items()}
    details = {code: {k: v for k, v in data.items() if k in DETAIL_KEYS} for code, data in entries.items()}
    return index, details


@functools.cache
def _details(folder: str) -> dict[str, dict]:
    index, details = Path(folder) / INDEX, Path(folder) / DETAILS
    if index.is_file() and details.is_file():
        import json

        with open(details, encoding="utf-8") as f:
            return json.load(f)
    return split_entries(read_entries(Path(folder)))[1]


@functools.cache
def catalogue() -> dict[str, RuleInfo]:
    import json

    folder = catalogue_dir()
    index = folder / INDEX
    if index.is_file() and (folder / DETAILS).is_file():
        with open(index, encoding="utf-8") as f:
            entries = json.load(f)
    else:
        entries = read_entries(folder)
    return {code: _info(data, str(folder / f"{code}.yaml")) for code, data in sorted(entries.items())}


def _option_specs(code: str, raw) -> dict[str, OptionSpec]:
    out = {}
    for name, d in (raw or {}).items():
        if not isinstance(d, dict) or d.get("type") not in OPTION_TYPES or "default" not in d or not d.get("doc"):
            raise CatalogueError(f"{code}: option {name!r} must declare type ({', '.join(OPTION_TYPES)}), "
                                 "default and doc")
        out[str(name)] = OptionSpec(str(name), d["type"], d["default"], str(d["doc"]).strip(), d.get("minimum"))
    return out


def options_schema() -> dict:
    """JSON Schema of the config's `rules:` mapping, built from the options each rule declares: an unknown
    rule, an unknown option or a value of the wrong type is a config error."""
    rules = {}
    for code, r in catalogue().items():
        rules[code] = {"type": "object", "additionalProperties": False,
                       "properties": {n: s.schema() for n, s in r.option_specs.items()}}
    return {"type": "object", "properties": rules, "additionalProperties": False}


def _check_extras(name: str, data: dict) -> None:
    """`cases:` and `references:`, when an entry has them."""
    for i, case in enumerate(data.get("cases") or ()):
        if not isinstance(case, dict) or case.get("expect") not in ("fail", "pass"):
            raise CatalogueError(f"{name}: cases[{i}] needs expect: fail or expect: pass")
        if case.get("config") is not None and not isinstance(case["config"], dict):
            raise CatalogueError(f"{name}: cases[{i}].config must be a mapping (the urdfcheck.yaml it lints with)")
    for kind in ("fail", "pass"):
        ex = (data.get("examples") or {}).get(kind)
        if isinstance(ex, dict) and ex.get("config") is not None and not isinstance(ex["config"], dict):
            raise CatalogueError(f"{name}: examples.{kind}.config must be a mapping")
    for i, ref in enumerate(data.get("references") or ()):
        url = ref.get("url") if isinstance(ref, dict) else None
        if not isinstance(url, str) or not url.startswith("https://") or not str(ref.get("what") or "").strip():
            raise CatalogueError(f"{name}: references[{i}] needs url: https://... and what: (what it shows)")


def _info(data: dict, path: str) -> RuleInfo:
    specs = _option_specs(str(data["code"]), data.get("options"))
    return RuleInfo(
        code=str(data["code"]), name=str(data["name"]), severity=Severity.parse(data["severity"]),
        family=str(data["family"]), summary=str(data["summary"]).strip(),
        options={n: s.default for n, s in specs.items()}, path=path, option_specs=specs,
        references=tuple(dict(r) for r in data.get("references") or ()),
    )


@functools.cache
def load_checks(consumers: bool = True) -> dict[str, Check]:
    """The registered checks, after importing their modules: all of them, or (`consumers=False`) those over the
    model alone (the consumer rules may be registered already: the engine asks each check what it `needs`)."""
    for name in (CHECK_MODULES if consumers else MODEL_MODULES):
        importlib.import_module(name)
    return dict(CHECKS)


def info(code: str) -> RuleInfo | None:
    return catalogue().get(code)


def example_files(ex: dict) -> dict[str, str]:
    """The files of a catalogue example: `files:` plus the `urdf:`/`xacro:` shorthands."""
    files = dict(ex.get("files") or {})
    if ex.get("config") is not None:  # the example runs with this config (its own urdfcheck.yaml)
        from urdfcheck.core.yamlimport import yaml

        files["urdfcheck.yaml"] = yaml.safe_dump(dict(ex["config"]), sort_keys=False)
    if "urdf" in ex:
        files["robot.urdf"] = ex["urdf"]
    if "xacro" in ex:
        files["robot.urdf.xacro"] = ex["xacro"]
    return files


def unknown_codes(patterns) -> list[str]:
    """Problems with selection patterns: each is 'CODE is not a rule code or prefix (did you mean ...)'.
    A pattern is valid when it is ALL, a rule code, or a prefix of at least one rule code."""
    from urdfcheck.core.findings import closest

    patterns = list(patterns or ())
    if not patterns:  # the catalogue is read later, while the first expansion runs in its worker
        return []
    codes = sorted(set(catalogue()) | set(CHECKS))
    out = []
    for p in patterns:
        if p == "ALL" or any(c.startswith(p) for c in codes):
            continue
        close = closest(p, codes, cutoff=0.6)
        out.append(f"{p!r} is not a rule code or prefix" + (f" (did you mean {close!r}?)" if close else
                                                           " (`urdfcheck rules` lists them)"))
    return out


def matches(code: str, patterns) -> bool:
    """ruff-style selection: a pattern is a full code or a prefix ('S', 'J00', 'ALL')."""
    return any(p == "ALL" or code.startswith(p) for p in patterns)


if __name__ == "__main__":  # python -m urdfcheck.rules.catalogue: regenerate rules/index.json and details.json
    print(write_index())
