"""How reports and messages show a path: the one helper, `shown(path, root)`.

A path below the root (default: the root of the run in progress, else the working directory) is relative to
it. A path beside it (a bringup package's model in a sibling folder) is relative too, with `..`, when both sit
in the same top-level folder: a runner's absolute path never reaches a pull request's annotations. Anything
else (/opt/ros/...) stays absolute. Messages are built with shown paths; nothing rewrites them afterwards.
"""
from __future__ import annotations

import os
from contextlib import contextmanager
from functools import lru_cache

_root: str | None = None  # the root of the run in progress (`showing`)


def shown(path, root: str | None = None) -> str:
    text = os.fspath(path) if not isinstance(path, str) else path
    if not text or text.startswith("<"):  # "<string>", "<stdin>": no file
        return text
    base = root or _root
    # the working directory only where it matters (one that was removed still shows absolute paths)
    cwd = "" if os.path.isabs(text) and base and os.path.isabs(base) else os.getcwd()
    return _shown(text, base, cwd)


@lru_cache(maxsize=1024)  # a broken large model has thousands of findings in one file
def _shown(text: str, root: str | None, cwd: str) -> str:
    p = os.path.join(cwd, text) if not os.path.isabs(text) else text
    p = os.path.normpath(p)
    base = os.path.normpath(os.path.join(cwd, root or cwd))
    rel = os.path.relpath(p, base)
    if rel != ".." and not rel.startswith(".." + os.sep):
        return rel
    top = p.split(os.sep)[1:2]
    return rel if top and top == base.split(os.sep)[1:2] and top != [""] else p


def showing_root() -> str | None:
    """The root a `showing` block set (None: the working directory): what a worker process is handed."""
    return _root


def root() -> str:
    """The folder paths are shown relative to: the run's root, else the working directory."""
    return os.path.abspath(_root or os.getcwd())


@contextmanager
def showing(root_folder: str | None):
    """Paths shown relative to `root_folder` (None or "": the working directory) while the block runs."""
    global _root
    before, _root = _root, (os.path.abspath(root_folder) if root_folder else None)
    try:
        yield
    finally:
        _root = before
