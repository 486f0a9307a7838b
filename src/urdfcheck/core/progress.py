"""One status line on stderr while a long lint runs: targets done of planned, and the one being checked.

Only on a terminal (never in a log or a pipe), not with --quiet, and only once the run has lasted `DELAY`
seconds: a short run prints nothing. The line is erased before the report is written.
"""
from __future__ import annotations

import os
import time

DELAY = 0.5
INTERVAL = 0.1

_LINE = None


class _Line:
    def __init__(self, stream):
        self.stream = stream
        self.start = time.monotonic()
        self.last = 0.0
        self.shown = False

    def step(self, done: int, total: int, label: str) -> None:
        now = time.monotonic()
        if now - self.start < DELAY or now - self.last < INTERVAL:
            return
        self.last = now
        try:
            width = os.get_terminal_size(self.stream.fileno()).columns
        except (AttributeError, OSError, ValueError):
            width = 0
        if width <= 0:  # not a terminal after all, or one whose size nobody set (`script`, some CI ptys)
            width = 80
        # the label is a file name from the checkout: no escape sequence of it reaches the terminal (OSC 52 would
        # write the clipboard, OSC 8 make a link), no bidi control reorders the line
        from urdfcheck.core.findings import clean_text, escape_bidi

        text = f"urdfcheck: {done}/{total} checked; {escape_bidi(clean_text(label, 4096))}"
        if len(text) > width - 1:
            text = text[:max(0, width - 2)] + "…"
        self.stream.write("\r" + text + "\x1b[K")
        self.stream.flush()
        self.shown = True

    def close(self) -> None:
        if self.shown:
            self.stream.write("\r\x1b[K")
            self.stream.flush()


def to_terminal(stream) -> None:
    """Show progress on `stream` if it is a terminal (None: never). A stream that copies what it is given
    (the lint cache's) is passed by its `untee`: progress is not part of the output."""
    global _LINE
    stream = getattr(stream, "untee", stream)
    try:
        tty = stream is not None and stream.isatty()
    except (AttributeError, ValueError, OSError):
        tty = False
    _LINE = _Line(stream) if tty else None


_BEFORE = 0  # targets of an earlier pass of the same run, counted in front of this pass's


def step(done: int, total: int, label: str) -> None:
    if _LINE is not None:
        _LINE.step(_BEFORE + done, _BEFORE + total, label)


class after:
    """A later pass of the same run (the libraries no model included) counts on from the `done` targets of the
    earlier one instead of starting again at 0."""

    def __init__(self, done: int):
        self.done = done

    def __enter__(self):
        global _BEFORE
        self.saved, _BEFORE = _BEFORE, self.done

    def __exit__(self, *exc):
        global _BEFORE
        _BEFORE = self.saved


def close() -> None:
    global _LINE
    if _LINE is not None:
        _LINE.close()
    _LINE = None
