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
    read = {os.path.realpath(f) for f in loaded_files if f and not str(f).startswith("<")}
    return [c for c in dict.fromkeys(candidates) if os.path.realpath(c) not in read]
