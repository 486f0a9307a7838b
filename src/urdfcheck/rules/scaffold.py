"""Start a new rule: `python -m urdfcheck.rules.scaffold J013 joint-name-too-long --module joints`.

Writes the catalogue entry `rules/J013.yaml` (every required field; its failing example does not fail yet, so
tests/test_catalogue.py stays red until the rule and its examples are written) and appends a check function that
yields nothing to `src/urdfcheck/rules/checks/<module>.py`. Refuses to overwrite an existing entry or a registered code.
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
"""

CHECK = '''

@check("{code}")
def {func}(model, ctx):
    """TODO: yield Problem(message, at=part) for each defect; never compute file or line here."""
    return
    yield
'''


def scaffold(root: Path, code: str, name: str, module: str) -> list[Path]:
    if not re.fullmatch(r"[A-Z][0-9]{3}", code) or code[0] not in FAMILIES:
        raise ValueError(f"code must be a family letter ({''.join(FAMILIES)}) and three digits: {code!r}")
    if not re.fullmatch(r"[a-z][a-z0-9-]*", name):
        raise ValueError(f"name must be lower-case words joined by '-': {name!r}")
    entry = root / "rules" / f"{code}.yaml"
    checks = root / "src" / "urdfcheck" / "rules" / "checks" / f"{module}.py"
    if entry.exists():
        raise ValueError(f"{entry} exists already")
    if not checks.is_file():
        raise ValueError(f"no check module {checks}")
    text = checks.read_text(encoding="utf-8")
    if f'"{code}"' in text:
        raise ValueError(f"{code} is already registered in {checks}")
    entry.write_text(ENTRY.format(code=code, name=name, family=FAMILIES[code[0]]), encoding="utf-8")
    checks.write_text(text.rstrip("\n") + "\n" + CHECK.format(code=code, func=name.replace("-", "_")),
                      encoding="utf-8")
    return [entry, checks]


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(prog="python -m urdfcheck.rules.scaffold", description=__doc__.splitlines()[0])
    ap.add_argument("code")
    ap.add_argument("name")
    ap.add_argument("--module", required=True, help="check module under src/urdfcheck/rules/checks/")
    ap.add_argument("--root", default=str(Path(__file__).resolve().parents[3]), help="source checkout")
    ns = ap.parse_args(argv)
    try:
        written = scaffold(Path(ns.root), ns.code, ns.name, ns.module)
    except ValueError as e:
        print(f"scaffold: {e}", file=sys.stderr)
        return 2
    for p in written:
        print(f"wrote {p}")
    print("next: fill in the TODOs, then regenerate rules/index.json and docs/rules.md (CONTRIBUTING.md)")
    return 0


if __name__ == "__main__":
    sys.exit(main())
