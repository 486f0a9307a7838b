"""`lint --config-from REV`: the runner names the base revision's config; the pull request's cannot lower the gate
(issue 36)."""
from __future__ import annotations

import os
import shutil
from pathlib import Path

import pytest
from gitrepo import edit, git, lint  # noqa: F401

ROOT = Path(__file__).resolve().parents[2]
AGV = ROOT / "examples" / "agv"
SRC = str(ROOT / "src")
CTRL = "agv_description/config/agv_controllers.yaml"

pytestmark = pytest.mark.skipif(shutil.which("git") is None, reason="git not installed")


@pytest.fixture
def repo(tmp_path):
    repo = tmp_path / "repo"
    shutil.copytree(AGV, repo / "agv_description")
    git("init", "-q", cwd=repo)
    git("add", "-A", cwd=repo)
    git("commit", "-qm", "base", cwd=repo)
    (tmp_path / "tmp").mkdir()
    return repo


def break_controller(repo: Path) -> None:
    edit(repo / CTRL, "left_wheel_names: [left_wheel_joint]", "left_wheel_names: [left_wheel_jointX]")


def test_the_base_config_is_used_not_the_pull_requests(repo, tmp_path):
    break_controller(repo)
    with open(repo / "agv_description/urdfcheck.yaml", "a") as f:
        f.write("ignore: [C001]\nseverity: {C001: info}\n")
    for cwd in (repo, repo / "agv_description"):
        res = lint("--config-from", "HEAD", cwd=cwd, tmp=tmp_path / "tmp")
        assert res.returncode == 1, res.stdout + res.stderr
        assert "C001" in res.stdout
        assert "using HEAD:agv_description/urdfcheck.yaml (trusted)" in res.stderr
        assert "differs from it" in res.stderr
        assert "urdfcheck-cfg-" not in res.stdout + res.stderr and str(tmp_path) not in res.stdout + res.stderr
    assert os.listdir(tmp_path / "tmp") == []


def test_the_same_config_is_said_to_be_the_same(repo, tmp_path):
    res = lint("--config-from", "HEAD", cwd=repo / "agv_description", tmp=tmp_path / "tmp")
    assert res.returncode == 0, res.stdout + res.stderr
    assert "is the same" in res.stderr


def test_pyproject_table_paths_name_the_working_tree(tmp_path):
    repo = tmp_path / "repo"
    shutil.copytree(AGV, repo / "agv_description")
    (repo / "agv_description/urdfcheck.yaml").unlink()
    (repo / "agv_description/pyproject.toml").write_text(
        '[tool.urdfcheck]\nmodels = [{path = "urdf/agv.urdf", controllers = ["config/agv_controllers.yaml"]}]\n')
    git("init", "-q", cwd=repo)
    git("add", "-A", cwd=repo)
    git("commit", "-qm", "base", cwd=repo)
    (tmp_path / "tmp").mkdir()
    (repo / "agv_description/pyproject.toml").unlink()  # the pull request drops the config ...
    break_controller(repo)                                 # ... and breaks the controller file it named
    res = lint("--config-from", "HEAD", cwd=repo, tmp=tmp_path / "tmp")
    assert res.returncode == 1 and "C001" in res.stdout, res.stdout + res.stderr
    assert "HEAD:agv_description/pyproject.toml" in res.stderr


def test_with_diff_base_the_base_is_linted_with_its_own_files(repo, tmp_path):
    break_controller(repo)
    git("commit", "-qam", "debt", cwd=repo)
    res = lint("--config-from", "HEAD", "--diff-base", "HEAD", cwd=repo / "agv_description", tmp=tmp_path / "tmp")
    assert "0 new, 0 fixed, 1 unchanged" in res.stdout, res.stdout + res.stderr
    assert res.returncode == 0


def test_a_config_the_runner_names_wins(repo, tmp_path):
    """--config FILE or --no-config typed beside --config-from (an Action's default and the workflow's flag)."""
    break_controller(repo)
    with open(repo / "agv_description/urdfcheck.yaml", "a") as f:
        f.write("ignore: [C001]\n")
    res = lint("--config-from", "HEAD", "--no-config", cwd=repo, tmp=tmp_path / "tmp")
    assert res.returncode == 1 and "--config-from HEAD is not used: --no-config is given" in res.stderr
    assert lint("--config-from", "nope", cwd=repo, tmp=tmp_path / "tmp").returncode == 2


def test_messages_name_no_temporary_or_absolute_path(repo, tmp_path):
    """The base config names a model the pull request deleted: a usage error naming REV:path and the model's
    path relative to the working directory (also with --root)."""
    (repo / "agv_description/urdf/agv.urdf").unlink()
    for extra in ((), ("--root", str(repo))):
        res = lint("--config-from", "HEAD", *extra, cwd=repo / "agv_description", tmp=tmp_path / "tmp")
        assert res.returncode == 2, res.stdout + res.stderr
        assert "HEAD:agv_description/urdfcheck.yaml" in res.stderr and "urdf/agv.urdf" in res.stderr
        assert str(tmp_path) not in res.stderr and "urdfcheck-cfg-" not in res.stderr
