"""C025 (issue 37): a launch file that runs xacro on, or loads, a model file of the checkout that does not exist is a
broken deployment at the launch file's line, not a deployment "not understood" (C021, info). Its severity follows
the evidence rule: a launch file run with its defaults is evidence; a launch-argument value other than the default
is a guess (info, naming it)."""
from __future__ import annotations

from pathlib import Path

from conftest import lint_json, run_cli

PACKAGE = """<?xml version="1.0"?>
<package format="3"><name>{name}</name><version>0.0.0</version><description>x</description>
<maintainer email="a@b.c">a</maintainer><license>MIT</license><buildtool_depend>ament_cmake</buildtool_depend>
</package>
"""
ROBOT = """<?xml version="1.0"?>
<robot name="r" xmlns:xacro="http://www.ros.org/wiki/xacro">
  <link name="base_link"/>
</robot>
"""


def _package(root: Path, launch: str, name: str = "my_robot", launch_name: str = "display.launch") -> Path:
    pkg = root / name
    (pkg / "urdf").mkdir(parents=True)
    (pkg / "launch").mkdir()
    (pkg / "package.xml").write_text(PACKAGE.format(name=name))
    (pkg / "urdf" / "robot.urdf.xacro").write_text(ROBOT)
    (pkg / "launch" / launch_name).write_text(launch)
    return pkg


ROS1 = """<launch>
  <param name="robot_description" command="$(find xacro)/xacro $(find {pkg})/urdf/{file}"/>
  <node pkg="robot_state_publisher" type="robot_state_publisher" name="rsp"/>
</launch>
"""


def _by_code(report, code):
    return [f for f in report["findings"] if f["code"] == code]


def test_a_misspelt_model_path_is_an_error_at_the_launch_line(tmp_path):
    _package(tmp_path, ROS1.format(pkg="my_robot", file="robott.urdf.xacro"))
    code, report = lint_json([], cwd=tmp_path)
    (f,) = _by_code(report, "C025")
    assert f["severity"] == "error" and code == 1
    assert f["location"]["file"] == "my_robot/launch/display.launch" and f["location"]["line"] == 2
    assert "my_robot/urdf/robott.urdf.xacro, which does not exist" in f["message"]
    assert "(did you mean my_robot/urdf/robot.urdf.xacro?)" in f["message"]
    assert [(s["how"], s["evidence"]) for s in f["evidence"]] == [("launched", True)]
    assert not _by_code(report, "C021")


def test_the_launch_file_named_on_the_command_line_gives_the_error(tmp_path):
    _package(tmp_path, ROS1.format(pkg="my_robot", file="robott.urdf.xacro"))
    code, out, _ = run_cli(["lint", "--no-config", "my_robot/launch/display.launch"], cwd=tmp_path)
    assert code == 1
    assert "my_robot/launch/display.launch:2  C025  error" in out, out


def test_a_python_launch_file_with_a_literal_path(tmp_path):
    launch = """from launch import LaunchDescription
from launch.substitutions import Command, PathJoinSubstitution
from launch_ros.actions import Node
from launch_ros.substitutions import FindPackageShare


def generate_launch_description():
    xacro_file = PathJoinSubstitution([FindPackageShare('my_robot'), 'urdf', 'old_robot.urdf.xacro'])
    return LaunchDescription([
        Node(package='robot_state_publisher', executable='robot_state_publisher',
             parameters=[{'robot_description': Command(['xacro ', xacro_file])}]),
    ])
"""
    _package(tmp_path, launch, launch_name="display.launch.py")
    code, report = lint_json([], cwd=tmp_path)
    (f,) = _by_code(report, "C025")
    assert f["severity"] == "error" and code == 1
    assert f["location"]["file"] == "my_robot/launch/display.launch.py"


def test_a_file_that_exists_gives_nothing(tmp_path):
    _package(tmp_path, ROS1.format(pkg="my_robot", file="robot.urdf.xacro"))
    code, report = lint_json([], cwd=tmp_path)
    assert not _by_code(report, "C025") and not _by_code(report, "C021") and code == 0


def test_a_package_outside_the_checkout_stays_an_info(tmp_path):
    # the workspace that builds the checkout provides the package: its files are not known here
    _package(tmp_path, ROS1.format(pkg="other_description", file="robot.urdf.xacro"))
    code, report = lint_json([], cwd=tmp_path)
    assert not _by_code(report, "C025") and code == 0
    (f,) = _by_code(report, "C021")
    assert f["severity"] == "info"


def test_a_urdf_the_package_builds_from_its_xacro_is_not_missing(tmp_path):
    # CMake's xacro macros write robot.urdf into the build and install spaces: the source tree never holds it
    pkg = _package(tmp_path, ROS1.format(pkg="my_robot", file="robot.urdf").replace(
        'command="$(find xacro)/xacro ', 'textfile="'))
    (pkg / "CMakeLists.txt").write_text("find_package(xacro REQUIRED)\nxacro_add_files(urdf/robot.urdf.xacro)\n")
    code, report = lint_json([], cwd=tmp_path)
    assert not _by_code(report, "C025") and code == 0


def test_a_launch_argument_value_other_than_the_default_is_an_info(tmp_path):
    launch = """<launch>
  <arg name="model" default="robot">
    <choice value="robot"/>
    <choice value="robot_v2"/>
  </arg>
  <param name="robot_description" command="$(find xacro)/xacro $(find my_robot)/urdf/$(arg model).urdf.xacro"/>
  <node pkg="robot_state_publisher" type="robot_state_publisher" name="rsp"/>
</launch>
"""
    _package(tmp_path, launch, launch_name="display.launch.xml")
    code, report = lint_json([], cwd=tmp_path)
    (f,) = _by_code(report, "C025")
    assert f["severity"] == "info" and "robot_v2.urdf.xacro" in f["message"]
    assert [s["how"] for s in f["evidence"] if not s["evidence"]] == ["choice"]
    assert code == 0


def test_a_missing_textfile_is_an_error_too(tmp_path):
    # ROS 1 `<param textfile=...>`: robot_description read as is
    _package(tmp_path, ROS1.format(pkg="my_robot", file="robot_v1.urdf").replace(
        'command="$(find xacro)/xacro ', 'textfile="'))
    code, report = lint_json([], cwd=tmp_path)
    (f,) = _by_code(report, "C025")
    assert f["severity"] == "error" and code == 1 and "robot_v1.urdf, which does not exist" in f["message"]


def test_a_file_of_that_name_elsewhere_in_the_package_may_be_installed_there(tmp_path):
    # install(FILES models/robot.urdf DESTINATION share/my_robot/urdf), or setup.py's data_files
    pkg = _package(tmp_path, ROS1.format(pkg="my_robot", file="robot.urdf").replace(
        'command="$(find xacro)/xacro ', 'textfile="'))
    (pkg / "models").mkdir()
    (pkg / "models" / "robot.urdf").write_text('<robot name="r"><link name="base_link"/></robot>\n')
    code, report = lint_json([], cwd=tmp_path)
    assert not _by_code(report, "C025")


DISPLAY = """from launch import LaunchDescription
from launch.actions import DeclareLaunchArgument
from launch.substitutions import Command, LaunchConfiguration, PathJoinSubstitution
from launch_ros.actions import Node
from launch_ros.substitutions import FindPackageShare


def generate_launch_description():
    default = PathJoinSubstitution([FindPackageShare('my_robot'), 'urdf', 'old_robot.urdf.xacro'])
    return LaunchDescription([
        DeclareLaunchArgument('model', default_value=default),
        Node(package='robot_state_publisher', executable='robot_state_publisher',
             parameters=[{'robot_description': Command(['xacro ', LaunchConfiguration('model')])}]),
    ])
"""
BRINGUP = """from launch import LaunchDescription
from launch.actions import DeclareLaunchArgument, IncludeLaunchDescription
from launch.conditions import IfCondition
from launch.launch_description_sources import PythonLaunchDescriptionSource
from launch.substitutions import LaunchConfiguration, PathJoinSubstitution
from launch_ros.substitutions import FindPackageShare


def generate_launch_description():
    display = PathJoinSubstitution([FindPackageShare('my_robot'), 'launch', 'display.launch.py'])
    model = PathJoinSubstitution([FindPackageShare('my_robot'), 'urdf', 'robot.urdf.xacro'])
    return LaunchDescription([
        DeclareLaunchArgument('rviz', default_value='false'),
        IncludeLaunchDescription(PythonLaunchDescriptionSource(display),
                                 condition=IfCondition(LaunchConfiguration('rviz')),
                                 launch_arguments={'model': model}.items()),
    ])
"""


def test_a_launch_file_another_one_includes_with_its_own_model_is_an_info(tmp_path):
    # bringup.launch.py includes display.launch.py (under a condition: not followed to it) and passes it `model`:
    # the default that does not exist may never be used
    pkg = _package(tmp_path, DISPLAY, launch_name="display.launch.py")
    (pkg / "launch" / "bringup.launch.py").write_text(BRINGUP)
    code, report = lint_json([], cwd=tmp_path)
    (f,) = _by_code(report, "C025")
    assert f["severity"] == "info" and code == 0
    assert [s["how"] for s in f["evidence"] if not s["evidence"]] == ["included"]
