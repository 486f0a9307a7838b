"""Write the attribute readers (readers.py) from the grammar: `python -m urdfcheck.model.readergen`.

One function per grammar element and URDF version, `read(builder, el) -> tuple of values in grammar order`.
The good path is straight-line code; anything else calls back into the builder (build._Builder), which reports
it. readers.py is generated rather than compiled at run time so that a run loads bytecode instead of compiling
81 functions (several milliseconds of every small lint); tests/model/test_grammar.py fails when it is stale, and
build.readers compiles the functions in memory if it ever is.
"""
from __future__ import annotations

import sys
from pathlib import Path

from urdfcheck.model import grammar as G

PATH = Path(__file__).with_name("readers.py")


def name(tag: str, version: G.Version) -> str:
    return f"{tag}_{version[0]}_{version[1]}"


def reader_source(tag: str, version: G.Version, fn: str = "read") -> str:
    el = G.GRAMMAR[tag]
    attrs = [a for a in el.attrs if a.since <= version]
    n = len(attrs)
    t = repr(tag)
    out = [f"def {fn}(b, el):"]
    if n:
        out.append("    get = el.get")
        out += [f"    a{i} = get({a.name!r})" for i, a in enumerate(attrs)]
        given = " + ".join(f"(a{i} is not None)" for i in range(n))
        out.append("    n = len(el.attrib)")
        out.append(f"    if n and n != (k := {given}) and (n != k + 1 or get(SRC) is None):  # SRC: xacro's marker")
    else:
        out.append("    n = len(el.attrib)")
        out.append("    if n and (n != 1 or el.get(SRC) is None):")
    out.append(f"        b.odd_attributes(el, {t})")
    if not el.children:
        out.append("    if len(el):")
        out.append(f"        b.children_of_leaf(el, {t})")
    index = {a.name: i for i, a in enumerate(attrs)}
    for group in el.exclusive:
        if all(g in index for g in group):  # only where this version reads them all
            out.append(f"    if {' and '.join(f'a{index[g]} is not None' for g in group)}:")
            out.append(f"        b.exclusive(el, {group!r})")
    if any(a.kind == G.VECTOR for a in attrs):
        out.append("    vectors = b.vectors")
    for i, a in enumerate(attrs):
        v, raw, d = f"v{i}", f"a{i}", repr(a.default)
        missing = [f"        b.missing(el, {t}, {i})"] if G.required(a, version) else []
        if a.kind == G.NAME:  # an empty name is no name
            out += [f"    if not {raw}:", *missing, f"        {v} = {d}", "    else:", f"        {v} = {raw}"]
            continue
        out += [f"    if {raw} is None:", *missing, f"        {v} = {d}", "    else:"]
        if a.kind == G.TEXT:
            out.append(f"        {v} = {raw}")
        elif a.kind == G.NUMBER:
            out += ["        try:",
                    f"            {v} = float({raw})",
                    "        except ValueError:",
                    f"            {v} = b.bad_number(el, {t}, {i}, {raw}, False)",
                    "        else:",
                    f"            if {v} - {v} != 0.0 or '_' in {raw}:  # nan/inf, or Python-only digit separators",
                    f"                {v} = b.bad_number(el, {t}, {i}, {raw}, True)"]
        else:
            out += [f"        {v} = vectors.get({raw})",
                    f"        if {v} is None or len({v}) != {a.size}:",
                    f"            {v} = b.vector(el, {t}, {i}, {raw}, {a.size})"]
    out.append(f"    return ({''.join(f'v{i}, ' for i in range(n))})")
    return "\n".join(out) + "\n"


def module_source() -> str:
    out = ['"""Attribute readers, one per URDF element and version: GENERATED from model/grammar.py by',
           '`python -m urdfcheck.model.readergen`. Do not edit; see readergen.py."""',
           "# flake8: noqa",
           "", f"SRC = {G.SRC_ATTR!r}", ""]
    for v in G.VERSIONS:
        for tag in G.GRAMMAR:
            out += ["", reader_source(tag, v, name(tag, v))]
    out.append("READERS = {")
    for v in G.VERSIONS:
        out.append(f"    {v!r}: {{")
        out += [f"        {tag!r}: {name(tag, v)}," for tag in G.GRAMMAR]
        out.append("    },")
    out.append("}")
    return "\n".join(out) + "\n"


def compiled(version: G.Version) -> dict:
    """The readers of one version compiled in memory (when readers.py is stale)."""
    ns: dict = {"SRC": G.SRC_ATTR}
    for tag in G.GRAMMAR:
        exec(compile(reader_source(tag, version, name(tag, version)), f"<reader {tag}>", "exec"), ns)
    return {tag: ns[name(tag, version)] for tag in G.GRAMMAR}


def main() -> int:
    PATH.write_text(module_source(), encoding="utf-8")
    print(PATH)
    return 0


if __name__ == "__main__":
    sys.exit(main())
