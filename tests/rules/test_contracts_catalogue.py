"""Issue 26: every controller family of the catalogue, every Gazebo TF owner, wheel directions by FK.

Each case is a small package with one seeded defect and its clean twin, linted through the real CLI with zero
config: the defect is found at its YAML/URDF line with its code, the twin has no finding of that code."""
import sys
from pathlib import Path

SRC = Path(__file__).resolve().parents[2] / "src"
if str(SRC) not in sys.path:
    sys.path.insert(0, str(SRC))

import pytest  # noqa: E402
from conftest import lint_json  # noqa: E402
from pkgs import arm_joint, gazebo, r2c, robot, steer, wheel, write  # noqa: E402

MANAGER = """controller_manager:
  ros__parameters:
    update_rate: 50
    joint_state_broadcaster:
      type: joint_state_broadcaster/JointStateBroadcaster
    {name}:
      type: {type}

{name}:
  ros__parameters:
{params}"""


def _yaml(params, indent):
    import json

    out = ""
    for k, v in params.items():
        if isinstance(v, dict):
            out += " " * indent + f"{k}:\n" + _yaml(v, indent + 2)
        else:
            out += " " * indent + f"{k}: {json.dumps(v)}\n"
    return out


def ctrl(name, type_, **params):
    return MANAGER.format(name=name, type=type_, params=_yaml(params, 4))


def line_of(text, needle):
    """The last line containing `needle` (the controller's own parameters follow the manager's list)."""
    found = [i for i, ln in enumerate(text.splitlines(), 1) if needle in ln]
    assert found, needle
    return found[-1]


def lint(tmp, urdf, files):
    path = write(tmp, urdf, files)
    code, report = lint_json([str(path)])
    return report["findings"]


def hits(findings, code):
    return [(Path(f["location"]["file"]).name, f["location"]["line"], f["severity"], f["message"])
            for f in findings if f["code"] == code]


def twin(tmp_path, code, urdf_bad, files_bad, urdf_good, files_good, where):
    """The seeded defect gives `code` at `where` (file name, line); the twin gives no `code`."""
    bad = hits(lint(tmp_path / "bad", urdf_bad, files_bad), code)
    good = hits(lint(tmp_path / "good", urdf_good, files_good), code)
    assert sorted({(f, ln) for f, ln, *_ in bad}) == [where], bad
    assert good == [], good
    return bad[0]


ARM = robot(arm_joint("joint1", "base_link", "l1"), arm_joint("joint2", "l1", "l2"),
            arm_joint("finger_joint", "l2", "finger", kind="prismatic"),
            r2c({"joint1": (["position"], ["position", "velocity"]), "joint2": (["position"], ["position", "velocity"]),
                 "finger_joint": (["position"], ["position", "velocity"])}, sensors=["ft", "imu_sensor"],
                gpios=["flash"]))


# --- joints named by the catalogue's families -----------------------------------------------------------------
JOINT_CASES = {
    "gripper_action": ("gripper_controller", "position_controllers/GripperActionController",
                       {"joint": "{j}"}, "finger_joint", "finger_jnt"),
    "gripper_action_new": ("gripper_controller", "gripper_action_controller/GripperActionController",
                           {"joint": "{j}"}, "finger_joint", "finger_jnt"),
    "parallel_gripper": ("gripper_controller", "parallel_gripper_action_controller/GripperActionController",
                         {"joint": "{j}"}, "finger_joint", "finger_jnt"),
    "admittance": ("admittance_controller", "admittance_controller/AdmittanceController",
                   {"joints": ["joint1", "{j}"], "command_interfaces": ["position"],
                    "state_interfaces": ["position", "velocity"]}, "joint2", "jointX"),
    "pid": ("pid_controller", "pid_controller/PidController",
            {"dof_names": ["{j}"], "command_interface": "position",
             "reference_and_state_interfaces": ["position"]}, "joint2", "joint_9"),
    "jtc_command_joints": ("arm_controller", "joint_trajectory_controller/JointTrajectoryController",
                           {"joints": ["joint1"], "command_joints": ["{j}"], "command_interfaces": ["position"],
                            "state_interfaces": ["position"]}, "joint1", "joint_1"),
    "ur_scaled_jtc": ("scaled_joint_trajectory_controller", "ur_controllers/ScaledJointTrajectoryController",
                      {"joints": ["joint1", "{j}"], "command_interfaces": ["position"],
                       "state_interfaces": ["position"]}, "joint2", "wrist_9_joint"),
    "ur_passthrough": ("passthrough_trajectory_controller", "ur_controllers/PassthroughTrajectoryController",
                       {"joints": ["joint1", "{j}"], "state_interfaces": ["position"]}, "joint2", "elbow_joint"),
}


def _fill(params, j):
    out = {}
    for k, v in params.items():
        out[k] = [j if x == "{j}" else x for x in v] if isinstance(v, list) else (j if v == "{j}" else v)
    return out


@pytest.mark.parametrize("case", sorted(JOINT_CASES))
def test_family_names_an_unknown_joint(tmp_path, case):
    name, type_, params, good, bad = JOINT_CASES[case]
    bad_yaml = ctrl(name, type_, **_fill(params, bad))
    good_yaml = ctrl(name, type_, **_fill(params, good))
    where = ("controllers.yaml", line_of(bad_yaml, bad))
    f = twin(tmp_path, "C001", ARM, {"config/controllers.yaml": bad_yaml}, ARM, {"config/controllers.yaml": good_yaml},
             where)
    assert f[2] == "error" and bad in f[3]


def test_forward_command_interface_name_is_compared(tmp_path):
    bad = ctrl("fwd", "forward_command_controller/ForwardCommandController", joints=["joint1"], interface_name="effort")
    good = ctrl("fwd", "forward_command_controller/ForwardCommandController", joints=["joint1"],
                interface_name="position")
    twin(tmp_path, "C005", ARM, {"config/controllers.yaml": bad}, ARM, {"config/controllers.yaml": good},
         ("controllers.yaml", line_of(bad, "joint1")))


def test_admittance_interfaces_are_compared(tmp_path):
    bad = ctrl("adm", "admittance_controller/AdmittanceController", joints=["joint1"], command_interfaces=["velocity"],
               state_interfaces=["position"])
    good = ctrl("adm", "admittance_controller/AdmittanceController", joints=["joint1"],
                command_interfaces=["position"], state_interfaces=["position"])
    twin(tmp_path, "C005", ARM, {"config/controllers.yaml": bad}, ARM, {"config/controllers.yaml": good},
         ("controllers.yaml", line_of(bad, "joint1")))


# --- sensors, GPIOs, frames -------------------------------------------------------------------------------------
@pytest.mark.parametrize("type_,key,good,bad", [
    ("imu_sensor_broadcaster/IMUSensorBroadcaster", "sensor_name", "imu_sensor", "imu"),
    ("force_torque_sensor_broadcaster/ForceTorqueSensorBroadcaster", "sensor_name", "ft", "ft_sensor"),
    ("range_sensor_broadcaster/RangeSensorBroadcaster", "sensor_name", "imu_sensor", "range1"),
    ("gpio_controllers/GpioCommandController", "gpios", ["flash"], ["flash", "horn"]),
], ids=["imu", "force_torque", "range", "gpio"])
def test_unknown_sensor_or_gpio(tmp_path, type_, key, good, bad):
    b = ctrl("bc", type_, **{key: bad, "frame_id": "base_link"})
    g = ctrl("bc", type_, **{key: good, "frame_id": "base_link"})
    twin(tmp_path, "C017", ARM, {"config/controllers.yaml": b}, ARM, {"config/controllers.yaml": g},
         ("controllers.yaml", line_of(b, f"{key}:")))


def test_sensor_name_prefixed_by_the_namespace_at_run_time(tmp_path):
    """husarion's imu_sensor_broadcaster puts the node's namespace before sensor_name
    (use_namespace_as_sensor_name_prefix): `imu_sensor` names `/imu_sensor` or `robot1/imu_sensor` at run time, so
    it is compared by its last segment; without the switch the name must match, and a wrong one stays C017."""
    spaced = NS_ARM
    b = ctrl("bc", "imu_sensor_broadcaster/IMUSensorBroadcaster", sensor_name="imu",
             use_namespace_as_sensor_name_prefix=True, frame_id="base_link")
    g = ctrl("bc", "imu_sensor_broadcaster/IMUSensorBroadcaster", sensor_name="imu_sensor",
             use_namespace_as_sensor_name_prefix=True, frame_id="base_link")
    twin(tmp_path, "C017", spaced, {"config/controllers.yaml": b}, spaced, {"config/controllers.yaml": g},
         ("controllers.yaml", line_of(b, "sensor_name:")))


NS_ARM = robot(arm_joint("joint1", "base_link", "l1"),
               r2c({"joint1": (["position"], ["position"])}, sensors=["/imu_sensor"]))


@pytest.mark.parametrize("type_,extra", [
    ("imu_sensor_broadcaster/IMUSensorBroadcaster", {"sensor_name": "imu_sensor"}),
    ("force_torque_sensor_broadcaster/ForceTorqueSensorBroadcaster", {"sensor_name": "ft"}),
    ("pose_broadcaster/PoseBroadcaster", {"pose_name": "ft"}),
], ids=["imu", "force_torque", "pose"])
def test_broadcaster_frame_id(tmp_path, type_, extra):
    b = ctrl("bc", type_, frame_id="tool_frame", **extra)
    g = ctrl("bc", type_, frame_id="l2", **extra)
    twin(tmp_path, "C020", ARM, {"config/controllers.yaml": b}, ARM, {"config/controllers.yaml": g},
         ("controllers.yaml", line_of(b, "tool_frame")))


def test_unknown_type_is_read_by_key_shape_as_a_warning(tmp_path):
    b = ctrl("mine", "my_pkg/MyController", arm_joints=["joint1", "jointZ"])
    g = ctrl("mine", "my_pkg/MyController", arm_joints=["joint1", "joint2"])
    f = twin(tmp_path, "C001", ARM, {"config/controllers.yaml": b}, ARM, {"config/controllers.yaml": g},
             ("controllers.yaml", line_of(b, "jointZ")))
    assert f[2] == "warning" and "not in urdfcheck's controller catalogue" in f[3]


def test_ros1_ackermann_names_joints(tmp_path):
    urdf = robot(wheel("rear_wheel", "-0.2 0 0"), steer("front_steer", "0.3 0 0"))
    y = "ackermann:\n  type: ackermann_steering_controller/AckermannSteeringController\n  rear_wheel: {r}\n" \
        "  front_steer: front_steer_joint\n  wheel_separation_h: 0.5\n  wheel_radius: 0.05\n"
    b, g = y.format(r="rear_whel_joint"), y.format(r="rear_wheel_joint")
    twin(tmp_path, "C001", urdf, {"config/ackermann.yaml": b}, urdf, {"config/ackermann.yaml": g},
         ("ackermann.yaml", 3))


# --- wheeled drives ------------------------------------------------------------------------------------------
def _r2c_wheels(names, steering=()):
    j = {n: (["velocity"], ["position", "velocity"]) for n in names}
    j.update({n: (["position"], ["position"]) for n in steering})
    return r2c(j)


CAR = [wheel("rear_left_wheel", "-0.2 0.2 0"), wheel("rear_right_wheel", "-0.2 -0.2 0"),
       steer("front_left_steer", "0.3 0.2 0"), steer("front_right_steer", "0.3 -0.2 0")]
CAR_R2C = _r2c_wheels(["rear_left_wheel_joint", "rear_right_wheel_joint"],
                      ["front_left_steer_joint", "front_right_steer_joint"])


def steering(type_, wheelbase=0.5, track=0.4, radius=0.05, **more):
    params = {"traction_joints_names": ["rear_right_wheel_joint", "rear_left_wheel_joint"],
              "steering_joints_names": ["front_right_steer_joint", "front_left_steer_joint"],
              "wheelbase": wheelbase, "traction_track_width": track, "traction_wheels_radius": radius,
              "position_feedback": True}
    params.update(more)
    return ctrl("steer", type_, **params)


@pytest.mark.parametrize("type_", ["ackermann_steering_controller/AckermannSteeringController",
                                   "tricycle_steering_controller/TricycleSteeringController"])
@pytest.mark.parametrize("defect", ["wheelbase", "track", "radius", "reversed"])
def test_steering_controllers(tmp_path, type_, defect):
    urdf = robot(*CAR, CAR_R2C)
    good = steering(type_)
    code, where, bad_urdf, bad = {
        "wheelbase": ("C016", "wheelbase", urdf, steering(type_, wheelbase=0.7)),
        "track": ("C010", "traction_track_width", urdf, steering(type_, track=0.5)),
        "radius": ("C011", "traction_wheels_radius", urdf, steering(type_, radius=0.08)),
        "reversed": ("C015", None, robot(CAR[0], wheel("rear_right_wheel", "-0.2 -0.2 0", axis="0 -1 0"), *CAR[2:],
                                          CAR_R2C), good),
    }[defect]
    if where is None:
        at = ("bot.urdf", line_of(bad_urdf, 'joint name="rear_right_wheel_joint" type'))
    else:
        at = ("controllers.yaml", line_of(bad, where + ":"))
    twin(tmp_path, code, bad_urdf, {"config/controllers.yaml": bad}, urdf, {"config/controllers.yaml": good}, at)


def test_bicycle_and_tricycle_wheelbase(tmp_path):
    urdf = robot(wheel("rear_wheel", "-0.2 0 0"), steer("front_steer", "0.3 0 0"),
                 _r2c_wheels(["rear_wheel_joint"], ["front_steer_joint"]))
    for i, (type_, params) in enumerate([
        ("bicycle_steering_controller/BicycleSteeringController",
         {"traction_joints_names": ["rear_wheel_joint"], "steering_joints_names": ["front_steer_joint"],
          "traction_wheel_radius": 0.05}),
        ("tricycle_controller/TricycleController",
         {"traction_joint_name": "rear_wheel_joint", "steering_joint_name": "front_steer_joint",
          "wheel_radius": 0.05}),
    ]):
        b = ctrl("drive", type_, wheelbase=0.6, **params)
        g = ctrl("drive", type_, wheelbase=0.5, **params)
        twin(tmp_path / str(i), "C016", urdf, {"config/controllers.yaml": b}, urdf, {"config/controllers.yaml": g},
             ("controllers.yaml", line_of(b, "wheelbase")))


MECANUM = [wheel("front_left_wheel", "0.2 0.25 0"), wheel("front_right_wheel", "0.2 -0.25 0"),
           wheel("rear_left_wheel", "-0.2 0.25 0"), wheel("rear_right_wheel", "-0.2 -0.25 0")]
MEC_R2C = _r2c_wheels([f"{w}_wheel_joint" for w in ("front_left", "front_right", "rear_left", "rear_right")])


def mecanum(radius=0.05, proj=0.45):
    return ctrl("mecanum", "mecanum_drive_controller/MecanumDriveController",
                front_left_wheel_command_joint_name="front_left_wheel_joint",
                front_right_wheel_command_joint_name="front_right_wheel_joint",
                rear_right_wheel_command_joint_name="rear_right_wheel_joint",
                rear_left_wheel_command_joint_name="rear_left_wheel_joint",
                kinematics={"wheels_radius": radius, "sum_of_robot_center_projection_on_X_Y_axis": proj})


@pytest.mark.parametrize("defect", ["radius", "projection", "reversed", "joint"])
def test_mecanum(tmp_path, defect):
    urdf = robot(*MECANUM, MEC_R2C)
    good = mecanum()
    rev = robot(*MECANUM[:3], wheel("rear_right_wheel", "-0.2 -0.25 0", axis="0 -1 0"), MEC_R2C)
    code, bad_urdf, bad, at = {
        "radius": ("C011", urdf, mecanum(radius=0.06), ("controllers.yaml", None, "wheels_radius")),
        "projection": ("C016", urdf, mecanum(proj=0.5), ("controllers.yaml", None, "sum_of_robot")),
        "reversed": ("C015", rev, good, ("bot.urdf", None, 'joint name="rear_right_wheel_joint" type')),
        "joint": ("C001", urdf, good.replace('rear_left_wheel_command_joint_name: "rear_left_wheel_joint"',
                                             'rear_left_wheel_command_joint_name: "rear_left_joint"'),
                  ("controllers.yaml", None, "rear_left_joint")),
    }[defect]
    text = bad_urdf if at[0] == "bot.urdf" else bad
    twin(tmp_path, code, bad_urdf, {"config/controllers.yaml": bad}, urdf, {"config/controllers.yaml": good},
         (at[0], line_of(text, at[2])))


DIFF = ctrl("diff_drive_controller", "diff_drive_controller/DiffDriveController",
            left_wheel_names=["left_wheel_joint"], right_wheel_names=["right_wheel_joint"], wheel_separation=0.4,
            wheel_radius=0.05)
DD_R2C = _r2c_wheels(["left_wheel_joint", "right_wheel_joint"])


def test_diff_drive_reversed_right_wheel_and_mirrored_twin(tmp_path):
    bad = robot(wheel("left_wheel", "0 0.2 0"), wheel("right_wheel", "0 -0.2 0", axis="0 -1 0"), DD_R2C)
    # the same right wheel in a mirrored frame (yaw pi) with the flipped axis: the effective axis is +y again
    good = robot(wheel("left_wheel", "0 0.2 0"), wheel("right_wheel", "0 -0.2 0", axis="0 -1 0", rpy="0 0 3.14159265"),
                 DD_R2C)
    f = twin(tmp_path, "C015", bad, {"config/controllers.yaml": DIFF}, good, {"config/controllers.yaml": DIFF},
             ("bot.urdf", line_of(bad, 'joint name="right_wheel_joint" type')))
    assert "spins in place" in f[3]


# --- Gazebo plugins ---------------------------------------------------------------------------------------------
DD_PLUGIN = """    <plugin name="diff_drive" filename="libgazebo_ros_diff_drive.so">
      <left_joint>left_wheel_joint</left_joint>
      <right_joint>right_wheel_joint</right_joint>
      <wheel_separation>{sep}</wheel_separation>
      <wheel_diameter>{dia}</wheel_diameter>
      <publish_odom_tf>{tf}</publish_odom_tf>
      <odometry_frame>odom</odometry_frame>
      <robot_base_frame>base_link</robot_base_frame>
    </plugin>
"""
ROS1_PLUGIN = """    <plugin name="diff_drive" filename="libgazebo_ros_diff_drive.so">
      <leftJoint>left_wheel_joint</leftJoint>
      <rightJoint>right_wheel_joint</rightJoint>
      <wheelSeparation>{sep}</wheelSeparation>
      <wheelDiameter>{dia}</wheelDiameter>
      <publishOdomTF>{tf}</publishOdomTF>
      <robotBaseFrame>base_link</robotBaseFrame>
    </plugin>
"""
GZ_PLUGIN = """    <plugin name="gz::sim::systems::DiffDrive" filename="gz-sim-diff-drive-system">
      <left_joint>left_wheel_joint</left_joint>
      <right_joint>right_wheel_joint</right_joint>
      <wheel_separation>{sep}</wheel_separation>
      <wheel_radius>{rad}</wheel_radius>
      <frame_id>odom</frame_id>
      <child_frame_id>base_link</child_frame_id>
    </plugin>
"""
WHEELS = [wheel("left_wheel", "0 0.2 0"), wheel("right_wheel", "0 -0.2 0")]


@pytest.mark.parametrize("plugin,sep_tag,rad_tag", [(DD_PLUGIN, "wheel_separation", "wheel_diameter"),
                                                    (ROS1_PLUGIN, "wheelSeparation", "wheelDiameter"),
                                                    (GZ_PLUGIN, "wheel_separation", "wheel_radius")],
                         ids=["gazebo_ros_diff_drive", "ros1", "gz-sim"])
def test_plugin_wheel_geometry(tmp_path, plugin, sep_tag, rad_tag):
    good = robot(*WHEELS, gazebo(plugin.format(sep=0.4, dia=0.1, rad=0.05, tf="true")))
    bad_sep = robot(*WHEELS, gazebo(plugin.format(sep=0.5, dia=0.1, rad=0.05, tf="true")))
    bad_rad = robot(*WHEELS, gazebo(plugin.format(sep=0.4, dia=0.2, rad=0.1, tf="true")))
    twin(tmp_path / "s", "C010", bad_sep, {}, good, {}, ("bot.urdf", line_of(bad_sep, f"<{sep_tag}>")))
    twin(tmp_path / "r", "C011", bad_rad, {}, good, {}, ("bot.urdf", line_of(bad_rad, f"<{rad_tag}>")))
    rev = robot(WHEELS[0], wheel("right_wheel", "0 -0.2 0", axis="0 -1 0"),
                gazebo(plugin.format(sep=0.4, dia=0.1, rad=0.05, tf="true")))
    twin(tmp_path / "d", "C015", rev, {}, good, {}, ("bot.urdf", line_of(rev, 'joint name="right_wheel_joint" type')))


GZ_R2C_PLUGIN = """    <plugin filename="libgazebo_ros2_control.so" name="gazebo_ros2_control">
      <parameters>$(find bot_description)/config/controllers.yaml</parameters>
    </plugin>
"""


@pytest.mark.parametrize("plugin", [DD_PLUGIN, ROS1_PLUGIN, GZ_PLUGIN], ids=["classic", "ros1", "gz-sim"])
def test_plugin_and_controller_both_own_odom_in_simulation(tmp_path, plugin):
    """gazebo_ros2_control in the model: the controllers run in the simulator beside the plugin: T001 naming both.
    The twin turns the plugin's transform off (classic) or leaves the frames implicit (gz-sim)."""
    on = plugin.format(sep=0.4, dia=0.1, rad=0.05, tf="true")
    off = plugin.format(sep=0.4, dia=0.1, rad=0.05, tf="false").replace("      <frame_id>odom</frame_id>\n", "")
    bad = robot(*WHEELS, DD_R2C.replace("mock_components/GenericSystem", "gazebo_ros2_control/GazeboSystem"),
                gazebo(on + GZ_R2C_PLUGIN))
    good = robot(*WHEELS, DD_R2C.replace("mock_components/GenericSystem", "gazebo_ros2_control/GazeboSystem"),
                 gazebo(off + GZ_R2C_PLUGIN))
    files = {"config/controllers.yaml": DIFF}
    at_line = line_of(bad, "<publish_odom_tf>") if "publish_odom_tf" in plugin else \
        line_of(bad, "<publishOdomTF>") if "publishOdomTF" in plugin else line_of(bad, "gz-sim-diff-drive-system")
    bad_f = lint(tmp_path / "bad", bad, files)
    t001 = [f for f in bad_f if f["code"] == "T001"]
    assert len(t001) == 1, hits(bad_f, "T001")
    msg = t001[0]["message"]
    assert "Gazebo plugin" in msg and "diff_drive_controller" in msg, msg
    lines = {(Path(f["location"]["file"]).name, f["location"]["line"]) for f in t001} | {
        (Path(r["file"]).name, r["line"]) for f in t001 for r in f.get("related", ())}
    assert ("bot.urdf", at_line) in lines, (lines, at_line)
    assert hits(lint(tmp_path / "good", good, files), "T001") == []


def test_real_robot_controllers_are_not_a_second_owner_of_the_plugins_edge(tmp_path):
    """No ros2_control in Gazebo: the controller YAML is the real robot's; the plugin runs only in simulation."""
    urdf = robot(*WHEELS, DD_R2C, gazebo(DD_PLUGIN.format(sep=0.4, dia=0.1, tf="true")))
    f = lint(tmp_path, urdf, {"config/controllers.yaml": DIFF})
    assert hits(f, "T001") == []


def test_two_plugins_own_odom(tmp_path):
    planar = """    <plugin name="move" filename="libgazebo_ros_planar_move.so">
      <publish_odom_tf>{tf}</publish_odom_tf>
      <robot_base_frame>base_link</robot_base_frame>
    </plugin>
"""
    dd = DD_PLUGIN.format(sep=0.4, dia=0.1, tf="true")
    bad = robot(*WHEELS, gazebo(dd + planar.format(tf="true")))
    good = robot(*WHEELS, gazebo(dd + planar.format(tf="false")))
    f = lint(tmp_path / "bad", bad, {})
    t = [x for x in f if x["code"] == "T001"]
    assert len(t) == 1 and "libgazebo_ros_planar_move.so" in t[0]["message"], hits(f, "T001")
    assert hits(lint(tmp_path / "good", good, {}), "T001") == []


def test_plugin_base_frame_not_the_root(tmp_path):
    """The diff-drive plugin's default robot_base_frame is base_footprint: a second tree beside the model's."""
    plugin = DD_PLUGIN.format(sep=0.4, dia=0.1, tf="true")
    bad = robot(*WHEELS, gazebo(plugin.replace("      <robot_base_frame>base_link</robot_base_frame>\n", "")))
    good = robot(*WHEELS, gazebo(plugin))
    f = lint(tmp_path / "bad", bad, {})
    assert hits(f, "T005"), [x["code"] for x in f]
    assert hits(lint(tmp_path / "good", good, {}), "T005") == []


@pytest.mark.parametrize("plugin", [
    """    <plugin name="js" filename="libgazebo_ros_joint_state_publisher.so">
      <joint_name>left_wheel_joint</joint_name>
      <joint_name>right_wheel_joint</joint_name>
    </plugin>
""",
    """    <plugin name="gz::sim::systems::JointStatePublisher" filename="gz-sim-joint-state-publisher-system"/>
""",
], ids=["classic", "gz-sim"])
def test_joint_state_plugins_supply_joint_states(tmp_path, plugin):
    launch = """<launch>
  <node pkg="robot_state_publisher" exec="robot_state_publisher" name="rsp"/>
</launch>
"""
    arm = robot(*WHEELS)
    bad = lint(tmp_path / "bad", arm, {"launch/bringup.launch.xml": launch})
    good = lint(tmp_path / "good", robot(*WHEELS, gazebo(plugin)), {"launch/bringup.launch.xml": launch})
    assert hits(bad, "C003"), [x["code"] for x in bad]
    assert hits(good, "C003") == []


SIM_LAUNCH = """
from launch import LaunchDescription
from launch.substitutions import Command, PathJoinSubstitution
from launch_ros.actions import Node
from launch_ros.substitutions import FindPackageShare


def generate_launch_description():
    urdf = PathJoinSubstitution([FindPackageShare('bot_description'), 'urdf', 'bot.urdf'])
    controllers = PathJoinSubstitution([FindPackageShare('bot_description'), 'config', 'controllers.yaml'])
    return LaunchDescription([
        Node(package='robot_state_publisher', executable='robot_state_publisher',
             parameters=[{'robot_description': Command(['xacro ', urdf])}]),
        Node(package='controller_manager', executable='ros2_control_node', parameters=[controllers]),
        Node(package='controller_manager', executable='spawner', arguments=['diff_drive_controller']),
        Node(package='controller_manager', executable='spawner', arguments=['joint_state_broadcaster']),
%s    ])
"""
SPAWN = "        Node(package='gazebo_ros', executable='spawn_entity.py', arguments=['-topic', 'robot_description']),\n"


@pytest.mark.parametrize("spawns", [True, False], ids=["simulation", "real-robot"])
def test_plugin_and_controller_in_a_launch_file_that_starts_the_simulator(tmp_path, spawns):
    """The deployment (a launch file) spawns the model into Gazebo and starts the controllers: the plugin's
    odom -> base_link and the controller's are two owners (T001). The same launch file without the spawn is the
    real robot: the plugin does not run there."""
    urdf = robot(*WHEELS, DD_R2C, gazebo(DD_PLUGIN.format(sep=0.4, dia=0.1, tf="true")))
    path = write(tmp_path, urdf, {"config/controllers.yaml": DIFF,
                                  "launch/bringup.launch.py": SIM_LAUNCH % (SPAWN if spawns else "")})
    code, report = lint_json([], cwd=tmp_path)
    t001 = [f for f in report["findings"] if f["code"] == "T001"]
    assert any(Path(m["path"]).name == path.name for m in report["models"]), report["models"]
    if spawns:
        assert len(t001) == 1 and "Gazebo plugin" in t001[0]["message"], [f["code"] for f in report["findings"]]
    else:
        assert t001 == []


@pytest.mark.parametrize("extra,enabled", [("", True), ("<publishTf>false</publishTf>", False),
                                           ("<publishOdomTF>0</publishOdomTF>", False)])
def test_ros1_diff_drive_plugin_transform_switches(extra, enabled):
    """gazebo_ros_diff_drive (ROS 1): publishOdomTF (default true) turns the transform on, and publishTf (default
    true) gates all odometry."""
    from urdfcheck.consumers.gazebo import read_plugins
    from urdfcheck.model.build import model_from_string

    urdf = robot(*WHEELS, gazebo(f"""    <plugin name="dd" filename="libgazebo_ros_diff_drive.so">
      <leftJoint>left_wheel_joint</leftJoint><rightJoint>right_wheel_joint</rightJoint>{extra}
    </plugin>
"""))
    (owner,) = read_plugins(model_from_string(urdf))
    assert (owner.odom.parent, owner.odom.child, owner.odom.enabled) == ("odom", "base_footprint", enabled)


def test_a_ros2_plugin_ignores_ros1_element_names():
    """neo_simulation2's mpo_500: a ROS 2 planar_move plugin (it has <ros>) given ROS 1's <robotBaseFrame>: ROS 2
    reads robot_base_frame only, so the transform goes to the default base_footprint, not base_link."""
    from urdfcheck.consumers.gazebo import read_plugins
    from urdfcheck.model.build import model_from_string

    def owner(inner):
        urdf = robot(gazebo(f"""    <plugin name="move" filename="libgazebo_ros_planar_move.so">
      {inner}<publish_odom_tf>true</publish_odom_tf><robotBaseFrame>base_link</robotBaseFrame>
    </plugin>
"""))
        (o,) = read_plugins(model_from_string(urdf))
        return o.odom.child

    assert owner("<ros><remapping>/tf:=tf</remapping></ros>") == "base_footprint"
    assert owner("") == "base_link"  # no <ros>: the ROS 1 build, which reads robotBaseFrame
