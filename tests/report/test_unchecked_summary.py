"""A run whose robot could not be checked for an environmental reason stays red (an unchecked robot never passes,
issue 37), and its summary line names the models, why they did not load and how to make them checkable."""
from __future__ import annotations

from pathlib import Path

from conftest import run_cli

PACKAGE = """<?xml version="1.0"?>
<package format="3"><name>bot_description</name><version>0.0.0</version><description>x</description>
<maintainer email="a@b.c">a</maintainer><license>MIT</license><buildtool_depend>ament_cmake</buildtool_depend>
</package>
"""


def _package(root: Path, robot: str) -> None:
    (root / "bot_description" / "urdf").mkdir(parents=True)
    (root / "bot_description" / "package.xml").write_text(PACKAGE)
    (root / "bot_description" / "urdf" / "bot.urdf.xacro").write_text(robot)


def test_a_package_outside_the_checkout_is_named_with_the_flag_that_provides_it(tmp_path):
    _package(tmp_path, """<?xml version="1.0"?>
<robot name="bot" xmlns:xacro="http://www.ros.org/wiki/xacro">
  <xacro:include filename="$(find vendor_sensors)/urdf/lidar.urdf.xacro"/>
  <link name="base_link"/>
</robot>
""")
    code, out, _ = run_cli(["lint", "--no-config", "--no-cache"], cwd=tmp_path)
    assert code == 1
    last = out.strip().splitlines()[-1]
    assert last == ("Not a pass: 1 model not checked (did not load): bot_description/urdf/bot.urdf.xacro (package "
                    "'vendor_sensors' is not in the checkout: pass --package vendor_sensors=PATH, or lint the "
                    "workspace that holds it)."), last


def test_a_required_argument_is_named_with_the_flag_that_sets_it(tmp_path):
    _package(tmp_path, """<?xml version="1.0"?>
<robot name="$(arg prefix)bot" xmlns:xacro="http://www.ros.org/wiki/xacro">
  <xacro:arg name="prefix" default=""/>
  <link name="base_link"/>
</robot>
""")
    code, out, _ = run_cli(["lint", "--no-config", "--no-cache"], cwd=tmp_path)
    assert code == 1
    last = out.strip().splitlines()[-1]
    assert "All checks passed" not in out
    assert last.startswith("Not a pass: 1 model not checked (did not load): bot_description/urdf/bot.urdf.xacro "
                           "(xacro argument 'prefix' has no default: pass --arg prefix:=..."), last


def test_a_run_red_only_for_missing_meshes_says_so_and_how_to_fetch_them(tmp_path):
    _package(tmp_path, """<?xml version="1.0"?>
<robot name="bot">
  <link name="base_link">
    <visual><geometry><mesh filename="package://bot_description/meshes/base.stl"/></geometry></visual>
  </link>
</robot>
""")
    code, out, _ = run_cli(["lint", "--no-config", "--no-cache"], cwd=tmp_path)
    assert code == 1 and "G001" in out
    assert out.strip().splitlines()[-1].startswith("Only missing meshes fail this run (G001): fetch the mesh files")


def test_a_run_with_other_errors_does_not_blame_the_meshes(tmp_path):
    _package(tmp_path, """<?xml version="1.0"?>
<robot name="bot">
  <link name="base_link">
    <visual><geometry><mesh filename="package://bot_description/meshes/base.stl"/></geometry></visual>
  </link>
  <joint name="j" type="revolute"><parent link="base_link"/><child link="arm"/><axis xyz="0 0 1"/>
    <limit lower="1" upper="-1" effort="1" velocity="1"/></joint>
  <link name="arm"/>
</robot>
""")
    code, out, _ = run_cli(["lint", "--no-config", "--no-cache"], cwd=tmp_path)
    assert code == 1 and "J003" in out and "Only missing meshes" not in out
