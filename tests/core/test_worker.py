"""worker.start/Job: the child runs while the parent works on; every outcome comes back as a value, and
every child is reaped (also when lint stops half-way)."""
import os
import signal
import sys
import time
from pathlib import Path

SRC = Path(__file__).resolve().parents[2] / "src"
if str(SRC) not in sys.path:  # runnable without an editable install
    sys.path.insert(0, str(SRC))

import importlib  # noqa: E402

import pytest  # noqa: E402

from urdfcheck.core import worker  # noqa: E402
from urdfcheck.core.paths import shown  # noqa: E402
from urdfcheck.load import loader  # noqa: E402

lint = importlib.import_module("urdfcheck.run")  # the package's `lint` attribute is the API function

pytestmark = pytest.mark.skipif(not hasattr(os, "fork"), reason="the worker forks")


def _wait_for(path: str, limit: float = 10.0) -> str:
    end = time.monotonic() + limit
    while not os.path.exists(path):
        if time.monotonic() > end:
            return "never saw it"
        time.sleep(0.01)
    return "saw it"


def _gone(pid: int) -> bool:
    try:
        os.waitpid(pid, os.WNOHANG)
    except ChildProcessError:
        return True  # already reaped: no zombie left behind
    return False


def test_start_returns_while_the_child_still_runs(tmp_path):
    flag = str(tmp_path / "go")
    job = worker.start(_wait_for, flag, timeout=30)
    # the child waits for a file only this process writes after start() returned: a blocking start
    # would make the child give up first
    Path(flag).write_text("")
    assert job.result() == "saw it"
    assert job.result() == "saw it"  # a second call gives the same value, it does not wait again


def test_outcomes_are_values():
    assert worker.run(sum, [1, 2, 3]) == 6
    failed = worker.run(int, "x")
    assert isinstance(failed, worker.Failure) and failed.kind == "error" and "ValueError" in failed.message
    timed_out = worker.run(time.sleep, 30, timeout=0.5)
    assert isinstance(timed_out, worker.Failure) and timed_out.kind == "timeout"
    crashed = worker.run(lambda: os.kill(os.getpid(), signal.SIGTERM))
    assert isinstance(crashed, worker.Failure) and crashed.kind == "crashed" and "SIGTERM" in crashed.message


def test_cancel_kills_and_reaps():
    job = worker.start(time.sleep, 60, timeout=120)
    pid = job.pid
    job.cancel()
    assert _gone(pid)
    job.cancel()  # twice is harmless


XACRO = """<robot name="r" xmlns:xacro="http://www.ros.org/wiki/xacro">
  <xacro:arg name="n" default="a"/>
  <link name="base_link"/>
  <link name="$(arg n)_link"/>
  <joint name="j" type="{jtype}"><parent link="base_link"/><child link="$(arg n)_link"/></joint>
</robot>
"""


def _targets(tmp_path, n=5):
    out = []
    for i in range(n):
        p = tmp_path / f"r{i}.urdf.xacro"
        p.write_text(XACRO.format(jtype="revolute" if i % 2 else "fixed"))  # revolute without <limit>
        out.append(lint.Target(p, {"n": f"m{i}"}))
    return out


def test_running_ahead_changes_no_finding(tmp_path):
    targets = _targets(tmp_path)
    together = lint.lint_targets(targets).findings
    from urdfcheck.finish.result import dedupe
    from urdfcheck.rules.engine import Selection

    one_by_one = dedupe([f for t in targets for f in lint.lint_target(t, Selection())[0]])
    assert together == one_by_one
    assert {f.code for f in together} == {"J002"}  # the revolute ones, in target order
    assert [f.location.file for f in together] == sorted(f.location.file for f in together)


def test_a_failure_half_way_leaves_no_child_behind(tmp_path, monkeypatch):
    jobs = []
    real_start = worker.start

    def recording_start(*a, **kw):
        job = real_start(*a, **kw)
        jobs.append((job, job.pid))
        return job

    def broken_check(*a, **kw):
        raise RuntimeError("stop here")

    monkeypatch.setattr(worker, "start", recording_start)
    monkeypatch.setattr(lint, "_check", broken_check)
    with pytest.raises(RuntimeError):
        lint.lint_targets(_targets(tmp_path))
    assert len(jobs) >= 2  # more than one expansion was under way when the first target failed
    assert all(job.pid is None and _gone(pid) for job, pid in jobs)


def test_expand_is_begin_then_result(tmp_path):
    p = _targets(tmp_path, 1)[0].path
    pending = loader.begin(p, {"n": "x"})
    exp = pending.result()
    assert exp.root is not None and exp.root.find("link[@name='x_link']") is not None
    assert loader.expand(p, {"n": "x"}).clean_text() == exp.clean_text()


def test_retain_keeps_each_parsed_document_and_changes_no_finding(tmp_path):
    targets = _targets(tmp_path, 3)
    kept = []
    with_retain = lint.lint_targets(targets, retain=kept).findings
    assert with_retain == lint.lint_targets(targets).findings
    assert [e.entry for e in kept] == [shown(t.path) for t in targets]
    assert all(e.root is not None for e in kept)


def test_only_the_console_entry_pauses_the_collector_and_keeps_documents(tmp_path):
    import gc

    from urdfcheck.cli import lint as runlint
    from urdfcheck.cli import main as cli

    p = _targets(tmp_path, 1)[0].path
    before = len(runlint._UNTIL_EXIT)
    assert gc.isenabled()
    assert cli.main(["lint", "--no-config", "--format", "json", str(p)]) == 0
    # in-process callers (tests, the pytest plugin, scripts) keep a working collector and free everything
    assert gc.isenabled() and len(runlint._UNTIL_EXIT) == before
    try:
        assert cli.main(["lint", "--no-config", "--format", "json", str(p)], one_shot=True) == 0
        kept = [type(x).__name__ for x in runlint._UNTIL_EXIT[before:]]
        assert not gc.isenabled() and kept == ["Expanded", "Result"]  # the document, then the result (its models)
    finally:
        gc.enable()
        del runlint._UNTIL_EXIT[before:]


def test_a_child_collects_garbage_even_when_the_parent_paused_the_collector():
    import gc

    gc.disable()
    try:
        assert worker.run(gc.isenabled) is True
    finally:
        gc.enable()


def test_a_result_collected_after_the_time_limit_is_still_delivered():
    # lint collects a worker only when it reaches that target; a finished child must not count as timed out
    # while its result (larger than a pipe buffer) waits to be read
    job = worker.start(lambda: "x" * 1_000_000, timeout=0.3)
    time.sleep(0.6)
    assert job.result() == "x" * 1_000_000


def test_a_hung_child_collected_late_still_times_out():
    job = worker.start(time.sleep, 60, timeout=0.2)
    time.sleep(0.3)
    t0 = time.monotonic()
    res = job.result()
    assert isinstance(res, worker.Failure) and res.kind == "timeout"
    assert time.monotonic() - t0 < 30  # a bounded grace, not the child's whole sleep


def test_the_console_entry_runs_atexit_handlers_and_keeps_the_exit_code(tmp_path):
    import subprocess

    flag = tmp_path / "atexit-ran"
    bad = tmp_path / "bad.urdf"
    bad.write_text('<robot name="r"><link name="a"/><joint name="j" type="revolute"/></robot>')
    code = ("import atexit, sys; "
            f"atexit.register(lambda: open({str(flag)!r}, 'w').write('ran')); "
            f"sys.argv = ['urdfcheck', 'lint', '--no-config', {str(bad)!r}]; "
            "from urdfcheck.cli.main import run; run()")
    env = dict(os.environ, PYTHONPATH=str(SRC) + os.pathsep + os.environ.get("PYTHONPATH", ""))
    proc = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, env=env, timeout=120)
    assert proc.returncode == 1, proc.stderr  # findings
    assert "J" in proc.stdout and flag.read_text() == "ran"


def test_no_targets_is_an_empty_result():
    result = lint.lint_targets([])
    assert result.findings == [] and result.models == {}


def _environment_seen():
    import posix

    return (dict(os.environ), {os.fsdecode(k) for k in os.environb}, {os.fsdecode(k) for k in posix.environ},
            list(sys.argv), list(getattr(sys, "orig_argv", [])), os.getenv("URDFCHECK_TEST_SECRET"))


def test_a_worker_starts_with_a_scrubbed_environment_and_argv(monkeypatch):
    # issue 11: a format-string walk (or anything else) in a worker found the CI job's secrets and command line
    monkeypatch.setenv("URDFCHECK_TEST_SECRET", "s3cr3t-worker-9f2")
    monkeypatch.setenv("KEPT_BY_ALLOW_ENV", "yes")
    monkeypatch.setattr(sys, "argv", sys.argv + ["ARGV_MARK_0c4e"])
    env, envb, raw, argv, orig, getenv = worker.run(_environment_seen, env_keep=("KEPT_BY_ALLOW_ENV",))
    for names in (set(env), envb, raw):
        assert "URDFCHECK_TEST_SECRET" not in names and "KEPT_BY_ALLOW_ENV" in names
        assert names <= set(worker.ENV_ALLOW) | {"KEPT_BY_ALLOW_ENV"}
    assert getenv is None  # the C environment too
    assert "ARGV_MARK_0c4e" not in " ".join(argv + orig)
    # the parent is untouched
    assert os.environ["URDFCHECK_TEST_SECRET"] == "s3cr3t-worker-9f2" and "ARGV_MARK_0c4e" in sys.argv


def test_a_trusted_worker_keeps_the_environment_but_not_argv(monkeypatch):
    monkeypatch.setenv("URDFCHECK_TEST_SECRET", "s3cr3t-worker-9f2")
    monkeypatch.setattr(sys, "argv", sys.argv + ["ARGV_MARK_0c4e"])
    env, _, _, argv, _, _ = worker.run(_environment_seen, scrub_env=False)
    assert env["URDFCHECK_TEST_SECRET"] == "s3cr3t-worker-9f2" and "ARGV_MARK_0c4e" not in argv


def test_a_job_cut_by_the_run_budget_gets_no_delivery_grace():
    """Against a twin with the usual grace (min(timeout, DELIVERY_GRACE) = 1 s here), collected in the same run:
    a ratio, not a wall-clock bound (the machine may be loaded)."""
    cut = worker.start(time.sleep, 60, timeout=1.0, grace=0.0)
    usual = worker.start(time.sleep, 60, timeout=1.0)
    time.sleep(1.5)
    t0 = time.monotonic()
    assert isinstance(cut.result(), worker.Failure)
    t1 = time.monotonic()
    assert isinstance(usual.result(), worker.Failure)
    t2 = time.monotonic()
    assert t1 - t0 < (t2 - t1) / 2, (t1 - t0, t2 - t1)


# ---- the spare xacro worker the console forks before it imports the planner -----------------------------------
def test_a_spare_runs_the_job_it_is_sent_by_name():
    lim = worker.Limits(timeout=10)
    worker.keep_spare("t", lim, preload=("json",))
    job = worker.take_spare("t", lim)
    assert job is not None and worker.take_spare("t", lim) is None  # handed out once
    job.send("os.path:join", "a", "b")
    assert job.result() == os.path.join("a", "b")


def test_a_spare_with_other_limits_is_not_used_and_leaves_no_child():
    worker.keep_spare("t", worker.Limits(timeout=10, scrub_env=True), preload=())
    pid = worker._SPARES["t"].pid
    # e.g. a config file that allows an environment variable: the spare's environment is already scrubbed
    assert worker.take_spare("t", worker.Limits(timeout=10, scrub_env=True, env_keep=("HOME",))) is None
    assert _gone(pid) and "t" not in worker._SPARES
    worker.keep_spare("u", worker.Limits(), preload=())
    pid = worker._SPARES["u"].pid
    worker.drop_spares()
    assert _gone(pid) and not worker._SPARES


def test_the_console_sends_the_first_expansion_to_its_spare_and_finds_the_same(tmp_path, monkeypatch):
    from urdfcheck.cli import lint as runlint
    from urdfcheck.cli import main as cli

    p = str(_targets(tmp_path, 1)[0].path)
    taken = []
    take = worker.take_spare
    monkeypatch.setattr(worker, "take_spare", lambda key, lim: taken.append(r := take(key, lim)) or r)
    before = len(runlint._UNTIL_EXIT)
    out = []
    import contextlib
    import io

    for one_shot in (False, True):
        buf = io.StringIO()
        try:
            with contextlib.redirect_stdout(buf):
                cli.main(["lint", "--no-config", "--format", "json", p], one_shot=one_shot)
        finally:
            import gc

            gc.enable()
            del runlint._UNTIL_EXIT[before:]
        out.append(buf.getvalue())
    assert [t is not None for t in taken] == [False, True]  # only the console entry forks a spare
    assert out[0] == out[1] and '"findings"' in out[0]
    assert not worker._SPARES


# --- a batch: the run's first xacro models expanded in children of the console's spare -------------------------
def _xacro(tmp_path, name: str, body: str) -> Path:
    p = tmp_path / name
    p.write_text('<?xml version="1.0"?>\n<robot name="r" xmlns:xacro="http://www.ros.org/wiki/xacro">\n'
                 f'{body}\n</robot>\n')
    return p


def _expanded_in_batch(paths, timeout=loader.XACRO_TIMEOUT):
    from urdfcheck.load.xacro import SPARE, SPARE_PRELOAD, worker_limits

    worker.keep_spare(SPARE, worker_limits(False, (), timeout), SPARE_PRELOAD)
    try:
        batch = loader.Batch()
        pending = [loader.begin(p, timeout=timeout, batch=batch) for p in paths]
        assert batch.items and len(batch.items) == len(paths)  # the spare takes them all
        batch.send()
        return [p.result() for p in pending], batch
    finally:
        worker.drop_spares()


def _same(a, b) -> bool:
    return (a.text, a.files, a.findings, a.suppressions, a.declared_args) == \
        (b.text, b.files, b.findings, b.suppressions, b.declared_args)


def test_a_batch_finds_what_lone_expansions_find(tmp_path):
    paths = [_xacro(tmp_path, "a.urdf.xacro", '<xacro:property name="w" value="2"/><link name="${w}"/>'),
             _xacro(tmp_path, "b.urdf.xacro", '<link name="b"/><xacro:bogus/>'),  # an error: located the same
             _xacro(tmp_path, "c.urdf.xacro", '<link name="${undefined_name}"/>')]
    got, _ = _expanded_in_batch(paths)
    for p, exp in zip(paths, got):
        assert _same(exp, loader.expand(p)), p
    assert got[0].root is not None and got[1].findings and got[2].findings


def test_a_hung_expansion_in_a_batch_times_out_alone(tmp_path, monkeypatch):
    from urdfcheck.load.xacro import expand as xexpand

    real = xexpand.expand_with

    def hangs_on_slow(path, options):  # the spare is forked after this patch: its children run it
        if "slow" in path:
            time.sleep(60)
        return real(path, options)

    monkeypatch.setattr(xexpand, "expand_with", hangs_on_slow)
    ok = _xacro(tmp_path, "ok.urdf.xacro", '<link name="fine"/>')
    slow = _xacro(tmp_path, "slow.urdf.xacro", '<link name="never"/>')
    start = time.monotonic()
    (good, bad), _ = _expanded_in_batch([ok, slow], timeout=1.0)
    assert time.monotonic() - start < 8.0
    assert good.root is not None and not good.findings  # its neighbour's time-out is not its own
    assert [f.code for f in bad.findings] == ["X012"] and "timed out" in bad.findings[0].message


def test_cancelling_a_batch_ends_the_spare_and_its_children(tmp_path, monkeypatch):
    import urdfcheck.load.xacro as xacro_pkg
    from urdfcheck.load.xacro import SPARE, SPARE_PRELOAD, worker_limits
    from urdfcheck.load.xacro import expand as xexpand

    monkeypatch.setattr(xexpand, "expand_with", lambda path, options: time.sleep(60))  # inherited by the spare
    monkeypatch.setattr(xacro_pkg, "batch_children", lambda n: n - 1)  # as with idle cores: a child for "a"
    worker.keep_spare(SPARE, worker_limits(False, (), 30.0), SPARE_PRELOAD)
    spare_pid = worker._SPARES[SPARE].pid
    try:
        batch = loader.Batch()
        for name in ("a", "b"):
            loader.begin(_xacro(tmp_path, f"{name}.urdf.xacro", '<link name="x"/>'), timeout=30.0, batch=batch)
        batch.send()
        assert batch.job is not None and batch.job.pid == spare_pid and batch.job.group
        end = time.monotonic() + 10
        # the spare (expanding the last model itself) and a child for the model before it
        while len(_group_alive(spare_pid)) < 2 and time.monotonic() < end:
            time.sleep(0.02)
        assert len(_group_alive(spare_pid)) == 2
        batch.shares[0].cancel()
        assert _gone(spare_pid)
        end = time.monotonic() + 5  # SIGKILL is delivered asynchronously: a child may still be on its way out
        while _group_alive(spare_pid) and time.monotonic() < end:
            time.sleep(0.02)
        assert _group_alive(spare_pid) == []  # its children were killed with it (init reaps what is left)
    finally:
        worker.drop_spares()


def _group_alive(pgid: int) -> list[int]:
    """Processes of the group that still run (a killed orphan is a zombie until init reaps it)."""
    out = []
    for d in os.listdir("/proc"):
        if d.isdigit():
            try:
                fields = Path(f"/proc/{d}/stat").read_text().rsplit(")", 1)[1].split()
            except OSError:
                continue
            if int(fields[2]) == pgid and fields[0] != "Z":
                out.append(int(d))
    return out


CONSOLE = """
import sys
from urdfcheck.cli import main
from urdfcheck.cli.cache import fork_early
fork_early(sys.argv[1:])
main.run(after=lambda code: (sys.stderr.write("yaml-in-console=%s\\n" % ("yaml" in sys.modules)), code)[1])
"""


def test_the_console_parses_no_yaml_itself_and_finds_the_same(tmp_path):
    """The AGV package's parameter files are parsed in the xacro worker (PyYAML is imported there for xacro): the
    console never imports PyYAML, and reports what a run that parses them itself reports."""
    import json
    import shutil
    import subprocess

    pkg = tmp_path / "agv"
    shutil.copytree(Path(__file__).resolve().parents[2] / "examples" / "agv", pkg)
    params = pkg / "config" / "agv_controllers.yaml"
    params.write_text(params.read_text().replace("wheel_radius: 0.10", "wheel_radius: 0.5", 1))  # a finding
    (pkg / "config" / "broken.yaml").write_text("controller_manager:\n  ros__parameters: [1, 2\n")  # an error back
    args = ["lint", "--no-config", "--no-cache", "--format", "json", "urdf/agv.urdf.xacro"]
    env = {**os.environ, "PYTHONPATH": str(SRC)}
    proc = subprocess.run([sys.executable, "-c", CONSOLE, *args], cwd=pkg, env=env, capture_output=True, text=True,
                          timeout=120)
    assert "yaml-in-console=False" in proc.stderr, proc.stderr
    alone = subprocess.run([sys.executable, "-c", "import sys; from urdfcheck.cli.main import main; "
                            "sys.exit(main(sys.argv[1:]))", *args], cwd=pkg, env=env, capture_output=True,
                           text=True, timeout=120)  # no spare: parsed in this process
    assert proc.returncode == alone.returncode == 1
    ours, theirs = json.loads(proc.stdout), json.loads(alone.stdout)
    assert ours["findings"] == theirs["findings"]
    assert "C011" in {f["code"] for f in ours["findings"]}  # the wheel radius, read from the worker's parse


def test_only_a_few_small_parameter_files_are_parsed_ahead(tmp_path):
    """The first results wait for the worker's parse: a package with many (or large) parameter files is read by
    the console as before, only what the prefilter lets through."""
    (tmp_path / "package.xml").write_text("<package><name>p</name></package>")
    (tmp_path / "config").mkdir()
    model = tmp_path / "r.urdf.xacro"
    model.write_text("<robot/>")
    t = lint.Target(model)
    for i in range(2):
        (tmp_path / "config" / f"c{i}.yaml").write_text("a: 1\n")
    func, (paths,) = lint._params_ahead([t])
    assert func.endswith(":parse_ahead") and sorted(os.path.basename(p) for p in paths) == ["c0.yaml", "c1.yaml"]
    (tmp_path / "config" / "big.yaml").write_text("a: 1\n" * (lint.PARAMS_AHEAD_BYTES // 4))
    assert lint._params_ahead([t]) is None
    (tmp_path / "config" / "big.yaml").unlink()
    for i in range(2, lint.PARAMS_AHEAD_FILES + 1):
        (tmp_path / "config" / f"c{i}.yaml").write_text("a: 1\n")
    assert lint._params_ahead([t]) is None


def _collector_state():
    import gc

    return gc.isenabled(), gc.get_freeze_count()


def test_a_child_collects_only_what_it_makes():
    """A child runs its job with the collector on (an expansion makes cyclic garbage), and what it inherited
    from the parent frozen: tracing it would write to every inherited object, copying the parent's pages."""
    import gc

    inherited = [[i] for i in range(1000)]  # noqa: F841 - objects the child inherits
    was = gc.isenabled()
    gc.disable()  # as a lint run forks its worker
    try:
        enabled, frozen = worker.run(_collector_state, timeout=30)
    finally:
        if was:
            gc.enable()
    assert enabled and frozen >= 1000
