"""Start a new rule: `python -m urdfcheck.rules.scaffold J013 joint-name-too-long --module joints`.

Writes the catalogue entry `rules/J013.yaml` (every required field; its failing example does not fail yet, so
tests/rules/test_catalogue.py stays red until the rule and its examples are written), appends a typed check function
that yields nothing to `src/urdfcheck/rules/checks/<module>.py` (or `<module>/__init__.py`), and regenerates what
is generated from the catalogue: rules/index.json and details.json, docs/rules.md and the rule table of
docs/design.md. Refuses to
overwrite an existing entry or a registered code.
"""
from __future__ import annotations

import argparse
import re
import sys
from pathlib import Path

FAMILIES = {"X": "loading", "U": "syntax", "S": "structure", "J": "joints", "I": "inertial", "G": "geometry",
            "F": "frames", "C": "contracts", "T": "tf", "V": "verify", "R": "runner", "P": "profiles"}

ENTRY = """\
code: {code}
name: {name}
severity: warning
family: {family}
summary: TODO one sentence, what is wrong.
rationale: |
  TODO what breaks, and what urdfdom, KDL, Gazebo, MuJoCo and Pinocchio do with it (verified in their sources).
fix: |
  TODO what to write instead.
examples:
  fail:
    urdf: |
      <robot name="r">
        <link name="base_link"/>
      </robot>
  pass:
    urdf: |
      <robot name="r">
        <link name="base_link"/>
      </robot>
# cases:            # more examples, each with its own urdfcheck.yaml
#   - expect: fail
#     title: what this case shows
#     config: {{rules: {{{code}: {{}}}}}}
#     urdf: |
#       <robot name="r"><link name="base_link"/></robot>
# references:       # the upstream source lines the rule follows (the first is SARIF's helpUri)
#   - url: https://github.com/ros/urdfdom/blob/master/urdf_parser/src/joint.cpp
#     what: TODO what that source does
"""

# the families whose rules read a model's consumers: their checks run only for a model that can have them
CONSUMER_FAMILIES = "CT"

CHECK = '''

@check("{code}"{needs})
def {func}(model: Model, ctx: Context) -> Iterator[Problem]:
    """TODO: yield Problem(message, at=part) for each defect; never compute file or line here."""
    return
    yield
'''

TYPES = """
from urdfcheck.core.records import TYPE_CHECKING  # no typing import at run time

if TYPE_CHECKING:  # the check's argument types (no import at run time)
    from collections.abc import Iterator

    from urdfcheck.core.findings import Problem
    from urdfcheck.model.robot import Model
    from urdfcheck.rules.engine import Context
"""


def _with_types(text: str) -> str:
    """The module with the names the typed stub uses, after its last top-level import."""
    if "from urdfcheck.rules.engine import Context" in text:
        return text
    import ast

    tree = ast.parse(text)
    last = max((n.end_lineno or 0 for n in tree.body if isinstance(n, (ast.Import, ast.ImportFrom))), default=0)
    lines = text.splitlines(keepends=True)
    return "".join(lines[:last]) + TYPES + "".join(lines[last:])


def scaffold(root: Path, code: str, name: str, module: str) -> list[Path]:
    if not re.fullmatch(r"[A-Z][0-9]{3}", code) or code[0] not in FAMILIES:
        raise ValueError(f"code must be a family letter ({''.join(FAMILIES)}) and three digits: {code!r}")
    if not re.fullmatch(r"[a-z][a-z0-9-]*", name):
        raise ValueError(f"name must be lower-case words joined by '-': {name!r}")
    entry = root / "rules" / f"{code}.yaml"
    checks = root / "src" / "urdfcheck" / "rules" / "checks" / f"{module}.py"
    if not checks.is_file() and (checks.with_suffix("") / "__init__.py").is_file():  # a package: rules/checks/tf/
        checks = checks.with_suffix("") / "__init__.py"
    if entry.exists():
        raise ValueError(f"{entry} exists already")
    if not checks.is_file():
        raise ValueError(f"no check module {checks}")
    text = checks.read_text(encoding="utf-8")
    if f'"{code}"' in text:
        raise ValueError(f"{code} is already registered in {checks}")
    entry.write_text(ENTRY.format(code=code, name=name, family=FAMILIES[code[0]]), encoding="utf-8")
    checks.write_text(_with_types(text).rstrip("\n") + "\n" + CHECK.format(
        code=code, func=name.replace("-", "_"), needs=', needs="consumers"' if code[0] in CONSUMER_FAMILIES else ""),
                      encoding="utf-8")
    _sort_imports(checks)
    return [entry, checks] + regenerate(root)


def _sort_imports(path: Path) -> None:
    import importlib.util
    import subprocess

    if importlib.util.find_spec("ruff") is not None:
        subprocess.run([sys.executable, "-m", "ruff", "check", "--fix", "--select", "I", "--quiet", str(path)],
                       check=False, capture_output=True)


def regenerate(root: Path) -> list[Path]:
    """rules/index.json and details.json, and (in this source checkout) docs/rules.md and design.md's rule table."""
    from urdfcheck.rules import catalogue as rulebook
    from urdfcheck.rules import docs

    index = rulebook.write_index(root / "rules")
    out = [index, index.with_name(rulebook.DETAILS)]
    if (root / "rules").resolve() != rulebook.catalogue_dir().resolve():
        return out  # another checkout: its docs are generated from its own catalogue there
    rulebook.catalogue.cache_clear()
    rulebook._details.cache_clear()
    rules_md = root / "docs" / "rules.md"
    if rules_md.parent.is_dir():
        rules_md.write_text(docs.rules_markdown(), encoding="utf-8")
        out.append(rules_md)
    design = root / "docs" / "design.md"
    if design.is_file() and docs.write_design_table(design):
        out.append(design)
    return out


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(prog="python -m urdfcheck.rules.scaffold", description=__doc__.splitlines()[0])
    ap.add_argument("code", nargs="?")
    ap.add_argument("name", nargs="?")
    ap.add_argument("--module", help="check module under src/urdfcheck/rules/checks/")
    ap.add_argument("--root", default=str(Path(__file__).resolve().parents[3]), help="source checkout")
    ap.add_argument("--regenerate", action="store_true",
                    help="only regenerate rules/index.json and details.json,"
                    " docs/rules.md and design.md's rule table")
    ns = ap.parse_args(argv)
    if ns.regenerate:
        for p in regenerate(Path(ns.root)):
            print(f"wrote {p}")
        return 0
    if not (ns.code and ns.name and ns.module):
        ap.error("CODE, NAME and --module are required (or --regenerate)")
    try:
        written = scaffold(Path(ns.root), ns.code, ns.name, ns.module)
    except ValueError as e:
        print(f"scaffold: {e}", file=sys.stderr)
        return 2
    for p in written:
        print(f"wrote {p}")
    print("next: fill in the TODOs and the examples; after editing the entry, regenerate with "
          "`python -m urdfcheck.rules.scaffold --regenerate`")
    return 0


if __name__ == "__main__":
    sys.exit(main())
