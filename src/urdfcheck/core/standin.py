"""Import a library while some modules it imports for features this tool never uses are stand-ins.

`import_with(target, {name: {attribute: value}})` imports `target` while each `name` not yet imported is a module
holding only those attributes (usually functions that import the real module on their first call, through `real`);
afterwards the stand-ins leave sys.modules, so every later import gets the real module. core/pathimport.py and
load/xacro/xacroimport.py use it; core/lxmlimport.py has its own (its inspect stand-in answers any attribute).
"""
from __future__ import annotations

import importlib
import sys
import types


def import_with(target: str, stand_ins: dict[str, dict]):
    made = {}
    for name, attributes in stand_ins.items():
        if name in sys.modules:
            continue
        mod = types.ModuleType(name, f"stand-in while {target} loads (urdfcheck.core.standin)")
        for key, value in {**attributes, "_stand_in": True}.items():
            setattr(mod, key, value)
        made[name] = mod
    sys.modules.update(made)
    try:
        return importlib.import_module(target)
    finally:
        for name, mod in made.items():
            if sys.modules.get(name) is mod:
                del sys.modules[name]


def real(name: str):
    """The real module `name`, imported now if a stand-in holds its place."""
    if getattr(sys.modules.get(name), "_stand_in", False):
        del sys.modules[name]
    return importlib.import_module(name)
