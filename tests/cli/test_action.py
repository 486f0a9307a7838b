"""The GitHub Action (`action.yml`, composite): its steps run here as the runner would run them (issues 22, 38).

The `${{ }}` expressions are evaluated by a small evaluator for the forms the action uses (names, strings, ==, !=,
!, &&, ||, parentheses, the status functions); each `run:` step runs with bash (`-eo pipefail`, like the runner) in
a temporary git repository, with GITHUB_OUTPUT, GITHUB_STEP_SUMMARY, RUNNER_TEMP and an event payload of its own.
A failed step skips the later ones unless their `if` says otherwise or the step has `continue-on-error`, as on
the runner. `uses:` steps are recorded (the upload can be told to fail, as it does without the permission).

The install step runs for real: `python3` is a Python that refuses pip (PEP 668, Debian's /usr/bin/python3 with
its EXTERNALLY-MANAGED marker) when one is on this machine, else this interpreter; the action's source is a small
stand-in project (built offline by a backend of its own) whose `urdfcheck` command records its arguments and runs
this checkout's urdfcheck.
"""
from __future__ import annotations

import json
import os
import re
import shutil
import subprocess
import sys
from pathlib import Path

import pytest
import yaml

ROOT = Path(__file__).resolve().parents[2]
SRC = str(ROOT / "src")

pytestmark = pytest.mark.skipif(shutil.which("bash") is None or shutil.which("git") is None,
                                reason="bash or git not installed")


def action() -> dict:
    return yaml.safe_load((ROOT / "action.yml").read_text())


def _managed_python() -> str | None:
    """A Python whose pip refuses to install (PEP 668) and that can make a virtual environment."""
    for exe in ("/usr/bin/python3",):
        if not os.path.exists(exe):
            continue
        probe = subprocess.run([exe, "-c", "import sysconfig, os, ensurepip, venv; print(os.path.exists("
                                "os.path.join(sysconfig.get_path('stdlib'), 'EXTERNALLY-MANAGED')))"],
                               capture_output=True, text=True)
        if probe.returncode == 0 and probe.stdout.strip() == "True":
            return exe
    return None


MANAGED = _managed_python()


STAND_IN = '''import os, sys


def main():
    args = sys.argv[1:]
    log = os.environ.get("URDFCHECK_TEST_ARGV")
    if log:
        with open(log, "a") as f:
            f.write(json.dumps(args) + "\\n")
    if os.environ.get("URDFCHECK_TEST_CONFIG_FROM"):  # an urdfcheck that has `lint --config-from REV`
        if args[:2] == ["lint", "--help"]:
            print("  --config-from REV   the config of revision REV")
            return
        if "--config-from" in args:
            i = args.index("--config-from")
            del args[i:i + 2]
    env = dict(os.environ, PYTHONPATH={src!r})
    os.execve({python!r}, [{python!r}, "-m", "urdfcheck", *args], env)


import json  # noqa: E402
'''


# A PEP 517 backend in the project itself (nothing to download): the wheel holds the stand-in module, its
# console script and the extras the action may ask for.
BACKEND = '''import base64, hashlib, os, zipfile

NAME = "urdfcheck-0.0.0"
FILES = {
    "urdfcheck_stand_in.py": open(os.path.join(os.path.dirname(__file__), "urdfcheck_stand_in.py")).read(),
    NAME + ".dist-info/METADATA": "Metadata-Version: 2.1\\nName: urdfcheck\\nVersion: 0.0.0\\n"
                                  "Provides-Extra: bag\\nProvides-Extra: consumers\\n",
    NAME + ".dist-info/WHEEL": "Wheel-Version: 1.0\\nGenerator: test\\nRoot-Is-Purelib: true\\nTag: py3-none-any\\n",
    NAME + ".dist-info/entry_points.txt": "[console_scripts]\\nurdfcheck = urdfcheck_stand_in:main\\n",
}


def get_requires_for_build_wheel(config_settings=None):
    return []


def build_wheel(wheel_directory, config_settings=None, metadata_directory=None):
    name = NAME + "-py3-none-any.whl"
    rows = []
    with zipfile.ZipFile(os.path.join(wheel_directory, name), "w") as z:
        for path, text in FILES.items():
            data = text.encode()
            z.writestr(path, data)
            digest = base64.urlsafe_b64encode(hashlib.sha256(data).digest()).rstrip(b"=").decode()
            rows.append(f"{path},sha256={digest},{len(data)}")
        rows.append(NAME + ".dist-info/RECORD,,")
        z.writestr(NAME + ".dist-info/RECORD", "\\n".join(rows) + "\\n")
    return name
'''


@pytest.fixture(scope="module")
def source(tmp_path_factory) -> Path:
    """What `github.action_path` holds for pip: a project named urdfcheck with the action's extras."""
    d = tmp_path_factory.mktemp("action_source")
    (d / "urdfcheck_stand_in.py").write_text(STAND_IN.format(src=SRC, python=sys.executable))
    (d / "stand_in_backend.py").write_text(BACKEND)
    (d / "pyproject.toml").write_text('[build-system]\nrequires = []\nbuild-backend = "stand_in_backend"\n'
                                      'backend-path = ["."]\n')
    return d


class Context:
    def __init__(self, inputs: dict, workspace: Path, source: Path, event_name: str, event: dict):
        self.inputs = inputs
        self.github = {"action_path": str(source), "workspace": str(workspace), "event_name": event_name,
                       "event": event, "repository": "owner/robot"}
        self.steps: dict[str, dict] = {}
        self.failed = False

    def value(self, name: str):
        head, _, rest = name.partition(".")
        if head == "inputs":
            return self.inputs[rest]
        if head == "github":
            value = self.github
            for part in rest.split("."):
                value = value.get(part, "") if isinstance(value, dict) else ""
            return value
        if head == "steps":
            sid, _, out = rest.partition(".outputs.")
            return self.steps.get(sid, {}).get(out, "")
        raise AssertionError(f"expression {name!r} not known to the test")

    def evaluate(self, expr: str):
        tokens = re.findall(r"(?:cancelled|always|success|failure)\(\)|'[^']*'|&&|\|\||==|!=|!|\(|\)"
                            r"|[A-Za-z_][\w.-]*", expr)
        assert "".join(tokens).replace(" ", "") == expr.replace(" ", ""), f"cannot evaluate {expr!r}"
        funcs = {"cancelled()": "False", "always()": "True", "success()": repr(not self.failed),
                 "failure()": repr(self.failed)}
        py = []
        for t in tokens:
            if t in funcs:
                py.append(funcs[t])
            elif t in ("&&", "||", "!"):
                py.append({"&&": "and", "||": "or", "!": "not"}[t])
            elif t in ("==", "!=", "(", ")"):
                py.append(t)
            elif t.startswith("'"):
                py.append(repr(t[1:-1]))
            else:
                py.append(repr(self.value(t)))
        return eval(" ".join(py))  # noqa: S307 - built from the tokens above only

    def substitute(self, text: str) -> str:
        return re.sub(r"\$\{\{\s*(.*?)\s*\}\}", lambda m: str(self.evaluate(m.group(1))), text)


def git(cwd: Path, *args: str) -> str:
    env = {**os.environ, "GIT_AUTHOR_NAME": "t", "GIT_AUTHOR_EMAIL": "t@t", "GIT_COMMITTER_NAME": "t",
           "GIT_COMMITTER_EMAIL": "t@t", "GIT_CONFIG_GLOBAL": os.devnull, "GIT_CONFIG_NOSYSTEM": "1"}
    return subprocess.run(["git", *args], cwd=cwd, env=env, check=True, capture_output=True,
                          text=True).stdout.strip()


def run_action(tmp_path: Path, workspace: Path, source: Path, inputs: dict | None = None, event_name: str = "push",
               event: dict | None = None, python: str | None = None, upload_fails: bool = False,
               extra_env: dict | None = None):
    tmp_path.mkdir(exist_ok=True)
    spec = action()
    defaults = {k: v.get("default", "") for k, v in spec["inputs"].items()}
    ctx = Context({**defaults, **(inputs or {})}, workspace, source, event_name, event or {})
    shims = tmp_path / "shims"
    shims.mkdir()
    (shims / "python3").symlink_to(python or MANAGED or sys.executable)
    files = {k: tmp_path / k.lower() for k in ("GITHUB_OUTPUT", "GITHUB_STEP_SUMMARY", "GITHUB_EVENT_PATH")}
    for f in files.values():
        f.write_text("")
    files["GITHUB_EVENT_PATH"].write_text(json.dumps(event or {}))
    argv_log = tmp_path / "argv.log"
    runner_temp = tmp_path / "runner_temp"
    runner_temp.mkdir()
    log = []
    for step in spec["runs"]["steps"]:
        cond = re.sub(r"^\$\{\{\s*(.*?)\s*\}\}$", r"\1", str(step.get("if", "success()")).strip())
        if not ctx.evaluate(cond):
            log.append((step["name"], "skipped", None))
            continue
        if "uses" in step:
            log.append((step["name"], "uses", {k: ctx.substitute(str(v)) for k, v in step.get("with", {}).items()}))
            if upload_fails and "upload-sarif" in step["uses"] and not step.get("continue-on-error"):
                ctx.failed = True
            continue
        assert step["shell"] == "bash"
        files["GITHUB_OUTPUT"].write_text("")
        env = {k: v for k, v in os.environ.items() if not k.startswith(("PIP_", "VIRTUAL_ENV", "PYTHON"))}
        env.update({"PATH": f"{shims}{os.pathsep}{os.environ['PATH']}", "RUNNER_TEMP": str(runner_temp),
                    "GITHUB_WORKSPACE": str(workspace), "GITHUB_EVENT_NAME": event_name,
                    "GITHUB_REPOSITORY": "owner/robot", "NO_COLOR": "1", "URDFCHECK_TEST_ARGV": str(argv_log),
                    "PIP_NO_INDEX": "1", "GIT_CONFIG_NOSYSTEM": "1",  # offline
                    **{k: str(v) for k, v in files.items()}, **(extra_env or {}),
                    **{k: ctx.substitute(str(v)) for k, v in step.get("env", {}).items()}})
        cwd = workspace / ctx.substitute(step.get("working-directory", "."))
        script = ctx.substitute(step["run"])
        res = subprocess.run(["bash", "--noprofile", "--norc", "-eo", "pipefail", "-c", script], cwd=cwd, env=env,
                             capture_output=True, text=True, timeout=300)
        outputs = dict(line.split("=", 1) for line in files["GITHUB_OUTPUT"].read_text().splitlines() if "=" in line)
        if "id" in step:
            ctx.steps[step["id"]] = outputs
        log.append((step["name"], res.returncode, res))
        if res.returncode != 0 and not step.get("continue-on-error"):
            ctx.failed = True
    argv = [json.loads(ln) for ln in argv_log.read_text().splitlines()] if argv_log.exists() else []
    return ctx, log, files["GITHUB_STEP_SUMMARY"].read_text(), argv


def status(log) -> dict:
    return {name: rc for name, rc, _ in log}


def workspace_with(tmp_path: Path, example: str, under: str = "src") -> Path:
    """A git repository holding the example package under `under`/<name>, committed."""
    ws = tmp_path / "ws"
    shutil.copytree(ROOT / example, ws / under / Path(example).name)
    git(ws, "init", "-q")
    git(ws, "add", "-A")
    git(ws, "commit", "-qm", "base")
    return ws


def lint_argv(argv) -> list:
    return next(a for a in argv if a and a[0] == "lint" and "--help" not in a)


def test_action_metadata():
    spec = action()
    assert spec["runs"]["using"] == "composite"
    assert set(spec["inputs"]) >= {"paths", "fail-on", "sarif", "summary", "args", "extras", "config-from-base",
                                   "diff-base"}
    assert all("description" in v for v in spec["inputs"].values())
    assert spec["inputs"]["fail-on"]["default"] == "warning"  # never the checkout's config
    steps = {s["name"]: s for s in spec["runs"]["steps"]}
    upload = steps["Upload SARIF to code scanning"]
    assert upload["uses"] == "github/codeql-action/upload-sarif@v3" and upload["continue-on-error"] is True
    for s in spec["runs"]["steps"]:  # inputs reach scripts through env, never pasted into them
        assert "inputs." not in s.get("run", "") and "github." not in s.get("run", ""), s["name"]


def test_clean_workspace(tmp_path, source):
    ws = workspace_with(tmp_path, "examples/agv")
    ctx, log, summary, argv = run_action(tmp_path, ws, source)
    st = status(log)
    assert st["Set up Python"] == "skipped"
    assert st["Install urdfcheck"] == 0, log[1][2].stdout + log[1][2].stderr
    assert st["urdfcheck lint"] == 0 and st["urdfcheck result"] == 0
    out = ctx.steps["lint"]
    assert out["exit-code"] == "0"
    sarif = json.loads(Path(out["sarif-file"]).read_text())
    assert sarif["version"] == "2.1.0" and sarif["runs"][0]["results"] == []
    assert not Path(out["sarif-file"]).is_relative_to(ws)  # reports outside the checkout
    upload = next(w for name, kind, w in log if kind == "uses")
    assert upload["sarif_file"] == out["sarif-file"] and upload["category"] == "urdfcheck"
    assert "urdfcheck" in summary and "mermaid" in summary
    assert not (ws / "urdfcheck-venv").exists() and git(ws, "status", "--porcelain") == ""  # nothing written


@pytest.mark.skipif(MANAGED is None, reason="no Python here refuses pip by PEP 668 (EXTERNALLY-MANAGED)")
def test_installs_into_its_own_environment_where_pip_is_refused(tmp_path, source):
    """On ubuntu-24.04 and in ros:jazzy containers `python3 -m pip install` is refused (PEP 668)."""
    refused = subprocess.run([MANAGED, "-m", "pip", "install", "--no-index", str(source)], capture_output=True,
                             text=True, env={k: v for k, v in os.environ.items() if not k.startswith("PIP_")})
    assert refused.returncode != 0 and "externally-managed-environment" in refused.stderr
    ws = workspace_with(tmp_path, "examples/broken/joint_limits")
    ctx, log, _, argv = run_action(tmp_path, ws, source, {"sarif": "false", "extras": "bag"}, python=MANAGED)
    st = status(log)
    assert st["Install urdfcheck"] == 0, log[1][2].stderr if log[1][2] else log
    exe = Path(ctx.steps["install"]["urdfcheck"])
    assert exe.parent.parent == tmp_path / "runner_temp" / "urdfcheck-venv"
    assert ctx.steps["lint"]["exit-code"] == "1" and st["urdfcheck result"] == 1
    assert lint_argv(argv)  # the environment's urdfcheck is what ran


def test_extras_are_names_only(tmp_path, source):
    ws = workspace_with(tmp_path, "examples/agv")
    ctx, log, _, _ = run_action(tmp_path, ws, source, {"extras": "bag] ; touch pwned ; ["})
    assert status(log)["Install urdfcheck"] == 2
    assert not any(p.name == "pwned" for p in tmp_path.rglob("pwned"))


def test_findings_fail_the_job_with_annotations(tmp_path, source):
    ws = workspace_with(tmp_path, "examples/broken/joint_limits")
    ctx, log, summary, _ = run_action(tmp_path, ws, source, {"sarif": "false"})
    st = {name: (rc, res) for name, rc, res in log}
    lint_rc, lint = st["urdfcheck lint"]
    assert lint_rc == 0 and ctx.steps["lint"]["exit-code"] == "1"  # the status waits for the upload
    assert "::error file=src/joint_limits/urdf/agv.urdf,line=" in lint.stdout
    assert st["Upload SARIF to code scanning"][0] == "skipped"
    assert st["urdfcheck result"][0] == 1
    assert "J00" in summary
    sarif = json.loads(Path(ctx.steps["lint"]["sarif-file"]).read_text())
    assert sarif["runs"][0]["results"]


def test_locations_are_relative_to_the_repository_root_from_a_subfolder(tmp_path, source):
    ws = workspace_with(tmp_path, "examples/broken/joint_limits", under="src/robot")
    ctx, log, _, _ = run_action(tmp_path, ws, source, {"working-directory": "src/robot/joint_limits"})
    lint = next(res for name, _, res in log if name == "urdfcheck lint")
    assert ctx.steps["lint"]["exit-code"] == "1"
    files = set(re.findall(r"^::\w+ file=([^,]+),", lint.stdout, re.M))
    assert files == {"src/robot/joint_limits/urdf/agv.urdf"}
    sarif = json.loads(Path(ctx.steps["lint"]["sarif-file"]).read_text())
    uris = {loc["physicalLocation"]["artifactLocation"]["uri"]
            for r in sarif["runs"][0]["results"] for loc in r["locations"]}
    assert uris == {"src/robot/joint_limits/urdf/agv.urdf"}
    upload = next(w for name, kind, w in log if kind == "uses")
    assert upload["checkout_path"] == str(ws)  # %SRCROOT% is the repository root the URIs are relative to


def test_fail_on_is_the_workflows_not_the_checkouts_config(tmp_path, source):
    """A pull request that adds `fail_on: error` to urdfcheck.yaml does not turn its warnings into a pass."""
    ws = workspace_with(tmp_path, "examples/broken/typo_orign")
    (ws / "urdfcheck.yaml").write_text("fail_on: error\n")
    ctx, log, _, argv = run_action(tmp_path, ws, source, {"sarif": "false"})
    assert ctx.steps["lint"]["exit-code"] == "1"
    assert status(log)["urdfcheck result"] == 1
    args = lint_argv(argv)
    assert args[args.index("--fail-on") + 1] == "warning"


FORK = "mallory/robot"


def pull_request(ws: Path, head_repo: str, change=None) -> dict:
    """Commit the pull request's change (`change(ws)`, else a README edit) and return its event."""
    base = git(ws, "rev-parse", "HEAD")
    if change is None:
        (ws / "README.md").write_text("the pull request's change\n")
    else:
        change(ws)
    git(ws, "add", "-A")
    git(ws, "commit", "-qm", "pr")
    return {"pull_request": {"number": 7, "base": {"sha": base, "repo": {"full_name": "owner/robot"}},
                             "head": {"sha": git(ws, "rev-parse", "HEAD"),
                                      "repo": {"full_name": head_repo, "fork": head_repo != "owner/robot"}}}}


def zero_velocity(urdf: str):
    """A pull request's change that adds one finding (J004 at line 77) to the joint_limits example's two errors."""
    def change(ws: Path):
        f = ws / urdf
        text = f.read_text()
        assert text.splitlines()[76].strip() == '<limit effort="20.0" velocity="10.0"/>'
        f.write_text(text.replace('<limit effort="20.0" velocity="10.0"/>', '<limit effort="20.0" velocity="0"/>', 1))
    return change


def test_fork_pull_request_from_a_subfolder_reports_what_it_adds(tmp_path, source):
    """All at once, as issue 38 asks: a pull request from a fork (read-only token), the action run with
    `working-directory: src/robot/joint_limits`, and the PEP 668 Python of this machine when it has one (the install
    step makes its own environment). The pull request adds J004 to a package with two old errors and an info: the
    upload is
    not tried, the summary names the new finding at its repository path, and the job fails on it alone."""
    urdf = "src/robot/joint_limits/urdf/agv.urdf"
    ws = workspace_with(tmp_path, "examples/broken/joint_limits", under="src/robot")
    event = pull_request(ws, FORK, zero_velocity(urdf))
    ctx, log, summary, argv = run_action(tmp_path, ws, source, {"working-directory": "src/robot/joint_limits"},
                                         event_name="pull_request", event=event, upload_fails=True)
    st = status(log)
    assert st["Install urdfcheck"] == 0
    assert Path(ctx.steps["install"]["urdfcheck"]).parent.parent == tmp_path / "runner_temp" / "urdfcheck-venv"
    assert st["Upload SARIF to code scanning"] == "skipped"  # a read-only token: not tried
    assert st["urdfcheck result"] == 1 and ctx.steps["lint"]["exit-code"] == "1"
    args = lint_argv(argv)
    base = event["pull_request"]["base"]["sha"]
    assert args[args.index("--config-from") + 1] == base  # the base revision's config, not the fork's
    assert args[args.index("--diff-base") + 1] == base
    lint = next(res for name, _, res in log if name == "urdfcheck lint")
    assert set(re.findall(r"^::\w+ file=([^,]+),", lint.stdout, re.M)) == {urdf}  # every finding annotated
    assert "1 new, 0 fixed, 3 unchanged" in summary  # the two errors and an info were there before
    # the headline says what the job's status judged: the new finding; the old errors do not gate (the info is
    # below the level)
    assert f"❌ **1 new finding at or above warning** in 1 model (2 unchanged since {base} at or above it, not " \
           "gating;" in summary, summary
    new = [ln for ln in summary.splitlines() if ln.startswith("- :new:")]
    assert len(new) == 1 and "J004" in new[0] and f"{urdf}:77" in new[0], summary
    assert str(ws) not in summary and str(tmp_path) not in summary


def test_a_pull_request_with_only_old_debts_passes_and_says_so(tmp_path, source):
    """The same package's old findings, a pull request that touches only the README: nothing new, the job
    passes, and the summary still lists every finding with the tally against the base."""
    ws = workspace_with(tmp_path, "examples/broken/joint_limits")
    event = pull_request(ws, FORK)
    ctx, log, summary, _ = run_action(tmp_path, ws, source, event_name="pull_request", event=event)
    assert ctx.steps["lint"]["exit-code"] == "0" and status(log)["urdfcheck result"] == 0
    assert "0 new, 0 fixed, 3 unchanged" in summary and "J003" in summary
    assert "✅ **no new findings at or above warning** in 1 model (2 unchanged since " in summary, summary


def test_diff_base_off_gates_a_pull_request_on_every_finding(tmp_path, source):
    ws = workspace_with(tmp_path, "examples/broken/joint_limits")
    event = pull_request(ws, FORK)
    ctx, log, summary, argv = run_action(tmp_path, ws, source, {"diff-base": "false"}, event_name="pull_request",
                                         event=event)
    assert "--diff-base" not in lint_argv(argv)
    assert ctx.steps["lint"]["exit-code"] == "1" and status(log)["urdfcheck result"] == 1
    assert "unchanged" not in summary


def test_a_shallow_pull_request_checkout_gets_the_base_commit_and_its_config(tmp_path, source):
    """actions/checkout fetches one commit: the action fetches the base commit (from the checkout's own remote) and
    passes `--config-from BASE_SHA` to an urdfcheck that has the flag."""
    origin = workspace_with(tmp_path, "examples/agv")
    event = pull_request(origin, FORK)
    base = event["pull_request"]["base"]["sha"]
    ws = tmp_path / "checkout"
    git(tmp_path, "clone", "-q", "--depth", "1", f"file://{origin}", str(ws))
    with pytest.raises(subprocess.CalledProcessError):
        git(ws, "cat-file", "-e", f"{base}^{{commit}}")  # not in the shallow checkout
    ctx, log, _, argv = run_action(tmp_path / "run", ws, source, {"sarif": "false"}, event_name="pull_request",
                                   event=event, extra_env={"URDFCHECK_TEST_CONFIG_FROM": "1"})
    args = lint_argv(argv)
    assert args[args.index("--config-from") + 1] == base
    git(ws, "cat-file", "-e", f"{base}^{{commit}}")  # fetched
    assert ctx.steps["lint"]["exit-code"] == "0"


def test_config_from_base_can_be_turned_off(tmp_path, source):
    ws = workspace_with(tmp_path, "examples/agv")
    event = pull_request(ws, FORK)
    _, _, _, argv = run_action(tmp_path, ws, source, {"config-from-base": "false", "sarif": "false"},
                               event_name="pull_request", event=event)
    assert "--config-from" not in lint_argv(argv)


def test_a_failed_upload_does_not_hide_the_result(tmp_path, source):
    """Same-repository pull request without `security-events: write`: the upload fails, the job still ends with
    urdfcheck's status."""
    ws = workspace_with(tmp_path, "examples/broken/joint_limits")
    event = pull_request(ws, "owner/robot", zero_velocity("src/joint_limits/urdf/agv.urdf"))
    ctx, log, _, _ = run_action(tmp_path, ws, source, {"config-from-base": "false"}, event_name="pull_request",
                                event=event, upload_fails=True)
    st = status(log)
    assert st["Upload SARIF to code scanning"] == "uses"  # tried
    assert st["urdfcheck result"] == 1


def test_fail_on_and_paths_inputs(tmp_path, source):
    ws = workspace_with(tmp_path, "examples/broken/joint_limits")
    ctx, _, _, _ = run_action(tmp_path, ws, source,
                              {"paths": "src/joint_limits", "fail-on": "error", "args": "--select J003"})
    assert ctx.steps["lint"]["exit-code"] == "1"  # J003 (inverted limits) is an error
    quiet = {"paths": "src/joint_limits", "args": "--select J011 --no-config"}
    ctx, _, _, _ = run_action(tmp_path / "again", ws, source, quiet)
    assert ctx.steps["lint"]["exit-code"] == "0"


def test_unusable_invocation_is_not_a_pass(tmp_path, source):
    ws = workspace_with(tmp_path, "examples/agv")
    ctx, log, summary, _ = run_action(tmp_path, ws, source, {"paths": "no/such/folder"})
    assert ctx.steps["lint"]["exit-code"] == "2"
    assert status(log)["urdfcheck result"] == 2
    assert "could not run" in summary
    assert next(kind for name, kind, _ in log if name.startswith("Upload")) == "skipped"
