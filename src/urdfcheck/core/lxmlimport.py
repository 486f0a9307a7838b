"""lxml.etree, imported without the inspect and typing modules it loads for features this tool never uses.

lxml.etree runs `from inspect import getfullargspec` at import, for parser targets (custom SAX-style target
objects, which no part of urdfcheck passes), and inspect imports ast, dis, tokenize and linecache: about 8 ms
of a 95 ms lint of a plain URDF. While lxml loads, `inspect` is a stand-in that imports the real module the
first time anything is asked of it (lxml's function included); afterwards the stand-in leaves sys.modules, so
every later `import inspect` gets the real module. Behaviour is unchanged: the stand-in only delays the import.

lxml.etree also runs `from typing import Generic, TypeVar` for one class that exists for type checkers
(`ElementTree[T]`); typing costs ~2 ms to import, and no module of this tool imports it at run time (they take
`TYPE_CHECKING` from core.records). While lxml loads, `typing` is a stand-in with those two names; afterwards it
leaves sys.modules too. A process that imported typing or inspect already keeps its own.
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


class _Generic:
    """`typing.Generic` as lxml.etree uses it at import, as the base of its `ElementTree[T]` hint class:
    subscripted, it is itself (`etree.ElementTree[str]` is `etree.ElementTree`)."""

    __slots__ = ()

    def __class_getitem__(cls, params):
        return cls


def _type_var(name, *constraints, **options):
    return name


def _stand_ins() -> dict:
    later = _Later("inspect", "stand-in until first use (urdfcheck.core.lxmlimport)")
    hints = types.ModuleType("typing", "lxml.etree's two names, stand-ins (urdfcheck.core.lxmlimport)")
    for mod, name, value in ((later, "getfullargspec", _getfullargspec), (hints, "Generic", _Generic),
                             (hints, "TypeVar", _type_var)):
        setattr(mod, name, value)
    return {"inspect": later, "typing": hints}


def _load():
    if "lxml.etree" in sys.modules:
        from lxml import etree

        return etree
    stand = {name: mod for name, mod in _stand_ins().items() if name not in sys.modules}
    sys.modules.update(stand)
    try:
        from lxml import etree
    finally:
        for name, mod in stand.items():
            if sys.modules.get(name) is mod:
                del sys.modules[name]
    return etree


etree = _load()
