"""Xacro expansions a lint run may take from the lint cache instead of expanding again, and the ones it made.

The lint cache (cli/cache.py) stores a run's report with the expansions the run made, each with what it read. On
a miss (a file the run read has changed), each stored expansion whose own files are all unchanged is offered
here; the loader takes an offered one for the same entry and options instead of starting the worker. So a pull
request that edits a controller file re-lints with no xacro worker at all, and one that edits a macro file
expands again only the models that include it. Only console runs with the cache on offer or record anything.
"""
from __future__ import annotations

import os

_OFFERED: dict[str, dict] = {}
_MADE: dict[str, dict] = {}
_RECORDING = [False]
_EXPECT_ALL = [False]
_COUNT = [0, 0]  # expansions finished, of them taken from the cache
_ROW = {"suppressions": 5, "warnings": 3, "xml_warnings": 4, "observed": 2}


def key(path: str, options: dict, resolver) -> str:
    """What an expansion's result depends on besides the files it reads (those are checked one by one): the
    entry, the options, and the package map's own settings (its answers come from probes the worker records)."""
    try:
        from _blake2 import blake2b  # hashlib would load OpenSSL first (cli/cache.py)
    except ImportError:  # pragma: no cover - an interpreter without it
        from hashlib import blake2b

    where = None
    if resolver is not None:
        where = [sorted((k, str(v)) for k, v in resolver.explicit.items()), str(resolver.named_workspace),
                 str(resolver.near)]
    shown = sorted((k, repr(sorted(v.items()) if isinstance(v, dict) else v)) for k, v in options.items()
                   if k != "resolver")
    text = repr([os.path.abspath(path), shown, where])
    return blake2b(text.encode("utf-8", "surrogateescape"), digest_size=16).hexdigest()


def record() -> None:
    """From now on, remember this run's expansions (the console's cache, before the run)."""
    _RECORDING[0] = True


def active() -> bool:
    return _RECORDING[0] or bool(_OFFERED)


def expect_all() -> None:
    """The newest stored run's expansions are all offered: the console forks no xacro worker up front."""
    _EXPECT_ALL[0] = True


def all_expected() -> bool:
    return _EXPECT_ALL[0]


def offer(k: str, result: dict) -> None:
    _OFFERED.setdefault(k, result)


def offered() -> int:
    return len(_OFFERED)


def take(k: str) -> dict | None:
    got = _OFFERED.get(k)
    if got is not None:
        _COUNT[1] += 1
    return got


def made(k: str, result) -> None:
    """A finished expansion: kept for the cache when it is a result (a worker that failed is not: what it would
    have read is unknown), counted in any case."""
    if not _RECORDING[0]:
        return
    _COUNT[0] += 1
    if isinstance(result, dict) and isinstance(result.get("observed"), list):
        _MADE.setdefault(k, result)


def made_list() -> list[tuple[str, dict]]:
    return sorted(_MADE.items())


def made_count() -> int:
    """How many expansions the run finished, kept or not."""
    return _COUNT[0]


def taken_count() -> int:
    """How many of them the cache gave."""
    return _COUNT[1]


def to_json(result: dict) -> dict:
    """The result as JSON values (tuples become lists; `from_json` restores them)."""
    out = dict(result)
    for name in _ROW:
        if name in out:
            out[name] = [list(row) for row in out[name]]
    out["suppressions"] = [row[:3] + [list(row[3])] + row[4:] for row in out.get("suppressions", [])]
    return out


def from_json(data) -> dict | None:
    """A stored result, checked field by field; None when anything is not what an expansion returns."""
    if not isinstance(data, dict) or not _error_or_text(data):
        return None
    if set(data) - {"xml", "error", "files", "suppressions", "warnings", "args", "xml_warnings", "observed",
                    "deps"}:
        return None
    out = {n: data[n] for n in ("xml", "error") if n in data}
    files, deps, args = data.get("files", []), data.get("deps", []), data.get("args", {})
    if not _strs(files) or not _strs(deps) or not isinstance(args, dict) or not _strs(list(args)) \
            or not all(v is None or isinstance(v, str) for v in args.values()):
        return None
    out.update(files=list(files), args=dict(args))
    if "deps" in data:
        out["deps"] = list(deps)
    for name, width in _ROW.items():
        rows = data.get(name, [])
        if not isinstance(rows, list) or not all(isinstance(r, list) and len(r) == width for r in rows):
            return None
        out[name] = [tuple(r) for r in rows]
    for idx, first, last, codes, cline in out["suppressions"]:
        if not (_ints(idx, first, last, cline) and _strs(codes) and 0 <= idx < len(files)):
            return None
    out["suppressions"] = [r[:3] + (tuple(r[3]),) + r[4:] for r in out["suppressions"]]
    for idx, code, message, line in out["xml_warnings"]:
        if not (_ints(idx) and 0 <= idx < len(files) and isinstance(code, str) and isinstance(message, str)
                and (line is None or _ints(line))):
            return None
    for kind, text, marker in out["warnings"]:
        if not (isinstance(kind, str) and isinstance(text, str) and (marker is None or isinstance(marker, str))):
            return None
    if not all(_strs(r) for r in out["observed"]):
        return None
    return out


def _error_or_text(data: dict) -> bool:
    """A result has its expanded text, or the error that stopped it ({code, message, marker})."""
    err = data.get("error")
    if err is None:
        return isinstance(data.get("xml"), str)
    return "xml" not in data and isinstance(err, dict) and set(err) == {"code", "message", "marker"} \
        and isinstance(err["code"], str) and isinstance(err["message"], str) \
        and (err["marker"] is None or isinstance(err["marker"], str))


def _strs(values) -> bool:
    return isinstance(values, (list, tuple)) and all(isinstance(v, str) for v in values)


def _ints(*values) -> bool:
    return all(type(v) is int for v in values)


def reset() -> None:
    _OFFERED.clear()
    _MADE.clear()
    _RECORDING[0] = False
    _EXPECT_ALL[0] = False
    _COUNT[:] = [0, 0]
