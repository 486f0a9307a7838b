"""Which ROS distribution a workspace is built for, read from its files (never by running anything, never git):
a `ROS_DISTRO` (or `ros_distro`/`rosdistro`) in CI files (.github/workflows/*.yml, .gitlab-ci.yml), `FROM ros:<d>`
(or osrf/ros:<d>-...) in Dockerfiles, `version: <d>` in .repos files, and the branch named in .git/HEAD
(`humble`, `humble-devel`, `ros2-humble`). The folders from the model's up to the repository root (the folder
with .git) are read; when several distributions are named (a CI matrix), the oldest is the one the model must
load on. `None` when nothing names one: the caller assumes Humble (ROS 2) or Noetic (catkin) and says so.
"""
from __future__ import annotations

import functools
import glob
import os
import re

from urdfcheck.core import lazyre

ROS2 = ("humble", "jazzy", "kilted", "rolling")  # oldest first: the strictest urdfdom is the oldest
DISTROS = ("noetic",) + ROS2
_NAME = "|".join(DISTROS)
_CI = lazyre.compile(rf"\b(?:ROS_DISTRO|ros_distro|rosdistro|ROS_DISTRIBUTION)\b\s*[:=]\s*\[?\s*[\"']?({_NAME})\b")
_CI_LIST = lazyre.compile(r"\b(?:ROS_DISTRO|ros_distro|rosdistro)\b\s*:\s*\[([^\]]*)\]")
_DOCKER = lazyre.compile(rf"^\s*FROM\s+(?:\S+/)?(?:ros|ros2)?:?({_NAME})\b|^\s*FROM\s+\S*ros\S*:({_NAME})\b",
                         re.M | re.I)
_REPOS = lazyre.compile(rf"^\s*version:\s*[\"']?(?:ros2-)?({_NAME})(?:-devel)?[\"']?\s*$", re.M)
_HEAD = lazyre.compile(rf"ref:\s*refs/heads/(?:.*[/-])?({_NAME})(?:[-/].*)?\s*$")
LIMIT = 256 * 1024
MAX_FILES = 40


def _read(path: str) -> str:
    from urdfcheck.core import door

    try:
        return door.read_text(path, limit=LIMIT)
    except (OSError, ValueError):
        return ""


def _found_in(folder: str) -> list[tuple[str, str]]:
    """(distribution, file) named by the files of one folder."""
    out = []
    ci = sorted(glob.glob(os.path.join(folder, ".github", "workflows", "*.y*ml")))[:MAX_FILES]
    ci += [p for p in (os.path.join(folder, ".gitlab-ci.yml"),) if os.path.isfile(p)]
    for path in ci:
        text = _read(path)
        for m in _CI_LIST.finditer(text):
            out += [(d, path) for d in re.findall(rf"\b({_NAME})\b", m.group(1))]
        out += [(m.group(1), path) for m in _CI.finditer(text)]
    for path in sorted(glob.glob(os.path.join(folder, "Dockerfile*")) +
                       glob.glob(os.path.join(folder, "docker", "Dockerfile*")))[:MAX_FILES]:
        out += [(m.group(1) or m.group(2), path) for m in _DOCKER.finditer(_read(path))]
    for path in sorted(glob.glob(os.path.join(folder, "*.repos")))[:MAX_FILES]:
        out += [(m.group(1), path) for m in _REPOS.finditer(_read(path))]
    head = os.path.join(folder, ".git", "HEAD")
    if os.path.isfile(head):  # a text file: read, never `git`
        m = _HEAD.search(_read(head))
        if m:
            out.append((m.group(1), head))
    return out


def workspace_distro(folder: str) -> tuple[str, str] | None:
    """(distribution, why) for a model in `folder`, or None."""
    return _workspace_distro(os.path.abspath(folder), os.getcwd())


@functools.lru_cache(maxsize=256)
def _workspace_distro(folder: str, cwd: str) -> tuple[str, str] | None:
    here = folder
    # up to the repository root (.git); without one, not above the working directory (or the model's own folder
    # when it lies outside it): the machine's other files say nothing about this workspace
    inside = here == cwd or here.startswith(cwd.rstrip(os.sep) + os.sep)
    stop = cwd if inside else here
    for _ in range(12):
        found = [(d, p) for d, p in _found_in(here) if d in DISTROS]
        if found:
            ros2 = [f for f in found if f[0] in ROS2]
            d, path = min(ros2 or found, key=lambda f: DISTROS.index(f[0]))
            names = sorted({f[0] for f in found}, key=DISTROS.index)
            rel = os.path.relpath(path, cwd) if path.startswith(cwd.rstrip(os.sep) + os.sep) else path
            extra = f" (of {', '.join(names)}: the oldest)" if len(names) > 1 else ""
            return d, f"{d} named in {rel}{extra}"
        if os.path.exists(os.path.join(here, ".git")):  # a folder, or a file in a git worktree
            break  # the repository's root: above it is someone else's
        if here == stop and not _repository_above(here):
            break
        up = os.path.dirname(here)
        if up == here:
            break
        here = up
    return None


def _repository_above(folder: str) -> bool:
    """Is `folder` inside a git checkout (a .git in an ancestor, at most 12 levels up)?"""
    here = folder
    for _ in range(12):
        up = os.path.dirname(here)
        if up == here:
            return False
        here = up
        if os.path.exists(os.path.join(here, ".git")):  # a folder, or a file in a git worktree
            return True
    return False
