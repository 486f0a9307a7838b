"""Allow-list evaluator for xacro's ``${...}`` and ``$(eval ...)`` expressions.

Stock xacro runs ``eval()`` with ``__builtins__`` emptied, which is no sandbox: lambdas, comprehensions,
``python.type``/``python.vars`` and ``'{0.__class__}'.format(x)`` all reach ``os.system``, and
``${10**10**8}`` never returns. Here the expression is parsed with :mod:`ast` and walked by a small
table-driven interpreter that

* accepts only the node types in ``_OK_NODES`` (no lambda, walrus, await/yield, no ``__`` names/attributes);
* performs every operation with the same Python operation eval would use (``operator.*``, real calls,
  real ``getattr``), so values, types and benign exceptions are those of ``eval``;
* calls only callables in the allow set (compared by identity) or allow-listed read-only methods of
  builtin data types, and never hands a non-allowed callable to an allowed one (``map(python.type, ..)``);
* refuses, before doing the work, operations whose cost explodes: huge ``**``/``<<``/``*``, long
  repetitions, ``str`` padding/format widths, more than ``max_iter`` iterations per evaluation, ...

Parity with stock xacro: every name and expression stock accepts is accepted, except these refusals for
safety (each one reaches code or memory stock would hand out):

* lambda, ``:=``, await/yield; ``python.type``/``python.vars`` (classes, ``__dict__``);
* names and attributes starting with ``__`` (stock refuses the same names, but not inside comprehensions or
  ``str.format`` fields); an attribute starting with one ``_`` only where it is a key of a mapping (a YAML
  key, a namespace's property), never a private attribute or method (``python._setitem``);
* ``str.format`` fields with ``.attr`` or ``[index]``; calls of anything outside the allow set; methods that grow a
  value in place (``list.append``/``extend``/``insert``, ``dict.update``/``setdefault``: sizes are charged once,
  when a value is made); shrinking ones (``pop``, ``remove``, ``clear``) and ``reverse`` are allowed;
* work beyond :class:`Limits` (huge ``**``, repetitions, widths, iterations).

A name with one leading underscore (``_origin_xyz``) is an ordinary name, as in stock xacro.

Anything refused raises :class:`Refused` (``expr`` + human ``reason``), which the sandbox reports as X011.
"""
from __future__ import annotations

import ast
import builtins
import math
import operator
import re
from functools import lru_cache
from types import BuiltinFunctionType, FunctionType, MethodType, ModuleType

from urdfcheck.core import lazyre
from urdfcheck.core.records import FrozenRecord

__all__ = ["Refused", "Limits", "Evaluator", "default_evaluator", "evaluate_substitution", "validate"]


class Refused(Exception):
    """The evaluator will not run this expression. ``reason`` names the construct."""

    def __init__(self, expr: str, reason: str):
        super().__init__(expr, reason)
        self.expr = expr
        self.reason = reason

    def __str__(self) -> str:
        shown = self.expr if len(self.expr) <= 120 else self.expr[:117] + "..."
        return f"{self.reason} (in expression {shown!r})"


class Limits(FrozenRecord):
    # max_bits: integer results (**, <<, *, factorial, ...)
    # max_len: items/characters of one sequence or string
    # max_iter: items iterated per evaluation (comprehensions, *args, consumers)
    # max_chars: expression text
    # max_depth: AST nesting
    # max_alloc: items created by repetition/concatenation per evaluation
    # max_total_iter: items iterated by all evaluations of one Evaluator (xacro: one expansion)
    _fields = ('max_bits', 'max_len', 'max_iter', 'max_chars', 'max_depth', 'max_alloc', 'max_total_iter')

    _defaults = {"max_bits": 100_000, "max_len": 10_000_000, "max_iter": 1_000_000, "max_chars": 100_000,
                 "max_depth": 100, "max_alloc": 50_000_000, "max_total_iter": None}


# --------------------------------------------------------------------------------------------------
# Static check (syntax allow-list)
# --------------------------------------------------------------------------------------------------

_OK_NODES = frozenset({
    ast.Expression, ast.Constant, ast.Name, ast.Attribute, ast.Subscript, ast.Slice, ast.Starred,
    ast.BinOp, ast.UnaryOp, ast.BoolOp, ast.Compare, ast.IfExp, ast.Call, ast.keyword,
    ast.Tuple, ast.List, ast.Set, ast.Dict, ast.ListComp, ast.SetComp, ast.DictComp, ast.GeneratorExp,
    ast.comprehension, ast.JoinedStr, ast.FormattedValue, ast.Load, ast.Store,
})
_NAMED_REFUSALS = {
    ast.Lambda: "lambda is not allowed",
    ast.NamedExpr: "assignment expression (:=) is not allowed",
    ast.Await: "await is not allowed",
    ast.Yield: "yield is not allowed",
    ast.YieldFrom: "yield is not allowed",
}
# python.type / python.vars hand out classes and __dict__s; refuse them already when spelled out
_DENIED_PYTHON = frozenset({"type", "vars"})
# a str.format field name may be a plain name or number, never ``.attr`` or ``[index]``
_PLAIN_FIELD = lazyre.compile(r"[^.\[]*")


def _is_plain_target(node) -> bool:
    if isinstance(node, ast.Name):
        return True
    if isinstance(node, ast.Starred):
        return _is_plain_target(node.value)
    if isinstance(node, (ast.Tuple, ast.List)):
        return all(_is_plain_target(e) for e in node.elts)
    return False


def _digits_reason(spec: str, limits: Limits) -> str | None:
    """Format specs with a width/precision above max_len would allocate that much."""
    for m in re.finditer(r"\d+", spec):
        d = m.group(0).lstrip("0")
        if len(d) > len(str(limits.max_len)) or (d and int(d) > limits.max_len):
            return f"format width or precision {m.group(0)[:12]} is too large"
    return None


def _format_reason(template: str, limits: Limits, level: int = 0) -> tuple[str | None, bool]:
    """(reason, has_nested_fields) for a str.format template."""
    import string  # a format template is rare: string's import (~0.4 ms) only then

    try:
        parsed = list(string.Formatter().parse(template))
    except ValueError:
        return None, False  # malformed: str.format raises the genuine ValueError itself
    nested = False
    for _literal, field, spec, _conv in parsed:
        if field is None:
            continue
        if not _PLAIN_FIELD.fullmatch(field):
            return f"format field '{{{field}}}' uses attribute or index access", nested
        if spec:
            if "{" in spec and level < 2:
                nested = True
                reason, _ = _format_reason(spec, limits, level + 1)
                if reason:
                    return reason, nested
            reason = _digits_reason(spec, limits)
            if reason:
                return reason, nested
    return None, nested


def _static_call_reason(node: ast.Call, limits: Limits) -> str | None:
    func = node.func
    if isinstance(func, ast.Attribute):
        if isinstance(func.value, ast.Name) and func.value.id == "python" and func.attr in _DENIED_PYTHON:
            return f"call of 'python.{func.attr}' is not allowed"
        if (func.attr in ("format", "format_map") and isinstance(func.value, ast.Constant)
                and isinstance(func.value.value, str)):
            return _format_reason(func.value.value, limits)[0]
    return None


def _static_reason(tree: ast.AST, limits: Limits) -> str | None:
    stack = [(tree, 0)]
    while stack:
        node, depth = stack.pop()
        if depth > limits.max_depth:
            return f"expression nested deeper than {limits.max_depth} levels"
        t = type(node)
        if t not in _OK_NODES and not isinstance(node, (ast.operator, ast.unaryop, ast.cmpop, ast.boolop)):
            return _NAMED_REFUSALS.get(t) or f"{t.__name__} is not allowed"
        if t is ast.Name:
            if node.id.startswith("__"):
                return f"name '{node.id}' is not allowed (names starting with '__' are reserved)"
        elif t is ast.Attribute:
            if node.attr.startswith("__"):
                return f"attribute '{node.attr}' is not allowed"
        elif t is ast.comprehension:
            if node.is_async:
                return "async comprehension is not allowed"
            if not _is_plain_target(node.target):
                return "comprehension targets must be names"
        elif t is ast.Call:
            reason = _static_call_reason(node, limits)
            if reason:
                return reason
        for child in ast.iter_child_nodes(node):
            stack.append((child, depth + 1 if isinstance(child, ast.expr) else depth))
    return None


def _compile(text: str, filename: str, limits: Limits) -> tuple[ast.Expression | None, str | None]:
    """Parse + static check. SyntaxError propagates exactly as compile() raises it."""
    if len(text) <= 2000:  # xacro evaluates the same short expressions over and over
        return _compile_cached(text, filename, limits)
    return _compile_uncached(text, filename, limits)


def _compile_uncached(text, filename, limits):
    if len(text) > limits.max_chars:
        return None, f"expression text longer than {limits.max_chars} characters"
    try:
        tree = ast.parse(text, filename, "eval")
    except (RecursionError, MemoryError):  # the C parser's own nesting limits
        return None, "expression nested too deeply"
    return tree, _static_reason(tree, limits)


_compile_cached = lru_cache(maxsize=8192)(_compile_uncached)  # exceptions are never cached


def validate(expr: str, limits: Limits | None = None) -> str | None:
    """Static check only: the reason the expression would be refused, or None.

    Raises SyntaxError for text that does not parse (that is a xacro error, not a refusal)."""
    return _compile(expr.strip(), "<expression>", limits or Limits())[1]


# --------------------------------------------------------------------------------------------------
# Allow-listed attributes/methods of builtin data types (read-only; looked up along the MRO, so
# YamlListWrapper gets list's and NameSpace/Table/YamlDictWrapper get dict's bound methods)
# --------------------------------------------------------------------------------------------------

_NUMBER = {"real", "imag", "conjugate"}
_METHODS: dict[type, frozenset[str]] = {
    str: frozenset({
        "capitalize", "casefold", "center", "count", "endswith", "expandtabs", "find", "format",
        "format_map", "index", "isalnum", "isalpha", "isascii", "isdecimal", "isdigit", "isidentifier",
        "islower", "isnumeric", "isprintable", "isspace", "istitle", "isupper", "join", "ljust", "lower",
        "lstrip", "partition", "removeprefix", "removesuffix", "replace", "rfind", "rindex", "rjust",
        "rpartition", "rsplit", "rstrip", "split", "splitlines", "startswith", "strip", "swapcase",
        "title", "upper", "zfill"}),
    bool: frozenset(_NUMBER | {"bit_length", "bit_count", "numerator", "denominator", "as_integer_ratio"}),
    int: frozenset(_NUMBER | {"bit_length", "bit_count", "numerator", "denominator", "as_integer_ratio"}),
    float: frozenset(_NUMBER | {"is_integer", "as_integer_ratio", "hex"}),
    complex: frozenset(_NUMBER),
    # mutators that only shrink or reorder a value (`${meshes.pop(0)}` in a recursive macro, as ar4 does): a size
    # charged before is still an upper bound. Growing ones (append, extend, insert, update, setdefault) are refused.
    list: frozenset({"index", "count", "copy", "pop", "remove", "reverse", "clear"}),
    tuple: frozenset({"index", "count"}),
    dict: frozenset({"get", "keys", "values", "items", "copy", "pop", "popitem", "clear"}),
    set: frozenset({"union", "intersection", "difference", "symmetric_difference", "issubset",
                    "issuperset", "isdisjoint", "copy"}),
    frozenset: frozenset({"union", "intersection", "difference", "symmetric_difference", "issubset",
                          "issuperset", "isdisjoint", "copy"}),
    range: frozenset({"start", "stop", "step", "index", "count"}),
    slice: frozenset({"start", "stop", "step"}),
    type(None): frozenset(),
}


def _method_names(cls: type) -> frozenset[str] | None:
    for base in cls.__mro__:
        names = _METHODS.get(base)
        if names is not None:
            return names
    return None


def _describe(fn) -> str:
    if isinstance(fn, BuiltinFunctionType) and not isinstance(fn.__self__, (ModuleType, type(None))):
        owner = fn.__self__
        cls = owner if isinstance(owner, type) else type(owner)
        return f"{cls.__name__}.{fn.__name__}"
    if isinstance(fn, (FunctionType, BuiltinFunctionType, type, MethodType)):
        return fn.__qualname__
    return f"{type(fn).__name__} object"


_SIZED = (str, bytes, list, tuple, dict, set, frozenset, range)
_NESTED = (list, tuple, dict, set, frozenset)  # containers whose items may be containers
_SEQ = (str, bytes, list, tuple)


def _range_len(r: range) -> int:
    try:
        return len(r)
    except OverflowError:
        return 1 << 64


def _weight(v) -> int:
    """Work units of one C-level pass over `v` (Limits.max_total_iter): 1 per 64 items/characters or 1024 bits.
    Zero for every value a real model uses; what makes a loop over big operands add up."""
    if type(v) is int:
        return v.bit_length() >> 10
    if isinstance(v, (str, bytes, list, tuple, dict, set, frozenset)):
        return len(v) >> 6
    return 0


def _int_work(values) -> int:
    """Big-integer multiplication/division is quadratic in the operands' sizes."""
    w = sorted((_weight(v) for v in values if type(v) is int), reverse=True)
    if len(w) < 2 or not w[0]:
        return 0
    return 4 * (w[0] + 1) * (w[1] + 1)


# --------------------------------------------------------------------------------------------------
# Guards: run before the real operation; may refuse, may return replaced (materialised) arguments
# --------------------------------------------------------------------------------------------------

def _log2_factorial(n: int) -> float:
    return math.lgamma(n + 1) / math.log(2) if n < 1e300 else math.inf


def _g_factorial(run, args, kwargs):
    if args and isinstance(args[0], int) and args[0] > 20 and _log2_factorial(args[0]) > run.limits.max_bits:
        run.refuse("factorial argument too large")
    return args


def _g_comb_perm(name):
    def guard(run, args, kwargs):
        if len(args) >= 1 and all(isinstance(a, int) for a in args[:2]):
            n = args[0]
            k = args[1] if len(args) > 1 and args[1] is not None else n
            if 0 <= k <= n and n > 20:
                small = min(k, n - k) if name == "comb" else k
                if small * math.log2(n) > run.limits.max_bits:
                    bits = _log2_factorial(n) - _log2_factorial(n - k)
                    if name == "comb":
                        bits -= _log2_factorial(k)
                    if bits > run.limits.max_bits:
                        run.refuse(f"{name} arguments too large")
        return args
    return guard


def _int_bits(values) -> int:
    return sum(v.bit_length() for v in values if isinstance(v, int))


def _g_prod(run, args, kwargs):
    if not args:
        return args
    items = list(run.iterate(args[0]))
    if _int_bits(items + [kwargs.get("start", 1)]) > run.limits.max_bits:
        run.refuse("math.prod result too large")
    return [items, *args[1:]]


def _g_lcm(run, args, kwargs):
    if _int_bits(args) > run.limits.max_bits:
        run.refuse("math.lcm result too large")
    return args


def _g_sum(run, args, kwargs):
    # sum() of lists/tuples concatenates quadratically: bound the total length first
    if not args:
        return args
    items = list(run.iterate(args[0]))
    start = args[1] if len(args) > 1 else kwargs.get("start", 0)
    if sum(len(v) for v in items + [start] if isinstance(v, _SEQ)) > run.limits.max_len:
        run.refuse(f"sum result longer than {run.limits.max_len} items")
    return [items, *args[1:]]


def _g_round(run, args, kwargs):
    # round(int, -n) computes 10**n
    if len(args) >= 2 or "ndigits" in kwargs:
        nd = args[1] if len(args) >= 2 else kwargs["ndigits"]
        if isinstance(args[0] if args else None, int) and isinstance(nd, int) and -nd * 3.33 > run.limits.max_bits:
            run.refuse("round() ndigits too large")
    return args


def _g_tokenize(run, args, kwargs):
    # xacro.tokenize builds re.split('[' + sep + ']'): a ']' or '\\' in sep escapes the character class
    # and makes an arbitrary (possibly catastrophically backtracking) regular expression
    sep = args[1] if len(args) > 1 else kwargs.get("sep")
    if isinstance(sep, str) and ("]" in sep or "\\" in sep):
        run.refuse("tokenize separator containing ']' or '\\' is not allowed")
    return args


def _m_width(run, s, args, kwargs):
    width = args[0] if args else kwargs.get("width")
    if isinstance(width, int) and width > run.limits.max_len:
        run.refuse(f"width {width} is too large")
    return args


def _m_expandtabs(run, s, args, kwargs):
    size = args[0] if args else kwargs.get("tabsize", 8)
    if isinstance(size, int) and len(s) + s.count("\t") * max(size, 0) > run.limits.max_len:
        run.refuse("expandtabs result too long")
    return args


def _m_replace(run, s, args, kwargs):
    if len(args) >= 2 and isinstance(args[0], str) and isinstance(args[1], str):
        old, new = args[0], args[1]
        count = args[2] if len(args) > 2 else kwargs.get("count", -1)
        n = len(s) + 1 if old == "" else s.count(old)
        if isinstance(count, int) and count >= 0:
            n = min(n, count)
        if len(s) + n * (len(new) - len(old)) > run.limits.max_len:
            run.refuse("str.replace result too long")
    return args


def _m_join(run, sep, args, kwargs):
    if len(args) != 1 or kwargs:
        return args
    items = list(run.iterate(args[0]))  # join materialises its argument anyway
    total = sum(len(i) for i in items if isinstance(i, str)) + len(sep) * max(len(items) - 1, 0)
    if total > run.limits.max_len:
        run.refuse("str.join result too long")
    return [items]


def _m_format(run, template, args, kwargs):
    reason, nested = _format_reason(template, run.limits)
    if reason:
        run.refuse(reason)
    if nested:  # a width taken from an argument: bound the integers, and the widths spelt in strings ('>999999999')
        for v in list(args) + list(kwargs.values()):
            if ((isinstance(v, int) and v > run.limits.max_len)
                    or (isinstance(v, str) and _digits_reason(v, run.limits))):
                run.refuse("format width taken from an argument is too large")
    return args


def _m_format_map(run, template, args, kwargs):
    reason, nested = _format_reason(template, run.limits)
    if reason:
        run.refuse(reason)
    if nested:
        run.refuse("nested replacement fields in a format_map spec are not allowed")
    return args


_METHOD_GUARDS = {
    (str, "center"): _m_width, (str, "ljust"): _m_width, (str, "rjust"): _m_width, (str, "zfill"): _m_width,
    (str, "expandtabs"): _m_expandtabs, (str, "replace"): _m_replace, (str, "join"): _m_join,
    (str, "format"): _m_format, (str, "format_map"): _m_format_map,
}

# printf-style conversion: (width, precision) may be digits or '*'
_PRINTF = lazyre.compile(r"%(?:\([^)]*\))?[-#0 +]*(\*|\d+)?(?:\.(\*|\d+))?")


def _guard_binop(run, op, a, b):
    lim = run.limits
    if op is ast.Pow:
        if isinstance(a, int) and isinstance(b, int) and b > 0 and abs(a) > 1:
            if b * math.log2(abs(a)) > lim.max_bits:
                run.refuse(f"exponent too large (result would exceed {lim.max_bits} bits)")
    elif op is ast.LShift:
        if isinstance(a, int) and isinstance(b, int) and a and b > 0 and a.bit_length() + b > lim.max_bits:
            run.refuse(f"shift too large (result would exceed {lim.max_bits} bits)")
    elif op is ast.Mult:
        if isinstance(a, int) and isinstance(b, int):
            if a.bit_length() + b.bit_length() > lim.max_bits:
                run.refuse(f"integer product too large (more than {lim.max_bits} bits)")
        else:
            seq, n = (a, b) if isinstance(b, int) else (b, a)
            if isinstance(n, int) and isinstance(seq, _SEQ) and n > 0:
                total = len(seq) * n
                if total > lim.max_len:
                    run.refuse(f"repetition result longer than {lim.max_len} items")
                run.alloc(total)
    elif op is ast.Add:
        if isinstance(a, _SEQ) and isinstance(b, _SEQ):
            total = len(a) + len(b)
            if total > lim.max_len:
                run.refuse(f"concatenation result longer than {lim.max_len} items")
            run.alloc(total)
    elif op is ast.Mod and isinstance(a, (str, bytes)):
        text = a if isinstance(a, str) else a.decode("latin-1")
        star = False
        for m in _PRINTF.finditer(text):
            for g in m.groups():
                if g == "*":
                    star = True
                elif g and _digits_reason(g, lim):
                    run.refuse(_digits_reason(g, lim))
        if star:
            values = b if isinstance(b, tuple) else (b,)
            if any(isinstance(v, int) and v > lim.max_len for v in values):
                run.refuse("'*' width or precision is too large")


# --------------------------------------------------------------------------------------------------
# The walker
# --------------------------------------------------------------------------------------------------

_BINOPS = {
    ast.Add: operator.add, ast.Sub: operator.sub, ast.Mult: operator.mul, ast.MatMult: operator.matmul,
    ast.Div: operator.truediv, ast.FloorDiv: operator.floordiv, ast.Mod: operator.mod, ast.Pow: operator.pow,
    ast.LShift: operator.lshift, ast.RShift: operator.rshift, ast.BitOr: operator.or_,
    ast.BitXor: operator.xor, ast.BitAnd: operator.and_,
}
_GUARDED_BINOPS = frozenset({ast.Pow, ast.LShift, ast.Mult, ast.Add, ast.Mod})
_QUADRATIC = frozenset({ast.Pow, ast.Mult, ast.FloorDiv, ast.Mod, ast.Div})
_DIVISIONS = frozenset({ast.FloorDiv, ast.Mod, ast.Div})
_UNARY = {ast.UAdd: operator.pos, ast.USub: operator.neg, ast.Not: operator.not_, ast.Invert: operator.invert}
_CMPOPS = {
    ast.Eq: operator.eq, ast.NotEq: operator.ne, ast.Lt: operator.lt, ast.LtE: operator.le,
    ast.Gt: operator.gt, ast.GtE: operator.ge, ast.Is: operator.is_, ast.IsNot: operator.is_not,
    ast.In: lambda a, b: operator.contains(b, a),
    ast.NotIn: lambda a, b: not operator.contains(b, a),
}
_CONVERSIONS = {115: str, 114: repr, 97: ascii}


class _Scope:
    """A comprehension scope: its own loop variables, chained to the enclosing comprehension (closure
    semantics: the dict is shared, so a lazy inner generator sees the outer variable's latest value)."""

    __slots__ = ("names", "values", "parent")

    def __init__(self, names, parent):
        self.names = names
        self.values = {}
        self.parent = parent


def _target_names(node, out: set) -> set:
    if isinstance(node, ast.Name):
        out.add(node.id)
    elif isinstance(node, ast.Starred):
        _target_names(node.value, out)
    else:
        for e in node.elts:
            _target_names(e, out)
    return out


class _Run:
    """State of one evaluation: budgets and name resolution. Generators it creates keep it alive, so a
    generator consumed later still charges (and is refused by) the evaluation that built it."""

    __slots__ = ("evaluator", "expr", "limits", "top", "glob", "extra", "iters", "allocated")

    def __init__(self, evaluator, expr, top, glob, extra=None):
        self.evaluator = evaluator
        self.expr = expr
        self.limits = evaluator.limits
        self.top = top  # name lookup at the top level
        self.glob = glob  # name lookup inside comprehensions (globals)
        self.extra = extra or {}
        self.iters = 0
        self.allocated = 0

    def refuse(self, reason):
        raise Refused(self.expr, reason)

    def tick(self, n=1):
        self.iters += n
        if self.iters > self.limits.max_iter:
            self.refuse(f"iteration over more than {self.limits.max_iter} items")
        total = self.limits.max_total_iter
        if total is not None and self.iters + self.evaluator.spent > total:  # many cheap-looking expressions
            self.refuse(f"expressions iterated over more than {self.limits.max_total_iter} items in total")

    def spend(self, units):
        """Charge work that is not iteration (big operands) to the evaluator-wide budget, when there is one."""
        if units and self.limits.max_total_iter is not None:
            self.tick(units)

    def alloc(self, n):
        self.allocated += n
        if self.allocated > self.limits.max_alloc:
            self.refuse(f"expression creates more than {self.limits.max_alloc} items in total")

    def iterate(self, value):
        """iter(value), charging the iteration budget (up front when the size is known)."""
        if isinstance(value, range):
            self.tick(_range_len(value))
            return iter(value)
        if isinstance(value, _SIZED):
            self.tick(len(value))
            return iter(value)
        return self._counted(iter(value))

    def _counted(self, it):
        for item in it:
            self.tick()
            yield item

    def check(self, value):
        lim = self.limits
        if isinstance(value, int):
            if value.bit_length() > lim.max_bits:
                self.refuse(f"integer result larger than {lim.max_bits} bits")
        elif isinstance(value, _SIZED) and not isinstance(value, range):
            if len(value) > lim.max_len:
                self.refuse(f"result longer than {lim.max_len} items")
            if isinstance(value, _NESTED) and self.evaluator._nested_size(self, value) > lim.max_len:
                # [[0]*10000]*3000 costs 13 000 items of memory and 30 million in every repr, comparison, hash or
                # error message ("... is not in list") that walks it
                self.refuse(f"result holds more than {lim.max_len} items and characters when nested values are "
                            "counted each time they occur")
        return value

    def ev(self, node, scope):
        return _HANDLERS[node.__class__](self, node, scope)

    # ---- names -----------------------------------------------------------------------------------
    def lookup(self, name, scope):
        s = scope
        while s is not None:
            if name in s.names:
                try:
                    return s.values[name]
                except KeyError:
                    if s is scope:
                        raise UnboundLocalError(
                            f"cannot access local variable '{name}' where it is not associated with a value"
                        ) from None
                    raise NameError(f"cannot access free variable '{name}' where it is not associated with "
                                    "a value in enclosing scope", name=name) from None
            s = s.parent
        return (self.top if scope is None else self.glob)(name)

    def assign(self, target, value, values):
        if isinstance(target, ast.Name):
            values[target.id] = value
            return
        elts = target.elts
        stars = [i for i, e in enumerate(elts) if isinstance(e, ast.Starred)]
        try:
            it = self.iterate(value)
        except TypeError:
            raise TypeError(f"cannot unpack non-iterable {type(value).__name__} object") from None
        items = list(it)
        if not stars:
            if len(items) < len(elts):
                raise ValueError(f"not enough values to unpack (expected {len(elts)}, got {len(items)})")
            if len(items) > len(elts):
                raise ValueError(f"too many values to unpack (expected {len(elts)})")
            for e, v in zip(elts, items):
                self.assign(e, v, values)
            return
        i = stars[0]
        after = len(elts) - i - 1
        if len(items) < len(elts) - 1:
            raise ValueError(f"not enough values to unpack (expected at least {len(elts) - 1}, got {len(items)})")
        for e, v in zip(elts[:i], items[:i]):
            self.assign(e, v, values)
        self.assign(elts[i].value, items[i:len(items) - after], values)
        for e, v in zip(elts[i + 1:], items[len(items) - after:]):
            self.assign(e, v, values)

    # ---- comprehensions --------------------------------------------------------------------------
    def loop(self, gens, local, first_iter):
        """Yield once per binding of the comprehension's loop variables that passes all conditions."""
        def rec(i, it):
            gen = gens[i]
            for item in it:  # `it` comes from iterate(): already charged to the budget
                self.assign(gen.target, item, local.values)
                if all(self.ev(cond, local) for cond in gen.ifs):
                    if i + 1 < len(gens):
                        yield from rec(i + 1, self.iterate(self.ev(gens[i + 1].iter, local)))
                    else:
                        yield
        return rec(0, first_iter)

    def comprehension(self, node, scope):
        # the first iterable is evaluated in the enclosing scope, eagerly (as Python does)
        first = self.iterate(self.ev(node.generators[0].iter, scope))
        names = set()
        for g in node.generators:
            _target_names(g.target, names)
        return _Scope(frozenset(names), scope), first


# ---- handlers: (run, node, scope) -> value --------------------------------------------------------

def _h_constant(run, node, scope):
    return node.value


def _h_name(run, node, scope):
    return run.lookup(node.id, scope)


def _h_attribute(run, node, scope):
    return run.evaluator._getattr(run, run.ev(node.value, scope), node.attr)


def _h_subscript(run, node, scope):
    value = run.ev(node.value, scope)
    result = run.check(operator.getitem(value, run.ev(node.slice, scope)))
    run.spend(_weight(result))  # a slice copies
    return result


def _h_slice(run, node, scope):
    return slice(*(None if p is None else run.ev(p, scope) for p in (node.lower, node.upper, node.step)))


def _h_binop(run, node, scope):
    a = run.ev(node.left, scope)
    b = run.ev(node.right, scope)
    op = node.op.__class__
    if op in _GUARDED_BINOPS:
        _guard_binop(run, op, a, b)
    run.spend(_weight(a) + _weight(b))
    result = run.check(_BINOPS[op](a, b))
    if op in _QUADRATIC:  # charged after the fact: at most one such operation overshoots the budget
        run.spend(_int_work((a, b, result) if op in _DIVISIONS else (result, result)))
    return result


def _h_unaryop(run, node, scope):
    return _UNARY[node.op.__class__](run.ev(node.operand, scope))


def _h_boolop(run, node, scope):
    is_and = isinstance(node.op, ast.And)
    for v in node.values:
        result = run.ev(v, scope)
        if (not result) if is_and else result:
            return result
    return result


def _h_compare(run, node, scope):
    left = run.ev(node.left, scope)
    last = len(node.ops) - 1
    for i, (op, comp) in enumerate(zip(node.ops, node.comparators)):
        right = run.ev(comp, scope)
        if isinstance(op, (ast.In, ast.NotIn)) and isinstance(right, range) and type(left) not in (int, bool):
            run.tick(_range_len(right))  # non-int membership in a range is a linear scan
        run.spend(_weight(left) + _weight(right))
        result = _CMPOPS[op.__class__](left, right)
        if i < last and not result:
            return result
        left = right
    return result


def _h_ifexp(run, node, scope):
    return run.ev(node.body if run.ev(node.test, scope) else node.orelse, scope)


def _elements(run, elts, scope):
    out = []
    for e in elts:
        if isinstance(e, ast.Starred):
            out.extend(run.iterate(run.ev(e.value, scope)))
        else:
            out.append(run.ev(e, scope))
    return out


def _h_tuple(run, node, scope):
    return run.check(tuple(_elements(run, node.elts, scope)))


def _h_list(run, node, scope):
    return run.check(_elements(run, node.elts, scope))


def _h_set(run, node, scope):
    out = set()
    for e in node.elts:
        if isinstance(e, ast.Starred):
            out.update(run.iterate(run.ev(e.value, scope)))
        else:
            out.add(run.ev(e, scope))
    return run.check(out)


def _h_dict(run, node, scope):
    out = {}
    for k, v in zip(node.keys, node.values):
        if k is None:
            m = run.ev(v, scope)
            run.tick(len(m) if isinstance(m, dict) else 0)
            out.update({**m})  # {**m} raises Python's own "not a mapping" TypeError
        else:
            key = run.ev(k, scope)
            out[key] = run.ev(v, scope)
    return run.check(out)


def _h_call(run, node, scope):
    fn = run.ev(node.func, scope)
    args = _elements(run, node.args, scope)
    kwargs = {}
    for kw in node.keywords:
        if kw.arg is None:
            m = run.ev(kw.value, scope)
            if not hasattr(type(m), "keys"):
                raise TypeError(f"argument after ** must be a mapping, not {type(m).__name__}")
            for key, value in {**m}.items():
                if key in kwargs:
                    raise TypeError(f"got multiple values for keyword argument '{key}'")
                kwargs[key] = value
        else:
            if kw.arg in kwargs:
                raise TypeError(f"got multiple values for keyword argument '{kw.arg}'")
            kwargs[kw.arg] = run.ev(kw.value, scope)
    return run.evaluator._invoke(run, fn, args, kwargs)


def _h_listcomp(run, node, scope):
    local, first = run.comprehension(node, scope)
    return run.check([run.ev(node.elt, local) for _ in run.loop(node.generators, local, first)])


def _h_setcomp(run, node, scope):
    local, first = run.comprehension(node, scope)
    return run.check({run.ev(node.elt, local) for _ in run.loop(node.generators, local, first)})


def _h_dictcomp(run, node, scope):
    local, first = run.comprehension(node, scope)
    out = {}
    for _ in run.loop(node.generators, local, first):
        key = run.ev(node.key, local)
        out[key] = run.ev(node.value, local)
    return run.check(out)


def _h_genexp(run, node, scope):
    local, first = run.comprehension(node, scope)

    def gen():  # lazy like Python's genexpr: any()/all() short-circuit, errors surface when consumed
        for _ in run.loop(node.generators, local, first):
            yield run.ev(node.elt, local)

    gen.__name__ = gen.__qualname__ = "<genexpr>"
    return gen()


def _h_joinedstr(run, node, scope):
    parts = [v.value if isinstance(v, ast.Constant) else run.ev(v, scope) for v in node.values]
    if sum(len(p) for p in parts) > run.limits.max_len:
        run.refuse(f"f-string result longer than {run.limits.max_len} characters")
    return "".join(parts)


def _h_formatted(run, node, scope):
    value = run.ev(node.value, scope)
    if node.conversion in _CONVERSIONS:
        value = _CONVERSIONS[node.conversion](value)
    spec = "" if node.format_spec is None else run.ev(node.format_spec, scope)
    reason = _digits_reason(spec, run.limits) if spec else None
    if reason:
        run.refuse(reason)
    return format(value, spec)


def _h_starred(run, node, scope):  # only reachable in a bad position; Python raises at compile time
    run.refuse("starred expression is not allowed here")


_HANDLERS = {
    ast.Constant: _h_constant, ast.Name: _h_name, ast.Attribute: _h_attribute, ast.Subscript: _h_subscript,
    ast.Slice: _h_slice, ast.BinOp: _h_binop, ast.UnaryOp: _h_unaryop, ast.BoolOp: _h_boolop,
    ast.Compare: _h_compare, ast.IfExp: _h_ifexp, ast.Tuple: _h_tuple, ast.List: _h_list, ast.Set: _h_set,
    ast.Dict: _h_dict, ast.Call: _h_call, ast.ListComp: _h_listcomp, ast.SetComp: _h_setcomp,
    ast.DictComp: _h_dictcomp, ast.GeneratorExp: _h_genexp, ast.JoinedStr: _h_joinedstr,
    ast.FormattedValue: _h_formatted, ast.Starred: _h_starred,
}

# builtins that neither iterate nor call their arguments (at most a C-level __str__/__index__/...
# of the argument's type): no iteration charge, and str(python.type) or isinstance(x, t) stay legal
_CHEAP = frozenset(id(f) for f in (len, str, repr, bool, hash, isinstance, issubclass, int, float, complex,
                                  abs, round, ord))


class Passed:
    """A callable that leaves the evaluator as a value: an argument of a call (``map(s.format, xs)``,
    ``sorted(xs, key=math.factorial)``) or the value of an expression. Calling it, from C code or anywhere,
    is a call through the evaluator that made it: the allow-list, the screening of its own arguments,
    the cost guards (str.format fields and widths, ljust, join, factorial, tokenize, ...) and the
    evaluation's budget all apply on every call. It exposes nothing of the callable it holds."""

    __slots__ = ("_fn", "_run")

    def __init__(self, fn, run):
        self._fn = fn
        self._run = run

    def __call__(self, *args, **kwargs):
        run = self._run
        return run.evaluator._invoke(run, self._fn, list(args), kwargs)

    def __repr__(self) -> str:
        return f"<function {_describe(self._fn)}>"

    __str__ = __repr__

    def __reduce__(self):  # never pickled out of a worker with what it holds
        raise TypeError("a function is not a value that can leave the expansion")


Passed.__name__ = "function"  # Python's own messages ("'function' object is not iterable") name no internals


class Evaluator:
    """Evaluate xacro expressions with an allow-list of callables (compared by identity).

    ``mapping_types``: classes whose attribute access is mapping access (xacro's NameSpace, Table,
    YamlDictWrapper); ``getattr`` is used on them exactly as Python would."""

    def __init__(self, allowed=(), *, mapping_types=(), limits: Limits | None = None):
        self.limits = limits or Limits()
        self.spent = 0  # items iterated by finished evaluations (Limits.max_total_iter)
        # id -> (container, nested size); values never grow in place (only shrinking mutators are allowed), so a
        # memoised size stays an upper bound
        self._sizes: dict[int, tuple[object, int]] = {}
        self._allowed: dict[int, object] = {}
        self._guards: dict[int, tuple[object, object]] = {}
        self._mapping_types: tuple[type, ...] = ()
        self.allow(*allowed)
        self.add_mapping_types(*mapping_types)
        for fn, guard in ((math.factorial, _g_factorial), (math.comb, _g_comb_perm("comb")),
                          (math.perm, _g_comb_perm("perm")), (math.prod, _g_prod), (math.lcm, _g_lcm),
                          (builtins.sum, _g_sum), (builtins.round, _g_round)):
            self.guard(fn, guard)

    # ---- configuration ---------------------------------------------------------------------------
    def allow(self, *fns) -> None:
        for fn in fns:
            self._allowed[id(fn)] = fn  # keep a reference: ids must not be reused while allowed

    def disallow(self, *fns) -> None:
        for fn in fns:
            if self._allowed.get(id(fn)) is fn:
                del self._allowed[id(fn)]

    def guard(self, fn, check) -> None:
        """``check(run, args, kwargs) -> args`` runs before every call of ``fn`` (may call run.refuse)."""
        self._guards[id(fn)] = (fn, check)

    def add_mapping_types(self, *types_) -> None:
        self._mapping_types = tuple(dict.fromkeys(self._mapping_types + tuple(types_)))

    def is_allowed(self, fn, extra=None) -> bool:
        if type(fn) is Passed:
            fn = fn._fn
        key = id(fn)
        if self._allowed.get(key) is fn or (extra and extra.get(key) is fn):
            return True
        # a read-only method bound to a builtin data value, e.g. 'a'.upper or yaml_dict.get
        if type(fn) is BuiltinFunctionType and not isinstance(fn.__self__, (ModuleType, type)):
            names = _method_names(type(fn.__self__))
            return names is not None and fn.__name__ in names
        return False

    # ---- evaluation ------------------------------------------------------------------------------
    def validate(self, expr: str) -> str | None:
        return validate(expr, self.limits)

    def evaluate(self, expr: str, symbols):
        """Like ``eval(compile(expr.strip(), "<expression>", "eval"), symbols)`` with builtins removed."""
        def lookup(name):
            try:
                return symbols[name]  # Table resolves lazily in __getitem__
            except KeyError:
                raise NameError(f"name '{name}' is not defined", name=name) from None

        return self._run(expr.strip(), "<expression>", lookup, lookup)

    def _run(self, text, filename, top, glob, extra=None):
        tree, reason = _compile(text, filename, self.limits)
        run = _Run(self, text, top, glob, extra)
        if reason:
            run.refuse(reason)
        try:
            result = run.check(run.ev(tree.body, None))
        finally:
            self.spent += run.iters
        if callable(result) and type(result) is not Passed and not isinstance(result, type):
            # a method or function as the value of an expression (a property): it leaves the evaluator
            # guarded; the evaluator unwraps it when an expression calls it
            return Passed(result, run)
        return result

    def _nested_size(self, run, value) -> int:
        """Items of `value` with nested containers counted each time they occur and strings by length (what a repr
        prints, a comparison or hash walks), capped at max_len + 1. Memoised per container, so the walk costs the
        values' memory, not their nested size; charged to the evaluation's budget."""
        memo, cap = self._sizes, self.limits.max_len + 1
        hit = memo.get(id(value))
        if hit is not None and hit[0] is value:
            return hit[1]
        work, stack, open_ = 0, [value], set()
        while stack:
            x = stack[-1]
            key = id(x)
            hit = memo.get(key)
            if hit is not None and hit[0] is x:
                stack.pop()
                continue
            items = (*x.keys(), *x.values()) if isinstance(x, dict) else x
            if key not in open_:  # first visit: size the nested containers first
                kinds = set(map(type, items))  # C speed: most values hold numbers only, or strings only
                if not any(issubclass(t, _NESTED) or issubclass(t, (str, bytes)) for t in kinds):
                    memo[key] = (x, min(len(items), cap))
                    stack.pop()
                    continue
                if all(issubclass(t, (str, bytes)) for t in kinds):
                    memo[key] = (x, min(len(items) + (sum(map(len, items)) >> 3), cap))
                    stack.pop()
                    continue
                open_.add(key)
                work += len(items)
                kids = [c for c in items if isinstance(c, _NESTED) and id(c) not in open_
                        and (memo.get(id(c)) or (None,))[0] is not c]
                if kids:
                    stack.extend(kids)
                    continue
            size = 0
            for c in items:
                if isinstance(c, _NESTED):
                    hit = memo.get(id(c))
                    size += hit[1] if hit is not None and hit[0] is c else 1  # a cycle (YAML anchors) counts once
                elif isinstance(c, (str, bytes)):
                    size += 1 + (len(c) >> 3)
                else:
                    size += 1
                if size > cap:
                    size = cap
                    break
            memo[key] = (x, size)
            open_.discard(key)
            stack.pop()
        run.spend(work >> 6)
        return memo[id(value)][1]

    def _getattr(self, run, obj, name):
        if name.startswith("_"):
            # a key of a mapping (a YAML key or property named '_x', as stock reads it); never a private
            # attribute or method of an object (Table._setitem would rewrite properties)
            if name.startswith("__") or not isinstance(obj, self._mapping_types) or name not in obj:
                run.refuse(f"attribute '{name}' is not allowed (only a mapping's own key may start with '_')")
            return obj[name]
        if isinstance(obj, self._mapping_types):
            return getattr(obj, name)  # NameSpace/YamlDictWrapper: their own __getattr__ semantics
        names = None if isinstance(obj, type) else _method_names(type(obj))
        if names is not None:
            if name in names:
                return getattr(obj, name)
            if not hasattr(type(obj), name):
                raise AttributeError(f"'{type(obj).__name__}' object has no attribute '{name}'")
        kind = f"type '{obj.__name__}'" if isinstance(obj, type) else f"'{type(obj).__name__}' objects"
        run.refuse(f"attribute '{name}' of {kind} is not allowed")

    def _screen(self, run, fn, v):
        """An argument of a call. A callable becomes a `Passed` (or is refused): whoever calls it later,
        C code included (map, filter, sorted(key=), min/max(key=), a nested map), goes through `_invoke`."""
        if type(v) is Passed:
            return v
        if not self.is_allowed(v, run.extra):
            # map/filter/sorted(key=)/max(key=)...: an allowed function must not call a non-allowed one for us
            run.refuse(f"passing '{_describe(v)}' to '{_describe(fn)}' is not allowed")
        return Passed(v, run)

    def _invoke(self, run, fn, args, kwargs):
        if type(fn) is Passed:
            fn = fn._fn
        if not self.is_allowed(fn, run.extra):
            if not callable(fn):
                raise TypeError(f"'{type(fn).__name__}' object is not callable")
            run.refuse(f"call of '{_describe(fn)}' is not allowed")
        key = id(fn)
        if key not in _CHEAP:
            args = [self._screen(run, fn, v) if callable(v) else v for v in args]
            if kwargs:
                kwargs = {k: self._screen(run, fn, v) if callable(v) else v for k, v in kwargs.items()}
            for v in list(args) + list(kwargs.values()):
                if isinstance(v, range):
                    run.tick(_range_len(v))
                elif isinstance(v, _SIZED):  # e.g. sorted() of a 10M-character string
                    run.tick(len(v))
        elif any(type(v) is Passed for v in args):  # isinstance(x, t) with t a passed type: the type itself
            args = [v._fn if type(v) is Passed and isinstance(v._fn, type) else v for v in args]
        values = list(args) + list(kwargs.values())  # str.find on a 1 MB string in a loop, divmod of big ints
        owner = getattr(fn, "__self__", None) if type(fn) is BuiltinFunctionType else None
        run.spend(sum(_weight(v) for v in values) + _weight(owner) + _int_work(values))
        guard = self._guards.get(key)
        if guard is not None and guard[0] is fn:
            args = guard[1](run, args, kwargs)
        elif type(fn) is BuiltinFunctionType and not isinstance(fn.__self__, (ModuleType, type)):
            owner = fn.__self__
            for base in type(owner).__mro__:
                mguard = _METHOD_GUARDS.get((base, fn.__name__))
                if mguard is not None:
                    args = mguard(run, owner, args, kwargs)
                    break
        result = run.check(fn(*args, **kwargs))
        run.spend(_weight(result) + (_int_work((result, result)) if type(result) is int else 0))
        return result


# --------------------------------------------------------------------------------------------------
# xacro wiring
# --------------------------------------------------------------------------------------------------

_TOP_BUILTINS = ("list", "dict", "map", "len", "str", "float", "int", "bool", "min", "max", "round",
                 "sorted", "range")
_XACRO_HELPERS = ("arg", "dotify", "tokenize", "message", "warning", "error", "print_location", "fatal",
                  "load_yaml", "abs_filename")
_TOP_DEPRECATED = ("load_yaml", "abs_filename", "dotify")


def default_evaluator(global_symbols, limits: Limits | None = None) -> Evaluator:
    """Evaluator allowing what xacro's ``_global_symbols`` exposes, minus what reaches internals.

    Reads the callables from ``global_symbols`` as they are *now*: swap in confined versions (e.g.
    load_yaml) before calling this, or use ``disallow()``/``allow()`` afterwards."""
    ev = Evaluator(limits=limits)

    def get(ns, name):
        try:
            return ns[name]
        except (KeyError, TypeError):
            return None

    def namespace(name):
        ns = get(global_symbols, name)
        if isinstance(ns, dict):
            for cls in type(ns).__mro__:  # NameSpace, Table (its parent class)
                if cls is dict:
                    break
                ev.add_mapping_types(cls)
        return ns

    python, math_ns, xacro_ns = namespace("python"), namespace("math"), namespace("xacro")
    for name in _TOP_BUILTINS + _TOP_DEPRECATED:
        fn = get(global_symbols, name)
        if callable(fn) and fn not in (type, vars):
            ev.allow(fn)
    if python is not None:
        for name in list(python.keys()):
            fn = get(python, name)
            if name not in _DENIED_PYTHON and callable(fn) and fn not in (type, vars):
                ev.allow(fn)
    if math_ns is not None:
        for name in list(math_ns.keys()):
            fn = get(math_ns, name)
            if not name.startswith("_") and callable(fn):
                ev.allow(fn)
                top = get(global_symbols, name)  # exposed directly too (the same object in xacro 2.x)
                if callable(top):
                    ev.allow(top)
    if xacro_ns is not None:
        for name in _XACRO_HELPERS:
            fn = get(xacro_ns, name)
            if callable(fn):
                ev.allow(fn)
        dotify = get(xacro_ns, "dotify")
        if isinstance(dotify, type):
            ev.add_mapping_types(dotify)  # YamlDictWrapper: dotted access to YAML keys
        tokenize = get(xacro_ns, "tokenize")
        if callable(tokenize):
            ev.guard(tokenize, _g_tokenize)
    return ev


# $(eval ...): stock eval() there has the *real* builtins; we keep a few harmless ones (True/False/None
# are constants in Python 3). list/dict/map are what substitution_args' own (ineffective) restricted
# __builtins__ meant to offer.
_SUBST_BUILTINS = {f.__name__: f for f in (int, float, str, bool, len, min, max, abs, round, list, dict, map)}


def _refused_in_eval(name):
    def refuse(*args, **kwargs):  # evaluate_substitution fills in the expression text
        raise Refused("", f"{name}() inside $(eval) is not allowed (no confined version was supplied)")
    refuse.__name__ = refuse.__qualname__ = name
    return refuse


def default_substitution_functions() -> dict:
    """xacro's ``substitution_args._eval_dict`` without env/optenv/find (those refuse; pass confined ones)."""
    out = {"true": True, "false": False, "True": True, "False": False}
    out.update({k: v for k, v in vars(math).items() if not k.startswith("_")})
    out.update({name: _refused_in_eval(name) for name in ("env", "optenv", "find")})
    return out


def evaluate_substitution(s: str, context: dict, *, functions: dict | None = None,
                          evaluator: Evaluator | None = None) -> str:
    """``$(eval s)`` with the semantics of ``xacro.substitution_args._eval``: names resolve to
    ``arg``/``dirname``, then ``functions`` (default: ``default_substitution_functions()``), then the
    arg values through ``convert_value(..., 'auto')``, then a few safe builtins. Returns ``str(result)``."""
    from xacro.substitution_args import ArgException, SubstitutionException, convert_value

    if "arg" not in context:
        context["arg"] = {}
    args = context["arg"]

    def arg(name):
        try:
            value = args[name]
        except KeyError:
            raise ArgException(name) from None
        return convert_value(value, "auto")

    def dirname():
        filename = context.get("filename")
        if not filename:
            raise SubstitutionException("Cannot substitute $(dirname),no file/directory information available.")
        # stock returns the runner's absolute path; "." names the same folder for everything that resolves a
        # relative name (include, load_yaml), relative to the current file, and tells nothing about the runner
        return "."

    funcs = {"arg": arg, "dirname": dirname}
    funcs.update(default_substitution_functions() if functions is None else functions)

    # no textual '__' test (stock's): '_' '_class_' '_' spells one around it. The parsed tree is checked
    # (names and attributes starting with '__', private attributes starting with '_', are refused) and str.format
    # fields are guarded on every call.

    def builtin(name):
        try:
            return _SUBST_BUILTINS[name]
        except KeyError:
            if hasattr(builtins, name):  # stock $(eval) has every builtin (exec, open, ...): a refusal, not a typo
                raise Refused(s, f"builtin '{name}' is not available in $(eval) in the sandbox") from None
            raise NameError(f"name '{name}' is not defined", name=name) from None

    def top(name):  # eval(s, {}, _DictWrapper(args, functions)): locals mapping, then builtins
        try:
            return funcs[name]
        except KeyError:
            pass
        try:
            return convert_value(args[name], "auto")
        except KeyError:
            return builtin(name)

    extra = {id(v): v for v in list(funcs.values()) + list(_SUBST_BUILTINS.values()) if callable(v)}
    ev = evaluator or _SUBST_EVALUATOR
    # eval() of a string skips leading spaces and tabs only; inside comprehensions only globals
    # (i.e. the builtins) are visible, not the locals mapping
    try:
        return str(ev._run(s.lstrip(" \t"), "<string>", top, builtin, extra))
    except Refused as e:
        if e.expr:
            raise
        raise Refused(s, e.reason) from None


_SUBST_EVALUATOR = Evaluator()
