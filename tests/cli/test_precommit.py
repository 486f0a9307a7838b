"""`.pre-commit-hooks.yaml` with the real `pre-commit` tool against throw-away git repositories.

`pre-commit try-repo PATH` clones PATH at HEAD; for a dirty tree it commits tracked changes (`git add -u`)
into a shadow clone, so untracked files (new modules, the hooks file itself) would be missing. The tests
therefore snapshot the working tree (tracked + untracked, minus ignored files) into a temporary git repo.
pre-commit then builds a virtualenv and pip-installs that snapshot: once for try-repo (which always uses a
fresh store) and once for the configured project (~20-30 s each, most of it pip).
"""
import os
import shutil
import subprocess
import sys

import pytest
import yaml
from conftest import REPO
from samples import BAD, GOOD

pytestmark = pytest.mark.slow

GIT_ENV = {"GIT_AUTHOR_NAME": "t", "GIT_AUTHOR_EMAIL": "t@example.com", "GIT_COMMITTER_NAME": "t",
           "GIT_COMMITTER_EMAIL": "t@example.com", "GIT_CONFIG_NOSYSTEM": "1"}


def test_hooks_file_is_well_formed():
    hooks = {h["id"]: h for h in yaml.safe_load((REPO / ".pre-commit-hooks.yaml").read_text())}
    assert set(hooks) == {"urdfcheck", "urdfcheck-package"}
    one = hooks["urdfcheck"]
    assert one["entry"] == "urdfcheck lint" and one["language"] == "python"
    assert one.get("pass_filenames", True) is True
    pkg = hooks["urdfcheck-package"]
    assert pkg["pass_filenames"] is False and pkg["entry"] == "urdfcheck lint"
    import re

    # every file kind that changes a contract: models, parameters, cartographer's .lua, MoveIt's SRDF, launch files
    for name in ("a.urdf", "urdf/b.urdf.xacro", "config/controllers.yaml", "config/carto.lua", "config/r.srdf",
                 "launch/bringup.launch.py", "launch/bringup_launch.py", "launch/b.launch.xml",
                 "launch/b.launch.yaml", "launch/b.launch", "config/moveit.srdf.xacro"):
        assert re.search(one["files"], name) and not re.search(one["exclude"], name), name
        assert re.search(pkg["files"], name), name
    for name in ("setup.py", "README.md", "scripts/node.py", "meshes/m.stl"):
        assert not re.search(one["files"], name), name
    for name in (".pre-commit-config.yaml", ".github/workflows/ci.yml", "sub/.gitlab-ci.yml"):
        assert re.search(one["exclude"], name)
    assert not re.search(one["files"], "a.urdf.bak")
    for name in ("urdf/a.xacro", "config/c.yaml", "meshes/m.STL", "launch/x.launch.py", "pyproject.toml"):
        assert re.search(pkg["files"], name), name


def git(*args, cwd, env):
    return subprocess.run(["git", *args], cwd=cwd, env=env, check=True, capture_output=True, text=True)


@pytest.fixture(scope="module")
def env(tmp_path_factory):
    if shutil.which("git") is None:
        pytest.skip("git not installed")
    try:
        import pre_commit  # noqa: F401
    except ImportError:
        pytest.skip("pre-commit not installed")
    base = tmp_path_factory.mktemp("precommit")
    environ = dict(os.environ, PRE_COMMIT_HOME=str(base / "home"), **GIT_ENV)
    environ.pop("PYTHONPATH", None)  # the hook must run the installed urdfcheck, not this checkout
    # snapshot of the working tree, committed
    snap = base / "urdfcheck"
    snap.mkdir()
    files = subprocess.run(["git", "ls-files", "-z", "--cached", "--others", "--exclude-standard"], cwd=REPO,
                           check=True, capture_output=True).stdout.decode().split("\0")
    for rel in filter(None, files):
        src = REPO / rel
        if src.is_file():
            dst = snap / rel
            dst.parent.mkdir(parents=True, exist_ok=True)
            shutil.copy2(src, dst)
    git("init", "-q", cwd=snap, env=environ)
    git("add", "-A", cwd=snap, env=environ)
    git("commit", "-q", "-m", "snapshot", cwd=snap, env=environ)
    rev = git("rev-parse", "HEAD", cwd=snap, env=environ).stdout.strip()
    yield {"base": base, "snap": snap, "rev": rev, "environ": environ}
    shutil.rmtree(base, ignore_errors=True)  # the hook virtualenvs are large


def project(env, name):
    proj = env["base"] / name
    proj.mkdir()
    git("init", "-q", cwd=proj, env=env["environ"])
    (proj / "bad.urdf").write_text(BAD)
    (proj / "good.urdf").write_text(GOOD)
    return proj


def pre_commit(*args, cwd, env):
    return subprocess.run([sys.executable, "-m", "pre_commit", *args], cwd=cwd, env=env["environ"],
                          capture_output=True, text=True, timeout=600)


def test_try_repo_bad_file_fails(env):
    """The documented way to try the hooks. try-repo installs into a fresh store every time (~25 s)."""
    proj = project(env, "try")
    bad = pre_commit("try-repo", str(env["snap"]), "urdfcheck", "--files", "bad.urdf", cwd=proj, env=env)
    assert bad.returncode == 1, bad.stdout + bad.stderr
    assert "bad.urdf:5  U002" in bad.stdout and "Failed" in bad.stdout


@pytest.fixture(scope="module")
def configured(env):
    """A project using both hooks from the snapshot; the hook environment is built once and reused."""
    proj = project(env, "configured")
    (proj / ".pre-commit-config.yaml").write_text(
        f"repos:\n  - repo: {env['snap']}\n    rev: {env['rev']}\n    hooks:\n"
        "      - id: urdfcheck\n      - id: urdfcheck-package\n        stages: [manual]\n")
    r = pre_commit("install-hooks", cwd=proj, env=env)
    assert r.returncode == 0, r.stdout + r.stderr
    return proj


def test_run_good_passes_bad_fails(env, configured):
    good = pre_commit("run", "urdfcheck", "--files", "good.urdf", cwd=configured, env=env)
    assert good.returncode == 0 and "Passed" in good.stdout, good.stdout + good.stderr
    bad = pre_commit("run", "urdfcheck", "--files", "bad.urdf", "good.urdf", cwd=configured, env=env)
    assert bad.returncode == 1, bad.stdout + bad.stderr
    assert "bad.urdf:5  U002" in bad.stdout and "good.urdf:" not in bad.stdout
    skipped = pre_commit("run", "urdfcheck", "--files", ".pre-commit-config.yaml", cwd=configured, env=env)
    assert skipped.returncode == 0 and "no files to check" in skipped.stdout


def test_installed_hook_blocks_a_bad_commit(env, configured):
    e = env["environ"]
    r = pre_commit("install", cwd=configured, env=env)
    assert r.returncode == 0, r.stderr
    git("add", ".pre-commit-config.yaml", "good.urdf", cwd=configured, env=e)
    ok = subprocess.run(["git", "commit", "-m", "good"], cwd=configured, env=e, capture_output=True, text=True)
    assert ok.returncode == 0, ok.stdout + ok.stderr
    git("add", "bad.urdf", cwd=configured, env=e)
    bad = subprocess.run(["git", "commit", "-m", "bad"], cwd=configured, env=e, capture_output=True, text=True)
    assert bad.returncode != 0
    assert "U002" in bad.stdout + bad.stderr
    assert git("log", "--format=%s", cwd=configured, env=e).stdout.split() == ["good"]
    git("reset", "-q", "bad.urdf", cwd=configured, env=e)


def test_package_hook_lints_what_the_config_declares_and_what_it_does_not(env, configured):
    # issue 36: a config found in the checkout adds to discovery; a clean model it declares hides no robot
    e = env["environ"]
    (configured / "urdf").mkdir()
    (configured / "urdf" / "arm.urdf").write_text(BAD)
    (configured / "urdfcheck.yaml").write_text("models:\n  - path: good.urdf\n")
    run = ("run", "urdfcheck-package", "--hook-stage", "manual", "--all-files")
    git("add", "-A", cwd=configured, env=e)
    r = pre_commit(*run, cwd=configured, env=env)
    assert r.returncode == 1, r.stdout + r.stderr
    assert "urdf/arm.urdf:5  U002" in r.stdout and "bad.urdf:5  U002" in r.stdout
    (configured / "urdfcheck.yaml").write_text("models:\n  - path: good.urdf\n  - path: urdf/arm.urdf\n")
    git("add", "-A", cwd=configured, env=e)
    r = pre_commit(*run, cwd=configured, env=env)
    assert r.returncode == 1, r.stdout + r.stderr
    assert "urdf/arm.urdf:5  U002" in r.stdout and "bad.urdf:5  U002" in r.stdout


CONTROLLERS_LAUNCH = """<launch>
  <node pkg="controller_manager" exec="ros2_control_node" name="controller_manager">
    <param from="$(find-pkg-share agv_description)/config/agv_controllers.yaml"/>
  </node>
  <node pkg="controller_manager" exec="spawner" name="s" args="diff_drive_controller"/>
</launch>
"""


def test_a_commit_of_only_a_launch_file_is_checked(env, configured):
    """Not "(no files to check) Skipped": the launch file's robots are linted (issue 38)."""
    e = env["environ"]
    pkg = configured / "agv_description"
    shutil.copytree(REPO / "examples" / "agv", pkg, ignore=shutil.ignore_patterns("urdfcheck.yaml"))
    git("add", "-A", cwd=configured, env=e)
    subprocess.run(["git", "commit", "-qm", "agv", "--no-verify"], cwd=configured, env=e, check=True)
    (pkg / "launch" / "controllers.launch.xml").write_text(CONTROLLERS_LAUNCH)  # starts no robot itself
    launch = pkg / "launch" / "agv.launch.xml"
    launch.write_text(launch.read_text().replace("</launch>", "  <!-- a comment -->\n</launch>"))
    git("add", "agv_description/launch", cwd=configured, env=e)
    r = pre_commit("run", "urdfcheck", cwd=configured, env=env)  # the staged files, as on a commit
    assert "no files to check" not in r.stdout, r.stdout
    assert r.returncode == 0 and "Passed" in r.stdout, r.stdout + r.stderr
    git("reset", "-q", "--hard", "HEAD", cwd=configured, env=e)
