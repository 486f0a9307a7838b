"""A xacro expansion's result as JSON and back, checked field by field (the lint cache keeps them: load/reuse.py).

JSON has no tuples: the rows of a result (suppressions, warnings, what it read) come back as tuples, as the worker
returned them. Anything that is not what an expansion returns makes the stored result unusable, never trusted.
"""
from __future__ import annotations

_ROW = {"suppressions": 5, "warnings": 3, "xml_warnings": 4, "observed": 2}
_FIELDS = frozenset(("xml", "error", "files", "suppressions", "warnings", "args", "xml_warnings", "observed", "deps"))


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
    if set(data) - _FIELDS:
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
