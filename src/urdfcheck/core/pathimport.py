"""pathlib, imported without urllib.parse (and the ipaddress module that imports).

pathlib imports `urllib.parse.quote_from_bytes` at load time for one method, `Path.as_uri()`, which a lint never
calls (the SARIF report does, and imports urllib itself). urllib.parse and ipaddress cost ~1.3 ms of every start-up
in a virtual environment holding only urdfcheck. While pathlib loads, `urllib.parse` is a stand-in whose
`quote_from_bytes` imports the real module the first time it is called (core/standin.py). A process that imported
pathlib or urllib.parse already (a site `.pth`, the caller) keeps them as they are.
"""
from __future__ import annotations

import sys

from urdfcheck.core.standin import import_with, real


def _quote_from_bytes(*args, **kwargs):
    return real("urllib.parse").quote_from_bytes(*args, **kwargs)


if "pathlib" not in sys.modules and "urllib.parse" not in sys.modules:
    import_with("pathlib", {"urllib.parse": {"quote_from_bytes": _quote_from_bytes}})
