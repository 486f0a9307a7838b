"""Wall-clock helpers for the benchmarks (bench/bench.py, left to the lead, builds on these).

    best_of(cmd, n=5)                  -> seconds: one warm-up run, then the minimum of n timed runs
    ratio_line(label, ours, peer, goal) prints one line: times, ratio ours/peer, goal, PASS/FAIL

Commands run with stdin closed and stdout/stderr discarded (check_urdf prints the whole tree; writing
it to a terminal would time the terminal). A non-zero exit status is not an error here, because a
linter that reports findings exits 1; pass check=True to insist on exit status 0.
"""
from __future__ import annotations

import subprocess
import time
from collections.abc import Mapping, Sequence


def run_once(cmd: Sequence[str], env: Mapping[str, str] | None = None, check: bool = False,
             timeout: float | None = None) -> float:
    """Wall time of one run of `cmd`, in seconds."""
    t0 = time.perf_counter()
    proc = subprocess.run(list(cmd), stdin=subprocess.DEVNULL, stdout=subprocess.DEVNULL,
                          stderr=subprocess.DEVNULL, env=None if env is None else dict(env),
                          timeout=timeout)
    dt = time.perf_counter() - t0
    if check and proc.returncode != 0:
        raise subprocess.CalledProcessError(proc.returncode, list(cmd))
    return dt


def best_of(cmd: list[str], n: int = 5, *, env: Mapping[str, str] | None = None, check: bool = False,
            timeout: float | None = None) -> float:
    """Minimum wall time (seconds) of `n` runs of `cmd` as a subprocess, after one untimed warm-up."""
    if n < 1:
        raise ValueError("n must be >= 1")
    run_once(cmd, env=env, check=check, timeout=timeout)  # warm-up: page cache, .pyc files
    return min(run_once(cmd, env=env, check=check, timeout=timeout) for _ in range(n))


def ratio_line(label: str, ours: float, peer: float, goal: float) -> str:
    """Print and return one line: `label  ours s vs peer s = ratio x (goal <= goal x) PASS|FAIL`."""
    ratio = ours / peer if peer > 0 else float("inf")
    verdict = "PASS" if ratio <= goal else "FAIL"
    line = (f"{label:<44} {ours * 1000:9.1f} ms vs {peer * 1000:9.1f} ms = {ratio:6.2f}x "
            f"(goal <= {goal:g}x) {verdict}")
    print(line, flush=True)
    return line


if __name__ == "__main__":  # tiny self-check: python bench/timing.py
    import sys
    py = sys.executable
    t_pass = best_of([py, "-c", "pass"], n=3)
    t_same = best_of([py, "-c", "pass"], n=3)
    ratio_line("python -c pass vs itself", t_same, t_pass, 1.5)
