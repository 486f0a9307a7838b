"""Inline suppressions written as XML comments.

    <!-- urdfcheck: ignore[J007,I004] reason -->   silences those codes for the next element (and its children)
    <!-- urdfcheck: ignore-file[G001] reason -->    silences those codes for the whole file
"""
from __future__ import annotations

import re
from dataclasses import dataclass

_RE = re.compile(r"urdfcheck:\s*(ignore|ignore-file)\[([A-Za-z0-9_,\s]*)\]")


@dataclass(frozen=True)
class Suppression:
    file: str
    first: int  # first line of the element it covers (0 for the whole file)
    last: int  # last line it covers
    codes: tuple[str, ...]
    comment_line: int


def parse_comment(text: str):
    m = _RE.search(text)
    if not m:
        return None
    codes = tuple(c.strip().upper() for c in m.group(2).split(",") if c.strip())
    return m.group(1), codes


def _last_line(el) -> int:
    last = el.sourceline or 0
    for d in el.iter():
        if d.sourceline and d.sourceline > last:
            last = d.sourceline
    return last


def scan_comments(root) -> list[tuple[int, int, tuple[str, ...], int]]:
    """(first, last, codes, comment_line) for every suppression comment in an lxml tree."""
    from lxml import etree

    out = []
    nodes = list(root.itersiblings(preceding=True)) + [root]
    for top in nodes:
        for c in top.iter(etree.Comment) if isinstance(top.tag, str) else [top]:
            if not isinstance(c, etree._Comment):
                continue
            parsed = parse_comment(c.text or "")
            if parsed is None:
                continue
            kind, codes = parsed
            if kind == "ignore-file":
                out.append((0, 10**9, codes, c.sourceline))
                continue
            target = c.getnext()
            while target is not None and not isinstance(target.tag, str):
                target = target.getnext()
            if target is None:
                continue
            out.append((target.sourceline, _last_line(target), codes, c.sourceline))
    return out
