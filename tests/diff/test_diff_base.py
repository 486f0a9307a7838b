"""What a pull request does to the findings: `lint --diff-base REV` (issue 38)."""
from __future__ import annotations

import json
import os
import shutil
import subprocess
import sys
from pathlib import Path

import pytest
from gitrepo import edit, git, lint  # noqa: F401

ROOT = Path(__file__).resolve().parents[2]
AGV = ROOT / "examples" / "agv"
SRC = str(ROOT / "src")

pytestmark = pytest.mark.skipif(shutil.which("git") is None, reason="git not installed")


@pytest.fixture
def repo(tmp_path):
    repo = tmp_path / "repo"
    shutil.copytree(AGV, repo / "agv_description")
    (repo / "agv_description/urdfcheck.yaml").unlink()  # zero config: the launch file's deployment
    git("init", "-q", cwd=repo)
    git("add", "-A", cwd=repo)
    git("commit", "-qm", "init", cwd=repo)
    (tmp_path / "tmp").mkdir()
    return repo


CTRL = "agv_description/config/agv_controllers.yaml"


def test_a_new_finding_is_new_and_fails(repo, tmp_path):
    edit(repo / CTRL, "left_wheel_names: [left_wheel_joint]", "left_wheel_names: [left_wheel_jointX]")
    res = lint("--diff-base", "HEAD", cwd=repo, tmp=tmp_path / "tmp")
    assert res.returncode == 1, res.stderr
    assert "against HEAD: 1 new, 0 fixed, 0 unchanged" in res.stdout
    assert f"NEW   {CTRL}:15: error C001" in res.stdout
    data = json.loads(lint("--diff-base", "HEAD", "--format", "json", cwd=repo, tmp=tmp_path / "tmp").stdout)
    assert [(x["code"], x["file"], x["line"]) for x in data["diff_base"]["new"]] == [("C001", CTRL, 15)]
    md = lint("--diff-base", "HEAD", "--format", "markdown", cwd=repo, tmp=tmp_path / "tmp").stdout
    assert "New in this change" in md and "C001" in md
    for out in (res.stdout + res.stderr, md, json.dumps(data)):
        assert "urdfcheck-rev-" not in out and str(tmp_path) not in out
    assert os.listdir(tmp_path / "tmp") == []  # the base revision's folder is removed
    status = subprocess.run(["git", "status", "--porcelain"], cwd=repo, capture_output=True, text=True).stdout
    assert status.split() == ["M", CTRL]  # nothing written into the user's tree


def test_an_old_debt_that_moved_lines_is_unchanged_and_passes(repo, tmp_path):
    edit(repo / CTRL, "left_wheel_names: [left_wheel_joint]", "left_wheel_names: [left_wheel_jointX]")
    git("commit", "-qam", "debt", cwd=repo)
    text = (repo / CTRL).read_text()
    (repo / CTRL).write_text("# a comment\n# and another\n" + text)
    res = lint("--diff-base", "HEAD", cwd=repo, tmp=tmp_path / "tmp")
    assert "against HEAD: 0 new, 0 fixed, 1 unchanged" in res.stdout, res.stdout + res.stderr
    assert res.returncode == 0  # --fail-on looks at new findings only
    assert f"{CTRL}:17:" in res.stdout  # the report itself still shows the finding where it is now
    assert lint(cwd=repo, tmp=tmp_path / "tmp").returncode == 1  # without --diff-base: it fails


def test_a_second_line_of_an_old_problem_is_new(repo, tmp_path):
    """Two wrong joint names in one file are one finding with an `also` line; the change that adds the second
    adds a problem though the finding's first line is the old one (it passed as "1 unchanged" before)."""
    edit(repo / CTRL, "left_wheel_names: [left_wheel_joint]", "left_wheel_names: [left_wheel_jointX]")
    git("commit", "-qam", "debt", cwd=repo)
    edit(repo / CTRL, "right_wheel_names: [right_wheel_joint]", "right_wheel_names: [right_wheel_jointX]")
    res = lint("--diff-base", "HEAD", "--format", "json", cwd=repo, tmp=tmp_path / "tmp")
    assert res.returncode == 1, res.stderr
    d = json.loads(res.stdout)["diff_base"]
    assert [x["code"] for x in d["new"]] == ["C001"] and d["fixed"] == [] and d["unchanged"] == 0
    git("commit", "-qam", "second debt", cwd=repo)  # both lines old: unchanged again
    d = json.loads(lint("--diff-base", "HEAD", "--format", "json", cwd=repo, tmp=tmp_path / "tmp").stdout)["diff_base"]
    assert (d["new"], d["fixed"], d["unchanged"]) == ([], [], 1)


def test_a_fixed_finding_is_fixed(repo, tmp_path):
    edit(repo / CTRL, "left_wheel_names: [left_wheel_joint]", "left_wheel_names: [left_wheel_jointX]")
    git("commit", "-qam", "debt", cwd=repo)
    edit(repo / CTRL, "left_wheel_names: [left_wheel_jointX]", "left_wheel_names: [left_wheel_joint]")
    res = lint("--diff-base", "HEAD", "--format", "json", cwd=repo / "agv_description", tmp=tmp_path / "tmp")
    assert res.returncode == 0, res.stderr
    d = json.loads(res.stdout)["diff_base"]
    assert (len(d["new"]), d["unchanged"]) == (0, 0)
    assert [(x["code"], x["file"], x["line"]) for x in d["fixed"]] == [("C001", "config/agv_controllers.yaml", 15)]


def test_a_package_new_in_the_change_has_only_new_findings(tmp_path):
    repo = tmp_path / "repo"
    (repo / "docs").mkdir(parents=True)
    (repo / "docs/readme.md").write_text("x\n")
    git("init", "-q", cwd=repo)
    git("add", "-A", cwd=repo)
    git("commit", "-qm", "init", cwd=repo)
    shutil.copytree(AGV, repo / "agv_description")
    edit(repo / CTRL, "left_wheel_names: [left_wheel_joint]", "left_wheel_names: [left_wheel_jointX]")
    (tmp_path / "tmp").mkdir()
    res = lint("--diff-base", "HEAD", "agv_description", cwd=repo, tmp=tmp_path / "tmp")
    assert res.returncode == 1 and "1 new, 0 fixed, 0 unchanged" in res.stdout, res.stdout + res.stderr


def test_no_repository_or_revision_is_a_usage_error(repo, tmp_path):
    assert lint("--diff-base", "no-such-rev", cwd=repo, tmp=tmp_path / "tmp").returncode == 2
    alone = tmp_path / "alone"
    shutil.copytree(AGV, alone)
    res = lint("--diff-base", "HEAD", cwd=alone, tmp=tmp_path / "tmp")
    assert res.returncode == 2 and "no git repository" in res.stderr


def test_diff_findings_tells_what_the_change_adds(repo, tmp_path):
    edit(repo / CTRL, "left_wheel_names: [left_wheel_joint]", "left_wheel_names: [left_wheel_jointX]")
    env_tmp = tmp_path / "tmp"
    cmd = [sys.executable, "-m", "urdfcheck", "diff", "--git", "HEAD", "--findings"]
    env = {**os.environ, "PYTHONPATH": SRC + os.pathsep + os.environ.get("PYTHONPATH", ""), "TMPDIR": str(env_tmp)}
    res = subprocess.run([*cmd, "--format", "json"], cwd=repo, capture_output=True, text=True, env=env, timeout=180)
    data = json.loads(res.stdout)
    assert [(x["code"], x["file"], x["line"]) for x in data["findings"]["new"]] == [("C001", CTRL, 15)]
    md = subprocess.run([*cmd, "--format", "markdown"], cwd=repo, capture_output=True, text=True, env=env,
                        timeout=180).stdout
    assert "New in this change" in md and f"C001` error at `{CTRL}:15`" in md
    assert os.listdir(env_tmp) == []


def test_a_xacro_finding_fixed_when_linting_a_named_model_from_the_package(repo, tmp_path):
    """The base's xacro is expanded from the base's files (also by a worker forked before the base was written)."""
    macro = repo / "agv_description/urdf/macros/components.xacro"
    edit(macro, '<axis xyz="0 1 0"/>', '<axis xyz="0 0 0"/>')
    git("commit", "-qam", "debt", cwd=repo)
    pkg = repo / "agv_description"
    res = lint("--diff-base", "HEAD", "urdf/agv.urdf.xacro", cwd=pkg, tmp=tmp_path / "tmp")
    assert "0 new, 0 fixed, 1 unchanged" in res.stdout, res.stdout + res.stderr
    edit(macro, '<axis xyz="0 0 0"/>', '<axis xyz="0 1 0"/>')
    res = lint("--diff-base", "HEAD", "urdf/agv.urdf.xacro", "--format", "json", cwd=pkg, tmp=tmp_path / "tmp")
    d = json.loads(res.stdout)["diff_base"]
    assert (len(d["new"]), d["unchanged"]) == (0, 0) and [x["code"] for x in d["fixed"]] == ["J006"], d
    assert res.returncode == 0


def test_the_json_report_with_diff_base_follows_the_schema(repo, tmp_path):
    jsonschema = pytest.importorskip("jsonschema")
    edit(repo / CTRL, "left_wheel_names: [left_wheel_joint]", "left_wheel_names: [left_wheel_jointX]")
    data = json.loads(lint("--diff-base", "HEAD", "--format", "json", cwd=repo, tmp=tmp_path / "tmp").stdout)
    schema = json.loads((ROOT / "src/urdfcheck/schemas/report.schema.json").read_text())
    jsonschema.validate(data, schema)
    assert data["diff_base"]["new"]


# --- the headline says what the gate judged: the new findings only ------------------------------------------

def _debt_and_a_new_finding(repo):
    edit(repo / CTRL, "left_wheel_names: [left_wheel_joint]", "left_wheel_names: [left_wheel_jointX]")
    git("commit", "-qam", "debt", cwd=repo)
    macro = repo / "agv_description/urdf/macros/components.xacro"
    edit(macro, '<axis xyz="0 1 0"/>', '<axis xyz="0 0 0"/>')  # J006, an error, in another file


def test_every_headline_counts_the_new_findings_the_gate_judged(repo, tmp_path):
    """The Markdown headline said "2 findings at or above warning" while the exit code judged the 1 new one."""
    _debt_and_a_new_finding(repo)
    tmp = tmp_path / "tmp"
    data = json.loads(lint("--diff-base", "HEAD", "--format", "json", cwd=repo, tmp=tmp).stdout)
    assert [x["code"] for x in data["diff_base"]["new"]] == ["J006"] and data["diff_base"]["unchanged"] >= 1
    above = sum(1 for f in data["findings"] if f["severity"] in ("error", "warning"))
    assert above >= 2
    assert data["diff_base"]["gate"] == {"fail_on": "warning", "gating": 1, "not_gating": above - 1}
    rest = f"{above - 1} unchanged since HEAD at or above it, not gating"
    res = lint("--diff-base", "HEAD", cwd=repo, tmp=tmp)
    assert res.returncode == 1, res.stderr
    assert f"Gate: 1 new finding at or above warning; {rest}." in res.stdout
    res = lint("--diff-base", "HEAD", "--format", "markdown", cwd=repo, tmp=tmp)
    assert res.returncode == 1
    head = next(ln for ln in res.stdout.splitlines() if ln.startswith(("❌", "✅", "⚠️")))
    assert head.startswith("❌ **1 new finding at or above warning** in ") and f" models ({rest}; " in head, head
    assert f"{above} findings at or above" not in res.stdout
    res = lint("--diff-base", "HEAD", "--format", "github", cwd=repo, tmp=tmp)
    assert res.returncode == 1
    assert res.stdout.splitlines()[-1].endswith(f"; 1 new finding at or above warning, {rest}"), res.stdout


def test_a_pass_with_old_debts_says_no_new_finding_and_what_did_not_gate(repo, tmp_path):
    _debt_and_a_new_finding(repo)
    git("commit", "-qam", "more debt", cwd=repo)
    tmp = tmp_path / "tmp"
    data = json.loads(lint("--diff-base", "HEAD", "--format", "json", cwd=repo, tmp=tmp).stdout)
    above = sum(1 for f in data["findings"] if f["severity"] in ("error", "warning"))
    assert data["diff_base"]["gate"] == {"fail_on": "warning", "gating": 0, "not_gating": above} and above >= 2
    res = lint("--diff-base", "HEAD", "--format", "markdown", cwd=repo, tmp=tmp)
    assert res.returncode == 0, res.stderr
    head = next(ln for ln in res.stdout.splitlines() if ln.startswith(("❌", "✅", "⚠️")))
    assert head.startswith("✅ **no new findings at or above warning** in "), head
    assert f" models ({above} unchanged since HEAD at or above it, not gating; " in head, head
    res = lint("--diff-base", "HEAD", cwd=repo, tmp=tmp)
    assert res.returncode == 0 and "Gate: no new findings at or above warning;" in res.stdout, res.stdout
    res = lint("--diff-base", "HEAD", "--fail-on", "error", cwd=repo, tmp=tmp)  # the level as given
    assert res.returncode == 0 and "Gate: no new findings at or above error;" in res.stdout, res.stdout


def test_a_workspace_headline_counts_by_each_packages_level_as_the_exit_code_does():
    """Package a fails on warnings, package b on errors only (its config): a new warning in b does not fail the run,
    and the headline does not count it; one in a does."""
    from urdfcheck.core.findings import Finding, Location, Severity
    from urdfcheck.diff.findings import FindingsDiff
    from urdfcheck.finish.result import Result
    from urdfcheck.plan.plan import Target
    from urdfcheck.report import render
    from urdfcheck.request.request import Settings

    ta = Target(Path("a/r.urdf"), settings=Settings(None, None, fail_on=Severity.WARNING))
    tb = Target(Path("b/r.urdf"), settings=Settings(None, None, fail_on=Severity.ERROR))
    for new_in, fails in (("b", False), ("a", True)):
        old = Finding("J003", Severity.WARNING, "old", Location("a/r.urdf", 3), "x", model="a/r.urdf")
        new = Finding("J004", Severity.WARNING, "new", Location(f"{new_in}/r.urdf", 4), "x", model=f"{new_in}/r.urdf")
        by = [[old] + ([new] if new_in == "a" else []), [new] if new_in == "b" else []]
        result = Result([old, new], [ta, tb], {}, by, fail_on=Severity.WARNING)
        result.changes = FindingsDiff("HEAD", [new], [], 1)
        assert result.failed() is fails
        head = next(ln for ln in render("markdown", result, fail_on=result.fail_on).splitlines()
                    if ln.startswith(("❌", "✅")))
        n = "1 new finding" if fails else "no new findings"
        assert head.startswith(("❌" if fails else "✅") + f" **{n} at or above each package's own level** in 2 models "
                               "(1 unchanged since HEAD at or above it, not gating;"), head
        assert f"Gate: {n} at or above each package's own level;" in render("text", result)
