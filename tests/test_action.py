"""The GitHub Action (`action.yml`, composite): its steps run here as the runner would run them (issue 22).

The `${{ }}` expressions are evaluated by a small evaluator for the forms the action uses; each `run:` step
runs with bash (`-eo pipefail`, like the runner) against an example package in a temporary workspace, with
GITHUB_OUTPUT, GITHUB_STEP_SUMMARY and RUNNER_TEMP files of its own. `python3` and `urdfcheck` are shims:
`pip install` is recorded (never run: no network), `urdfcheck` runs this checkout.
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

ROOT = Path(__file__).resolve().parents[1]
SRC = str(ROOT / "src")

pytestmark = pytest.mark.skipif(shutil.which("bash") is None, reason="bash not installed")


def action() -> dict:
    return yaml.safe_load((ROOT / "action.yml").read_text())


class Context:
    def __init__(self, inputs: dict, workspace: Path):
        self.inputs = inputs
        self.github = {"action_path": str(ROOT), "workspace": str(workspace)}
        self.steps: dict[str, dict] = {}

    def value(self, name: str):
        head, _, rest = name.partition(".")
        if head == "inputs":
            return self.inputs[rest]
        if head == "github":
            return self.github[rest]
        if head == "steps":
            sid, _, out = rest.partition(".outputs.")
            return self.steps.get(sid, {}).get(out, "")
        raise AssertionError(f"expression {name!r} not known to the test")

    def evaluate(self, expr: str):
        """The expression forms the action uses: names, '' strings, == and !=, &&, !cancelled()."""
        tokens = re.findall(r"!cancelled\(\)|'[^']*'|&&|\|\||==|!=|[A-Za-z_][\w.-]*", expr)
        assert "".join(tokens).replace(" ", "") == expr.replace(" ", ""), f"cannot evaluate {expr!r}"
        py = []
        for t in tokens:
            if t == "!cancelled()":
                py.append("True")
            elif t in ("&&", "||"):
                py.append("and" if t == "&&" else "or")
            elif t in ("==", "!="):
                py.append(t)
            elif t.startswith("'"):
                py.append(repr(t[1:-1]))
            else:
                py.append(repr(self.value(t)))
        return eval(" ".join(py))  # noqa: S307 - built from the tokens above only

    def substitute(self, text: str) -> str:
        return re.sub(r"\$\{\{\s*(.*?)\s*\}\}", lambda m: str(self.evaluate(m.group(1))), text)


def run_action(tmp_path: Path, workspace: Path, inputs: dict | None = None):
    tmp_path.mkdir(exist_ok=True)
    spec = action()
    defaults = {k: v.get("default", "") for k, v in spec["inputs"].items()}
    ctx = Context({**defaults, **(inputs or {})}, workspace)
    shims = tmp_path / "shims"
    shims.mkdir()
    pip_log = tmp_path / "pip.log"
    (shims / "python3").write_text(
        f'#!/bin/sh\nif [ "$1 $2 $3" = "-m pip install" ]; then echo "$@" >> "{pip_log}"; exit 0; fi\n'
        f'exec "{sys.executable}" "$@"\n')
    (shims / "urdfcheck").write_text(f'#!/bin/sh\nexec "{sys.executable}" -m urdfcheck "$@"\n')
    for f in shims.iterdir():
        f.chmod(0o755)
    files = {k: tmp_path / k.lower() for k in ("GITHUB_OUTPUT", "GITHUB_STEP_SUMMARY")}
    for f in files.values():
        f.write_text("")
    runner_temp = tmp_path / "runner_temp"
    runner_temp.mkdir()
    log = []
    for step in spec["runs"]["steps"]:
        if "if" in step and not ctx.evaluate(re.sub(r"^\$\{\{\s*(.*?)\s*\}\}$", r"\1", step["if"].strip())):
            log.append((step["name"], "skipped", None))
            continue
        if "uses" in step:
            log.append((step["name"], "uses", {k: ctx.substitute(str(v)) for k, v in step.get("with", {}).items()}))
            continue
        assert step["shell"] == "bash"
        files["GITHUB_OUTPUT"].write_text("")
        env = {**os.environ, "PATH": f"{shims}{os.pathsep}{os.environ['PATH']}", "RUNNER_TEMP": str(runner_temp),
               "PYTHONPATH": SRC, "GITHUB_WORKSPACE": str(workspace), "NO_COLOR": "1",
               **{k: str(v) for k, v in files.items()},
               **{k: ctx.substitute(str(v)) for k, v in step.get("env", {}).items()}}
        cwd = workspace / ctx.substitute(step.get("working-directory", "."))
        script = ctx.substitute(step["run"])
        res = subprocess.run(["bash", "--noprofile", "--norc", "-eo", "pipefail", "-c", script], cwd=cwd, env=env,
                             capture_output=True, text=True, timeout=300)
        outputs = dict(line.split("=", 1) for line in files["GITHUB_OUTPUT"].read_text().splitlines() if "=" in line)
        if "id" in step:
            ctx.steps[step["id"]] = outputs
        log.append((step["name"], res.returncode, res))
        if res.returncode != 0:
            break
    return ctx, log, files["GITHUB_STEP_SUMMARY"].read_text(), pip_log


def workspace_with(tmp_path: Path, example: str) -> Path:
    ws = tmp_path / "ws"
    shutil.copytree(ROOT / example, ws / "src" / Path(example).name)
    return ws


def test_action_metadata():
    spec = action()
    assert spec["runs"]["using"] == "composite"
    assert set(spec["inputs"]) >= {"paths", "fail-on", "sarif", "summary", "args"}
    assert all("description" in v for v in spec["inputs"].values())
    uses = [s["uses"] for s in spec["runs"]["steps"] if "uses" in s]
    assert "github/codeql-action/upload-sarif@v3" in uses
    for s in spec["runs"]["steps"]:  # inputs reach scripts through env, never pasted into them
        assert "inputs." not in s.get("run", ""), s["name"]


def test_clean_workspace(tmp_path):
    ws = workspace_with(tmp_path, "examples/agv")
    ctx, log, summary, pip_log = run_action(tmp_path, ws)
    status = {name: rc for name, rc, _ in log}
    assert status["Set up Python"] == "skipped"
    assert str(ROOT) in pip_log.read_text()  # installed from the action's own checkout
    assert status["urdfcheck lint"] == 0 and status["urdfcheck result"] == 0
    out = ctx.steps["lint"]
    assert out["exit-code"] == "0"
    sarif = json.loads(Path(out["sarif-file"]).read_text())
    assert sarif["version"] == "2.1.0" and sarif["runs"][0]["results"] == []
    assert not Path(out["sarif-file"]).is_relative_to(ws)  # reports outside the checkout
    upload = next(w for name, kind, w in log if kind == "uses")
    assert upload["sarif_file"] == out["sarif-file"] and upload["category"] == "urdfcheck"
    assert "urdfcheck" in summary and "mermaid" in summary


def test_findings_fail_the_job_with_annotations(tmp_path):
    ws = workspace_with(tmp_path, "examples/broken/joint_limits")
    ctx, log, summary, _ = run_action(tmp_path, ws, {"sarif": "false"})
    status = {name: (rc, res) for name, rc, res in log}
    lint_rc, lint = status["urdfcheck lint"]
    assert lint_rc == 0 and ctx.steps["lint"]["exit-code"] == "1"  # the status waits for the upload
    assert "::error file=src/joint_limits/urdf/agv.urdf,line=" in lint.stdout
    assert status["Upload SARIF to code scanning"][0] == "skipped"
    assert status["urdfcheck result"][0] == 1
    assert "J00" in summary
    sarif = json.loads(Path(ctx.steps["lint"]["sarif-file"]).read_text())
    assert sarif["runs"][0]["results"]


def test_fail_on_and_paths_inputs(tmp_path):
    ws = workspace_with(tmp_path, "examples/broken/joint_limits")
    ctx, _, _, _ = run_action(tmp_path, ws, {"paths": "src/joint_limits", "fail-on": "error", "args": "--select J003"})
    assert ctx.steps["lint"]["exit-code"] == "1"  # J003 (inverted limits) is an error
    quiet = {"paths": "src/joint_limits", "args": "--select J011 --no-config"}
    ctx, _, _, _ = run_action(tmp_path / "again", ws, quiet)
    assert ctx.steps["lint"]["exit-code"] == "0"


def test_unusable_invocation_is_not_a_pass(tmp_path):
    ws = workspace_with(tmp_path, "examples/agv")
    ctx, log, summary, _ = run_action(tmp_path, ws, {"paths": "no/such/folder"})
    assert ctx.steps["lint"]["exit-code"] == "2"
    assert {name: rc for name, rc, _ in log}["urdfcheck result"] == 2
    assert "could not run" in summary
    assert next(kind for name, kind, _ in log if name.startswith("Upload")) == "skipped"
