"""What real ROS set-ups write (issue 39), in the shapes of tests/bag/test_bag.py's recordings (rosbags' writers):
the recording's own facts, prefixes, replay order, second publishers without callerids, and the wording."""
import json
import math
import os

import pytest
from bagwriter import FORMATS, write
from conftest import run_cli
from test_bag import ARM, CAMERA, clean_run, expected_tf

pytest.importorskip("rosbags")


def lint(tmp_path, bag, *extra, robot=ARM):
    (tmp_path / "robot.urdf").write_text(robot)
    code, out, err = run_cli(["bag", "robot.urdf", os.path.relpath(bag, tmp_path), "--format", "json", "--no-config",
                              *extra], cwd=tmp_path)
    assert code in (0, 1), err
    return code, json.loads(out)["findings"]


def codes(found):
    return {f["code"] for f in found}


def _longer_arm(events):
    """The robot runs a URDF whose upper arm is 5 cm longer: every /tf of the elbow differs from the replay."""
    out = []
    for ev in events:
        if ev[0] == "tf" and ev[3] == "/tf":
            s, e = ev[2]
            ev = (ev[0], ev[1], [s, (e[0], e[1], (0.35, 0.0, 0.0), e[3])], *ev[3:])
        out.append(ev)
    return out


@pytest.mark.parametrize("fmt", FORMATS)
def test_tf_written_just_before_its_joint_state_is_replayed(fmt, tmp_path):
    """`rosbag record` often writes robot_state_publisher's /tf 0.17 ms before the JointState it came from."""
    events = []
    for ev in _longer_arm(clean_run()):
        if ev[0] == "tf" and ev[3] == "/tf":
            ev = ("tf", ev[1] - 0.00017, ev[2], "/tf", None, None, ev[1])  # recorded earlier, stamped the same
        events.append(ev)
    events.sort(key=lambda ev: ev[1])
    code, found = lint(tmp_path, write(tmp_path / "rec", fmt, events))
    (b013,) = [f for f in found if f["code"] == "B013"]
    # every transform replayed (the shoulder's match, the elbow's 50 differ); looking only backwards: none
    assert b013["message"].startswith("50 of 100 recorded /tf transforms"), b013["message"]


def test_old_tf_message_type_is_read(tmp_path):
    events = [(*ev[:4], None, "tf/msg/tfMessage") if ev[0] == "tf" and ev[3] == "/tf" else ev
              for ev in _longer_arm(clean_run())]
    code, found = lint(tmp_path, write(tmp_path / "rec", "ros1", events))
    assert codes(found) == {"B013"}, found


@pytest.mark.parametrize("fmt", FORMATS)
def test_robot_under_a_frame_prefix_is_compared(fmt, tmp_path):
    """robot1/ and robot2/ in one recording; robot1's camera is 20 mm off. Recognised from the names, or
    named in the config (which then picks robot2, whose camera is right)."""
    def prefixed(pre, events, cam_x):
        out = []
        for ev in events:
            if ev[0] == "tf":
                edges = [(pre + p, pre + c, (cam_x, *xyz[1:]) if c == "camera_link" else xyz, q)
                         for p, c, xyz, q in ev[2]]
                ev = (ev[0], ev[1], edges, *ev[3:])
            out.append(ev)
        return out

    base = clean_run()
    events = prefixed("robot1/", base, 0.12) + [ev for ev in prefixed("robot2/", base, 0.1) if ev[0] == "tf"]
    events.sort(key=lambda ev: ev[1])
    bag = write(tmp_path / "rec", fmt, events)
    code, found = lint(tmp_path, bag)
    assert codes(found) == {"B011"}, found
    assert "robot1/base_link -> robot1/camera_link 20.0 mm" in found[0]["message"]
    (tmp_path / "urdfcheck.yaml").write_text(
        f"models:\n  - path: robot.urdf\n    frame_prefix: robot2/\n    bags: [{os.path.relpath(bag, tmp_path)}]\n")
    code, out, err = run_cli(["lint", "--format", "json"], cwd=tmp_path)
    assert code == 0, out
    (tmp_path / "urdfcheck.yaml").write_text(
        f"models:\n  - path: robot.urdf\n    frame_prefix: robot1/\n    bags: [{os.path.relpath(bag, tmp_path)}]\n")
    code, out, err = run_cli(["lint", "--format", "json"], cwd=tmp_path)
    assert "B011" in {f["code"] for f in json.loads(out)["findings"]}


@pytest.mark.parametrize("fmt", FORMATS)
def test_movable_edge_from_another_node_without_callerids(fmt, tmp_path):
    """Another node also publishes upper_arm -> tool on /tf, with stamps of its own: none matches a JointState,
    while robot_state_publisher's all do."""
    events = clean_run()
    for i in range(20):
        t = 1.0 + i / 20 + 0.003
        events.append(("tf", t, [expected_tf(0.0, 0.0)[1]], "/tf"))
    events.sort(key=lambda ev: ev[1])
    code, found = lint(tmp_path, write(tmp_path / "rec", fmt, events))
    b010 = [f for f in found if f["code"] == "B010"]
    assert b010 and "upper_arm -> tool" in b010[0]["message"] and "match no JointState" in b010[0]["message"], found


def test_several_drivers_on_one_topic_are_not_a_stamp_going_back(tmp_path):
    events = [("tf", 0.0, [CAMERA], "/tf_static")]
    for i in range(100):
        t = 1.0 + i / 50
        events.append(("js", t, ["shoulder"], [0.1], [], t))  # the base driver
        events.append(("js", t + 0.001, ["elbow"], [0.2], [], t - 3.0))  # the arm driver, its clock 3 s behind
    code, found = lint(tmp_path, write(tmp_path / "rec", "mcap", events))
    assert "B008" not in codes(found), found
    events.append(("js", 3.5, ["shoulder"], [0.1], [], 1.5))  # the base driver's clock jumps back 2 s
    code, found = lint(tmp_path, write(tmp_path / "rec2", "mcap", events))
    (b008,) = [f for f in found if f["code"] == "B008"]
    assert "backwards 1 time (by up to 1.480 s)" in b008["message"], b008["message"]


def test_ros1_zero_stamps_are_described_as_ros1_does(tmp_path):
    events = [("js", 1.0 + i / 50, ["shoulder", "elbow"], [0.1, 0.2], [], 0.0) for i in range(10)]
    code, found = lint(tmp_path, write(tmp_path / "rec", "ros1", events))
    (b008,) = [f for f in found if f["code"] == "B008"]
    assert "(ROS 1)" in b008["message"] and "never published" in b008["message"]
    code, found = lint(tmp_path, write(tmp_path / "rec2", "mcap", events))
    (b008,) = [f for f in found if f["code"] == "B008"]
    assert "published once" in b008["message"]


@pytest.mark.parametrize("fmt", FORMATS)
def test_locations_are_offsets_from_the_start(fmt, tmp_path):
    """From the recording's first message of any topic (a timeline viewer's zero), not epoch seconds."""
    events = [("tf", 0.5, [CAMERA], "/tf_other")] + clean_run(back_at=20)[1:]
    code, found = lint(tmp_path, write(tmp_path / "rec", fmt, events))
    (b008,) = [f for f in found if f["code"] == "B008"]
    assert "message 21 (at +0.920 s)" in b008["message"], b008["message"]  # 1.0 + 21 / 50 - 0.5


def test_renamed_joint_is_said_and_no_fixed_joint_is_suggested(tmp_path):
    events = [("js", *ev[1:2], ["shoulder", "elbow_joint"], *ev[3:]) if ev[0] == "js" else ev for ev in clean_run()]
    events.append(("js", 5.0, ["camera_joint_x"], [0.0]))
    code, found = lint(tmp_path, write(tmp_path / "rec", "mcap", events))
    (b002,) = [f for f in found if f["code"] == "B002"]
    assert "'elbow' is never named" in b002["message"] and "another name" in b002["message"]
    assert "upper_arm -> tool" in b002["message"] and "'elbow_joint'" in b002["message"]
    (b001,) = [f for f in found if f["code"] == "B001"]
    assert "'camera_joint'" not in b001["message"], b001["message"]  # a fixed joint is never a JointState name


def test_nothing_of_the_model_compared_is_a_finding(tmp_path):
    events = clean_run()
    bag = write(tmp_path / "rec", "mcap", events)
    code, found = lint(tmp_path, bag, "--joint-states", "/wrong/joint_states")
    (b015,) = [f for f in found if f["code"] == "B015"]
    assert code == 1 and b015["severity"] == "warning" and "none of the model's 2 movable joints" in b015["message"]
    code, found = lint(tmp_path, write(tmp_path / "static", "sqlite3", [("tf", 1.0, [CAMERA], "/tf_static")]))
    assert code == 1 and [f["code"] for f in found] == ["B015"], found


def test_unpublished_joints_are_said(tmp_path):
    """robot_state_publisher listens elsewhere: /tf carries the shoulder (another publisher) but never the elbow,
    which 50 JointStates name."""
    events = []
    for ev in clean_run():
        if ev[0] == "tf" and ev[3] == "/tf":
            ev = ("tf", ev[1], [ev[2][0]], "/tf")
        events.append(ev)
    code, found = lint(tmp_path, write(tmp_path / "rec", "sqlite3", events))
    (b002,) = [f for f in found if f["code"] == "B002"]
    assert "robot_state_publisher did not publish joint 'elbow'" in b002["message"]


def test_replay_tolerates_nothing_else(tmp_path):
    """The clean twin of the cases above passes in every format (no false alarm from the new checks)."""
    for fmt in FORMATS:
        code, found = lint(tmp_path, write(tmp_path / f"rec_{fmt}", fmt, clean_run()))
        assert code == 0 and not found, (fmt, found)
    assert math.isfinite(0.0)
