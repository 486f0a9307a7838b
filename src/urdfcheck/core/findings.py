"""Findings: what every stage of the pipeline hands to the reports."""
from __future__ import annotations

import enum
import os
import re

from urdfcheck.core import lazyre
from urdfcheck.core.records import TupleRecord


class Severity(enum.IntEnum):
    INFO = 1
    WARNING = 2
    ERROR = 3

    @classmethod
    def parse(cls, text: str) -> Severity:
        try:
            return cls[text.strip().upper()]
        except KeyError:
            raise ValueError(f"unknown severity {text!r} (use error, warning or info)") from None

    def __str__(self) -> str:
        return self.name.lower()


class Location(TupleRecord):
    """Where something was written. `via` holds the xacro macro call sites, innermost first."""

    file: str
    line: int | None = None
    column: int | None = None
    via: tuple[Location, ...] = ()

    def shown(self, root: str | None = None) -> Location:
        """This location with its files as reports show them (`core.paths.shown`)."""
        from urdfcheck.core.paths import shown

        file = shown(self.file, root) if os.path.isabs(self.file) else self.file
        return Location(file, self.line, self.column, tuple(v.shown(root) for v in self.via))

    def __str__(self) -> str:
        out = self.file
        if self.line:
            out += f":{self.line}"
            if self.column:
                out += f":{self.column}"
        return out


class Place(TupleRecord):
    """One model (and variant) a collapsed finding applies to; `message` when it reads differently there
    (a macro used with another prefix names other links)."""

    model: str
    variant: str = ""
    message: str = ""
    via: tuple = ()  # the macro call chain of this instance (Location.via), when it has one


class Also(TupleRecord):
    """Another line of the same file where the same problem is written again (finish/collapse.py)."""

    location: Location
    message: str


class Finding(TupleRecord):
    code: str
    severity: Severity
    message: str
    location: Location
    name: str = ""  # rule name (kebab-case), for reports
    related: tuple[Location, ...] = ()
    model: str = ""  # the entry model the finding came from
    variant: str = ""  # xacro argument set name, when several were linted
    # every model/variant the same problem was found in, when several (finish/collapse.py); () means just
    # `model`/`variant` above, which are always the first of them
    where: tuple[Place, ...] = ()
    # the same problem at other lines of the same file, in the same models/variants (twelve joints named like
    # their links, six joints with effort 0): one line in the reports, each place kept here
    also: tuple[Also, ...] = ()
    # the consumer profile (rules/checks/profiles) the finding predicts a behaviour of: "mujoco", "gazebo"... or ""
    profile: str = ""
    # the planning steps the finding rests on (core.evidence.Step): how its model, deployment, parameter files
    # and features were chosen; a finding with a step that is a guess is said at info (rules.engine)
    evidence: tuple = ()
    # every active profile whose consumer the finding concerns (`profile` is the first): two roots are refused by
    # Pinocchio, Gazebo, KDL and PyBullet alike, and `--profile gazebo,kdl` says so for both
    profiles: tuple = ()

    def places(self) -> tuple[Place, ...]:
        return self.where or (Place(self.model, self.variant),)

    def sort_key(self):
        loc = self.location
        return (loc.file, loc.line or 0, loc.column or 0, self.code, self.message, self.variant)


# CSI sequences and OSC strings (OSC 52 writes the clipboard, OSC 8 makes links) go whole, payload included; then
# every C0/C1 control character
_CONTROL = lazyre.compile(r"\x1b\[[0-9;?]*[ -/]*[@-~]|\x1b\][^\x07\x1b\x9c]*(?:\x07|\x1b\\|\x9c)?"
                          r"|[\x00-\x08\x0b-\x1f\x7f-\x9f]")
# Azure Pipelines reads `##vso[` anywhere in a line and `##[` formatting commands; GitHub reads `::` only where a line
# starts (after blanks): that one is defused at the start of the text here and in report/github.py, so
# `gz::sim::systems::DiffDrive` stays copyable everywhere else
_WORKFLOW = lazyre.compile(r"##vso\[|##\[")
_LINE_COMMAND = lazyre.compile(r"^(\s*):(?=:)", re.M)  # blanks as .NET's TrimStart sees them
MAX_TEXT = 500


def clean_text(text: object, limit: int = MAX_TEXT) -> str:
    """Make text from an untrusted model safe to print in any report format.

    Strips ANSI escapes and control characters, defuses CI workflow commands (`##vso[`, and `::` where it would
    start a line: `::error`), and truncates absurdly long values.
    """
    s = str(text)
    if len(s) > 4 * limit + 64:  # a 60 MB joint name from a recording: cut before the expressions run over it
        s = s[: 4 * limit + 64]
    s = _CONTROL.sub("", s.replace("\n", " ").replace("\t", " "))
    s = _WORKFLOW.sub(lambda m: m.group(0)[0] + "\u200b" + m.group(0)[1:], s)
    s = guard_lines(s)
    if _SURROGATE.search(s):  # a file name that is not UTF-8 (surrogateescape): its bytes as `\xff`
        s = _SURROGATE.sub(lambda m: show_byte(m.group(0)), s)
    if len(s) > limit:
        s = s[: limit - 1] + "\u2026"
    return s


_SURROGATE = lazyre.compile("[\ud800-\udfff]")


def show_byte(ch: str) -> str:
    """A lone surrogate as text: `\\xff` for a byte that surrogateescape kept, else `\\udXXX`."""
    n = ord(ch)
    return f"\\x{n - 0xdc00:02x}" if 0xdc80 <= n <= 0xdcff else f"\\u{n:04x}"


def guard_lines(text: str) -> str:
    """No line of `text` starts (after blanks) with `::`, the start of a GitHub workflow command: a zero-width space
    goes between the colons there, nowhere else."""
    return _LINE_COMMAND.sub("\\1:\u200b", text) if "::" in text else text


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


class Problem:
    """What a check yields. The engine turns it into a Finding; a check never computes file/line.

    `at` is a model part (anything with a `.loc` Location) or a Location; `related` likewise.
    `severity` None means the catalogue default; `code` is for checks that serve several codes.
    `absent`: the problem claims that nothing supplies something (what might: "publish them"); the engine
    keeps its severity only where the consumers understood everything that could supply it (issue 20).
    `rests_on`: the planning steps (core.evidence.Step) the check used beyond the target's own (a parameter
    file's pairing with the model, the feature taken as the wheel); the engine says the problem at info when
    one of them, or of the target's, is a guess (issue 37).
    """

    __slots__ = ("message", "at", "related", "severity", "code", "data", "absent", "rests_on")

    def __init__(self, message: str, at: object = None, related: tuple = (), severity: Severity | None = None,
                 code: str | None = None, data: dict | None = None, absent: str | None = None,
                 rests_on: tuple = ()):
        self.absent = absent
        self.rests_on = tuple(rests_on)
        self.message = message
        self.at = at
        self.related = related
        self.severity = severity
        self.code = code
        self.data = {} if data is None else data

    def __repr__(self) -> str:
        return f"Problem({self.code or ''} {self.message!r})"


# "Did you mean" compares a name with every option: a model with thousands of links and as many dangling
# references would spend minutes on hints alone. A run (`reset_hints`) compares at most this many candidates
# from the model's names (a fraction of a second); past it, findings come without hints, the same ones on every
# run of the same input. A small set (the grammar's names, a rule's options) costs little and is not counted.
HINT_CANDIDATES = 100_000
SMALL_SET = 64
_hints_left = [HINT_CANDIDATES]


def reset_hints() -> None:
    _hints_left[0] = HINT_CANDIDATES


def closest(word: str, options, cutoff: float = 0.75) -> str | None:
    """The option most like `word` (for "did you mean"), or None (also once the run's hints are spent)."""
    options = list(options)
    if len(options) > SMALL_SET:
        if len(options) > _hints_left[0]:
            return None
        _hints_left[0] -= len(options)
    # difflib indexes `word` first, in time and memory linear in its length: a 48 MB joint name in a recording
    # took 14 s and 2 GB. An option whose length is too far from the word's cannot reach the cutoff (difflib's own
    # first test, real_quick_ratio, is this bound): those go first, and with them every hint for such a word.
    n = len(word)
    options = [o for o in options if (2.0 * min(n, len(o)) / (n + len(o)) if n + len(o) else 1.0) >= cutoff]
    if not options:
        return None
    import difflib  # only when something is misspelt: its import costs more than most lint runs spend here

    close = difflib.get_close_matches(word, options, n=1, cutoff=cutoff)
    return close[0] if close else None
