"""Plain record classes: field-wise repr and equality without `dataclasses`.

Why not dataclasses: importing them pulls in `inspect`, and each decorated class is generated with
`exec` at import (~0.7 ms a class). A lint run starts ~20 such classes, which cost more than lxml's
import. A record lists its fields in `_fields` and writes its own `__init__`.
"""
from __future__ import annotations


class Record:
    __slots__ = ()
    _fields: tuple[str, ...] = ()

    def _values(self) -> tuple:
        return tuple(getattr(self, n) for n in self._fields)

    def __repr__(self) -> str:
        inner = ", ".join(f"{n}={getattr(self, n)!r}" for n in self._fields)
        return f"{type(self).__name__}({inner})"

    def __eq__(self, other) -> bool:
        if other.__class__ is not self.__class__:
            return NotImplemented
        return self._values() == other._values()

    __hash__ = None  # mutable: like a dataclass, equal by value and unhashable


class FrozenRecord(Record):
    """An immutable record, hashable by value. `__init__` fills `self.__dict__` directly."""

    __slots__ = ()

    def __setattr__(self, name, value):
        raise AttributeError(f"{type(self).__name__} is immutable: cannot set {name!r}")

    def __delattr__(self, name):
        raise AttributeError(f"{type(self).__name__} is immutable: cannot delete {name!r}")

    def __hash__(self) -> int:
        return hash(self._values())
