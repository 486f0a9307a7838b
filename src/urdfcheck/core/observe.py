"""What a run looked at: every file it opened for reading, every folder it listed, every path it probed.

The lint cache (cli/cache.py) keys a stored report on these: a later run with the same settings replays the
report only when each of them still looks the same (`fingerprint`). Reads are seen through the interpreter's
audit events ("open", "os.listdir", "os.scandir"), so no reader has to take part; existence probes
(`os.path.exists`, `Path.is_file`, `realpath`) go through `os.stat`/`os.lstat`, which have no audit event and
are wrapped while recording. A forked xacro worker records the same way and hands its part back with its result
(`take`, `add`).

Kinds: "r" a file read (its bytes), "l" a folder listed (names and entry types), "p"/"q" a path probed with
stat/lstat (type and size), "m" a module file of the interpreter or an installed package (size and mtime: the
installed code, not the user's tree).

Not recordable (`taint`): a worker that crashed or timed out, a run cut by its time budget: what they would
have read is unknown, so such a run is never stored.
"""
from __future__ import annotations

import os
import stat
import sys

_SEEN: set | None = None
_TAINTED = ""
_LIB: tuple[str, ...] = ()
_STAT = os.stat
_LSTAT = os.lstat
_CWD = ""
_ROOT = [0]  # the process that records (its direct children start afresh: `forked`)


def active() -> bool:
    return _SEEN is not None


def start(library_roots=()) -> None:
    """Record from now on (once per process; audit hooks cannot be removed)."""
    global _SEEN, _LIB, _CWD
    if _SEEN is not None:
        return
    _SEEN = set()
    _ROOT[0] = os.getpid()
    _CWD = os.getcwd()
    roots = {sys.prefix, sys.base_prefix, sys.exec_prefix, getattr(sys, "pycache_prefix", None), *library_roots}
    _LIB = tuple(sorted({os.path.join(os.path.abspath(r), "") for r in roots if r}))
    sys.addaudithook(_hook)
    os.stat = _stat
    os.lstat = _lstat


def taint(why: str = "a worker failed or the time budget ran out") -> None:
    global _TAINTED
    _TAINTED = _TAINTED or why


def tainted() -> str:
    """Why this run must not be stored ("" when it may be)."""
    return _TAINTED


def take() -> list[tuple[str, str]]:
    """What was seen so far, as (kind, absolute path) pairs."""
    return sorted(_SEEN) if _SEEN is not None else []


def installed_modules() -> list[tuple[str, str]]:
    """("m", file) for each loaded module of an installed package (site- or dist-packages). A worker that
    inherited its imports never opened those files, and its result depends on them (xacro, PyYAML, lxml)."""
    out = set()
    for mod in list(sys.modules.values()):
        f = getattr(mod, "__file__", None)
        if isinstance(f, str) and ("site-packages" in f or "dist-packages" in f):
            out.add(("m", os.path.abspath(f)))
    return sorted(out)


def snapshot() -> frozenset | None:
    """What was seen so far (None when not recording), for `restore`."""
    return frozenset(_SEEN) if _SEEN is not None else None


def restore(snap: frozenset | None) -> None:
    """Back to a `snapshot`: a step run in this process as a forked child would be (an expansion in the xacro
    worker) keeps its reads to its own result."""
    if _SEEN is not None and snap is not None:
        _SEEN.clear()
        _SEEN.update(snap)


def forked() -> None:
    """First thing in a forked worker. A child of the recording process starts afresh: what the run saw so far is
    that process's to report, and the child's result then carries only its own part. A child of a worker keeps
    what its parent saw (the xacro and PyYAML modules the spare imported, which nobody else reports)."""
    if _SEEN is not None and os.getppid() == _ROOT[0]:
        _SEEN.clear()


def add(items) -> None:
    """Merge what a worker saw (its result's "observed")."""
    if _SEEN is None or not items:
        return
    try:
        for kind, path in items:
            if kind in KINDS and isinstance(path, str):
                _SEEN.add((kind, path))
    except (TypeError, ValueError):
        taint()


KINDS = frozenset("rlpqm")


_EDITED_FIRST = {"r": 0, "l": 1, "p": 2, "q": 2, "m": 3}


def _order(item) -> tuple:
    """Sort key of a stored [kind, path, fingerprint]: the files read first, the most recently modified of them
    first, then listings and probes, installed modules last: an edit changes one of the first, so a changed record
    is told after few looks, even in a workspace whose record reads thousands of files. A malformed item comes
    before all, so that it is found at once. (The order only decides how soon a change is seen: every item is
    compared all the same when none has changed.)"""
    if not (isinstance(item, list) and item and isinstance(item[0], str)):
        return (-1, 0)
    kind = _EDITED_FIRST.get(item[0], 3)
    if kind == 0 and len(item) > 1 and isinstance(item[1], str):
        try:
            return (0, -_STAT(item[1]).st_mtime_ns)
        except (OSError, ValueError):
            return (-1, 0)  # gone or unreadable: a change, looked at first
    return (kind, 0)


def valid_items(items) -> bool:
    """Whether `items` is a stored record: a list of [kind, absolute path, fingerprint]."""
    return isinstance(items, list) and all(map(_valid_item, items))


def _valid_item(item) -> bool:
    return isinstance(item, list) and len(item) == 3 and all(isinstance(x, str) for x in item) and item[0] in KINDS \
        and os.path.isabs(item[1])


MALFORMED = "\0malformed"  # what `first_change` answers for a record that is not one (never a path: it has a NUL)


def first_change(items, looks: dict, digest) -> str | None:
    """The path of the first item of a stored record that looks different now (in `_order`), None when
    none does, MALFORMED when the record is not one. Items are checked one by one as they are looked at: a miss,
    the common answer, is told after a few looks, without validating the whole record first (a hit must still
    validate it, with its checksum, before anything stored is used). `looks`: (kind, path) -> fingerprint, shared
    by the records a run compares."""
    if not isinstance(items, list):
        return MALFORMED
    for item in sorted(items, key=_order):
        if not _valid_item(item):
            return MALFORMED
        kind, path, fp = item
        now = looks.get((kind, path))
        if now is None:
            now = looks[kind, path] = fingerprint(kind, path, digest)
        if now != fp:
            return path
    return None


_SYSTEM = ("/proc/", "/sys/", "/dev/")  # the kernel's files (a worker reads its own /proc/self/status)


def _path(p) -> str | None:
    if isinstance(p, int) or p is None:
        return None if p is not None else _CWD  # scandir() / listdir() without an argument: the working dir
    try:
        p = os.fsdecode(os.fspath(p))
    except (TypeError, ValueError):
        return None
    return os.path.normpath(os.path.join(_CWD, p))


def _note(kind: str, p) -> None:
    path = _path(p)
    if path is None or _SEEN is None or path.startswith(_SYSTEM):
        return
    if kind == "r" and (path.startswith(_LIB) or path.endswith((".pyc", ".so"))):  # code, not the user's tree
        kind = "m"
    _SEEN.add((kind, path))


def _hook(event: str, args) -> None:
    if event == "open":
        path, mode, flags = args
        if mode is not None:
            if any(c in mode for c in "wax+"):
                return
        elif flags is not None and flags & (os.O_WRONLY | os.O_RDWR | os.O_CREAT):
            return
        _note("r", path)
    elif event == "os.listdir" or event == "os.scandir":
        _note("l", args[0])


def _stat(path, *args, **kwargs):
    if not args and not kwargs.get("dir_fd"):
        _note("p" if kwargs.get("follow_symlinks", True) else "q", path)
    return _STAT(path, *args, **kwargs)


def _lstat(path, *args, **kwargs):
    if not args and not kwargs.get("dir_fd"):
        _note("q", path)
    return _LSTAT(path, *args, **kwargs)


# --- fingerprints: what a path looks like now ------------------------------------------------------------------
def fingerprint(kind: str, path: str, digest) -> str:
    """A short text that changes when what the run saw at `path` changes. `digest(bytes) -> str`."""
    try:
        st = _STAT(path) if kind != "q" else _LSTAT(path)
    except (OSError, ValueError):
        return "-"
    mode = st.st_mode
    if kind == "m":
        return f"{st.st_size}:{st.st_mtime_ns}"
    if kind in ("p", "q"):
        if stat.S_ISLNK(mode):  # where a link points decides what the run may read (the checkout boundary)
            try:
                return "l" + os.readlink(path)
            except OSError:
                return "l?"
        return f"{_type(mode)}{st.st_size if stat.S_ISREG(mode) else ''}"
    if stat.S_ISDIR(mode):
        return "d" + _listing(path, digest)
    if kind == "l":
        return _type(mode)
    if not stat.S_ISREG(mode):
        return _type(mode)
    try:
        from urdfcheck.core import door

        return "f" + digest(door.read_bytes(path, limit=1 << 30))
    except OSError:
        return "?"


def _listing(path: str, digest) -> str:
    try:
        with os.scandir(path) as it:
            names = sorted(f"{e.name}\0{'d' if e.is_dir() else 'l' if e.is_symlink() else 'f'}" for e in it)
    except OSError:
        return "?"
    return digest("\n".join(names).encode("utf-8", "surrogateescape"))


def _type(mode: int) -> str:
    if stat.S_ISREG(mode):
        return "f"
    if stat.S_ISDIR(mode):
        return "d"
    if stat.S_ISLNK(mode):
        return "l"
    return "o"
