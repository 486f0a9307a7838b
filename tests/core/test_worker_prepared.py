"""Issue 12: one sandboxed worker. The verify peers' needs (import before the job arrives, progress, captured
C-level output) are options of core.worker, and those children get the same limits as the xacro worker."""
import os
import resource
import sys
import time

import pytest

from urdfcheck.core import worker

pytestmark = pytest.mark.skipif(not hasattr(os, "fork"), reason="the worker forks")


def _limits_seen(*_):
    return {"core": resource.getrlimit(resource.RLIMIT_CORE), "as": resource.getrlimit(resource.RLIMIT_AS),
            "cpu": resource.getrlimit(resource.RLIMIT_CPU), "env": dict(os.environ), "argv": list(sys.argv)}


def test_a_prepared_child_gets_the_same_limits_as_a_started_one(monkeypatch):
    monkeypatch.setenv("URDFCHECK_TEST_SECRET", "s3cr3t-peer-77")
    monkeypatch.setattr(sys, "argv", sys.argv + ["ARGV_MARK_peer"])
    started = worker.run(_limits_seen)
    job = worker.prepare(_limits_seen)
    job.send()
    prepared = job.result()
    for seen in (started, prepared):
        assert seen["core"] == (0, 0)
        assert seen["as"][0] != resource.RLIM_INFINITY and seen["cpu"][0] != resource.RLIM_INFINITY
        assert "URDFCHECK_TEST_SECRET" not in seen["env"] and set(seen["env"]) <= set(worker.ENV_ALLOW)
        assert seen["argv"] == worker.WORKER_ARGV
    assert os.environ["URDFCHECK_TEST_SECRET"] == "s3cr3t-peer-77"  # the parent keeps its own


def test_the_memory_allowance_is_on_top_of_what_the_child_inherits():
    # as an absolute limit, half of what this interpreter already maps would leave the child unable to run
    allowance = worker._vm_size() // 2
    assert allowance > 0
    assert worker.run(sum, [1, 2], memory=allowance) == 3
    hog = worker.run(bytearray, 4 * allowance, memory=allowance)
    assert isinstance(hog, worker.Failure) and hog.kind == "memory"


def _loaded(name):
    return name in sys.modules


def test_preload_imports_before_the_job_and_the_clock_starts_at_send():
    name = next((m for m in ("colorsys", "wave", "mailbox", "netrc") if m not in sys.modules), None)
    if name is None:
        pytest.skip("every candidate module is imported already")
    job = worker.prepare(_loaded, preload=(name,), limits=worker.Limits(timeout=0.5))
    time.sleep(1.0)  # longer than the timeout: waiting for the job does not count
    job.send(name)
    assert job.result() is True
    assert name not in sys.modules  # imported in the child only


def _count(progress, n):
    for i in range(n):
        progress(i, n)
        time.sleep(0.03)
    progress(n, n)
    os.write(1, b"said on stdout\n")
    os.write(2, b"said on stderr\n")
    return n


def test_progress_and_output_come_back():
    seen, done = [], []
    job = worker.prepare(_count, progress=True, name="counter")
    job.send(20)
    worker.wait([job], on_progress=lambda j: seen.append(j.progress), on_done=lambda j: done.append(j.name))
    assert job.result() == 20 and done == ["counter"]
    assert seen and seen[-1] == (20, 20) and seen == sorted(seen)
    assert "said on stdout" in job.stderr and "said on stderr" in job.stderr
    assert 0 < job.seconds < 30


def test_cancel_before_send_reaps_the_waiting_child():
    job = worker.prepare(_loaded, preload=("json",))
    pid = job.pid
    job.cancel()
    with pytest.raises(ChildProcessError):
        os.waitpid(pid, os.WNOHANG)


def _spin(_progress=None):
    while True:
        pass


def test_a_prepared_job_that_hangs_times_out_and_is_reaped():
    job = worker.prepare(_spin, limits=worker.Limits(timeout=0.5))
    job.send()
    pid = job.pid
    res = job.result()
    assert isinstance(res, worker.Failure) and res.kind == "timeout"
    with pytest.raises(ChildProcessError):
        os.waitpid(pid, os.WNOHANG)


def test_a_parent_under_ulimit_still_gets_working_children():
    # the allowance on top of the inherited address space, or the CPU limit, may exceed the user's own hard
    # limits (ulimit -v / -t): the child is held to the lower one instead of failing to start
    import subprocess

    code = ("import resource\n"
            "resource.setrlimit(resource.RLIMIT_AS, (3 * 1024**3, 3 * 1024**3))\n"
            "resource.setrlimit(resource.RLIMIT_CPU, (500, 500))\n"
            "from urdfcheck.core import worker\n"
            "print(worker.run(sum, [1, 2], memory=4 * 1024**3, timeout=1000))\n")
    src = os.path.join(os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__)))), "src")
    env = dict(os.environ, PYTHONPATH=src + os.pathsep + os.environ.get("PYTHONPATH", ""))
    proc = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, env=env, timeout=60)
    assert proc.returncode == 0 and proc.stdout.strip() == "3", proc.stdout + proc.stderr
