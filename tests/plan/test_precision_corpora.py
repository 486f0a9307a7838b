"""Precision on the corpora (issue 37, docs/triage.md): each planning guess that made a zero-config run red on a
correct repository, reproduced by a small package under tests/data/precision37 and linted with the real command
line from inside it, as a new user would."""
from __future__ import annotations

import shutil
from pathlib import Path

import pytest
from conftest import lint_json

DATA = Path(__file__).parent.parent / "data" / "precision37"


@pytest.fixture
def repo(tmp_path):
    def copy(name):
        dst = tmp_path / name
        shutil.copytree(DATA / name, dst)
        return dst
    return copy


def _hard(report):
    return [(f["code"], f["location"]["file"], f["message"]) for f in report["findings"]
            if f["severity"] in ("warning", "error")]


def test_a_required_launch_argument_is_no_model_path_and_the_license_is_no_robot(repo):
    # abb_ros2: the model is `xacro <robot_xacro_file>`, an argument without default: the path was nothing but a
    # launch-time piece, matched against the working directory, and LICENSE and README.md were linted as robots
    root = repo("launch_arg_model")
    code, report = lint_json([], cwd=root)
    assert _hard(report) == [] and code == 0
    assert not [f for f in report["findings"] if f["location"]["file"] in ("LICENSE", "README.md")]
    (c021,) = [f for f in report["findings"] if f["code"] == "C021"]
    assert c021["severity"] == "info" and "decided at launch time" in c021["message"]


def test_an_sdformat_model_given_to_robot_state_publisher_is_not_linted_as_urdf(repo):
    # ros_gz_project_template: robot_state_publisher reads model.sdf (through sdformat_urdf); it was linted as a
    # URDF (U001 error "root element is <sdf>"); now the deployment is said not understood, at info
    root = repo("sdf_model")
    code, report = lint_json([], cwd=root)
    assert _hard(report) == [] and code == 0
    (c021,) = [f for f in report["findings"] if f["code"] == "C021"]
    assert "SDFormat" in c021["message"] and c021["severity"] == "info"


def test_a_package_outside_the_checkout_is_the_workspaces_business(repo):
    # turtlebot4, rexrov2, panther: `$(find dependency)` of a package the repository does not contain
    root = repo("outside_package")
    (root / "bot_description" / "urdf" / "typo.urdf.xacro").unlink()
    _, report = lint_json([], cwd=root)
    (x013,) = [f for f in report["findings"] if f["code"] == "X013"]
    assert x013["severity"] == "info"
    assert "to confirm: pass --package vendor_sensors_description=PATH" in x013["message"]
    assert [s["how"] for s in x013["evidence"] if not s["evidence"]] == ["outside"]
    assert _hard(report) == []


def test_a_misspelt_package_of_the_checkout_stays_an_error(repo):
    root = repo("outside_package")
    code, report = lint_json([], cwd=root)
    x013 = {f["message"].split("'")[1]: f["severity"] for f in report["findings"] if f["code"] == "X013"}
    assert x013 == {"vendor_sensors_description": "info", "bot_descripton": "error"} and code == 1


def test_a_required_xacro_argument_of_a_model_no_launch_file_runs_is_an_info(repo):
    # Universal_Robots_ROS2_Description's ur.urdf.xacro: `name` has no default; the deployment that gives it is
    # what is missing from a zero-config run of the description package, not a defect of the model
    root = repo("required_arg")
    _, report = lint_json([], cwd=root)
    (x010,) = [f for f in report["findings"] if f["code"] == "X010"]
    assert x010["severity"] == "info" and "'name' has no default" in x010["message"]
    assert "to confirm: lint the launch file that runs it" in x010["message"]
    assert _hard(report) == []
    # named by the runner, the model is theirs to give arguments to: the error stays
    code, report = lint_json(["arm_description/urdf/arm.urdf.xacro"], cwd=root)
    assert [f["severity"] for f in report["findings"] if f["code"] == "X010"] == ["error"] and code == 1


def test_other_tools_yaml_in_a_config_folder_is_not_read_as_ros_parameters(repo):
    # tracked_vehicle_demo's VINS camera files (OpenCV FileStorage, `%YAML:1.0`) and ar4's ros_gz_bridge topic
    # list were C007 errors "YAML syntax error" / "must be a mapping"; a broken ROS parameter file still is one
    root = repo("foreign_yaml")
    code, report = lint_json([], cwd=root)
    c007 = [(f["location"]["file"], f["severity"]) for f in report["findings"] if f["code"] == "C007"]
    assert c007 == [("rover_description/config/broken.yaml", "error")] and code == 1


def test_an_option_alone_keeps_the_error_and_a_combination_of_options_is_an_info(repo):
    # franka_description / vrx: five options, so pairwise variants, each flipping several at once; what one
    # option breaks is now shown in the variant of that option alone, and what only a combination no launch
    # file uses breaks rests on a guess
    root = repo("variants")
    code, report = lint_json([], cwd=root)
    hard = [(f["code"], f["location"]["line"], f["variant"]) for f in report["findings"]
            if f["severity"] in ("warning", "error")]
    assert hard == [("S007", 11, "mirror=true")] and code == 1
    hitch = [f for f in report["findings"] if f["location"]["line"] in (18, 19)]
    assert hitch and all(f["severity"] == "info" for f in hitch)
    assert all("options set together" in f["message"] for f in hitch)


def test_a_file_whose_path_is_handed_to_a_macro_that_includes_it_is_a_fragment(repo):
    # vrx: `<xacro:wamv_gazebo thruster_layout="$(find wamv_gazebo)/urdf/thruster_layouts/wamv_aft_thrusters.xacro"/>`
    # and the macro's `<xacro:include filename="${thruster_layout}"/>`: the layout, linted alone, failed on the
    # includer's `namespace` (X010 error)
    root = repo("macro_path")
    code, report = lint_json([], cwd=root)
    assert _hard(report) == [] and code == 0


def test_a_file_of_includes_only_is_a_library_when_its_expansion_has_no_link(repo):
    # uuv_simulator's snippets.xacro / sensor_snippets.xacro: S011 error "the model defines no <link>"
    root = repo("include_only")
    _, report = lint_json([], cwd=root)
    assert _hard(report) == []


def test_parts_attached_to_another_robots_link_are_no_robot_but_a_misspelt_parent_is_an_error(repo):
    # intera_common's controller_box.urdf: every link hangs from Sawyer's `base` (S003 error "parent link 'base'
    # is not defined"); arm.urdf has its root link and a misspelt parent
    root = repo("attachable")
    code, report = lint_json([], cwd=root)
    s003 = sorted((f["location"]["file"].rsplit("/", 1)[-1], f["severity"]) for f in report["findings"]
                  if f["code"] == "S003")
    assert s003 == [("arm.urdf", "error"), ("controller_box.urdf", "info"), ("controller_box.urdf", "info")]
    assert code == 1


def test_a_model_chosen_by_eval_conditions_is_the_one_the_launch_file_runs(repo):
    # ned_ros: `<arg name="urdf_path" value="...gripper1_n_camera.urdf.xacro" if="$(eval simulation_mode and
    # gazebo and simu_gripper)"/>`: the `and`/`not` conditions were undecided, the last definition won, and the
    # gripper's controller file was checked against the model without the gripper (C001 error)
    root = repo("eval_model")
    code, report = lint_json([], cwd=root)
    assert _hard(report) == [] and code == 0
    # and a path decided at launch time is shown as reports show paths, never the runner's absolute folder
    assert not [f for f in report["findings"] if str(root) in f["message"]]


def test_a_missing_mesh_named_by_a_file_uri_is_shown_without_the_runners_folder(repo):
    # denso_robot_ros2: G001 "mesh 'file:////work/shared/corpus2/...'": the runner's absolute path in a report
    root = repo("file_uri")
    _, report = lint_json([], cwd=root)
    (g001,) = [f for f in report["findings"] if f["code"] == "G001"]
    assert str(root) not in g001["message"] and "cam_description/meshes/base.dae" in g001["message"]


def test_a_controller_the_deployment_configures_but_does_not_spawn_rests_on_a_guess(repo):
    # schunk_svh_ros_driver: the launch file spawns only the hand its `control` argument names (right_hand);
    # left_hand, configured in the same file for the other choice, was checked against the right hand (C001)
    root = repo("idle_controller")
    code, report = lint_json([], cwd=root)
    assert _hard(report) == [] and code == 0
    (c001,) = [f for f in report["findings"] if f["code"] == "C001"]
    assert "Left_Finger" in c001["message"] and "not spawned by this deployment" in c001["message"]


def test_a_launch_argument_choice_that_needs_the_users_own_file_is_an_info(repo):
    # panther_ros: `wheel_type:=custom` reads config/custom.yaml, which its users provide (X010 error); the
    # default choice keeps the error if its file is missing
    root = repo("choice_files")
    _, report = lint_json([], cwd=root)
    (x010,) = [f for f in report["findings"] if f["code"] == "X010"]
    assert x010["severity"] == "info" and "custom.yaml" in x010["message"]
    assert "a launch-argument value other than the default" in x010["message"]
    (root / "wh_description" / "config" / "WH01.yaml").unlink()
    code, report = lint_json([], cwd=root)
    assert [f["severity"] for f in report["findings"] if f["code"] == "X010" and "WH01" in f["message"]] == ["error"]
    assert code == 1


def test_ros1_joint_state_controller_extra_joints_are_state_sources():
    # diffbot: joint_state_controller `extra_joints: [{name: rear_caster_rotation_joint, ...}]` publishes the
    # passive caster's joint; C003 said nothing publishes it
    from urdfcheck.consumers.controllers import read_controllers
    from urdfcheck.consumers.params import parse_params

    text = ("diffbot:\n  joint_state_controller:\n    type: joint_state_controller/JointStateController\n"
            "    extra_joints:\n      - name: rear_caster_rotation_joint\n        position: 0.01\n"
            "      - name: rear_caster_wheel_joint\n")
    (jsc,) = list(read_controllers([parse_params(text, "diffbot_control.yaml")]))
    assert [u.joint for u in jsc.state_joints] == ["rear_caster_rotation_joint", "rear_caster_wheel_joint"]


def test_a_xacro_argument_a_launch_file_passes_from_a_required_launch_argument_is_an_info(repo):
    # denso_robot_ros2: `model:=<LaunchConfiguration('model')>`, a launch argument without default (X010 error)
    root = repo("launch_required")
    _, report = lint_json([], cwd=root)
    (x010,) = [f for f in report["findings"] if f["code"] == "X010"]
    assert x010["severity"] == "info" and "a launch argument without default" in x010["message"]
    # a launch file that does not pass it at all keeps the error
    f = root / "arm_bringup" / "launch" / "bringup.launch.py"
    f.write_text(f.read_text().replace('" name:=", LaunchConfiguration("name")', '" "'))
    code, report = lint_json([], cwd=root)
    assert [x["severity"] for x in report["findings"] if x["code"] == "X010"] == ["error"] and code == 1
