"""Automatic variants: the boolean xacro:args of a model and the argument sets a lint covers.

    boolean_args(path, packages) -> {name: default}        # the entry's and its included files'
    auto_variants(path, base, packages) -> [(name, args)]   # what `variants: auto` and zero config lint

Up to MAX_AUTO_ARGS free boolean arguments: every combination. Beyond: the defaults, then a pairwise
covering array - every value of every pair of arguments appears in at least one variant - so that a defect
needing two arguments true (`use_arm and use_gripper`) is linted, at a handful of variants (7 for 5
arguments, 17 for 20). Arguments are read as text (no expansion): the entry file's, then those of the
files it includes literally (an argument declared in an included macro file is a command-line argument of the
robot too; xacro keeps the first declaration's default). Included files are looked at only inside the package
roots the loader reads from (the entry's package, the named packages, the packages its `$(find)`s resolve).
"""
from __future__ import annotations

import itertools
import os
import re
from collections.abc import Mapping
from pathlib import Path

from urdfcheck.core import lazyre

MAX_AUTO_ARGS = 4  # every combination up to 2**4 variants; beyond, pairwise
MAX_ROWS = 64
_ARG = lazyre.compile(r"<\s*xacro:arg\b([^>]*)/?>", re.S)
_ATTR = lazyre.compile(r"""(\w+)\s*=\s*(["'])(.*?)\2""", re.S)
_BOOLS = {"true": "false", "false": "true", "True": "False", "False": "True", "1": "0", "0": "1"}


def _declared(text: str, out: dict[str, str]) -> None:
    text = re.sub(r"<!--.*?-->", "", text, flags=re.S)
    for m in _ARG.finditer(text):
        attrs = {k: v for k, _, v in _ATTR.findall(m.group(1))}
        name, default = attrs.get("name"), attrs.get("default")
        if name and name not in out:
            out[name] = default.strip() if default is not None else ""


def boolean_args(path: str, packages: Mapping[str, str] | None = None, *, included: bool = True) -> dict[str, str]:
    """xacro:args whose default is a boolean literal (name -> default), in declaration order: the entry's, then
    (with `included`) those its literal includes declare."""
    from urdfcheck.core import door

    declared: dict[str, str] = {}
    try:
        text = door.read_bytes(path, limit=4 * 1024 * 1024)[:4 * 1024 * 1024].decode("utf-8", "replace")
    except OSError:
        return {}
    _declared(text, declared)
    if included and "include" in text:
        for _, inc in _included(path, packages or {}):
            _declared(inc, declared)
    return {k: v for k, v in declared.items() if v in _BOOLS}


def defaulted_args(path: str, packages: Mapping[str, str] | None = None) -> dict[str, str]:
    """The xacro:args declared with a default (name -> its text, the first declaration's), in the entry and its
    literal includes: what a config's `args` replace rather than supply (request.config; issue 36)."""
    from urdfcheck.core import door

    try:
        text = door.read_bytes(path, limit=4 * 1024 * 1024)[:4 * 1024 * 1024].decode("utf-8", "replace")
    except OSError:
        return set()
    texts = [text]
    if "include" in text:
        texts.extend(inc for _, inc in _included(path, packages or {}))
    out: dict[str, str] = {}
    for t in texts:
        for m in _ARG.finditer(re.sub(r"<!--.*?-->", "", t, flags=re.S)):
            attrs = {k: v for k, _, v in _ATTR.findall(m.group(1))}
            if attrs.get("name") and "default" in attrs and attrs["name"] not in out:
                out[attrs["name"]] = attrs["default"].strip()
    return out


def _included(path: str, packages: Mapping[str, str]):
    from urdfcheck.load.packages import Resolver, enclosing_package, literal_includes, real

    entry = os.path.abspath(path)
    resolver = Resolver(dict(packages), near=Path(entry))
    pkg = enclosing_package(Path(entry).parent)
    fixed = [os.path.abspath(p) for p in (*packages.values(), pkg or os.path.dirname(entry))]
    real_roots: dict[str, str] = {}  # root -> its real path, once a model (once a run: packages.real)

    def allow(file: str) -> bool:
        # the package roots the loader reads from (the entry's, the named ones, those its $(find)s resolved):
        # written inside (nothing outside is ever looked at), and really inside (no link out)
        roots = fixed + [os.path.abspath(str(p)) for p in resolver.used.values()]
        if not _under(file, roots):
            return False
        for r in roots:
            if r not in real_roots:
                real_roots[r] = real(r)
        return _under(real(file), [real_roots[r] for r in roots])

    for file, text in literal_includes([entry], resolver.find, max_files=100, allow=allow):
        if file != entry:
            yield file, text


def _under(path: str, roots) -> bool:
    return any(path == r or path.startswith(r.rstrip(os.sep) + os.sep) for r in roots)


def auto_variants(path: str, base: Mapping[str, str], packages: Mapping[str, str] | None = None
                  ) -> list[tuple[str, dict]]:
    """(name, args) for each variant: every combination of the free boolean args (at most 2**MAX_AUTO_ARGS),
    else the defaults and a pairwise covering array. Named by what differs from the defaults."""
    flags = {k: v for k, v in boolean_args(path, packages).items() if k not in base}
    if not flags:
        return [("", {})]
    names = list(flags)
    if len(names) <= MAX_AUTO_ARGS:
        rows = list(itertools.product((False, True), repeat=len(names)))
    else:
        # each flag flipped alone first: a defect one option reaches is seen in a variant of that option alone,
        # not only inside a combination of several (which no launch file may use: a guess, plan.plan.variants)
        single = [tuple(i == j for j in range(len(names))) for i in range(len(names))]
        rows = list(dict.fromkeys([*pairwise(len(names))[:1], *single, *pairwise(len(names))[1:]]))
    out = []
    for flips in rows:
        args = {n: (_BOOLS[flags[n]] if f else flags[n]) for n, f in zip(names, flips)}
        if len(names) > MAX_AUTO_ARGS:
            args = {n: v for n, v in args.items() if v != flags[n]}  # the defaults are the file's
        flipped = ",".join(f"{k}={v}" for k, v in args.items() if v != flags[k])
        out.append((flipped or "defaults", args))
    return out


def pairwise(n: int) -> list[tuple[bool, ...]]:
    """Rows of n booleans (True = flipped from the default), the first all False, such that every pair of
    columns shows all four value pairs in some row. Greedy (AETG-like), deterministic."""
    rows = [tuple([False] * n)]
    todo = {(i, a, j, b) for i, j in itertools.combinations(range(n), 2) for a in (False, True) for b in (False, True)}
    todo -= _pairs(rows[0])
    while todo and len(rows) < MAX_ROWS:
        i, a, j, b = min(todo)
        row: list[bool | None] = [None] * n
        row[i], row[j] = a, b
        for k in range(n):
            if row[k] is not None:
                continue
            gain = {}
            for v in (True, False):
                gain[v] = sum((min(k, m), v if k < m else row[m], max(k, m), row[m] if k < m else v) in todo
                              for m in range(n) if row[m] is not None)
            row[k] = max((True, False), key=lambda v: gain[v])
        done = tuple(bool(x) for x in row)
        rows.append(done)
        todo -= _pairs(done)
    return rows


def _pairs(row) -> set:
    return {(i, row[i], j, row[j]) for i, j in itertools.combinations(range(len(row)), 2)}
