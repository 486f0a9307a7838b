"""`lint FRAGMENT` where the robot includes the fragment only under a non-default xacro argument (issue 37): linted
through the variant of the robot that includes it, and said so (variant label, evidence `reaching`)."""
from __future__ import annotations

import os
from pathlib import Path

from conftest import lint_json, run_cli

from urdfcheck.core import door
from urdfcheck.load.reach import reaching

PACKAGE = """<?xml version="1.0"?>
<package format="3"><name>bot</name><version>0.0.0</version><description>x</description>
<maintainer email="a@b.c">a</maintainer><license>MIT</license><buildtool_depend>ament_cmake</buildtool_depend>
</package>
"""
ARM = """<?xml version="1.0"?>
<robot xmlns:xacro="http://www.ros.org/wiki/xacro">
  <xacro:macro name="arm" params="parent">
    <joint name="arm_joint" type="revolute">
      <parent link="${parent}"/>
      <child link="arm_link"/>
      <axis xyz="0 0 1"/>
      <limit lower="1" upper="-1" effort="1" velocity="1"/>
    </joint>
    <link name="arm_link"/>
  </xacro:macro>
</robot>
"""


def _robot(condition: str, arg: str, kind: str = "if", extra: str = "") -> str:
    return f"""<?xml version="1.0"?>
<robot name="r" xmlns:xacro="http://www.ros.org/wiki/xacro">
  {arg}
  {extra}
  <link name="base_link"/>
  <xacro:{kind} value="{condition}">
    <xacro:include filename="$(find bot)/urdf/arm.xacro"/>
    <xacro:arm parent="base_link"/>
  </xacro:{kind}>
</robot>
"""


def _package(root: Path, robot: str, launch: bool = False) -> Path:
    pkg = root / "bot"
    (pkg / "urdf").mkdir(parents=True)
    (pkg / "package.xml").write_text(PACKAGE)
    (pkg / "urdf" / "robot.urdf.xacro").write_text(robot)
    (pkg / "urdf" / "arm.xacro").write_text(ARM)
    if launch:  # the deployment runs the robot with its defaults
        (pkg / "launch").mkdir()
        (pkg / "launch" / "display.launch").write_text(
            '<launch>\n  <param name="robot_description" command="$(find xacro)/xacro '
            '$(find bot)/urdf/robot.urdf.xacro"/>\n'
            '  <node pkg="robot_state_publisher" type="robot_state_publisher" name="rsp"/>\n</launch>\n')
    return pkg


def _j003(report):
    return [f for f in report["findings"] if f["code"] == "J003"]


def test_a_fragment_a_literal_comparison_reaches_is_linted_through_that_value(tmp_path):
    _package(tmp_path, _robot("${'$(arg arm)' == 'small'}", '<xacro:arg name="arm" default="none"/>'))
    code, report = lint_json(["bot/urdf/arm.xacro"], cwd=tmp_path)
    (f,) = _j003(report)
    assert code == 1 and f["severity"] == "error" and f["location"]["file"] == "bot/urdf/arm.xacro"
    assert f["variant"] == "arm=small (includes arm.xacro)"
    assert ("reaching", True) in [(s["how"], s["evidence"]) for s in f["evidence"]]


def test_a_deployment_that_runs_the_robot_with_its_defaults_does_not_hide_the_fragment(tmp_path):
    # the launch file's deployment was the only target, with use_arm false: "All checks passed"
    _package(tmp_path, _robot("$(arg use_arm)", '<xacro:arg name="use_arm" default="false"/>'), launch=True)
    code, out, _ = run_cli(["lint", "--no-config", "--no-cache", "bot/urdf/arm.xacro"], cwd=tmp_path)
    assert code == 1, out
    assert "bot/urdf/arm.xacro:8  J003  error" in out and "[variant use_arm=true (includes arm.xacro)]" in out


def test_a_property_bound_to_an_argument_and_unless_with_not_equal(tmp_path):
    robot = _robot("${arm != 'small'}", '<xacro:arg name="arm" default="none"/>', kind="unless",
                   extra='<xacro:property name="arm" value="$(arg arm)"/>')
    _package(tmp_path, robot)
    code, report = lint_json(["bot/urdf/arm.xacro"], cwd=tmp_path)
    (f,) = _j003(report)
    assert f["variant"] == "arm=small (includes arm.xacro)" and code == 1


def test_a_condition_not_decided_is_said(tmp_path):
    _package(tmp_path, _robot("${'$(arg arm)' in ['small', 'large']}", '<xacro:arg name="arm" default="none"/>'))
    code, out, err = run_cli(["lint", "--no-config", "--no-cache", "bot/urdf/arm.xacro"], cwd=tmp_path)
    assert "a condition urdfcheck does not decide" in out + err
    assert "pass the arguments that include it with --arg" in out + err


def test_the_defaults_that_reach_it_add_no_variant(tmp_path):
    _package(tmp_path, _robot("$(arg use_arm)", '<xacro:arg name="use_arm" default="true"/>'))
    code, report = lint_json(["bot/urdf/arm.xacro"], cwd=tmp_path)
    (f,) = _j003(report)
    assert "includes arm.xacro" not in f["variant"]


def test_reaching_through_an_intermediate_file_collects_both_conditions(tmp_path):
    pkg = tmp_path / "bot"
    (pkg / "urdf").mkdir(parents=True)
    (pkg / "urdf" / "robot.urdf.xacro").write_text("""<robot name="r" xmlns:xacro="http://www.ros.org/wiki/xacro">
  <xacro:arg name="sim" default="false"/>
  <xacro:arg name="tool" default="none"/>
  <xacro:if value="$(arg sim)"><xacro:include filename="sim.xacro"/></xacro:if>
</robot>""")
    (pkg / "urdf" / "sim.xacro").write_text("""<robot xmlns:xacro="http://www.ros.org/wiki/xacro">
  <xacro:if value="${'$(arg tool)' == 'gripper'}"><xacro:include filename="gripper.xacro"/></xacro:if>
</robot>""")
    (pkg / "urdf" / "gripper.xacro").write_text("<robot/>")
    with door.guarded([str(tmp_path)], 1 << 24):
        r = reaching(str(pkg / "urdf" / "robot.urdf.xacro"), str(pkg / "urdf" / "gripper.xacro"), lambda n: None)
        none = reaching(str(pkg / "urdf" / "robot.urdf.xacro"), str(pkg / "urdf" / "other.xacro"), lambda n: None)
    assert r.args == {"sim": "true", "tool": "gripper"} and not r.undecided
    assert [os.path.basename(f) for f, _ in r.via] == ["robot.urdf.xacro", "sim.xacro"]
    assert none is None


def test_a_package_run_lints_a_macro_file_its_robot_includes_only_under_another_value(tmp_path):
    # zero config on the package: the robot with its defaults never includes arm.xacro, a macro file that was then
    # never checked at all ("All checks passed")
    _package(tmp_path, _robot("${'$(arg arm)' == 'small'}", '<xacro:arg name="arm" default="none"/>'))
    code, report = lint_json([], cwd=tmp_path)
    (f,) = _j003(report)
    assert code == 1 and f["severity"] == "error" and f["variant"] == "arm=small (includes arm.xacro)"
    assert "reaching" not in [s["how"] for s in f["evidence"]]  # nobody named the fragment
