"""Run a function in a forked child with memory, CPU and wall-clock limits: the one sandbox of urdfcheck.

Forking keeps start-up cost near zero (the child inherits the imported modules) and lets the child
patch module globals freely: nothing it does reaches the parent. A crash, an out-of-memory or a
time-out comes back as a `Failure`, never as a result.

Two ways in, one child:

* ``start(fn, *args)`` (xacro expansion): the child runs fn at once; arguments are inherited, not pickled.
* ``prepare(fn, preload=...)`` then ``job.send(*args)`` (the verify peers): the child imports `preload`
  while the parent works on, then waits for its arguments (pickled through a temp file, so the parent never
  blocks on a child that is still importing). The clock starts when the job is sent. ``progress=True``
  passes fn a ``progress(done, total)`` callable as its first argument; ``wait(jobs, on_progress)`` reports.
* ``keep_spare(key, limits, preload)`` then ``take_spare(key, limits)``: a prepared child forked before the
  caller knows its job (the console lint forks the xacro worker before it imports the planner, so the two
  imports run at once); the job names its function as ``"module:function"``. A spare whose limits differ from
  the job's is not used. A spare leads its own process group: a job that forks children of its own (a batch of
  expansions, each in a child of the spare) is ended with them.

Every child gets the same limits (`Limits`): an address-space allowance on top of what it inherits, a CPU
limit and a wall clock per job, core dumps off, and (unless trusted) a scrubbed environment and argv.
"""
from __future__ import annotations

import gc
import os
import pickle
import select
import signal
import sys
import time

from urdfcheck.core.records import FrozenRecord

DEFAULT_MEMORY = 2 * 1024**3  # address space a child may add to what it inherits
DEFAULT_TIMEOUT = 20.0
MAX_RESULT = 256 * 1024 * 1024
MAX_OUTPUT = 256 * 1024  # captured stdout/stderr kept
DELIVERY_GRACE = 2.0  # seconds a late-collected child has to hand over its result
PROGRESS_INTERVAL = 0.1  # seconds between progress messages from a child


class Failure(FrozenRecord):
    # kind: "timeout", "memory", "crashed", "output", "error"
    _fields = ('kind', 'message', 'stderr')
    _defaults = {"stderr": ""}


class Limits(FrozenRecord):
    """What every child is held to. memory: bytes of address space on top of the parent's at fork (None: no
    limit); timeout: wall-clock seconds for the job, and the job's CPU seconds (RLIMIT_CPU, +1); result: bytes
    of pickled result (None: no cap, for results whose size the parent chose); scrub_env: drop the environment
    but `env_keep` (argv is always replaced)."""

    _fields = ('memory', 'timeout', 'result', 'scrub_env', 'env_keep')
    memory: int | None
    timeout: float
    result: int | None
    scrub_env: bool
    env_keep: tuple

    def __init__(self, memory: int | None = DEFAULT_MEMORY, timeout: float = DEFAULT_TIMEOUT,
                 result: int = MAX_RESULT, scrub_env: bool = True, env_keep=()):
        d = self.__dict__
        d["memory"] = memory
        d["timeout"] = timeout
        d["result"] = result
        d["scrub_env"] = scrub_env
        d["env_keep"] = tuple(env_keep)


# What a worker keeps of the environment (plus what the caller names, e.g. --allow-env). A CI job's environment
# holds its secrets; an expansion needs none of it. Locale only: it was read at start-up already.
ENV_ALLOW = ("LANG", "LANGUAGE", "LC_ALL", "LC_CTYPE", "TZ")
WORKER_ARGV = ["urdfcheck-worker"]


def scrub(keep=()) -> None:
    """In the child: drop every environment variable not allow-listed, from every copy Python keeps (os.environ,
    os.environb, posix.environ, which a format-string walk could reach, and the C environment through unsetenv),
    and the command line (sys.argv, sys.orig_argv)."""
    allowed = set(ENV_ALLOW) | set(keep)
    for key in list(os.environ):
        if key not in allowed:
            del os.environ[key]  # unsetenv as well
    environb = getattr(os, "environb", None)
    if environb is not None:
        for key in list(environb):
            if os.fsdecode(key) not in allowed:
                environb._data.pop(key, None)  # the C environment is already clean
    posix = sys.modules.get("posix") or sys.modules.get("nt")
    raw = getattr(posix, "environ", None)
    if isinstance(raw, dict):
        for key in list(raw):
            if os.fsdecode(key) not in allowed:
                del raw[key]
    _replace_argv()


def _replace_argv() -> None:
    sys.argv[:] = WORKER_ARGV
    if hasattr(sys, "orig_argv"):
        sys.orig_argv = list(WORKER_ARGV)


def _vm_size() -> int:
    try:
        with open("/proc/self/status") as f:
            for line in f:
                if line.startswith("VmSize:"):
                    return int(line.split()[1]) * 1024
    except OSError:
        pass
    return 0


def _cpu_used() -> float:
    import resource

    r = resource.getrusage(resource.RUSAGE_SELF)
    return r.ru_utime + r.ru_stime


def _limit_memory(memory: int | None) -> None:
    """Address space and core dumps, at fork. The allowance is on top of what the child inherits: an absolute
    limit would fail every child of a parent that has grown past it."""
    import resource

    resource.setrlimit(resource.RLIMIT_CORE, (0, 0))
    if memory:
        limit = _vm_size() + int(memory)
        _lower(resource.RLIMIT_AS, limit, limit)


def _limit_cpu(timeout: float | None) -> None:
    """CPU seconds for the job, from now (a prepared child's imports do not count)."""
    import resource

    if timeout:
        secs = int(_cpu_used() + timeout) + 1
        _lower(resource.RLIMIT_CPU, secs, secs + 1)


def _lower(which, soft: int, hard: int) -> None:
    """Set a limit, never above the one the user already set (ulimit): raising a hard limit fails."""
    import resource

    _, cur = resource.getrlimit(which)
    if cur != resource.RLIM_INFINITY:
        soft, hard = min(soft, cur), min(hard, cur)
    resource.setrlimit(which, (soft, hard))


def _resolve(limits, timeout, memory, env_keep, scrub_env) -> Limits:
    if limits is not None:
        return limits
    return Limits(memory=memory, timeout=timeout, scrub_env=scrub_env, env_keep=env_keep)


def run(fn, *args, timeout: float = DEFAULT_TIMEOUT, memory: int | None = DEFAULT_MEMORY,
        capture_fd2: bool = False, env_keep=(), scrub_env: bool = True, **kwargs):
    """fn(*args, **kwargs) in a child. Returns its (picklable) result or a Failure."""
    return start(fn, *args, timeout=timeout, memory=memory, capture_fd2=capture_fd2, env_keep=env_keep,
                 scrub_env=scrub_env, **kwargs).result()


def start(fn, *args, timeout: float = DEFAULT_TIMEOUT, memory: int | None = DEFAULT_MEMORY,
          capture_fd2: bool = False, env_keep=(), scrub_env: bool = True, grace: float = DELIVERY_GRACE,
          **kwargs) -> Job:
    """Fork the child now and return at once: the caller works on while it runs. The clock starts here.

    The child starts with a scrubbed environment (`ENV_ALLOW` + `env_keep`) and argv unless `scrub_env` is
    false (--trusted expansions, whose $(env) may read any variable). `capture_fd2`: the child's stderr comes
    back in `Job.stderr` / `Failure.stderr` instead of reaching the terminal."""
    if not hasattr(os, "fork"):  # pragma: no cover - non-POSIX: no isolation available
        return Job(None, None, None, None, value=fn(*args, **kwargs))
    lim = _resolve(None, timeout, memory, env_keep, scrub_env)
    job = _fork(fn, lim, call=(args, kwargs), capture="stderr" if capture_fd2 else "", grace=grace)
    job.started = time.monotonic()
    job.deadline = job.started + lim.timeout
    return job


def prepare(fn, *, limits: Limits | None = None, preload=(), progress: bool = False, capture: str = "output",
            name: str = "", grace: float = DELIVERY_GRACE) -> Job:
    """Fork a child that imports `preload` and then waits for ``job.send(*args)``; the clock starts there.
    `capture`: "output" (C-level stdout and stderr), "stderr" or "" (none); captured text is `Job.stderr`."""
    return _fork(fn, limits or Limits(), preload=preload, progress=progress, capture=capture, name=name,
                 grace=grace)


def _fork(fn, lim: Limits, *, call=None, preload=(), progress=False, capture="", name="",
          grace=DELIVERY_GRACE, group: bool = False) -> Job:
    rfd, wfd = os.pipe()
    efd_r = efd_w = prog_r = prog_w = go_r = go_w = job_file = None
    if capture:
        efd_r, efd_w = os.pipe()
    if progress:
        prog_r, prog_w = os.pipe()
    if call is None:
        go_r, go_w = os.pipe()
        job_file = _scratch_file()
    sys.stdout.flush()
    sys.stderr.flush()
    pid = os.fork()
    if pid == 0:  # child
        code = 0
        try:
            if group:
                os.setpgid(0, 0)
            for fd in (rfd, efd_r, prog_r, go_w):
                if fd is not None:
                    os.close(fd)
            _child(fn, lim, call, preload, prog_w, efd_w, capture, go_r, job_file, wfd)
        except BaseException:
            code = 70
        finally:
            os._exit(code)
    for fd in (wfd, efd_w, prog_w, go_r):
        if fd is not None:
            os.close(fd)
    if group:
        try:  # here too: a kill sent before the child ran must reach its group (the usual two-sided call)
            os.setpgid(pid, pid)
        except OSError:
            pass
    job = Job(pid, rfd, efd_r, None, timeout=lim.timeout, grace=grace)
    job.group = group
    job.limits, job.name, job.prog_fd, job.go_fd, job.job_file = lim, name, prog_r, go_w, job_file
    return job


def _scratch_file():
    """An anonymous file for a prepared job's arguments: a memfd where there is one (nothing on disk, and no
    `tempfile` import, which pulls in `random` and `hashlib`: 3 ms of the console's start-up)."""
    if hasattr(os, "memfd_create"):
        try:
            return os.fdopen(os.memfd_create("urdfcheck-job", os.MFD_CLOEXEC), "w+b")
        except OSError:
            pass
    import tempfile

    return tempfile.TemporaryFile()


def _child(fn, lim: Limits, call, preload, prog_w, efd_w, capture, go_r, job_file, wfd) -> None:
    observe = sys.modules.get("urdfcheck.core.observe")
    if observe is not None:  # the lint cache: what this child reports (see `forked`)
        observe.forked()
    if efd_w is not None:
        os.dup2(efd_w, 2)
        if capture == "output":  # a library's C-level prints (Pinocchio, yourdfpy's logging) come back too
            os.dup2(efd_w, 1)
            sys.stdout = sys.stderr = open(2, "w", closefd=False)  # Python-level writes too
        import faulthandler

        if faulthandler.is_enabled():  # it would write to an inherited descriptor, not ours
            faulthandler.disable()
    _limit_memory(lim.memory)
    for module in preload:  # while the parent works on
        try:
            __import__(module)
        except BaseException:
            pass
    if lim.scrub_env:
        scrub(lim.env_keep)
    else:
        _replace_argv()
    if call is None:
        if not os.read(go_r, 1):  # cancelled before a job arrived
            os._exit(0)
        job_file.seek(0)
        guard, args = pickle.load(job_file)
        kwargs = {}
        if guard is not None:
            from urdfcheck.core import door

            door.enter_carried(guard)
    else:
        args, kwargs = call
    if prog_w is not None:
        args = (_progress_writer(prog_w),) + tuple(args)
    _limit_cpu(lim.timeout)
    # a one-shot lint pauses the collector; an expansion makes cyclic garbage (DOM trees). What this child
    # inherited and imported is never garbage here: frozen, the collector never traces it (tracing writes to
    # every object, and each page written is copied from the parent's)
    gc.freeze()
    gc.enable()
    t0 = time.monotonic()
    try:
        payload: tuple = ("ok", fn(*args, **kwargs))
    except MemoryError:
        payload = ("memory", "out of memory")
    except RecursionError:
        payload = ("error", "recursion too deep")
    except BaseException as e:  # report, never propagate into the parent's code path
        payload = ("error", f"{type(e).__name__}: {e}")
    payload += (time.monotonic() - t0,)
    try:
        data = pickle.dumps(payload, protocol=pickle.HIGHEST_PROTOCOL)
    except MemoryError:
        data = pickle.dumps(("memory", "out of memory (result)", payload[2]))
    except Exception as e:
        data = pickle.dumps(("error", f"result not transferable: {e}", payload[2]))
    for stream in (sys.stdout, sys.stderr):
        try:
            stream.flush()
        except Exception:
            pass
    view = memoryview(data)
    while view:
        n = os.write(wfd, view)
        view = view[n:]


def _progress_writer(fd):
    last = [0.0]

    def progress(done, total):
        now = time.monotonic()
        if now - last[0] < PROGRESS_INTERVAL and done < total:
            return
        last[0] = now
        try:
            os.write(fd, f"{done} {total}\n".encode())
        except OSError:
            pass

    return progress


# --- spares: prepared children forked before their job is known ----------------------------------------------
_SPARES: dict = {}


def _by_name(ref: str, *args):
    """Call `module:function` in a prepared child: the function's module is imported there, not in the parent."""
    import importlib

    module, _, name = ref.partition(":")
    return getattr(importlib.import_module(module), name)(*args)


def keep_spare(key: str, limits: Limits, preload=()) -> None:
    """Fork a child now that imports `preload` and waits; `take_spare` hands it a job, `drop_spares` ends it."""
    if hasattr(os, "fork") and key not in _SPARES:
        _SPARES[key] = _fork(_by_name, limits, preload=preload, group=True)


def spare_limits(key: str) -> Limits | None:
    """The limits of the spare kept under `key` (None: there is none): whether a job may go to it."""
    job = _SPARES.get(key)
    return job.limits if job is not None else None


def take_spare(key: str, limits: Limits):
    """The spare kept under `key` if it was forked with exactly these limits (then `job.send("module:fn", ...)`);
    None otherwise (a spare with other limits is ended: its environment or allowance would be wrong)."""
    job = _SPARES.pop(key, None)
    if job is not None and job.limits != limits:
        job.cancel()
        return None
    return job


def drop_spares() -> None:
    while _SPARES:
        _SPARES.popitem()[1].cancel()


class Job:
    """A running child. `result()` waits for it (once); `cancel()` kills it. Either reaps the child.

    After `result()`: `stderr` (captured output, if any) and `seconds` (the job's own run time)."""

    def __init__(self, pid, rfd, efd, deadline, timeout: float = DEFAULT_TIMEOUT, value=None,
                 grace: float = DELIVERY_GRACE):
        self.pid, self.rfd, self.efd, self.deadline, self.timeout = pid, rfd, efd, deadline, timeout
        self.value = value
        self.grace = grace
        self.name = ""
        self.limits: Limits | None = None
        self.group = False  # the child leads a process group: kills reach the children it forked
        self.prog_fd: int | None = None
        self.go_fd: int | None = None
        self.job_file = None  # a prepared child's job file (a binary file object)
        self.progress = (0, 0)
        self.started = time.monotonic()
        self.seconds = 0.0
        self.stderr = ""
        self._chunks: list[bytes] = []
        self._errs: list[bytes] = []
        self._size = 0
        self._failure: Failure | None = None

    def send(self, *args) -> None:
        """Hand a prepared child its arguments; its clock starts now."""
        assert self.job_file is not None and self.go_fd is not None, "send: the child was not prepared"
        # a prepared child was forked before the run entered its door (cli.cache.fork_early, cli.main): the guard
        # of the run in progress goes with the job, so the child reads as a worker forked now would (issue 36)
        door = sys.modules.get("urdfcheck.core.door")
        guard = door.carried() if door is not None else None
        pickle.dump((guard, args), self.job_file, protocol=pickle.HIGHEST_PROTOCOL)
        self.job_file.flush()
        try:
            os.write(self.go_fd, b"1")
        except OSError:  # the child is gone already: collecting it says how
            pass
        self._close("go_fd")
        self.started = time.monotonic()
        self.deadline = self.started + self.timeout

    def cancel(self) -> None:
        if self.pid is None:
            return
        self._kill()
        self._reap()

    def _kill(self) -> None:
        if self.group:
            try:
                os.killpg(self.pid, signal.SIGKILL)
                return
            except OSError:  # no group (yet, or any more): the child alone
                pass
        try:
            os.kill(self.pid, signal.SIGKILL)
        except ProcessLookupError:
            pass

    def _close(self, attr: str) -> None:
        fd = getattr(self, attr)
        setattr(self, attr, None)
        if fd is not None:
            try:
                os.close(fd)
            except OSError:
                pass

    def _reap(self) -> int:
        pid, self.pid = self.pid, None
        _, status, usage = os.wait4(pid, 0)
        self._cpu = usage.ru_utime + usage.ru_stime
        for attr in ("rfd", "efd", "prog_fd", "go_fd"):
            self._close(attr)
        if self.job_file is not None:
            self.job_file.close()
            self.job_file = None
        return status

    # --- waiting (see `wait`) -----------------------------------------------------------------------------
    def _fds(self) -> list:
        return [fd for fd in (self.rfd, self.efd, self.prog_fd) if fd is not None]

    def _read(self, fd) -> None:
        block = os.read(fd, 1 << 20)
        if fd == self.prog_fd:
            if not block:
                self._close("prog_fd")
                return
            lines = block.decode(errors="replace").split()
            if len(lines) >= 2:
                try:
                    self.progress = (int(lines[-2]), int(lines[-1]))
                except ValueError:
                    pass
        elif not block:
            self._close("rfd" if fd == self.rfd else "efd")
        elif fd == self.rfd:
            self._chunks.append(block)
            self._size += len(block)
            limit = self.limits.result if self.limits is not None else MAX_RESULT
            if limit is not None and self._size > limit:
                self._failure = Failure("output", f"output larger than {limit} bytes")
                self._close("rfd")
        elif self._size_errs() < MAX_OUTPUT:
            self._errs.append(block)

    def _size_errs(self) -> int:
        return sum(len(e) for e in self._errs)

    def _finish(self) -> None:
        if self._failure is not None:
            self._kill()
        if self.efd is not None and self._failure is None:  # what the child wrote just before it exited
            while self.efd is not None and select.select([self.efd], [], [], 0)[0]:
                self._read(self.efd)
        status = self._reap()
        self.stderr = b"".join(self._errs).decode("utf-8", "replace")
        self.value, self.seconds = _outcome(status, self._failure, self._chunks, self.stderr, self.timeout,
                                            self._cpu, time.monotonic() - self.started)
        self._chunks = self._errs = []

    def result(self):
        if self.pid is None:
            return self.value
        wait([self])
        return self.value


def wait(jobs, on_progress=None, on_done=None) -> None:
    """Collect every job (see `Job.result`), reading all their pipes together. `on_progress(job)` when a
    job reports progress, `on_done(job)` when it is collected."""
    # A child that finished while the caller was busy may still be writing into the full pipe: it gets a
    # moment to deliver, not a time-out. (A child burning CPU meanwhile was stopped by RLIMIT_CPU.)
    now = time.monotonic()
    pending = [j for j in jobs if j.pid is not None]
    ends = {id(j): max(j.deadline if j.deadline is not None else now + j.timeout, now + min(j.timeout, j.grace))
            for j in pending}
    try:
        while pending:
            now = time.monotonic()
            for j in list(pending):
                if j.rfd is None or (j._failure is None and now >= ends[id(j)]):
                    if j.rfd is not None:
                        j._failure = Failure("timeout", f"did not finish within {j.timeout:g} s")
                    pending.remove(j)
                    j._finish()
                    if on_done:
                        on_done(j)
            if not pending:
                break
            owner = {fd: j for j in pending for fd in j._fds()}
            left = max(0.0, min(ends[id(j)] for j in pending) - now)
            ready, _, _ = select.select(list(owner), [], [], left)
            for fd in ready:
                j = owner[fd]
                before = j.progress
                j._read(fd)
                if on_progress and j.progress != before:
                    on_progress(j)
    finally:
        for j in pending:  # interrupted: never leave a child behind
            if j.pid is not None:
                j.cancel()


def _outcome(status: int, failure, chunks, stderr: str, timeout: float, cpu: float, elapsed: float):
    """(value or Failure, seconds)."""
    if failure is not None:
        return Failure(failure.kind, failure.message, stderr), elapsed
    if os.WIFSIGNALED(status):
        sig = os.WTERMSIG(status)
        name = signal.Signals(sig).name if sig in signal.Signals._value2member_map_ else str(sig)
        if sig == signal.SIGXCPU or (sig == signal.SIGKILL and cpu >= timeout):  # RLIMIT_CPU, soft or hard
            return Failure("timeout", f"used more than {timeout:g} s of CPU", stderr), elapsed
        if "bad_alloc" in stderr or "MemoryError" in stderr:  # a C++ library aborting on the address-space limit
            return Failure("memory", f"killed by {name} after a failed allocation", stderr), elapsed
        if sig == signal.SIGKILL:
            return Failure("crashed", "killed by SIGKILL (the kernel's out-of-memory killer?)", stderr), elapsed
        return Failure("crashed", f"crashed with signal {name}", stderr), elapsed
    try:
        kind, value, seconds = pickle.loads(b"".join(chunks))
    except Exception:
        return Failure("crashed", f"exited with status {os.WEXITSTATUS(status)} and no result", stderr), elapsed
    if kind == "ok":
        return value, seconds
    return Failure(kind, value, stderr), seconds
