"""Files of the user's lint cache folder: a digest, the versions kept under a key, whole-file reads and atomic writes.

Shared by the report cache (cli/cache.py) and the expansions a miss reuses (load/reuse.py). Entries are JSON
written to a temporary file and renamed into place, so a parallel run sees the old entry or the new one.
"""
from __future__ import annotations

import os


def digest(data: bytes) -> str:
    try:
        from _blake2 import blake2b  # hashlib would load OpenSSL first: 7 ms at every start
    except ImportError:  # pragma: no cover - an interpreter without it
        from hashlib import blake2b
    return blake2b(data, digest_size=16).hexdigest()


def digest_json(value) -> str:
    """The digest of a JSON value as entries write it (the checksums and keys of the cache)."""
    import json

    return digest(json.dumps(value, ensure_ascii=False, separators=(",", ":")).encode("utf-8", "surrogateescape"))


def linked_in_checkout(folder: str, cwd: str) -> bool:
    """`folder` (absolute) lies in the checkout around `cwd` and a folder on its way there, itself included, is a
    symbolic link: a `.urdfcheck-cache` link committed in a pull request would send the cache's writes and its
    pruning anywhere the runner may write. The runner's own cache folder elsewhere may be reached through links."""
    from urdfcheck.core.checkout import around

    top = around(os.path.abspath(cwd))
    folder = os.path.normpath(folder)
    if not folder.startswith(top.rstrip(os.sep) + os.sep):
        return False
    d = folder
    while len(d) > len(top):
        if os.path.islink(d):
            return True
        d = os.path.dirname(d)
    return False


def versions(folder: str) -> list[str]:
    """The entries (.json) in `folder`, most recently used first; none when `folder` is a symbolic link (a
    key's folder a checked tree planted), and no entry that is one."""
    found = []
    if os.path.islink(folder):
        return []
    try:
        with os.scandir(folder) as it:
            for e in it:
                if e.name.endswith(".json"):
                    try:
                        if e.is_symlink():
                            continue
                        found.append((e.stat(follow_symlinks=False).st_mtime_ns, e.path))
                    except OSError:
                        continue
    except OSError:
        return []
    return [p for _, p in sorted(found, reverse=True)]


def read_json(path: str, limit: int):
    """The JSON value in `path`, or None (missing, larger than `limit`, not JSON)."""
    import json

    from urdfcheck.core import door

    if os.path.islink(path) or os.path.islink(os.path.dirname(path)):
        return None  # the cache writes no links: one is planted
    try:
        data = door.read_bytes(path, limit=limit, runner=True)  # the runner's cache folder, named by them
    except OSError:
        return None
    if len(data) > limit:
        return None
    try:
        return json.loads(data.decode("utf-8"))
    except (UnicodeDecodeError, ValueError, RecursionError):
        return None


def write(folder: str, name: str, data: bytes) -> str:
    """`data` as `folder`/`name`, atomically (the folder is made, private to the user); returns the path.
    Never through a folder that is a symbolic link (the cache makes none: one was planted)."""
    if os.path.islink(folder) or os.path.islink(os.path.dirname(folder)):
        raise OSError(f"the cache folder {os.path.basename(folder)} is a symbolic link; not written")
    os.makedirs(folder, mode=0o700, exist_ok=True)
    final = os.path.join(folder, name)
    tmp = os.path.join(folder, f".{name}.{os.getpid()}.{id(data):x}.tmp")
    fd = os.open(tmp, os.O_WRONLY | os.O_CREAT | os.O_EXCL | getattr(os, "O_CLOEXEC", 0), 0o600)
    try:
        with os.fdopen(fd, "wb") as f:
            f.write(data)
        os.replace(tmp, final)  # atomic: a parallel reader sees the old entry or the new one
    except BaseException:
        unlink(tmp)
        raise
    return final


def touch(path: str) -> None:
    """Mark an entry used (the least recently used go first when the folder is pruned)."""
    try:
        os.utime(path)
    except OSError:
        pass


def unlink(path: str) -> bool:
    try:
        os.unlink(path)
        return True
    except OSError:
        return False
