"""The files of a git revision, written into a temporary folder outside the user's tree, for `urdfcheck diff --git`.

Read with `git ls-tree` and `git cat-file --batch` (what `git show REV:PATH` prints, for many files in one
process): no checkout, no change to the index or the working tree, no network. Symbolic links and submodules
are not written (a link could point anywhere on the machine); files above `MAX_FILE` bytes are written empty
(a mesh's existence is all a comparison of descriptions needs).
"""
from __future__ import annotations

import os
import subprocess
import tempfile

from urdfcheck.request.request import UsageError

MAX_FILE = 8 * 1024 * 1024
MAX_FILES = 50_000
# git without the user's or the system's hooks, pagers, prompts, fsmonitor or filters: plain object reads
_GIT = ("git", "-c", "core.fsmonitor=false", "-c", "core.hooksPath=/dev/null", "--no-pager")


def _env() -> dict:
    env = {k: v for k, v in os.environ.items() if not k.startswith("GIT_")}
    env.update(GIT_TERMINAL_PROMPT="0", GIT_CONFIG_NOSYSTEM="1", GIT_OPTIONAL_LOCKS="0")
    return env


def _git(args, cwd: str, data: bytes | None = None) -> bytes:
    try:
        p = subprocess.run([*_GIT, *args], cwd=cwd, input=data, capture_output=True, env=_env(), timeout=120)
    except FileNotFoundError:
        raise UsageError("--git: git is not installed") from None
    except subprocess.TimeoutExpired:
        raise UsageError(f"--git: git {args[0]} took too long") from None
    if p.returncode != 0:
        msg = p.stderr.decode("utf-8", "replace").strip().splitlines()
        raise UsageError(f"--git: {msg[-1] if msg else 'git ' + args[0] + ' failed'}")
    return p.stdout


def repo_root(path: str) -> str:
    return _git(["rev-parse", "--show-toplevel"], path).decode().strip()


def export(rev: str, repo: str) -> tempfile.TemporaryDirectory:
    """A temporary folder holding the tree of `rev` (the whole repository: a model includes its sibling
    packages). The caller removes it (a context manager)."""
    if rev.startswith("-"):
        raise UsageError(f"--git: {rev!r} is not a revision")
    commit = _git(["rev-parse", "--verify", "--quiet", "--end-of-options", f"{rev}^{{commit}}"], repo).decode().strip()
    listing = _git(["ls-tree", "-r", "-z", "--full-tree", commit], repo)
    entries = []
    for rec in listing.split(b"\0"):
        if not rec:
            continue
        meta, _, path = rec.partition(b"\t")
        mode, kind, sha = meta.split()
        if kind != b"blob" or mode == b"120000":  # submodules, symbolic links: not written
            continue
        entries.append((path.decode("utf-8", "surrogateescape"), sha.decode()))
        if len(entries) > MAX_FILES:
            raise UsageError(f"--git: more than {MAX_FILES} files in {rev}")
    sizes = _git(["cat-file", "--batch-check=%(objectsize)"], repo,
                 "".join(f"{sha}\n" for _, sha in entries).encode()).split()
    small = [(p, sha) for (p, sha), n in zip(entries, sizes) if int(n) <= MAX_FILE]
    out = tempfile.TemporaryDirectory(prefix="urdfcheck-diff-")
    try:
        data = _git(["cat-file", "--batch"], repo, "".join(f"{sha}\n" for _, sha in small).encode())
        blobs, pos = {}, 0
        for _, sha in small:
            end = data.index(b"\n", pos)
            size = int(data[pos:end].split()[2])
            blobs[sha] = data[end + 1:end + 1 + size]
            pos = end + 1 + size + 1
        for path, sha in entries:
            if os.path.isabs(path) or ".." in path.split("/"):
                continue
            dest = os.path.join(out.name, path)
            os.makedirs(os.path.dirname(dest), exist_ok=True)
            with open(dest, "wb") as f:
                f.write(blobs.get(sha, b""))
    except BaseException:
        out.cleanup()
        raise
    return out
