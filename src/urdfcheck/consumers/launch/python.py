"""A ROS 2 Python launch file read for its deployment: which model robot_state_publisher gets, with which
xacro arguments, and the nodes around it. Read with `ast`; nothing is imported or executed.

Launch substitutions are evaluated for one set of launch arguments (`args`: what an including file or a
variant passes; the rest take their `DeclareLaunchArgument` defaults): string constants, f-strings, `+`,
`os.path.join`, `PathJoinSubstitution`, `FindPackageShare` / `get_package_share_directory` (through the
caller's `find_package`), `ThisLaunchFileDir`, `__file__`, `LaunchConfiguration` (and `.perform(context)`,
`context.launch_configurations[...]`), `TextSubstitution`, `FindExecutable`, `Command([...])`,
`ParameterValue(...)`, `xacro.process_file(path, mappings={...}).toxml()`, `open(path).read()` and variables
assigned once. A piece decided only at launch time (`os.getenv`, `EnvironmentVariable`, `PythonExpression`,
an argument without default) becomes `UNKNOWN` inside the string; the deployment finder matches such a
model path against the files that exist.
"""
from __future__ import annotations

import ast
import os
from collections.abc import Callable, Mapping

from urdfcheck.consumers.common import Value, as_bool
from urdfcheck.consumers.launch.info import (  # noqa: F401 - UNKNOWN, ModelRef, command_model: read here too
    _DESCRIPTION_WHY,
    UNKNOWN,
    Declared,
    Include,
    LaunchInfo,
    LaunchNode,
    ModelRef,
    command_model,
    record_node,
)
from urdfcheck.core.findings import Location
from urdfcheck.core.records import TYPE_CHECKING, TupleRecord

if TYPE_CHECKING:
    from typing import Any

_MAX_DEPTH = 40
_MAX_STEPS = 50_000
_MAX_LEN = 64 * 1024
# strings, lists and mappings the evaluation builds, in items, for the whole file: `[*a, *a]` doubling over
# names costs as much as a string that doubles (issue 19: a 25 kB file took 3.9 GB)
_MAX_ITEMS = 1_000_000


_SOURCES = {"PythonLaunchDescriptionSource", "XMLLaunchDescriptionSource", "YAMLLaunchDescriptionSource",
            "AnyLaunchDescriptionSource", "FrontendLaunchDescriptionSource"}


class Cmd(TupleRecord):
    """`Command([...])`: the command line robot_state_publisher's parameter gets the output of."""
    text: str


class XacroDoc(TupleRecord):
    """`xacro.process_file(path, mappings=...)` (and its `.toxml()`)."""
    path: str
    mappings: dict


class FileOpen(TupleRecord):
    path: str


class FileText(TupleRecord):
    """The text of a file (`open(path).read()`)."""
    path: str


class MoveItBuilder(TupleRecord):
    """`MoveItConfigsBuilder(robot_name, package_name=...)` and its `.robot_description(file_path, mappings)`."""
    robot_name: str
    package: str
    file_path: str | None
    mappings: dict


def _callee(call: ast.Call) -> str:
    """The called name of a Python launch file's call: `Node(...)` and `launch_ros.actions.Node(...)` -> Node."""
    f = call.func
    return f.id if isinstance(f, ast.Name) else f.attr if isinstance(f, ast.Attribute) else ""


def _dotted(node: ast.AST) -> str:
    """`a.b.c` of an attribute chain ("" parts where it is not plain names)."""
    parts = []
    while isinstance(node, ast.Attribute):
        parts.append(node.attr)
        node = node.value
    if isinstance(node, ast.Name):
        parts.append(node.id)
    return ".".join(reversed(parts))


_INDEXED = (ast.Assign, ast.AnnAssign, ast.AugAssign, ast.With, ast.AsyncWith, ast.For, ast.comprehension,
            ast.arguments)


def _edits(value: ast.AST | None, name: str) -> bool:
    """`name.replace(...)` / `name.strip()`: an edit of the text bound to `name`."""
    return isinstance(value, ast.Call) and isinstance(value.func, ast.Attribute) \
        and value.func.attr in ("replace", "strip") and isinstance(value.func.value, ast.Name) \
        and value.func.value.id == name


def _index(tree: ast.AST) -> dict:
    """Calls by callee name, and under "*" the nodes that bind names."""
    out: dict = {"*": [], "^": {}, "def": {}}
    for n in ast.walk(tree):
        if isinstance(n, ast.Call):
            out.setdefault(_callee(n), []).append(n)
        elif isinstance(n, _INDEXED):
            out["*"].append(n)
        if isinstance(n, ast.FunctionDef):  # BFS: an inner function is seen after its outer one and wins
            out["def"].setdefault(n.name, []).append(n)
            for inner in ast.walk(n):
                if inner is not n and isinstance(inner, ast.Call):
                    out["^"][id(inner)] = n
    return out


def text_of(v: Any) -> str:
    """A value as launch would turn it into text; unknown parts become UNKNOWN (so does a value whose text
    would exceed _MAX_LEN: lists that share sublists can describe huge texts in few lines)."""
    budget = [_MAX_LEN]
    try:
        return _text(v, budget, 0)
    except _TooLong:
        return UNKNOWN


class _TooLong(Exception):
    pass


def _text(v: Any, budget: list, depth: int) -> str:
    budget[0] -= 1
    if budget[0] < 0 or depth > _MAX_DEPTH:
        raise _TooLong
    if isinstance(v, str):
        budget[0] -= len(v)
        if budget[0] < 0:
            raise _TooLong
        return v
    if isinstance(v, bool):
        return "true" if v else "false"
    if isinstance(v, (int, float)):
        return str(v)
    if isinstance(v, list):
        return "".join(_text(x, budget, depth + 1) for x in v)
    return UNKNOWN


class PyLaunch:
    def __init__(self, path: str, tree: ast.AST, args: Mapping[str, str | None] | None,
                 find_package: Callable[[str], str | None]):
        self.path = path
        self.tree = tree
        self.overrides = dict(args or {})
        self.find_package = find_package
        self.assign: dict[str, ast.AST | None] = {}
        self.params: set[str] = set()  # names of function parameters (scopes are not tracked)
        self.declared_nodes: dict[str, tuple[ast.Call, Location]] = {}
        self.consulted: set[str] = set()
        self.steps = 0
        self.items = 0  # items of the strings, lists and mappings built so far (_MAX_ITEMS)
        self._values: dict[str, Any] = {}
        self._configs: dict[str, str] = {}
        self._busy: set[str] = set()
        idx = getattr(tree, "_uc_index", None)
        if idx is None:  # one walk per parsed file, however many argument sets it is read with
            idx = _index(tree)
            try:
                tree._uc_index = idx
            except AttributeError:
                pass
        self._calls = idx
        self.bindings: dict[str, Any] = {}  # a helper function's parameters while one of its calls is read
        for n in idx["*"]:
            if isinstance(n, ast.Assign):
                for t in n.targets:
                    self._bind(t, n.value)
            elif isinstance(n, ast.AnnAssign) and n.value is not None:
                self._bind(n.target, n.value)
            elif isinstance(n, ast.AugAssign) and isinstance(n.target, ast.Name):
                self.assign[n.target.id] = None
            elif isinstance(n, (ast.With, ast.AsyncWith)):
                for item in n.items:
                    if item.optional_vars is not None:
                        self._bind(item.optional_vars, item.context_expr)
            elif isinstance(n, (ast.For, ast.comprehension)):
                self._bind(n.target, None)
            elif isinstance(n, ast.arguments):  # a parameter is known only while a call is read (bindings)
                for a in n.args + n.kwonlyargs + n.posonlyargs:
                    self.params.add(a.arg)
        for c in self.calls("DeclareLaunchArgument"):
            kw = {k.arg: k.value for k in c.keywords if k.arg}
            name_node = c.args[0] if c.args else kw.get("name")
            if isinstance(name_node, ast.Constant) and isinstance(name_node.value, str):
                self.declared_nodes.setdefault(name_node.value, (c, self.loc(c)))

    def _bind(self, target: ast.AST, value: ast.AST | None) -> None:
        if isinstance(target, ast.Name):
            if target.id in self.assign and _edits(value, target.id):
                return  # `desc = desc.replace(...)`: the same document, its text edited (package:// -> file://)
            self.assign[target.id] = None if target.id in self.assign else value
        elif isinstance(target, (ast.Tuple, ast.List)):
            for e in target.elts:
                self._bind(e, None)

    def loc(self, node: ast.AST) -> Location:
        return Location(self.path, getattr(node, "lineno", None), (getattr(node, "col_offset", -1) + 1) or None)

    def calls(self, *names: str) -> list[ast.Call]:
        out = [c for name in names for c in self._calls.get(name, ())]
        out.sort(key=lambda c: (c.lineno, c.col_offset))
        return out

    # --- launch configurations --------------------------------------------------------------------
    def declared(self) -> dict[str, Declared]:
        out = {}
        for name, (c, loc) in self.declared_nodes.items():
            kw = {k.arg: k.value for k in c.keywords if k.arg}
            default = text_of(self.ev(kw["default_value"])) if "default_value" in kw else None
            choices = None
            if "choices" in kw:
                v = self.ev(kw["choices"])
                if isinstance(v, list) and v and all(isinstance(x, str) and UNKNOWN not in x for x in v):
                    choices = tuple(v)
            out[name] = Declared(default, choices, loc)
        return out

    def config(self, name: str, fallback: ast.AST | None = None) -> str:
        self.consulted.add(name)
        if name in self.overrides:
            v = self.overrides[name]
            return UNKNOWN if v is None else str(v)
        if name in self._configs:
            return self._configs[name]
        if name in self._busy:
            return UNKNOWN
        self._busy.add(name)
        try:
            value = UNKNOWN
            got = self.declared_nodes.get(name)
            kw = {k.arg: k.value for k in got[0].keywords if k.arg} if got else {}
            if "default_value" in kw:
                value = text_of(self.ev(kw["default_value"]))
            elif fallback is not None:
                value = text_of(self.ev(fallback))
        finally:
            self._busy.discard(name)
        self._configs[name] = value
        return value

    def configs(self) -> dict[str, str | None]:
        """Every configuration this file knows, as an included file would inherit them."""
        out = {k: (None if v is None else str(v)) for k, v in self.overrides.items()}
        for name in self.declared_nodes:
            if name not in out:
                v = self.config(name)
                out[name] = None if UNKNOWN in v else v
        return out

    # --- evaluation -------------------------------------------------------------------------------
    def ev(self, node: ast.AST | None, depth: int = 0) -> Any:
        """The value `node` evaluates to; None when unknown."""
        self.steps += 1
        if node is None or depth > _MAX_DEPTH or self.steps > _MAX_STEPS:
            return None
        out = self._ev(node, depth + 1)
        if isinstance(out, (str, list, dict)):
            if len(out) > _MAX_LEN:
                return None
            self.items += len(out)
            if self.items > _MAX_ITEMS:
                self.steps = _MAX_STEPS + 1  # the budget is spent: nothing more is evaluated
                return None
        return out

    def _ev(self, node: ast.AST, d: int) -> Any:
        if isinstance(node, ast.Constant):
            return node.value
        if isinstance(node, ast.Name):
            if node.id == "__file__":
                return os.path.abspath(self.path)
            if node.id in self.bindings:
                return self.bindings[node.id]
            if self.bindings:  # inside a helper call: names may depend on its parameters, no caching
                value = self.assign.get(node.id)
                return self.ev(value, d) if value is not None else None
            if node.id in self._values:
                return self._values[node.id]
            value = self.assign.get(node.id)
            self._values[node.id] = None  # while evaluated: a self-reference is unknown
            self._values[node.id] = self.ev(value, d) if value is not None else None
            return self._values[node.id]
        if isinstance(node, ast.JoinedStr):
            return "".join(text_of(self.ev(v.value, d)) if isinstance(v, ast.FormattedValue) else text_of(self.ev(v, d))
                           for v in node.values)
        if isinstance(node, (ast.List, ast.Tuple)):
            out = []
            for e in node.elts:
                if isinstance(e, ast.Starred):
                    v = self.ev(e.value, d)
                    out.extend(v if isinstance(v, list) else [None])
                else:
                    out.append(self.ev(e, d))
                if len(out) > _MAX_LEN:  # before it grows further
                    return None
            return out
        if isinstance(node, ast.Dict):
            out = {}
            for k, v in zip(node.keys, node.values):
                if k is None:
                    more = self.ev(v, d)
                    if isinstance(more, dict):
                        out.update(more)
                        if len(out) > _MAX_LEN:
                            return None
                    continue
                key = self.ev(k, d)
                if isinstance(key, str):
                    out[key] = self.ev(v, d)
            return out
        if isinstance(node, ast.IfExp):
            b = _truth(self.ev(node.test, d))
            return None if b is None else self.ev(node.body if b else node.orelse, d)
        if isinstance(node, ast.UnaryOp) and isinstance(node.op, ast.Not):
            b = _truth(self.ev(node.operand, d))
            return None if b is None else not b
        if isinstance(node, ast.BinOp) and isinstance(node.op, ast.Add):
            a, b = self.ev(node.left, d), self.ev(node.right, d)
            if isinstance(a, list) and isinstance(b, list):
                return a + b if len(a) + len(b) <= _MAX_LEN else None
            if isinstance(a, (int, float)) and isinstance(b, (int, float)) and not isinstance(a, bool):
                return a + b
            ta, tb = text_of(a), text_of(b)
            return ta + tb if len(ta) + len(tb) <= _MAX_LEN else None
        if isinstance(node, ast.Subscript):
            if _dotted(node.value).endswith("launch_configurations"):
                key = self.ev(node.slice, d)
                return self.config(key) if isinstance(key, str) else None
            base, key = self.ev(node.value, d), self.ev(node.slice, d)
            if isinstance(base, dict) and isinstance(key, str):
                return base.get(key)
            if isinstance(base, list) and isinstance(key, int) and -len(base) <= key < len(base):
                return base[key]
            return None
        if isinstance(node, ast.Call):
            return self._call(node, d)
        if isinstance(node, ast.Attribute) and node.attr == "robot_description":
            base = self.ev(node.value, d)
            if isinstance(base, MoveItBuilder):  # moveit_config.robot_description: {"robot_description": ...}
                root = self.find_package(base.package)
                rel = base.file_path or os.path.join("config", f"{base.robot_name}.urdf.xacro")
                path = os.path.join(root, rel) if root else UNKNOWN
                return {"robot_description": XacroDoc(path, base.mappings)}
        return None

    def _kw(self, call: ast.Call) -> dict[str, ast.AST]:
        return {k.arg: k.value for k in call.keywords if k.arg}

    def _arg(self, call: ast.Call, i: int, *names: str) -> ast.AST | None:
        if len(call.args) > i:
            return call.args[i]
        kw = self._kw(call)
        for n in names:
            if n in kw:
                return kw[n]
        return None

    def _call(self, node: ast.Call, d: int) -> Any:
        name, full = _callee(node), _dotted(node.func)
        attr_of = node.func.value if isinstance(node.func, ast.Attribute) else None
        if name == "LaunchConfiguration":
            key = self.ev(self._arg(node, 0, "variable_name"), d)
            if not isinstance(key, str):
                return None
            return self.config(key, self._kw(node).get("default"))
        if attr_of is not None and name in ("perform", "items", "toxml", "toprettyxml", "strip"):
            return self.ev(attr_of, d)
        if attr_of is not None and name == "get" and _dotted(attr_of).endswith("launch_configurations"):
            key = self.ev(self._arg(node, 0), d)
            return self.config(key) if isinstance(key, str) else None
        if attr_of is not None and name == "replace":  # a model's text edited: still that model
            base = self.ev(attr_of, d)
            return base if isinstance(base, (XacroDoc, FileText)) else None
        if attr_of is not None and name in ("read", "read_text"):
            base = self.ev(attr_of, d)
            if isinstance(base, FileOpen):
                return FileText(base.path)
            if name == "read_text" and isinstance(base, str):
                return FileText(base)
            return None
        if name == "FileContent":  # launch's FileContent(path): the file's text
            p = self.ev(self._arg(node, 0, "path"), d)
            return FileText(text_of(p)) if p is not None else None
        if name == "open" and not full.startswith("os."):
            p = self.ev(self._arg(node, 0, "file"), d)
            return FileOpen(text_of(p)) if p is not None else None
        if name in ("Path", "PurePath", "str", "TextSubstitution") and full.split(".")[0] not in ("os",):
            return self.ev(self._arg(node, 0, "text"), d)
        if full in ("os.path.join", "join", "path.join") or name == "PathJoinSubstitution":
            parts = node.args
            if name == "PathJoinSubstitution" and parts and isinstance(parts[0], (ast.List, ast.Tuple)):
                parts = parts[0].elts
            texts = [text_of(self.ev(p, d)) for p in parts]
            return os.path.join(*texts) if texts else None
        if name in ("FindPackageShare", "get_package_share_directory", "FindPackagePrefix", "get_package_prefix",
                    "get_package_share_path"):
            pkg = self.ev(self._arg(node, 0, "package", "package_name"), d)
            if not isinstance(pkg, str) or UNKNOWN in pkg:
                return None
            got = self.find_package(pkg)
            return got if got is not None else None
        if name in _SOURCES:  # a launch description source kept in a variable: the file it names
            return self.ev(self._arg(node, 0, "launch_file_path"), d)
        if name == "ThisLaunchFileDir":
            return os.path.dirname(os.path.abspath(self.path))
        if full in ("os.path.dirname", "dirname", "path.dirname", "os.path.abspath", "os.path.realpath"):
            inner = self.ev(self._arg(node, 0), d)
            if not isinstance(inner, str):
                return None
            return os.path.dirname(inner) if full.endswith("dirname") else inner
        if name == "FindExecutable":
            return self.ev(self._arg(node, 0, "name"), d)
        if name == "Command":
            parts = self.ev(self._arg(node, 0, "command"), d)
            return Cmd(text_of(parts))
        if name == "ParameterValue":
            return self.ev(self._arg(node, 0, "value"), d)
        if name in ("process_file",):
            p = self.ev(self._arg(node, 0, "input_file_name"), d)
            m = self.ev(self._kw(node).get("mappings"), d)
            mappings = {k: text_of(v) for k, v in m.items()} if isinstance(m, dict) else {}
            return XacroDoc(text_of(p), mappings)
        if name in ("ParameterFile",):
            return self.ev(self._arg(node, 0, "param_file"), d)
        if name == "find" and isinstance(attr_of, ast.Call) and _callee(attr_of) == "FindPackageShare":
            pkg = self.ev(self._arg(node, 0), d)
            return self.find_package(pkg) if isinstance(pkg, str) and UNKNOWN not in pkg else None
        if name in ("RewrittenYaml", "ReplaceString"):
            return self.ev(self._arg(node, 0, "source_file"), d)
        if name == "MoveItConfigsBuilder":
            robot = self.ev(self._arg(node, 0, "robot_name"), d)
            pkg = self.ev(self._kw(node).get("package_name"), d) if "package_name" in self._kw(node) else None
            if not isinstance(robot, str) or UNKNOWN in robot:
                return None
            return MoveItBuilder(robot, pkg if isinstance(pkg, str) else f"{robot}_moveit_config", None, {})
        if attr_of is not None and isinstance(attr_of, (ast.Call, ast.Name)):
            base = self.ev(attr_of, d)
            if isinstance(base, MoveItBuilder):  # the builder's other settings say nothing of the model
                if name != "robot_description":
                    return base
                fp = self.ev(self._arg(node, 0, "file_path"), d)
                m = self.ev(self._kw(node).get("mappings"), d)
                mappings = {k: text_of(v) for k, v in m.items()} if isinstance(m, dict) else {}
                return base._replace(file_path=fp if isinstance(fp, str) else None, mappings=mappings)
        if name == "PythonExpression":
            return _python_expression(text_of(self.ev(self._arg(node, 0, "expression"), d)))
        if name == "EnvironmentVariable" or full in ("os.getenv", "getenv", "os.environ.get", "environ.get"):
            # like xacro's $(optenv VAR default) in the sandbox: the default, never the runner's environment
            default = self._arg(node, 1, "default_value", "default")
            return self.ev(default, d) if default is not None else None
        if isinstance(node.func, ast.Name):  # a function of this launch file (`get_robot_description()`)
            return self._local_call(node, name, d)
        return None  # os.getenv, EnvironmentVariable, PythonExpression, anything else: decided at launch time

    def _local_call(self, node: ast.Call, name: str, d: int) -> Any:
        """What a function defined in this launch file returns, when it has one `return` and its parameters are
        given (or defaulted): read, never run."""
        defs = self._calls.get("def", {}).get(name, ())
        key = "\x00def " + name  # (beside the launch arguments being read)
        if len(defs) != 1 or key in self._busy:
            return None
        fd = defs[0]
        rets = [n for n in ast.walk(fd) if isinstance(n, ast.Return) and n.value is not None]
        if len(rets) != 1:
            return None
        params = [a.arg for a in fd.args.posonlyargs + fd.args.args]
        defaults = dict(zip(params[len(params) - len(fd.args.defaults):], fd.args.defaults))
        b = {}
        for p, arg in zip(params, node.args):
            b[p] = self.ev(arg, d)
        for k in node.keywords:
            if k.arg in params:
                b[k.arg] = self.ev(k.value, d)
        for p in params:
            if p not in b:
                if p not in defaults:
                    return None
                b[p] = self.ev(defaults[p], d)
        saved = self.bindings
        self._busy.add(key)
        try:
            if b:
                self.bindings = {**saved, **b}
            return self.ev(rets[0].value, d)
        finally:
            self.bindings = saved
            self._busy.discard(key)

    # --- conditions -------------------------------------------------------------------------------
    def condition(self, call: ast.Call) -> tuple[bool, str | None]:
        """(active?, undecided condition text) of a `condition=` keyword."""
        node = self._kw(call).get("condition")
        if node is None:
            return True, None
        if isinstance(node, ast.Call):
            kind = _callee(node)
            if kind in ("IfCondition", "UnlessCondition") and node.args:
                b = as_bool(text_of(self.ev(node.args[0])))
                if b is not None:
                    return (b if kind == "IfCondition" else not b), None
            if kind in ("LaunchConfigurationEquals", "LaunchConfigurationNotEquals") and len(node.args) >= 2:
                key, want = self.ev(node.args[0]), self.ev(node.args[1])
                if isinstance(key, str) and isinstance(want, str):
                    have = self.config(key)
                    if UNKNOWN not in have:
                        return (have == want) == (kind == "LaunchConfigurationEquals"), None
        try:
            return True, f"condition={ast.unparse(node)[:120]}"
        except (RecursionError, ValueError):
            return True, "condition=?"


def _truth(v: Any) -> bool | None:
    if isinstance(v, bool):
        return v
    if isinstance(v, (list, dict)):
        return bool(v)
    if isinstance(v, str) and UNKNOWN not in v:
        return as_bool(v) if as_bool(v) is not None else bool(v)
    return None


def helper_calls(r: PyLaunch, call: ast.Call) -> list[dict] | None:
    """When `call` sits in a local helper function that is called with literal arguments
    (`def controller_spawner(controllers, active=True): return Node(...)`), the parameter bindings of each
    call of the helper; None when `call` is not in such a helper."""
    fd = r._calls["^"].get(id(call))
    if fd is None:
        return None
    params = [a.arg for a in fd.args.posonlyargs + fd.args.args]
    sites = r.calls(fd.name)
    if not params or not sites:
        return None
    defaults = dict(zip(params[len(params) - len(fd.args.defaults):], fd.args.defaults))
    out = []
    for site in sites[:20]:
        b = {}
        for name, node in zip(params, site.args):
            b[name] = r.ev(node)
        for k in site.keywords:
            if k.arg in params:
                b[k.arg] = r.ev(k.value)
        for name in params:
            if name not in b and name in defaults:
                b[name] = r.ev(defaults[name])
        out.append(b)
    return out


def model_ref(value: Any, loc: Location) -> ModelRef | None:
    """The model behind a robot_description value, when it names one."""
    if isinstance(value, XacroDoc):
        return ModelRef(value.path, tuple(sorted(value.mappings.items())), "xacro", loc)
    if isinstance(value, FileText):
        return ModelRef(value.path, (), "file", loc)
    if isinstance(value, Cmd):
        return command_model(value.text, loc)
    return None


def node_values(r: PyLaunch, call: ast.Call) -> dict:
    """package, executable, name, namespace, arguments (list or None), params (name -> Value; a model ref
    for robot_description), param files."""
    kw = r._kw(call)

    def text(*names) -> str:
        for n in names:
            if n in kw:
                v = r.ev(kw[n])
                t = text_of(v)
                return "" if UNKNOWN in t else t
        return ""

    args: tuple | None = ()
    if "arguments" in kw:
        v = r.ev(kw["arguments"])
        # an unknown piece stays UNKNOWN in its token: a spawner's controller names are still literal
        args = tuple(text_of(x) for x in v) if isinstance(v, list) else None
    params: dict[str, Value] = {}
    files: list[str] = []
    plist = kw.get("parameters")
    elts = plist.elts if isinstance(plist, (ast.List, ast.Tuple)) else ([plist] if plist is not None else [])
    for el in elts:
        v = r.ev(el)
        if isinstance(v, dict):
            for k, val in _flatten(v):
                loc = r.loc(el)
                if k == "robot_description":
                    ref = model_ref(val, loc)
                    params[k] = Value(ref, loc)
                    if ref is None:
                        why = unread(r, el, call)
                        if why:
                            params[_DESCRIPTION_WHY] = Value(why, loc)
                    continue
                if isinstance(val, (str, int, float, bool)) and not (isinstance(val, str) and UNKNOWN in val):
                    params[k] = Value(val, loc)
                elif isinstance(val, list) and all(isinstance(x, (str, int, float, bool)) for x in val) \
                        and not any(isinstance(x, str) and UNKNOWN in x for x in val):
                    params[k] = Value(val, loc)
                else:
                    params[k] = Value(None, loc)
        elif isinstance(v, (str, list)):
            t = text_of(v)
            if UNKNOWN not in t and t:
                files.append(t)
    return {"package": text("package"), "executable": text("executable", "node_executable"),
            "name": text("name", "node_name"), "namespace": text("namespace", "node_namespace"),
            "args": args, "params": params, "files": tuple(files)}


# modules whose functions the reader evaluates itself (launch, launch_ros, xacro's API, paths)
_READ_MODULES = ("launch", "launch_ros", "xacro", "os", "pathlib", "ament_index_python", "typing")


def unread(r: PyLaunch, el: ast.AST, node: ast.Call) -> str:
    """The construct a robot_description value comes from that is not read (never run): a function of another
    module, a class method, a function of this file with several returns, an OpaqueFunction's arguments; ""
    when none of these."""
    imported: dict[str, str] = {}
    for n in ast.walk(r.tree):
        if isinstance(n, ast.ImportFrom) and n.module:
            for a in n.names:
                imported[a.asname or a.name] = n.module
        elif isinstance(n, ast.Import):
            for a in n.names:
                imported[(a.asname or a.name).split(".")[0]] = a.name
    defined = {n.name for n in ast.walk(r.tree) if isinstance(n, ast.ClassDef)}
    classes = {name: v.func.id for name, v in r.assign.items()  # instances of this file's classes
               if isinstance(v, ast.Call) and isinstance(v.func, ast.Name) and v.func.id in defined}
    seen: set[int] = set()
    queue, steps = [el], 0
    while queue and steps < 200:
        cur = queue.pop(0)
        steps += 1
        if id(cur) in seen:
            continue
        seen.add(id(cur))
        for sub in ast.walk(cur):
            if isinstance(sub, ast.Name) and r.assign.get(sub.id) is not None:
                queue.append(r.assign[sub.id])
            if not isinstance(sub, ast.Call):
                continue
            f = sub.func
            if isinstance(f, ast.Attribute) and isinstance(f.value, ast.Name) and f.value.id in ("self", "cls"):
                return f"it comes from `{f.value.id}.{f.attr}()`, a class method, which urdfcheck does not run"
            if isinstance(f, ast.Attribute) and isinstance(f.value, ast.Name) and f.value.id in classes:
                return f"it comes from `{f.value.id}.{f.attr}()`, a method of class {classes[f.value.id]} of this " \
                       "launch file, which urdfcheck does not run"
            head = _dotted(f).split(".")[0]
            module = imported.get(head)
            if module is not None and module.split(".")[0] not in _READ_MODULES:
                return f"it comes from `{_dotted(f)}()` of module {module}, which urdfcheck does not run"
            if isinstance(f, ast.Name):
                defs = r._calls.get("def", {}).get(f.id, ())
                if len(defs) == 1:
                    rets = [x.value for x in ast.walk(defs[0]) if isinstance(x, ast.Return) and x.value is not None]
                    if len(rets) > 1:
                        return f"it comes from `{f.id}()`, a function of this launch file with {len(rets)} returns, " \
                               "which urdfcheck does not run"
                    queue.extend(rets)
    fd = r._calls["^"].get(id(node))
    if fd is not None and any(_refers(c, fd.name) for c in r.calls("OpaqueFunction")):
        return f"it is computed inside OpaqueFunction({fd.name}) from what the launch passes it, which urdfcheck " \
               "does not run"
    return ""


def _refers(call: ast.Call, name: str) -> bool:
    return any(isinstance(n, ast.Name) and n.id == name for a in (*call.args, *(k.value for k in call.keywords))
               for n in ast.walk(a))


def _flatten(d: dict, prefix: str = ""):
    for k, v in d.items():
        if isinstance(v, dict):
            yield from _flatten(v, prefix + k + ".")
        else:
            yield prefix + k, v


def include_calls(r: PyLaunch, with_calls: bool = False) -> list[tuple]:
    """(file or None, location, arguments passed, undecided condition, package and base name of a file not
    known) per IncludeLaunchDescription; `with_calls`: and the call itself, last."""
    out = []
    inherited = r.configs()
    for call in r.calls("IncludeLaunchDescription"):
        active, cond = r.condition(call)
        if not active:
            continue
        kw = r._kw(call)
        source = call.args[0] if call.args else kw.get("launch_description_source")
        file, t = None, ""
        if isinstance(source, ast.Call):
            src = source.args[0] if source.args else r._kw(source).get("launch_file_path")
            t = text_of(r.ev(src))
            file = None if UNKNOWN in t or not t else t
        elif source is not None:
            t = text_of(r.ev(source))
            file = None if UNKNOWN in t or not t else t
        passed = dict(inherited)
        given = r.ev(kw.get("launch_arguments"))
        if isinstance(given, dict):
            items = given.items()
        elif isinstance(given, list):
            items = [tuple(p) for p in given if isinstance(p, list) and len(p) == 2]
        else:
            items = []
        for k, v in items:
            if isinstance(k, str):
                given_text = text_of(v)
                passed[k] = None if UNKNOWN in given_text else given_text
        out.append((file, r.loc(call), passed, cond, _named_package(r, source) if file is None else None,
                    os.path.basename(t.replace(UNKNOWN, "")) if file is None else "", *((call,) if with_calls else ())))
    return out


def _named_package(r: PyLaunch, source: ast.AST | None) -> str | None:
    """The package an include's path is found in (`FindPackageShare('realsense2_camera')`), when the path is not
    known because the package is not in the workspace: a known driver's launch file is still recognised."""
    if source is None:
        return None
    todo, seen = [source], 0
    while todo and seen < 200:
        n = todo.pop()
        seen += 1
        if isinstance(n, ast.Name) and isinstance(r.assign.get(n.id), ast.AST):
            todo.append(r.assign[n.id])
            continue
        if isinstance(n, ast.Call) and _callee(n) in ("FindPackageShare", "get_package_share_directory") and n.args:
            v = r.ev(n.args[0])
            if isinstance(v, str) and UNKNOWN not in v:
                return v
        todo.extend(ast.iter_child_nodes(n))
    return None


def inactive_include_files(path: str, tree: ast.AST, find_package) -> list[str]:
    """The files of the IncludeLaunchDescription calls whose condition is false with the defaults (an
    alternative the file may start: it is still not a launch file of its own)."""
    r = PyLaunch(path, tree, {}, find_package)
    out = []
    for call in r.calls("IncludeLaunchDescription"):
        active, _ = r.condition(call)
        if active:
            continue
        source = call.args[0] if call.args else r._kw(call).get("launch_description_source")
        if isinstance(source, ast.Call):
            source = source.args[0] if source.args else r._kw(source).get("launch_file_path")
        t = text_of(r.ev(source))
        if t and UNKNOWN not in t:
            out.append(t)
    return out


def namespaces(r: PyLaunch) -> dict[int, str]:
    """id(Node or IncludeLaunchDescription call) -> namespace pushed by an enclosing
    GroupAction([PushRosNamespace(...), ...])."""
    out: dict[int, str] = {}
    for g in r.calls("GroupAction"):
        acts = g.args[0] if g.args else r._kw(g).get("actions")
        acts_v = acts
        if isinstance(acts, ast.Name):
            acts_v = r.assign.get(acts.id)
        if not isinstance(acts_v, (ast.List, ast.Tuple)):
            continue
        ns = ""
        for a in acts_v.elts:
            if isinstance(a, ast.Call) and _callee(a) in ("PushRosNamespace", "PushROSNamespace"):
                t = text_of(r.ev(a.args[0] if a.args else r._kw(a).get("namespace")))
                ns = "?" if UNKNOWN in t else t.strip("/")
        if not ns:
            continue
        for n in ast.walk(acts_v):
            if isinstance(n, ast.Call) and _callee(n) in ("Node", "IncludeLaunchDescription"):
                out[id(n)] = "/" + "/".join(x for x in (ns, out.get(id(n), "").strip("/")) if x)
    return out


_NODE_CALLS = ("Node", "LifecycleNode")


def read(path: str, tree: ast.AST, args: Mapping[str, str | None] | None,
         find_package: Callable[[str], str | None]):
    """A `launch.LaunchInfo` of a Python launch file for one argument set (includes carry their arguments;
    robot_state_publishers carry their model)."""
    r = PyLaunch(path, tree, args, find_package)
    info = LaunchInfo(path, "ros2-py")
    info.declared = r.declared()
    pushed = namespaces(r)
    for call in r.calls(*_NODE_CALLS):
        for bindings in helper_calls(r, call) or [{}]:
            r.bindings = bindings
            try:
                _read_node(r, info, call, pushed)
            finally:
                r.bindings = {}
    for file, loc, passed, cond, package, name, call in include_calls(r, with_calls=True):
        info.includes.append(Include(file, loc, passed, cond, package, name,
                                     namespace=pushed.get(id(call), "").strip("/")))
    info.consulted = set(r.consulted)  # the launch arguments this reading depended on
    return info


def _read_node(r: PyLaunch, info, call: ast.Call, pushed: dict) -> None:
    active, cond = r.condition(call)
    if not active:
        return
    v = node_values(r, call)
    ns = v["namespace"]
    outer = pushed.get(id(call), "")
    ns = "/" + "/".join(x for x in (outer.strip("/"), ns.strip("/")) if x)
    if v["package"] == "robot_state_publisher" and "robot_description" not in v["params"] and v["args"]:
        first = v["args"][0]  # ROS 2 robot_state_publisher also takes the model file as its argument
        if first.endswith((".urdf", ".xacro")):
            how = "xacro" if first.endswith(".xacro") else "file"
            v["params"]["robot_description"] = Value(ModelRef(first, (), how, r.loc(call)), r.loc(call))
    node = LaunchNode(v["package"], v["executable"], v["name"], ns, v["args"], r.loc(call), v["params"],
                      v["files"], cond)
    record_node(info, node, 2)


def _python_expression(text: str) -> Any:
    """A PythonExpression whose pieces are all known, when it only uses literals, `+`, `==`/`!=`, `not`,
    `and`/`or` and `x if c else y` (evaluated by consumers.launch.expr, never by Python); otherwise None."""
    from urdfcheck.consumers.launch import expr as launch_expr

    if UNKNOWN in text:
        return None
    v = launch_expr.evaluate(text, name={"true": True, "false": False}.get, conditional=True)
    if v is None:
        return None
    return v if isinstance(v, str) else ("true" if v is True else "false" if v is False else str(v))
