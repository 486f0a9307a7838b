"""Run a function in a forked child with memory, CPU and wall-clock limits.

Forking keeps start-up cost near zero (the child inherits the imported modules) and lets the child
patch module globals freely: nothing it does reaches the parent. A crash, an out-of-memory or a
time-out comes back as a `Failure`, never as a result.
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

DEFAULT_MEMORY = 2 * 1024**3
DEFAULT_TIMEOUT = 20.0
MAX_RESULT = 256 * 1024 * 1024
DELIVERY_GRACE = 2.0  # seconds a late-collected child has to hand over its result


class Failure(FrozenRecord):
    # kind: "timeout", "memory", "crashed", "output", "error"
    _fields = ('kind', 'message', 'stderr')

    def __init__(self, kind: str, message: str, stderr: str = ""):
        d = self.__dict__  # FrozenRecord forbids setattr
        d["kind"] = kind
        d["message"] = message
        d["stderr"] = stderr


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
    sys.argv[:] = WORKER_ARGV
    if hasattr(sys, "orig_argv"):
        sys.orig_argv = list(WORKER_ARGV)


def _limit(memory: int | None, cpu: float | None) -> None:
    import resource

    if memory:
        resource.setrlimit(resource.RLIMIT_AS, (memory, memory))
    if cpu:
        secs = int(cpu) + 1
        resource.setrlimit(resource.RLIMIT_CPU, (secs, secs + 1))
    resource.setrlimit(resource.RLIMIT_CORE, (0, 0))


def run(fn, *args, timeout: float = DEFAULT_TIMEOUT, memory: int | None = DEFAULT_MEMORY,
        capture_fd2: bool = False, env_keep=(), scrub_env: bool = True, **kwargs):
    """fn(*args, **kwargs) in a child. Returns its (picklable) result or a Failure."""
    return start(fn, *args, timeout=timeout, memory=memory, capture_fd2=capture_fd2, env_keep=env_keep,
                 scrub_env=scrub_env, **kwargs).result()


def start(fn, *args, timeout: float = DEFAULT_TIMEOUT, memory: int | None = DEFAULT_MEMORY,
          capture_fd2: bool = False, env_keep=(), scrub_env: bool = True, grace: float = DELIVERY_GRACE,
          **kwargs) -> "Job":
    """Fork the child now and return at once: the caller works on while it runs. The clock starts here.

    The child starts with a scrubbed environment (`ENV_ALLOW` + `env_keep`) and argv unless `scrub_env` is
    false (--trusted expansions, whose $(env) may read any variable)."""
    if not hasattr(os, "fork"):  # pragma: no cover - non-POSIX: no isolation available
        return Job(None, None, None, None, value=fn(*args, **kwargs))
    rfd, wfd = os.pipe()
    efd_r = efd_w = None
    if capture_fd2:
        efd_r, efd_w = os.pipe()
    sys.stdout.flush()
    sys.stderr.flush()
    pid = os.fork()
    if pid == 0:  # child
        code = 0
        try:
            os.close(rfd)
            if efd_w is not None:
                os.close(efd_r)
                os.dup2(efd_w, 2)
            _limit(memory, timeout)
            if scrub_env:
                scrub(env_keep)
            else:
                sys.argv[:] = WORKER_ARGV
            gc.enable()  # a one-shot lint pauses the collector; an expansion makes cyclic garbage (DOM trees)
            try:
                payload = ("ok", fn(*args, **kwargs))
            except MemoryError:
                payload = ("memory", "out of memory")
            except RecursionError:
                payload = ("error", "recursion too deep")
            except BaseException as e:  # report, never propagate into the parent's code path
                payload = ("error", f"{type(e).__name__}: {e}")
            try:
                data = pickle.dumps(payload, protocol=pickle.HIGHEST_PROTOCOL)
            except MemoryError:
                data = pickle.dumps(("memory", "out of memory"))
            except Exception as e:
                data = pickle.dumps(("error", f"result not transferable: {e}"))
            view = memoryview(data)
            while view:
                n = os.write(wfd, view)
                view = view[n:]
        except BaseException:
            code = 70
        finally:
            os._exit(code)
    os.close(wfd)
    if efd_w is not None:
        os.close(efd_w)
    return Job(pid, rfd, efd_r, time.monotonic() + timeout, timeout=timeout, grace=grace)


class Job:
    """A running child. `result()` waits for it (once); `cancel()` kills it. Either reaps the child."""

    def __init__(self, pid, rfd, efd, deadline, timeout: float = DEFAULT_TIMEOUT, value=None,
                 grace: float = DELIVERY_GRACE):
        self.pid, self.rfd, self.efd, self.deadline, self.timeout = pid, rfd, efd, deadline, timeout
        self.value = value
        self.grace = grace

    def cancel(self) -> None:
        if self.pid is None:
            return
        try:
            os.kill(self.pid, signal.SIGKILL)
        except ProcessLookupError:
            pass
        self._reap()

    def _reap(self) -> int:
        pid, self.pid = self.pid, None
        _, status = os.waitpid(pid, 0)
        for fd in (self.rfd, self.efd):
            if fd is not None:
                try:
                    os.close(fd)
                except OSError:
                    pass
        return status

    def result(self):
        if self.pid is None:
            return self.value
        rfd, efd_r, timeout = self.rfd, self.efd, self.timeout
        # A child that finished while the caller was busy may still be writing into the full pipe: it gets a
        # moment to deliver, not a time-out. (A child burning CPU meanwhile was stopped by RLIMIT_CPU.)
        deadline = max(self.deadline, time.monotonic() + min(timeout, self.grace))
        chunks, size, errs = [], 0, []
        failure = None
        open_fds = {rfd} | ({efd_r} if efd_r is not None else set())
        try:
            while rfd in open_fds:
                left = deadline - time.monotonic()
                if left <= 0:
                    failure = Failure("timeout", f"did not finish within {timeout:g} s")
                    break
                ready, _, _ = select.select(list(open_fds), [], [], left)
                for fd in ready:
                    block = os.read(fd, 1 << 20)
                    if not block:
                        open_fds.discard(fd)
                    elif fd == rfd:
                        chunks.append(block)
                        size += len(block)
                        if size > MAX_RESULT:
                            failure = Failure("output", f"output larger than {MAX_RESULT} bytes")
                            open_fds.discard(rfd)
                    else:
                        if sum(len(e) for e in errs) < 65536:
                            errs.append(block)
        finally:
            if failure is not None:
                try:
                    os.kill(self.pid, signal.SIGKILL)
                except ProcessLookupError:
                    pass
            status = self._reap()
        self.value = _outcome(status, failure, chunks, b"".join(errs).decode("utf-8", "replace"), timeout)
        return self.value


def _outcome(status: int, failure, chunks, stderr: str, timeout: float):
    if failure is not None:
        return Failure(failure.kind, failure.message, stderr)
    if os.WIFSIGNALED(status):
        sig = os.WTERMSIG(status)
        if sig in (signal.SIGXCPU, signal.SIGKILL):
            return Failure("timeout", f"used more than {timeout:g} s of CPU", stderr)
        name = signal.Signals(sig).name if sig in signal.Signals._value2member_map_ else str(sig)
        return Failure("crashed", f"crashed with signal {name}", stderr)
    try:
        kind, value = pickle.loads(b"".join(chunks))
    except Exception:
        return Failure("crashed", f"exited with status {os.WEXITSTATUS(status)} and no result", stderr)
    if kind == "ok":
        return value
    return Failure(kind, value, stderr)
