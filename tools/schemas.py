"""The enums of the JSON schemas (src/urdfcheck/schemas/*.schema.json), written from the one list each comes from:

    python tools/schemas.py           # say which schema is not current
    python tools/schemas.py --write   # rewrite their enums from the lists

severity: core.findings.Severity; target: model.grammar.TARGETS; profile(s): rules.checks.profiles.common.PROFILES;
evidence how: core.evidence.HOW (the CLI's choices come from the same lists: cli/options.py `choices`). Only the
enum arrays are rewritten; the rest of each file is kept as written. tests/project/test_schema_enums.py fails when a
committed schema is not this output.
"""
from __future__ import annotations

import json
import sys
from pathlib import Path

REPO = Path(__file__).resolve().parent.parent
SCHEMAS = REPO / "src" / "urdfcheck" / "schemas"
NAMES = ("config.schema.json", "report.schema.json")


def lists() -> dict[str, tuple[str, ...]]:
    """Property name -> the one list its enum is."""
    sys.path.insert(0, str(REPO / "src"))
    from urdfcheck.cli.options import choices
    from urdfcheck.core.evidence import HOW

    profiles = choices("profiles")
    return {"severity": choices("severities"), "target": choices("targets"), "profile": profiles,
            "profiles": profiles, "how": tuple(HOW)}


def _enums(node, out: list, key: str = "") -> list:
    """(property name, enum list) of every enum, an array's items' enum counting as its property's."""
    if isinstance(node, dict):
        if "enum" in node and key:
            out.append((key, node["enum"]))
        for k, v in node.items():
            _enums(v, out, key if k in ("items", "enum") else k)
    elif isinstance(node, list):
        for v in node:
            _enums(v, out, key)
    return out


def generated(text: str, wanted: dict[str, tuple[str, ...]]) -> str:
    """`text` with each enum of a listed property replaced by its list."""
    swap: dict[str, str] = {}  # an enum as written -> its list (every enum written alike is replaced at once)
    for key, old in _enums(json.loads(text), []):
        if key in wanted and tuple(old) != wanted[key]:
            after = json.dumps(list(wanted[key]))
            if swap.setdefault(json.dumps(old), after) != after:
                raise ValueError(f"the enum {json.dumps(old)} stands for two lists: write one differently")
    for before, after in swap.items():
        if before not in text:
            raise ValueError(f"enum not written as {before}: write it on one line")
        text = text.replace(before, after)
    got = _enums(json.loads(text), [])
    stale = [k for k, v in got if k in wanted and tuple(v) != wanted[k]]
    if stale:
        raise ValueError(f"enums not rewritten: {stale}")
    return text


def main(argv: list[str]) -> int:
    wanted = lists()
    stale = []
    for name in NAMES:
        path = SCHEMAS / name
        text = path.read_text(encoding="utf-8")
        new = generated(text, wanted)
        if new != text:
            stale.append(name)
            if "--write" in argv:
                path.write_text(new, encoding="utf-8")
    for name in stale:
        print(f"{'wrote' if '--write' in argv else 'not current'}: src/urdfcheck/schemas/{name}")
    return 1 if stale and "--write" not in argv else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
