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


def versions(folder: str) -> list[str]:
    """The entries (.json) in `folder`, most recently used first."""
    found = []
    try:
        with os.scandir(folder) as it:
            for e in it:
                if e.name.endswith(".json"):
                    try:
                        found.append((e.stat(follow_symlinks=False).st_mtime_ns, e.path))
                    except OSError:
                        continue
    except OSError:
        return []
    return [p for _, p in sorted(found, reverse=True)]


def read_json(path: str, limit: int):
    """The JSON value in `path`, or None (missing, larger than `limit`, not JSON)."""
    import json

    from urdfcheck.core.safeio import read_file

    try:
        data = read_file(path, limit)
    except OSError:
        return None
    if len(data) > limit:
        return None
    try:
        return json.loads(data.decode("utf-8"))
    except (UnicodeDecodeError, ValueError, RecursionError):
        return None


def write(folder: str, name: str, data: bytes) -> str:
    """`data` as `folder`/`name`, atomically (the folder is made, private to the user); returns the path."""
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
