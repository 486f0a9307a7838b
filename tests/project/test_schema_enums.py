"""The schemas' enums are written from the one list each comes from (`python tools/schemas.py --write`), and a
list changed without rewriting them fails here."""
from __future__ import annotations

import importlib.util
import json

from conftest import REPO


def _tool():
    spec = importlib.util.spec_from_file_location("schemas_tool", REPO / "tools" / "schemas.py")
    mod = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(mod)
    return mod


def test_committed_schemas_are_the_generated_ones():
    tool = _tool()
    wanted = tool.lists()
    for name in tool.NAMES:
        text = (tool.SCHEMAS / name).read_text(encoding="utf-8")
        assert tool.generated(text, wanted) == text, "run: python tools/schemas.py --write"


def test_a_new_list_entry_reaches_every_enum_of_its_property():
    """A way of taking a step added to core.evidence.HOW (the bug of 6e3a6a8), a profile, a target: the generator
    puts it into every enum of that property, in both schemas."""
    tool = _tool()
    wanted = tool.lists()
    more = {k: (*v, "added") for k, v in wanted.items()}
    seen = set()
    for name in tool.NAMES:
        data = json.loads(tool.generated((tool.SCHEMAS / name).read_text(encoding="utf-8"), more))
        for key, enum in tool._enums(data, []):
            if key in more:
                assert tuple(enum) == more[key], (name, key)
                seen.add(key)
    assert seen == set(more)
