"""Module-level regular expressions compiled on their first use, not at import.

A lint run imports ~60 module-level patterns and uses a fraction of them (a plain URDF never reaches the launch
readers' or the distro finder's), and compiling costs about 0.1-0.3 ms each. After the first use the bound
methods of the compiled pattern sit in the instance's dict, so a call costs what it costs on the pattern itself.
"""
from __future__ import annotations

import re

_TAKEN = ("match", "search", "fullmatch", "finditer", "findall", "sub", "subn", "split", "scanner",
          "pattern", "flags", "groups", "groupindex")


class Pattern:
    def __init__(self, pattern, flags=0):
        self._source = (pattern, flags)

    def __getattr__(self, name):  # asked only while `name` is not in the instance's dict: before the first use
        compiled = re.compile(*self._source)
        for n in _TAKEN:
            self.__dict__[n] = getattr(compiled, n)
        return getattr(compiled, name)

    def __repr__(self) -> str:
        return f"lazyre.compile({self._source[0]!r}, {self._source[1]!r})"


def compile(pattern, flags=0) -> Pattern:  # noqa: A001 - the name of what it stands for
    return Pattern(pattern, flags)
