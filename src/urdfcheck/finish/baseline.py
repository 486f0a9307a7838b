"""Baselines: accept today's findings, fail only on new ones.

    urdfcheck lint --write-baseline urdfcheck-baseline.json     # record (exit 0)
    urdfcheck lint --baseline urdfcheck-baseline.json           # fail only on findings not recorded

A finding is keyed WITHOUT its line number, so inserting or moving lines elsewhere keeps the baseline valid:

* ``code``;
* ``file``: relative to the baseline file's folder, forward slashes (so the baseline works from any working
  directory and on any OS);
* ``message``: with embedded line references (``line 12``, ``a.xacro:12``) normalised to ``N``;
* ``context``: a short hash of the *content* of the source line the finding points at (whitespace
  squeezed) and of the xacro call-site lines in ``Location.via``, so that two identical messages from
  different elements, or from two calls of one macro, are told apart;
* ``count``: how many findings share that key (a third identical finding is new).

Matching is in two passes: first on the full key, then, for what is left, on (code, file, message) alone,
so a finding whose line was merely reformatted stays accepted while the total count still cannot grow.
"""
from __future__ import annotations

import hashlib
import json
import os
import re
from collections import Counter

from urdfcheck.core import lazyre
from urdfcheck.core.findings import Finding

VERSION = 1

_LINE_REF = lazyre.compile(r"\b(lines?)\s+\d+(\s*(?:-|–|to|and)\s*\d+)?", re.IGNORECASE)
_FILE_LINE = lazyre.compile(r"((?:\.[A-Za-z0-9_]+)|\]):\d+(?::\d+)?")


def normalise_message(message: str) -> str:
    """The message without line numbers (they change whenever lines move)."""
    s = _LINE_REF.sub(lambda m: m.group(1) + " N", message)
    return _FILE_LINE.sub(lambda m: m.group(1) + ":N", s)


def portable_path(file: str, base: str | None = None) -> str:
    """`file` relative to the folder `base` (when given and possible), with forward slashes."""
    p = file
    if base is not None and file:
        try:
            p = os.path.relpath(os.path.abspath(file), os.path.abspath(base))
        except ValueError:  # another drive on Windows
            p = file
    return p.replace(os.sep, "/")


_LINES_CACHE: dict[str, list[str]] = {}


def _source_line(file: str, line: int | None) -> str:
    if not line:
        return ""
    lines = _LINES_CACHE.get(file)
    if lines is None:
        try:
            from urdfcheck.core import door

            data = door.read_bytes(file, limit=64 * 1024 * 1024)[:64 * 1024 * 1024]
            lines = data.decode("utf-8", "replace").splitlines()
        except OSError:
            lines = []
        _LINES_CACHE[file] = lines
    if 0 < line <= len(lines):
        return " ".join(lines[line - 1].split())
    return ""


def context(f: Finding) -> str:
    """Hash of the source text the finding points at (its line and its macro call-site lines)."""
    parts = [_source_line(f.location.file, f.location.line)]
    parts += [_source_line(v.file, v.line) for v in f.location.via]
    return hashlib.sha256("\n".join(parts).encode("utf-8", "surrogateescape")).hexdigest()[:16]


def key(f: Finding, base: str | None = None) -> tuple[str, str, str, str]:
    return (f.code, portable_path(f.location.file, base), normalise_message(f.message), context(f))


def _base_of(path: str) -> str:
    return os.path.dirname(os.path.abspath(path))


def as_dict(findings: list[Finding], base: str | None = None) -> dict:
    _LINES_CACHE.clear()
    counts = Counter(key(f, base) for f in findings)
    entries = [{"code": c, "file": p, "message": m, "context": h, "count": n}
               for (c, p, m, h), n in sorted(counts.items())]
    return {"version": VERSION, "tool": "urdfcheck", "findings": entries}


def write(path: str, findings: list[Finding]) -> None:
    """Write `findings` as a baseline to `path` (deterministic, sorted: diffs stay small)."""
    data = as_dict(findings, _base_of(path))
    text = json.dumps(data, indent=2, sort_keys=True, ensure_ascii=False) + "\n"
    try:
        text.encode("utf-8")
    except UnicodeEncodeError:  # a file name that is not UTF-8: as `\udcff` escapes, read back as the same key
        text = json.dumps(data, indent=2, sort_keys=True) + "\n"
    with open(path, "w", encoding="utf-8") as f:
        f.write(text)


MAX_BYTES = 64 * 1024 * 1024


def load(path: str) -> Counter:
    """Counter of keys in a baseline file. Raises OSError or ValueError, whose messages never quote the file:
    it may be a link a pull request pointed at a secret (refused when it leaves the working directory), a FIFO
    (refused, never waited on), too large, or nested to exhaust the parser."""
    from urdfcheck.core import door
    from urdfcheck.load.packages import leaves_cwd

    if leaves_cwd(path):
        raise ValueError("it is a link that leads out of the working directory; refused")
    raw = door.read_bytes(path, limit=MAX_BYTES)
    if len(raw) > MAX_BYTES:
        raise ValueError(f"larger than {MAX_BYTES // 2**20} MiB; refused")
    try:
        data = json.loads(raw.decode("utf-8"))
    except RecursionError:
        raise ValueError("nested too deeply; not a urdfcheck baseline") from None
    except (UnicodeDecodeError, json.JSONDecodeError) as e:
        raise ValueError(f"not JSON (line {getattr(e, 'lineno', '?')}); not a urdfcheck baseline") from None
    if not isinstance(data, dict) or data.get("version") != VERSION or not isinstance(data.get("findings"), list):
        raise ValueError(f"not a urdfcheck baseline (version {VERSION})")
    budget: Counter = Counter()
    for i, e in enumerate(data["findings"]):
        try:
            k = (str(e["code"]), str(e["file"]), str(e["message"]), str(e.get("context", "")))
            n = int(e.get("count", 1))
        except (KeyError, TypeError, ValueError, AttributeError, RecursionError):
            raise ValueError(f"malformed baseline entry {i + 1} (entries are code, file, message, context, "
                             "count)") from None
        budget[k] += max(n, 0)
    return budget


def filter_new(path: str, findings: list[Finding]) -> list[Finding]:
    """The findings that the baseline at `path` does not account for (order preserved)."""
    budget = load(path)
    _LINES_CACHE.clear()
    base = _base_of(path)
    keys = [key(f, base) for f in findings]
    matched = [False] * len(findings)
    for i, k in enumerate(keys):  # pass 1: exact key (content hash included)
        if budget[k] > 0:
            budget[k] -= 1
            matched[i] = True
    loose: Counter = Counter()
    for (c, p, m, _h), n in budget.items():
        if n > 0:
            loose[(c, p, m)] += n
    for i, k in enumerate(keys):  # pass 2: the element's line changed, the finding did not
        if not matched[i] and loose[k[:3]] > 0:
            loose[k[:3]] -= 1
            matched[i] = True
    return [f for f, m in zip(findings, matched) if not m]
