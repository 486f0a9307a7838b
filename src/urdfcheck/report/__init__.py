"""Report formats. Each module has `render(result, **opts) -> str`; modules are imported on demand."""
from __future__ import annotations

import importlib

FORMATS = {
    "text": "text",
    "json": "jsonout",
    "sarif": "sarif",
    "junit": "junit",
    "github": "github",
    "markdown": "markdown",
}


def render(fmt: str, result, **opts) -> str:
    if fmt not in FORMATS:
        raise ValueError(f"unknown format {fmt!r} (choose from {', '.join(FORMATS)})")
    mod = importlib.import_module(f"{__name__}.{FORMATS[fmt]}")
    return mod.render(result, **opts)
