"""Recordings made by real ROS software (issue 39): Debian's ROS 1 robot_state_publisher, rospy joint state
drivers, tf2_ros broadcasters and `rosbag record` (tools/record_ros1_bags.py wrote tests/fixtures/ros1; `rosbag
compress` made the lz4 and bz2 copies, rosbag's Python API the callerid-less one), and the same bags converted to
rosbag2 sqlite3 and MCAP (zstd) with `rosbags-convert`, here."""
import json
import os
import shutil
import subprocess
import sys
from pathlib import Path

import pytest
from conftest import run_cli

pytest.importorskip("rosbags")

FIXTURES = Path(__file__).parent.parent / "fixtures" / "ros1"
FORMATS = ("ros1", "sqlite3", "mcap")

# scenario -> codes expected (a clean recording: none)
EXPECTED = {
    "clean": set(),
    "drivers": set(),  # a wheel driver and an arm driver (its clock 3 s behind) on one /joint_states
    "no_tf_static": set(),  # ROS 1 robot_state_publisher with use_tf_static false: fixed joints on /tf
    "prefix_laser": {"B011"},  # tf_prefix robot1, and the robot's laser 20 mm from the repository's
    "remapped": {"B002"},  # robot_state_publisher listens on /robot/joint_states: the joints never reach /tf
    "second_static_nocaller": {"B010", "B011"},  # a calibration node latches base_link -> laser too
}


def convert(bag: Path, fmt: str, dst: Path) -> Path:
    if fmt == "ros1":
        return bag
    args = [sys.executable, "-m", "rosbags.convert", "--src", str(bag), "--dst", str(dst), "--dst-storage", fmt]
    if fmt == "mcap":
        args += ["--compress", "zstd", "--compress-mode", "storage"]
    subprocess.run(args, check=True, capture_output=True)
    return dst


def lint(tmp_path, recording) -> tuple[int, list]:
    shutil.copyfile(FIXTURES / "robot.urdf", tmp_path / "robot.urdf")
    code, out, err = run_cli(["bag", "robot.urdf", os.path.relpath(recording, tmp_path), "--format", "json",
                              "--no-config"], cwd=tmp_path)
    assert code in (0, 1), err
    return code, json.loads(out)["findings"]


def _copy(tmp_path, name) -> Path:
    shutil.copyfile(FIXTURES / f"{name}.bag", tmp_path / f"{name}.bag")
    return tmp_path / f"{name}.bag"


@pytest.fixture(autouse=True)
def _fixtures():
    if not (FIXTURES / "clean.bag").exists():
        pytest.skip("tests/fixtures/ros1 is absent")


@pytest.mark.parametrize("fmt", FORMATS)
@pytest.mark.parametrize("scenario", sorted(EXPECTED))
def test_real_recordings(scenario, fmt, tmp_path):
    rec = convert(_copy(tmp_path, scenario), fmt, tmp_path / f"{scenario}_{fmt}")
    code, found = lint(tmp_path, rec)
    assert {f["code"] for f in found} == EXPECTED[scenario], [(f["code"], f["message"]) for f in found]
    assert code == (1 if EXPECTED[scenario] else 0)
    if scenario == "prefix_laser":
        (b011,) = found
        assert "robot1/base_link -> robot1/laser 20.0 mm" in b011["message"]
    if scenario == "remapped":
        (b002,) = found
        assert "robot_state_publisher did not publish" in b002["message"]
        assert "left_wheel_joint" in b002["message"]


@pytest.mark.parametrize("name", ["clean_lz4", "clean_bz2"])
def test_rosbag_compressed(name, tmp_path):
    code, found = lint(tmp_path, _copy(tmp_path, name))
    assert code == 0 and not found, found


def test_two_odometry_publishers_by_callerid(tmp_path):
    code, found = lint(tmp_path, _copy(tmp_path, "two_odom"))
    (b010,) = found
    assert b010["code"] == "B010" and "odom -> base_link" in b010["message"]
    assert "/diff_drive" in b010["message"] and "/ekf" in b010["message"]


@pytest.mark.parametrize("fmt", ["sqlite3", "mcap"])
def test_two_odometry_publishers_without_callerids(fmt, tmp_path):
    """Converted to rosbag2 the callerids are gone; the edge still jumps between the two nodes' values."""
    code, found = lint(tmp_path, convert(_copy(tmp_path, "two_odom"), fmt, tmp_path / f"two_odom_{fmt}"))
    (b010,) = found
    assert b010["code"] == "B010" and "odom -> base_link jumps back and forth" in b010["message"]


def test_second_static_publisher_by_callerid(tmp_path):
    code, found = lint(tmp_path, _copy(tmp_path, "second_static"))
    b010 = [f for f in found if f["code"] == "B010"]
    assert b010 and "/laser_calib" in b010[0]["message"] and "/robot_state_publisher" in b010[0]["message"]


def test_metadata_yaml_means_its_folder(tmp_path):
    folder = convert(_copy(tmp_path, "clean"), "sqlite3", tmp_path / "clean_sqlite3")
    code, found = lint(tmp_path, folder / "metadata.yaml")
    assert code == 0 and not found, found
    folder = convert(_copy(tmp_path, "remapped"), "mcap", tmp_path / "remapped_mcap")
    code, found = lint(tmp_path, folder / "metadata.yaml")
    assert [f["code"] for f in found] == ["B002"]
