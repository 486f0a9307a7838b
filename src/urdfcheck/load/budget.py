"""One budget for a whole lint run: wall-clock seconds for all models and variants, and the main process's memory.

Each xacro worker has its own limits (20 s, 2 GiB); without a budget for the run, eight hostile models with eight
automatic variants each cost 64 of those. `run_budget()` opens the budget for a run (the pipeline wraps a lint run in
it); `loader.begin` asks `current()` before it starts a model: a worker's time-out never reaches past the budget,
and a model that is not started, or is cut short, because the budget is spent gets an X017 finding at its entry
file instead of a result.

Defaults: URDFCHECK_RUN_BUDGET (seconds, or "SECONDS:MEGABYTES") or 300 s and 4 GiB of peak resident memory.
"""
from __future__ import annotations

import contextlib
import os
import time

DEFAULT_SECONDS = 300.0
DEFAULT_MEMORY = 4 * 1024**3
MIN_SLICE = 0.5  # an expansion is not started with less time than this left


class RunBudget:
    def __init__(self, seconds: float | None = None, memory: int | None = None):
        env_s, env_m = _from_env()
        self.seconds = float(seconds if seconds is not None else env_s if env_s is not None else DEFAULT_SECONDS)
        self.memory = int(memory if memory is not None else env_m if env_m is not None else DEFAULT_MEMORY)
        self.deadline = time.monotonic() + self.seconds

    def remaining(self) -> float:
        return self.deadline - time.monotonic()

    def spent(self) -> str | None:
        """Why nothing more may start (time or memory used up), or None."""
        if self.remaining() < MIN_SLICE:
            return f"the run's time budget ({self.seconds:g} s) is used up"
        rss = _peak_rss()
        if rss is not None and rss > self.memory:
            return f"the run's memory budget ({self.memory // 2**20} MiB) is used up"
        return None

    def timeout(self, requested: float) -> tuple[float, bool]:
        """(time-out for one expansion, whether the budget shortened it)."""
        left = max(self.remaining(), MIN_SLICE)
        return (left, True) if left < requested else (requested, False)


def _from_env() -> tuple[float | None, int | None]:
    raw = os.environ.get("URDFCHECK_RUN_BUDGET", "").strip()
    if not raw:
        return None, None
    secs, _, mem = raw.partition(":")
    try:
        s = float(secs) if secs else None
        m = int(float(mem) * 2**20) if mem else None
    except ValueError:
        return None, None
    return (s if s is None or s > 0 else None), (m if m is None or m > 0 else None)


def _peak_rss() -> int | None:
    # VmHWM is this program's own peak: getrusage's ru_maxrss keeps the peak of the process that forked and
    # exec'ed it (a test runner, a CI step that used a lot before starting us), which is not ours to count
    hwm = _status_kb("VmHWM:")
    if hwm is not None:
        return hwm * 1024
    try:
        import resource
    except ImportError:  # pragma: no cover - not POSIX
        return None
    kb = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss  # KiB on Linux
    return kb * 1024


_current: RunBudget | None = None


def current() -> RunBudget | None:
    return _current


@contextlib.contextmanager
def run_budget(seconds: float | None = None, memory: int | None = None):
    """The budget of one run; nested calls share the outermost."""
    global _current
    if _current is not None:
        yield _current
        return
    _current = RunBudget(seconds, memory)
    restore = _limit_memory(_current.memory)
    try:
        yield _current
    finally:
        _current = None
        restore()


def _limit_memory(memory: int):
    """The memory budget as a limit of this process (RLIMIT_DATA: heap and anonymous mappings), not only a
    check between models: a reader that grows without bound gets a MemoryError (an X017 or a located error)
    instead of taking the machine. Returns what restores the previous limit. Never raises the limit."""
    try:
        import resource
    except ImportError:  # pragma: no cover - not POSIX
        return lambda: None
    try:
        soft, hard = resource.getrlimit(resource.RLIMIT_DATA)
        # what the process uses already, plus the budget: the budget is for the run, not the interpreter
        want = memory + _data_now()
        if hard != resource.RLIM_INFINITY:
            want = min(want, hard)
        if soft != resource.RLIM_INFINITY and soft <= want:
            return lambda: None
        resource.setrlimit(resource.RLIMIT_DATA, (want, hard))
    except (ValueError, OSError):
        return lambda: None

    def restore():
        try:
            resource.setrlimit(resource.RLIMIT_DATA, (soft, hard))
        except (ValueError, OSError):
            pass
    return restore


def _data_now() -> int:
    """This process's data segment size now (VmData), 0 when unknown."""
    kb = _status_kb("VmData:")
    return 0 if kb is None else kb * 1024


def _status_kb(key: str) -> int | None:
    """A `kB` line of /proc/self/status (Linux), None elsewhere."""
    try:
        with open("/proc/self/status", encoding="ascii") as f:
            for line in f:
                if line.startswith(key):
                    return int(line.split()[1])
    except (OSError, ValueError, IndexError):
        pass
    return None
