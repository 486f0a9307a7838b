"""Inline suppressions written as XML comments.

    <!-- urdfcheck: ignore[J007,I004] reason -->   silences those codes for the next element (and its children)
    <!-- urdfcheck: ignore-file[G001] reason -->    silences those codes for the whole file
"""
from __future__ import annotations

from urdfcheck.core import lazyre
from urdfcheck.core.records import TupleRecord

_RE = lazyre.compile(r"urdfcheck:\s*(ignore|ignore-file)\[([A-Za-z0-9_,\s]*)\]")


class Suppression(TupleRecord):
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
    from urdfcheck.core.lxmlimport import etree

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


# --- YAML files (controller/driver parameters that contract findings point into) -------------------
#
#     # urdfcheck: ignore[C001] reason        on its own line: the next content line and the block under it
#     joints: [a, b]  # urdfcheck: ignore[C001] reason    trailing: that line and the block under it
#     # urdfcheck: ignore-file[C010] reason   anywhere: the whole file
#
# The engine reads a YAML file's suppressions lazily (only when a finding points into it) and caches
# them per (path, mtime, size); see `yaml_suppressions`. Unused YAML suppressions are not reported
# as R002, because a YAML file is only read when a finding points into it.

YAML_SUFFIXES = (".yaml", ".yml")


def _yaml_comment(line: str) -> int:
    """Index of the `#` that starts a comment on a YAML line, or -1 (quotes are respected)."""
    quote = None
    i = 0
    while i < len(line):
        ch = line[i]
        if quote == "'":
            if ch == "'":
                if i + 1 < len(line) and line[i + 1] == "'":
                    i += 1
                else:
                    quote = None
        elif quote == '"':
            if ch == "\\":
                i += 1
            elif ch == '"':
                quote = None
        elif ch in "'\"" and (i == 0 or line[i - 1] in " \t[{,:-?"):
            quote = ch
        elif ch == "#" and (i == 0 or line[i - 1] in " \t"):
            return i
        i += 1
    return -1


def _indent(line: str) -> int:
    return len(line) - len(line.lstrip(" "))


def scan_yaml_comments(text: str) -> list[tuple[int, int, tuple[str, ...], int]]:
    """(first, last, codes, comment_line) for every `# urdfcheck: ignore[...]` comment in YAML text.

    Same tuples as `scan_comments`: lines are 1-based; `first == 0` means the whole file. A comment on
    its own line covers the next content line, a trailing comment its own line; either way the block
    below that line (following lines indented deeper, blank and comment lines included) is covered too.
    """
    lines = text.splitlines()
    # per line: (is content, indent, comment text)
    info = []
    for raw in lines:
        pos = _yaml_comment(raw)
        body = raw if pos < 0 else raw[:pos]
        comment = "" if pos < 0 else raw[pos + 1:]
        content = body.strip() not in ("", "---", "...")
        info.append((content, _indent(body.replace("\t", " ")), comment))

    def block_end(start: int) -> int:
        """Last line (0-based) of the block that starts at content line `start`."""
        base = info[start][1]
        pos = _yaml_comment(lines[start])
        opens = (lines[start] if pos < 0 else lines[start][:pos]).rstrip().endswith(":")
        last = start
        for k in range(start + 1, len(lines)):
            content, ind, _ = info[k]
            if not content:
                continue
            # `key:` may hold a sequence written at its own indent ("key:\n- a\n- b")
            same_level_item = opens and ind == base and lines[k].lstrip(" ").startswith("-")
            if ind <= base and not same_level_item:
                break
            last = k
        return last

    out = []
    for i, (content, _ind, comment) in enumerate(info):
        if not comment:
            continue
        parsed = parse_comment(comment)
        if parsed is None:
            continue
        kind, codes = parsed
        if kind == "ignore-file":
            out.append((0, 10**9, codes, i + 1))
            continue
        target = i if content else next((k for k in range(i + 1, len(info)) if info[k][0]), None)
        if target is None:
            continue
        out.append((target + 1, block_end(target) + 1, codes, i + 1))
    return out


_YAML_CACHE: dict = {}


def _cached(cache: dict, file: str, scan) -> list[Suppression]:
    """`scan(data)`'s suppressions of `file`, read once per (path, mtime, size): an edited file is read again.
    An unreadable file, or one `scan` cannot read, suppresses nothing."""
    import os

    try:
        st = os.stat(file)
    except OSError:
        return []
    key = (file, st.st_mtime_ns, st.st_size)
    hit = cache.get(key)
    if hit is None:
        try:
            from urdfcheck.core import door

            found = scan(door.read_bytes(file, limit=16 * 1024 * 1024)[:16 * 1024 * 1024])
        except Exception:  # noqa: BLE001 - see above
            found = []
        hit = [Suppression(file, a, b, c, d) for a, b, c, d in found]
        if len(cache) > 256:
            cache.clear()
        cache[key] = hit
    return hit


def yaml_suppressions(file: str) -> list[Suppression]:
    """Suppressions written in the YAML file `file` (a finding's `Location.file`)."""
    return _cached(_YAML_CACHE, file, lambda data: scan_yaml_comments(data.decode("utf-8", "replace")))


def is_yaml(file: str) -> bool:
    return file.lower().endswith(YAML_SUFFIXES)


# --- SRDF files (MoveIt semantic descriptions that M findings point into) --------------------------
#
#     <!-- urdfcheck: ignore[M003] reason -->   before an element: that element
#     <!-- urdfcheck: ignore-file[M011] -->     anywhere: the whole file
#
# Read like YAML files: lazily, when a finding points into the file, cached per (path, mtime, size).

SRDF_SUFFIXES = (".srdf", ".srdf.xacro")
_SRDF_CACHE: dict = {}


def is_srdf(file: str) -> bool:
    return file.lower().endswith(SRDF_SUFFIXES)


def srdf_suppressions(file: str) -> list[Suppression]:
    """Suppressions written as XML comments in the SRDF `file` (a finding's `Location.file`). A malformed file has
    none."""
    from urdfcheck.core import xmlfront

    return _cached(_SRDF_CACHE, file, lambda data: scan_comments(xmlfront.parse(data)[0]))
