"""Module-level patterns compile on their first use (core/lazyre) and then behave as the compiled pattern."""
import ast
import re
from pathlib import Path

import pytest

from urdfcheck.core import lazyre

SRC = Path(__file__).resolve().parents[2] / "src" / "urdfcheck"


def test_compiles_on_first_use_only(monkeypatch):
    calls = []
    real = re.compile
    monkeypatch.setattr(lazyre.re, "compile", lambda *a: calls.append(a) or real(*a))
    p = lazyre.compile(r"(\w+)-(\d+)", re.I)
    assert calls == []
    assert p.search("x ABC-12").groups() == ("ABC", "12")
    assert p.findall("a-1 b-2") == [("a", "1"), ("b", "2")]
    assert calls == [(r"(\w+)-(\d+)", re.I)]  # once, then the compiled pattern's own methods
    assert p.pattern == r"(\w+)-(\d+)" and p.flags & re.I and p.groups == 2


@pytest.mark.parametrize("method,args", [
    ("match", ("ab12",)), ("fullmatch", ("ab12",)), ("sub", ("-", "ab12 cd3")), ("subn", ("-", "ab12 cd3")),
    ("split", ("ab12 cd3",)), ("findall", ("ab12 cd3",)),
])
def test_same_answers_as_re(method, args):
    lazy, plain = lazyre.compile(r"[a-z]+(\d)"), re.compile(r"[a-z]+(\d)")
    got, want = getattr(lazy, method)(*args), getattr(plain, method)(*args)
    if isinstance(want, re.Match):
        assert (got.span(), got.groups()) == (want.span(), want.groups())
    else:
        assert got == want
    assert [m.span() for m in lazy.finditer("ab12 cd3")] == [m.span() for m in plain.finditer("ab12 cd3")]


def test_a_bad_pattern_fails_where_it_is_used():
    p = lazyre.compile("(")
    with pytest.raises(re.error):
        p.search("x")


def test_no_module_compiles_its_patterns_at_import():
    """A module-level `re.compile` costs every run its compile time, used or not: they go through lazyre."""
    found = []
    for path in SRC.rglob("*.py"):
        for node in ast.parse(path.read_text(encoding="utf-8")).body:
            value = getattr(node, "value", None)
            if isinstance(value, ast.Call) and isinstance(value.func, ast.Attribute) and value.func.attr == "compile" \
                    and isinstance(value.func.value, ast.Name) and value.func.value.id == "re":
                found.append(f"{path.relative_to(SRC)}:{node.lineno}")
    assert not found, found
