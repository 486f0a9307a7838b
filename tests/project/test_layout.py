"""docs/design.md's folder list is what `python tools/layout.py` makes from the tree, every module listed."""
from __future__ import annotations

import importlib.util

from conftest import REPO


def _layout():
    spec = importlib.util.spec_from_file_location("layout", REPO / "tools" / "layout.py")
    mod = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(mod)
    return mod


def test_design_folder_list_is_the_generated_one():
    layout = _layout()
    committed = layout.committed((REPO / "docs" / "design.md").read_text(encoding="utf-8"))
    assert committed == layout.section(), "run: python tools/layout.py --write"


def test_every_module_is_in_the_list():
    picture = _layout().picture()
    src = REPO / "src" / "urdfcheck"
    for f in src.rglob("*.py"):
        rel = f.relative_to(src)
        if f.name in ("__init__.py", "__main__.py") or "__pycache__" in rel.parts:
            continue
        shown = str(rel.relative_to(rel.parts[0])) if len(rel.parts) > 1 else str(rel)
        assert any(line.split()[0] == shown for line in picture.splitlines()[1:-1] if line.strip()), rel
