"""xacro, imported without its command-line module.

xacro's package imports `xacro.cli` for one function its own `main` calls (`process_args`), and that module imports
optparse and textwrap (with gettext and locale): about 1.5 ms of every xacro worker, for a command line the expander
never runs. While xacro loads, `xacro.cli` is a stand-in whose `process_args` imports the real module the first
time it is called (core/standin.py). A process that imported xacro already keeps it as it is.
"""
from __future__ import annotations

from urdfcheck.core.standin import import_with, real


def _process_args(*args, **kwargs):  # xacro.main's, from the real module
    return real("xacro.cli").process_args(*args, **kwargs)


xacro = import_with("xacro", {"xacro.cli": {"process_args": _process_args}})
