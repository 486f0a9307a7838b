"""`IncludeLaunchDescription(...)` in a ROS 2 Python launch file, read with `ast` (nothing is executed).

The file to include is usually built from a few well-known pieces, which are evaluated here and nowhere
else: string constants, `os.path.join`, `PathJoinSubstitution([...])`, a list of pieces (launch concatenates
them), `+`, f-strings, `get_package_share_directory('pkg')` / `FindPackageShare('pkg')`,
`ThisLaunchFileDir()`, `os.path.dirname(__file__)`, `LaunchConfiguration('x')` (through the caller's
`literal`) and module or function variables assigned once. Anything else leaves the include unresolved.
"""
from __future__ import annotations

import ast
import os
from collections.abc import Callable

from urdfcheck.contracts.common import as_bool
from urdfcheck.contracts.launchinfo import Include
from urdfcheck.contracts.launchinfo import callee as _callee
from urdfcheck.contracts.launchinfo import dotted as _dotted
from urdfcheck.core.findings import Location

_SOURCES = {"PythonLaunchDescriptionSource", "XMLLaunchDescriptionSource", "YAMLLaunchDescriptionSource",
            "AnyLaunchDescriptionSource", "FrontendLaunchDescriptionSource"}
_MAX_DEPTH = 20
_MAX_STEPS = 20_000  # node evaluations per file: variables built from each other must not explode
_MAX_LEN = 4096  # characters of one path or argument


class _Paths:
    def __init__(self, tree: ast.AST, path: str, literal: Callable, find_package: Callable[[str], str | None]):
        self.path = path
        self.literal = literal
        self.find_package = find_package
        self.names: dict[str, ast.AST | None] = {}  # None: assigned more than once
        self.known: dict[str, str | None] = {}  # variables evaluated so far
        self.steps = 0
        for n in ast.walk(tree):
            if isinstance(n, ast.Assign) and len(n.targets) == 1 and isinstance(n.targets[0], ast.Name):
                name = n.targets[0].id
                self.names[name] = None if name in self.names else n.value

    def text(self, node: ast.AST, depth: int = 0) -> str | None:
        """The string `node` evaluates to, or None."""
        self.steps += 1
        if depth > _MAX_DEPTH or self.steps > _MAX_STEPS:
            return None
        out = self._text(node, depth + 1)
        return out if out is None or len(out) <= _MAX_LEN else None

    def _text(self, node: ast.AST, d: int) -> str | None:
        if isinstance(node, ast.Constant):
            return node.value if isinstance(node.value, str) else None
        if isinstance(node, ast.Name):
            if node.id == "__file__":
                return os.path.abspath(self.path)
            if node.id not in self.known:
                value = self.names.get(node.id)
                self.known[node.id] = None  # while it is evaluated: a variable that refers to itself is unknown
                self.known[node.id] = self.text(value, d) if value is not None else None
            return self.known[node.id]
        if isinstance(node, (ast.List, ast.Tuple)):  # a substitution list: its pieces are concatenated
            return self._join("", node.elts, d)
        if isinstance(node, ast.BinOp) and isinstance(node.op, ast.Add):
            return self._join("", [node.left, node.right], d)
        if isinstance(node, ast.JoinedStr):
            return self._join("", [v.value if isinstance(v, ast.FormattedValue) else v for v in node.values], d)
        if not isinstance(node, ast.Call):
            return None
        name, full = _callee(node), _dotted(node.func)
        args = list(node.args) + [k.value for k in node.keywords if k.arg in ("package", "package_name")]
        if full in ("os.path.join", "join"):
            return self._join(os.sep, node.args, d)
        if name == "PathJoinSubstitution" and node.args and isinstance(node.args[0], (ast.List, ast.Tuple)):
            return self._join(os.sep, node.args[0].elts, d)
        if name in ("get_package_share_directory", "FindPackageShare"):
            pkg = self.text(args[0], d) if args else None
            return self.find_package(pkg) if pkg else None
        if name == "ThisLaunchFileDir" or full in ("os.path.dirname", "dirname"):
            if name == "ThisLaunchFileDir":
                return os.path.dirname(os.path.abspath(self.path))
            inner = self.text(node.args[0], d) if node.args else None
            return os.path.dirname(inner) if inner else None
        if name in _SOURCES:  # the description source names the file
            inner = {k.arg: k.value for k in node.keywords if k.arg}
            src = node.args[0] if node.args else inner.get("launch_file_path")
            return self.text(src, d) if src is not None else None
        if name == "LaunchConfiguration":
            value, ok = self.literal(node)
            return str(value) if ok and value is not None else None
        if name == "str" and len(node.args) == 1:
            return self.text(node.args[0], d)
        return None

    def _join(self, sep: str, parts, depth: int) -> str | None:
        texts, size = [], 0
        for p in parts:
            t = self.text(p, depth)
            if t is None:  # one unknown piece: the whole is unknown, evaluate no further
                return None
            size += len(t)
            if size > _MAX_LEN:  # too long for a path: stop before joining
                return None
            texts.append(t)
        if sep == "":
            return "".join(texts)
        return os.path.join(*texts) if texts else None


def _condition(call: ast.Call, literal: Callable) -> tuple[bool, str | None]:
    """(active?, undecided condition text) of a `condition=IfCondition(...)` keyword."""
    kw = {k.arg: k.value for k in call.keywords if k.arg}
    node = kw.get("condition")
    if node is None:
        return True, None
    if isinstance(node, ast.Call) and node.args and _callee(node) in ("IfCondition", "UnlessCondition"):
        value, ok = literal(node.args[0])
        b = as_bool(value) if ok else None
        if b is not None:
            return (b if _callee(node) == "IfCondition" else not b), None
    try:
        return True, f"condition={ast.unparse(node)[:120]}"
    except (RecursionError, ValueError):
        return True, "condition=?"


def _arguments(node: ast.AST | None, paths: _Paths) -> dict[str, str | None]:
    """`launch_arguments={...}.items()`, a dict, or a list of pairs."""
    if node is None:
        return {}
    if isinstance(node, ast.Call) and isinstance(node.func, ast.Attribute) and node.func.attr == "items":
        node = node.func.value
    pairs = []
    if isinstance(node, ast.Dict):
        pairs = [(k, v) for k, v in zip(node.keys, node.values) if k is not None]
    elif isinstance(node, (ast.List, ast.Tuple)):
        pairs = [tuple(e.elts) for e in node.elts if isinstance(e, (ast.Tuple, ast.List)) and len(e.elts) == 2]
    out = {}
    for k, v in pairs:
        key = paths.text(k)
        if key is None:
            continue
        if isinstance(v, ast.Constant) and isinstance(v.value, bool):
            out[key] = "true" if v.value else "false"
        elif isinstance(v, ast.Constant) and isinstance(v.value, (int, float)):
            out[key] = str(v.value)
        else:
            out[key] = paths.text(v)  # None: not literal
    return out


def find_includes(tree: ast.AST, path: str, literal: Callable, find_package: Callable[[str], str | None],
                  inherited: dict | None = None) -> list:
    """The includes of a Python launch file, as `launchinfo.Include` records, in source order. `inherited`: the
    launch configurations the including file knows, which ROS 2 passes on to every included file."""
    paths = _Paths(tree, path, literal, find_package)
    calls = sorted((n for n in ast.walk(tree) if isinstance(n, ast.Call) and _callee(n) == "IncludeLaunchDescription"),
                   key=lambda c: (c.lineno, c.col_offset))
    out = []
    for call in calls:
        active, cond = _condition(call, literal)
        if not active:
            continue
        kw = {k.arg: k.value for k in call.keywords if k.arg}
        source = call.args[0] if call.args else kw.get("launch_description_source")
        file = paths.text(source) if source is not None else None
        loc = Location(path, call.lineno, call.col_offset + 1)
        passed = {**(inherited or {}), **_arguments(kw.get("launch_arguments"), paths)}
        out.append(Include(file, loc, passed, cond))
    return out
