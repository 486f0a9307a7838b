"""A file that is no robot, named by itself (the per-file pre-commit hook), stands for the robots that depend on it
(issue 38): a launch file that starts no robot gives the deployments that include it, a `.lua` or `.srdf` file the
models of its package, a YAML file the robots and deployments that read it. From a folder of many repositories the
answer is the one a plan of the whole folder gives, without planning the whole folder.
"""
from __future__ import annotations

import os
import shutil
from pathlib import Path

import pytest
from conftest import REPO, run_cli

from urdfcheck.plan import dependents
from urdfcheck.plan.plan import Planner
from urdfcheck.request.request import make_request

BRINGUP = """<launch>
  <node pkg="robot_state_publisher" exec="robot_state_publisher" name="robot_state_publisher">
    <param name="robot_description" type="str"
           value="$(command 'xacro $(find-pkg-share agv_description)/urdf/agv.urdf.xacro')"/>
  </node>
  <include file="$(find-pkg-share agv_bringup)/launch/controllers.launch.xml"/>
  <node pkg="cartographer_ros" exec="cartographer_node" name="cartographer_node"
        args="-configuration_directory $(find-pkg-share agv_bringup)/config -configuration_basename slam.lua"/>
</launch>
"""
CONTROLLERS = """<launch>
  <node pkg="controller_manager" exec="ros2_control_node" name="controller_manager">
    <param from="$(find-pkg-share agv_bringup)/config/controllers.yaml"/>
  </node>
  <node pkg="controller_manager" exec="spawner" name="s1" args="joint_state_broadcaster"/>
  <node pkg="controller_manager" exec="spawner" name="s2" args="diff_drive_controller"/>
</launch>
"""


@pytest.fixture
def mono(tmp_path) -> Path:
    """Two repositories side by side: repoA (a description package and a bringup package that deploys it with a
    controllers-only launch file it includes), repoB (another robot)."""
    a = tmp_path / "repoA"
    desc = a / "agv_description"
    shutil.copytree(REPO / "examples" / "agv", desc)
    shutil.rmtree(desc / "launch")
    (desc / "urdfcheck.yaml").unlink()
    (desc / "config" / "carto.lua").write_text("options = { map_frame = 'map', tracking_frame = 'base_link' }\n")
    (desc / "config" / "agv.srdf").write_text('<robot name="agv"><group name="base"><joint name="left_wheel_joint"/>'
                                              '</group></robot>\n')
    bringup = a / "agv_bringup"
    (bringup / "launch").mkdir(parents=True)
    (bringup / "config").mkdir()
    (bringup / "package.xml").write_text((desc / "package.xml").read_text().replace("agv_description",
                                                                                    "agv_bringup"))
    shutil.copy(desc / "config" / "agv_controllers.yaml", bringup / "config" / "controllers.yaml")
    (bringup / "launch" / "bringup.launch.xml").write_text(BRINGUP)
    (bringup / "launch" / "controllers.launch.xml").write_text(CONTROLLERS)
    (bringup / "config" / "slam.lua").write_text('options = {\n  map_frame = "map",\n  tracking_frame = "base_link",\n'
                                                  '  published_frame = "odom",\n  odom_frame = "odom",\n'
                                                  '  provide_odom_frame = false,\n}\nreturn options\n')
    other = tmp_path / "repoB" / "other_bringup"  # another robot's file of the same name: not a reader
    (other / "launch").mkdir(parents=True)
    (other / "package.xml").write_text((desc / "package.xml").read_text().replace("agv_description",
                                                                                  "other_bringup"))
    (other / "launch" / "slam.launch.xml").write_text(
        '<launch><node pkg="cartographer_ros" exec="cartographer_node" name="c" args="-configuration_directory '
        '$(find-pkg-share other_bringup)/config -configuration_basename slam.lua"/></launch>\n')
    # a launch file of the same name as repoA's, included by name in its own package (a generic name names that
    # package's file)
    (other / "launch" / "bringup.launch.xml").write_text(
        '<launch><node pkg="joy" exec="joy_node" name="joy"/></launch>\n')
    (other / "launch" / "all.launch.xml").write_text(
        '<launch><include file="$(find-pkg-share other_bringup)/launch/bringup.launch.xml"/></launch>\n')
    shutil.copytree(REPO / "examples" / "broken" / "joint_limits", tmp_path / "repoB" / "joint_limits")
    # repoC: a robot whose model (through an include) loads repoA's shared controller file in its Gazebo plugin; its
    # launch file names neither that file nor its package (turtlebot4 reading create3's control.yaml)
    bot = tmp_path / "repoC" / "bot_description"
    (bot / "urdf").mkdir(parents=True)
    (bot / "launch").mkdir()
    (bot / "package.xml").write_text((desc / "package.xml").read_text().replace("agv_description", "bot_description"))
    (bringup / "config" / "shared_controllers.yaml").write_text(
        "controller_manager:\n  ros__parameters:\n    update_rate: 50\n")
    (bot / "urdf" / "bot.urdf.xacro").write_text(
        '<robot name="bot" xmlns:xacro="http://www.ros.org/wiki/xacro">\n  <link name="base_link"/>\n'
        '  <xacro:include filename="$(find bot_description)/urdf/plugin.xacro"/>\n</robot>\n')
    (bot / "urdf" / "plugin.xacro").write_text(
        '<robot xmlns:xacro="http://www.ros.org/wiki/xacro">\n  <gazebo>\n'
        '    <plugin filename="libgz_ros2_control-system.so" name="gz_ros2_control::GazeboSimROS2ControlPlugin">\n'
        '      <parameters>$(find agv_bringup)/config/shared_controllers.yaml</parameters>\n'
        '    </plugin>\n  </gazebo>\n</robot>\n')
    (bot / "launch" / "bot.launch.xml").write_text(
        '<launch>\n  <node pkg="robot_state_publisher" exec="robot_state_publisher" name="robot_state_publisher">\n'
        '    <param name="robot_description" type="str"\n'
        '           value="$(command \'xacro $(find-pkg-share bot_description)/urdf/bot.urdf.xacro\')"/>\n'
        '  </node>\n</launch>\n')
    return tmp_path


def listed(out: str, prefix: str = "") -> list[str]:
    """The target lines of `--list`, with `prefix` taken off the paths."""
    lines = out.split("\n\n", 1)[0].splitlines()
    return sorted(ln.replace(prefix, "") for ln in lines if ln and not ln.startswith(("ROS distribution", "info")))


def test_a_launch_file_that_starts_no_robot_gives_the_deployments_including_it(mono):
    code, out, err = run_cli(["lint", "--no-cache", "--list", "repoA/agv_bringup/launch/controllers.launch.xml"],
                             cwd=mono)
    assert code == 0, err
    assert listed(out) == ["repoA/agv_description/urdf/agv.urdf.xacro [repoA/agv_bringup/launch/bringup.launch.xml]"]
    code, out, err = run_cli(["lint", "--no-cache", "repoA/agv_bringup/launch/controllers.launch.xml"], cwd=mono)
    assert code == 0, out + err


@pytest.mark.parametrize("name", ["carto.lua", "agv.srdf"])
def test_lua_and_srdf_files_stand_for_their_packages_robots(mono, name):
    code, out, err = run_cli(["lint", "--no-cache", "--list", f"repoA/agv_description/config/{name}"], cwd=mono)
    assert code == 0, err
    assert listed(out) == ["repoA/agv_description/urdf/agv.urdf",
                           "repoA/agv_description/urdf/agv.urdf.xacro [repoA/agv_bringup/launch/bringup.launch.xml]"]


def test_a_lua_file_stands_for_the_deployments_whose_launch_files_name_it(mono):
    code, out, err = run_cli(["lint", "--no-cache", "--list", "repoA/agv_bringup/config/slam.lua"], cwd=mono)
    assert code == 0, err
    assert listed(out) == ["repoA/agv_description/urdf/agv.urdf.xacro [repoA/agv_bringup/launch/bringup.launch.xml]"]


def test_a_lua_file_nothing_reads_is_an_info_line(tmp_path):
    (tmp_path / "cfg.lua").write_text("options = {}\n")
    code, out, err = run_cli(["lint", "--no-cache", "cfg.lua"], cwd=tmp_path)
    assert code == 0 and "a .lua file that no robot or deployment of its workspace reads" in err, out + err


@pytest.mark.parametrize("rel", ["repoA/agv_bringup/config/controllers.yaml", "repoA/agv_bringup/config/slam.lua",
                                 "repoA/agv_bringup/launch/controllers.launch.xml",
                                 "repoA/agv_description/config/agv_controllers.yaml"])
def test_from_the_folder_of_repositories_as_from_the_repository(mono, rel):
    code, top, err = run_cli(["lint", "--no-cache", "--list", rel], cwd=mono)
    assert code == 0, err
    code, own, err = run_cli(["lint", "--no-cache", "--list", rel.split("/", 1)[1]], cwd=mono / "repoA")
    assert code == 0, err
    assert listed(top, "repoA/") == listed(own) and listed(own)


def _keys(targets) -> set:
    return {(os.path.realpath(t.path), t.variant, tuple(sorted(t.args.items())), tuple(sorted(t.packages.items())))
            for t in targets}


def _both(monkeypatch, here: Path, files: list[str]):
    """What the per-file plan gives for each file, and what filtering a plan of the whole folder gives."""
    monkeypatch.chdir(here)
    fast, whole = [], []
    slow_planner = None
    for rel in files:
        request = make_request([rel], use_config=False)
        planner = Planner(request, str(here))
        fast.append(_keys(planner.path_targets(rel)))
        if slow_planner is None:
            slow_planner = Planner(request, str(here))  # one whole plan of the folder, shared
        with monkeypatch.context() as m:
            m.setattr(dependents, "_candidates", lambda p, ws, *a: p.workspace_targets(ws))
            whole.append(_keys(slow_planner.path_targets(rel)))
    return fast, whole


def test_the_same_targets_as_a_plan_of_the_whole_folder(mono, monkeypatch):
    files = ["repoA/agv_bringup/config/controllers.yaml", "repoA/agv_description/config/agv_controllers.yaml",
             "repoA/agv_description/config/carto.lua", "repoA/agv_bringup/launch/controllers.launch.xml",
             "repoA/agv_bringup/config/slam.lua", "repoA/agv_description/config/agv.srdf",
             "repoA/agv_bringup/config/shared_controllers.yaml"]
    fast, whole = _both(monkeypatch, mono, files)
    assert fast == whole and all(fast), [(sorted(a - b), sorted(b - a)) for a, b in zip(fast, whole) if a != b]


def test_the_same_targets_as_a_plan_of_the_whole_corpus(corpus, monkeypatch):
    repo = corpus / "linorobot+linorobot2"
    if not repo.is_dir():
        pytest.skip("linorobot2 is not in the corpus")
    files = [str(p.relative_to(corpus)) for p in sorted(repo.glob("*/config/*.yaml"))[:6]]
    fast, whole = _both(monkeypatch, corpus, files)
    assert fast == whole and any(fast), [(sorted(a - b), sorted(b - a)) for a, b in zip(fast, whole) if a != b]


def test_a_guarded_run_plans_only_the_launch_files_that_can_reach_the_file(mono, monkeypatch):
    """As the command line runs it (the door guarding the checkout around the file): a sibling repository's launch
    files that name nothing of the file are not planned. Before, the name search could not read them (outside the
    run's roots until the plan made the folder a root) and kept each as "may name it": from the 22-repository
    corpus, 77 launch files planned for one SRDF macro. Nor one that includes a file of the same name in its own
    package (repoB's all.launch.xml includes its own bringup.launch.xml)."""
    from urdfcheck.core import door
    from urdfcheck.core.checkout import run_roots

    monkeypatch.chdir(mono)
    rel = "repoA/agv_bringup/launch/controllers.launch.xml"
    planned = []
    real_find = Planner.find

    def find(self, root, settings, files=None):
        planned.extend(os.path.relpath(f, mono) for f in files or ())
        return real_find(self, root, settings, files)

    monkeypatch.setattr(Planner, "find", find)
    with door.guarded(run_roots([rel], cwd=str(mono))):
        got = Planner(make_request([rel], use_config=False), str(mono)).path_targets(rel)
    assert [os.path.relpath(str(t.path), mono) for t in got] == ["repoA/agv_description/urdf/agv.urdf.xacro"]
    assert not [f for f in planned if f.startswith("repoB")], planned


def test_a_macro_file_of_the_examples_gives_their_robots_from_the_repository_and_from_above_it():
    """The per-file hook on a macro file of examples/agv (whose examples/ folder holds COLCON_IGNORE): the robots
    including it, the same from this repository's root and from the folder above it. Before, the walk of the
    repository skipped examples/ and said no robot includes the file."""
    rel = "examples/agv/urdf/macros/components.xacro"
    code, own, err = run_cli(["lint", "--no-cache", "--list", rel], cwd=REPO)
    assert code == 0, err
    code, top, err = run_cli(["lint", "--no-cache", "--list", f"{REPO.name}/{rel}"], cwd=REPO.parent)
    assert code == 0, err
    assert listed(own) == ["2 target(s)", "examples/agv/urdf/agv.urdf.xacro [camera] use_camera:=true  (config "
                           "examples/agv/urdfcheck.yaml)",
                           "examples/agv/urdf/agv.urdf.xacro [no_camera] use_camera:=false  (config "
                           "examples/agv/urdfcheck.yaml)"]
    assert listed(top, f"{REPO.name}/") == listed(own)


def test_a_macro_file_of_a_corpus_repository_gives_the_same_robots_from_the_corpus_root(corpus):
    repo = corpus / "linorobot+linorobot2"
    if not repo.is_dir():
        pytest.skip("linorobot2 is not in the corpus")
    rel = "linorobot2_description/urdf/mech/wheel.urdf.xacro"
    code, own, err = run_cli(["lint", "--no-cache", "--list", rel], cwd=repo)
    assert code == 0, err
    code, top, err = run_cli(["lint", "--no-cache", "--list", f"{repo.name}/{rel}"], cwd=corpus)
    assert code == 0, err
    assert listed(top, f"{repo.name}/") == listed(own) and listed(own)
