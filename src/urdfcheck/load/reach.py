"""Which xacro arguments make a robot include a file (issue 37): a fragment that only a non-default argument reaches.

    reaching(entry, fragment, find) -> Reach | None

`lint arm.xacro`, where the robot includes arm.xacro only under `<xacro:if value="$(arg use_arm)">` (default false)
or `<xacro:if value="${'$(arg arm)' == 'small'}">`, lints the robot; with its defaults the include never happens and
the fragment is never expanded. This reads the robot's text (no expansion) along its literal includes, down to the
include of `fragment`, and collects the conditions around each include on the way. A condition is decided when it
is an argument (`$(arg x)`, or a property whose value is `$(arg x)`) taken as a boolean, or compared with a literal
(`==`, `!=`); the values that satisfy every condition are the variant that reaches the fragment. Anything else (a
macro parameter, an expression) is not decided: `Reach.undecided` names it, and the caller says so.
"""
from __future__ import annotations

import os

from urdfcheck.core import lazyre
from urdfcheck.core.records import Record

XACRO_NS = ("http://www.ros.org/wiki/xacro", "http://wiki.ros.org/xacro", "http://ros.org/wiki/xacro")
MAX_FILES = 100
_ARG = lazyre.compile(r"^\s*\$\(\s*arg\s+([\w.-]+)\s*\)\s*$")
_PROP = lazyre.compile(r"^\s*\$\{\s*([A-Za-z_]\w*)\s*\}\s*$")
_NOT = lazyre.compile(r"^\s*\$\{\s*not\s+([A-Za-z_]\w*)\s*\}\s*$")
_CMP = lazyre.compile(
    r"""^\s*\$\{\s*(?:(['"])\$\(\s*arg\s+([\w.-]+)\s*\)\1|([A-Za-z_]\w*))\s*(==|!=)\s*(['"])(.*?)\5\s*\}\s*$""")
_TRUE, _FALSE = ("true", "True", "1"), ("false", "False", "0")
_OTHER = "\x00!="  # "any value other than": a condition `!=` under if (`==` under unless)


class Reach(Record):
    # args: argument -> the value that makes the include happen ({} when the defaults already reach it)
    # via: the include elements on the way (file, line), from the robot down to the fragment
    # undecided: the first condition on the way that is not decided ("" when all are)
    _fields = ('args', 'via', 'undecided')

    def __init__(self, args=None, via=(), undecided=""):
        self.args = dict(args or {})
        self.via = tuple(via)
        self.undecided = undecided


def reaching(entry: str, fragment: str, find) -> Reach | None:
    """How `entry` comes to include `fragment` (real paths compared), or None when no literal include of it is
    found on the way. `find(package) -> folder or None` resolves `$(find package)`."""
    target = os.path.realpath(fragment)
    props: dict[str, str] = {}
    defaults: dict[str, str] = {}
    seen: set[str] = set()
    path = _walk(os.path.abspath(entry), target, find, props, defaults, seen, ())
    if path is None:
        return None
    args: dict[str, str] = {}
    via = []
    for file, line, conds in path:
        via.append((file, line))
        for kind, value in conds:
            got = _decide(kind, value, props)
            if got is None:
                return Reach({}, via, f"{value} ({os.path.basename(file)})")
            for name, want in got:
                have = args.get(name)
                if have is not None and not _same(have, want):
                    return Reach({}, via, f"{value} ({os.path.basename(file)}): contradicts another condition")
                args[name] = want
    out = {}
    for k, v in args.items():
        have = defaults.get(k)
        if v.startswith(_OTHER):
            if have is None or have == v[len(_OTHER):]:
                return Reach({}, via, f"{k} other than {v[len(_OTHER):]!r}")
        elif have is None or not _same(have, v):  # what the defaults already satisfy needs no variant
            out[k] = v
    return Reach(out, via)


def _same(a: str, b: str) -> bool:
    return a in _TRUE and b in _TRUE or a in _FALSE and b in _FALSE or a == b


def _decide(kind: str, value: str, props: dict[str, str]):
    """[(argument, value)] that make the condition `value` of `kind` (if/unless) true, or None."""
    want = kind == "if"
    m = _ARG.match(value)
    if m:
        return [(m.group(1), "true" if want else "false")]
    m = _NOT.match(value)
    if m and _arg_of(m.group(1), props):
        return [(_arg_of(m.group(1), props), "false" if want else "true")]
    m = _PROP.match(value)
    if m and _arg_of(m.group(1), props):
        return [(_arg_of(m.group(1), props), "true" if want else "false")]
    m = _CMP.match(value)
    if m:
        name = m.group(2) or _arg_of(m.group(3) or "", props)
        if not name:
            return None
        equal = (m.group(4) == "==") == want
        # any value but one: the defaults may give it (checked in `reaching`); no single value to choose otherwise
        return [(name, m.group(6) if equal else _OTHER + m.group(6))]
    return None


def _arg_of(prop: str, props: dict[str, str]) -> str:
    m = _ARG.match(props.get(prop, ""))
    return m.group(1) if m else ""


def _xacro(el, name: str) -> bool:
    tag = el.tag if isinstance(el.tag, str) else ""
    if tag.startswith("{"):
        ns, _, local = tag[1:].partition("}")
        return local == name and ns in XACRO_NS
    return tag == f"xacro:{name}"


def _walk(path: str, target: str, find, props, defaults, seen, conds):
    """[(file, line, conditions)] from `path` down to the include of `target`, or None."""
    from urdfcheck.load.packages import _literal_include

    if path in seen or len(seen) >= MAX_FILES:
        return None
    seen.add(path)
    root = _parse(path)
    if root is None:
        return None
    for el in root.iter():
        if _xacro(el, "property") and el.get("name") and el.get("value") is not None:
            props.setdefault(el.get("name"), el.get("value"))
        elif _xacro(el, "arg") and el.get("name") and el.get("default") is not None:
            defaults.setdefault(el.get("name"), el.get("default").strip())
    for el in root.iter():
        if not _xacro(el, "include"):
            continue
        ref = (el.get("filename") or "").strip()
        got = _literal_include(ref, path, find)
        if got is None:
            continue
        here = tuple((k, a.get("value") or "") for a in el.iterancestors()
                     for k in ("if", "unless") if _xacro(a, k))
        step = (path, el.sourceline, here)
        if os.path.realpath(got) == target:
            return [step]
        deeper = _walk(got, target, find, props, defaults, seen, conds + here)
        if deeper is not None:
            return [step, *deeper]
    return None


def _parse(path: str):
    from urdfcheck.core import door, xmlfront

    try:
        data = door.read_bytes(path, limit=4 * 1024 * 1024)
        root, _ = xmlfront.parse(data)
    except (OSError, ValueError, xmlfront.XmlRefused):
        return None
    return root
