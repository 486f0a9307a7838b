"""lxml.etree, imported without the inspect module it loads for a feature this tool never uses.

lxml.etree runs `from inspect import getfullargspec` at import, for parser targets (custom SAX-style target
objects, which no part of urdfcheck passes), and inspect imports ast, dis, tokenize and linecache: about 8 ms
of a 95 ms lint of a plain URDF. While lxml loads, `inspect` is a stand-in that imports the real module the
first time anything is asked of it (lxml's function included); afterwards the stand-in leaves sys.modules, so
every later `import inspect` gets the real module. Behaviour is unchanged: the stand-in only delays the import.
"""
from __future__ import annotations

import sys
import types


def _real_inspect():
    mod = sys.modules.get("inspect")
    if isinstance(mod, _Later):
        del sys.modules["inspect"]
    import inspect

    return inspect


class _Later(types.ModuleType):
    def __getattr__(self, name):
        return getattr(_real_inspect(), name)


def _getfullargspec(func):
    return _real_inspect().getfullargspec(func)


def _load():
    if "lxml.etree" in sys.modules or "inspect" in sys.modules:
        from lxml import etree

        return etree
    later = _Later("inspect", "stand-in until first use (urdfcheck.core.lxmlimport)")
    later.getfullargspec = _getfullargspec
    sys.modules["inspect"] = later
    try:
        from lxml import etree
    finally:
        if sys.modules.get("inspect") is later:
            del sys.modules["inspect"]
    return etree


etree = _load()
