"""The evidence rule (issue 37): every target and consumer file records how it was chosen; a finding resting on a
guess is an info naming the guess and how to confirm it; pairing goes by reference first."""
from __future__ import annotations

import shutil
from pathlib import Path

import pytest
from conftest import REPO, lint_json

DATA = Path(__file__).parent.parent / "data" / "evidence"


@pytest.fixture
def pkg(tmp_path):
    def copy(name):
        dst = tmp_path / name
        shutil.copytree(DATA / name, dst)
        return dst
    return copy


def _errors(report):
    return [(f["code"], f["severity"], f["message"]) for f in report["findings"] if f["severity"] != "info"]


def test_a_controller_file_that_one_models_plugin_names_is_not_checked_against_the_other_model(pkg):
    # urdf/robot.urdf.xacro's gazebo_ros2_control plugin loads config/controllers.yaml; urdf/old_robot.urdf (an
    # older variant without the arm) shares the wheel joints: the file was checked against it too, C001 error
    root = pkg("plugin_names_controllers")
    code, report = lint_json(["."], cwd=root)
    assert _errors(report) == [] and code == 0
    assert not [f for f in report["findings"] if f["code"].startswith("C")]


def test_the_referenced_model_is_still_checked_against_its_file(pkg):
    root = pkg("plugin_names_controllers")
    f = root / "config" / "controllers.yaml"
    f.write_text(f.read_text().replace("joints: [arm_joint]", "joints: [arm_jiont]"))
    code, report = lint_json(["."], cwd=root)
    c001 = [x for x in report["findings"] if x["code"] == "C001"]
    assert [x["severity"] for x in c001] == ["error"] and code == 1
    assert c001[0]["model"].endswith("robot.urdf.xacro")
    steps = {s["how"] for s in c001[0]["evidence"]}
    assert "referenced" in steps and all(s["evidence"] for s in c001[0]["evidence"])


def test_a_pairing_by_joint_names_alone_is_an_info_that_says_how_to_confirm_it(pkg):
    # no model names the file: it is checked against both models whose joints it names, a guess
    root = pkg("overlap_only")
    code, report = lint_json(["."], cwd=root)
    assert code == 0
    (c001,) = [f for f in report["findings"] if f["code"] == "C001"]
    assert c001["severity"] == "info"
    assert "paired by the joint names it shares with the model" in c001["message"]
    assert "to confirm: name it under models: in urdfcheck.yaml" in c001["message"]
    guess = [s for s in c001["evidence"] if not s["evidence"]]
    assert [(s["what"], s["how"]) for s in guess] == [("parameters", "overlap")]
    assert "config/controllers.yaml for " in guess[0]["subject"] and "old_robot.urdf" in guess[0]["subject"]


def test_a_confirmed_pairing_keeps_the_severity(pkg):
    root = pkg("overlap_only")
    (root / "urdfcheck.yaml").write_text("models:\n  - path: urdf/old_robot.urdf\n"
                                         "    controllers: [config/controllers.yaml]\n")
    import json

    from conftest import run_cli

    code, out, _ = run_cli(["lint", "--format", "json", "."], cwd=root)
    found = [(f["code"], f["severity"]) for f in json.loads(out)["findings"] if f["code"] == "C001"]
    assert found == [("C001", "error")] and code == 1
    (f,) = [f for f in json.loads(out)["findings"] if f["code"] == "C001"]
    assert {s["how"] for s in f["evidence"]} == {"config"}


def test_the_json_report_says_how_the_model_was_chosen():
    _, report = lint_json(["examples/broken/zero_axis"], cwd=REPO)
    assert report["findings"]
    for f in report["findings"]:
        assert f["evidence"][0]["what"] == "model" and f["evidence"][0]["how"] == "complete"
    named = next(Path(REPO, "examples/broken/zero_axis").rglob("*.urdf*"))
    _, report = lint_json([str(named.relative_to(REPO))], cwd=REPO)
    assert report["findings"] and all(f["evidence"][0]["how"] == "named" for f in report["findings"])


def test_a_deployment_is_evidence_of_its_launch_file():
    _, report = lint_json(["examples/broken/contract_launch_override"], cwd=REPO)
    launched = [f for f in report["findings"] if f.get("evidence") and f["evidence"][0]["how"] == "launched"]
    assert launched, [(f["code"], f.get("evidence")) for f in report["findings"]]
    assert launched[0]["evidence"][0]["what"] == "deployment"
    assert launched[0]["evidence"][0]["subject"].endswith((".launch.py", ".launch.xml", ".launch"))


def test_a_description_launch_file_beside_the_model_claims_no_absence(pkg):
    # zero config: the package's only launch file starts robot_state_publisher alone (its model goes through a
    # wrapper script, not understood): it is meant to be included by a bringup file that starts the rest, so
    # "nothing publishes joint states" is not failed (the open-world rule's own page: info)
    root = pkg("description_launch")
    code, report = lint_json(["."], cwd=root)
    c003 = [f for f in report["findings"] if f["code"] == "C003"]
    assert [f["severity"] for f in c003] == ["info"] and code == 0
    assert "description launch file" in c003[0]["message"]


def test_a_launch_file_naming_a_file_name_that_several_models_share_is_a_guess(pkg):
    # robots/alpha/model.urdf and robots/beta/model.urdf: `$(arg robot)/model.urdf` names neither of them
    root = pkg("shared_name")
    code, report = lint_json(["."], cwd=root)
    c003 = [f for f in report["findings"] if f["code"] == "C003"]
    assert len(c003) == 2 and {f["severity"] for f in c003} == {"info"} and code == 0
    for f in c003:
        assert any(s["how"] == "guess" and s["what"] == "launch" for s in f["evidence"])


def test_fragments_a_package_lint_finds_are_infos_and_never_fail_it(pkg):
    # urdf/robot.urdf.xacro includes sensors/$(arg sensor).urdf.xacro (a computed name) and, in a comment, a drop-in
    # alternative chassis: those files rest on the robot's macros, properties and links; linted alone, the camera
    # gave X010 "unknown macro name" (error) and a model "not checked": a red run on a correct robot
    root = pkg("fragments")
    code, report = lint_json(["."], cwd=root)
    assert [f for f in report["findings"] if f["severity"] != "info"] == [] and code == 0
    (x010,) = [f for f in report["findings"] if f["code"] == "X010"]
    assert x010["location"]["file"].endswith("sensors/camera.urdf.xacro")
    assert [s["how"] for s in x010["evidence"]] == ["probe"]
    assert "may be a fragment of another model" in x010["message"]


def test_a_legacy_unprefixed_include_names_a_fragment(tmp_path):
    from urdfcheck.load.discover import discover

    (tmp_path / "package.xml").write_text("<package><name>legacy</name></package>")
    u = tmp_path / "urdf"
    u.mkdir()
    (u / "robot.urdf.xacro").write_text('<robot name="r" xmlns:xacro="http://www.ros.org/wiki/xacro">\n'
                                        '  <link name="base_link"/>\n  <include filename="arm.xacro"/>\n</robot>\n')
    (u / "arm.xacro").write_text('<robot xmlns:xacro="http://www.ros.org/wiki/xacro">\n  <link name="arm"/>\n'
                                 '  <joint name="j" type="fixed"><parent link="base_link"/>'
                                 '<child link="arm"/></joint>\n</robot>\n')
    found = discover(tmp_path)
    assert [p.rsplit("/", 1)[-1] for p in found.models] == ["robot.urdf.xacro"]
    assert [p.rsplit("/", 1)[-1] for p in found.probes] == ["arm.xacro"]


def test_a_boolean_launch_argument_that_reaches_a_xacro_argument_is_a_variant():
    # the launch file passes use_camera:=$(var use_camera) (default true): use_camera:=false is as free as the
    # xacro argument, and only that variant shows the driver stamping data in camera_link (C020); zero config
    # linted the launch default alone and passed
    code, report = lint_json(["--no-cache", "examples/broken/variant_camera_off"], cwd=REPO)
    c020 = [f for f in report["findings"] if f["code"] == "C020"]
    assert [f["severity"] for f in c020] == ["warning"] and code == 1
    assert "use_camera=false" in c020[0]["variant"]
    assert any(m["args"].get("use_camera") == "false" for m in report["models"])


def test_a_boolean_launch_argument_that_does_not_reach_the_model_adds_no_deployment(tmp_path):
    from urdfcheck.plan.deployments import find_deployments

    agv = tmp_path / "agv"
    shutil.copytree(Path(REPO, "examples/agv"), agv)
    launch = agv / "launch" / "agv.launch.xml"
    launch.write_text(launch.read_text().replace(
        '<arg name="use_camera"', '<arg name="use_rviz" default="false"/>\n  <node pkg="rviz2" exec="rviz2" '
        'if="$(var use_rviz)"/>\n  <arg name="use_camera"'))
    deps = find_deployments(agv)
    assert sorted(d.variant for d in deps if d.model) == ["", "use_camera=false"]


def _launch_pkg(tmp_path, name: str, launch_name: str, launch_text: str) -> Path:
    root = tmp_path / name
    (root / "urdf").mkdir(parents=True)
    (root / "launch").mkdir()
    (root / "package.xml").write_text(f"<package format='3'><name>{name}</name></package>")
    shutil.copy(DATA / "overlap_only" / "urdf" / "old_robot.urdf", root / "urdf" / "bot.urdf.xacro")
    (root / "launch" / launch_name).write_text(launch_text)
    return root


def _models(root):
    from urdfcheck.plan.deployments import find_deployments

    return [Path(d.model).name if d.model else None for d in find_deployments(root)]


def test_xacro_found_by_its_package_prefix_in_xml_launch(tmp_path):
    root = _launch_pkg(tmp_path, "prefixbot", "a.launch.xml", """<launch>
  <node pkg="robot_state_publisher" exec="robot_state_publisher">
    <param name="robot_description"
           value="$(command '$(find-pkg-prefix xacro)/bin/xacro $(find-pkg-share prefixbot)/urdf/bot.urdf.xacro')"/>
  </node>
</launch>
""")
    assert _models(root) == ["bot.urdf.xacro"]


def test_xacro_run_by_a_wrapper_script_in_ros1_launch(tmp_path):
    root = _launch_pkg(tmp_path, "wrapbot", "description.launch", """<launch>
  <arg name="config" default="base"/>
  <param name="robot_description"
         command="$(find wrapbot)/scripts/env_run $(find wrapbot)/urdf/configs/$(arg config)
                  $(find xacro)/xacro $(find wrapbot)/urdf/bot.urdf.xacro --inorder"/>
  <node name="robot_state_publisher" pkg="robot_state_publisher" type="robot_state_publisher"/>
</launch>
""")
    assert _models(root) == ["bot.urdf.xacro"]


def test_a_model_returned_by_a_function_of_the_launch_file_through_xacros_python_api(tmp_path):
    # andino's spawn_robot.launch.py, ar4's main.launch.py: `get_robot_description()` returns
    # xacro.process_file(...).toprettyxml(), its text edited (package:// -> file://): the deployment was C021
    root = _launch_pkg(tmp_path, "apibot", "spawn.launch.py", '''
import os
from ament_index_python.packages import get_package_share_directory
from launch import LaunchDescription
from launch_ros.actions import Node
from xacro import process_file


def get_robot_description(use_ros_control: str) -> str:
    doc = process_file(os.path.join(get_package_share_directory("apibot"), "urdf", "bot.urdf.xacro"),
                       mappings={"use_ros_control": use_ros_control})
    robot_desc = doc.toprettyxml(indent="  ")
    folder = get_package_share_directory("apibot")
    robot_desc = robot_desc.replace("package://apibot/", f"file://{folder}/")
    return robot_desc


def generate_launch_description():
    rsp = Node(package="robot_state_publisher", executable="robot_state_publisher",
               parameters=[{"robot_description": get_robot_description("true")}])
    return LaunchDescription([rsp])
''')
    from urdfcheck.plan.deployments import find_deployments

    (d,) = find_deployments(root)
    assert Path(d.model).name == "bot.urdf.xacro" and d.args == {"use_ros_control": "true"}


@pytest.mark.parametrize("launch, says", [
    ("a.launch.py", "it comes from `load_description()` of module my_robot_utils.description, which urdfcheck does "
                    "not run"),
    ("b.launch.py", "it comes from `robot.urdf()`, a method of class Robot of this launch file"),
    ("c.launch.py", "it is computed inside OpaqueFunction(launch_setup)"),
])
def test_a_model_computed_where_urdfcheck_does_not_read_is_one_precise_c021(launch, says):
    _, report = lint_json(["--no-cache", "tests/data/evidence/launch_constructs"], cwd=REPO)
    (c021,) = [f for f in report["findings"] if f["code"] == "C021" and f["location"]["file"].endswith(launch)]
    assert c021["severity"] == "info" and says in c021["message"]


def test_naming_a_fragment_lints_the_robot_that_includes_it(pkg):
    # sensors/camera.urdf.xacro is included by urdf/robot.urdf.xacro under a computed name: named alone it gave
    # X010 "unknown macro name" (error), the macro its includer defines
    root = pkg("fragments")
    code, report = lint_json(["urdf/sensors/camera.urdf.xacro"], cwd=root)
    assert [m["path"] for m in report["models"]] == ["urdf/robot.urdf.xacro"]
    assert report["findings"] == [] and code == 0


def test_a_robot_made_of_includes_alone_is_whole_not_a_probe(tmp_path):
    # its text has no link (the links come from the files it includes): expanded as a probe, but nothing includes
    # it, so it is a whole robot and its findings keep their severity
    root = tmp_path / "incbot"
    (root / "urdf").mkdir(parents=True)
    (root / "package.xml").write_text("<package format='3'><name>incbot</name></package>")
    src = next(Path(REPO, "examples/broken/zero_axis/urdf").glob("*.urdf"))
    body = src.read_text().split("?>", 1)[-1].strip()
    inner = body[body.index(">", body.index("<robot")) + 1: body.rindex("</robot>")]
    (root / "urdf" / "body.xacro").write_text(f'<robot xmlns:xacro="http://www.ros.org/wiki/xacro">{inner}</robot>\n')
    (root / "urdf" / "robot.urdf.xacro").write_text(
        '<robot name="incbot" xmlns:xacro="http://www.ros.org/wiki/xacro">\n'
        '  <xacro:include filename="body.xacro"/>\n</robot>\n')
    code, report = lint_json(["."], cwd=root)
    bad = [f for f in report["findings"] if f["severity"] != "info"]
    assert bad and code == 1
    assert all(f["evidence"][0]["how"] == "complete" for f in bad)


def test_a_controller_file_the_plugin_loads_only_in_another_branch_is_not_read(pkg):
    # andino_gz_classic: the gazebo_ros2_control plugin (which loads config/controllers.yaml) sits under
    # xacro:if use_ros2_control, the Gazebo diff-drive plugin under xacro:unless; the deployment runs the default
    # (false): the controllers' odom -> base_link was counted beside the plugin's, a false T001 error
    root = pkg("plugin_branch")
    code, report = lint_json(["."], cwd=root)
    assert [f for f in report["findings"] if f["severity"] != "info"] == [] and code == 0
    assert not [f for f in report["findings"] if f["code"] == "T001"]


def test_a_launch_file_pairs_by_the_folder_when_two_parameter_files_share_a_name(tmp_path):
    from urdfcheck.consumers.pairing import launch_files_named

    a, b = tmp_path / "config" / "a" / "controllers.yaml", tmp_path / "config" / "b" / "controllers.yaml"
    lf = tmp_path / "launch" / "a.launch"
    for f in (a, b, lf):
        f.parent.mkdir(parents=True, exist_ok=True)
    a.write_text("x: 1\n")
    b.write_text("x: 1\n")
    lf.write_text('<launch><param name="robot_description" textfile="$(find p)/urdf/a.urdf"/>'
                  '<rosparam file="$(find p)/config/a/controllers.yaml"/></launch>')
    got = launch_files_named([str(lf)], [str(tmp_path / "urdf" / "a.urdf"), str(tmp_path / "urdf" / "b.urdf")],
                             [str(a), str(b)])
    assert got == {str((tmp_path / "urdf" / "a.urdf").resolve()): {str(a.resolve())}}


def test_a_description_launch_file_whose_model_is_not_understood_claims_no_absence(pkg):
    # zero config pairs the model with the package's launch file; it starts robot_state_publisher alone with a model
    # from a generator script: a description launch file, meant to be included
    root = pkg("description_launch")
    lf = root / "launch" / "description.launch"
    text = lf.read_text()
    start, end = text.index('command="') + len('command="'), text.index('" />')
    lf.write_text(text[:start] + "$(find rover_description)/scripts/generate_description $(arg config)" + text[end:])
    code, report = lint_json(["."], cwd=root)
    c003 = [f for f in report["findings"] if f["code"] == "C003"]
    assert [f["severity"] for f in c003] == ["info"] and code == 0
    assert "description launch file" in c003[0]["message"]


def test_joints_a_workspace_broadcaster_does_not_name_rest_on_a_guessed_pairing(pkg):
    # moose: the description launch file starts robot_state_publisher alone; a JointStateController in another
    # package's control.yaml names the steering joint only (a ROS 1 controller publishes whatever the hardware
    # registers): "nothing publishes the state of the wheels" was a warning resting on that file's pairing
    root = pkg("workspace_broadcaster")
    code, report = lint_json(["."], cwd=root)
    c003 = [f for f in report["findings"] if f["code"] == "C003"]
    assert c003 and {f["severity"] for f in c003} == {"info"} and code == 0
    wheel = [f for f in c003 if "left_wheel_joint" in f["message"]]
    assert wheel and any(s["how"] == "overlap" and "control.yaml" in s["subject"] for s in wheel[0]["evidence"])


def test_a_symbol_from_a_package_the_includer_cannot_find_may_be_provided(tmp_path):
    from urdfcheck.plan.robots import includer_texts, provided

    inc = tmp_path / "base.xacro"
    inc.write_text('<robot xmlns:xacro="http://www.ros.org/wiki/xacro">\n'
                   '  <xacro:include filename="$(find sensor_plugins)/urdf/dvl.xacro"/>\n</robot>\n')
    texts = includer_texts([str(inc)], lambda name: None)
    assert provided("unknown macro name: xacro:default_dvl_macro", texts)
    found = includer_texts([str(inc)], lambda name: str(tmp_path) if name == "sensor_plugins" else None)
    assert not provided("unknown macro name: xacro:default_dvl_macro", found)
    assert provided("name 'ns' is not defined", ['<xacro:property name="ns" value="a"/>'])
    assert not provided("No such file or directory: x.xacro", ['<xacro:property name="ns" value="a"/>'])


def test_the_report_schema_knows_every_way_a_step_is_taken():
    """The JSON report's `evidence[].how` enum is core.evidence.HOW (a key added there and not here made every
    report with that step invalid)."""
    import json

    from conftest import REPO

    from urdfcheck.core.evidence import HOW

    schema = json.loads((REPO / "src/urdfcheck/schemas/report.schema.json").read_text())
    how = schema["$defs"]["finding"]["properties"]["evidence"]["items"]["properties"]["how"]["enum"]
    assert set(how) == set(HOW)
