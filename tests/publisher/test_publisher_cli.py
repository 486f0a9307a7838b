"""`urdfcheck tf|publish|tree` through the real CLI entry point."""
import json
import math

import pytest
from conftest import run_cli

ROBOT = """<robot name="r">
  <link name="base"/><link name="arm"/><link name="tool"/><link name="cam"/><link name="wheel"/>
  <joint name="shoulder" type="revolute"><parent link="base"/><child link="arm"/><origin xyz="0 0 1"/>
    <axis xyz="0 0 1"/><limit lower="-3" upper="3" effort="1" velocity="1"/></joint>
  <joint name="tool_joint" type="fixed"><parent link="arm"/><child link="tool"/><origin xyz="1 0 0"/></joint>
  <joint name="cam_joint" type="fixed"><parent link="base"/><child link="cam"/>
    <origin xyz="0 0 2" rpy="0 0.5 0"/></joint>
  <joint name="wheel_joint" type="continuous"><parent link="base"/><child link="wheel"/><axis xyz="0 1 0"/>
    <mimic joint="shoulder" multiplier="2"/></joint>
</robot>"""


@pytest.fixture
def robot(tmp_path):
    p = tmp_path / "robot.urdf"
    p.write_text(ROBOT)
    return p


def test_tf_text_and_json(robot):
    code, out, err = run_cli(["tf", robot, "base", "tool", "--joint", "shoulder=1.5707963267948966"])
    assert code == 0, err
    assert "Pose of tool in base" in out
    assert "- Translation: [0.000000, 1.000000, 1.000000]" in out
    assert "- Rotation: in RPY (degree) [0.000000, -0.000000, 90.000000]" in out  # -0, as tf2_echo prints
    code, out, err = run_cli(["tf", robot, "base", "tool", "--joint", "shoulder=0.5", "--format", "json"])
    d = json.loads(out)
    assert d["translation"] == pytest.approx([math.cos(0.5), math.sin(0.5), 1.0])
    assert d["rotation"] == pytest.approx([0, 0, math.sin(0.25), math.cos(0.25)])
    assert d["rpy"] == pytest.approx([0, 0, 0.5])
    # tf2_echo semantics: swapping the frames inverts the transform
    code, out, err = run_cli(["tf", robot, "tool", "base", "--joint", "shoulder=0.5", "--format", "json"])
    inv = json.loads(out)
    assert inv["translation"] == pytest.approx([-1.0, 0.0, -1.0], abs=1e-12)
    assert inv["rotation"] == pytest.approx([0, 0, -math.sin(0.25), math.cos(0.25)])


def test_tf_errors(robot, tmp_path):
    code, out, err = run_cli(["tf", robot, "base", "tool"])
    assert code == 2 and "no value for joint 'shoulder'" in err
    assert run_cli(["tf", robot, "base", "tool", "--zero-missing"])[0] == 0
    code, out, err = run_cli(["tf", robot, "base", "nowhere", "--zero-missing"])
    assert code == 2 and "does not exist" in err
    code, out, err = run_cli(["tf", robot, "base", "tool", "--joint", "elbow=1"])
    assert code == 2 and "elbow" in err
    broken = tmp_path / "broken.urdf"
    broken.write_text("<robot name='r'><link name='a'>")
    code, out, err = run_cli(["tf", broken, "a", "a"])
    assert code == 1 and "X001" in err  # the loader's findings, exit 1


def test_tf_through_xacro_args(tmp_path):
    x = tmp_path / "r.urdf.xacro"
    x.write_text("""<robot name="r" xmlns:xacro="http://www.ros.org/wiki/xacro">
      <xacro:arg name="height" default="1"/>
      <link name="a"/><link name="b"/>
      <joint name="j" type="fixed"><parent link="a"/><child link="b"/><origin xyz="0 0 $(arg height)"/></joint>
    </robot>""")
    code, out, err = run_cli(["tf", x, "a", "b", "--arg", "height:=2.5", "--format", "json"])
    assert code == 0, err
    assert json.loads(out)["translation"] == [0.0, 0.0, 2.5]


def test_tree_formats(robot):
    code, out, err = run_cli(["tree", robot])
    assert code == 0
    assert out.splitlines()[0] == "base"
    assert "arm  [shoulder (revolute, dynamic)]" in out
    assert "tool  [tool_joint (fixed, static)]" in out
    assert "wheel  [wheel_joint (continuous, dynamic, mimic shoulder)]" in out
    code, out, err = run_cli(["tree", robot, "--format", "json"])
    d = json.loads(out)
    pub = {e["joint"]: (e["publication"], e.get("topic")) for e in d["edges"]}
    assert pub == {"shoulder": ("dynamic", "/tf"), "tool_joint": ("static", "/tf_static"),
                   "cam_joint": ("static", "/tf_static"), "wheel_joint": ("dynamic", "/tf")}
    code, out, err = run_cli(["tree", robot, "--format", "mermaid"])
    assert out.startswith("graph TD") and '-.->|"tool_joint (fixed, static)"|' in out
    code, out, err = run_cli(["tree", robot, "--format", "dot", "--frame-prefix", "r1/"])
    assert out.startswith("digraph tf {") and '"r1/base" -> "r1/arm"' in out and "style=dashed" in out


def test_publish_replays_messages(robot, tmp_path):
    js = tmp_path / "js.yaml"
    js.write_text("""
- {name: [shoulder], position: [0.5], stamp: 1.0}
- {name: [shoulder], position: [0.6], stamp: 1.02}     # throttled at 20 Hz
- {name: [shoulder, ghost], position: [0.7, 1.0], stamp: [1, 60000000]}
- {name: [shoulder], position: [], stamp: 2.0}         # rejected
""")
    code, out, err = run_cli(["publish", robot, "--joint-states", js])
    assert code == 1, err  # the input's defects are said: an unknown name (B001), a rejected message (B003)
    assert "B001" in err and "B003" in err
    d = json.loads(out)
    assert [(t["parent"], t["child"]) for t in d["startup"]["/tf_static"]] == [("base", "cam"), ("arm", "tool")]
    m = d["messages"]
    assert [(t["parent"], t["child"]) for t in m[0]["/tf"]] == [("base", "arm"), ("base", "wheel")]
    assert m[0]["/tf"][1]["rotation"] == pytest.approx([0, math.sin(0.5), 0, math.cos(0.5)])  # mimic x2
    assert m[1]["throttled"] and m[1]["/tf"] == []
    assert m[2]["published"] and m[2]["unknown_joints"] == ["ghost"]
    assert m[2]["/tf"][0]["stamp"] == {"sec": 1, "nanosec": 60000000}
    assert "position member was empty" in m[3]["error"]
    assert "1 message(s) rejected" in err


def test_publish_options_ros1_json(robot, tmp_path):
    js = tmp_path / "js.json"
    js.write_text(json.dumps([
        {"name": ["shoulder"], "position": [0.1], "header": {"stamp": {"sec": 5, "nanosec": 0}}},
        {"name": ["shoulder"], "position": [0.2], "header": {"stamp": {"sec": 5, "nanosec": 1}}},
    ]))
    code, out, err = run_cli(["publish", robot, "--joint-states", js, "--profile", "ros1", "--no-tf-static",
                              "--frame-prefix", "/bot", "--ignore-timestamp"])
    assert code == 0, err
    d = json.loads(out)
    assert d["profile"] == "ros1" and d["publish_frequency"] == 50.0 and not d["use_tf_static"]
    assert d["startup"]["/tf_static"] == []
    first = d["messages"][0]["/tf"]
    # the fixed transforms ride on /tf, future-dated by 0.5 s, then the dynamic ones
    assert [(t["parent"], t["child"]) for t in first] == [("bot/base", "bot/cam"), ("bot/arm", "bot/tool"),
                                                          ("bot/base", "bot/arm"), ("bot/base", "bot/wheel")]
    assert first[0]["stamp"] == {"sec": 5, "nanosec": 500000000}
    assert len(d["messages"][1]["/tf"]) == 2  # 1 ns later: no timer tick, ignore_timestamp publishes


def test_publish_bad_input(robot, tmp_path):
    bad = tmp_path / "bad.yaml"
    bad.write_text("{ this is: [not yaml")
    assert run_cli(["publish", robot, "--joint-states", bad])[0] == 2
    assert run_cli(["publish", robot, "--joint-states", tmp_path / "none.yaml"])[0] == 2
    freq = tmp_path / "ok.yaml"
    freq.write_text("[]")
    code, out, err = run_cli(["publish", robot, "--joint-states", freq, "--publish-frequency", "5000"])
    assert code == 2 and "publish_frequency" in err
