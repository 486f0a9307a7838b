"""Issue 41: the MoveIt config beside the model (M rules), the blocks that name parts of the model (S012-S014) and
angles in degrees (U011), through the real CLI: each broken example's clean twin is clean, the SRDF is read as
xacro too, a config package is linted by the model it names, and the pairing's evidence sets the severity."""
from __future__ import annotations

import os
import shutil

import pytest
from conftest import REPO, lint_json, run_cli

BROKEN = REPO / "examples" / "broken"


def _copy(name: str, tmp_path):
    dst = tmp_path / name
    shutil.copytree(BROKEN / name, dst)
    (dst / "EXPECTED").unlink()
    return dst


def _codes(report, prefix: str = "") -> list[tuple[str, str]]:
    return [(f["code"], f["severity"]) for f in report["findings"] if f["code"].startswith(prefix)]


def _edit(path, old: str, new: str) -> None:
    text = path.read_text(encoding="utf-8")
    assert old in text, (path, old)
    path.write_text(text.replace(old, new), encoding="utf-8")


# --- the broken examples and their clean twins ---------------------------------------------------------------
@pytest.mark.parametrize("name,fixes,codes", [
    ("moveit_config", [("arm_moveit_config/config/arm.srdf", 'tip_link="tool"', 'tip_link="tool0"'),
                       ("arm_moveit_config/config/arm.srdf", '"jointZ"', '"joint2"'),
                       ("arm_moveit_config/config/joint_limits.yaml", "joint_5:", "joint2:")], "M"),
    ("model_references", [("urdf/bot.urdf", 'reference="lasr"', 'reference="laser_link"'),
                          ("urdf/bot.urdf", 'name="jaa"', 'name="pan_joint"'),
                          ("urdf/bot.urdf", "laser_lnk", "laser_link")], "S01"),
    ("units_degrees", [("urdf/pan.urdf", 'lower="-180" upper="180"', 'lower="-3.14159" upper="3.14159"'),
                       ("urdf/pan.urdf", 'rpy="0 0 90"', 'rpy="0 0 1.5708"')], "U011"),
])
def test_the_clean_twin_of_each_broken_example_is_clean(tmp_path, name, fixes, codes):
    pkg = _copy(name, tmp_path)
    _, broken = lint_json([name], cwd=tmp_path)
    assert _codes(broken, codes), broken["findings"]
    for rel, old, new in fixes:
        _edit(pkg / rel, old, new)
    code, clean = lint_json([name], cwd=tmp_path)
    assert clean["findings"] == [] and code == 0, clean["findings"]


# --- MoveIt: reading and pairing --------------------------------------------------------------------------------
def test_a_moveit_config_package_is_linted_through_the_model_its_setup_assistant_names(tmp_path):
    _copy("moveit_config", tmp_path)
    folder = tmp_path / "moveit_config"
    code, report = lint_json(["arm_moveit_config"], cwd=folder)
    assert code == 1
    assert sorted(c for c, _ in _codes(report, "M")) == ["M001", "M002", "M010"]
    # from inside the config package: the model is a package of its workspace, as a launch file's $(find) finds it
    code, report = lint_json(["."], cwd=folder / "arm_moveit_config")
    assert sorted(c for c, _ in _codes(report, "M")) == ["M001", "M002", "M010"]


def test_a_setup_assistant_naming_a_package_outside_the_workspace_leads_nowhere(tmp_path):
    """A file of the checkout does not make the run lint an installed package elsewhere on the machine; the
    runner can name it (--package)."""
    _copy("moveit_config", tmp_path)
    ws = tmp_path / "ws"
    ws.mkdir()
    shutil.move(str(tmp_path / "moveit_config" / "arm_moveit_config"), ws / "arm_moveit_config")
    elsewhere = tmp_path / "moveit_config" / "arm_description"
    env = os.environ.get("ROS_PACKAGE_PATH")
    os.environ["ROS_PACKAGE_PATH"] = str(elsewhere)  # resolvable, but outside the workspace
    try:
        code, _, err = run_cli(["lint", "--no-config", "."], cwd=ws / "arm_moveit_config")
        assert code == 2 and "no URDF or xacro model found" in err
        code, report = lint_json([".", "--package", f"arm_description={elsewhere}"], cwd=ws / "arm_moveit_config")
        assert sorted(c for c, _ in _codes(report, "M")) == ["M001", "M002", "M010"]
    finally:
        if env is None:
            os.environ.pop("ROS_PACKAGE_PATH", None)
        else:
            os.environ["ROS_PACKAGE_PATH"] = env


def test_an_srdf_written_as_xacro_is_expanded(tmp_path):
    pkg = _copy("moveit_config", tmp_path)
    cfg = pkg / "arm_moveit_config" / "config"
    srdf = (cfg / "arm.srdf").read_text(encoding="utf-8")
    srdf = srdf.replace('<robot name="arm">', '<robot name="arm" xmlns:xacro="http://www.ros.org/wiki/xacro">\n'
                        '  <xacro:property name="tip" value="tool9"/>')
    srdf = srdf.replace('tip_link="tool"', 'tip_link="${tip}"')
    (cfg / "arm.srdf").unlink()
    (cfg / "arm.srdf.xacro").write_text(srdf, encoding="utf-8")
    _edit(pkg / "arm_moveit_config" / ".setup_assistant", "config/arm.srdf", "config/arm.srdf.xacro")
    _, report = lint_json(["moveit_config"], cwd=tmp_path)
    m001 = [f for f in report["findings"] if f["code"] == "M001"]
    assert len(m001) == 1 and "'tool9'" in m001[0]["message"], report["findings"]
    assert m001[0]["location"]["file"].endswith("arm.srdf.xacro") and m001[0]["location"]["line"] == 5


def test_a_config_paired_only_by_the_robot_name_gives_infos(tmp_path):
    pkg = _copy("moveit_config", tmp_path)
    (pkg / "arm_moveit_config" / ".setup_assistant").unlink()
    code, report = lint_json(["moveit_config"], cwd=tmp_path)
    found = _codes(report, "M")
    assert sorted(c for c, _ in found) == ["M001", "M002", "M010"] and {s for _, s in found} == {"info"}
    assert code == 0
    assert all("picked by its shape" in f["message"] for f in report["findings"] if f["code"].startswith("M"))


def test_the_config_of_another_robot_beside_the_model_is_not_its_config(tmp_path):
    pkg = _copy("moveit_config", tmp_path)
    srdf = pkg / "arm_moveit_config" / "config" / "arm.srdf"
    for old, new in (('"base_link"', '"left_base_link"'), ('"link1"', '"left_link1"'), ('"tool0"', '"left_tool0"'),
                     ('"joint1"', '"left_joint1"'), ('"joint2"', '"left_joint2"')):
        srdf.write_text(srdf.read_text(encoding="utf-8").replace(old, new), encoding="utf-8")
    _, report = lint_json(["moveit_config"], cwd=tmp_path)
    assert _codes(report, "M") == [], report["findings"]


def test_moveit_yaml_shapes_ros1_controller_list_and_kinematics_under_ros_parameters(tmp_path):
    pkg = _copy("moveit_config", tmp_path)
    cfg = pkg / "arm_moveit_config" / "config"
    _edit(cfg / "arm.srdf", 'tip_link="tool"', 'tip_link="tool0"')
    _edit(cfg / "arm.srdf", '"jointZ"', '"joint2"')
    (cfg / "joint_limits.yaml").unlink()
    (cfg / "kinematics.yaml").write_text(
        "/**:\n  ros__parameters:\n    robot_description_kinematics:\n      manipulator:\n"
        "        kinematics_solver: kdl_kinematics_plugin/KDLKinematicsPlugin\n", encoding="utf-8")
    (cfg / "controllers.yaml").write_text(
        "controller_list:\n  - name: arm_controller\n    action_ns: follow_joint_trajectory\n"
        "    type: FollowJointTrajectory\n    joints: [joint1, joint_2]\n", encoding="utf-8")
    _, report = lint_json(["moveit_config"], cwd=tmp_path)
    got = {(f["code"], f["location"]["file"].rsplit("/", 1)[1], f["location"]["line"]) for f in report["findings"]}
    assert got == {("M013", "kinematics.yaml", 4), ("M014", "controllers.yaml", 5)}, report["findings"]


def test_limits_and_initial_positions_are_compared_conservatively(tmp_path):
    pkg = _copy("moveit_config", tmp_path)
    cfg = pkg / "arm_moveit_config" / "config"
    _edit(cfg / "arm.srdf", 'tip_link="tool"', 'tip_link="tool0"')
    _edit(cfg / "arm.srdf", '"jointZ"', '"joint2"')
    (cfg / "joint_limits.yaml").write_text(
        "joint_limits:\n"
        "  joint1:\n    has_velocity_limits: true\n    max_velocity: 6.0\n"     # wider than 2.0: M011, not degrees
        "  joint2:\n    has_position_limits: true\n    max_position: 90\n"     # degrees: M012 only
        "    has_velocity_limits: false\n    max_velocity: 9.0\n", encoding="utf-8")  # limits off: nothing
    (cfg / "initial_positions.yaml").write_text(
        "initial_positions:\n  joint1: 3.17\n  joint2: 1.7\n", encoding="utf-8")  # within 0.05 / beyond it
    _, report = lint_json(["moveit_config"], cwd=tmp_path)
    got = sorted((f["code"], f["location"]["file"].rsplit("/", 1)[1], f["location"]["line"])
                 for f in report["findings"])
    assert got == [("M011", "joint_limits.yaml", 4), ("M012", "joint_limits.yaml", 7),
                   ("M015", "initial_positions.yaml", 3)], report["findings"]
    m012 = next(f for f in report["findings"] if f["code"] == "M012")
    assert "1.571 rad" in m012["message"]


def test_srdf_names_the_virtual_joint_and_passive_joints(tmp_path):
    pkg = _copy("moveit_config", tmp_path)
    srdf = pkg / "arm_moveit_config" / "config" / "arm.srdf"
    _edit(srdf, 'tip_link="tool"', 'tip_link="tool0"')
    _edit(srdf, '"jointZ"', '"joint2"')
    _edit(srdf, 'child_link="base_footprint"', 'child_link="link1"')
    _edit(srdf, "</robot>", '  <passive_joint name="virtual_joint"/>\n  <end_effector name="tip" parent_link="tol0" '
                            'group="wrist"/>\n  <group name="all">\n    <joint name="virtual_joint"/>\n'
                            '  </group>\n</robot>')
    _, report = lint_json(["moveit_config"], cwd=tmp_path)
    got = sorted((f["code"], f["location"]["line"]) for f in report["findings"] if f["code"].startswith("M"))
    assert got == [("M001", 17), ("M004", 13), ("M010", 9)], report["findings"]


# --- blocks that name the model, and degrees ----------------------------------------------------------------------
def _robot(tmp_path, body: str):
    (tmp_path / "robot.urdf").write_text(
        '<robot name="r">\n  <link name="base_link"/>\n  <link name="ns/cam_link"/>\n'
        '  <joint name="cam_joint" type="fixed">\n    <parent link="base_link"/>\n    <child link="ns/cam_link"/>\n'
        '  </joint>\n' + body + '</robot>\n', encoding="utf-8")
    _, report = lint_json(["robot.urdf"], cwd=tmp_path)
    return [(f["code"], f["severity"]) for f in report["findings"] if f["code"] in ("S012", "S013", "S014")]


def test_references_to_sdf_links_joints_and_prefixed_frames_are_not_reported(tmp_path):
    body = ('  <gazebo><link name="extra_link"/></gazebo>\n  <gazebo reference="extra_link"><mu1>1</mu1></gazebo>\n'
            '  <gazebo reference="cam_joint"><provideFeedback>true</provideFeedback></gazebo>\n'
            '  <gazebo reference="ns/cam_link"><sensor name="c" type="camera"><plugin name="p" filename="x.so">'
            '<frameName>cam_link</frameName></plugin></sensor></gazebo>\n'
            '  <gazebo reference="base_link"><sensor name="imu" type="imu"><gz_frame_id>world</gz_frame_id>'
            '</sensor></gazebo>\n')
    assert _robot(tmp_path, body) == []


def test_a_sensor_frame_without_a_near_link_is_information(tmp_path):
    body = ('  <gazebo reference="base_link"><sensor name="imu" type="imu">\n'
            '    <gz_frame_id>imu_frame</gz_frame_id></sensor></gazebo>\n')
    assert _robot(tmp_path, body) == [("S014", "info")]


@pytest.mark.parametrize("origin,limit,expected", [
    ('rpy="0 0 1.5708"', 'lower="-3.14" upper="3.14"', []),
    ('rpy="0 0 45"', 'lower="-90" upper="90"', [("U011", "warning")]),      # 45 may be anything; 90 is degrees
    ('rpy="3.14159 0 -180"', 'lower="-1" upper="1"', [("U011", "warning")]),
    ('xyz="0 0 90"', 'lower="0" upper="6.28"', []),                           # a length, not an angle
])
def test_angles_in_degrees_only_where_unambiguous(tmp_path, origin, limit, expected):
    (tmp_path / "robot.urdf").write_text(
        f'<robot name="r">\n  <link name="base_link"/>\n  <link name="l"/>\n'
        f'  <joint name="j" type="revolute">\n    <origin {origin}/>\n    <parent link="base_link"/>\n'
        f'    <child link="l"/>\n    <axis xyz="0 0 1"/>\n    <limit {limit} effort="1" velocity="1"/>\n'
        f'  </joint>\n</robot>\n', encoding="utf-8")
    _, report = lint_json(["robot.urdf"], cwd=tmp_path)
    assert [(f["code"], f["severity"]) for f in report["findings"] if f["code"] == "U011"] == expected


def test_a_prismatic_limit_of_90_is_not_degrees(tmp_path):
    (tmp_path / "robot.urdf").write_text(
        '<robot name="r">\n  <link name="base_link"/>\n  <link name="l"/>\n'
        '  <joint name="j" type="prismatic">\n    <parent link="base_link"/>\n    <child link="l"/>\n'
        '    <axis xyz="0 0 1"/>\n    <limit lower="0" upper="90" effort="1" velocity="1"/>\n'
        '  </joint>\n</robot>\n', encoding="utf-8")
    _, report = lint_json(["robot.urdf"], cwd=tmp_path)
    assert [f for f in report["findings"] if f["code"] == "U011"] == []


def test_no_model_and_no_setup_assistant_is_still_a_usage_error(tmp_path):
    (tmp_path / "cfg").mkdir()
    (tmp_path / "cfg" / "package.xml").write_text("<package><name>cfg</name></package>", encoding="utf-8")
    code, _, err = run_cli(["lint", "--no-config", "cfg"], cwd=tmp_path)
    assert code == 2 and "no URDF or xacro model found" in err


def test_a_launch_file_pairs_by_whole_file_names(tmp_path):
    pkg = _copy("moveit_config", tmp_path)
    cfg = pkg / "arm_moveit_config"
    (cfg / ".setup_assistant").unlink()
    _edit(cfg / "config" / "arm.srdf", '<robot name="arm">', '<robot name="arm_cell">')  # no pairing by name
    (cfg / "launch").mkdir()
    launch = cfg / "launch" / "demo.launch.py"
    launch.write_text('DESC = ("arm_description", "urdf/arm.urdf.xacro")\n', encoding="utf-8")
    _, report = lint_json(["moveit_config"], cwd=tmp_path)
    assert _codes(report, "M") == [], report["findings"]  # arm.urdf.xacro is another file than arm.urdf
    launch.write_text('DESC = ("arm_description", "urdf/arm.urdf")\n', encoding="utf-8")
    _, report = lint_json(["moveit_config"], cwd=tmp_path)
    assert sorted(_codes(report, "M")) == [("M001", "error"), ("M002", "error"), ("M010", "warning")]


def test_the_setup_assistant_vouches_only_for_the_srdf_it_names(tmp_path):
    pkg = _copy("moveit_config", tmp_path)
    _edit(pkg / "arm_moveit_config" / ".setup_assistant", "config/arm.srdf", "config/other.srdf")
    _, report = lint_json(["moveit_config"], cwd=tmp_path)
    found = _codes(report, "M")
    assert sorted(c for c, _ in found) == ["M001", "M002", "M010"] and {s for _, s in found} == {"info"}


def test_an_srdf_comment_suppresses_a_finding_in_the_srdf(tmp_path):
    pkg = _copy("moveit_config", tmp_path)
    _edit(pkg / "arm_moveit_config" / "config" / "arm.srdf", "    <chain ",
          "    <!-- urdfcheck: ignore[M001] the tool link comes with the gripper -->\n    <chain ")
    _, report = lint_json(["moveit_config"], cwd=tmp_path)
    assert sorted(c for c, _ in _codes(report, "M")) == ["M002", "M010"]


def test_a_moveit_controller_joint_its_ros2_control_controller_does_not_command(tmp_path):
    pkg = _copy("moveit_config", tmp_path)
    cfg = pkg / "arm_moveit_config" / "config"
    _edit(cfg / "arm.srdf", 'tip_link="tool"', 'tip_link="tool0"')
    _edit(cfg / "arm.srdf", '"jointZ"', '"joint2"')
    _edit(cfg / "joint_limits.yaml", "joint_5:", "joint2:")
    (cfg / "moveit_controllers.yaml").write_text(
        "moveit_simple_controller_manager:\n  controller_names: [arm_controller]\n  arm_controller:\n"
        "    type: FollowJointTrajectory\n    action_ns: follow_joint_trajectory\n    joints: [joint1, joint2]\n",
        encoding="utf-8")
    (cfg / "ros2_controllers.yaml").write_text(
        "controller_manager:\n  ros__parameters:\n    update_rate: 100\n    arm_controller:\n"
        "      type: joint_trajectory_controller/JointTrajectoryController\n"
        "arm_controller:\n  ros__parameters:\n    joints: [joint1]\n    command_interfaces: [position]\n"
        "    state_interfaces: [position]\n", encoding="utf-8")
    _, report = lint_json(["moveit_config"], cwd=tmp_path)
    got = [(f["code"], f["severity"], f["location"]["line"]) for f in report["findings"]]
    assert got == [("M014", "error", 6)], report["findings"]
    # the same joint as a mimic of joint1 is never in a trajectory MoveIt sends: nothing to say
    urdf = pkg / "arm_description" / "urdf" / "arm.urdf"
    _edit(urdf, '<limit lower="-1.57" upper="1.57" effort="10" velocity="2.0"/>',
          '<limit lower="-1.57" upper="1.57" effort="10" velocity="2.0"/>\n    <mimic joint="joint1"/>')
    _, report = lint_json(["moveit_config"], cwd=tmp_path)
    assert [f for f in report["findings"] if f["code"] == "M014"] == []


def test_a_variant_of_the_model_meets_the_srdf_of_the_same_arguments(tmp_path):
    """gripper:=false (an explored variant) has no hand: the SRDF xacro expanded with gripper:=false has none
    either; a plain SRDF written for the default cannot follow, and what it says of that variant is an info."""
    pkg = _copy("moveit_config", tmp_path)
    desc, cfg = pkg / "arm_description", pkg / "arm_moveit_config"
    urdf = (desc / "urdf" / "arm.urdf").read_text(encoding="utf-8")
    urdf = urdf.replace('<robot name="arm">', '<robot name="arm" xmlns:xacro="http://www.ros.org/wiki/xacro">\n'
                        '  <xacro:arg name="gripper" default="true"/>')
    urdf = urdf.replace("</robot>", '  <xacro:if value="$(arg gripper)">\n    <link name="hand"/>\n'
                        '    <joint name="hand_joint" type="fixed">\n      <parent link="tool0"/>\n'
                        '      <child link="hand"/>\n    </joint>\n  </xacro:if>\n</robot>')
    (desc / "urdf" / "arm.urdf").unlink()
    (desc / "urdf" / "arm.urdf.xacro").write_text(urdf, encoding="utf-8")
    _edit(cfg / ".setup_assistant", "urdf/arm.urdf", "urdf/arm.urdf.xacro")
    (cfg / "config" / "joint_limits.yaml").unlink()
    srdf = (cfg / "config" / "arm.srdf").read_text(encoding="utf-8")
    srdf = srdf.replace('tip_link="tool"', 'tip_link="tool0"').replace('"jointZ"', '"joint2"')
    xacro = srdf.replace('<robot name="arm">', '<robot name="arm" xmlns:xacro="http://www.ros.org/wiki/xacro">\n'
                         '  <xacro:arg name="gripper" default="true"/>')
    xacro = xacro.replace("</robot>", '  <xacro:if value="$(arg gripper)">\n'
                          '    <group name="hand">\n      <link name="hand"/>\n    </group>\n'
                          '  </xacro:if>\n</robot>')
    (cfg / "config" / "arm.srdf").unlink()
    (cfg / "config" / "arm.srdf.xacro").write_text(xacro, encoding="utf-8")
    _edit(cfg / ".setup_assistant", "config/arm.srdf", "config/arm.srdf.xacro")
    _, report = lint_json(["moveit_config"], cwd=tmp_path)
    assert _codes(report, "M") == [], report["findings"]
    # the same SRDF written plain, for the default: the gripper:=false variant's hand is missing, said as info
    plain = srdf.replace("</robot>", '  <group name="hand">\n    <link name="hand"/>\n  </group>\n</robot>')
    (cfg / "config" / "arm.srdf.xacro").unlink()
    (cfg / "config" / "arm.srdf").write_text(plain, encoding="utf-8")
    _edit(cfg / ".setup_assistant", "config/arm.srdf.xacro", "config/arm.srdf")
    _, report = lint_json(["moveit_config"], cwd=tmp_path)
    assert _codes(report, "M") == [("M001", "info")], report["findings"]
    assert "gripper:=false" in next(f["message"] for f in report["findings"] if f["code"] == "M001")
