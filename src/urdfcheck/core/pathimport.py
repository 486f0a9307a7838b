"""pathlib, imported without urllib.parse (and the ipaddress module that imports).

pathlib imports `urllib.parse.quote_from_bytes` at load time for one method, `Path.as_uri()`, which a lint never
calls (the SARIF report does, and imports urllib itself). urllib.parse and ipaddress cost ~1.3 ms of every start-up
in a virtual environment holding only urdfcheck. While pathlib loads, `urllib.parse` is a stand-in whose
`quote_from_bytes` imports the real module the first time it is called; afterwards the stand-in leaves
sys.modules, so every `import urllib.parse` gets the real module. A process that imported pathlib or urllib.parse
already (a site `.pth`, the caller) keeps them as they are.
"""
from __future__ import annotations

import sys
import types


def _quote_from_bytes(*args, **kwargs):
    stand = sys.modules.get("urllib.parse")
    if getattr(stand, "_stand_in", False):
        del sys.modules["urllib.parse"]
    from urllib.parse import quote_from_bytes

    return quote_from_bytes(*args, **kwargs)


def _load() -> None:
    if "pathlib" in sys.modules or "urllib.parse" in sys.modules:
        return
    stand = types.ModuleType("urllib.parse", "stand-in while pathlib loads (urdfcheck.core.pathimport)")
    for name, value in (("quote_from_bytes", _quote_from_bytes), ("_stand_in", True)):
        setattr(stand, name, value)
    sys.modules["urllib.parse"] = stand
    try:
        import pathlib  # noqa: F401
    finally:
        if sys.modules.get("urllib.parse") is stand:
            del sys.modules["urllib.parse"]


_load()
