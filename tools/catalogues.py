"""Write the JSON twins of the hand-edited YAML catalogues that a lint run reads.

    python tools/catalogues.py          # rewrite the twins
    python tools/catalogues.py --check  # exit 1 when a twin is stale (tests/rules/test_catalogue_twins.py runs this)

The YAML files are what people edit (comments, anchors). A lint run reads the JSON twin: the standard library's
json is already imported by then, PyYAML is not, and importing it costs ~16 ms of a 130 ms run on a plain URDF.
"""
from __future__ import annotations

import json
import sys
from pathlib import Path

import yaml

ROOT = Path(__file__).resolve().parent.parent / "src" / "urdfcheck"
CATALOGUES = ("consumers/controller_types.yaml", "consumers/tfowners.yaml")


def twin_text(source: Path) -> str:
    data = yaml.safe_load(source.read_text(encoding="utf-8")) or {}
    return json.dumps(data, indent=1, sort_keys=True, ensure_ascii=False) + "\n"


def main(argv: list[str]) -> int:
    stale = []
    for rel in CATALOGUES:
        source = ROOT / rel
        twin = source.with_suffix(".json")
        text = twin_text(source)
        if twin.exists() and twin.read_text(encoding="utf-8") == text:
            continue
        if "--check" in argv:
            stale.append(str(twin.relative_to(ROOT.parent.parent)))
        else:
            twin.write_text(text, encoding="utf-8")
            print(f"wrote {twin.relative_to(ROOT.parent.parent)}")
    if stale:
        print("stale (run python tools/catalogues.py): " + ", ".join(stale), file=sys.stderr)
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
