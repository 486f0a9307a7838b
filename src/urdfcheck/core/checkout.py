"""The checkout a run works in, for showing paths: never the runner's absolute path for a file of the checkout.

Reports show a path relative to the working directory when it lies below it. Run from a package's sub-folder
(`cd launch && urdfcheck lint`), the model lies beside, not below: it is shown as `../urdf/robot.urdf.xacro`,
relative to the working directory, as long as it lies in the same checkout (the nearest folder above holding
`.git`, else the outermost folder above holding a package.xml). Other files keep their absolute path.
"""
from __future__ import annotations

import os

_TOPS: dict[str, str | None] = {}


def top(base: str) -> str | None:
    """The checkout around the folder `base` (absolute), or None when it is in none above it."""
    if base not in _TOPS:
        found, d = None, base
        while True:
            if os.path.exists(os.path.join(d, ".git")):
                found = d
                break
            if os.path.isfile(os.path.join(d, "package.xml")):
                found = d  # keep climbing: the outermost package (a repository of several)
            up = os.path.dirname(d)
            if up == d:
                break
            d = up
        _TOPS[base] = found if found != base else None
    return _TOPS[base]


def relative(p: str, base: str) -> str | None:
    """`p` relative to `base` when both lie in one checkout (p above or beside base), else None."""
    t = top(base)
    if t is not None and (p == t or p.startswith(t.rstrip(os.sep) + os.sep)):
        return os.path.relpath(p, base)
    return None


def around(folder: str) -> str:
    """The checkout holding the folder `folder` (absolute): the nearest folder above holding `.git`, else the
    outermost holding a package.xml, else `folder` itself."""
    return marked(folder) or folder


def marked(folder: str) -> str | None:
    """`around`, or None when no folder at or above `folder` holds `.git` or a package.xml."""
    found = top(folder)
    if found is not None:
        return found
    if os.path.exists(os.path.join(folder, ".git")) or os.path.isfile(os.path.join(folder, "package.xml")):
        return folder
    return None


def run_roots(typed=(), cwd: str | None = None) -> list[str]:
    """The folders a run may read below before any package is resolved (core.door.guarded): the checkout around
    each path the runner typed, and the checkout around the working directory when it lies in one (or when
    nothing is typed). A working directory in no checkout (`/` in a container, a home folder) is no root when
    paths are typed: it would hold every file the checked tree could link to.
    A typed path inside a root adds nothing: its real path must stay inside (a link committed there that leads
    out is refused by the door)."""
    base = os.path.abspath(cwd or os.getcwd())
    typed = [os.path.normpath(os.path.join(base, os.fspath(p))) for p in typed if p]
    here = marked(base)
    roots = [here] if here is not None else ([] if typed else [base])
    for a in typed:
        if any(a == r or a.startswith(r.rstrip(os.sep) + os.sep) for r in roots):
            continue
        folder = a if os.path.isdir(a) else os.path.dirname(a)
        roots.append(around(folder))
    return roots

