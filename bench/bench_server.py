"""The language server's answers against a cold `urdfcheck lint` of the same package from the shell (issue 43).

    python bench/bench_server.py [-n RUNS]

On a copy of examples/agv: (1) the wall time of a cold `urdfcheck lint --no-cache PKG` process; (2) in one warm
server session (`server.session.Session`, what `urdfcheck server` runs), the wall time from an edit of the AGV's
macro file to its diagnostics; (3) the same document asked again unchanged. Medians of RUNS, ratios against (1)
measured in the same run; the goals are (2) <= 0.5x and (3) <= 0.1x. Nothing is asserted: this prints.
"""
from __future__ import annotations

import argparse
import os
import shutil
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

REPO = Path(__file__).resolve().parent.parent


def main() -> int:
    ap = argparse.ArgumentParser()
    ap.add_argument("-n", type=int, default=7)
    ns = ap.parse_args()
    sys.path.insert(0, str(REPO / "src"))
    from urdfcheck.server.session import Session

    base = Path(tempfile.mkdtemp(prefix="urdfcheck-bench-server-"))
    pkg = base / "agv"
    shutil.copytree(REPO / "examples" / "agv", pkg)
    macros = sorted((pkg / "urdf" / "macros").glob("*.xacro"))
    target = macros[0]
    text = target.read_text(encoding="utf-8")
    env = dict(os.environ, PYTHONPATH=str(REPO / "src"))
    cold, edit, again = [], [], []
    session = Session(str(base))
    session.open(str(target), text)
    session.lint(str(target))  # warm: the server has linted the package once when the file was opened
    for i in range(ns.n):
        t = time.perf_counter()
        subprocess.run([sys.executable, "-m", "urdfcheck", "lint", "--no-cache", "--quiet", str(pkg)], cwd=base,
                       env=env, capture_output=True, check=False)
        cold.append(time.perf_counter() - t)
        session.open(str(target), text + f"\n<!-- edit {i} -->\n")
        t = time.perf_counter()
        session.lint(str(target))
        edit.append(time.perf_counter() - t)
        t = time.perf_counter()
        session.lint(str(target))
        again.append(time.perf_counter() - t)
    c, e, a = (statistics.median(x) for x in (cold, edit, again))
    print(f"cold lint (process)        median {c * 1000:8.1f} ms")
    print(f"server, after an edit      median {e * 1000:8.1f} ms   ratio {e / c:5.2f}x  (goal <= 0.5x)")
    print(f"server, unchanged document median {a * 1000:8.1f} ms   ratio {a / c:5.3f}x  (goal <= 0.1x)")
    shutil.rmtree(base, ignore_errors=True)
    return 0


if __name__ == "__main__":
    sys.exit(main())
