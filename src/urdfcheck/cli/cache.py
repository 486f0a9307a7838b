"""The lint cache: an unchanged run answers from the user's cache folder without importing the pipeline.

A `urdfcheck lint` run (console entry only, never the API) is stored as its report text, its stderr and its exit
code, under a key made of everything the command line and the process decide (urdfcheck's version and code, the
interpreter, the working directory, the arguments, the environment, whether stdout is a terminal), together with
what the run looked at (core/observe: each file it read by content hash, each folder it listed, each path it
probed, the installed modules by size and mtime). A later run with the same key replays the entry only when
every one of those still looks the same; otherwise it runs and stores anew. Xacro expansions are stored apart,
each with what it read: any run with the same settings takes one whose reads are all unchanged instead of
expanding again, whatever its command line (load/reuse.py).

Where: `--cache-dir DIR`, else $URDFCHECK_CACHE_DIR, else the user's cache folder (as platformdirs names it:
$XDG_CACHE_HOME/urdfcheck or ~/.cache/urdfcheck on Linux). A config file in the checked tree can only turn the
cache off (`cache: false`), never point it somewhere: every file of a pull request's checkout is the author's.
Off: `--no-cache`, URDFCHECK_NO_CACHE=1. $URDFCHECK_CACHE_TRACE=1 says on stderr what the cache did.

Safety: entries are JSON (never pickle), written to a temporary file and renamed into place (parallel runs never
see half an entry), checked field by field and against their own checksum and key before use; a corrupt, foreign
or unreadable entry is a miss. Not stored: runs with a report file (--output, --report), --list,
--write-baseline, runs whose worker crashed or timed out or whose time budget ran out (what they would have read
is unknown). The folder is kept under MAX_BYTES and MAX_ENTRIES, least recently used first out.
"""
from __future__ import annotations

import os
import sys

from urdfcheck.cli import options
from urdfcheck.cli.commands import COMMANDS
from urdfcheck.cli.early import may_hold_xacro, reads_yaml_config
from urdfcheck.core import cachefile
from urdfcheck.core.cachefile import digest

SCHEMA = 2
MAX_BYTES = 64 * 1024 * 1024
MAX_ENTRIES = 2000
MAX_ENTRY = 16 * 1024 * 1024
_FIELDS = frozenset(("schema", "key", "code", "stdout", "stderr", "observed", "expansions", "made", "sum"))
_VOLATILE = frozenset(("PWD", "OLDPWD", "SHLVL", "_", "URDFCHECK_CACHE_TRACE"))
# lint options that write files or print something else than the report: such a run is not stored
# --bag: recordings are read by rosbags and sqlite, whose reads the observer does not see (bag/check.py taints too)
# --diff-base, --config-from: what a revision names (a branch moving) is no file the observer sees
_NOT_STORED = ("--list", "--write-baseline", "--output", "--report", "--help", "--version", "--bag", "--diff-base",
               "--config-from")


MAX_VERSIONS = 4  # entries kept per key: the states a pre-commit user goes back and forth between


class Spec:
    """`folder`: the cache's folder for this schema; `key`: the settings' hash; `versions`: the folder holding
    this key's entries, one per state of the files it read (newest used first); `base`: the hash of the settings
    but the command line's own words (what a xacro expansion's key starts from: load/reuse.py)."""
    __slots__ = ("folder", "key", "versions", "trace", "base")

    def __init__(self, folder: str, key: str, trace: bool, base: str = ""):
        self.folder, self.key, self.trace, self.base = folder, key, trace, base
        self.versions = os.path.join(folder, key)


def user_cache_dir() -> str:
    """platformdirs.user_cache_dir("urdfcheck") without importing it."""
    home = os.path.expanduser("~")
    if sys.platform == "darwin":
        return os.path.join(home, "Library", "Caches", "urdfcheck")
    if os.name == "nt":
        base = os.environ.get("LOCALAPPDATA") or os.path.join(home, "AppData", "Local")
        return os.path.join(base, "urdfcheck", "Cache")
    base = os.environ.get("XDG_CACHE_HOME", "")
    if not os.path.isabs(base):  # the XDG spec: a relative value is invalid and ignored
        base = os.path.join(home, ".cache")
    return os.path.join(base, "urdfcheck")


def lint_argv(argv: list[str]) -> list[str]:
    """argv as `main` reads it: a path first means `lint PATH`."""
    if argv and not argv[0].startswith("-") and argv[0] not in COMMANDS:
        return ["lint"] + argv
    return argv


def plan(argv: list[str]) -> Spec | None:
    """The cache entry this command line would use, or None when the run is not cached."""
    argv = lint_argv(list(argv))
    env = os.environ
    if not argv or argv[0] != "lint" or env.get("URDFCHECK_NO_CACHE", "") not in ("", "0"):
        return None
    folder = None
    it = iter(argv[1:])
    for a in it:
        if a == "--":
            return None
        if a.startswith("-") and not a.startswith("--") and a[1:2] in ("o", "h"):
            return None
        if not a.startswith("--"):
            continue
        name = a.split("=", 1)[0]
        if name == "--no-cache":
            return None
        if name == "--cache-dir":
            folder = a.split("=", 1)[1] if "=" in a else next(it, None)
            if not folder:
                return None
            continue
        if len(name) > 3 and any(full.startswith(name) for full in _NOT_STORED):
            return None
        if name.startswith("--ca") or name.startswith("--no-ca"):  # an abbreviation: leave it to argparse
            return None
    folder = os.path.abspath(folder or env.get("URDFCHECK_CACHE_DIR") or user_cache_dir())
    folder = os.path.join(folder, f"v{SCHEMA}")
    if cachefile.linked_in_checkout(folder, os.getcwd()):
        if env.get("URDFCHECK_CACHE_TRACE", "") not in ("", "0"):
            print("urdfcheck: cache off (its folder lies in the checkout and is reached through a symbolic link "
                  "there: a link the checked files made would redirect the cache's writes)", file=sys.stderr)
        return None

    import urdfcheck

    pkg = os.path.dirname(os.path.abspath(urdfcheck.__file__))
    base = [SCHEMA, urdfcheck.__version__, pkg, _code_stamp(pkg), sys.version, sys.executable, os.getcwd(),
            sorted((k, v) for k, v in env.items() if k not in _VOLATILE)]
    material = base + [argv, _isatty(sys.stdout)]
    trace = env.get("URDFCHECK_CACHE_TRACE", "") not in ("", "0")
    return Spec(folder, cachefile.digest_json(material), trace, cachefile.digest_json(base))



def _isatty(stream) -> bool:
    try:
        return bool(stream.isatty())
    except (AttributeError, ValueError, OSError):
        return False


def _code_stamp(pkg: str) -> str:
    """An installed release is its version; a source checkout changes under the same version, so there it is
    the sizes and mtimes of its files."""
    if os.path.basename(os.path.dirname(pkg)) in ("site-packages", "dist-packages"):
        return ""
    parts = []
    for folder, dirs, files in os.walk(pkg):
        dirs[:] = sorted(d for d in dirs if d != "__pycache__")
        for name in sorted(files):
            if name.endswith((".py", ".json", ".yaml")):
                try:
                    st = os.stat(os.path.join(folder, name))
                except OSError:
                    continue
                parts.append(f"{folder}/{name}:{st.st_size}:{st.st_mtime_ns}")
    return digest("\n".join(parts).encode("utf-8", "surrogateescape"))


def _say(spec: Spec, what: str) -> None:
    if spec.trace:
        sys.stderr.write(f"urdfcheck: cache {what}\n")


# --- hit ----------------------------------------------------------------------------------------------------------
def replay(spec: Spec) -> int | None:
    """Write the stored report and return its exit code, or None (no usable entry: run)."""
    from urdfcheck.core.observe import MALFORMED, first_change

    why = "miss"
    looks: dict = {}  # (kind, path) -> what it looks like now: a key's versions share most of their paths
    newest = None
    for path in cachefile.versions(spec.versions)[:MAX_VERSIONS]:
        entry = cachefile.read_json(path, MAX_ENTRY)
        if not isinstance(entry, dict) or entry.get("key") != spec.key:
            continue
        changed = first_change(entry.get("observed"), looks, digest)
        if changed == MALFORMED:
            continue
        if changed is not None:  # a miss is validated whole only when it is the newest: _expect reads it
            if newest is None and _valid(entry, spec.key):
                newest, why = entry, f"miss ({changed} changed)"
            continue
        if not _valid(entry, spec.key):
            continue
        cachefile.touch(path)
        sys.stdout.write(entry["stdout"])
        sys.stderr.write(entry["stderr"])
        _say(spec, "hit")
        return entry["code"]
    if newest is not None and newest["expansions"]:
        why += _expect(spec, newest)
    _say(spec, why)
    return None


def _expect(spec: Spec, entry: dict) -> str:
    """A miss after a stored run: when the cache has every expansion that run made, each with all it read
    unchanged (load/reuse.py), the console forks no xacro worker up front (the loader starts one if the run
    needs another expansion after all)."""
    from urdfcheck.load import reuse

    reuse.configure(spec.folder, spec.base)
    have = sum(map(reuse.available, entry["expansions"]))
    if have == len(entry["expansions"]) == entry["made"]:
        reuse.expect_all()
        return f"; its {have} expansion(s) are stored, no xacro worker"
    return f"; {have} of its {entry['made']} expansion(s) are stored"


def _valid(entry, key: str) -> bool:
    if not isinstance(entry, dict) or set(entry) != _FIELDS:
        return False
    if entry["schema"] != SCHEMA or entry["key"] != key or type(entry["code"]) is not int \
            or entry["code"] not in (0, 1):
        return False
    if not isinstance(entry["stdout"], str) or not isinstance(entry["stderr"], str) \
            or not isinstance(entry["observed"], list) or not isinstance(entry["sum"], str):
        return False
    from urdfcheck.core.observe import valid_items

    if not valid_items(entry["observed"]):
        return False
    if not isinstance(entry["expansions"], list) or not all(isinstance(k, str) for k in entry["expansions"]) \
            or type(entry["made"]) is not int:
        return False
    return entry["sum"] == _checksum(entry)


def _checksum(entry: dict) -> str:
    body = [entry["key"], entry["code"], entry["stdout"], entry["stderr"], entry["observed"], entry["expansions"],
            entry["made"]]
    return cachefile.digest_json(body)


# --- miss ----------------------------------------------------------------------------------------------------------
class _Tee:
    """A standard stream that keeps a copy of what is written (the report and stderr lines to replay)."""

    def __init__(self, stream):
        self._stream = stream
        self.parts: list[str] = []

    def write(self, text):
        self.parts.append(text)
        return self._stream.write(text)

    @property
    def untee(self):  # what must not be replayed (core/progress) writes here
        return self._stream

    def __getattr__(self, name):
        return getattr(self._stream, name)


def record(spec: Spec):
    """Start recording a run that may be stored; returns `finish(code) -> code`."""
    import site

    from urdfcheck.core import observe
    from urdfcheck.load import reuse

    pkg = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
    roots = [pkg] + [p for p in (getattr(site, "USER_SITE", None),) if p]
    observe.start(roots)
    reuse.configure(spec.folder, spec.base)
    reuse.record()
    out, err = _Tee(sys.stdout), _Tee(sys.stderr)
    sys.stdout, sys.stderr = out, err

    def finish(code: int) -> int:
        sys.stdout, sys.stderr = out._stream, err._stream
        try:
            why = _store(spec, code, "".join(out.parts), "".join(err.parts))
        except (OSError, ValueError, TypeError) as e:  # the cache never changes a run's outcome
            why = f"not stored ({type(e).__name__}: {e})"
        _say(spec, why)
        return code

    return finish


def _store(spec: Spec, code: int, stdout: str, stderr: str) -> str:
    import json

    from urdfcheck.core import observe
    from urdfcheck.load import reuse

    if code not in (0, 1):
        return "not stored (exit code)"
    if observe.tainted():
        return f"not stored ({observe.tainted()})"
    if len(stdout) + len(stderr) > MAX_ENTRY // 2:
        return "not stored (too large)"
    seen = reuse.seen  # fingerprints shared with the expansions stored below (one look at each path)
    observed = seen(observe.take())
    entry = {"schema": SCHEMA, "key": spec.key, "code": code, "stdout": stdout, "stderr": stderr,
             "observed": observed, "expansions": reuse.store(), "made": reuse.made_count()}
    entry["sum"] = _checksum(entry)
    data = json.dumps(entry, ensure_ascii=False, separators=(",", ":")).encode("utf-8", "surrogateescape")
    if len(data) > MAX_ENTRY:
        return "not stored (too large)"
    _tag(os.path.dirname(spec.folder))
    version = cachefile.digest_json(observed)
    cachefile.write(spec.versions, f"{version}.json", data)
    for old in cachefile.versions(spec.versions)[MAX_VERSIONS:]:
        cachefile.unlink(old)
    prune(spec.folder)
    if reuse.made_count():
        return f"stored (xacro expansions: {reuse.taken_count()} reused, " \
               f"{reuse.made_count() - reuse.taken_count()} expanded)"
    return "stored"


def _tag(folder: str) -> None:
    """CACHEDIR.TAG: backup tools skip the folder (https://bford.info/cachedir/)."""
    tag = os.path.join(folder, "CACHEDIR.TAG")
    if not os.path.exists(tag):
        try:
            with open(tag, "x", encoding="ascii") as f:
                f.write("Signature: 8a477f597d28d172789f06886806bc55\n# urdfcheck's lint cache\n")
        except OSError:
            pass


def prune(folder: str, max_bytes: int = MAX_BYTES, max_entries: int = MAX_ENTRIES) -> int:
    """Remove the least recently used entries (and temporary files left by a killed run) until the folder
    (one sub-folder per key) is under both bounds; returns how many files were removed."""
    import time

    entries, total, removed = [], 0, 0
    stale = time.time() - 3600
    try:
        with os.scandir(folder) as keys:
            subs = [k.path for k in keys if k.is_dir(follow_symlinks=False)]
    except OSError:
        return removed
    for sub in subs:
        try:
            with os.scandir(sub) as it:
                for e in it:
                    try:
                        st = e.stat(follow_symlinks=False)
                    except OSError:
                        continue
                    if e.name.endswith(".tmp") and st.st_mtime < stale:
                        removed += cachefile.unlink(e.path)
                    elif e.name.endswith(".json"):
                        entries.append((st.st_mtime_ns, st.st_size, e.path))
                        total += st.st_size
        except OSError:
            continue
    if total > max_bytes or len(entries) > max_entries:
        entries.sort()
        keep_bytes, keep_entries, left = max_bytes * 3 // 4, max_entries * 3 // 4, len(entries)
        for _, size, path in entries:
            if total <= keep_bytes and left <= keep_entries:
                break
            if cachefile.unlink(path):
                total -= size
                left -= 1
                removed += 1
    for sub in subs:  # an emptied key's folder
        try:
            os.rmdir(sub)
        except OSError:
            pass
    return removed


# --- the console entry ----------------------------------------------------------------------------------------------
def console() -> None:
    """`urdfcheck ...` (console script and `python -m urdfcheck`): a cache hit answers here; anything else runs
    `cli.main` and, for a lint run that may be stored, records it."""
    finish = None
    try:
        spec = plan(sys.argv[1:])
        if spec is not None:
            code = replay(spec)
            if code is not None:
                _exit(code)
            finish = record(spec)
    except BrokenPipeError:  # `urdfcheck lint | head`: as cli.main answers it
        _exit(0)
    except Exception:  # noqa: BLE001 - the cache never stops a run: without it, lint runs as usual
        if os.environ.get("URDFCHECK_DEBUG"):
            raise
    if lint_argv(sys.argv[1:])[:1] == ["lint"]:
        # a lint run pauses the collector (cli.main.cmd_lint): from here already, as the imports allocate many
        # objects and free few (and the xacro worker forked next starts with nothing to trace: core.worker)
        import gc

        gc.disable()
    fork_early(sys.argv[1:])
    from urdfcheck.cli import main

    main.run(after=finish)


# lint's options (cli/options.py, pure data): those taking a value (a value is not a path) and plain flags
_VALUED = options.valued_flags("lint")
_FLAGS = options.plain_flags("lint")


def fork_early(argv: list[str]) -> None:
    """Fork the xacro worker before argparse and cli.main are imported, with the limits the flags give, so it
    imports xacro meanwhile (cli.main would fork it a few milliseconds later: `_fork_xacro_worker`). The worker
    is used only when its limits equal the job's; an option this reading does not know leaves it to cli.main."""
    argv = lint_argv(list(argv))
    if not argv or argv[0] != "lint":
        return
    trusted, allow_env, timeout, paths, config = False, [], None, [], None
    it = iter(argv[1:])
    for a in it:
        if not a.startswith("-") or a == "-":
            paths.append(a)
            continue
        name, eq, value = a.partition("=")
        if name in ("--list", "--write-baseline"):  # no lint run (cli.main forks no worker for them either)
            return
        if name in _FLAGS and not eq:
            trusted = trusted or name == "--trusted"
            config = "" if name == "--no-config" else config
            continue
        if name not in _VALUED:
            return
        if not eq:
            value = next(it, None)
            if value is None:
                return
        if name == "--config" and config is None:
            config = value
        if name == "--allow-env":
            allow_env.append(value)
        elif name == "--timeout":
            try:
                timeout = float(value)
            except ValueError:
                return
    yaml_config = reads_yaml_config(config, paths or ["."])  # looked for once: both questions ask it
    if not may_hold_xacro(paths or ["."], config, yaml_config=yaml_config):
        return
    if _no_worker_expected():
        return
    # the XML front end (lxml) before the fork: this process needs it anyway, and the worker inherits it instead of
    # importing it again (17 ms of CPU); the worker is ready no later, as it would import it first
    from urdfcheck.core import worker, xmlfront  # noqa: F401
    from urdfcheck.load.xacro import SPARE, SPARE_PRELOAD, XACRO_TIMEOUT, worker_limits

    _both_import()
    if yaml_config:
        from urdfcheck.core import yamlimport  # noqa: F401 - the config's reader here, xacro's there

    worker.keep_spare(SPARE, worker_limits(trusted, allow_env, timeout or XACRO_TIMEOUT), SPARE_PRELOAD)


def _no_worker_expected() -> bool:
    """The lint cache offers every expansion the newest stored run made (`_offer`): no xacro worker up front
    (the loader starts one if an expansion is not offered after all)."""
    reuse = sys.modules.get("urdfcheck.load.reuse")
    return reuse is not None and reuse.all_expected()


def _both_import() -> None:
    """What the worker imports and this process imports later anyway: imported once, before the fork, instead of
    once on each side (~10 ms of CPU on two cores that the expansions need). Only what every xacro lint imports:
    a module only the worker needs stays out, as this process would wait for it instead of importing the rules.

    ast and glob: the worker always imports them (xacro, the expander), this process for any launch file."""
    import ast  # noqa: F401 - xacro there, Python launch files here
    import glob  # noqa: F401 - the expander there, the deployment finder here
    import math  # noqa: F401
    import resource  # noqa: F401 - the worker's limits there, the run's memory budget here
    import weakref  # noqa: F401

    from urdfcheck.consumers import params, yamldoc  # noqa: F401
    from urdfcheck.core import door, observe, paths, safeio  # noqa: F401
    from urdfcheck.load import packages  # noqa: F401


def _exit(code: int) -> None:
    for stream in (sys.stdout, sys.stderr):
        try:
            stream.flush()
        except (BrokenPipeError, OSError, ValueError):
            pass
    os._exit(code)
