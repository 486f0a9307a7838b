"""The one static evaluator of launch-time expressions (issue 42): roslaunch's `$(eval ...)` (consumers.launch.xml)
and ROS 2's `PythonExpression` (consumers.launch.python). The text is parsed and its tree evaluated here, by one
allow-list of node kinds, never by Python: each copy of the allow-list was where a limit was added once and
missed once. What the two dialects do differently is a named parameter of `evaluate`, with its reason.
(xacro's `${...}` is a full Python subset with its own sandbox and budget: load.xacro.safeeval.)"""
from __future__ import annotations

from collections.abc import Callable

from urdfcheck.core.records import TYPE_CHECKING

if TYPE_CHECKING:
    from typing import Any

MAX_TEXT = 2000  # longer expressions are decided at launch time
MAX_DEPTH = 30
MAX_STR = 4096  # a joined string longer than this is not a file name or a flag
MAX_BOOL_VALUES = 16


def evaluate(text: str, *, name: Callable[[str], Any], call: Callable[[str, list], Any] | None = None,
             typed: bool = False, conditional: bool = False) -> Any:
    """The value of `text`, or None when it is not made only of literals and what the parameters allow.

    `name(id)`: the value of a bare name (None: unknown). `call(func, args)`: a call of a bare name with
    positional arguments (None: unknown); without it no call is evaluated.
    `typed`: roslaunch's `$(eval)` values come from arguments whose types were guessed, so `and`/`or`/`not` take
    booleans only (at most MAX_BOOL_VALUES), `==` compares values of one type, and `+` does not mix a string with
    a number or take a boolean; a PythonExpression's pieces are literals of the launch file, read as Python does.
    `conditional`: `x if c else y` (PythonExpression conditions use it; `$(eval)` is kept to what roslaunch files
    in the corpus write).
    """
    if len(text) > MAX_TEXT:
        return None
    import ast  # here: most launch files have no expression, and ast costs 5 ms to import

    try:
        tree = ast.parse(text.strip(), mode="eval")
    except (SyntaxError, ValueError, RecursionError, MemoryError):
        return None

    def ev(n, depth=0):
        if depth > MAX_DEPTH:
            raise ValueError
        if isinstance(n, ast.Expression):
            return ev(n.body, depth + 1)
        if isinstance(n, ast.Constant) and isinstance(n.value, (str, int, float, bool)):
            return n.value
        if isinstance(n, ast.Name):
            v = name(n.id)
            if v is None:
                raise ValueError
            return v
        if conditional and isinstance(n, ast.IfExp):
            return ev(n.body, depth + 1) if ev(n.test, depth + 1) else ev(n.orelse, depth + 1)
        if isinstance(n, ast.BoolOp) and (not typed or len(n.values) <= MAX_BOOL_VALUES):
            vals = [ev(x, depth + 1) for x in n.values]
            if typed and not all(isinstance(x, bool) for x in vals):
                raise ValueError
            return all(vals) if isinstance(n.op, ast.And) else any(vals)
        if isinstance(n, ast.UnaryOp) and isinstance(n.op, ast.Not):
            x = ev(n.operand, depth + 1)
            if typed and not isinstance(x, bool):
                raise ValueError
            return not x
        if isinstance(n, ast.Compare) and len(n.ops) == 1 and isinstance(n.ops[0], (ast.Eq, ast.NotEq)):
            a, b = ev(n.left, depth + 1), ev(n.comparators[0], depth + 1)
            if typed and type(a) is not type(b):
                raise ValueError
            return (a == b) if isinstance(n.ops[0], ast.Eq) else (a != b)
        if call is not None and isinstance(n, ast.Call) and isinstance(n.func, ast.Name) and not n.keywords:
            v = call(n.func.id, [ev(a, depth + 1) for a in n.args])
            if v is None:
                raise ValueError
            return v
        if isinstance(n, ast.BinOp) and isinstance(n.op, ast.Add):
            a, b = ev(n.left, depth + 1), ev(n.right, depth + 1)
            if typed:
                if isinstance(a, str) != isinstance(b, str) or isinstance(a, bool) or isinstance(b, bool):
                    raise ValueError
            elif type(a) is not type(b) or not isinstance(a, (str, int, float)):
                raise ValueError
            out = a + b
            if isinstance(out, str) and len(out) > MAX_STR:
                raise ValueError
            return out
        raise ValueError

    try:
        return ev(tree)
    except (ValueError, TypeError, RecursionError):
        return None
