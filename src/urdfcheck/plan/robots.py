"""Robot or library: decided from the parsed, expanded XML, never from raw text (issue 19).

A robot is a file whose expansion (with its defaults, or a deployment's arguments) has links. Text tricks cannot
hide one: comments are not read, `<xacro:element xacro:name="link">` counts because the expansion result is
what is counted. Discovery (load.discover) only sets aside what certainly expands to no link (macros,
properties and arguments, nothing else); every other file whose root is <robot> and that no other file
includes is expanded, and a *probe* target (`Target.probe`) whose expansion has no link is a library.

    has_links(root) -> bool                 # an expanded document's root: a robot?
    missed(candidates, loaded_files) -> [path]   # included files that no loaded model actually read
"""
from __future__ import annotations

import os

from urdfcheck.core.walk import real as realpath  # remembered for the run


def has_links(root) -> bool:
    """Whether an expanded document (lxml root element; comments are not elements) holds a <link>."""
    if root is None:
        return False
    for el in root.iter("link"):
        return el is not None
    return False


def missed(candidates, loaded_files) -> list[str]:
    """The `candidates` (files discovery took for included libraries) that no model of the run actually
    read: another file's include was commented out, conditional or never expanded, so nothing checked them."""
    read = {realpath(f) for f in loaded_files if f and not str(f).startswith("<")}
    return [c for c in dict.fromkeys(candidates) if realpath(c) not in read]


# --- fragments: a file that fails only on symbols its includers provide (issue 37) ---------------------------
_SYMBOL = (  # (pattern of a loader message, what defines the symbol in an includer's text)
    (r"unknown macro name: (?:xacro:)?([\w.-]+)", r'<\s*xacro:macro\b[^>]*\bname\s*=\s*["\']{}["\']'),
    (r"name '(\w+)' is not defined", r'\bname\s*=\s*["\']{}["\']|\bparams\s*=\s*["\'][^"\']*\b{}\b'),
    (r"xacro argument '([\w.-]+)' has no default", r'<\s*xacro:arg\b[^>]*\bname\s*=\s*["\']{}["\']|\b{}:='),
    (r"Undefined parameters \[([\w.-]+)", r'\bparams\s*=\s*["\'][^"\']*\b{}\b'),
)


def provided(message: str, texts) -> bool:
    """The loader's message names a symbol (a macro, property, argument or macro parameter) that one of `texts`
    (the includers' files) defines: the file fails only on what its includer provides."""
    import re

    for pattern, definition in _SYMBOL:
        m = re.search(pattern, message)
        if m:
            name = re.escape(m.group(1))
            rx = re.compile(definition.replace("{}", name))
            return any(t == "*" or rx.search(t) for t in texts)
    return False


_FIND_INCLUDE = r"""<\s*xacro:include\b[^>]*\bfilename\s*=\s*["']\$\(\s*find\s+([\w-]+)\s*\)"""


def includer_texts(includers, find) -> list[str]:
    """The text of the includers and of what they include literally (their macro libraries). An includer that
    includes a file of a package that is not found may get any symbol from it (that package's absence is said
    at the includer, X013): the text "*" then stands for it."""
    import re

    from urdfcheck.load.packages import literal_includes

    if not includers:
        return []
    texts = [text for _path, text in literal_includes(list(includers), find)]
    if any(find(m.group(1)) is None for t in texts for m in re.finditer(_FIND_INCLUDE, t)):
        texts.append("*")
    return texts


def includers_of(path: str) -> list[str]:
    """The xacro files of `path`'s package whose text names its file name: who may include it."""
    from pathlib import Path

    from urdfcheck.core import door
    from urdfcheck.load.discover import discover
    from urdfcheck.load.packages import enclosing_package, leaves_cwd

    pkg = enclosing_package(Path(os.path.abspath(path)).parent)
    if pkg is None:
        return []
    found = discover(str(pkg))
    base, real, out = os.path.basename(path).encode(), realpath(path), []
    for f in (*found.models, *found.libraries, *found.probes):
        if realpath(f) == real or leaves_cwd(f):
            continue
        try:
            if base in door.read_bytes(f, limit=4 * 1024 * 1024):
                out.append(f)
        except OSError:
            continue
    return list(dict.fromkeys(out))
