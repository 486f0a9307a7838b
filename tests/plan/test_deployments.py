"""Deployments found in the launch files of small workspaces (several packages, Python launch files):
which model robot_state_publisher gets, with which xacro arguments, and what runs beside it."""
from pathlib import Path

from work import counted

from urdfcheck.load import loader
from urdfcheck.load.packages import workspace_map
from urdfcheck.plan.deployments import describe, find_deployments
from urdfcheck.rules import engine

XACRO = 'xmlns:xacro="http://www.ros.org/wiki/xacro"'


def write(path: Path, text: str) -> Path:
    path.parent.mkdir(parents=True, exist_ok=True)
    path.write_text(text)
    return path


def pkg(folder: Path, name: str) -> Path:
    write(folder / "package.xml", f"<package format='3'><name>{name}</name></package>")
    return folder


ROBOT = f"""<robot name="bot" {XACRO}>
  <xacro:arg name="wheel_sep" default="0.4"/>
  <link name="base_link"/>
  <xacro:macro name="wheel" params="side y">
    <link name="${{side}}_wheel"><visual><geometry><cylinder radius="0.1" length="0.05"/></geometry></visual></link>
    <joint name="${{side}}_wheel_joint" type="continuous"><parent link="base_link"/><child link="${{side}}_wheel"/>
      <origin xyz="0 ${{y}} 0" rpy="-1.5708 0 0"/><axis xyz="0 0 1"/></joint>
  </xacro:macro>
  <xacro:wheel side="left" y="${{$(arg wheel_sep)/2}}"/>
  <xacro:wheel side="right" y="${{-$(arg wheel_sep)/2}}"/>
</robot>
"""

DESCRIPTION_LAUNCH = """
from launch import LaunchDescription
from launch.actions import DeclareLaunchArgument
from launch.substitutions import Command, LaunchConfiguration, PathJoinSubstitution
from launch_ros.actions import Node
from launch_ros.substitutions import FindPackageShare


def generate_launch_description():
    model = LaunchConfiguration('model')
    xacro_file = PathJoinSubstitution([FindPackageShare('bot_description'), 'urdf', model, 'bot.urdf.xacro'])
    robot_description = {'robot_description': Command(['xacro ', xacro_file, ' wheel_sep:=',
                                                       LaunchConfiguration('wheel_sep')])}
    return LaunchDescription([
        DeclareLaunchArgument('model', default_value='small', choices=['small', 'large']),
        DeclareLaunchArgument('wheel_sep', default_value='0.4'),
        DeclareLaunchArgument('namespace', default_value=''),
        Node(package='robot_state_publisher', executable='robot_state_publisher',
             namespace=LaunchConfiguration('namespace'), parameters=[robot_description]),
    ])
"""

BRINGUP_LAUNCH = """
import os
from ament_index_python.packages import get_package_share_directory
from launch import LaunchDescription
from launch.actions import IncludeLaunchDescription
from launch.launch_description_sources import PythonLaunchDescriptionSource
from launch.substitutions import PathJoinSubstitution
from launch_ros.actions import Node
from launch_ros.substitutions import FindPackageShare

open('PWNED', 'w').write('the launch file ran')  # read, never run: this must not happen


def generate_launch_description():
    desc = get_package_share_directory('bot_description')
    controllers = PathJoinSubstitution([FindPackageShare('bot_control'), 'config', 'controllers.yaml'])
    ekf = os.path.join(get_package_share_directory('bot_bringup'), 'config', 'ekf.yaml')
    return LaunchDescription([
        IncludeLaunchDescription(
            PythonLaunchDescriptionSource(os.path.join(desc, 'launch', 'description.launch.py')),
            launch_arguments={'wheel_sep': '0.5'}.items()),
        Node(package='controller_manager', executable='ros2_control_node', parameters=[controllers]),
        Node(package='controller_manager', executable='spawner',
             arguments=['diff_cont', '--controller-manager', '/controller_manager']),
        Node(package='controller_manager', executable='spawner', arguments=['joint_broad']),
        Node(package='robot_localization', executable='ekf_node', parameters=[ekf]),
        Node(package='tf2_ros', executable='static_transform_publisher',
             arguments=['--x', '0.1', '--frame-id', 'base_link', '--child-frame-id', 'laser']),
    ])
"""

CONTROLLERS = """
controller_manager:
  ros__parameters:
    diff_cont:
      type: diff_drive_controller/DiffDriveController
    joint_broad:
      type: joint_state_broadcaster/JointStateBroadcaster
diff_cont:
  ros__parameters:
    left_wheel_names: ["left_wheel_joint"]
    right_wheel_names: ["right_whel_joint"]
    wheel_separation: 0.5
    wheel_radius: 0.1
"""


def workspace(tmp_path: Path) -> Path:
    """src/{bot_description, bot_control, bot_bringup} in two repositories."""
    d = pkg(tmp_path / "src" / "bot" / "bot_description", "bot_description")
    for size in ("small", "large"):
        write(d / "urdf" / size / "bot.urdf.xacro", ROBOT)
    write(d / "launch" / "description.launch.py", DESCRIPTION_LAUNCH)
    c = pkg(tmp_path / "src" / "bot" / "bot_control", "bot_control")
    write(c / "config" / "controllers.yaml", CONTROLLERS)
    b = pkg(tmp_path / "src" / "deploy" / "nested" / "bot_bringup", "bot_bringup")
    write(b / "launch" / "bringup.launch.py", BRINGUP_LAUNCH)
    write(b / "config" / "ekf.yaml", "ekf_filter_node:\n  ros__parameters:\n    world_frame: odom\n"
                                     "    base_link_frame: base_link\n    publish_tf: true\n")
    return tmp_path


def test_deployment_from_an_included_python_launch_file(tmp_path, monkeypatch):
    root = workspace(tmp_path)
    monkeypatch.chdir(tmp_path)
    deps = find_deployments(root / "src")
    assert not (tmp_path / "PWNED").exists()
    bringup = root / "src" / "deploy" / "nested" / "bot_bringup" / "launch" / "bringup.launch.py"
    assert [d.variant for d in deps] == ["", "model=large"]
    small, large = deps
    assert small.model.endswith("urdf/small/bot.urdf.xacro") and large.model.endswith("urdf/large/bot.urdf.xacro")
    assert small.args == {"wheel_sep": "0.5"}  # the including file's argument, not the default 0.4
    assert small.launch.file == str(bringup)  # the root of the include chain defines the deployment
    include_line = BRINGUP_LAUNCH.splitlines().index("        IncludeLaunchDescription(") + 1
    assert [loc.line for loc in small.chain] == [include_line]
    assert small.rsp.file.endswith("description.launch.py")
    assert small.controller_files == [str(root / "src" / "bot" / "bot_control" / "config" / "controllers.yaml")]
    assert [n for n, _ in small.spawned] == ["diff_cont", "joint_broad"]
    assert small.localization_files[0].endswith("bot_bringup/config/ekf.yaml")
    assert [(t.parent, t.child) for t in small.static_tfs] == [("base_link", "laser")]
    assert small.label == "src/deploy/nested/bot_bringup/launch/bringup.launch.py"
    text = describe(deps)
    assert small.chosen_args() == {"wheel_sep": "0.5"}  # passed by the including file: not a launch default
    assert "  model: src/bot/bot_description/urdf/large/bot.urdf.xacro\n    wheel_sep:=0.5\n" in text
    assert ("spawned: diff_cont (diff_drive_controller/DiffDriveController), "
            "joint_broad (joint_state_broadcaster/JointStateBroadcaster)") in text


def test_contract_checks_run_on_the_deployment_model(tmp_path, monkeypatch):
    root = workspace(tmp_path)
    monkeypatch.chdir(tmp_path)
    dep = find_deployments(root / "src")[0]
    exp = loader.expand(dep.model, dep.args, packages=workspace_map(root / "src", near=dep.model))
    model = loader.build_model(exp)
    assert model is not None, exp.findings
    assert abs(model.joints["left_wheel_joint"].origin.xyz[1] - 0.25) < 1e-9  # wheel_sep:=0.5 reached the model
    ctx = engine.Context(expanded=exp, contracts=dep.consumers(), selection=engine.Selection(("C001",)))
    found = [f for f in engine.run_checks(model, ctx) if f.code == "C001"]
    assert len(found) == 1 and "right_whel_joint" in found[0].message
    assert found[0].location.file.endswith("controllers.yaml")


def test_a_model_chosen_by_an_environment_variable_gives_one_deployment_per_file(tmp_path, monkeypatch):
    d = pkg(tmp_path / "desc", "desc")
    for name in ("2wd", "4wd"):
        write(d / "urdf" / "robots" / f"{name}.urdf.xacro", ROBOT)
    write(d / "launch" / "d.launch.py", """
import os
from launch_ros.actions import Node
from launch.actions import DeclareLaunchArgument
from launch.substitutions import Command, LaunchConfiguration, PathJoinSubstitution
from launch_ros.substitutions import FindPackageShare
base = os.getenv('ROBOT_BASE')
path = PathJoinSubstitution([FindPackageShare('desc'), 'urdf/robots', f'{base}.urdf.xacro'])
def generate_launch_description():
    return [DeclareLaunchArgument(name='urdf', default_value=path),
            Node(package='robot_state_publisher', executable='robot_state_publisher',
                 parameters=[{'robot_description': Command(['xacro ', LaunchConfiguration('urdf')])}])]
""")
    monkeypatch.setenv("ROBOT_BASE", "4wd")  # never read: the environment of the runner decides nothing
    deps = find_deployments(tmp_path)
    assert [d.variant for d in deps] == ["model=2wd.urdf.xacro", "model=4wd.urdf.xacro"]


def test_a_required_argument_with_choices_gives_one_deployment_per_choice(tmp_path):
    d = pkg(tmp_path / "arm", "arm")
    write(d / "urdf" / "arm.urdf.xacro", ROBOT)
    write(d / "launch" / "arm.launch.py", """
from launch.actions import DeclareLaunchArgument
from launch.substitutions import Command, FindExecutable, LaunchConfiguration, PathJoinSubstitution
from launch_ros.actions import Node
from launch_ros.parameter_descriptions import ParameterValue
from launch_ros.substitutions import FindPackageShare
def generate_launch_description():
    kind = LaunchConfiguration('kind')
    content = Command([PathJoinSubstitution([FindExecutable(name='xacro')]), ' ',
                       PathJoinSubstitution([FindPackageShare('arm'), 'urdf', 'arm.urdf.xacro']), ' ',
                       'name:=', kind, ' ', 'ip:=', LaunchConfiguration('ip')])
    return [DeclareLaunchArgument('kind', choices=['a3', 'a5']), DeclareLaunchArgument('ip'),
            Node(package='robot_state_publisher', executable='robot_state_publisher',
                 parameters=[{'robot_description': ParameterValue(content, value_type=str)}])]
""")
    deps = find_deployments(tmp_path)
    assert [(d.variant, d.args) for d in deps] == [("kind=a3", {"name": "a3"}), ("kind=a5", {"name": "a5"})]
    assert deps[0].dropped_args == ["ip"]  # no default: decided at launch time, the xacro default is used


def test_xml_launch_files_ros2_command_and_ros1_param(tmp_path):
    d = pkg(tmp_path / "demo", "demo")
    write(d / "description" / "urdf" / "demo.urdf.xacro", ROBOT)  # source layout; installed as share/demo/urdf
    write(d / "bringup" / "config" / "ctl.yaml", CONTROLLERS)
    command = "xacro $(find-pkg-share demo)/urdf/demo.urdf.xacro wheel_sep:=$(var sep)"
    write(d / "bringup" / "launch" / "demo.launch.xml", f"""<launch>
  <arg name="sep" default="0.6"/>
  <let name="robot_description" value="$(command '{command}')"/>
  <node pkg="robot_state_publisher" exec="robot_state_publisher">
    <param name="robot_description" value="$(var robot_description)"/>
  </node>
  <node pkg="controller_manager" exec="spawner" args="diff_cont -p $(find-pkg-share demo)/config/ctl.yaml"/>
</launch>
""")
    old = pkg(tmp_path / "old", "old")
    write(old / "urdf" / "old.xacro", ROBOT)
    write(old / "launch" / "view.launch", """<launch>
  <param name="robot_description" command="$(find xacro)/xacro --inorder '$(find old)/urdf/old.xacro' wheel_sep:=0.3"/>
  <node name="rsp" pkg="robot_state_publisher" type="robot_state_publisher"/>
</launch>
""")
    deps = {Path(d.launch.file).name: d for d in find_deployments(tmp_path)}
    assert deps["demo.launch.xml"].model == str(d / "description" / "urdf" / "demo.urdf.xacro")
    assert deps["demo.launch.xml"].args == {"wheel_sep": "0.6"}
    assert deps["demo.launch.xml"].controller_files == [str(d / "bringup" / "config" / "ctl.yaml")]
    assert deps["view.launch"].model == str(old / "urdf" / "old.xacro")
    assert deps["view.launch"].args == {"wheel_sep": "0.3"}


def test_what_is_not_understood_is_said(tmp_path):
    d = pkg(tmp_path / "p", "p")
    write(d / "launch" / "x.launch.py", """
from launch_ros.actions import Node
def generate_launch_description():
    desc = make_description()
    return [Node(package='robot_state_publisher', executable='robot_state_publisher',
                 parameters=[{'robot_description': desc}])]
""")
    write(d / "launch" / "broken.launch.py", "def (:\n")
    deps = find_deployments(tmp_path)
    assert len(deps) == 1 and deps[0].model is None
    assert any("not understood" in m for m, _ in deps[0].notes)
    assert "model: not understood" in describe(deps)


def test_a_custom_driver_is_read_by_the_shape_of_its_keys_and_warns(tmp_path, monkeypatch):
    root = workspace(tmp_path)
    monkeypatch.chdir(tmp_path)
    b = root / "src" / "deploy" / "nested" / "bot_bringup"
    write(b / "config" / "base.yaml", "my_base:\n  ros__parameters:\n    left_wheel_names: [left_wheel_joint]\n"
                                      "    right_wheel_names: [right_wheel_joint]\n    wheel_separation: 0.7\n"
                                      "    wheel_radius: 0.1\n    base_frame_id: base_lnk\n")
    launch = b / "launch" / "bringup.launch.py"
    launch.write_text(launch.read_text().replace(
        "        Node(package='robot_localization'",
        "        Node(package='my_base_driver', executable='driver', name='my_base',\n"
        "             parameters=[os.path.join(get_package_share_directory('bot_bringup'), 'config', 'base.yaml')]),\n"
        "        Node(package='robot_localization'"))
    dep = find_deployments(root / "src")[0]
    assert [n.package for n, _ in dep.driver_nodes] == ["my_base_driver"]
    exp = loader.expand(dep.model, dep.args, packages=workspace_map(root / "src", near=dep.model))
    model = loader.build_model(exp)
    ctx = engine.Context(expanded=exp, contracts=dep.consumers(), selection=engine.Selection(("C010", "C020")))
    found = {f.code: f for f in engine.run_checks(model, ctx)}
    assert set(found) == {"C010", "C020"}
    assert all(f.severity.name == "WARNING" for f in found.values())  # inferred meaning: warnings, not errors
    assert "base_lnk" in found["C020"].message and found["C020"].location.file.endswith("base.yaml")


def test_a_controller_type_set_on_the_spawner_command_line(tmp_path, monkeypatch):
    root = workspace(tmp_path)
    monkeypatch.chdir(tmp_path)
    yaml = root / "src" / "bot" / "bot_control" / "config" / "controllers.yaml"
    yaml.write_text(CONTROLLERS.replace("      type: diff_drive_controller/DiffDriveController\n", ""))
    launch = root / "src" / "deploy" / "nested" / "bot_bringup" / "launch" / "bringup.launch.py"
    launch.write_text(launch.read_text().replace(
        "arguments=['diff_cont', '--controller-manager', '/controller_manager']",
        "arguments=['diff_cont', '-t', 'diff_drive_controller/DiffDriveController']"))
    dep = find_deployments(root / "src")[0]
    ctrls = {c.name: c for c in dep.consumers().controllers}
    assert ctrls["diff_cont"].type == "diff_drive_controller/DiffDriveController"
    assert [u.joint for u in ctrls["diff_cont"].joints] == ["left_wheel_joint", "right_whel_joint"]


def test_moveit_config_builder_and_yaml_launch_files(tmp_path):
    cfg = pkg(tmp_path / "arm_moveit_config", "arm_moveit_config")
    write(cfg / "config" / "arm.urdf.xacro", ROBOT)
    write(cfg / "launch" / "demo.launch.py", """
from launch_ros.actions import Node
from moveit_configs_utils import MoveItConfigsBuilder
def generate_launch_description():
    moveit_config = (MoveItConfigsBuilder("arm").robot_description(mappings={"wheel_sep": "0.9"})
                     .planning_pipelines(pipelines=["ompl"]).to_moveit_configs())
    return [Node(package="robot_state_publisher", executable="robot_state_publisher",
                 parameters=[moveit_config.robot_description])]
""")
    y = pkg(tmp_path / "ybot", "ybot")
    write(y / "urdf" / "y.urdf.xacro", ROBOT)
    command = "xacro $(find-pkg-share ybot)/urdf/y.urdf.xacro wheel_sep:=$(var sep)"
    write(y / "launch" / "y.launch.yaml", f"""launch:
- arg: {{name: sep, default: "0.2"}}
- node:
    pkg: robot_state_publisher
    exec: robot_state_publisher
    param:
    - {{name: robot_description, value: "$(command '{command}')"}}
""")
    deps = {Path(d.launch.file).name: d for d in find_deployments(tmp_path)}
    assert deps["demo.launch.py"].model == str(cfg / "config" / "arm.urdf.xacro")
    assert deps["demo.launch.py"].args == {"wheel_sep": "0.9"}
    assert deps["y.launch.yaml"].model == str(y / "urdf" / "y.urdf.xacro")
    assert deps["y.launch.yaml"].args == {"wheel_sep": "0.2"}


def test_hostile_launch_files_stay_cheap_and_are_never_run(tmp_path):

    d = pkg(tmp_path / "evil", "evil")
    write(d / "urdf" / "r.urdf.xacro", ROBOT)
    chain = "a0 = ['x']\n" + "".join(f"a{i + 1} = [a{i}, a{i}]\n" for i in range(60))  # 2**60 pieces
    nested = "(" * 80 + "'x'" + ")" * 80
    write(d / "launch" / "evil.launch.py", chain + f"""
import os
os.system('touch PWNED')
b = {nested}
from launch.substitutions import Command
from launch_ros.actions import Node
Node(package='robot_state_publisher', executable='robot_state_publisher',
     parameters=[{{'robot_description': Command(['xacro ', a60, ' x:=', b])}}])
Node(package='robot_state_publisher', executable='robot_state_publisher', namespace='n2',
     parameters=[{{'robot_description': Command(['xacro $(find evil)/urdf/r.urdf.xacro x:=', a60])}}])
""")
    deps: list = []
    work, error = counted(lambda: deps.extend(find_deployments(tmp_path)))
    assert error is None, error
    # 2**60 list pieces and 80 nested parentheses are not built (counted, not timed)
    assert work.calls < 2_000_000 and work.peak_bytes < 64 * 1024 * 1024, (work.calls, work.peak_bytes)
    assert not (tmp_path / "PWNED").exists() and not (d / "launch" / "PWNED").exists()
    assert len(deps) == 2 and all(x.model is None for x in deps)


def test_an_alternative_included_under_a_false_condition_is_no_deployment_of_its_own(tmp_path):
    root = workspace(tmp_path)
    b = root / "src" / "deploy" / "nested" / "bot_bringup"
    write(b / "launch" / "alternative.launch.py", """
import os
from ament_index_python.packages import get_package_share_directory
from launch.actions import IncludeLaunchDescription
from launch.launch_description_sources import PythonLaunchDescriptionSource
def generate_launch_description():
    desc = get_package_share_directory('bot_description')
    return [IncludeLaunchDescription(PythonLaunchDescriptionSource(
        os.path.join(desc, 'launch', 'description.launch.py')), launch_arguments={'wheel_sep': '0.8'}.items())]
""")
    launch = b / "launch" / "bringup.launch.py"
    launch.write_text(launch.read_text().replace("    return LaunchDescription([", """    return LaunchDescription([
        DeclareLaunchArgument('alt', default_value='false'),
        IncludeLaunchDescription(PythonLaunchDescriptionSource(
            os.path.join(get_package_share_directory('bot_bringup'), 'launch', 'alternative.launch.py')),
            condition=IfCondition(LaunchConfiguration('alt'))),""").replace(
        "from launch.actions import IncludeLaunchDescription",
        "from launch.actions import DeclareLaunchArgument, IncludeLaunchDescription\n"
        "from launch.conditions import IfCondition\nfrom launch.substitutions import LaunchConfiguration"))
    deps = find_deployments(root / "src")
    assert {Path(d.launch.file).name for d in deps} == {"bringup.launch.py"}
    assert {d.args["wheel_sep"] for d in deps} == {"0.5"}


def test_spawners_made_by_a_local_helper_function(tmp_path):
    d = pkg(tmp_path / "arm", "arm")
    write(d / "urdf" / "arm.urdf.xacro", ROBOT)
    write(d / "launch" / "arm.launch.py", """
from launch.substitutions import Command
from launch_ros.actions import Node
def launch_setup(context, *args):
    def controller_spawner(controllers, active=True):
        inactive_flags = ["--inactive"] if not active else []
        return Node(package="controller_manager", executable="spawner",
                    arguments=["--controller-manager", "/controller_manager"] + inactive_flags + controllers)
    active = ["joint_state_broadcaster", "arm_controller"]
    return [controller_spawner(active), controller_spawner(["spare_controller"], active=False),
            Node(package="robot_state_publisher", executable="robot_state_publisher",
                 parameters=[{"robot_description": Command(["xacro ", "$(find arm)/urdf/arm.urdf.xacro"])}])]
""".replace("$(find arm)", str(d)))
    dep = find_deployments(tmp_path)[0]
    assert [n for n, _ in dep.spawned] == ["joint_state_broadcaster", "arm_controller", "spare_controller"]
    spawners = [n for n in dep.infos[0].nodes if n.executable == "spawner"]
    assert [n.args.count("--inactive") for n in spawners] == [0, 1]


def test_lint_list_shows_each_deployment_once_with_controllers_and_publishers(tmp_path, monkeypatch, capsys):
    from urdfcheck.cli import main as cli

    workspace(tmp_path)
    monkeypatch.chdir(tmp_path)
    assert cli.main(["lint", "--list", "src"]) == 0
    out = capsys.readouterr().out
    assert not (tmp_path / "PWNED").exists()
    # found once for the named folder: the bringup file is the root, the description file it includes is not
    assert out.count("\nsrc/deploy/nested/bot_bringup/launch/bringup.launch.py\n") == 1
    assert "\nsrc/bot/bot_description/launch/description.launch.py" not in out
    assert "spawned: diff_cont (diff_drive_controller/DiffDriveController)" in out
    assert "publishers: robot_state_publisher" in out and "static transforms: base_link->laser" in out
    assert "localization: ekf" in out
    assert "2 deployment(s), 2 with a model" in out


def test_list_counts_arguments_equal_to_launch_defaults_and_shows_paths_relative(tmp_path, monkeypatch):
    """The description package's own launch file, alone: wheel_sep is its declared default (counted, not
    listed); a xacro argument naming a file below the working directory is shown relative."""
    root = workspace(tmp_path)
    launch = root / "src" / "bot" / "bot_description" / "launch" / "description.launch.py"
    launch.write_text(DESCRIPTION_LAUNCH.replace(
        "' wheel_sep:=',", "' limits:=', PathJoinSubstitution([FindPackageShare('bot_description'), 'config', "
                           "'limits.yaml']), ' wheel_sep:=',"))
    write(root / "src" / "bot" / "bot_description" / "config" / "limits.yaml", "a: 1\n")
    monkeypatch.chdir(tmp_path)
    deps = find_deployments(root / "src" / "bot")
    small = deps[0]
    assert small.args["wheel_sep"] == "0.4" and small.chosen_args() == {
        "limits": str(root / "src" / "bot" / "bot_description" / "config" / "limits.yaml")}
    text = describe(deps)
    assert "model: src/bot/bot_description/urdf/small/bot.urdf.xacro (+1 xacro argument(s) equal to launch " \
           "defaults)\n    limits:=src/bot/bot_description/config/limits.yaml\n" in text
    assert "wheel_sep:=" not in text and str(tmp_path) not in text

    import contextlib
    import io

    from urdfcheck.cli import main as cli

    buf = io.StringIO()
    with contextlib.redirect_stdout(buf):
        assert cli.main(["lint", "--list", "src/bot"]) == 0
    out = buf.getvalue()
    assert str(tmp_path) not in out, out
    first = out.splitlines()[0]  # the target line: model, launch file, the choices (files below)
    assert first == ("src/bot/bot_description/urdf/small/bot.urdf.xacro "
                     "[src/bot/bot_description/launch/description.launch.py] (+2 more)"), out
    with contextlib.redirect_stdout(io.StringIO()) as buf2:
        assert cli.main(["lint", "--list", "--root", "src", "src/bot"]) == 0
    assert buf2.getvalue().splitlines()[0] == ("bot/bot_description/urdf/small/bot.urdf.xacro "
                                               "[bot/bot_description/launch/description.launch.py] (+2 more)")
    assert "    limits:=bot/bot_description/config/limits.yaml\n" in buf2.getvalue()
    # every report: the JSON models' variant (the launch file) and arguments, relative to --root too
    import json

    with contextlib.redirect_stdout(io.StringIO()) as buf3:
        cli.main(["lint", "--format", "json", "--root", "src", "src/bot"])
    got = json.loads(buf3.getvalue())
    assert str(tmp_path) not in buf3.getvalue()
    assert {m["variant"] for m in got["models"]} == {"bot/bot_description/launch/description.launch.py",
                                                     "bot/bot_description/launch/description.launch.py [model=large]"}
    assert {m["args"]["limits"] for m in got["models"]} == {"bot/bot_description/config/limits.yaml"}
    assert all(p["variant"].startswith("bot/") for f in got["findings"] for p in f.get("where", ()))
