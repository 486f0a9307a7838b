"""Reading a file of the checkout: a regular file only, opened non-blocking, never more than a cap.

A pull request can commit a named pipe (a FIFO) where a model, a YAML or a launch file is expected; a plain
`open()` of it blocks the linter forever, and a device node (`/dev/zero` through a path that reaches it) never
ends. `read_file` looks at the file type before opening, opens with O_NONBLOCK (a FIFO swapped in meanwhile
cannot block), checks the type again on the open descriptor, and reads at most `limit + 1` bytes, so callers
tell "too large" from "exactly the cap".
"""
from __future__ import annotations

import _thread  # thread-local state without importing threading (start-up)
import contextlib
import errno
import os
import stat

_KINDS = ((stat.S_ISFIFO, "a named pipe"), (stat.S_ISCHR, "a character device"), (stat.S_ISBLK, "a block device"),
          (stat.S_ISSOCK, "a socket"), (stat.S_ISDIR, "a folder"))
_FLAGS = os.O_RDONLY | getattr(os, "O_NONBLOCK", 0) | getattr(os, "O_NOCTTY", 0) | getattr(os, "O_CLOEXEC", 0)


class NotRegularFile(OSError):
    """The path is not a regular file. An OSError, so `except OSError as e: ... e.strerror` reads well."""

    def __init__(self, path, kind: str):
        super().__init__(errno.EINVAL, f"not a regular file ({kind})", os.fspath(path))
        self.kind = kind


def _kind(mode: int) -> str | None:
    if stat.S_ISREG(mode):
        return None
    for test, name in _KINDS:
        if test(mode):
            return name
    return "a special file"


def check_regular(path) -> os.stat_result:
    """stat() of `path` (following links); NotRegularFile unless it is a regular file."""
    st = os.stat(path)
    kind = _kind(st.st_mode)
    if kind is not None:
        raise NotRegularFile(path, kind)
    return st


_overlay = _thread._local()


@contextlib.contextmanager
def overlaid(texts):
    """Reads of these files (path -> bytes) return these bytes instead of the disk's: the unsaved text of an
    editor's open documents (`urdfcheck server`). Set per thread; a forked worker inherits it."""
    prev = getattr(_overlay, "texts", None)
    _overlay.texts = {os.path.realpath(os.fspath(k)): bytes(v) for k, v in dict(texts).items()}
    try:
        yield
    finally:
        _overlay.texts = prev


def read_file(path, limit: int) -> bytes:
    """At most `limit + 1` bytes of the regular file `path`. OSError (NotRegularFile for a FIFO, device,
    socket or folder) otherwise; never blocks on the file type."""
    texts = getattr(_overlay, "texts", None)
    if texts:
        data = texts.get(os.path.realpath(os.fspath(path)))
        if data is not None:
            return data[: limit + 1]
    check_regular(path)
    fd = os.open(path, _FLAGS)
    try:
        st = os.fstat(fd)
        kind = _kind(st.st_mode)
        if kind is not None:  # replaced between the stat and the open
            raise NotRegularFile(path, kind)
        # one read of the whole file where it does not grow meanwhile (1 MiB reads joined cost 6 ms on 9 MB)
        step = max(1 << 20, st.st_size + 1)
        chunks, left = [], limit + 1
        while left > 0:
            want = min(left, step)
            try:
                block = os.read(fd, want)
            except BlockingIOError:  # a regular file never does this; be safe rather than spin
                break
            chunks.append(block)
            left -= len(block)
            if len(block) < want:  # a regular file's short read is its end: no second read to be told so
                break
        return b"".join(chunks)
    finally:
        os.close(fd)


def read_text(path, limit: int, errors: str = "replace") -> str:
    """`read_file` decoded as UTF-8."""
    return read_file(path, limit).decode("utf-8", errors)


# --- encodings ---------------------------------------------------------------------------------------------------
# urdfdom (TinyXML2) reads UTF-8 only; xacro's expat would take UTF-16 with a byte-order mark. A model in any other
# encoding is reported (X001), never silently skipped or read as garbage.
_BOMS = ((b"\x00\x00\xfe\xff", "utf-32-be", "UTF-32 (big-endian)"),
         (b"\xff\xfe\x00\x00", "utf-32-le", "UTF-32 (little-endian)"),
         (b"\xfe\xff", "utf-16-be", "UTF-16 (big-endian)"), (b"\xff\xfe", "utf-16-le", "UTF-16 (little-endian)"))
_NUL_PATTERNS = ((b"\x00\x00\x00<", "utf-32-be", "UTF-32 (big-endian)"),
                 (b"<\x00\x00\x00", "utf-32-le", "UTF-32 (little-endian)"),
                 (b"\x00<", "utf-16-be", "UTF-16 (big-endian)"), (b"<\x00", "utf-16-le", "UTF-16 (little-endian)"))
UTF8_BOM = b"\xef\xbb\xbf"


def foreign_encoding(data: bytes) -> tuple[str, str] | None:
    """(codec, description) when `data` is UTF-16 or UTF-32 (by its byte-order mark, or by the NUL bytes around
    the first '<'); None for UTF-8 (with or without a BOM) and anything else."""
    for bom, codec, name in _BOMS:
        if data.startswith(bom):
            return codec, f"{name} with a byte-order mark"
    head = data[:4]
    for pattern, codec, name in _NUL_PATTERNS:
        if head.startswith(pattern):
            return codec, name
    return None


def decode_model_text(data: bytes) -> str:
    """Text of a model file for a quick look (discovery): UTF-16/32 decoded as such, else UTF-8, lenient."""
    enc = foreign_encoding(data)
    if enc is not None:
        return data.decode(enc[0], "replace").lstrip("\ufeff")
    return data.decode("utf-8", "replace").lstrip("\ufeff")


def encoding_problem(data: bytes) -> str | None:
    """Why a model file cannot be read like urdfdom reads it (UTF-8), or None."""
    enc = foreign_encoding(data)
    if enc is None:
        return None
    return (f"the file is encoded as {enc[1]}; urdfdom (TinyXML2) and robot_state_publisher read UTF-8 only: "
            "save it as UTF-8")
