"""PyYAML, imported without compiling its regular expressions before they are used.

PyYAML compiles its patterns at import. One of them, the pure-Python reader's class of non-printable code points,
costs about 7 ms to compile, and this tool never uses it: it parses with libyaml's reader (`CSafeLoader`) where
the C extension is present. While `yaml` loads, the patterns its own modules compile are `lazyre` patterns, which
compile on their first use; patterns compiled by any other module are compiled as usual.
"""
from __future__ import annotations

import sys


def _load():
    if "yaml" in sys.modules:
        import yaml

        return yaml
    import re

    from urdfcheck.core import lazyre

    real = re.compile

    def compile(pattern, flags=0):  # noqa: A001 - stands for re.compile while yaml loads
        caller = sys._getframe(1).f_globals.get("__name__", "")
        if caller == "yaml" or caller.startswith("yaml."):
            return lazyre.compile(pattern, flags)
        return real(pattern, flags)

    re.compile = compile
    try:
        import yaml
    finally:
        re.compile = real
    return yaml


yaml = _load()
