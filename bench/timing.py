"""Wall-clock helpers for the benchmarks (bench/bench.py, left to the lead, builds on these).

    best_of(cmd, n=5)                  -> seconds: one warm-up run, then the minimum of n timed runs
    paired(a, b, n=11)                 -> (median a, median b, median of the pair ratios): A B A B ... on a shared
                                          machine, after one warm-up of each; each run's wall and CPU seconds
    peak_kib(cmd)                      -> the child's peak resident memory (KiB, ru_maxrss of that one process)
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


def run_measured(cmd: Sequence[str], env: Mapping[str, str] | None = None, before=None) -> tuple[float, float, int]:
    """(wall s, CPU s of the child and what it waited for, peak KiB) of one run. `before()` runs first, untimed."""
    import os

    if before is not None:
        before()
    t0 = time.perf_counter()
    proc = subprocess.Popen(list(cmd), stdin=subprocess.DEVNULL, stdout=subprocess.DEVNULL,
                            stderr=subprocess.DEVNULL, env=None if env is None else dict(env))
    _, _, usage = os.wait4(proc.pid, 0)
    dt = time.perf_counter() - t0
    proc.returncode = 0  # reaped above
    return dt, usage.ru_utime + usage.ru_stime, usage.ru_maxrss


def _median(xs):
    xs = sorted(xs)
    n = len(xs)
    return xs[n // 2] if n % 2 else (xs[n // 2 - 1] + xs[n // 2]) / 2


def _quartiles(xs) -> tuple[float, float]:
    """The 25th and 75th percentiles (nearest rank): the spread a median comes from."""
    xs = sorted(xs)
    if not xs:
        return float("inf"), float("inf")
    return xs[round(0.25 * (len(xs) - 1))], xs[round(0.75 * (len(xs) - 1))]


def paired(a: list[str], b: list[str], n: int = 11, *, env=None, env_b=None, before_a=None, before_b=None,
           warm: bool = True) -> dict:
    """A and B in turn, n pairs after one warm-up each (`warm`): medians of wall and CPU, and the medians of the
    pair ratios (pairing keeps a ratio meaningful while a shared machine's speed drifts), with their quartiles
    (`wall_q`, `cpu_q`), and the largest peak resident size (KiB) of each side (`rss_a`, `rss_b`)."""
    if warm:
        run_measured(a, env, before_a)
        run_measured(b, env_b if env_b is not None else env, before_b)
    ra, rb = [], []
    for _ in range(n):
        ra.append(run_measured(a, env, before_a))
        rb.append(run_measured(b, env_b if env_b is not None else env, before_b))
    walls = [x[0] / y[0] for x, y in zip(ra, rb)]
    cpus = [x[1] / y[1] for x, y in zip(ra, rb) if y[1] > 0] or [float("inf")]
    return {"wall_a": _median([x[0] for x in ra]), "wall_b": _median([x[0] for x in rb]),
            "cpu_a": _median([x[1] for x in ra]), "cpu_b": _median([x[1] for x in rb]),
            "wall": _median(walls), "cpu": _median(cpus), "wall_q": _quartiles(walls), "cpu_q": _quartiles(cpus),
            "rss_a": max(x[2] for x in ra), "rss_b": max(x[2] for x in rb)}


def peak_kib(cmd: list[str], env: Mapping[str, str] | None = None) -> int:
    return run_measured(cmd, env)[2]


def paired_line(label: str, r: dict, goal_wall: float | None, goal_cpu: float | None = None) -> str:
    """One line for a `paired` result: medians, the median pair ratios [their quartiles], the goals."""
    def spread(key):
        q = r.get(f"{key}_q")
        return f" [{q[0]:.2f}-{q[1]:.2f}]" if q else ""

    verdict = []
    if goal_wall is not None:
        verdict.append(f"wall {r['wall']:.2f}x{spread('wall')} (goal <= {goal_wall:g}x) "
                       f"{'PASS' if r['wall'] <= goal_wall else 'FAIL'}")
    else:
        verdict.append(f"wall {r['wall']:.2f}x{spread('wall')}")
    if goal_cpu is not None:
        verdict.append(f"CPU {r['cpu']:.2f}x{spread('cpu')} (goal <= {goal_cpu:g}x) "
                       f"{'PASS' if r['cpu'] <= goal_cpu else 'FAIL'}")
    else:
        verdict.append(f"CPU {r['cpu']:.2f}x{spread('cpu')}")
    line = (f"{label:<44} {r['wall_a'] * 1000:7.1f} ms vs {r['wall_b'] * 1000:7.1f} ms (CPU {r['cpu_a'] * 1000:.0f} "
            f"vs {r['cpu_b'] * 1000:.0f} ms) medians: " + "; ".join(verdict))
    print(line, flush=True)
    return line


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
