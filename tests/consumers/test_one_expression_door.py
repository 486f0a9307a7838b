"""One evaluator of launch-time expressions (consumers.launch.expr, issue 42). roslaunch's `$(eval)` and ROS 2's
`PythonExpression` had an allow-list of node kinds each, and the limits of one (string length) were missing from
the other. The scan fails when a module outside the expression doors (expr; load.xacro.safeeval, xacro's own
sandbox) parses text as an expression or dispatches on the node kinds an evaluator allows. The one other place
allowed is the reader of Python launch programs (`PyLaunch._ev`): it follows a launch file's own code, names,
calls and substitution objects whose values are unknown until launch, not an expression string."""
from __future__ import annotations

import ast
from pathlib import Path

import pytest

from urdfcheck.consumers.launch import expr

SRC = Path(__file__).resolve().parents[2] / "src" / "urdfcheck"
DOORS = {"consumers/launch/expr.py", "load/xacro/safeeval.py"}
EVALUATED = {"BoolOp", "IfExp", "UnaryOp", "BinOp", "Compare"}
PROGRAM_READER = ("consumers/launch/python.py", "PyLaunch", "_ev")


def _outside_program_reader(rel, tree):
    """The nodes of `tree`, without the body of the Python launch program reader."""
    skip = set()
    if rel == PROGRAM_READER[0]:
        for cls in tree.body:
            if isinstance(cls, ast.ClassDef) and cls.name == PROGRAM_READER[1]:
                for fn in cls.body:
                    if isinstance(fn, ast.FunctionDef) and fn.name == PROGRAM_READER[2]:
                        skip |= {id(n) for n in ast.walk(fn)}
    return [n for n in ast.walk(tree) if id(n) not in skip]


def test_only_the_expression_doors_evaluate():
    found = []
    for path in sorted(SRC.rglob("*.py")):
        rel = path.relative_to(SRC).as_posix()
        if rel in DOORS:
            continue
        for node in _outside_program_reader(rel, ast.parse(path.read_text(encoding="utf-8"))):
            if isinstance(node, ast.Call) and isinstance(node.func, ast.Attribute) and node.func.attr == "parse" \
                    and any(k.arg == "mode" and getattr(k.value, "value", None) == "eval" for k in node.keywords):
                found.append(f"{rel}:{node.lineno} parses an expression")
            if isinstance(node, ast.Call) and getattr(node.func, "id", None) == "isinstance" and len(node.args) == 2:
                kinds = node.args[1].elts if isinstance(node.args[1], ast.Tuple) else [node.args[1]]
                for k in kinds:
                    if isinstance(k, ast.Attribute) and isinstance(k.value, ast.Name) and k.value.id == "ast" \
                            and k.attr in EVALUATED:
                        found.append(f"{rel}:{node.lineno} evaluates ast.{k.attr}")
    assert not found, found


ROSLAUNCH = dict(name={"sim": True, "robot": "ur5"}.get, typed=True)
PYTHON = dict(name={"true": True, "false": False}.get, conditional=True)


@pytest.mark.parametrize("text, kw, want", [
    ("'a' + 'b'", PYTHON, "ab"),
    ("'a' if true else 'b'", PYTHON, "a"),
    ("'a' if sim else 'b'", ROSLAUNCH, None),  # not in the roslaunch dialect
    ("sim and not sim", ROSLAUNCH, False),
    ("robot and sim", ROSLAUNCH, None),  # typed: booleans only
    ("'x' + 1", ROSLAUNCH, None),
    ("1 + 2", PYTHON, 3),
    ("__import__('os')", PYTHON, None),
    ("open('f')", ROSLAUNCH, None),
    ("'a' * 9", PYTHON, None),
    ("'" + "a" * 1500 + "' + '" + "a" * 1500 + "'", PYTHON, None),  # past MAX_TEXT
])
def test_the_dialects(text, kw, want):
    assert expr.evaluate(text, **kw) == want


def test_a_long_joined_string_is_refused_in_both_dialects():
    long = "a" * 3000
    assert expr.evaluate("x + x", name={"x": long}.get, typed=True) is None
    assert expr.evaluate("x + x", name={"x": long}.get) is None
