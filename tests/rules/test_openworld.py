"""Issue 20: deployments in an open world. Nothing dropped (every parameter file of a package is checked
against its models, whether a launch file reads it or not), no absence claimed where the tool did not
understand what could supply it, attachable fragments, and deployments not understood said as findings."""
import shutil
from pathlib import Path

import pytest

from tests.conftest import REPO, lint_json

AGV = REPO / "examples" / "agv"

DESCRIPTION_LAUNCH = """<launch>
  <arg name="use_camera" default="true"/>
  <param name="robot_description"
         command="$(find xacro)/xacro '$(find agv_description)/urdf/agv.urdf.xacro' use_camera:=$(arg use_camera)"/>
  <node pkg="robot_state_publisher" type="robot_state_publisher" name="robot_state_publisher"/>
</launch>
"""


def write(path: Path, text: str) -> Path:
    path.parent.mkdir(parents=True, exist_ok=True)
    path.write_text(text)
    return path


def seed(tmp: Path) -> Path:
    """The seed tutorial's description package: urdf/, config/ (the base driver's ROS 1 YAML and a
    ros2_control controller YAML) and launch/description.launch, which starts robot_state_publisher alone."""
    ws = tmp / "agv_description"
    ws.mkdir()
    for part in ("urdf", "config"):
        shutil.copytree(AGV / part, ws / part)
    (ws / "urdf" / "agv.urdf").unlink()  # the xacro is the model here
    shutil.copy(AGV / "package.xml", ws / "package.xml")
    write(ws / "launch" / "description.launch", DESCRIPTION_LAUNCH)
    return ws


def edit(path: Path, old: str, new: str) -> None:
    text = path.read_text()
    assert old in text, (path, old)
    path.write_text(text.replace(old, new, 1))


CTRL, DRV = "config/agv_controllers.yaml", "config/agv_driver_ros1.yaml"
XACRO, MACROS = "urdf/agv.urdf.xacro", "urdf/macros/components.xacro"
CASTER = """  <link name="caster_link"/>
  <joint name="caster_joint" type="continuous">
    <parent link="base_link"/><child link="caster_link"/><origin xyz="0.22 0 -0.05"/><axis xyz="0 0 1"/>
  </joint>
</robot>"""
TILTED = [(MACROS, "params=\"prefix side_sign ", "params=\"prefix side_sign axis:='0 1 0' "),
          (MACROS, '<axis xyz="0 1 0"/>', '<axis xyz="${axis}"/>'),
          (XACRO, '<xacro:wheel prefix="right" side_sign="-1"',
           '<xacro:wheel prefix="right" side_sign="-1" axis="0 0.8 0.6"')]

# (name, edits, expected code, severity, file the finding is in)
SEEDED = [
    ("controller joint misspelt",
     [(CTRL, "left_wheel_names: [left_wheel_joint]", "left_wheel_names: [left_wheel_jiont]")], "C001", "error", CTRL),
    ("controller wheel separation", [(CTRL, "wheel_separation: 0.50", "wheel_separation: 0.56")],
     "C010", "error", CTRL),
    ("controller wheel radius", [(CTRL, "wheel_radius: 0.10", "wheel_radius: 0.12")], "C011", "error", CTRL),
    ("controller base frame", [(CTRL, "base_frame_id: base_link", "base_frame_id: base_lnk")],
     "C020", "error", CTRL),
    ("controller wheels swapped",
     [(CTRL, "left_wheel_names: [left_wheel_joint]", "left_wheel_names: [right_wheel_joint]"),
      (CTRL, "right_wheel_names: [right_wheel_joint]", "right_wheel_names: [left_wheel_joint]")],
     "C014", "error", CTRL),
    ("fixed wheel", [(MACROS, 'type="continuous"', 'type="${\'fixed\' if prefix == \'right\' else \'continuous\'}"')],
     "C002", "error", CTRL),
    ("wheel axes not parallel", TILTED, "C012", "error", MACROS),
    ("caster nothing publishes", [(XACRO, "</robot>", CASTER)], "C003", "warning", XACRO),
    ("driver joint misspelt", [(DRV, "left_wheel_joint: left_wheel_joint", "left_wheel_joint: left_wheel_jiont")],
     "C001", "warning", DRV),
    ("driver wheel separation", [(DRV, "wheel_separation: 0.50", "wheel_separation: 0.56")], "C010", "warning", DRV),
    ("driver wheel radius", [(DRV, "wheel_radius: 0.10", "wheel_radius: 0.12")], "C011", "warning", DRV),
    ("driver imu frame", [(DRV, "imu_frame_id: imu_link", "imu_frame_id: imu")], "C020", "warning", DRV),
    ("driver laser frame", [(DRV, "laser_frame_id: laser_link", "laser_frame_id: lazer_link")], "C020", "warning", DRV),
]


def _failing(report):
    return [f for f in report["findings"] if f["severity"] in ("error", "warning")]


def test_seed_clean_passes(tmp_path):
    ws = seed(tmp_path)
    code, report = lint_json([], cwd=ws)
    assert _failing(report) == [], report["findings"]
    assert code == 0


@pytest.mark.parametrize("name,edits,code,severity,where", SEEDED, ids=[s[0] for s in SEEDED])
def test_seeded_contract_defect_found(tmp_path, name, edits, code, severity, where):
    ws = seed(tmp_path)
    for f, old, new in edits:
        edit(ws / f, old, new)
    rc, report = lint_json([], cwd=ws)
    got = [(f["code"], f["severity"], f["location"]["file"]) for f in report["findings"]]
    assert (code, severity, where) in got, got
    assert rc == 1


# --- fragments ------------------------------------------------------------------------------------------
GRIPPER = """<robot name="gripper">
  <link name="gripper_base"/>
  <link name="finger"/>
  <joint name="gripper_mount" type="fixed"><parent link="{parent}"/><child link="gripper_base"/></joint>
  <joint name="finger_joint" type="prismatic"><parent link="gripper_base"/><child link="finger"/>
    <axis xyz="1 0 0"/><limit lower="0" upper="0.04" effort="10" velocity="0.1"/></joint>
  {extra}
</robot>
"""


def test_end_effector_fragment_is_an_info_naming_its_attach_link(tmp_path):
    f = write(tmp_path / "gripper.urdf", GRIPPER.format(parent="tool0", extra=""))
    code, report = lint_json([f], cwd=tmp_path)
    s003 = [x for x in report["findings"] if x["code"] == "S003"]
    assert [x["severity"] for x in s003] == ["info"] and "'tool0'" in s003[0]["message"], report["findings"]
    assert "attachable fragment" in s003[0]["message"]
    assert code == 0


def test_fragment_keeps_its_other_findings(tmp_path):
    bad = '<joint name="finger2_joint" type="revolute"><parent link="gripper_base"/><child link="finger2"/>' \
          '<axis xyz="0 0 0"/><limit lower="0" upper="1" effort="1" velocity="1"/></joint><link name="finger2"/>'
    f = write(tmp_path / "gripper.urdf", GRIPPER.format(parent="tool0", extra=bad))
    code, report = lint_json([f], cwd=tmp_path)
    assert ("J006", "error") in {(x["code"], x["severity"]) for x in report["findings"]}
    assert code == 1


@pytest.mark.parametrize("parent,extra", [
    ("base_lnk", '<link name="base_link"/><joint name="j0" type="fixed"><parent link="base_link"/>'
                 '<child link="other"/></joint><link name="other"/>'),  # a typo of a defined link
    ("tool0", '<joint name="j9" type="fixed"><parent link="finger"/><child link="nowhere"/></joint>'),  # two dangling
])
def test_a_missing_link_that_is_no_attach_point_stays_an_error(tmp_path, parent, extra):
    f = write(tmp_path / "gripper.urdf", GRIPPER.format(parent=parent, extra=extra))
    _, report = lint_json([f], cwd=tmp_path)
    assert "error" in {x["severity"] for x in report["findings"] if x["code"] == "S003"}, report["findings"]


# --- false alarms: absence claimed about a world the tool only partly understood --------------------------
PKG = "<package format='3'><name>{}</name></package>"
BOT = """<robot name="bot">
  <link name="base_link"/>
  <link name="left_wheel"/><link name="right_wheel"/><link name="camera_link"/>
  <joint name="left_wheel_joint" type="continuous"><parent link="base_link"/><child link="left_wheel"/>
    <origin xyz="0 0.2 0"/><axis xyz="0 1 0"/></joint>
  <joint name="right_wheel_joint" type="continuous"><parent link="base_link"/><child link="right_wheel"/>
    <origin xyz="0 -0.2 0"/><axis xyz="0 1 0"/></joint>
  <joint name="camera_joint" type="fixed"><parent link="base_link"/><child link="camera_link"/></joint>
  <ros2_control name="bot" type="system"><hardware><plugin>mock_components/GenericSystem</plugin></hardware>
    <joint name="left_wheel_joint"><command_interface name="velocity"/><state_interface name="position"/></joint>
    <joint name="right_wheel_joint"><command_interface name="velocity"/><state_interface name="position"/></joint>
  </ros2_control>
</robot>
"""
RSP = """  <node pkg="robot_state_publisher" exec="robot_state_publisher">
    <param name="robot_description" value="$(command 'cat $(find-pkg-share bot_description)/urdf/bot.urdf')"/>
  </node>
"""


def description_ws(tmp: Path, launch_body: str = "") -> Path:
    d = tmp / "bot_description"
    write(d / "package.xml", PKG.format("bot_description"))
    write(d / "urdf" / "bot.urdf", BOT)
    write(d / "launch" / "description.launch.xml", "<launch>\n" + RSP + launch_body + "</launch>\n")
    return d


def by_code(report, code):
    return [x for x in report["findings"] if x["code"] == code]


def test_broadcaster_in_a_control_package_is_a_supplier_elsewhere(tmp_path):
    description_ws(tmp_path)
    ctl = tmp_path / "bot_control"
    write(ctl / "package.xml", PKG.format("bot_control"))
    write(ctl / "config" / "controllers.yaml", """controller_manager:
  ros__parameters:
    joint_state_broadcaster: {type: joint_state_broadcaster/JointStateBroadcaster}
    diff_drive_controller: {type: diff_drive_controller/DiffDriveController}
diff_drive_controller:
  ros__parameters:
    left_wheel_names: [left_wheel_joint]
    right_wheel_names: [right_wheel_joint]
""")
    write(ctl / "launch" / "control.launch.xml", """<launch>
  <node pkg="controller_manager" exec="ros2_control_node">
    <param from="$(find-pkg-share bot_control)/config/controllers.yaml"/></node>
  <node pkg="controller_manager" exec="spawner" args="joint_state_broadcaster"/>
</launch>
""")
    code, report = lint_json([], cwd=tmp_path)
    c003 = by_code(report, "C003")
    assert c003 and all(x["severity"] == "info" for x in c003), report["findings"]
    assert "joint_state_broadcaster" in c003[0]["message"] and "controllers.yaml" in c003[0]["message"]
    assert code == 0


def test_description_only_launch_file_claims_no_absence(tmp_path):
    d = description_ws(tmp_path)
    write(d / "config" / "controllers.yaml", """diff_drive_controller:
  ros__parameters:
    type: diff_drive_controller/DiffDriveController
    left_wheel_names: [left_wheel_joint]
    right_wheel_names: [right_wheel_joint]
    wheel_separation: 0.4
    wheel_radius: 0.05
""")
    code, report = lint_json([], cwd=d)
    c003 = by_code(report, "C003")
    assert c003 and all(x["severity"] == "info" for x in c003), report["findings"]
    assert "description launch file" in c003[0]["message"]
    assert code == 0


def test_own_joint_state_script_in_the_launch_file_is_named(tmp_path):
    d = description_ws(tmp_path, '  <node pkg="bot_description" exec="my_joint_publisher.py"/>\n')
    code, report = lint_json([], cwd=d)
    c003 = by_code(report, "C003")
    assert c003 and all(x["severity"] == "info" for x in c003), report["findings"]
    assert "`my_joint_publisher.py`" in c003[0]["message"] and "description.launch.xml" in c003[0]["message"]
    assert code == 0


@pytest.mark.parametrize("camera_params", ["", '<param name="publish_tf" value="true"/>'
                                               '<param name="base_frame_id" value="camera_link"/>'])
def test_camera_driver_may_publish_its_own_frames(tmp_path, camera_params):
    camera = f'  <node pkg="realsense2_camera" exec="realsense2_camera_node">{camera_params}</node>\n'
    d = description_ws(tmp_path, camera + """
  <node pkg="bot_base" exec="base_driver"><param from="$(find-pkg-share bot_description)/config/base.yaml"/></node>
  <node pkg="joint_state_publisher" exec="joint_state_publisher"/>
""")
    write(d / "config" / "base.yaml", """base_driver:
  ros__parameters:
    left_wheel_joint: left_wheel_joint
    right_wheel_joint: right_wheel_joint
    camera_frame_id: camera_color_optical_frame
""")
    code, report = lint_json([], cwd=d)
    # realsense2_camera is a known TF owner (contracts/tfowners.yaml): with publish_tf (default true) its frames
    # are published, so nothing is absent; were it unknown, the claim would be an info naming the node
    c020 = by_code(report, "C020")
    assert all(x["severity"] == "info" and "realsense2_camera" in x["message"] for x in c020), report["findings"]
    assert code == 0


def test_understood_deployment_still_fails_an_absence(tmp_path):
    """The same launch file with only known nodes: nothing publishes the wheel states is a warning."""
    d = description_ws(tmp_path, '  <node pkg="controller_manager" exec="ros2_control_node">'
                                 '<param from="$(find-pkg-share bot_description)/config/c.yaml"/></node>\n'
                                 '  <node pkg="controller_manager" exec="spawner" args="diff_drive_controller"/>\n')
    write(d / "config" / "c.yaml", """controller_manager:
  ros__parameters:
    diff_drive_controller: {type: diff_drive_controller/DiffDriveController}
diff_drive_controller:
  ros__parameters:
    left_wheel_names: [left_wheel_joint]
    right_wheel_names: [right_wheel_joint]
""")
    code, report = lint_json([], cwd=d)
    assert [x["severity"] for x in by_code(report, "C003")] == ["warning"], report["findings"]
    assert code == 1


# --- deployments not understood are findings ----------------------------------------------------------------
PY_HEAD = """from launch import LaunchDescription
from launch_ros.actions import Node
"""
NOT_UNDERSTOOD = {
    "helper function": PY_HEAD + """from bot_common.description import robot_description


def generate_launch_description():
    return LaunchDescription([Node(package='robot_state_publisher', executable='robot_state_publisher',
                                   parameters=[{'robot_description': robot_description('bot')}])])
""",
    "calibrated at run time": PY_HEAD + """from launch.substitutions import Command


def generate_launch_description():
    return LaunchDescription([Node(package='robot_state_publisher', executable='robot_state_publisher',
        parameters=[{'robot_description': Command(['cat ', '/var/lib/bot/calibrated.urdf'])}])])
""",
    "file content": PY_HEAD + """from launch.substitutions import FileContent, PathJoinSubstitution, LaunchConfiguration
from launch_ros.substitutions import FindPackageShare


def generate_launch_description():
    path = PathJoinSubstitution([FindPackageShare(LaunchConfiguration('pkg')), 'urdf', 'bot.urdf'])
    return LaunchDescription([Node(package='robot_state_publisher', executable='robot_state_publisher',
        parameters=[{'robot_description': FileContent(path)}])])
""",
}
ROS1_NOT_UNDERSTOOD = {
    "eval find": """<launch>
  <arg name="robot" default="bot"/>
  <param name="robot_description"
         command="$(find xacro)/xacro $(eval find(arg('robot') + '_description') + '/urdf/x.xacro')"/>
  <node pkg="robot_state_publisher" type="robot_state_publisher" name="rsp"/>
</launch>
""",
}


@pytest.mark.parametrize("name", sorted(NOT_UNDERSTOOD) + sorted(ROS1_NOT_UNDERSTOOD))
def test_deployment_not_understood_is_a_finding_or_a_target(tmp_path, name):
    d = tmp_path / "bot_bringup"
    write(d / "package.xml", PKG.format("bot_bringup"))
    write(d / "urdf" / "bot.urdf", '<robot name="bot"><link name="base_link"/></robot>')
    if name in NOT_UNDERSTOOD:
        write(d / "launch" / "bringup.launch.py", NOT_UNDERSTOOD[name])
    else:
        write(d / "launch" / "bringup.launch", ROS1_NOT_UNDERSTOOD[name])
    code, report = lint_json([], cwd=d)
    c021 = by_code(report, "C021")
    deployed = [m for m in report.get("models", []) if "launch" in str(m)]
    assert c021 or deployed, report
    for x in c021:
        assert x["severity"] == "info" and "bringup.launch" in x["message"] and "urdfcheck.yaml" in x["message"]
        assert x["location"]["file"].startswith("launch/bringup.launch")
    assert code == 0


@pytest.mark.parametrize("fmt", ["text", "sarif", "junit", "github", "markdown"])
def test_not_understood_in_every_report_format(tmp_path, fmt):
    from tests.conftest import run_cli

    d = tmp_path / "bot_bringup"
    write(d / "package.xml", PKG.format("bot_bringup"))
    write(d / "urdf" / "bot.urdf", '<robot name="bot"><link name="base_link"/></robot>')
    write(d / "launch" / "bringup.launch.py", NOT_UNDERSTOOD["helper function"])
    code, out, err = run_cli(["lint", "--no-config", "--format", fmt], cwd=d)
    assert code == 0, err
    assert "C021" in out or "deployment-not-understood" in out, out


CONTROLLERS = """controller_manager:
  ros__parameters:
    diff_drive_controller: {type: diff_drive_controller/DiffDriveController}
diff_drive_controller:
  ros__parameters:
    left_wheel_names: [left_wheel_joint]
    right_wheel_names: [right_wheel_joint]
    wheel_separation: 0.4
    wheel_radius: 0.05
"""
CONTROL_NODES = ('  <node pkg="controller_manager" exec="ros2_control_node">'
                 '<param from="$(find-pkg-share bot_description)/config/c.yaml"/></node>\n'
                 '  <node pkg="controller_manager" exec="spawner" args="diff_drive_controller"/>\n')


@pytest.mark.parametrize("script,severity", [
    ("from sensor_msgs.msg import JointState\n", "info"),  # may publish them: not failed
    ("from sensor_msgs.msg import BatteryState\n", "warning"),  # read, supplies nothing: the world is understood
])
def test_a_projects_own_script_is_read_when_it_is_in_the_workspace(tmp_path, script, severity):
    d = description_ws(tmp_path, CONTROL_NODES + '  <node pkg="bot_description" exec="helper_node.py"/>\n')
    write(d / "config" / "c.yaml", CONTROLLERS)
    write(d / "scripts" / "helper_node.py", "#!/usr/bin/env python3\nimport rclpy\n" + script)
    _, report = lint_json([], cwd=d)
    assert [x["severity"] for x in by_code(report, "C003")] == [severity], report["findings"]


def test_a_launch_file_included_by_an_unfollowed_include_is_not_a_closed_world(tmp_path):
    """bringup includes the description launch file only under a condition that is false by default: the
    description launch file is a deployment of its own, and whoever includes it may supply the joint states."""
    d = description_ws(tmp_path, CONTROL_NODES)
    write(d / "config" / "c.yaml", CONTROLLERS)
    b = tmp_path / "bot_bringup"
    write(b / "package.xml", PKG.format("bot_bringup"))
    write(b / "launch" / "bringup.launch.py", '''import os
from ament_index_python.packages import get_package_share_directory
from launch import LaunchDescription
from launch.actions import DeclareLaunchArgument, IncludeLaunchDescription
from launch.conditions import IfCondition
from launch.launch_description_sources import AnyLaunchDescriptionSource
from launch.substitutions import LaunchConfiguration


def generate_launch_description():
    desc = os.path.join(get_package_share_directory('bot_description'), 'launch', 'description.launch.xml')
    return LaunchDescription([
        DeclareLaunchArgument('use_desc', default_value='false'),
        IncludeLaunchDescription(AnyLaunchDescriptionSource(desc),
                                 condition=IfCondition(LaunchConfiguration('use_desc'))),
    ])
''')
    code, report = lint_json([], cwd=tmp_path)
    c003 = by_code(report, "C003")
    assert [x["severity"] for x in c003] == ["info"], report["findings"]
    assert "(not followed to it)" in c003[0]["message"] and "description launch file" not in c003[0]["message"]
    assert code == 0


def test_a_config_listing_the_launch_file_gives_the_same_verdict(tmp_path):
    """Zero config and a config that lists the same launch file agree: an unknown node makes the absence an
    info in both."""
    d = description_ws(tmp_path, CONTROL_NODES + '  <node pkg="bot_description" exec="my_joint_publisher.py"/>\n')
    write(d / "config" / "c.yaml", CONTROLLERS)
    _, plain = lint_json([], cwd=d)
    write(d / "urdfcheck.yaml", "models:\n  - path: urdf/bot.urdf\n    controllers: [config/c.yaml]\n"
                                "    launch: [launch/description.launch.xml]\npackages: {bot_description: .}\n")
    from tests.conftest import run_cli

    code, out, err = run_cli(["lint", "--format", "json"], cwd=d)
    import json

    configured = json.loads(out)
    assert [x["severity"] for x in by_code(plain, "C003")] == ["info"], plain["findings"]
    assert [x["severity"] for x in by_code(configured, "C003")] == ["info"], configured["findings"]
    assert code == 0, err


SEED_LAB_LAUNCH = """<launch>
  <arg name="use_camera" default="true"/>
  <param name="robot_description"
         command="$(find xacro)/xacro '$(find agv_description)/urdf/agv.urdf.xacro' use_camera:=$(arg use_camera)"/>
  <node pkg="robot_state_publisher" type="robot_state_publisher" name="robot_state_publisher"/>
  <node pkg="tf2_ros" type="static_transform_publisher" name="map_to_odom" args="0 0 0 0 0 0 map odom"/>
  {odom}
</launch>
"""


@pytest.mark.parametrize("odom,severity", [
    ('<node pkg="ros1_tf_lab" type="odom_tf_broadcaster" name="odom_tf_broadcaster"/>', "info"),
    ('<node pkg="controller_manager" type="spawner" name="spawner" args="joint_state_controller"/>', "warning"),
])
def test_seed_tf_ownership_odom_from_its_own_broadcaster(tmp_path, odom, severity):
    """The seed tutorial's ownership table: map -> odom from a static publisher, odom -> base_link from the
    tutorial's own odom_tf_broadcaster (a node the tool cannot read), base_link -> sensors from
    robot_state_publisher. With the broadcaster in the launch file, T005 is an info naming it; with only known
    nodes beside robot_state_publisher (a spawner), nothing can publish odom -> base_link and T005 warns."""
    ws = seed(tmp_path)
    write(ws / "launch" / "description.launch", SEED_LAB_LAUNCH.format(odom=odom))
    _, report = lint_json([], cwd=ws)
    t005 = by_code(report, "T005")
    assert t005 and {x["severity"] for x in t005} == {severity}, report["findings"]
    if severity == "info":
        assert "`odom_tf_broadcaster`" in t005[0]["message"]


EKF = """ekf_filter_node:
  ros__parameters:
    frequency: 30.0
    world_frame: odom
    base_link_frame: base_link
    odom0: /diff_drive_controller/odom
"""


def test_seed_odom_owned_twice_in_unlaunched_parameter_files_is_found(tmp_path):
    """Issue 37's seed miss: the package's controller file keeps enable_odom_tf and its EKF file (publish_tf by
    default) fuses that controller's odometry; no launch file names either. Both publish odom -> base_link."""
    ws = seed(tmp_path)
    write(ws / "config" / "ekf.yaml", EKF)
    rc, report = lint_json([], cwd=ws)
    got = [(f["code"], f["severity"], f["location"]["file"]) for f in report["findings"]]
    assert ("T001", "error", CTRL) in got, got
    assert rc == 1


def test_seed_odom_owners_not_known_to_run_together_are_said_as_info(tmp_path):
    """Without the filter fusing the controller's odometry, that the two files run together is a guess from the
    package: said at info, naming the step and how to confirm it."""
    ws = seed(tmp_path)
    write(ws / "config" / "ekf.yaml", EKF.replace("odom0: /diff_drive_controller/odom", "odom0: /wheel/odometry"))
    rc, report = lint_json([], cwd=ws)
    t001 = [f for f in report["findings"] if f["code"] == "T001"]
    assert t001 and all(f["severity"] == "info" and "same package" in f["message"] for f in t001), t001
    assert _failing(report) == [], report["findings"]


@pytest.mark.parametrize("frame", ["os_imu", "velodyne", "imu_optical_frame"])
def test_a_driver_frame_that_only_resembles_a_link_is_no_typo(tmp_path, frame):
    """A lidar driver's own IMU frame (ouster's os_imu) resembles imu_link but is no misspelling of it: no
    "did you mean", so no warning (the driver may publish the frame itself)."""
    ws = seed(tmp_path)
    edit(ws / DRV, "imu_frame_id: imu_link", f"imu_frame_id: {frame}")
    rc, report = lint_json([], cwd=ws)
    c020 = [f for f in report["findings"] if f["code"] == "C020"]
    assert all("did you mean" not in f["message"] and f["severity"] == "info" for f in c020), c020
    assert _failing(report) == [], report["findings"]
