"""Xacro expansions a lint run takes from the lint cache instead of expanding again, and the ones it stores.

Each expansion the console's run makes is stored in the user's cache folder (cli/cache.py decides where) with
what it read, under a key of the entry path, its options, the package map's state, and the settings the run's
own key has but its command line (tool version and code, interpreter, working directory, environment). A later
run, whatever files it was asked about, takes a stored expansion with the same key when every file, folder and
installed module it read still looks the same. So a commit that edits a controller file re-lints the robot with
no xacro worker at all, and one that edits a macro file expands again only the models that include it. Only a
console run with the cache on (`configure`, `record`) looks here; the API and the tests' in-process runs never do.
"""
from __future__ import annotations

import os

MAX_VERSIONS = 4  # stored results per key (the states a pre-commit user goes back and forth between)
MAX_ENTRY = 16 * 1024 * 1024  # bytes of one stored expansion: a larger one is expanded again each time
_STATE = {"folder": "", "base": "", "recording": False, "expect_all": False}
_FOUND: dict[str, dict | None] = {}  # key -> the usable stored result (None: none), looked up once per run
_MADE: dict[str, dict] = {}  # key -> result, this run's expansions
_TAKEN: set[str] = set()
_COUNT = [0]  # expansions this run finished, kept or not
_NOW: dict = {}  # (kind, path) -> fingerprint, once per run and path


def configure(folder: str, base: str) -> None:
    """Where the cache lives (its schema's folder) and the hash of the run's settings but its command line."""
    _STATE["folder"], _STATE["base"] = folder, base


def record() -> None:
    """From now on, remember this run's expansions for `store`."""
    _STATE["recording"] = True


def active() -> bool:
    return bool(_STATE["base"])


def key(path: str, options: dict, resolver) -> str:
    """What an expansion's result depends on besides the files it reads (those are checked one by one): the
    entry, the options, the package map as the worker receives it (what the console found out already, such as
    the workspace folder, it does not look at again), and the run's settings."""
    state = None
    if resolver is not None:
        state = sorted((k, repr(v)) for k, v in vars(resolver).items() if k != "used")
    shown = sorted((k, repr(sorted(v.items()) if isinstance(v, dict) else v)) for k, v in options.items()
                   if k != "resolver")
    from urdfcheck.core.cachefile import digest

    text = repr([_STATE["base"], os.path.abspath(path), shown, state])
    return digest(text.encode("utf-8", "surrogateescape"))


def take(k: str) -> dict | None:
    """The stored result for key `k` whose reads are all unchanged, or None."""
    got = _lookup(k)
    if got is not None:
        _TAKEN.add(k)
    return got


def available(k: str) -> bool:
    return _lookup(k) is not None


def expect_all() -> None:
    """Every expansion of the last stored run is available: the console forks no xacro worker up front."""
    _STATE["expect_all"] = True


def all_expected() -> bool:
    return _STATE["expect_all"]


def made(k: str, result) -> None:
    """A finished expansion (taken or made): kept for `store` when it is a result with what it read (a worker
    that failed is not: what it would have read is unknown), counted in any case."""
    if not _STATE["recording"]:
        return
    _COUNT[0] += 1
    if isinstance(result, dict) and isinstance(result.get("observed"), list):
        _MADE.setdefault(k, result)


def made_count() -> int:
    return _COUNT[0]


def taken_count() -> int:
    return len(_TAKEN)


def seen(items) -> list:
    """[kind, path, fingerprint] for each (kind, path), leaving out the cache's own files."""
    from urdfcheck.core.cachefile import digest
    from urdfcheck.core.observe import fingerprint

    folder = os.path.join(_STATE["folder"], "")
    # reading an entry resolves its path, which probes the cache folder and those above it: only a run that
    # found an entry makes those probes, and two runs of the same tree must agree on what they looked at
    above = set()
    if _STATE["folder"]:
        d = os.path.normpath(_STATE["folder"])
        while d not in above:
            above.add(d)
            d = os.path.dirname(d)
    out = []
    for kind, path in items:
        if folder != os.sep and path.startswith(folder) or kind in ("p", "q") and path in above:
            continue
        fp = _NOW.get((kind, path))
        if fp is None:
            fp = _NOW[kind, path] = fingerprint(kind, path, digest)
        out.append([kind, path, fp])
    return out


def store() -> list[str]:
    """Store this run's expansions that did not come from the cache; returns the keys of all it finished."""
    import json

    from urdfcheck.core import cachefile
    from urdfcheck.load import stored

    for k, res in sorted(_MADE.items()):
        if k in _TAKEN:
            continue
        observed = seen(res["observed"])
        result = stored.to_json({n: v for n, v in res.items() if n != "observed"})
        entry = {"key": k, "result": result, "observed": observed}
        entry["sum"] = _checksum(entry)
        data = json.dumps(entry, ensure_ascii=False, separators=(",", ":")).encode("utf-8", "surrogateescape")
        if len(data) > MAX_ENTRY:
            continue
        folder = _folder(k)
        cachefile.write(folder, f"{_checksum({'observed': observed})}.json", data)
        for old in cachefile.versions(folder)[MAX_VERSIONS:]:
            cachefile.unlink(old)
    return sorted(_MADE)


def _folder(k: str) -> str:
    return os.path.join(_STATE["folder"], "x" + k)  # beside the reports' keys: pruned with them


def _lookup(k: str) -> dict | None:
    if k in _FOUND:
        return _FOUND[k]
    _FOUND[k] = None
    if not _STATE["folder"]:
        return None
    from urdfcheck.core import cachefile
    from urdfcheck.load import stored

    for path in cachefile.versions(_folder(k))[:MAX_VERSIONS]:
        entry = cachefile.read_json(path, MAX_ENTRY)
        if not isinstance(entry, dict) or entry.get("key") != k or _changed(entry.get("observed")) \
                or not _valid(entry, k):
            continue
        res = stored.from_json(entry["result"])
        if res is None:
            continue
        res["observed"] = [(kind, p) for kind, p, _ in entry["observed"]]  # the run's own record keeps them
        cachefile.touch(path)
        _FOUND[k] = res
        break
    return _FOUND[k]


def _changed(observed) -> bool:
    """Whether anything the expansion read looks different now (or the record is not one)."""
    from urdfcheck.core.cachefile import digest
    from urdfcheck.core.observe import first_change

    return first_change(observed, _NOW, digest) is not None


def _valid(entry, k: str) -> bool:
    from urdfcheck.core.observe import valid_items

    return isinstance(entry, dict) and set(entry) == {"key", "result", "observed", "sum"} and entry["key"] == k \
        and isinstance(entry["result"], dict) and valid_items(entry["observed"]) \
        and entry["sum"] == _checksum(entry)


def _checksum(entry: dict) -> str:
    from urdfcheck.core.cachefile import digest_json

    return digest_json([entry.get("key"), entry.get("result"), entry["observed"]])


def reset() -> None:
    """Forget the run's state (a test, or a long-lived process that runs the console twice)."""
    _STATE.update(folder="", base="", recording=False, expect_all=False)
    _FOUND.clear()
    _MADE.clear()
    _TAKEN.clear()
    _COUNT[0] = 0
    _NOW.clear()
