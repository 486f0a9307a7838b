"""xacro, imported without its command-line module.

xacro's package imports `xacro.cli` for one function its own `main` calls (`process_args`), and that module imports
optparse and textwrap (with gettext and locale): about 1.5 ms of every xacro worker, for a command line the expander
never runs. While xacro loads, `xacro.cli` is a stand-in whose `process_args` imports the real module the first
time it is called; afterwards the stand-in leaves sys.modules, so `import xacro.cli` gets the real module. A process
that imported xacro already keeps it as it is.
"""
from __future__ import annotations

import sys
import types


def _process_args(*args, **kwargs):  # xacro.main's, from the real module
    if getattr(sys.modules.get("xacro.cli"), "_stand_in", False):
        del sys.modules["xacro.cli"]
    from xacro import cli

    return cli.process_args(*args, **kwargs)


def _load():
    if "xacro" in sys.modules:
        import xacro

        return xacro
    stand = types.ModuleType("xacro.cli", "stand-in until xacro's command line runs (urdfcheck.load.xacro.xacroimport)")
    for name, value in (("process_args", _process_args), ("_stand_in", True)):
        setattr(stand, name, value)
    sys.modules["xacro.cli"] = stand
    try:
        import xacro
    finally:
        if sys.modules.get("xacro.cli") is stand:
            del sys.modules["xacro.cli"]
    return xacro


xacro = _load()
