"""Report formats. Each module has `render(result, **opts) -> str`; modules are imported on demand."""
from __future__ import annotations

import importlib

from urdfcheck.core import lazyre

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
    return escape_bidi(mod.render(result, **opts), json=fmt in ("json", "sarif"))


# Unicode bidirectional controls (embeddings, overrides, isolates, marks): a link or file name holding U+202E shows
# reversed text in a terminal, a PR annotation or a code-scanning page ("Trojan Source"). Every report shows them
# as the visible escape `\u202e`; in JSON formats the escape is itself escaped, so a parsed string holds the six
# visible characters, not the control.
_BIDI = "\u061c\u200e\u200f\u202a\u202b\u202c\u202d\u202e\u2066\u2067\u2068\u2069"
_BIDI_RE = lazyre.compile(f"[{_BIDI}]")
_BIDI_JSON_ESCAPE = lazyre.compile(r"(?<!\\)((?:\\\\)*)\\u(061[cC]|200[eEfF]|202[a-eA-E]|206[6-9])")


def escape_bidi(text: str, json: bool = False) -> str:
    if json:
        text = _BIDI_JSON_ESCAPE.sub(lambda m: m.group(1) + "\\\\u" + m.group(2).lower(), text)
        return _BIDI_RE.sub(lambda m: f"\\\\u{ord(m.group(0)):04x}", text)
    return _BIDI_RE.sub(lambda m: f"\\u{ord(m.group(0)):04x}", text)
