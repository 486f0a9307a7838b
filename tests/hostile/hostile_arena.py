"""Harness for the hostile-input tests (one test module per attack in this folder).

Every attack runs the real CLI in-process (`conftest.run_cli`) inside a throw-away arena:

    <tmp>/                      the working directory of the CLI call
      ws/victim_description/    the package under test (package.xml, urdf/, config/, meshes/)
      outside/                  secrets next to the workspace, outside every package root:
        secret.txt, secret.xacro, secret.yaml   (all carry CANARY_FILE)
        PWNED                   the marker every code-execution payload tries to `touch`

and one call (`Arena.lint`) asserts what must hold for *every* hostile input:

* exit code 1 (a hostile model is a finding, never a crash or a usage error);
* the whole CLI call takes at most TIME_BOUND seconds of wall time;
* nothing was written anywhere: the arena listing (names, sizes, mtimes) is unchanged, and an audit
  hook saw no write-mode open, no file-system mutation, no process or network start;
* no secret leaked: neither the environment canary, nor the canary file's text, nor /etc/passwd's
  first line appears on stdout or stderr;
* nothing outside the package roots was opened, listed or stat'ed (following links) by the parent or
  by the forked xacro worker (the audit hook and the os.stat wrapper are inherited across fork; the
  child reports through an O_APPEND log file). `os.lstat` of path components, which `realpath` needs
  to resolve symlinks before deciding a path is outside, is deliberately not counted;
* the marker file the payloads `touch` does not exist.

Data files live in `data/`; `@MARKER@`, `@OUTSIDE@` and `@CANARY_VAR@` in them are replaced by the
arena's paths when they are copied into the package.
"""
from __future__ import annotations

import json
import os
import sys
import time
from dataclasses import dataclass, field
from pathlib import Path

import pytest
from conftest import flatten, run_cli

DATA = Path(__file__).resolve().parent / "data"
# wall-clock bound for one whole CLI call on hostile input: a guard against hangs, not a speed target (each refusal
# is asserted by what it counts -- elements, steps, bytes -- and speed lives in bench/). 2 s failed on a busy
# 2-core machine at 2.1 s; the default timeout of one expansion is 20 s (URDFCHECK_HOSTILE_TIME_BOUND overrides).
TIME_BOUND = float(os.environ.get("URDFCHECK_HOSTILE_TIME_BOUND", "8.0"))
CANARY_VAR = "URDFCHECK_CANARY_TOKEN"
CANARY_ENV = "canary-env-7c1e5d2a90"
CANARY_FILE = "canary-file-4b9f03e6d1"
PASSWD_MARK = "root:x:0:0"
PKG = "victim_description"
XACRO_NS = 'xmlns:xacro="http://www.ros.org/wiki/xacro"'
MAX_OUTPUT = 64 * 1024  # bytes of report for a handful of findings, whatever the input's size


def formats() -> list[str]:
    from urdfcheck.report import FORMATS

    return list(FORMATS)


# --------------------------------------------------------------------------------------------------
# Audit: a process-wide hook (armed only during Arena.lint) plus an os.stat wrapper. Both survive the
# worker's fork; records go through a pre-opened O_APPEND fd (os.write raises no audit event).
# --------------------------------------------------------------------------------------------------

class _Audit:
    fd: int | None = None
    forbidden: tuple[str, ...] = ()


_EXEC_EVENTS = ("os.system", "os.exec", "os.posix_spawn", "os.spawn", "subprocess.Popen", "pty.spawn",
                "os.startfile", "ctypes.dlopen", "socket.connect", "socket.bind", "socket.getaddrinfo",
                "urllib.Request", "webbrowser.open")
_MUTATE_EVENTS = ("os.remove", "os.rename", "os.mkdir", "os.rmdir", "os.chmod", "os.chown", "os.symlink",
                  "os.link", "os.truncate", "os.utime", "os.mkfifo", "os.mknod",
                  "shutil.copyfile", "shutil.copytree", "shutil.move", "shutil.rmtree")
_PATH_EVENTS = ("os.listdir", "os.scandir")
_WRITE_FLAGS = os.O_WRONLY | os.O_RDWR | os.O_CREAT | os.O_TRUNC | os.O_APPEND


def _as_path(p) -> str | None:
    if isinstance(p, bytes):
        p = p.decode("utf-8", "replace")
    if isinstance(p, os.PathLike):
        p = os.fspath(p)
    if not isinstance(p, str):
        return None
    return os.path.abspath(p)


def _under_forbidden(path: str | None) -> bool:
    return path is not None and any(path == f or path.startswith(f.rstrip("/") + "/") for f in _Audit.forbidden)


def _bytecode_cache(event: str, args) -> bool:
    """The import system writing a module's bytecode (a module first imported during the lint, with bytecode
    writing on): `mkdir __pycache__`, then a temporary .pyc renamed into place. The interpreter's cache, never the
    checked tree (whose listing is compared separately); write-opens there are not counted either."""
    paths = [_as_path(a) for a in args if isinstance(a, (str, bytes, os.PathLike))]
    if not paths or any(p is None for p in paths):
        return False
    if event == "os.mkdir":
        return os.path.basename(paths[0]) == "__pycache__"
    return event in ("os.rename", "os.replace") and all(
        os.path.basename(os.path.dirname(p)) == "__pycache__" and ".pyc" in os.path.basename(p) for p in paths)


def _record(text: str) -> None:
    fd = _Audit.fd
    if fd is not None:
        try:
            os.write(fd, (f"[pid {os.getpid()}] " + text.replace("\n", " ") + "\n").encode("utf-8", "replace"))
        except OSError:
            pass


def _hook(event: str, args) -> None:
    if _Audit.fd is None:
        return
    if event.startswith(_EXEC_EVENTS):
        _record(f"{event} {args!r}"[:500])
    elif event.startswith(_MUTATE_EVENTS):
        if not _bytecode_cache(event, args):
            _record(f"mutate {event} {args!r}"[:500])
    elif event == "open":
        path = _as_path(args[0]) if args else None
        mode = args[1] if len(args) > 1 else None
        flags = args[2] if len(args) > 2 else 0
        writing = (isinstance(mode, str) and any(c in mode for c in "wax+")) or \
            (mode is None and isinstance(flags, int) and flags & _WRITE_FLAGS)
        if writing and path is not None and "__pycache__" not in path:
            _record(f"write-open {path} mode={mode!r} flags={flags!r}")
        elif _under_forbidden(path):
            _record(f"open {path}")
    elif event in _PATH_EVENTS:
        path = _as_path(args[0]) if args else None
        if _under_forbidden(path):
            _record(f"{event} {path}")


sys.addaudithook(_hook)

_real_stat = os.stat


def _audited_stat(path, *args, **kwargs):
    if _Audit.fd is not None and kwargs.get("follow_symlinks", True) and not isinstance(path, int):
        p = _as_path(path)
        if _under_forbidden(p):
            _record(f"stat {p}")
    return _real_stat(path, *args, **kwargs)


# --------------------------------------------------------------------------------------------------
# The arena
# --------------------------------------------------------------------------------------------------

@dataclass
class Outcome:
    code: int
    out: str
    err: str
    seconds: float
    fmt: str
    report: dict | None = None  # parsed JSON when fmt == "json"
    audit: list[str] = field(default_factory=list)

    @property
    def findings(self) -> list[dict]:
        # one finding per line, as the rules found them
        return flatten((self.report or {}).get("findings", []))

    def codes(self) -> list[str]:
        return [f["code"] for f in self.findings]

    def find(self, code: str, file_suffix: str | None = None, line: int | None = None) -> dict:
        """The one finding with this code (and location); fails with the whole report otherwise."""
        hits = [f for f in self.findings if f["code"] == code
                and (file_suffix is None or f["location"]["file"].endswith(file_suffix))
                and (line is None or f["location"]["line"] == line)]
        assert hits, f"no {code} at {file_suffix}:{line}; findings: " + json.dumps(
            [(f["code"], f["location"], f["message"][:160]) for f in self.findings], indent=1)
        return hits[0]


class Arena:
    def __init__(self, root: Path, monkeypatch, log_dir: Path):
        self.root = root
        self.ws = root / "ws"
        self.pkg = self.ws / PKG
        self.outside = root / "outside"
        self.marker = self.outside / "PWNED"
        self._mp = monkeypatch
        self._log = log_dir / "audit.log"
        (self.pkg / "urdf").mkdir(parents=True)
        (self.pkg / "config").mkdir()
        (self.pkg / "meshes").mkdir()
        (self.pkg / "package.xml").write_text(
            f'<?xml version="1.0"?>\n<package format="3">\n  <name>{PKG}</name>\n  <version>0.0.0</version>\n'
            "  <description>victim</description>\n  <maintainer email=\"a@b.c\">a</maintainer>\n"
            "  <license>BSD</license>\n</package>\n")
        (self.pkg / "meshes" / "base.stl").write_text("solid base\nendsolid base\n")
        self.outside.mkdir()
        (self.outside / "secret.txt").write_text(CANARY_FILE + "\n")
        (self.outside / "secret.xacro").write_text(f'<robot name="{CANARY_FILE}">\n  <link name="{CANARY_FILE}"/>\n'
                                                   f"</robot>\n")
        (self.outside / "secret.yaml").write_text(f"token: {CANARY_FILE}\nlink: {CANARY_FILE}\n")
        monkeypatch.setenv(CANARY_VAR, CANARY_ENV)

    # ---- files ----------------------------------------------------------------------------------
    def subst(self, text: str) -> str:
        return (text.replace("@MARKER@", str(self.marker)).replace("@OUTSIDE@", str(self.outside))
                .replace("@CANARY_VAR@", CANARY_VAR).replace("@PKG@", PKG))

    def write(self, rel: str, text: str) -> Path:
        p = self.pkg / rel
        p.parent.mkdir(parents=True, exist_ok=True)
        p.write_text(self.subst(text), encoding="utf-8")
        return p

    def data(self, name: str, rel: str | None = None) -> Path:
        """Copy data/<name> into the package (as `rel`, default urdf/<basename>)."""
        return self.write(rel or f"urdf/{Path(name).name}", (DATA / name).read_text(encoding="utf-8"))

    def rel(self, p: Path) -> str:
        return os.path.relpath(p, self.root)

    def listing(self) -> dict:
        out = {}
        for d, dirs, files in os.walk(self.root):
            for n in dirs + files:
                p = os.path.join(d, n)
                st = os.lstat(p)
                out[os.path.relpath(p, self.root)] = (st.st_mode, st.st_size, st.st_mtime_ns)
        return out

    # ---- one checked CLI call --------------------------------------------------------------------
    def lint(self, *targets, fmt: str = "json", extra=(), expect_code: int = 1, command: str = "lint",
             forbid_extra=()) -> Outcome:
        args = [command]
        if command == "lint":
            args += ["--no-config", "--format", fmt, "--color", "never"]
        args += [*extra, *[self.rel(Path(t)) if isinstance(t, Path) else t for t in targets]]
        before = self.listing()
        cwd_before = sorted(os.listdir(self.root))
        _Audit.forbidden = (str(self.outside), "/etc/passwd", "/etc/shadow", "/proc/self/environ",
                            *map(str, forbid_extra))
        fd = os.open(self._log, os.O_WRONLY | os.O_CREAT | os.O_APPEND, 0o600)
        self._mp.setattr(os, "stat", _audited_stat)
        _Audit.fd = fd
        t0 = time.monotonic()
        try:
            code, out, err = run_cli(args, cwd=self.root)
        finally:
            seconds = time.monotonic() - t0
            _Audit.fd = None
            self._mp.setattr(os, "stat", _real_stat)
            os.close(fd)
        audit = self._log.read_text().splitlines() if self._log.exists() else []
        self._log.unlink(missing_ok=True)
        report = json.loads(out) if fmt == "json" and command == "lint" and out.strip() else None
        outcome = Outcome(code, out, err, seconds, fmt, report, audit)
        if os.environ.get("URDFCHECK_HOSTILE_TIMES"):  # `-s` shows the wall time of every call
            print(f"\n[hostile] {seconds:6.3f} s  {fmt:8} {' '.join(args[6:] if command == 'lint' else args)}",
                  file=sys.__stderr__)

        where = f"{' '.join(map(str, args))}\nstdout: {out[:3000]}\nstderr: {err[:3000]}"
        assert code == expect_code, f"exit code {code}, wanted {expect_code}: {where}"
        assert "Traceback" not in err and "internal error" not in err, where
        assert seconds <= TIME_BOUND, f"took {seconds:.2f} s (bound {TIME_BOUND} s): {where}"
        assert not self.marker.exists(), f"code execution: the payload created {self.marker}"
        assert self.listing() == before, f"files changed: {set(self.listing()) ^ set(before)} {where}"
        assert sorted(os.listdir(self.root)) == cwd_before
        for secret in (CANARY_ENV, CANARY_FILE, PASSWD_MARK):
            assert secret not in out and secret not in err, f"secret {secret!r} leaked: {where}"
        assert not audit, "audit:\n" + "\n".join(audit)
        return outcome

    def lint_all_formats(self, *targets, extra=(), expect_code: int = 1) -> dict[str, Outcome]:
        return {fmt: self.lint(*targets, fmt=fmt, extra=extra, expect_code=expect_code) for fmt in formats()}


@pytest.fixture
def arena(tmp_path, monkeypatch, tmp_path_factory):
    root = tmp_path / "arena"
    root.mkdir()
    return Arena(root, monkeypatch, tmp_path_factory.mktemp("audit"))


# --------------------------------------------------------------------------------------------------
# Positive controls: the payloads are real (stock xacro, unsandboxed, in a forked child)
# --------------------------------------------------------------------------------------------------

def stock_xacro(path: Path, cwd: Path) -> str:
    """Expand with stock xacro (its own eval, no confinement). Returns the XML or the error text."""
    from urdfcheck.core import worker

    def run():
        import xacro

        os.chdir(cwd)
        try:
            return xacro.process_file(str(path)).toprettyxml(indent="  ")
        except BaseException as e:  # noqa: BLE001 - the control only reports
            return f"stock xacro failed: {type(e).__name__}: {e}"

    res = worker.run(run, timeout=30, scrub_env=False)  # the control: stock xacro as a user runs it
    return res if isinstance(res, str) else f"stock xacro failed: {res}"


def assert_stock_executes(arena: Arena, path: Path) -> None:
    """Stock xacro runs the payload (it creates the marker): the attack in the data file is real."""
    stock_xacro(path, arena.root)
    assert arena.marker.exists(), f"the payload in {path.name} does not work on stock xacro: the test is vacuous"
    arena.marker.unlink()


def line_of(path: Path, needle: str) -> int:
    """1-based line of the first line containing `needle` (the line findings must point at)."""
    for i, ln in enumerate(path.read_text(encoding="utf-8").splitlines(), 1):
        if needle in ln:
            return i
    raise AssertionError(f"{needle!r} not in {path}")
