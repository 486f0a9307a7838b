"""A parsed YAML document with the location of every value (`consumers.yamlsrc` parses; this module does not
import PyYAML, so a document parsed in the xacro worker is read back here without it)."""
from __future__ import annotations

from collections.abc import Iterator

from urdfcheck.core.findings import Location
from urdfcheck.core.records import TYPE_CHECKING, Record

if TYPE_CHECKING:
    from typing import Any


class YamlDoc(Record):
    """A parsed YAML document: plain values plus the location of every key path.

    A key path is a tuple of mapping keys and sequence indices from the document root.
    """

    # notes: (message, Location): duplicate keys and the like
    _fields = ('file', 'data', '_value_locs', '_key_locs', 'notes')

    def __init__(self, file: str,
                 data: Any,
                 _value_locs: dict | None = None,
                 _key_locs: dict | None = None,
                 notes: list | None = None):
        self.file = file
        self.data = data
        self._value_locs = {} if _value_locs is None else _value_locs
        self._key_locs = {} if _key_locs is None else _key_locs
        self.notes = [] if notes is None else notes

    def loc(self, *path) -> Location:
        """Where the value at `path` was written; the nearest located ancestor otherwise (file-only at worst)."""
        p = tuple(path)
        while True:
            if p in self._value_locs:
                return self._value_locs[p]
            if not p:
                return Location(self.file)
            p = p[:-1]

    def key_loc(self, *path) -> Location:
        """Where the mapping key ending `path` was written (falls back to `loc`)."""
        p = tuple(path)
        if p in self._key_locs:
            return self._key_locs[p]
        return self.loc(*p)

    def has(self, *path) -> bool:
        return tuple(path) in self._value_locs

    def get(self, *path, default=None):
        cur = self.data
        for k in path:
            if isinstance(cur, dict) and k in cur:
                cur = cur[k]
            elif isinstance(cur, list) and isinstance(k, int) and 0 <= k < len(cur):
                cur = cur[k]
            else:
                return default
        return cur

    def walk(self) -> Iterator[tuple[tuple, Any]]:
        """(path, value) for every value, parents before children, document order."""
        yield from _walk((), self.data)


def _walk(path, value):
    yield path, value
    if isinstance(value, dict):
        for k, v in value.items():
            yield from _walk(path + (k,), v)
    elif isinstance(value, list):
        for i, v in enumerate(value):
            yield from _walk(path + (i,), v)
