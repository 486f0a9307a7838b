"""TF owners that are not the model (slam_toolbox, cartographer, robot_localization configured in the launch file,
realsense2_camera) and the launch constructs real repositories use. Each case is a small package with a seeded
defect and its clean twin: the defect is found (at its YAML / .lua / launch line) zero-config, the twin passes."""
import json
from pathlib import Path

import pytest
from conftest import CORPUS, REPO, lint_json, run_cli

URDF = """<robot name="bot">
  <link name="base_link"/>
  <link name="laser"/>
  <link name="camera_link"/>
  <joint name="laser_joint" type="fixed"><parent link="base_link"/><child link="laser"/></joint>
  <joint name="camera_joint" type="fixed"><parent link="base_link"/><child link="camera_link"/></joint>
{extra}</robot>
"""

PY_HEAD = """import os
from ament_index_python.packages import get_package_share_directory
from launch import LaunchDescription
from launch.actions import IncludeLaunchDescription
from launch.launch_description_sources import PythonLaunchDescriptionSource
from launch.substitutions import PathJoinSubstitution
from launch_ros.actions import Node
from launch_ros.substitutions import FindPackageShare


def generate_launch_description():
    share = get_package_share_directory("bot")
    model = open(os.path.join(share, "urdf", "bot.urdf")).read()
    return LaunchDescription([
        Node(package="robot_state_publisher", executable="robot_state_publisher",
             parameters=[{"robot_description": model}]),
"""


def write(root: Path, files: dict) -> Path:
    for name, text in files.items():
        p = root / name
        p.parent.mkdir(parents=True, exist_ok=True)
        p.write_text(text)
    return root


def package(tmp_path: Path, nodes: str, files: dict | None = None, extra: str = "") -> Path:
    root = tmp_path / "bot"
    return write(root, {"package.xml": "<package format='3'><name>bot</name></package>\n",
                        "urdf/bot.urdf": URDF.format(extra=extra),
                        "launch/bringup.launch.py": PY_HEAD + nodes + "    ])\n", **(files or {})})


def tf(root: Path) -> list[tuple[str, str, int, str]]:
    _, report = lint_json(["--select", "T,C007,C020,X"], cwd=root)
    return [(f["code"], Path(f["location"]["file"]).name, f["location"].get("line"), f["message"])
            for f in report["findings"]]


EKF_ODOM = """        Node(package="robot_localization", executable="ekf_node", name="ekf_odom",
             parameters=[{"world_frame": "odom", "base_link_frame": "base_link", "two_d_mode": True}]),
"""
SLAM = """        Node(package="slam_toolbox", executable="async_slam_toolbox_node", name="slam_toolbox",
             parameters=[os.path.join(share, "config", "slam.yaml")]),
"""
SLAM_YAML = """slam_toolbox:
  ros__parameters:
    odom_frame: odom
    map_frame: map
    base_frame: base_link
    transform_publish_period: 0.02
"""


def test_slam_toolbox_is_a_second_owner_of_map_to_odom(tmp_path):
    ekf_map = EKF_ODOM.replace('"ekf_odom"', '"ekf_map"').replace('"world_frame": "odom"', '"world_frame": "map"')
    root = package(tmp_path, EKF_ODOM + ekf_map + SLAM, {"config/slam.yaml": SLAM_YAML})
    found = tf(root)
    t001 = [f for f in found if f[0] == "T001"]
    assert len(t001) == 1 and "map -> odom" in t001[0][3], found
    assert "slam_toolbox" in t001[0][3] and "robot_localization" in t001[0][3], found
    # each owner named at the line that turns its transform on: slam's period (YAML), the ekf's world_frame
    assert "slam.yaml:6" in t001[0][3] and "bringup.launch.py:" in t001[0][3], found


def test_slam_toolbox_clean_twin_joins_the_tree(tmp_path):
    root = package(tmp_path, EKF_ODOM + SLAM, {"config/slam.yaml": SLAM_YAML})
    assert tf(root) == []  # ekf: odom -> base_link; slam_toolbox: map -> odom; one tree


def test_slam_toolbox_period_zero_publishes_nothing(tmp_path):
    ekf_map = EKF_ODOM.replace('"ekf_odom"', '"ekf_map"').replace('"world_frame": "odom"', '"world_frame": "map"')
    root = package(tmp_path, EKF_ODOM + ekf_map + SLAM,
                   {"config/slam.yaml": SLAM_YAML.replace("0.02", "0.0")})
    assert [f for f in tf(root) if f[0] == "T001"] == []


LUA = """include "map_builder.lua"
include "trajectory_builder.lua"

options = {
  map_builder = MAP_BUILDER,
  trajectory_builder = TRAJECTORY_BUILDER,
  map_frame = "map",
  tracking_frame = "base_link",
  published_frame = "{published}",
  odom_frame = "odom",
  provide_odom_frame = {provide},
  use_odometry = true,
}

MAP_BUILDER.use_trajectory_builder_2d = true
return options
"""
CARTO = """        Node(package="cartographer_ros", executable="cartographer_node",
             arguments=["-configuration_directory", os.path.join(share, "config"),
                        "-configuration_basename", "bot.lua"]),
"""


def test_cartographer_providing_odom_is_a_second_owner_of_odom_to_base(tmp_path):
    lua = LUA.replace("{published}", "base_link").replace("{provide}", "true")
    root = package(tmp_path, EKF_ODOM + CARTO, {"config/bot.lua": lua})
    t001 = [f for f in tf(root) if f[0] == "T001"]
    assert len(t001) == 1 and "odom -> base_link" in t001[0][3] and "cartographer" in t001[0][3], t001
    assert "bot.lua:11" in t001[0][3]  # provide_odom_frame = true, named with the other owner's line


def test_cartographer_clean_twin_publishes_map_to_odom_only(tmp_path):
    lua = LUA.replace("{published}", "odom").replace("{provide}", "false")
    root = package(tmp_path, EKF_ODOM + CARTO, {"config/bot.lua": lua})
    assert tf(root) == []


def test_cartographer_lua_is_read_as_text():
    import tempfile

    from urdfcheck.consumers.localization import make_node, read_lua_options

    with tempfile.TemporaryDirectory() as d:
        p = Path(d) / "x.lua"
        p.write_text(LUA.replace("{published}", "odom").replace("{provide}", "false")
                     + 'os.execute("touch /tmp/never")\n')
        got = read_lua_options(str(p))
        assert got["published_frame"].value == "odom" and got["provide_odom_frame"].value is False
        assert got["provide_odom_frame"].loc.line == 11
        n = make_node("cartographer", "carto", str(p), got["map_frame"].loc, got)
        assert [(e.parent, e.child) for e in n.edges()] == [("map", "odom")]
    assert not Path("/tmp/never").exists()


def test_robot_localization_inline_parameters_twice_on_one_edge(tmp_path):
    second = EKF_ODOM.replace('"ekf_odom"', '"ekf_again"')
    root = package(tmp_path, EKF_ODOM + second)
    t001 = [f for f in tf(root) if f[0] == "T001"]
    assert len(t001) == 1 and "odom -> base_link" in t001[0][3], t001
    assert "ekf_odom" in t001[0][3] and "ekf_again" in t001[0][3]
    assert t001[0][1] == "bringup.launch.py"


def test_robot_localization_inline_parameters_clean_twin(tmp_path):
    second = EKF_ODOM.replace('"ekf_odom"', '"ekf_map"').replace('"world_frame": "odom"', '"world_frame": "map"')
    assert tf(package(tmp_path, EKF_ODOM + second)) == []


def test_a_node_with_its_parameter_file_is_one_owner_not_two(tmp_path):
    node = """        Node(package="robot_localization", executable="ekf_node", name="ekf_filter_node",
             parameters=[os.path.join(share, "config", "ekf.yaml")]),
"""
    ekf = "ekf_filter_node:\n  ros__parameters:\n    world_frame: odom\n    base_link_frame: base_link\n"
    assert tf(package(tmp_path, node, {"config/ekf.yaml": ekf})) == []


ROS1 = """<launch>
  <arg name="world" default="{world}"/>
  <param name="robot_description" textfile="$(find bot)/urdf/bot.urdf"/>
  <node pkg="robot_state_publisher" type="robot_state_publisher" name="rsp"/>
  <node pkg="robot_localization" type="ekf_localization_node" name="ekf_odom">
    <param name="world_frame" value="odom"/>
    <param name="base_link_frame" value="base_link"/>
  </node>
  <node pkg="robot_localization" type="ekf_localization_node" name="ekf_second">
{second}
  </node>
</launch>
"""


def ros1_package(tmp_path: Path, launch: str, files: dict | None = None) -> Path:
    return write(tmp_path / "bot", {"package.xml": "<package format='2'><name>bot</name></package>\n",
                                    "urdf/bot.urdf": URDF.format(extra=""), "launch/bringup.launch": launch,
                                    **(files or {})})


@pytest.mark.parametrize("second,defect", [
    ('    <param name="world_frame" value="odom"/>', True),
    ('    <param name="world_frame" value="map"/>', False),
    ("    <rosparam>\n      world_frame: odom\n    </rosparam>", True),
    ("    <rosparam>\n      world_frame: map\n    </rosparam>", False),
    ('    <rosparam command="load" file="$(find bot)/config/ekf.yaml" subst_value="true"/>', None),
])
def test_ros1_robot_localization_from_param_and_rosparam(tmp_path, second, defect):
    files = {"config/ekf.yaml": "world_frame: $(arg world)\nbase_link_frame: base_link\n"}
    for world, want in (("odom", True), ("map", False)) if defect is None else (("odom", defect),):
        root = ros1_package(tmp_path / world, ROS1.format(world=world, second=second), files)
        t001 = [f for f in tf(root) if f[0] == "T001"]
        assert bool(t001) == want, (second, world, tf(root))
        if want:
            assert "ekf_odom" in t001[0][3] and "ekf_second" in t001[0][3]
            where = "ekf.yaml" if defect is None else "bringup.launch"
            assert t001[0][1] == where or where in t001[0][3], t001


REALSENSE_NODE = """        Node(package="realsense2_camera", executable="realsense2_camera_node", name="camera",
             parameters=[{{"publish_tf": {publish}, "camera_name": "camera"}}]),
"""
DEPTH_IN_MODEL = """  <link name="camera_depth_frame"/>
  <joint name="camera_depth_joint" type="fixed"><parent link="camera_link"/><child link="camera_depth_frame"/></joint>
"""


def test_realsense_publishing_a_frame_of_the_model_is_a_second_owner(tmp_path):
    root = package(tmp_path, REALSENSE_NODE.format(publish="True"), extra=DEPTH_IN_MODEL)
    t001 = [f for f in tf(root) if f[0] == "T001"]
    assert len(t001) == 1 and "camera_link -> camera_depth_frame" in t001[0][3], t001
    assert "realsense2_camera" in t001[0][3] and t001[0][1] == "bringup.launch.py"


def test_realsense_clean_twin_publish_tf_false(tmp_path):
    assert tf(package(tmp_path, REALSENSE_NODE.format(publish="False"), extra=DEPTH_IN_MODEL)) == []


def test_realsense_frames_join_the_tree_by_default(tmp_path):
    # its own frames hang below camera_link: one tree, no frame reported missing
    assert tf(package(tmp_path, REALSENSE_NODE.format(publish="True"))) == []


def test_realsense_launch_file_included_from_its_package(tmp_path):
    include = """        IncludeLaunchDescription(PythonLaunchDescriptionSource(PathJoinSubstitution(
            [FindPackageShare("realsense2_camera"), "launch", "rs_launch.py"])),
            launch_arguments={{"camera_name": "camera", "publish_tf": "{publish}"}}.items()),
"""
    root = package(tmp_path, include.format(publish="true"), extra=DEPTH_IN_MODEL)
    t001 = [f for f in tf(root) if f[0] == "T001"]
    assert len(t001) == 1 and "realsense2_camera" in t001[0][3], tf(root)
    assert tf(package(tmp_path / "twin", include.format(publish="false"), extra=DEPTH_IN_MODEL)) == []


# --- launch constructs -------------------------------------------------------------------------------
STATIC_DUP = """        Node(package="tf2_ros", executable="static_transform_publisher",
             arguments=["0", "0", "0.1", "0", "0", "0", parent, child]),
"""


def test_static_transform_with_frames_in_variables_same_with_and_without_config(tmp_path):
    nodes = STATIC_DUP
    root = package(tmp_path, nodes)
    launch = root / "launch" / "bringup.launch.py"
    launch.write_text(launch.read_text().replace('    share = get_package_share_directory("bot")\n',
                                                 '    share = get_package_share_directory("bot")\n'
                                                 '    parent, child = "base_link", "laser"\n'
                                                 .replace('parent, child = "base_link", "laser"',
                                                          'parent = "base_link"\n    child = "laser"')))
    zero = [f[:3] for f in tf(root)]
    line = next(i for i, x in enumerate(launch.read_text().splitlines(), 1) if "static_transform_publisher" in x)
    assert zero == [("T001", "bringup.launch.py", line)], zero
    (root / "urdfcheck.yaml").write_text("models:\n  - path: urdf/bot.urdf\n    launch: [launch/bringup.launch.py]\n")
    code, out, err = run_cli(["lint", "--format", "json", "--select", "T,C007,C020,X"], cwd=root)
    configured = [(f["code"], Path(f["location"]["file"]).name, f["location"].get("line"))
                  for f in json.loads(out)["findings"]]
    assert sorted(configured) == sorted(zero), (configured, zero, err)


def test_file_content_names_the_model(tmp_path):
    head = PY_HEAD.replace('model = open(os.path.join(share, "urdf", "bot.urdf")).read()',
                           'model = FileContent(PathJoinSubstitution([share, "urdf", "bot.urdf"]))')
    root = package(tmp_path, "")
    (root / "launch" / "bringup.launch.py").write_text(head + STATIC_DUP.replace("parent, child",
                                                                                 '"base_link", "laser"') + "    ])\n")
    code, out, _ = run_cli(["lint", "--list"], cwd=root)
    assert "model: urdf/bot.urdf" in out.replace("bot/urdf", "urdf"), out
    assert [f[0] for f in tf(root)] == ["T001"]


XML_EVAL = """<launch>
  <param name="robot_description" textfile="$(eval find('bot') + '/urdf/bot.urdf')"/>
  <node pkg="robot_state_publisher" type="robot_state_publisher" name="rsp"/>
  <node pkg="tf" type="static_transform_publisher" name="dup" args="0 0 0.1 0 0 0 base_link {child} 100"/>
</launch>
"""


@pytest.mark.parametrize("child,want", [("laser", ["T001"]), ("somewhere", [])])
def test_eval_find_names_the_model(tmp_path, child, want):
    root = ros1_package(tmp_path, XML_EVAL.format(child=child), {"urdf/other.urdf": URDF.format(extra="")})
    assert [f[0] for f in tf(root)] == want
    code, out, _ = run_cli(["lint", "--list"], cwd=root)
    assert "1 deployment(s), 1 with a model" in out and "model: urdf/bot.urdf" in out, out  # not a guess


INCLUDING = """<launch>
  <include file="$(find bot)/launch/description.launch">
    <arg name="model" default="$(find bot)/urdf/{name}.urdf"/>
  </include>
</launch>
"""
DESCRIPTION = """<launch>
  <arg name="model"/>
  <param name="robot_description" textfile="$(arg model)"/>
  <node pkg="robot_state_publisher" type="robot_state_publisher" name="rsp"/>
</launch>
"""


def test_include_arg_default_is_passed(tmp_path):
    root = ros1_package(tmp_path, INCLUDING.format(name="bot"), {"launch/description.launch": DESCRIPTION,
                                                                 "urdf/other.urdf": URDF.format(extra="")})
    (root / "launch" / "bringup.launch").rename(root / "launch" / "robot.launch")
    code, out, _ = run_cli(["lint", "--list"], cwd=root)
    assert "launch/robot.launch\n  model: urdf/bot.urdf\n" in out and "1 deployment(s)" in out, out


XML_CHOICES = """<launch>
  <arg name="robot" default="a">
    <choice value="a"/>
    <choice value="b"/>
  </arg>
  <node pkg="robot_state_publisher" exec="robot_state_publisher" name="rsp">
    <param name="robot_description"
           value="$(command 'xacro $(find-pkg-share bot)/urdf/robot_$(var robot).urdf.xacro')"/>
  </node>
</launch>
"""


def test_file_name_built_from_an_argument_with_choices(tmp_path):
    root = write(tmp_path / "bot", {
        "package.xml": "<package format='3'><name>bot</name></package>\n",
        "urdf/robot_a.urdf.xacro": '<robot name="a" xmlns:xacro="http://www.ros.org/wiki/xacro">'
                                   '<link name="base_link"/></robot>\n',
        "urdf/robot_b.urdf.xacro": '<robot name="b" xmlns:xacro="http://www.ros.org/wiki/xacro">'
                                   '<link name="base_link"/><joint name="j" type="fixed"><parent link="base_link"/>'
                                   '<child link="nowhere"/></joint></robot>\n',
        "launch/bringup.launch.xml": XML_CHOICES})
    code, out, _ = run_cli(["lint", "--list"], cwd=root)
    assert "model: urdf/robot_a.urdf.xacro" in out and "[robot=b]" in out, out  # the default, then choice b
    _, report = lint_json(["--select", "S003"], cwd=root)
    assert [Path(f["location"]["file"]).name for f in report["findings"]] == ["robot_b.urdf.xacro"]


def test_list_names_the_node_of_each_localization_file(tmp_path):
    root = package(tmp_path, EKF_ODOM + SLAM, {"config/slam.yaml": SLAM_YAML})
    code, out, _ = run_cli(["lint", "--list"], cwd=root)
    line = next(x for x in out.splitlines() if "localization:" in x)
    assert "slam_toolbox slam_toolbox (" in line and "slam.yaml" in line and "amcl" not in line, line


# --- one reader per launch format, whoever asks -----------------------------------------------------
def _summary(info):
    if not hasattr(info, "nodes"):
        return ("error", str(info))
    return (info.format,
            sorted((t.parent, t.child, t.xyz, t.rpy, t.loc.line) for t in info.static_tfs),
            sorted((s.name, s.namespace, s.frame_prefix, s.loc.line, s.description and s.description.path)
                   for s in info.state_publishers),
            sorted((n.package, n.executable, n.name, n.namespace, n.loc.line, tuple(sorted(n.params)))
                   for n in info.nodes),
            sorted((i.file or "", i.loc.line) for i in info.includes),
            sorted(info.spawned, key=str))


@pytest.mark.parametrize("where", ["examples", "corpus"])
def test_config_and_planner_read_every_launch_file_alike(where):
    """The config path (`consumers`: `launch.read_launch`) and the deployment finder (`_Workspace.read`) read
    each launch file of the examples and the corpus into the same record."""
    from urdfcheck.consumers.common import ConsumerError
    from urdfcheck.consumers.launch.xml import read_launch
    from urdfcheck.plan.deployments import _Workspace, launch_files

    root = REPO / "examples" if where == "examples" else CORPUS
    if not root.is_dir():
        pytest.skip(f"{root} not here")
    ws = _Workspace(str(root))
    files = launch_files(str(root))
    assert files
    for p in files:
        planner = ws.read(p, {})
        try:
            configured = read_launch(p, packages=ws.package_map(p))
        except ConsumerError as e:
            configured = e
        assert _summary(planner) == _summary(configured), p


def test_alternative_launch_files_of_a_package_are_not_two_owners(tmp_path):
    """No launch file starts robot_state_publisher: the package's launch files are read as alternatives (sim and
    real each start their own ekf); their nodes are not counted together."""
    start = "    return LaunchDescription([\n"
    body = PY_HEAD.split(start)[0] + start + EKF_ODOM + "    ])\n"
    root = package(tmp_path, "", {"launch/sim.launch.py": body, "launch/real.launch.py": body})
    (root / "launch" / "bringup.launch.py").unlink()
    assert [f for f in tf(root) if f[0] == "T001"] == []


def test_two_robots_in_one_launch_file_each_have_their_ekf(tmp_path):
    """Two robot_state_publishers in two namespaces, /tf remapped into each (as rosbot's bringup does): each
    deployment counts the ekf of its own namespace, not both."""
    nodes = ""
    for ns in ("r1", "r2"):
        nodes += f"""        Node(package="robot_state_publisher", executable="robot_state_publisher", namespace="{ns}",
             parameters=[{{"robot_description": model}}], remappings=[("/tf", "tf"), ("/tf_static", "tf_static")]),
        Node(package="robot_localization", executable="ekf_node", name="ekf", namespace="{ns}",
             parameters=[{{"world_frame": "odom", "base_link_frame": "base_link"}}],
             remappings=[("/tf", "tf")]),
"""
    head = PY_HEAD.split("        Node(package=\"robot_state_publisher\"")[0]
    root = package(tmp_path, "")
    (root / "launch" / "bringup.launch.py").write_text(head + nodes + "    ])\n")
    assert [f for f in tf(root) if f[0] == "T001"] == []


ROS1_SERVER = """<launch>
  <arg name="world" default="{world}"/>
  <param name="robot_description" textfile="$(find bot)/urdf/bot.urdf"/>
  <node pkg="robot_state_publisher" type="robot_state_publisher" name="rsp"/>
  <param name="ekf_odom/world_frame" value="odom"/>
  <node pkg="robot_localization" type="ekf_localization_node" name="ekf_odom"/>
  <rosparam command="load" file="$(find bot)/config/ekf.yaml" ns="ekf_second" subst_value="true"/>
  <node pkg="robot_localization" type="ekf_localization_node" name="ekf_second"/>
</launch>
"""


@pytest.mark.parametrize("world,want", [("odom", True), ("map", False)])
def test_ros1_parameters_written_outside_the_node(tmp_path, world, want):
    files = {"config/ekf.yaml": "world_frame: $(arg world)\nbase_link_frame: base_link\n"}
    root = ros1_package(tmp_path, ROS1_SERVER.format(world=world), files)
    t001 = [f for f in tf(root) if f[0] == "T001"]
    assert bool(t001) == want, tf(root)
    if want:
        assert "ekf.yaml:1" in t001[0][3] and "bringup.launch:5" in t001[0][3], t001


def test_ros2_xml_include_of_the_realsense_launch_file(tmp_path):
    launch = """<launch>
  <node pkg="robot_state_publisher" exec="robot_state_publisher" name="rsp">
    <param name="robot_description" value="$(command 'cat $(find-pkg-share bot)/urdf/bot.urdf')"/>
  </node>
  <include file="$(find-pkg-share realsense2_camera)/launch/rs_launch.py">
    <arg name="publish_tf" value="{publish}"/>
  </include>
</launch>
"""
    for publish, want in (("true", ["T001"]), ("false", [])):
        root = write(tmp_path / publish / "bot", {
            "package.xml": "<package format='3'><name>bot</name></package>\n",
            "urdf/bot.urdf": URDF.format(extra=DEPTH_IN_MODEL),
            "launch/bringup.launch.xml": launch.format(publish=publish)})
        assert [f[0] for f in tf(root)] == want, tf(root)


@pytest.mark.parametrize("publish,want", [("True", ["T001"]), ("False", [])])
def test_laser_odometry_publishing_odom_beside_an_ekf(tmp_path, publish, want):
    rf2o = f"""        Node(package="rf2o_laser_odometry", executable="rf2o_laser_odometry_node",
             parameters=[{{"odom_frame_id": "odom", "publish_tf": {publish}}}]),
"""
    assert [f[0] for f in tf(package(tmp_path, EKF_ODOM + rf2o))] == want


def test_mapping_and_localization_files_of_a_package_are_alternatives(tmp_path):
    """slam_toolbox's and AMCL's parameter files in one package, no launch file starting them: one runs for
    mapping, the other for localization; not two owners of map -> odom."""
    amcl = ("amcl:\n  ros__parameters:\n    global_frame_id: map\n    odom_frame_id: odom\n"
            "    base_frame_id: base_link\n")
    root = package(tmp_path, EKF_ODOM, {"config/slam.yaml": SLAM_YAML, "config/amcl.yaml": amcl})
    (root / "launch" / "bringup.launch.py").unlink()
    assert [f for f in tf(root) if f[0] == "T001"] == []


@pytest.mark.parametrize("sep,want", [("0.52", ["C010"]), ("0.50", [])])
def test_ros1_controllers_loaded_with_subst_value(tmp_path, sep, want):
    import shutil

    root = tmp_path / "agv"
    shutil.copytree(REPO / "examples" / "broken" / "contract_launch_override", root)
    ctrl = root / "config" / "agv_controllers.yaml"
    ctrl.write_text(ctrl.read_text().replace("wheel_separation: 0.50", "wheel_separation: $(arg sep)"))
    launch = root / "launch" / "agv.launch"
    text = launch.read_text().replace('<param name="diff_drive_controller/wheel_separation" value="0.52"/>', "")
    text = text.replace("<launch>", f'<launch>\n  <arg name="sep" default="{sep}"/>')
    text = text.replace('agv_controllers.yaml"/>', 'agv_controllers.yaml" subst_value="true"/>')
    launch.write_text(text)
    _, report = lint_json(["--select", "C010"], cwd=root)
    got = [(f["code"], Path(f["location"]["file"]).name, f["location"].get("line")) for f in report["findings"]]
    assert [g[0] for g in got] == want, got
    if want:
        assert got[0][1:] == ("agv_controllers.yaml", 11)  # where the value is written, substituted


# --- drivers that publish their own frames (issue 37) -------------------------------------------------------------
OUSTER = """        Node(package="ouster_ros", executable="os_driver", name="os_driver",
             parameters=[os.path.join(share, "config", "ouster.yaml")]),
"""
OUSTER_YAML = """os_driver:
  ros__parameters:
    sensor_hostname: os-122201000999.local
    lidar_mode: 1024x10
    sensor_frame: os_sensor
    lidar_frame: os_lidar
    imu_frame: os_imu
"""
F1TENTH = """        Node(package="f1tenth_simulator", executable="simulator", name="simulator",
             parameters=[os.path.join(share, "config", "sim.yaml")]),
"""
F1TENTH_YAML = """simulator:
  ros__parameters:
    map_frame: map
    base_frame: base_link
    scan_frame: laser_frame
    scan_distance_to_base_link: 0.275
    broadcast_transform: true
"""
OS_JOINT = ('  <link name="os_sensor"/>\n  <joint name="os_joint" type="fixed"><parent link="base_link"/>'
            '<child link="os_sensor"/></joint>\n')


def test_a_lidar_driver_publishing_its_own_imu_frame_is_no_c020(tmp_path):
    """ouster_ros broadcasts os_sensor -> os_lidar and os_sensor -> os_imu itself: os_imu is in the tree (not a
    misspelt imu_link)."""
    root = package(tmp_path, OUSTER, {"config/ouster.yaml": OUSTER_YAML}, extra=OS_JOINT)
    assert [f for f in tf(root) if f[0] == "C020"] == []


def test_a_simulator_publishing_its_scan_frame_is_no_c020(tmp_path):
    """f1tenth_simulator broadcasts base_frame -> scan_frame on every scan (and map -> base_frame)."""
    root = package(tmp_path, F1TENTH, {"config/sim.yaml": F1TENTH_YAML})
    assert [f for f in tf(root) if f[0] == "C020"] == []


ZED = """        Node(package="zed_wrapper", executable="zed_wrapper", name="zed_node",
             parameters=[os.path.join(share, "config", "zed.yaml")]),
"""
ZED_YAML = """/**:
  ros__parameters:
    general:
      camera_name: zed
    pos_tracking:
      map_frame: 'map'
      odometry_frame: 'odom'
"""
ZED_LINK = ('  <link name="zed_camera_link"/>\n')


def test_a_camera_driver_publishing_tf_by_default_is_no_c020(tmp_path):
    """zed_wrapper publishes odom -> zed_camera_link and map -> odom (pos_tracking.publish_tf and publish_map_tf
    default true): its map and odom frames are its own, not frames missing from the tree."""
    root = package(tmp_path, ZED, {"config/zed.yaml": ZED_YAML}, extra=ZED_LINK)
    found = tf(root)
    assert [f for f in found if f[0] == "C020"] == [], found


MICROSTRAIN = """        Node(package="microstrain_inertial_driver", executable="microstrain_inertial_driver_node",
             name="microstrain_inertial_driver", parameters=[os.path.join(share, "config", "gq7.yml")]),
"""
MICROSTRAIN_YAML = """microstrain_inertial_driver:
  ros__parameters:
    use_enu_frame: True
    frame_id: 'camera_link'
    gnss1_frame_id: "gq7_gnss_1_antenna_link"
    gnss2_frame_id: "gq7_gnss_2_antenna_link"
    odometer_frame_id: "gq7_odometer_link"
    publish_mount_to_frame_id_transform: False
"""


def test_an_ins_driver_publishing_its_antenna_frames_is_no_c020(tmp_path):
    """microstrain_inertial_driver broadcasts frame_id -> each GNSS antenna frame and the odometer frame itself."""
    root = package(tmp_path, MICROSTRAIN, {"config/gq7.yml": MICROSTRAIN_YAML})
    found = tf(root)
    assert [f for f in found if f[0] == "C020"] == [], found
