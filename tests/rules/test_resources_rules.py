"""Issue 41: ros2_control resources (C022, C023), navigation frames (C024), self-collision at zero (G006).

Each seeded defect is an example package (examples/broken/, checked by test_examples.py); here each one's clean twin
(the one-line fix its model comment names) has no finding of the code, and the cases around each rule's edges
(inactive spawners, conditions, unlaunched files, SRDF entries, adjacency, coal missing) behave as documented."""
import shutil
from pathlib import Path

import pytest
from conftest import REPO, lint_json

BROKEN = REPO / "examples" / "broken"


def _copy(tmp_path, name):
    dst = tmp_path / name
    shutil.copytree(BROKEN / name, dst)
    (dst / "EXPECTED").unlink()
    return dst


def _edit(path: Path, old: str, new: str):
    text = path.read_text(encoding="utf-8")
    assert old in text, old
    path.write_text(text.replace(old, new), encoding="utf-8")


def _codes(folder, code):
    _, report = lint_json([str(folder)])
    return [(Path(f["location"]["file"]).name, f["location"]["line"], f["severity"]) for f in report["findings"]
            if f["code"] == code]


def test_claimed_twice_twin_spawns_inactive(tmp_path):
    pkg = _copy(tmp_path, "ros2control_claimed_twice")
    assert _codes(pkg, "C022") == [("arm.launch.xml", 10, "error")]
    _edit(pkg / "launch" / "arm.launch.xml", 'args="admittance_controller"', 'args="admittance_controller --inactive"')
    assert _codes(pkg, "C022") == []


@pytest.mark.parametrize("flag", ["--stopped", "--load-only"])
def test_claimed_twice_other_inactive_flags(tmp_path, flag):
    pkg = _copy(tmp_path, "ros2control_claimed_twice")
    _edit(pkg / "launch" / "arm.launch.xml", 'args="admittance_controller"', f'args="admittance_controller {flag}"')
    assert _codes(pkg, "C022") == []


def test_claimed_twice_alternatives_behind_a_condition(tmp_path):
    """Spawners behind a launch argument are alternatives: not compared."""
    pkg = _copy(tmp_path, "ros2control_claimed_twice")
    _edit(pkg / "launch" / "arm.launch.xml", '<launch>',
          '<launch>\n  <arg name="admittance" default="false"/>')
    _edit(pkg / "launch" / "arm.launch.xml", 'exec="spawner" args="admittance_controller"',
          'exec="spawner" args="admittance_controller" if="$(var admittance)"')
    assert _codes(pkg, "C022") == []


def test_claimed_twice_one_spawner_names_both(tmp_path):
    pkg = _copy(tmp_path, "ros2control_claimed_twice")
    _edit(pkg / "launch" / "arm.launch.xml", 'args="arm_controller"', 'args="arm_controller admittance_controller"')
    _edit(pkg / "launch" / "arm.launch.xml",
          '  <node pkg="controller_manager" exec="spawner" args="admittance_controller"/>\n', '')
    assert _codes(pkg, "C022") == [("arm.launch.xml", 9, "error")]


def test_claimed_twice_different_interfaces_do_not_conflict(tmp_path):
    pkg = _copy(tmp_path, "ros2control_claimed_twice")
    urdf = pkg / "urdf" / "arm.urdf"
    _edit(urdf, '<joint name="joint2"><command_interface name="position"/>',
          '<joint name="joint2"><command_interface name="position"/><command_interface name="velocity"/>')
    yaml = pkg / "config" / "controllers.yaml"
    text = yaml.read_text(encoding="utf-8")
    head, _, tail = text.partition("admittance_controller:\n  ros__parameters:")
    yaml.write_text(head + "admittance_controller:\n  ros__parameters:" +
                    tail.replace("joints: [joint1, joint2]", "joints: [joint2]").replace(
                        "command_interfaces: [position]", "command_interfaces: [velocity]"), encoding="utf-8")
    assert _codes(pkg, "C022") == []


# --- C022 across included launch files ---------------------------------------------------------------------------
def test_claimed_twice_through_an_include_twin(tmp_path):
    """The admittance spawner in an included file: found there; spawned inactive, the pair is clean."""
    pkg = _copy(tmp_path, "ros2control_claimed_included")
    assert _codes(pkg, "C022") == [("admittance.launch.xml", 3, "error")]
    _edit(pkg / "launch" / "admittance.launch.xml", 'args="admittance_controller"',
          'args="admittance_controller --inactive"')
    code, report = lint_json([str(pkg)])
    assert (code, report["findings"]) == (0, [])


@pytest.mark.parametrize("include", [
    # under a condition: an alternative
    '<arg name="admittance" default="false"/>\n  <include file="INC" if="$(var admittance)"/>',
    # in another namespace: another controller_manager
    '<group>\n    <push-ros-namespace namespace="right"/>\n    <include file="INC"/>\n  </group>',
    # an argument the included file reads, given a value other than its default
    '<include file="INC"><arg name="stage" value="admittance_controller"/></include>',
])
def test_claimed_twice_includes_not_followed(tmp_path, include):
    pkg = _copy(tmp_path, "ros2control_claimed_included")
    assert _codes(pkg, "C022") == [("admittance.launch.xml", 3, "error")]
    inc = "$(find-pkg-share included_arm_description)/launch/admittance.launch.xml"
    _edit(pkg / "launch" / "arm.launch.xml", f'<include file="{inc}"/>', include.replace("INC", inc))
    if "stage" in include:
        _edit(pkg / "launch" / "admittance.launch.xml", "<launch>",
              '<launch>\n  <arg name="stage" default="none_controller"/>')
        _edit(pkg / "launch" / "admittance.launch.xml", 'args="admittance_controller"', 'args="$(var stage)"')
    assert _codes(pkg, "C022") == []


def test_claimed_twice_through_a_python_include(tmp_path):
    pkg = _copy(tmp_path, "ros2control_claimed_included")
    (pkg / "launch" / "admittance.launch.xml").unlink()
    (pkg / "launch" / "admittance.launch.py").write_text(
        "from launch import LaunchDescription\nfrom launch_ros.actions import Node\n\n\n"
        "def generate_launch_description():\n    return LaunchDescription([\n"
        "        Node(package='controller_manager', executable='spawner', arguments=['admittance_controller']),\n"
        "    ])\n", encoding="utf-8")
    (pkg / "launch" / "arm.launch.xml").unlink()
    (pkg / "launch" / "arm.launch.py").write_text(
        "import os\n\nfrom ament_index_python.packages import get_package_share_directory\n"
        "from launch import LaunchDescription\nfrom launch.actions import IncludeLaunchDescription\n"
        "from launch.launch_description_sources import PythonLaunchDescriptionSource\n"
        "from launch_ros.actions import Node\n\n\n"
        "def generate_launch_description():\n"
        "    share = get_package_share_directory('included_arm_description')\n"
        "    with open(os.path.join(share, 'urdf', 'arm.urdf')) as f:\n        description = f.read()\n"
        "    return LaunchDescription([\n"
        "        Node(package='robot_state_publisher', executable='robot_state_publisher',\n"
        "             parameters=[{'robot_description': description}]),\n"
        "        Node(package='controller_manager', executable='ros2_control_node',\n"
        "             parameters=[os.path.join(share, 'config', 'controllers.yaml')]),\n"
        "        Node(package='controller_manager', executable='spawner', arguments=['arm_controller']),\n"
        "        IncludeLaunchDescription(PythonLaunchDescriptionSource(\n"
        "            os.path.join(share, 'launch', 'admittance.launch.py'))),\n"
        "    ])\n", encoding="utf-8")
    assert _codes(pkg, "C022") == [("admittance.launch.py", 7, "error")]


# --- C022 in ROS 1 -------------------------------------------------------------------------------------------------
def test_claimed_twice_ros1_twin(tmp_path):
    pkg = _copy(tmp_path, "ros1_claimed_twice")
    assert _codes(pkg, "C022") == [("arm.launch", 6, "error")]
    _edit(pkg / "launch" / "arm.launch", 'args="joint_group_position_controller"',
          'args="--stopped joint_group_position_controller"')
    code, report = lint_json([str(pkg)])
    assert (code, report["findings"]) == (0, [])


def test_claimed_twice_ros1_one_spawner_and_other_interfaces(tmp_path):
    """One spawner starting both is the same conflict; a velocity controller on the same joints claims another
    interface (a robot's RobotHW may allow that) and is not reported."""
    pkg = _copy(tmp_path, "ros1_claimed_twice")
    launch = pkg / "launch" / "arm.launch"
    _edit(launch, 'args="joint_state_controller arm_controller"',
          'args="joint_state_controller arm_controller joint_group_position_controller"')
    _edit(launch, '  <node name="group_spawner" pkg="controller_manager" type="spawner" '
          'args="joint_group_position_controller"/>\n', '')
    assert _codes(pkg, "C022") == [("arm.launch", 5, "error")]
    _edit(pkg / "config" / "controllers.yaml", "position_controllers/JointGroupPositionController",
          "velocity_controllers/JointGroupVelocityController")
    assert _codes(pkg, "C022") == []


def test_claimed_twice_ros1_included_spawner(tmp_path):
    pkg = _copy(tmp_path, "ros1_claimed_twice")
    launch = pkg / "launch" / "arm.launch"
    _edit(launch, '  <node name="group_spawner" pkg="controller_manager" type="spawner" '
          'args="joint_group_position_controller"/>\n',
          '  <include file="$(find ros1_arm_description)/launch/group.launch"/>\n')
    (pkg / "launch" / "group.launch").write_text(
        '<launch>\n  <node name="group_spawner" pkg="controller_manager" type="spawner" '
        'args="joint_group_position_controller"/>\n</launch>\n', encoding="utf-8")
    assert _codes(pkg, "C022") == [("group.launch", 2, "error")]
    _edit(launch, '<include file="$(find ros1_arm_description)/launch/group.launch"/>',
          '<include ns="left" file="$(find ros1_arm_description)/launch/group.launch"/>')
    assert _codes(pkg, "C022") == []


def test_chained_reference_twin(tmp_path):
    pkg = _copy(tmp_path, "ros2control_chained_reference")
    assert _codes(pkg, "C023") == [("controllers.yaml", 16, "error")]
    _edit(pkg / "config" / "controllers.yaml", "    joints: [joint1]\n", "    joints: [joint1, joint2]\n")
    assert _codes(pkg, "C023") == []


def test_nav2_frame_twin(tmp_path):
    pkg = _copy(tmp_path, "nav2_frame_typo")
    assert _codes(pkg, "C024") == [("nav2_params.yaml", 10, "warning")]
    _edit(pkg / "config" / "nav2_params.yaml", "base_footprnt", "base_footprint")
    assert _codes(pkg, "C024") == []


def test_nav2_frame_unlaunched_is_info(tmp_path):
    """Without a launch file giving a Nav2 node the file, the claim rests on the file lying in the package."""
    pkg = _copy(tmp_path, "nav2_frame_typo")
    (pkg / "launch" / "nav.launch.xml").unlink()
    assert _codes(pkg, "C024") == [("nav2_params.yaml", 10, "info")]


def test_nav2_sensor_frame_and_rep105(tmp_path):
    """An observation source's sensor_frame is checked; map and odom are localization's and never reported."""
    pkg = _copy(tmp_path, "nav2_frame_typo")
    _edit(pkg / "config" / "nav2_params.yaml", "base_footprnt", "base_footprint")
    _edit(pkg / "config" / "nav2_params.yaml", "sensor_frame: laser_link", "sensor_frame: laser_lnk")
    assert _codes(pkg, "C024") == [("nav2_params.yaml", 18, "warning")]


def test_self_collision_twin(tmp_path):
    pytest.importorskip("coal")
    pkg = _copy(tmp_path, "self_collision_home")
    assert _codes(pkg, "G006") == [("arm.urdf", 34, "info")]
    urdf = pkg / "urdf" / "arm.urdf"
    _edit(urdf, '<origin xyz="0 0 -0.25"/>\n      <geometry><box size="0.05 0.05 0.3"/>',
          '<origin xyz="0 0 -0.1"/>\n      <geometry><box size="0.05 0.05 0.1"/>')
    assert _codes(pkg, "G006") == []


def _srdf(pkg, entries):
    (pkg / "config").mkdir(exist_ok=True)
    (pkg / "config" / "arm.srdf").write_text(
        '<?xml version="1.0"?>\n<robot name="home_arm">\n  <group name="arm"><chain base_link="base_link" '
        f'tip_link="link2"/></group>\n{entries}</robot>\n', encoding="utf-8")


def test_self_collision_srdf_of_the_robot(tmp_path):
    """An SRDF of the robot that does not disable the pair makes it a warning; one that does silences it."""
    pytest.importorskip("coal")
    pkg = _copy(tmp_path, "self_collision_home")
    _srdf(pkg, '  <disable_collisions link1="base_link" link2="link1" reason="Adjacent"/>\n')
    assert _codes(pkg, "G006") == [("arm.urdf", 34, "warning")]
    _srdf(pkg, '  <disable_collisions link1="link2" link2="${prefix}base_link" reason="Default"/>\n')
    assert _codes(pkg, "G006") == []


def test_self_collision_limits_exclude_zero(tmp_path):
    """A joint between the links that cannot be at zero: the zero pose of the pair is never reached."""
    pytest.importorskip("coal")
    pkg = _copy(tmp_path, "self_collision_home")
    _edit(pkg / "urdf" / "arm.urdf", '<limit lower="-3" upper="3" effort="10" velocity="1"/>\n  </joint>\n</robot>',
          '<limit lower="0.5" upper="3" effort="10" velocity="1"/>\n  </joint>\n</robot>')
    assert _codes(pkg, "G006") == []


def test_self_collision_adjacent_and_welded_links(tmp_path):
    """Parent and child of a joint, and links welded by fixed joints, are never compared."""
    pytest.importorskip("coal")
    pkg = _copy(tmp_path, "self_collision_home")
    urdf = pkg / "urdf" / "arm.urdf"
    # base_link welded to link1 (joint1 fixed): link2 is then adjacent to the group base_link + link1
    _edit(urdf, '<joint name="joint1" type="revolute">', '<joint name="joint1" type="fixed">')
    assert _codes(pkg, "G006") == []
    # link2 hangs from base_link itself: adjacent; what remains is link2 against its sibling link1
    _edit(urdf, '<joint name="joint1" type="fixed">', '<joint name="joint1" type="revolute">')
    _edit(urdf, '<parent link="link1"/>\n    <child link="link2"/>',
          '<parent link="base_link"/>\n    <child link="link2"/>')
    _, report = lint_json([str(pkg)])
    pairs = [f["message"] for f in report["findings"] if f["code"] == "G006"]
    assert pairs and all("base_link" not in str(p) for p in pairs), pairs


def test_self_collision_without_coal_says_nothing(monkeypatch):
    """Without coal the rule is silent (no crash, no finding)."""
    from urdfcheck.rules import selfcollision

    monkeypatch.setattr(selfcollision, "_coal", lambda: (None, None))
    model = _model(BROKEN / "self_collision_home" / "urdf" / "arm.urdf")
    assert list(selfcollision.self_collisions(model, "", 0.005)) == []
    monkeypatch.undo()
    pytest.importorskip("coal")
    assert len(list(selfcollision.self_collisions(model, "", 0.005))) == 1


def _model(path):
    from urdfcheck.load.loader import load_model

    return load_model(str(path))


def test_nav2_params_file_given_to_nav2_bringup(tmp_path):
    """A launch file of the deployment that includes nav2_bringup with `params_file` runs Nav2 with that file."""
    pkg = _copy(tmp_path, "nav2_frame_typo")
    launch = pkg / "launch" / "nav.launch.xml"
    text = launch.read_text(encoding="utf-8")
    head = text[:text.index('  <node pkg="nav2_controller"')]
    launch.write_text(head + '  <include file="$(find-pkg-share nav2_bringup)/launch/navigation_launch.py">\n'
                      '    <arg name="params_file"'
                      ' value="$(find-pkg-share bot_description)/config/nav2_params.yaml"/>\n'
                      '  </include>\n</launch>\n', encoding="utf-8")
    assert _codes(pkg, "C024") == [("nav2_params.yaml", 10, "warning")]


def test_self_collision_loads_coal_only_for_candidates(tmp_path):
    """The bounding-box test runs first: a model whose shapes cannot interpenetrate by `depth` never imports coal
    (it takes over a second to import); one with a candidate pair does."""
    import subprocess
    import sys

    pytest.importorskip("coal")
    pkg = _copy(tmp_path, "self_collision_home")
    code = ("import sys; from urdfcheck.load.loader import load_model; from urdfcheck.rules import selfcollision as s;"
            "m = load_model(sys.argv[1]); n = len(list(s.self_collisions(m, '', 0.005)));"
            "print(n, 'coal' in sys.modules)")
    env = {"PYTHONPATH": str(REPO / "src"), "PATH": "/usr/bin:/bin"}

    def run():
        out = subprocess.run([sys.executable, "-c", code, str(pkg / "urdf" / "arm.urdf")], capture_output=True,
                             text=True, env=env, check=True)
        return out.stdout.split()

    assert run() == ["1", "True"]
    _edit(pkg / "urdf" / "arm.urdf", '<origin xyz="0 0 -0.25"/>\n      <geometry><box size="0.05 0.05 0.3"/>',
          '<origin xyz="0 0 -0.1"/>\n      <geometry><box size="0.05 0.05 0.1"/>')
    assert run() == ["0", "False"]


def test_amcl_odom_frame_nobody_publishes(tmp_path):
    """AMCL publishes map -> odom_frame_id itself; the odom frame must come from odometry: a frame only AMCL's own
    edge names is reported, REP-105 `odom` never."""
    pkg = _copy(tmp_path, "nav2_frame_typo")
    params = pkg / "config" / "nav2_params.yaml"
    _edit(params, "base_footprnt", "base_footprint")
    params.write_text(params.read_text(encoding="utf-8") + "\namcl:\n  ros__parameters:\n    base_frame_id: "
                      "base_footprint\n    global_frame_id: map\n    odom_frame_id: odom_frame\n", encoding="utf-8")
    _edit(pkg / "launch" / "nav.launch.xml", "</launch>",
          '  <node pkg="nav2_amcl" exec="amcl" name="amcl">\n'
          '    <param from="$(find-pkg-share bot_description)/config/nav2_params.yaml"/>\n  </node>\n</launch>')
    assert _codes(pkg, "C024") == [("nav2_params.yaml", 25, "warning")]
    _edit(params, "odom_frame_id: odom_frame", "odom_frame_id: odom")
    assert _codes(pkg, "C024") == []


@pytest.mark.parametrize("size", ["1e300 1e300 1e300", "inf 1 1", "nan 1 1", "0 0 0"])
def test_self_collision_absurd_sizes_are_skipped(tmp_path, size):
    """A box of no size or of an absurd one is left out: no crash, no finding about it."""
    pkg = _copy(tmp_path, "self_collision_home")
    _edit(pkg / "urdf" / "arm.urdf", '<box size="0.2 0.2 0.1"/>', f'<box size="{size}"/>')
    _, report = lint_json([str(pkg)])
    assert [f for f in report["findings"] if f["code"] in ("G006", "R001")] == []
