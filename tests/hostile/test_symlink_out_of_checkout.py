"""A pull request commits symbolic links that lead out of the checkout (CI's working directory).

Whatever they point at, urdfcheck names the link as a finding and reads nothing behind it, unless the run is
--trusted. Links that stay inside the checkout work as before.
"""
import json
import os

import pytest
from conftest import run_cli

pytestmark = pytest.mark.skipif(not hasattr(os, "symlink"), reason="needs symbolic links")

SECRET = "RUNNER_SECRET_4711"
BAD_URDF = f"""<robot name="r">
  <link name="base_link"/>
  <link name="{SECRET}"/>
  <joint name="j" type="{SECRET}_type"><parent link="base_link"/><child link="{SECRET}"/></joint>
</robot>
"""
GOOD_URDF = """<robot name="r">
  <link name="base_link"/>
  <link name="arm"/>
  <joint name="left_wheel_joint" type="continuous"><parent link="base_link"/><child link="arm"/>
    <axis xyz="0 1 0"/></joint>
</robot>
"""
CTRL = f"""diff_drive_controller:
  ros__parameters:
    type: diff_drive_controller/DiffDriveController
    left_wheel_names: [{SECRET}]
"""


@pytest.fixture
def places(tmp_path):
    checkout, outside = tmp_path / "checkout", tmp_path / "outside"
    (outside / "desc" / "urdf").mkdir(parents=True)
    (outside / "desc" / "package.xml").write_text("<package><name>desc</name></package>")
    (outside / "desc" / "urdf" / "r.urdf").write_text(BAD_URDF)
    (outside / "ctrl.yaml").write_text(CTRL)
    (outside / "r.urdf").write_text(BAD_URDF)
    pkg = checkout / "robot_description"
    (pkg / "urdf").mkdir(parents=True)
    (pkg / "config").mkdir()
    (pkg / "package.xml").write_text("<package><name>robot_description</name></package>")
    (pkg / "urdf" / "robot.urdf").write_text(GOOD_URDF)
    return checkout, outside


def lint(checkout, *args):
    code, out, err = run_cli(["lint", "--format", "json", *args], cwd=checkout)
    assert "Traceback" not in err
    return code, out + err, [(f["code"], f["location"]["file"]) for f in json.loads(out)["findings"]] if out else []


def test_a_linked_folder_named_on_the_command_line(places):
    checkout, outside = places
    os.symlink(outside / "desc", checkout / "other_description")
    code, text, found = lint(checkout, "other_description")
    assert code == 1 and found == [("X014", "other_description")] and SECRET not in text
    code, text, _ = lint(checkout, "other_description", "--trusted")  # your own files: followed
    assert code == 1 and SECRET in text


def test_a_file_reached_through_a_linked_folder(places):
    checkout, outside = places
    os.symlink(outside / "desc", checkout / "other_description")
    code, text, found = lint(checkout, "other_description/urdf/r.urdf")
    assert code == 1 and [c for c, _ in found] == ["X014"] and SECRET not in text


def test_a_linked_controller_file_in_a_package(places):
    checkout, outside = places
    os.symlink(outside / "ctrl.yaml", checkout / "robot_description" / "config" / "ctrl.yaml")
    code, text, found = lint(checkout, "robot_description")
    assert code == 1 and ("C007", "robot_description/config/ctrl.yaml") in found
    assert "symbolic link" in text and SECRET not in text


def test_a_linked_model_file_in_a_package(places):
    checkout, outside = places
    os.symlink(outside / "r.urdf", checkout / "robot_description" / "urdf" / "r.urdf")
    code, text, found = lint(checkout, "robot_description")
    assert code == 1 and [c for c, _ in found] == ["X014"] and SECRET not in text


def test_links_inside_the_checkout_are_followed(places):
    checkout, _ = places
    os.symlink(checkout / "robot_description", checkout / "alias_description")
    code, text, found = lint(checkout, "alias_description")
    assert code == 0, text


def test_trusted_runs_classify_files_behind_a_linked_folder_as_usual(places):
    checkout, outside = places
    urdf = outside / "desc" / "urdf"
    (urdf / "r.urdf").unlink()
    (urdf / "parts.xacro").write_text('<robot xmlns:xacro="http://www.ros.org/wiki/xacro">\n'
                                      '  <xacro:macro name="arm"><link name="arm"/></xacro:macro>\n</robot>\n')
    (urdf / "robot.urdf.xacro").write_text('<robot name="r" xmlns:xacro="http://www.ros.org/wiki/xacro">\n'
                                           '  <xacro:include filename="parts.xacro"/>\n'
                                           '  <link name="base_link"/>\n  <xacro:arm/>\n'
                                           '  <joint name="j" type="fixed"><parent link="base_link"/>'
                                           '<child link="arm"/></joint>\n</robot>\n')
    os.symlink(outside / "desc", checkout / "other_description")
    code, text, found = lint(checkout, "other_description", "--trusted")
    assert code == 0, text  # the macro library is expanded through the robot, not linted as a model
    assert json.loads(run_cli(["lint", "--format", "json", "--trusted", "other_description"],
                              cwd=checkout)[1])["models"][0]["path"].endswith("robot.urdf.xacro")
    code, text, found = lint(checkout, "other_description")
    assert code == 1 and found == [("X014", "other_description")]
