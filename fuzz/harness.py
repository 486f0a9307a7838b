"""What the wave-4 fuzzers (recordings.py, gitrev.py, configs.py) share: batches of inputs run in a forked child
that holds the canaries, a per-input wall limit enforced from the parent, and the properties counted per input.

A child runs the real CLI in-process (`urdfcheck.cli.main.main`, with URDFCHECK_DEBUG=1 so an internal error is
raised, not hidden behind exit 2) in a throw-away checkout it `chdir`s into, and reports one JSON line per input.
The parent kills a child that says nothing for `hang` seconds, counts a hang for the input it was on, and goes on
with the next one in a fresh child.

Counted per input:
  leaks       the canary secret of the environment, the canary file's text (outside the checkout), or an absolute
              temp/runner path (the checkout's, the outside folder's, the temp base's) in any output;
  tracebacks  an exception out of main(), "Traceback" or "internal error" in any output, an exit code other than
              0/1/2, or exit 2 without a one-line "urdfcheck: ..." reason;
  hangs       an input slower than `hang` seconds;
  silent      exit 0 or "All checks passed" where the case says something broken is present (`must_fail`), or
              exit 0 where nothing was checked;
  writes      a file created, changed or removed in the checkout by the run.
"""
from __future__ import annotations

import contextlib
import io
import json
import os
import select
import signal
import sys
import tempfile
import time
from pathlib import Path

HERE = Path(__file__).resolve().parent
sys.path.insert(0, str(HERE.parent / "src"))

SECRET_VAR = "URDFCHECK_FUZZ_SECRET"
SECRET = "fuzz-w4-s3cr3t-9b2d"
FILE_SECRET = "fuzz-w4-file-s3cr3t-c41e"
SECRET_VARS = (SECRET_VAR, "GITHUB_TOKEN", "AWS_SECRET_ACCESS_KEY")
INTERNAL = ("Traceback (most recent call last)", "internal error")
KINDS = ("leaks", "tracebacks", "hangs", "silent", "writes")
# the seeded broken robot: a joint whose lower limit lies above its upper one (J003), a joint naming a missing link
# (S003); no config the pull request writes may make it pass
BROKEN = """<?xml version="1.0"?>
<robot name="r"><link name="base_link"/><link name="tool"/>
<joint name="j" type="revolute"><parent link="base_link"/><child link="tool"/>
<limit lower="1" upper="-1" effort="1" velocity="1"/></joint>
<joint name="k" type="fixed"><parent link="base_link"/><child link="ghost"/></joint>
</robot>
"""


def base_dir(prefix: str) -> Path:
    shm = "/dev/shm" if os.path.isdir("/dev/shm") and os.access("/dev/shm", os.W_OK) else None
    return Path(tempfile.mkdtemp(prefix=prefix, dir=shm))


def outside(base: Path) -> Path:
    """A folder outside every checkout holding the canary file."""
    out = base / "outside"
    out.mkdir(exist_ok=True)
    (out / "secret.yaml").write_text(f"token: {FILE_SECRET}\nname: [{FILE_SECRET}]\n")
    (out / "secret.txt").write_text(FILE_SECRET + "\n")
    return out


def markers(base: Path) -> tuple[str, ...]:
    """What no output may hold: the canaries and the absolute temp paths (as given and resolved)."""
    paths = {str(base), os.path.realpath(base)}
    return (SECRET, FILE_SECRET, *sorted(paths, key=len, reverse=True))


def snapshot(root: Path) -> dict:
    """name -> (kind, size, mtime) of every entry under root (symlinks not followed)."""
    out = {}
    for dirpath, dirnames, filenames in os.walk(root):
        for n in dirnames + filenames:
            p = os.path.join(dirpath, n)
            try:
                st = os.lstat(p)
            except OSError:
                continue
            out[os.path.relpath(p, root)] = (st.st_mode >> 12, st.st_size if n not in dirnames else 0, st.st_mtime_ns
                                             if n not in dirnames else 0)
    return out


def cli(argv: list[str]) -> tuple[int | str, str]:
    """The real CLI in-process: (exit code or 'EXC', everything it printed)."""
    import gc

    from urdfcheck.cli.main import main

    out, err = io.StringIO(), io.StringIO()
    try:
        with contextlib.redirect_stdout(out), contextlib.redirect_stderr(err):
            code = main(argv)
    except SystemExit as e:
        code = e.code if isinstance(e.code, int) else 2
        if not isinstance(e.code, int) and e.code:
            err.write(str(e.code))
    except BaseException as e:  # noqa: BLE001 - what is counted
        if isinstance(e, KeyboardInterrupt):
            raise
        import traceback

        tb = "".join(traceback.format_exception(type(e), e, e.__traceback__))
        tb = tb if len(tb) < 6000 else tb[:3000] + "\n...\n" + tb[-3000:]  # where it started and where it broke
        return "EXC", (out.getvalue() + err.getvalue())[-2000:] + "\n" + tb
    finally:
        gc.enable()  # a console run pauses the collector for the rest of its process
    return code, out.getvalue() + err.getvalue()


def in_checkout(ws: Path, back: Path, argv: list[str], marks, must_fail: bool) -> tuple:
    """The CLI run from inside the checkout `ws` (then back to `back`): (code, text, problem kinds), writes into
    the checkout counted."""
    os.chdir(ws)
    before = snapshot(ws)
    code, text = cli(argv)
    os.chdir(back)
    bad = judge(code, text, marks, must_fail=must_fail)
    if snapshot(ws) != before:
        bad.append("writes")
    return code, text, bad


def detail(code, text: str) -> str:
    """What an example keeps of the output: where a traceback started, else the end."""
    return text[:4000] if code == "EXC" else text[-1500:]


def judge(code, text: str, marks, must_fail: bool, checked: bool = True) -> list[str]:
    """The problem kinds of one run."""
    bad = []
    if any(m and m in text for m in marks):
        bad.append("leaks")
    if code == "EXC" or code not in (0, 1, 2) or any(m in text for m in INTERNAL):
        bad.append("tracebacks")
    elif code == 2 and "urdfcheck" not in text:
        bad.append("tracebacks")  # exit 2 with no reason given
    if code == 0 and (must_fail or not checked):
        bad.append("silent")
    elif must_fail and "All checks passed" in text:
        bad.append("silent")
    return bad


def run_batches(cases, do_one, hang: float, batch: int, stats: dict, examples: list, env: dict | None = None,
                show=lambda case: case, progress=None) -> None:
    """Run `do_one(case) -> {"bad": [...], "outcome": str, "detail": str}` for every case in forked children."""
    cases = list(cases)
    i = 0
    while i < len(cases):
        chunk = cases[i:i + batch]
        r, w = os.pipe()
        pid = os.fork()
        if pid == 0:  # the child: canaries in its environment, one JSON line per input
            os.close(r)
            signal.signal(signal.SIGTERM, signal.SIG_DFL)
            try:
                import resource

                resource.setrlimit(resource.RLIMIT_AS, (4 * 1024**3, 4 * 1024**3))
                os.environ.update(env or {})
                for v in SECRET_VARS:
                    os.environ[v] = SECRET
                os.environ["URDFCHECK_DEBUG"] = "1"
                for case in chunk:
                    try:
                        out = do_one(case)
                    except BaseException as e:  # noqa: BLE001 - a fault of the harness is a finding too
                        import traceback

                        out = {"bad": ["tracebacks"], "outcome": "harness",
                               "detail": "".join(traceback.format_exception(type(e), e, e.__traceback__))[-1500:]}
                    os.write(w, (json.dumps(out) + "\n").encode())
            finally:
                os._exit(0)
        os.close(w)
        try:
            buf, done, last = b"", 0, time.monotonic()
            while done < len(chunk):
                ready, _, _ = select.select([r], [], [], 0.2)
                if ready:
                    block = os.read(r, 1 << 16)
                    if not block:
                        break
                    buf += block
                    while b"\n" in buf:
                        line, buf = buf.split(b"\n", 1)
                        _account(stats, examples, chunk[done], json.loads(line), show)
                        done += 1
                        last = time.monotonic()
                elif time.monotonic() - last > hang:
                    break
        except BaseException:  # stopped (SIGTERM, ^C): the child goes too, before the temp folder is removed
            with contextlib.suppress(ProcessLookupError):
                os.kill(pid, signal.SIGKILL)
            os.waitpid(pid, 0)
            raise
        if done < len(chunk):  # the child hung (or died) on chunk[done]
            with contextlib.suppress(ProcessLookupError):
                os.kill(pid, signal.SIGKILL)
            _account(stats, examples, chunk[done], {"bad": ["hangs"], "outcome": "hang",
                                                    "detail": f"no answer within {hang:g} s"}, show)
            done += 1
        os.waitpid(pid, 0)
        os.close(r)
        i += done
        if progress is not None:
            progress(i)


def _account(stats: dict, examples: list, case, out: dict, show) -> None:
    stats["inputs"] += 1
    o = out.get("outcome", "?")
    stats["outcomes"][o] = stats["outcomes"].get(o, 0) + 1
    for kind in dict.fromkeys(out.get("bad", [])):
        stats[kind] += 1
        if len(examples) < 40:
            examples.append({"kind": kind, "outcome": o, "detail": str(out.get("detail", ""))[:8000],
                             "case": show(case)})


def steps(count: int, step: int, seconds: float | None, t0: float, make, run_cases, stats: dict, examples: list,
          report: str | None) -> int:
    """Inputs made and run `step` at a time (`make(done, n)` -> cases, `run_cases(cases)`), the figures written to
    `report` after each step, no new step begun after `seconds`; returns how many inputs were made."""
    done = 0
    while done < count and (seconds is None or time.monotonic() - t0 < seconds):
        n = min(step, count - done)
        run_cases(make(done, n))
        done += n
        if report:
            Path(report).write_text(json.dumps({**stats, "examples": examples[:20],
                                                "seconds": round(time.monotonic() - t0, 1)}, indent=1))
    return done


class Session:
    """One fuzzing run: its temp folder (removed at the end, SIGTERM included), the canary folder outside every
    checkout, the markers no output may hold, the figures and failing examples, the start time."""

    def __init__(self, prefix: str, *kinds: str):
        self.base = base_dir(prefix)
        self.out = outside(self.base)
        self.marks = markers(self.base)
        self.stats, self.examples = new_stats(), []
        self.stats.update({k: 0 for k in kinds})
        self.t0 = time.monotonic()

    def __enter__(self) -> Session:
        return self

    def __exit__(self, *exc) -> None:
        import shutil

        shutil.rmtree(self.base, ignore_errors=True)

    def steps(self, count: int, step: int, seconds: float | None, report: str | None, make, do_one, hang: float,
              batch: int, **kw) -> int:
        """`steps` of `make(done, n)` inputs, each run by `do_one` in forked children (run_batches)."""
        return steps(count, step, seconds, self.t0, make,
                     lambda cases: run_batches(cases, do_one, hang, batch, self.stats, self.examples, **kw),
                     self.stats, self.examples, report)

    def result(self) -> tuple[dict, list, float]:
        return self.stats, self.examples, self.t0


def new_stats() -> dict:
    return {"inputs": 0, **{k: 0 for k in KINDS}, "outcomes": {}}


def parser(doc: str, *, count: int, seed: int, hang: float, batch: int):
    """The options every fuzzer takes (--count --seed --hang --batch --seconds --report); its own go on top.
    Called from a fuzzer's `main`, so the SIGTERM handler is installed there only."""
    import argparse

    stop_on_sigterm()
    ap = argparse.ArgumentParser(description=doc.splitlines()[0])
    ap.add_argument("--count", type=int, default=count)
    ap.add_argument("--seed", type=int, default=seed)
    ap.add_argument("--hang", type=float, default=hang)
    ap.add_argument("--batch", type=int, default=batch)
    ap.add_argument("--seconds", type=float, help="start no new step of inputs after this many seconds")
    ap.add_argument("--report")
    return ap


def stop_on_sigterm() -> None:
    """A fuzzing run stopped with SIGTERM still removes its temp folder (the callers' `finally`). Only for a
    fuzzer's own process (`main`): in the test suite a handler would outlive the test and change how every later
    forked child dies."""
    signal.signal(signal.SIGTERM, lambda *_: sys.exit(143))


def finish(stats: dict, examples: list, t0: float, report: str | None, show: int = 5) -> int:
    stats["seconds"] = round(time.monotonic() - t0, 1)
    print(json.dumps(stats, indent=1))
    for ex in examples[:show]:
        print("---", json.dumps(ex)[:2000])
    if report:
        Path(report).write_text(json.dumps({**stats, "examples": examples}, indent=1))
    return 1 if any(stats[k] for k in KINDS) else 0
