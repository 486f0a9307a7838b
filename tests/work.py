"""Work counted, not timed: how many Python and C calls a piece of code makes, and the memory it holds at its
peak. Unlike wall-clock time, these do not change on a loaded machine (wall-clock belongs to bench/)."""
from __future__ import annotations

import sys
import tracemalloc


class Work:
    calls = 0
    peak_bytes = 0


def counted(fn, *args, **kwargs) -> tuple[Work, BaseException | None]:
    """Run fn; (the work it did, the exception it raised or None)."""
    work = Work()

    def count(frame, event, arg):
        if event in ("call", "c_call"):
            work.calls += 1

    error = None
    tracing = tracemalloc.is_tracing()
    if not tracing:
        tracemalloc.start()
    tracemalloc.reset_peak()
    before = tracemalloc.get_traced_memory()[0]
    old = sys.getprofile()
    sys.setprofile(count)
    try:
        fn(*args, **kwargs)
    except BaseException as e:  # noqa: BLE001 - handed to the caller, which expects it
        error = e
    finally:
        sys.setprofile(old)
        work.peak_bytes = tracemalloc.get_traced_memory()[1] - before
        if not tracing:
            tracemalloc.stop()
    return work, error
