"""The one walk over a folder tree (discovery, the planner's workspace pass, package scans).

Depth-first in name order (the same order on every machine), a symbolic link to a folder never entered (a
committed link must not take the walk out of the checkout).

What is skipped is what ROS's own tools skip, by the marker files they read, never by a folder's name (a package
under a plain folder named `build`, `log`, `install` or `venv` is built by colcon, so it is linted; issue 36):
- a folder holding COLCON_IGNORE, AMENT_IGNORE or CATKIN_IGNORE (colcon, ament and catkin skip it; colcon writes
  COLCON_IGNORE into the build, install and log bases it creates: colcon_core verb/build.py `_create_path`,
  location.py `create_log_path`; catkin's CMake writes CATKIN_IGNORE into its build folder);
- hidden folders (.git and the like: colcon's crawl and catkin_pkg skip names starting with a dot);
- outputs of other tools, by the file the tool writes, and only in a folder that is no package (a package.xml
  beside the marker wins, as colcon would build it): a Python venv (`pyvenv.cfg`), a catkin devel or install
  space (`.catkin`, which catkin_pkg's `exclude_subspaces` reads), a `node_modules` folder that npm, yarn or pnpm
  filled (`.package-lock.json`, `.yarn-integrity`, `.modules.yaml`).
The folder a walk starts at is never skipped: the person running the tool named it.
"""
from __future__ import annotations

import operator
import os
from collections.abc import Iterator

SKIP_DIRS: frozenset = frozenset()  # no folder is skipped by its name (kept for importers; see the module doc)
IGNORE_MARKERS = frozenset({"COLCON_IGNORE", "AMENT_IGNORE", "CATKIN_IGNORE"})
OUTPUT_MARKERS = frozenset({"pyvenv.cfg", ".catkin"})
NODE_MARKERS = frozenset({".package-lock.json", ".yarn-integrity", ".modules.yaml"})
MEMO_ENTRIES = 50_000  # entries one run keeps listed (a few MB); a larger tree is listed again where walked again
_NAME = operator.attrgetter("name")
_LISTED: list[dict] = []  # one memo per run in progress (see `remembered`)


class remembered:
    """Within this block each folder is listed once: in a run, consumer discovery walks the model's package and
    the package resolver walks the folder around it, which holds that package again. Outside, every walk lists
    afresh (a long-lived process walks again after edits)."""

    def __enter__(self):
        _LISTED.append({"": 0})

    def __exit__(self, *exc):
        _LISTED.pop()


def forget() -> None:
    """Drop the listings remembered so far (a forked worker whose reads are recorded lists afresh)."""
    for memo in _LISTED:
        memo.clear()
        memo[""] = 0


def run_memo(name: str) -> dict | None:
    """A dict the run in progress keeps under `name` (None outside a run): what it may remember of the file
    system besides listings (packages.real, packages.layout_hits). Dropped with the run, and by `forget`."""
    if not _LISTED:
        return None
    return _LISTED[-1].setdefault((name,), {})  # a tuple: never a folder's path


def run_cached(name: str, key, compute, limit: int = 10_000):
    """compute(), remembered under `key` in the run's memo `name` (at most `limit` entries); computed afresh
    outside a run."""
    memo = run_memo(name)
    if memo is None:
        return compute()
    got = memo.get(key)
    if got is None:
        got = compute()
        if len(memo) < limit:
            memo[key] = got
    return got


def real(path) -> str:
    """os.path.realpath, remembered for the run in progress: the confinement checks and the consumer pairing ask
    about the same package roots, folders and files again and again (an lstat per path component each: a lint
    of one package asked ~230 times about each folder above it). Outside a run, looked up afresh."""
    memo = run_memo("realpath")
    if memo is None:
        return os.path.realpath(os.path.abspath(path))
    got = memo.get(path) if type(path) is str else None  # asked again as it was stored (absolute, normal)
    if got is not None:
        return got
    key = os.path.abspath(path)
    got = memo.get(key)
    if got is None:
        # the folder's real path (remembered: the files of one folder share it), then the last component: an lstat
        # for a file instead of one per component of its path (a corpus-wide name search reads ~400 files)
        head, tail = os.path.split(key)
        if not tail or head == key:
            got = os.path.realpath(key)
        else:
            joined = os.path.join(real(head), tail)
            got = os.path.realpath(joined) if os.path.islink(joined) else joined
        if len(memo) < 50_000:
            memo[key] = got
    return got


def _entries(here: str) -> list[os.DirEntry]:
    memo = _LISTED[-1] if _LISTED else None
    if memo is not None:
        got = memo.get(here)
        if got is not None:
            return got
    with os.scandir(here) as it:
        entries = sorted(it, key=_NAME)
    if memo is not None and memo[""] + len(entries) <= MEMO_ENTRIES:
        memo[""] += len(entries)
        memo[here] = entries
    return entries


def folders(top, *, max_dirs: int | None = None, max_depth: int | None = None
            ) -> Iterator[tuple[str, list[os.DirEntry]]]:
    """(folder, its entries sorted by name) for `top` and every folder below it, parents first; at most
    `max_dirs` folders, `max_depth` levels below `top`. An unreadable folder is skipped."""
    stack = [(os.fspath(top), 0)]
    seen = 0
    while stack:
        if max_dirs is not None and seen >= max_dirs:
            return
        here, depth = stack.pop()
        seen += 1
        try:
            entries = _entries(here)
        except OSError:
            continue
        if depth and skipped(here, entries):
            continue
        yield here, entries
        if max_depth is not None and depth >= max_depth:
            continue
        stack.extend((e.path, depth + 1) for e in reversed(entries)
                     if not e.name.startswith(".") and _is_folder(e))


def skipped(folder: str, entries) -> bool:
    """Does a ROS tool skip `folder` (its entries listed) by a marker file it holds? See the module doc."""
    names = {e.name for e in entries}
    if names & IGNORE_MARKERS:
        return True
    if "package.xml" in names:
        return False
    if names & OUTPUT_MARKERS:
        return True
    return os.path.basename(folder) == "node_modules" and bool(names & NODE_MARKERS)


def _is_folder(e: os.DirEntry) -> bool:
    try:
        return e.is_dir(follow_symlinks=False)
    except OSError:
        return False


def files(entries: list[os.DirEntry]) -> list[str]:
    """The names of the entries that are not folders (what os.walk lists as files: links to folders count as
    folders there, so they are left out here too)."""
    out = []
    for e in entries:
        try:
            if not e.is_dir():
                out.append(e.name)
        except OSError:
            out.append(e.name)
    return out
