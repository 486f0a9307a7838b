"""`urdfcheck bag`: recordings written with rosbags' writers (ROS 1, ROS 2 sqlite3 and MCAP), one seeded defect
each, and a clean twin; the report names exactly the seeded defect."""
import json
import math
import os

import pytest
from bagwriter import FORMATS, write
from conftest import run_cli

pytest.importorskip("rosbags")

ROBOT = """<?xml version="1.0"?>
<robot name="arm">
  <link name="base_link"/>
  <link name="upper_arm"/>
  <link name="tool"/>
  <link name="camera_link"/>
  <joint name="shoulder" type="revolute">
    <parent link="base_link"/>
    <child link="upper_arm"/>
    <origin xyz="0 0 0.1"/>
    <axis xyz="0 0 1"/>
    <limit lower="-1.5" upper="1.5" effort="10" velocity="1"/>
  </joint>
  <joint name="elbow" type="{elbow_type}">
    <parent link="upper_arm"/>
    <child link="tool"/>
    <origin xyz="0.3 0 0"/>
    <axis xyz="{elbow_axis}"/>
    <limit lower="{lo}" upper="{hi}" effort="10" velocity="1"/>
  </joint>
  <joint name="camera_joint" type="fixed">
    <parent link="base_link"/>
    <child link="camera_link"/>
    <origin xyz="0.1 0 0.2"/>
  </joint>
</robot>
"""
ARM = ROBOT.format(elbow_type="revolute", elbow_axis="0 1 0", lo=-2, hi=2)
SLIDER = ROBOT.format(elbow_type="prismatic", elbow_axis="1 0 0", lo=0, hi=0.2)
CAMERA = ("base_link", "camera_link", (0.1, 0.0, 0.2), (0.0, 0.0, 0.0, 1.0))


def expected_tf(q_shoulder, q_elbow, prismatic=False):
    """What robot_state_publisher publishes, written out by hand (not through urdfcheck's publisher)."""
    s = ("base_link", "upper_arm", (0.0, 0.0, 0.1), (0.0, 0.0, math.sin(q_shoulder / 2), math.cos(q_shoulder / 2)))
    if prismatic:
        e = ("upper_arm", "tool", (0.3 + q_elbow, 0.0, 0.0), (0.0, 0.0, 0.0, 1.0))
    else:
        e = ("upper_arm", "tool", (0.3, 0.0, 0.0), (0.0, math.sin(q_elbow / 2), 0.0, math.cos(q_elbow / 2)))
    return [s, e]


def clean_run(n=50, rate=50.0, scale=1.0, prismatic=False, gap_at=None, back_at=None, edit=None):
    """Joint states and the matching /tf at `rate` Hz, /tf_static at the start. `scale`: the unit the driver
    reports in (57.3: degrees); `edit(i, names, positions)` seeds a defect into message i."""
    events = [("tf", 0.0, [CAMERA], "/tf_static")]
    t = 1.0
    for i in range(n):
        t += 1.0 / rate
        if gap_at is not None and i == gap_at:
            t += 2.0
        q = (0.4 * math.sin(i / 10), 0.05 + 0.1 * (i / n) if prismatic else 0.5 * math.cos(i / 10))
        names, pos = ["shoulder", "elbow"], [q[0] * (1.0 if prismatic else scale), q[1] * scale]
        if edit is not None:
            names, pos = edit(i, names, pos)
        stamp = t - 0.5 if back_at is not None and i == back_at else t
        events.append(("js", t, names, pos, [], stamp))
        if len(names) == len(pos) and all(math.isfinite(p) for p in pos) and "elbow" in names:
            events.append(("tf", stamp, expected_tf(pos[0], pos[1], prismatic), "/tf"))
    return events


def _seed(i, k, value):
    return lambda j, names, pos: (names, [value if (j == i and m == k) else p for m, p in enumerate(pos)])


DEFECTS = {
    "clean": (ARM, clean_run(), set()),
    "B001": (ARM, clean_run(edit=lambda i, n, p: (n + ["wrist"], p + [0.0]) if i == 3 else (n, p)), {"B001"}),
    "B002": (ARM, [("tf", 0.0, [CAMERA], "/tf_static")] +
             [("js", 1 + i / 50, ["shoulder"], [0.1]) for i in range(20)], {"B002"}),
    "B003": (ARM, clean_run(edit=lambda i, n, p: (n, p[:1]) if i == 7 else (n, p)), {"B003"}),
    "B004": (ARM, clean_run(edit=_seed(9, 0, float("nan"))), {"B004"}),
    "B005": (ARM, clean_run(edit=_seed(11, 0, 1.7)), {"B005"}),
    "B006": (ARM, clean_run(scale=180 / math.pi * 3), {"B006"}),
    "B007": (SLIDER, clean_run(scale=1000.0, prismatic=True), {"B007"}),
    "B008": (ARM, clean_run(back_at=20), {"B008"}),
    "B009": (ARM, clean_run(gap_at=30), {"B009"}),
    "B010": (ARM, clean_run() + [("tf", 1.5, [CAMERA], "/tf")], {"B010"}),
    "B011": (ARM, [("tf", 0.0, [("base_link", "camera_link", (0.11, 0.0, 0.2), (0, 0, 0, 1))], "/tf_static")]
             + clean_run()[1:], {"B011"}),
    "B012": (ARM, clean_run() + [("tf", 1.5, [("odom", "camera_link", (0, 0, 0), (0, 0, 0, 1))], "/tf")], {"B012"}),
}


def _b13():
    events = clean_run()
    out = []
    for ev in events:
        if ev[0] == "tf" and ev[3] == "/tf":
            s, e = ev[2]
            e = (e[0], e[1], (0.35, 0.0, 0.0), e[3])  # the robot runs a URDF with a longer upper arm
            ev = ("tf", ev[1], [s, e], "/tf")
        out.append(ev)
    return out


DEFECTS["B013"] = (ARM, _b13(), {"B013"})
if True:  # degrees with a scale that still fits the limits after / 57.3 (the 3x above is for the check's margin)
    DEFECTS["B006"] = (ARM, clean_run(scale=180 / math.pi), {"B006"})


def _lint(tmp_path, robot, bag, *extra):
    (tmp_path / "robot.urdf").write_text(robot)
    code, out, err = run_cli(["bag", "robot.urdf", os.path.relpath(bag, tmp_path), "--format", "json", *extra],
                             cwd=tmp_path)
    assert code in (0, 1), err
    return code, json.loads(out)


@pytest.mark.parametrize("fmt", FORMATS)
@pytest.mark.parametrize("case", sorted(DEFECTS))
def test_seeded_defect_found_exactly(case, fmt, tmp_path):
    robot, events, expected = DEFECTS[case]
    bag = write(tmp_path / "rec", fmt, events)
    code, report = _lint(tmp_path, robot, bag)
    codes = {f["code"] for f in report["findings"]}
    assert codes == expected, [(f["code"], f["message"]) for f in report["findings"]]
    assert code == (1 if expected else 0)
    for f in report["findings"]:
        assert f["location"]["file"] == os.path.relpath(bag, tmp_path)


def test_ros1_two_callerids_on_one_edge(tmp_path):
    events = [ev + ("/robot_state_publisher",) if ev[0] == "tf" else ev for ev in clean_run()]
    events.append(("tf", 1.3, [expected_tf(0.1, 0.2)[0]], "/tf", "/arm_driver"))
    bag = write(tmp_path / "rec", "ros1", events)
    _, report = _lint(tmp_path, ARM, bag)
    hits = [f for f in report["findings"] if f["code"] == "B010"]
    assert any("/arm_driver" in f["message"] and "/robot_state_publisher" in f["message"] for f in hits), hits


@pytest.mark.parametrize("fmt", FORMATS)
def test_truncated_bag_is_a_finding(fmt, tmp_path):
    bag = write(tmp_path / "rec", fmt, clean_run(n=400))
    victim = bag if bag.is_file() else next(p for p in bag.iterdir() if p.suffix in (".db3", ".mcap"))
    data = victim.read_bytes()
    victim.write_bytes(data[: len(data) * 2 // 3])
    code, report = _lint(tmp_path, ARM, bag)
    assert code == 1
    assert any(f["code"] == "B014" for f in report["findings"]), report["findings"]


def test_garbage_and_fifo_recordings_are_findings(tmp_path):
    (tmp_path / "junk.mcap").write_bytes(b"\x89MCAP0\r\n" + os.urandom(2000))
    code, report = _lint(tmp_path, ARM, tmp_path / "junk.mcap")
    assert code == 1 and [f["code"] for f in report["findings"]] == ["B014"]
    os.mkfifo(tmp_path / "pipe.bag")
    code, report = _lint(tmp_path, ARM, tmp_path / "pipe.bag")  # must not block
    assert code == 1 and [f["code"] for f in report["findings"]] == ["B014"]


@pytest.mark.parametrize("first", [b"\x02", b"\x01\x00\x00\x00\x00\x00\x00\x00\x00\x02\x14" + bytes(7)])
def test_garbage_that_starts_like_a_footer_is_a_finding(first, tmp_path):
    """Random bytes after the magic once began with the footer's opcode (1 in 256 of the garbage test's runs), and
    the reader took it for the end of an empty recording: "nothing was checked" instead of unreadable."""
    (tmp_path / "junk.mcap").write_bytes(b"\x89MCAP0\r\n" + first + bytes(range(256)) * 4)
    code, report = _lint(tmp_path, ARM, tmp_path / "junk.mcap")
    assert code == 1 and [f["code"] for f in report["findings"]] == ["B014"]


def test_no_topics_is_said_not_passed(tmp_path):
    bag = write(tmp_path / "rec", "mcap", [("tf", 1.0, [CAMERA], "/tf_other")])
    code, report = _lint(tmp_path, ARM, bag)
    assert [f["code"] for f in report["findings"]] == ["B015"]


def test_other_joint_state_topic_makes_absence_information(tmp_path):
    robot = ARM
    (tmp_path / "rec.yaml").write_text(
        "- {name: [shoulder], position: [0.1], stamp: 1.0}\n"
        "- {topic: /gripper/joint_states, name: [elbow], position: [0.1], stamp: 1.0}\n")
    code, report = _lint(tmp_path, robot, tmp_path / "rec.yaml")
    (b2,) = [f for f in report["findings"] if f["code"] == "B002"]
    assert b2["severity"] == "info" and "/gripper/joint_states" in b2["message"]
    code, report = _lint(tmp_path, robot, tmp_path / "rec.yaml", "--joint-states", "/gripper/joint_states")
    assert {f["code"] for f in report["findings"]} == {"B002"}  # now shoulder is the one never named


def test_usage_errors(tmp_path):
    (tmp_path / "robot.urdf").write_text(ARM)
    code, _, err = run_cli(["bag", "robot.urdf"], cwd=tmp_path)
    assert code == 2 and "expected MODEL and RECORDING" in err
    code, _, err = run_cli(["bag", "robot.urdf", "missing.bag"], cwd=tmp_path)
    assert code == 2 and "missing.bag" in err


def test_config_bags_contract(tmp_path):
    bag = write(tmp_path / "rec", "sqlite3", DEFECTS["B005"][1])
    (tmp_path / "robot.urdf").write_text(ARM)
    (tmp_path / "urdfcheck.yaml").write_text(f"models:\n  - path: robot.urdf\n    bags: [{bag.name}]\n")
    code, out, err = run_cli(["lint", "--format", "json"], cwd=tmp_path)
    assert code == 1, err
    assert "B005" in {f["code"] for f in json.loads(out)["findings"]}


def test_bags_in_config_are_confined_to_the_checkout(tmp_path):
    (tmp_path / "robot.urdf").write_text(ARM)
    (tmp_path / "urdfcheck.yaml").write_text("models:\n  - path: robot.urdf\n    bags: [missing.mcap]\n")
    code, _, err = run_cli(["lint"], cwd=tmp_path)
    assert code == 2 and "missing.mcap" in err


def test_publish_joint_states_are_checked(tmp_path):
    pytest.importorskip("numpy")
    (tmp_path / "robot.urdf").write_text(ARM)
    (tmp_path / "states.yaml").write_text(
        "- {name: [shoulder, elbow], position: [0.1, 0.2], stamp: 2.0}\n"
        "- {name: [shoulder, elbow], position: [90.0, .nan], stamp: 1.0}\n")
    code, out, err = run_cli(["publish", "robot.urdf", "--joint-states", "states.yaml"], cwd=tmp_path)
    assert code == 1
    for c in ("B004", "B005", "B008"):
        assert c in err, err
    json.loads(out)  # what robot_state_publisher would publish is still printed
