"""Shared small types for the consumer readers: a located value and the reader error."""
from __future__ import annotations

from urdfcheck.core.findings import Location
from urdfcheck.core.records import TYPE_CHECKING, FrozenRecord

if TYPE_CHECKING:
    from typing import Any


class ConsumerError(Exception):
    """A consumer file (parameter YAML, launch file) could not be read.

    Never a traceback for the user: the engine reports it as C007 at `location`.
    """

    def __init__(self, message: str, location: Location):
        super().__init__(message)
        self.message = message
        self.location = location

    def __reduce__(self):  # both fields (Exception pickles its args only): a file parsed in the worker comes back
        return type(self), (self.message, self.location)

    def __str__(self) -> str:
        return f"{self.location.shown()}: {self.message}"


class Value(FrozenRecord):
    """A value read from a consumer file, with where it was written.

    `default` is True when the reader supplied the value because the file did not set it
    (then `loc` points at the owning node or controller).
    """

    # items: for a list: the Location of each element
    _fields = ('value', 'loc', 'default', 'items')
    value: Any
    loc: Location
    default: bool
    items: tuple

    def __init__(self, value: Any, loc: Location, default: bool = False, items: tuple = ()):
        d = self.__dict__  # FrozenRecord forbids setattr
        d["value"] = value
        d["loc"] = loc
        d["default"] = default
        d["items"] = items

    def item_loc(self, i: int) -> Location:
        return self.items[i] if 0 <= i < len(self.items) else self.loc

    def __str__(self) -> str:
        return str(self.value)


def read_capped(path, max_bytes: int, what: str = "file", *, runner: bool = False) -> bytes:
    """The bytes of a consumer file, refusing one over `max_bytes`. Raises ConsumerError."""
    import os

    from urdfcheck.load.packages import leaves_cwd

    file = str(path)
    if leaves_cwd(file):
        raise ConsumerError(f"{what} is, or lies in, a symbolic link that leads out of the working directory; "
                            "not read", Location(file))
    from urdfcheck.core import door

    try:
        # confined first: the size of a file outside the run's roots is not told either
        size = os.path.getsize(door.confine(file, runner=runner))
        if size > max_bytes:
            raise ConsumerError(f"{what} is larger than {max_bytes} bytes ({size}); refused", Location(file))
        return door.read_bytes(file, limit=max_bytes, runner=runner)  # inside the roots; never a FIFO
    except OSError as e:
        raise ConsumerError(f"cannot read file: {e.strerror or e}", Location(file)) from None


def as_str_list(value: Any) -> list[str] | None:
    """A YAML value that should be a list of strings (a single string is accepted). None: not that shape."""
    if isinstance(value, str):
        return [value]
    if isinstance(value, (list, tuple)) and all(isinstance(v, str) for v in value):
        return list(value)
    return None


def as_float(value: Any) -> float | None:
    if isinstance(value, bool):
        return None
    if isinstance(value, (int, float)):
        f = float(value)
        return f if f == f and f not in (float("inf"), float("-inf")) else None
    if isinstance(value, str):
        try:
            f = float(value.strip())
        except ValueError:
            return None
        return f if f == f and f not in (float("inf"), float("-inf")) else None
    return None


_TRUE = {"true", "yes", "on", "1"}
_FALSE = {"false", "no", "off", "0"}


def as_bool(value: Any) -> bool | None:
    if isinstance(value, bool):
        return value
    if isinstance(value, int):
        return bool(value)
    if isinstance(value, str):
        s = value.strip().lower()
        if s in _TRUE:
            return True
        if s in _FALSE:
            return False
    return None
