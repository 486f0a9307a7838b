"""This repository cloned into a colcon workspace (as the README suggests for ament_cmake_urdfcheck) does not break
`colcon build` (issue 38): the example packages under examples/ (no CMakeLists.txt, a catkin one) are behind a
COLCON_IGNORE; ament_cmake_urdfcheck stays a package. Checked with Debian's colcon (python3-colcon-*), skipped
without it. A path the user names below the marker is still linted.
"""
from __future__ import annotations

import os
import shutil
import subprocess
from pathlib import Path

import pytest
from conftest import run_cli

ROOT = Path(__file__).resolve().parents[2]
COLCON = shutil.which("colcon")

DESCRIPTION_XML = """<?xml version="1.0"?>
<package format="3">
  <name>my_robot_description</name>
  <version>0.0.1</version>
  <description>a robot</description>
  <maintainer email="me@example.com">me</maintainer>
  <license>MIT</license>
  <export><build_type>cmake</build_type></export>
</package>
"""
DESCRIPTION_CMAKE = """cmake_minimum_required(VERSION 3.5)
project(my_robot_description NONE)
install(DIRECTORY urdf DESTINATION share/${PROJECT_NAME})
"""


def colcon(ws: Path, *args: str) -> subprocess.CompletedProcess:
    env = {k: v for k, v in os.environ.items() if not k.startswith("COLCON_")}
    env["COLCON_HOME"] = str(ws / ".colcon_home")  # no user defaults, no writes outside the workspace
    return subprocess.run([COLCON, "--log-base", str(ws / "log"), *args], cwd=ws, env=env, capture_output=True,
                          text=True, timeout=300)


@pytest.fixture
def workspace(tmp_path) -> Path:
    ws = tmp_path / "ws"
    (ws / "src").mkdir(parents=True)
    (ws / "src" / "urdfcheck").symlink_to(ROOT, target_is_directory=True)  # the clone
    pkg = ws / "src" / "my_robot_description"
    (pkg / "urdf").mkdir(parents=True)
    (pkg / "package.xml").write_text(DESCRIPTION_XML)
    (pkg / "CMakeLists.txt").write_text(DESCRIPTION_CMAKE)
    shutil.copy(ROOT / "examples" / "agv" / "urdf" / "agv.urdf", pkg / "urdf" / "robot.urdf")
    return ws


def test_examples_carry_a_colcon_ignore():
    assert (ROOT / "examples" / "COLCON_IGNORE").is_file()
    assert not (ROOT / "ament_cmake_urdfcheck" / "COLCON_IGNORE").exists()


@pytest.mark.skipif(COLCON is None, reason="colcon not installed (apt-get install python3-colcon-ros ...)")
def test_colcon_sees_only_the_real_packages(workspace):
    res = colcon(workspace, "list", "--names-only")
    assert res.returncode == 0, res.stderr
    assert sorted(res.stdout.split()) == ["ament_cmake_urdfcheck", "my_robot_description"]


@pytest.mark.skipif(COLCON is None or shutil.which("cmake") is None, reason="colcon or cmake not installed")
def test_colcon_build_of_the_workspace(workspace):
    # ament_cmake_urdfcheck needs ament_cmake (a ROS installation): built when one is sourced, else left out
    skip = [] if os.environ.get("AMENT_PREFIX_PATH") else ["--packages-skip", "ament_cmake_urdfcheck"]
    res = colcon(workspace, "build", "--build-base", str(workspace / "build"), "--install-base",
                 str(workspace / "install"), "--event-handlers", "console_direct-", *skip)
    assert res.returncode == 0, res.stdout + res.stderr
    assert (workspace / "install" / "my_robot_description" / "share" / "my_robot_description" / "urdf"
            / "robot.urdf").is_file()
    assert not (ROOT / "build").exists() and not (ROOT / "install").exists()


def test_a_named_path_below_the_marker_is_still_linted():
    """COLCON_IGNORE keeps examples/ out of a workspace-wide run; `urdfcheck lint examples/agv` names the folder."""
    code, out, err = run_cli(["lint", "--no-cache", "--list", "examples/agv"], cwd=ROOT)
    assert code == 0, err
    assert "examples/agv/urdf/agv.urdf.xacro" in out
    code, out, err = run_cli(["lint", "--no-cache", "--no-config", "examples/broken/joint_limits"], cwd=ROOT)
    assert code == 1 and "J003" in out, err
