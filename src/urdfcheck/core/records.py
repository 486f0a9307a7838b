"""Plain record classes: field-wise repr and equality without `dataclasses`.

Why not dataclasses: importing them pulls in `inspect`, and each decorated class is generated with
`exec` at import (~0.7 ms a class). A lint run starts ~20 such classes, which cost more than lxml's
import. A record lists its fields in `_fields`; a `FrozenRecord` that writes no `__init__` takes them from
`_fields` and `_defaults` with the generic one below (no code generated: a generated `__init__` costs a compile,
0.3-0.9 ms a class on a loaded machine; the generic one costs a few microseconds a call, which is why the
records made per link or joint are `TupleRecord`s and the per-model ones use this).

`TupleRecord` is `typing.NamedTuple` without its start-up cost: typing evaluates every annotation (a
`compile()` each, under `from __future__ import annotations`), 0.35 ms a class against 0.08 ms for the
`collections.namedtuple` it builds; a lint run starts ~50 such classes.
"""
from __future__ import annotations

import collections

TYPE_CHECKING = False  # typing.TYPE_CHECKING without importing typing (start-up); mypy reads the name as true

# what a class body may not define (namedtuple's own machinery), and what it defines but is not copied
_PROHIBITED = frozenset(("__new__", "__init__", "__slots__", "__getnewargs__", "_fields", "_field_defaults",
                         "_make", "_replace", "_asdict", "_source"))
_NOT_COPIED = frozenset(("__module__", "__qualname__", "__annotations__", "__doc__", "__dict__", "__weakref__"))


class _TupleMeta(type):
    def __new__(mcls, name, bases, ns):
        if ns.get("_is_base"):  # TupleRecord itself
            return super().__new__(mcls, name, bases, ns)
        if bases != (TupleRecord,):
            raise TypeError(f"{name}: a TupleRecord class derives from TupleRecord alone")
        fields = tuple(ns.get("__annotations__", {}))  # names only: the annotations are never evaluated
        defaults = []
        for f in fields:
            if f in ns:
                defaults.append(ns[f])
            elif defaults:
                raise TypeError(f"{name}: field {f!r} without a default follows fields with defaults")
        cls = collections.namedtuple(name, fields, defaults=defaults or None, module=ns.get("__module__"))
        cls.__qualname__ = ns.get("__qualname__", name)
        if ns.get("__doc__"):
            cls.__doc__ = ns["__doc__"]
        for key, value in ns.items():
            if key in _PROHIBITED:
                raise AttributeError(f"{name}: cannot overwrite TupleRecord attribute {key}")
            if key not in _NOT_COPIED and key not in fields:
                setattr(cls, key, value)
        return cls


if TYPE_CHECKING:  # what it is to a type checker: a NamedTuple (the metaclass below builds the same)
    from typing import NamedTuple as TupleRecord
else:
    class TupleRecord(metaclass=_TupleMeta):
        """`class Pose(TupleRecord): xyz: Vec3 = (0.0, 0.0, 0.0)` is a `collections.namedtuple` with those fields,
        defaults, methods and properties, like `typing.NamedTuple` (whose annotations cost a compile each)."""

        _is_base = True


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

    __hash__ = None  # type: ignore[assignment]  # mutable: like a dataclass, equal by value and unhashable


class FrozenRecord(Record):
    """An immutable record, hashable by value. `__init__` fills `self.__dict__` directly: a class's own, or
    this generic one (fields by position or name, `_defaults` holding immutable values for the missing ones)."""

    __slots__ = ()
    _defaults: dict = {}

    def __init__(self, *args, **kwargs):
        fields = self._fields
        if len(args) > len(fields):
            raise TypeError(f"{type(self).__name__} takes {len(fields)} fields, got {len(args)}")
        d = self.__dict__  # __setattr__ is refused
        for name, value in zip(fields, args):
            if name in kwargs:
                raise TypeError(f"{type(self).__name__}: {name!r} given twice")
            d[name] = value
        for name in fields[len(args):]:
            if name in kwargs:
                d[name] = kwargs.pop(name)
            elif name in self._defaults:
                d[name] = self._defaults[name]
            else:
                raise TypeError(f"{type(self).__name__}: missing field {name!r}")
        if kwargs:
            raise TypeError(f"{type(self).__name__}: unknown field {sorted(kwargs)[0]!r}")

    def __setattr__(self, name, value):
        raise AttributeError(f"{type(self).__name__} is immutable: cannot set {name!r}")

    def __delattr__(self, name):
        raise AttributeError(f"{type(self).__name__} is immutable: cannot delete {name!r}")

    def _values(self) -> tuple:
        # immutable: the values are read once (a record used as a cache key is hashed and compared on every lookup:
        # the sandbox's limits, once per ${...} of an expansion); kept beside the fields, never one of them
        d = self.__dict__
        got = d.get(_VALUES)
        if got is None:
            got = d[_VALUES] = tuple(getattr(self, n) for n in self._fields)
        return got

    def __hash__(self) -> int:  # type: ignore[override]  # immutable: hashable again
        return hash(self._values())


_VALUES = "\0values"  # the key of a FrozenRecord's values in its __dict__ (no field can be named so)

