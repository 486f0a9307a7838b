"""Launch files read statically: ROS 1 XML, ROS 2 XML/YAML/Python; static transforms in every argument form."""
import math
import sys
from pathlib import Path

SRC = Path(__file__).resolve().parents[2] / "src"
if str(SRC) not in sys.path:  # runnable without an editable install
    sys.path.insert(0, str(SRC))

import pytest  # noqa: E402

from urdfcheck.consumers.common import ConsumerError  # noqa: E402
from urdfcheck.consumers.launch.xml import parse_launch, parse_static_tf_args, read_launch  # noqa: E402

HALF_PI = math.pi / 2


def tf_tuple(t):
    return (t.parent, t.child, tuple(round(v, 6) for v in t.xyz), tuple(round(v, 4) for v in t.rpy))


# --- argument forms --------------------------------------------------------------------------------------------
@pytest.mark.parametrize("tokens,ros,pkg,expected", [
    # ROS 1 tf: x y z yaw pitch roll parent child period_ms
    ("1 2 3 1.5708 0 0 base laser 100", 1, "tf", ("base", "laser", (1, 2, 3), (0, 0, 1.5708))),
    # ROS 1 tf: quaternion + period
    ("0 0 0 0 0 0.7071068 0.7071068 base laser 100", 1, "tf", ("base", "laser", (0, 0, 0), (0, 0, 1.5708))),
    # ROS 1 tf2_ros: no period
    ("1 0 0 0 0.5 0.25 base cam", 1, "tf2_ros", ("base", "cam", (1, 0, 0), (0.25, 0.5, 0))),
    ("0 0 0 0 0 0 1 base imu", 1, "tf2_ros", ("base", "imu", (0, 0, 0), (0, 0, 0))),
    # ROS 2 positional (deprecated) forms
    ("0.1 0 0 0 0 3.14159 base_link laser", 2, "tf2_ros", ("base_link", "laser", (0.1, 0, 0), (3.1416, 0, 0))),
    ("0 0 0 0.7071068 0 0 0.7071068 base_link laser", 2, "tf2_ros", ("base_link", "laser", (0, 0, 0), (1.5708, 0, 0))),
    # ROS 2 flag form; --ros-args tail ignored
    ("--x 1 --yaw 0.5 --frame-id map --child-frame-id odom --ros-args -r __node:=x", 2, "tf2_ros",
     ("map", "odom", (1, 0, 0), (0, 0, 0.5))),
    ("--qz 0.7071068 --qw 0.7071068 --frame-id a --child-frame-id b", 2, "tf2_ros",
     ("a", "b", (0, 0, 0), (0, 0, 1.5708))),
])
def test_static_tf_argument_forms(tokens, ros, pkg, expected):
    parent, child, xyz, rpy = parse_static_tf_args(tokens.split(), ros, pkg)
    assert (parent, child) == expected[:2]
    assert xyz == pytest.approx(expected[2], abs=1e-9)
    assert rpy == pytest.approx(expected[3], abs=1e-4)


@pytest.mark.parametrize("tokens", ["1 2 3", "a b c 0 0 0 p c", "--x 1 --frame-id a", "0 0 0 0 0 0 0 p c"])
def test_bad_static_tf_arguments(tokens):
    with pytest.raises(ValueError):
        parse_static_tf_args(tokens.split(), 2)


# --- ROS 1 XML -------------------------------------------------------------------------------------------------
ROS1 = """<launch>
  <arg name="laser_x" default="0.2"/>
  <arg name="sim" default="false"/>
  <arg name="fixed" value="base_link"/>
  <node pkg="tf" type="static_transform_publisher" name="laser_tf"
        args="$(arg laser_x) 0 0.1 1.5708 0 0 $(arg fixed) laser 100"/>
  <node pkg="tf2_ros" type="static_transform_publisher" name="imu_tf" args="0 0 0 0 0 0 1 base_link imu_link"/>
  <group if="$(arg sim)">
    <node pkg="tf2_ros" type="static_transform_publisher" name="sim_only" args="0 0 0 0 0 0 world map"/>
  </group>
  <node pkg="tf2_ros" type="static_transform_publisher" name="env" args="0 0 0 0 0 0 map odom" if="$(env USE_MAP)"/>
  <node pkg="tf" type="static_transform_publisher" name="found" args="$(find pkg)/x 0 0 0 0 0 a b 10"/>
  <node pkg="robot_state_publisher" type="robot_state_publisher" name="rsp">
    <param name="tf_prefix" value="r1"/>
  </node>
  <node pkg="joint_state_publisher" type="joint_state_publisher" name="jsp"/>
  <rosparam command="load" file="$(find my_pkg)/config/controllers.yaml"/>
  <node pkg="controller_manager" type="spawner" name="sp" \
args="--timeout 5 diff_drive_controller joint_state_controller"/>
</launch>
"""


def test_ros1_xml():
    li = parse_launch(ROS1, "bringup.launch", args={"laser_x": "0.3"}, packages={"my_pkg": "/opt/my_pkg"})
    assert li.format == "ros1-xml"
    tfs = {t.node_name: t for t in li.static_tfs}
    assert set(tfs) == {"laser_tf", "imu_tf", "env"}  # sim_only is off, "found" is not literal
    assert tf_tuple(tfs["laser_tf"]) == ("base_link", "laser", (0.3, 0, 0.1), (0, 0, 1.5708))
    assert tfs["laser_tf"].loc.line in (5, 6) and tfs["laser_tf"].source_file == "bringup.launch"
    assert tfs["env"].condition == "if=$(env USE_MAP)"
    assert [(s.name, s.frame_prefix) for s in li.state_publishers] == [("rsp", "r1/")]
    assert [j.name for j in li.joint_state_publishers] == ["jsp"]
    assert [p for p, _ in li.param_files] == ["/opt/my_pkg/config/controllers.yaml"]
    assert [n for n, _ in li.spawned] == ["diff_drive_controller", "joint_state_controller"]
    assert any("not literal" in m or "not understood" in m for m, _ in li.notes)


# --- ROS 2 XML -------------------------------------------------------------------------------------------------
ROS2_XML = """<launch>
  <arg name="ns" default="robot1"/>
  <let name="fp" value="$(var ns)/"/>
  <group>
    <push-ros-namespace namespace="$(var ns)"/>
    <node pkg="tf2_ros" exec="static_transform_publisher"
          args="--x 1 --y 2 --z 3 --yaw 0.5 --frame-id base_link --child-frame-id cam"/>
    <node pkg="tf2_ros" exec="static_transform_publisher" args="1 2 3 0 0 0 base_link cam2"/>
    <node pkg="robot_state_publisher" exec="robot_state_publisher">
      <param name="frame_prefix" value="$(var fp)"/>
      <param name="robot_description" value="$(command 'xacro robot.urdf.xacro')"/>
    </node>
  </group>
  <node pkg="tf2_ros" exec="static_transform_publisher" args="0 0 0 0 0 0 a b" unless="true"/>
</launch>
"""


def test_ros2_xml():
    li = parse_launch(ROS2_XML, "bringup.launch.xml")
    assert li.format == "ros2-xml"
    assert [tf_tuple(t) for t in li.static_tfs] == [
        ("base_link", "cam", (1, 2, 3), (0, 0, 0.5)), ("base_link", "cam2", (1, 2, 3), (0, 0, 0))]
    (rsp,) = li.state_publishers
    assert (rsp.namespace, rsp.frame_prefix) == ("/robot1", "robot1/")


def test_ros2_xml_arguments_from_caller():
    li = parse_launch(ROS2_XML, "bringup.launch.xml", args={"ns": "r7"})
    assert li.state_publishers[0].frame_prefix == "r7/"


# --- ROS 2 YAML ------------------------------------------------------------------------------------------------
ROS2_YAML = """\
launch:
- arg: {name: parent, default: base_link}
- node:
    pkg: tf2_ros
    exec: static_transform_publisher
    args: "0 0 0.5 0 0 0 $(var parent) lidar"
- node:
    pkg: tf2_ros
    exec: static_transform_publisher
    args: ["--x", "1", "--qz", "0.7071068", "--qw", "0.7071068", "--frame-id", "map", "--child-frame-id", "odom"]
- group:
    children:
    - node: {pkg: robot_state_publisher, exec: robot_state_publisher, param: [{name: frame_prefix, value: "a/"}]}
    - node: {pkg: joint_state_publisher_gui, exec: joint_state_publisher_gui}
"""


def test_ros2_yaml():
    li = parse_launch(ROS2_YAML, "bringup.launch.yaml")
    assert li.format == "ros2-yaml"
    assert [tf_tuple(t) for t in li.static_tfs] == [
        ("base_link", "lidar", (0, 0, 0.5), (0, 0, 0)), ("map", "odom", (1, 0, 0), (0, 0, 1.5708))]
    assert li.static_tfs[0].loc.line == 3
    assert li.state_publishers[0].frame_prefix == "a/"
    assert len(li.joint_state_publishers) == 1


# --- ROS 2 Python (ast only) -----------------------------------------------------------------------------------
PY = """
import os
from launch import LaunchDescription
from launch.actions import DeclareLaunchArgument
from launch.conditions import IfCondition
from launch.substitutions import LaunchConfiguration
from launch_ros.actions import Node
open(os.path.join(os.path.dirname(__file__), "EXECUTED"), "w").write("pwned")

def generate_launch_description():
    return LaunchDescription([
        DeclareLaunchArgument('child', default_value='laser'),
        Node(package='tf2_ros', executable='static_transform_publisher',
             arguments=['0.1', '0', '0.2', '0', '0', '0', 'base_link', LaunchConfiguration('child')]),
        Node(package='tf2_ros', executable='static_transform_publisher',
             arguments=['--x', '0.5', '--frame-id', 'base_link', '--child-frame-id', 'cam']),
        Node(package='tf2_ros', executable='static_transform_publisher', arguments=some_list()),
        Node(package='tf2_ros', executable='static_transform_publisher',
             arguments=['0', '0', '0', '0', '0', '0', 'a', 'b'], condition=IfCondition('false')),
        Node(package='robot_state_publisher', executable='robot_state_publisher',
             parameters=[{'robot_description': desc, 'frame_prefix': 'r2/'}]),
        Node(package='joint_state_publisher', executable='joint_state_publisher',
             condition=IfCondition(LaunchConfiguration('gui'))),
    ])
"""


def test_ros2_python_is_read_not_run(tmp_path):
    f = tmp_path / "bringup.launch.py"
    f.write_text(PY)
    li = read_launch(f)
    assert not (tmp_path / "EXECUTED").exists()
    assert li.format == "ros2-py"
    assert [tf_tuple(t) for t in li.static_tfs] == [
        ("base_link", "laser", (0.1, 0, 0.2), (0, 0, 0)), ("base_link", "cam", (0.5, 0, 0), (0, 0, 0))]
    assert li.static_tfs[0].loc.line == 13
    assert [m for m, _ in li.notes] == ["static_transform_publisher arguments are not literal; skipped"]
    assert li.state_publishers[0].frame_prefix == "r2/"
    assert li.joint_state_publishers[0].condition.startswith("condition=")


# --- hostile / broken ------------------------------------------------------------------------------------------
def test_bad_launch_files_are_consumer_errors():
    with pytest.raises(ConsumerError) as e:
        parse_launch("<launch>\n  <node pkg='a'\n</launch>", "bad.launch")
    assert e.value.location.line is not None
    with pytest.raises(ConsumerError, match="DOCTYPE"):
        parse_launch('<!DOCTYPE l [<!ENTITY x "y">]><launch>&x;</launch>', "ent.launch.xml")
    with pytest.raises(ConsumerError, match="syntax"):
        parse_launch("def f(:\n", "bad.launch.py")
    with pytest.raises(ConsumerError):
        parse_launch("x = " + "(" * 5000 + ")" * 5000 + "\n", "deep.launch.py")
    with pytest.raises(ConsumerError, match="launch:"):
        parse_launch("nodes: []\n", "x.launch.yaml")
    with pytest.raises(ConsumerError, match="<launch>"):
        parse_launch("<robot/>", "x.launch")


def test_corpus_launch_files_read(corpus):
    files = sorted(corpus.rglob("*.launch")) + sorted(corpus.rglob("*.launch.xml"))
    assert len(files) > 10
    for f in files:
        li = read_launch(f)
        assert li.format in ("ros1-xml", "ros2-xml")
    li = read_launch(corpus / "ros-controls+ros2_control_demos/example_2/bringup/launch/diffbot.launch.xml")
    assert [s.name for s in li.state_publishers] == ["robot_state_publisher"]


# --- includes of configured launch files ------------------------------------------------------------------
import json  # noqa: E402
import os  # noqa: E402

from conftest import run_cli  # noqa: E402

INC_URDF = """<robot name="r">
  <link name="base_link"/><link name="laser_link"/>
  <joint name="laser_joint" type="fixed"><parent link="base_link"/><child link="laser_link"/></joint>
</robot>
"""


def _include_pkg(root, bringup, extra=None):
    (root / "urdf").mkdir(parents=True)
    (root / "launch").mkdir()
    (root / "package.xml").write_text("<package format='3'><name>inc_description</name></package>")
    (root / "urdf" / "r.urdf").write_text(INC_URDF)
    (root / "launch" / "bringup.launch.xml").write_text(bringup)
    (root / "launch" / "tf.launch.xml").write_text(
        '<launch>\n  <arg name="child" default="camera_link"/>\n'
        '  <node pkg="tf2_ros" exec="static_transform_publisher" name="extra_tf"\n'
        '        args="--frame-id base_link --child-frame-id $(var child)"/>\n</launch>\n')
    for name, text in (extra or {}).items():
        (root / "launch" / name).write_text(text)
    (root / "urdfcheck.yaml").write_text("models:\n  - path: urdf/r.urdf\n    launch: [launch/bringup.launch.xml]\n")
    code, out, err = run_cli(["lint", "--format", "json", "--select", "T,C007"], cwd=root)
    assert code in (0, 1), err
    return [(f["code"], os.path.basename(f["location"]["file"]), f["location"]["line"])
            for f in json.loads(out)["findings"]]


def test_a_static_tf_in_an_included_file_is_seen(tmp_path):
    bringup = ('<launch>\n  <include file="$(find-pkg-share inc_description)/launch/tf.launch.xml">\n'
               '    <arg name="child" value="laser_link"/>\n  </include>\n</launch>\n')
    found = _include_pkg(tmp_path / "inc_description", bringup)
    # the include passes child:=laser_link: the static TF doubles the URDF's fixed joint
    assert ("T001", "tf.launch.xml", 4) in found, found


def test_includes_that_cannot_be_decided_or_leave_the_package_are_not_followed(tmp_path):
    outside = tmp_path / "elsewhere"
    outside.mkdir()
    (outside / "tf.launch.xml").write_text(
        '<launch><node pkg="tf2_ros" exec="static_transform_publisher" '
        'args="--frame-id base_link --child-frame-id laser_link"/></launch>\n')
    bringup = ('<launch>\n  <arg name="sim" default="$(env SIM)"/>\n'
               '  <include file="$(dirname)/tf.launch.xml" if="$(var sim)"><arg name="child" value="laser_link"/>'
               '</include>\n'
               f'  <include file="{outside}/tf.launch.xml"/>\n'
               '  <include file="$(dirname)/loop.launch.xml"/>\n</launch>\n')
    loop = '<launch><include file="$(dirname)/bringup.launch.xml"/></launch>\n'
    assert _include_pkg(tmp_path / "inc_description", bringup, {"loop.launch.xml": loop}) == []


def test_reading_includes_records_what_the_included_file_is_passed(tmp_path):
    from urdfcheck.consumers.launch.xml import parse_launch

    ros1 = parse_launch(b'<launch><arg name="a" default="1"/>'
                        b'<include file="x.launch"><arg name="b" value="$(arg a)"/></include>'
                        b'<include file="y.launch" pass_all_args="true"/></launch>', "t.launch")
    assert [dict(i.args) for i in ros1.includes] == [{"b": "1"}, {"a": "1"}]
    ros2 = parse_launch(b'<launch><arg name="a" default="1"/><let name="c" value="$(env X)"/>'
                        b'<include file="x.launch.xml"><arg name="b" value="2"/></include></launch>', "t.launch.xml")
    (inc,) = ros2.includes
    assert dict(inc.args) == {"a": "1", "c": None, "b": "2"}  # ROS 2: the including file's configurations too
    yml = parse_launch(b"launch:\n- include:\n    file: x.launch.yaml\n    arg:\n    - {name: b, value: 3}\n",
                       "t.launch.yaml")
    assert dict(yml.includes[0].args) == {"b": "3"}


PY_BRINGUP = '''import os
from ament_index_python.packages import get_package_share_directory
from launch import LaunchDescription
from launch.actions import IncludeLaunchDescription
from launch.conditions import IfCondition
from launch.launch_description_sources import PythonLaunchDescriptionSource
from launch.substitutions import LaunchConfiguration, PathJoinSubstitution
from launch_ros.substitutions import FindPackageShare


def generate_launch_description():
    share = get_package_share_directory("inc_description")
    tf = IncludeLaunchDescription(
        PythonLaunchDescriptionSource(os.path.join(share, "launch", "tf.launch.py")),
        launch_arguments={"child": "laser_link"}.items())
    sim = IncludeLaunchDescription(
        PythonLaunchDescriptionSource([FindPackageShare("inc_description"), "/launch/tf.launch.py"]),
        condition=IfCondition(LaunchConfiguration("use_sim")))
    other = IncludeLaunchDescription(PathJoinSubstitution([FindPackageShare("unknown_pkg"), "x.launch.py"]))
    return LaunchDescription([tf, sim, other])
'''
PY_TF = '''from launch import LaunchDescription
from launch.actions import DeclareLaunchArgument
from launch.substitutions import LaunchConfiguration
from launch_ros.actions import Node


def generate_launch_description():
    return LaunchDescription([
        DeclareLaunchArgument("child", default_value="camera_link"),
        Node(package="tf2_ros", executable="static_transform_publisher",
             arguments=["--frame-id", "base_link", "--child-frame-id", LaunchConfiguration("child")]),
    ])
'''


def test_python_includes_are_read_without_running_anything(tmp_path):
    from urdfcheck.consumers.launch.xml import parse_launch

    root = tmp_path / "inc_description"
    (root / "launch").mkdir(parents=True)
    (root / "package.xml").write_text("<package format='3'><name>inc_description</name></package>")
    info = parse_launch(PY_BRINGUP.encode(), str(root / "launch" / "bringup.launch.py"))
    tf, sim, other = info.includes
    assert tf.file == os.path.join(str(root), "launch", "tf.launch.py") and dict(tf.args) == {"child": "laser_link"}
    assert tf.condition is None and tf.loc.line == 13
    assert sim.file == str(root) + "/launch/tf.launch.py" and sim.condition.startswith("condition=IfCondition")
    assert other.file is None  # a package nobody maps


def test_a_static_tf_in_an_included_python_file_is_seen(tmp_path):
    bringup = PY_BRINGUP.replace('    return LaunchDescription([tf, sim, other])', '    return LaunchDescription([tf])')
    found = _include_pkg(tmp_path / "inc_description", "<launch/>\n",
                         {"bringup.launch.py": bringup, "tf.launch.py": PY_TF})
    assert found == []  # the config lists bringup.launch.xml, which includes nothing
    root = tmp_path / "inc_description"
    (root / "urdfcheck.yaml").write_text("models:\n  - path: urdf/r.urdf\n    launch: [launch/bringup.launch.py]\n")
    code, out, err = run_cli(["lint", "--format", "json", "--select", "T,C007"], cwd=root)
    found = [(f["code"], os.path.basename(f["location"]["file"])) for f in json.loads(out)["findings"]]
    assert ("T001", "tf.launch.py") in found, (found, err)


@pytest.mark.parametrize("body,expected", [
    ('name = "inc_description"\n'
     'src = PythonLaunchDescriptionSource([os.path.join(get_package_share_directory(name), "launch", "a.launch.py")])\n'
     'x = IncludeLaunchDescription(src, launch_arguments={"urdf": os.path.join(get_package_share_directory(name), '
     '"urdf", "r.urdf")}.items())\n', "launch/a.launch.py"),
    ('x = IncludeLaunchDescription(PythonLaunchDescriptionSource([ThisLaunchFileDir(), "/b.launch.py"]))\n',
     "launch/b.launch.py"),
    ('pkg = FindPackageShare("inc_description")\n'
     'path = PathJoinSubstitution([pkg, "launch", "c.launch.py"])\n'
     'x = IncludeLaunchDescription(PythonLaunchDescriptionSource(path))\n', "launch/c.launch.py"),
    ('x = IncludeLaunchDescription(XMLLaunchDescriptionSource(f"{os.path.dirname(__file__)}/d.launch.xml"))\n',
     "launch/d.launch.xml"),
    ('p = "a"\np = "b"\nx = IncludeLaunchDescription(PythonLaunchDescriptionSource(p))\n', None),  # reassigned
    ('p = p + "x"\nx = IncludeLaunchDescription(PythonLaunchDescriptionSource(p))\n', None),  # refers to itself
])
def test_python_include_paths(tmp_path, body, expected):
    from urdfcheck.consumers.launch.xml import parse_launch

    root = tmp_path / "inc_description"
    (root / "launch").mkdir(parents=True)
    (root / "package.xml").write_text("<package format='3'><name>inc_description</name></package>")
    (inc,) = parse_launch(("import os\n" + body).encode(), str(root / "launch" / "bringup.launch.py")).includes
    if expected is None:
        assert inc.file is None
    else:
        assert os.path.normpath(inc.file) == str(root / expected)
    if "urdf" in body:
        assert dict(inc.args) == {"urdf": os.path.join(str(root), "urdf", "r.urdf")}
