"""Issue 20: deployments in an open world. Nothing dropped (every parameter file of a package is checked
against its models, whether a launch file reads it or not), no absence claimed where the tool did not
understand what could supply it, attachable fragments, and deployments not understood said as findings."""
import shutil
from pathlib import Path

import pytest

from tests.conftest import REPO, lint_json

AGV = REPO / "examples" / "agv"

DESCRIPTION_LAUNCH = """<launch>
  <arg name="use_camera" default="true"/>
  <param name="robot_description"
         command="$(find xacro)/xacro '$(find agv_description)/urdf/agv.urdf.xacro' use_camera:=$(arg use_camera)"/>
  <node pkg="robot_state_publisher" type="robot_state_publisher" name="robot_state_publisher"/>
</launch>
"""


def write(path: Path, text: str) -> Path:
    path.parent.mkdir(parents=True, exist_ok=True)
    path.write_text(text)
    return path


def seed(tmp: Path) -> Path:
    """The seed tutorial's description package: urdf/, config/ (the base driver's ROS 1 YAML and a
    ros2_control controller YAML) and launch/description.launch, which starts robot_state_publisher alone."""
    ws = tmp / "agv_description"
    ws.mkdir()
    for part in ("urdf", "config"):
        shutil.copytree(AGV / part, ws / part)
    (ws / "urdf" / "agv.urdf").unlink()  # the xacro is the model here
    shutil.copy(AGV / "package.xml", ws / "package.xml")
    write(ws / "launch" / "description.launch", DESCRIPTION_LAUNCH)
    return ws


def edit(path: Path, old: str, new: str) -> None:
    text = path.read_text()
    assert old in text, (path, old)
    path.write_text(text.replace(old, new, 1))


CTRL, DRV = "config/agv_controllers.yaml", "config/agv_driver_ros1.yaml"
XACRO, MACROS = "urdf/agv.urdf.xacro", "urdf/macros/components.xacro"
CASTER = """  <link name="caster_link"/>
  <joint name="caster_joint" type="continuous">
    <parent link="base_link"/><child link="caster_link"/><origin xyz="0.22 0 -0.05"/><axis xyz="0 0 1"/>
  </joint>
</robot>"""
TILTED = [(MACROS, "params=\"prefix side_sign ", "params=\"prefix side_sign axis:='0 1 0' "),
          (MACROS, '<axis xyz="0 1 0"/>', '<axis xyz="${axis}"/>'),
          (XACRO, '<xacro:wheel prefix="right" side_sign="-1"', '<xacro:wheel prefix="right" side_sign="-1" axis="0 0.8 0.6"')]

# (name, edits, expected code, severity, file the finding is in)
SEEDED = [
    ("controller joint misspelt", [(CTRL, "left_wheel_names: [left_wheel_joint]", "left_wheel_names: [left_wheel_jiont]")],
     "C001", "error", CTRL),
    ("controller wheel separation", [(CTRL, "wheel_separation: 0.50", "wheel_separation: 0.56")], "C010", "error", CTRL),
    ("controller wheel radius", [(CTRL, "wheel_radius: 0.10", "wheel_radius: 0.12")], "C011", "error", CTRL),
    ("controller base frame", [(CTRL, "base_frame_id: base_link", "base_frame_id: base_lnk")], "C020", "error", CTRL),
    ("controller wheels swapped", [(CTRL, "left_wheel_names: [left_wheel_joint]", "left_wheel_names: [right_wheel_joint]"),
                                   (CTRL, "right_wheel_names: [right_wheel_joint]", "right_wheel_names: [left_wheel_joint]")],
     "C014", "error", CTRL),
    ("fixed wheel", [(MACROS, 'type="continuous"', 'type="${\'fixed\' if prefix == \'right\' else \'continuous\'}"')],
     "C002", "error", CTRL),
    ("wheel axes not parallel", TILTED, "C012", "error", MACROS),
    ("caster nothing publishes", [(XACRO, "</robot>", CASTER)], "C003", "warning", XACRO),
    ("driver joint misspelt", [(DRV, "left_wheel_joint: left_wheel_joint", "left_wheel_joint: left_wheel_jiont")],
     "C001", "warning", DRV),
    ("driver wheel separation", [(DRV, "wheel_separation: 0.50", "wheel_separation: 0.56")], "C010", "warning", DRV),
    ("driver wheel radius", [(DRV, "wheel_radius: 0.10", "wheel_radius: 0.12")], "C011", "warning", DRV),
    ("driver imu frame", [(DRV, "imu_frame_id: imu_link", "imu_frame_id: imu")], "C020", "warning", DRV),
    ("driver laser frame", [(DRV, "laser_frame_id: laser_link", "laser_frame_id: lazer_link")], "C020", "warning", DRV),
]


def _failing(report):
    return [f for f in report["findings"] if f["severity"] in ("error", "warning")]


def test_seed_clean_passes(tmp_path):
    ws = seed(tmp_path)
    code, report = lint_json([], cwd=ws)
    assert _failing(report) == [], report["findings"]
    assert code == 0


@pytest.mark.parametrize("name,edits,code,severity,where", SEEDED, ids=[s[0] for s in SEEDED])
def test_seeded_contract_defect_found(tmp_path, name, edits, code, severity, where):
    ws = seed(tmp_path)
    for f, old, new in edits:
        edit(ws / f, old, new)
    rc, report = lint_json([], cwd=ws)
    got = [(f["code"], f["severity"], f["location"]["file"]) for f in report["findings"]]
    assert (code, severity, where) in got, got
    assert rc == 1
