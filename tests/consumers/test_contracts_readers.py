"""Controller, driver, localization and discovery readers, on hand-written files and on the corpus."""
import sys
from pathlib import Path

SRC = Path(__file__).resolve().parents[2] / "src"
if str(SRC) not in sys.path:  # runnable without an editable install
    sys.path.insert(0, str(SRC))

import pytest  # noqa: E402

from urdfcheck.consumers.controllers import (  # noqa: E402
    DIFF_DRIVE,
    FORWARD,
    JSB,
    JSC,
    JTC,
    DriverSpec,
    load_controllers,
    read_controllers,
    read_driver,
)
from urdfcheck.consumers.localization import localization_from_params  # noqa: E402
from urdfcheck.consumers.params import parse_params, read_params  # noqa: E402
from urdfcheck.load.discover import discover  # noqa: E402

DDC = "ros-controls+ros_controllers/diff_drive_controller/test"


def ctrls(*texts):
    return read_controllers([parse_params(t, f"f{i}.yaml") for i, t in enumerate(texts)])


# --- ROS 2 controllers ---------------------------------------------------------------------------------------
def test_ros2_manager_and_own_sections():
    cs = ctrls("""\
controller_manager:
  ros__parameters:
    update_rate: 100
    joint_state_broadcaster:
      type: joint_state_broadcaster/JointStateBroadcaster
    arm_controller:
      type: joint_trajectory_controller/JointTrajectoryController
arm_controller:
  ros__parameters:
    joints: [j1, j2]
    command_interfaces: [position]
    state_interfaces: [position, velocity]
base:
  ros__parameters:
    type: diff_drive_controller/DiffDriveController
    left_wheel_names: [l]
    right_wheel_names: [r]
    wheel_separation: 0.5
    wheel_radius: 0.1
    wheel_separation_multiplier: 1.1
    position_feedback: false
""")
    assert {c.name: c.kind for c in cs} == {"joint_state_broadcaster": JSB, "arm_controller": JTC, "base": DIFF_DRIVE}
    arm = cs.by_name("arm_controller")
    assert [(u.joint, u.command, u.state) for u in arm.joints] == [
        ("j1", ("position",), ("position", "velocity")), ("j2", ("position",), ("position", "velocity"))]
    assert arm.joints[1].loc.line == 10
    assert cs.by_name("joint_state_broadcaster").broadcasts_all
    base = cs.by_name("base")
    assert base.joints[0].state == ("velocity",)  # position_feedback false
    assert base.drive.separation == pytest.approx(0.55)
    assert base.drive.radius("left") == pytest.approx(0.1)
    assert (base.odom_tf.parent, base.odom_tf.child, base.odom_tf.enabled) == ("odom", "base_link", True)


def test_tf_prefix_and_namespaces():
    cs = ctrls("""\
/robot1/base:
  ros__parameters:
    type: diff_drive_controller/DiffDriveController
    left_wheel_names: [l]
    right_wheel_names: [r]
    tf_frame_prefix_enable: true
    odom_frame_id: /odom
/robot2/base:
  ros__parameters:
    type: diff_drive_controller/DiffDriveController
    left_wheel_names: [l]
    right_wheel_names: [r]
    tf_frame_prefix: "~"
    enable_odom_tf: false
""")
    r1, r2 = cs.controllers["/robot1/base"], cs.controllers["/robot2/base"]
    assert (r1.odom_tf.parent, r1.odom_tf.child) == ("robot1/odom", "robot1/base_link")
    assert (r2.odom_tf.parent, r2.odom_tf.enabled) == ("robot2/odom", False)


def test_wildcard_templates_apply_to_concrete_nodes(corpus):
    cs, errs = load_controllers([corpus / "ros-controls+ros2_control_demos/example_15/bringup/config/"
                                 "multi_controller_manager_rrbot_generic_controllers.yaml"])
    assert not errs
    fwd = cs.controllers["/rrbot_1/forward_position_controller"]
    assert fwd.kind == FORWARD
    assert [(u.joint, u.command) for u in fwd.joints] == [("rrbot_1_joint1", ("position",)),
                                                          ("rrbot_1_joint2", ("position",))]
    assert "/rrbot_2/position_trajectory_controller" in cs.controllers


def test_chained_controllers_resolve_to_joints(corpus):
    cs, _ = load_controllers([corpus / "ros-controls+ros2_control_demos/example_16/bringup/config/"
                                       "diffbot_chained_controllers.yaml"])
    dd = cs.by_name("diffbot_base_controller")
    assert ([(u.joint, u.via, u.command) for u in dd.drive.left]
            == [("left_wheel_joint", "pid_controller_left_wheel_joint", ())])


def test_every_corpus_controller_file_reads(corpus):
    files = sorted((corpus / "ros-controls+ros2_control_demos").rglob("config/*.yaml"))
    files += sorted((corpus / DDC).glob("*.yaml"))
    assert len(files) > 30
    kinds = set()
    for f in files:
        cs, errs = load_controllers([f])
        assert not errs, errs
        kinds |= {c.kind for c in cs}
    assert {DIFF_DRIVE, JTC, JSB, FORWARD} <= kinds
    dd = [c for f in files for c in load_controllers([f])[0] if c.kind == DIFF_DRIVE]
    assert any(c.ros == 1 for c in dd) and any(c.ros == 2 for c in dd)


# --- ROS 1 controllers ---------------------------------------------------------------------------------------
def test_ros1_diff_drive_files_merge_in_order(corpus):
    d = corpus / DDC
    cs = read_controllers([read_params(d / "diffbot_controllers.yaml"),
                           read_params(d / "diffbot_left_right_multipliers.yaml")])
    c = cs.by_name("diffbot_controller")
    assert c.ros == 1 and c.kind == DIFF_DRIVE
    assert ([u.joint for u in c.drive.left] == ["wheel_0_joint"]
            and [u.joint for u in c.drive.right] == ["wheel_1_joint"])
    assert c.drive.from_urdf and c.drive.wheel_separation is None
    assert c.drive.left_radius_multiplier.value == 1.4
    assert c.drive.separation_multiplier.value == 2.3
    assert c.drive.left_radius_multiplier.loc.file.endswith("diffbot_left_right_multipliers.yaml")


def test_ros1_single_multiplier_applies_to_both_sides(corpus):
    d = corpus / DDC
    cs = read_controllers([read_params(d / "diffbot_controllers.yaml"), read_params(d / "diffbot_multipliers.yaml")])
    drive = cs.by_name("diffbot_controller").drive
    assert drive.left_radius_multiplier.value == drive.right_radius_multiplier.value == 1.4


def test_skidsteer_no_wheels_reads_an_empty_side(corpus):
    cs, errs = load_controllers([corpus / DDC / "skidsteerbot_no_wheels.yaml"])
    drive = cs.by_name("skidsteerbot_controller").drive
    assert drive.left == () and [u.joint for u in drive.right] == ["wheel_3_joint", "wheel_4_joint", "wheel_5_joint"]
    assert drive.right[1].loc.column > drive.right[0].loc.column  # each list item has its own column


def test_ros1_joint_state_controller_and_group_controllers():
    cs = ctrls("jsc:\n  type: joint_state_controller/JointStateController\n"
               "arm:\n  type: effort_controllers/JointTrajectoryController\n  joints: [a, b]\n"
               "grip:\n  type: position_controllers/JointPositionController\n  joint: g\n")
    assert cs.by_name("jsc").kind == JSC and cs.by_name("jsc").broadcasts_all
    assert [u.joint for u in cs.by_name("arm").joints] == ["a", "b"]
    assert [u.joint for u in cs.by_name("grip").joints] == ["g"]


# --- custom drivers -------------------------------------------------------------------------------------------
def test_custom_driver_by_key_paths(tmp_path):
    f = tmp_path / "drv.yaml"
    f.write_text("left_wheel_joint: lw\nright_wheel_joint: rw\nwheel_separation: 0.5\nwheel_radius: 0.1\n"
                 "imu_frame_id: imu_link\npublish_odom_tf: true\n")
    drv = read_driver(DriverSpec(str(f), joints=("left_wheel_joint", "right_wheel_joint"),
                                 left_wheels=("left_wheel_joint",), right_wheels=("right_wheel_joint",),
                                 wheel_separation="wheel_separation", wheel_radius="wheel_radius",
                                 frames=("imu_frame_id", "gps_frame_id"), odom_tf="publish_odom_tf"))
    assert [u.joint for u in drv.joints] == ["lw", "rw"]
    assert drv.drive.separation == 0.5 and drv.drive.radius("right") == 0.1
    assert [v.value for v in drv.frames] == ["imu_link"]
    assert drv.odom_tf.enabled and drv.odom_tf.parent == "odom"
    assert [k for k, _ in drv.missing] == ["gps_frame_id"]


def test_turtlebot3_driver_with_node_and_nested_keys(corpus):
    f = corpus / "ROBOTIS-GIT+turtlebot3/turtlebot3_bringup/param/burger.yaml"
    drv = read_driver(DriverSpec(str(f), node="turtlebot3_node", wheel_separation="wheels.separation",
                                 wheel_radius="wheels.radius"))
    assert drv.drive.separation == pytest.approx(0.16) and drv.drive.radius("left") == pytest.approx(0.033)
    odom = read_driver(DriverSpec(str(f), node="diff_drive_controller", odom_tf="odometry.publish_tf",
                                  odom_frame="odometry.frame_id", base_frame="odometry.child_frame_id"))
    assert (odom.odom_tf.parent, odom.odom_tf.child, odom.odom_tf.enabled) == ("odom", "base_footprint", True)


# --- localization ---------------------------------------------------------------------------------------------
def test_robot_localization_edges():
    pf = parse_params("""\
ekf_odom:
  ros__parameters:
    two_d_mode: true
    odom0: /wheel/odometry
    frequency: 30.0
ekf_map:
  ros__parameters:
    world_frame: map
    base_link_frame: base_footprint
ukf_quiet:
  ros__parameters:
    world_frame: odom
    publish_tf: false
""", "ekf.yaml")
    nodes = {n.node: n for n in localization_from_params([pf])}
    assert nodes["/ekf_odom"].edge() == ("odom", "base_link")
    assert nodes["/ekf_map"].edge() == ("map", "odom")
    assert nodes["/ekf_map"].edge_loc.line == 8
    assert nodes["/ukf_quiet"].kind == "ukf" and nodes["/ukf_quiet"].edge() is None


def test_amcl_from_nav2_params(corpus):
    pf = read_params(corpus / "ROBOTIS-GIT+turtlebot3/turtlebot3_navigation2/param/burger.yaml")
    amcl = [n for n in localization_from_params([pf]) if n.kind == "amcl"]
    assert len(amcl) == 1 and amcl[0].edge() == ("map", "odom")
    assert amcl[0].base_frame.value == "base_footprint"


def test_ros1_ekf_at_top_level():
    pf = parse_params("frequency: 30\nworld_frame: odom\nodom0: wheel\nbase_link_frame: base_footprint\n", "ekf.yaml")
    (n,) = localization_from_params([pf])
    assert n.edge() == ("odom", "base_footprint")


# --- discovery ------------------------------------------------------------------------------------------------
def test_discovery_of_a_package(tmp_path):
    (tmp_path / "urdf" / "inc").mkdir(parents=True)
    (tmp_path / "config").mkdir()
    (tmp_path / "launch").mkdir()
    (tmp_path / "build").mkdir()
    (tmp_path / "urdf" / "robot.urdf.xacro").write_text(
        '<robot name="r" xmlns:xacro="http://www.ros.org/wiki/xacro">\n'
        '  <xacro:include filename="$(find pkg)/urdf/inc/parts.xacro"/>\n'
        '  <xacro:include filename="lib.xacro"/>\n  <link name="base_link"/>\n</robot>\n')
    (tmp_path / "urdf" / "inc" / "parts.xacro").write_text(
        '<robot xmlns:xacro="http://www.ros.org/wiki/xacro"><link name="x"/></robot>')
    (tmp_path / "urdf" / "lib.xacro").write_text(
        '<robot xmlns:xacro="http://www.ros.org/wiki/xacro"><link name="y"/></robot>')
    (tmp_path / "urdf" / "macros_only.xacro").write_text(
        '<?xml version="1.0"?>\n<!-- <robot> in a comment -->\n<robot xmlns:xacro="http://www.ros.org/wiki/xacro">'
        '<xacro:macro name="m" params=""><link name="z"/></xacro:macro></robot>')
    (tmp_path / "urdf" / "plain.urdf").write_text('<robot name="p"><link name="a"/></robot>')
    (tmp_path / "urdf" / "notrobot.xacro").write_text('<launch/>')
    (tmp_path / "config" / "c.yaml").write_text("a: 1\n")
    (tmp_path / "launch" / "a.launch.py").write_text("")
    (tmp_path / "launch" / "b.launch.xml").write_text("<launch/>")
    (tmp_path / "launch" / "notes.txt").write_text("")
    (tmp_path / "build" / "x.urdf").write_text("<robot/>")
    (tmp_path / "build" / "COLCON_IGNORE").write_text("")  # colcon's build base: skipped by its marker, not its name
    d = discover(tmp_path)
    rel = lambda xs: [str(Path(x).relative_to(tmp_path)) for x in xs]  # noqa: E731
    assert rel(d.models) == ["urdf/plain.urdf", "urdf/robot.urdf.xacro"]
    assert rel(d.params) == ["config/c.yaml"]
    assert rel(d.launch) == ["launch/a.launch.py", "launch/b.launch.xml"]
    assert set(rel(d.libraries)) == {"urdf/inc/parts.xacro", "urdf/lib.xacro", "urdf/macros_only.xacro",
                                     "urdf/notrobot.xacro"}


def test_discovery_on_corpus(corpus):
    d = discover(corpus / "ros-controls+ros_controllers/diff_drive_controller")
    names = [Path(m).name for m in d.models]
    assert "diffbot_bad.xacro" in names and "diffbot.xacro" in names
    assert "wheel.xacro" not in names  # included by diffbot.xacro through $(find ...)
    demos = discover(corpus / "ros-controls+ros2_control_demos/example_2")
    assert [Path(m).name for m in demos.models] == ["diffbot.urdf.xacro"]
    assert [Path(p).name for p in demos.params] == ["diffbot_controllers.yaml"]
    assert [Path(p).name for p in demos.launch] == ["diffbot.launch.xml"]
    assert d == discover(corpus / "ros-controls+ros_controllers/diff_drive_controller")  # deterministic
