"""Report formats. Each module has `render(result, **opts) -> str`; modules are imported on demand."""
from __future__ import annotations

import importlib

from urdfcheck.core import lazyre
from urdfcheck.core.findings import _SURROGATE, escape_bidi
from urdfcheck.core.findings import show_byte as _byte

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
    return finish_text(mod.render(result, **opts), fmt)


def gate(result, fail_on=None) -> tuple[list, list]:
    """(the findings that fail the run, those at or above the level that do not gate): `Result.gate`, so that every
    headline says what the exit code judged (with `lint --diff-base`, the new findings only)."""
    judge = getattr(result, "gate", None)
    if judge is not None:
        return judge(fail_on)
    from urdfcheck.core.findings import Severity

    level = fail_on or getattr(result, "fail_on", Severity.WARNING)
    return [f for f in result.findings if f.severity >= level], []


def gate_words(result, fail_on) -> tuple[int, str, str] | None:
    """With `lint --diff-base REV`: (how many fail the run, what gates, what does not), e.g. (1, "1 new finding at or
    above warning", "2 unchanged since HEAD at or above it, not gating"); the last is "" when none. None without it.
    At the run's own level the count is the exit code's judgement (each package's config level in a workspace)."""
    changes = getattr(result, "changes", None)
    if changes is None:
        return None
    from urdfcheck.core.findings import clean_text

    own = fail_on == getattr(result, "fail_on", None)
    gating, quiet = gate(result, None if own else fail_on)
    levels = {t.settings.fail_on for t in getattr(result, "targets", ()) if getattr(t, "settings", None) is not None}
    level = "each package's own level" if own and len(levels) > 1 else str(fail_on)
    n = len(gating)
    head = f"{n or 'no'} new finding{'s' if n != 1 else ''} at or above {level}"
    rest = (f"{len(quiet)} unchanged since {clean_text(changes.rev)} at or above it, not gating" if quiet else "")
    return n, head, rest


def finish_text(text: str, fmt: str) -> str:
    """What every report (lint's, diff's, consumers') goes through last: bidi controls and the bytes of a
    non-UTF-8 file name made visible, no line starting a GitHub workflow command (github's own lines aside)."""
    from urdfcheck.core.findings import guard_lines

    json = fmt in ("json", "sarif")
    text = escape_bidi(visible_bytes(text, json=json), json=json)
    return text if fmt == "github" else guard_lines(text)


# A file name that is not UTF-8 reaches us with its bytes as lone surrogates (U+DC80-U+DCFF, Python's
# surrogateescape): no report could be encoded with them. They are shown as `\xff` (in JSON formats escaped again,
# so a parsed string holds the four visible characters).
# (a `\udcXX` escape right after a high one is half of a pair, an ordinary character outside the BMP)
_SURROGATE_JSON_ESCAPE = lazyre.compile(
    r"(?<!\\u[dD][89abAB][0-9a-fA-F]{2})"
    r"(?<!\\)((?:\\\\)*)\\u([dD][cC][89a-fA-F][0-9a-fA-F])")


def visible_bytes(text: str, json: bool = False) -> str:
    if json and "\\u" in text:
        text = _SURROGATE_JSON_ESCAPE.sub(lambda m: m.group(1) + "\\" + _byte(chr(int(m.group(2), 16))), text)
    if not _SURROGATE.search(text):
        return text
    return _SURROGATE.sub(lambda m: ("\\" if json else "") + _byte(m.group(0)), text)
