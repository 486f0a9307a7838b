"""YAML with locations (yamlsrc) and ROS parameter files (params): normal use and hostile input."""
import sys
from pathlib import Path

SRC = Path(__file__).resolve().parents[2] / "src"
if str(SRC) not in sys.path:  # runnable without an editable install
    sys.path.insert(0, str(SRC))

import pytest  # noqa: E402
from work import counted  # noqa: E402

from urdfcheck.consumers.common import ConsumerError  # noqa: E402
from urdfcheck.consumers.params import lookup, node_key_matches, parse_params, read_params  # noqa: E402
from urdfcheck.consumers.yamlsrc import load_yaml, parse_yaml  # noqa: E402


# --- yamlsrc -------------------------------------------------------------------------------------------------
def test_values_and_locations():
    doc = parse_yaml("a:\n  b: [1, 2.5, x]\n  c: {d: true}\n", "f.yaml")
    assert doc.data == {"a": {"b": [1, 2.5, "x"], "c": {"d": True}}}
    assert (doc.loc("a", "b").line, doc.loc("a", "b").column) == (2, 6)
    assert doc.loc("a", "b", 2).column == 15
    assert doc.key_loc("a", "c").line == 3 and doc.key_loc("a", "c").column == 3
    assert doc.loc("a", "nope").line == 2  # nearest located ancestor: the mapping under a
    assert doc.loc("a", "c", "d").file == "f.yaml"


def test_merge_keys_and_duplicates():
    doc = parse_yaml("base: &b {x: 1, y: 2}\nn:\n  <<: *b\n  x: 5\n  k: 1\n  k: 2\n", "f.yaml")
    assert doc.data["n"] == {"x": 5, "y": 2, "k": 2}
    assert doc.loc("n", "y").line == 1
    assert doc.loc("n", "k").line == 6
    assert any("duplicate key 'k'" in m for m, _ in doc.notes)


def test_duplicate_node_keys_merge_like_rcl():
    doc = parse_yaml("/**:\n  a: {ros__parameters: {x: 1}}\n/**:\n  b: {ros__parameters: {y: 2}}\n", "p.yaml")
    assert set(doc.data["/**"]) == {"a", "b"}


def test_unknown_and_python_tags_are_plain_text():
    doc = parse_yaml("a: !!python/object/apply:os.system [echo hi]\nb: !custom 3\nc: !!python/name:os.system x\n",
                     "t.yaml")
    assert doc.data["a"] == ["echo hi"]
    assert doc.data["b"] == "3"
    assert doc.data["c"] == "x"


def test_syntax_error_is_a_located_consumer_error():
    with pytest.raises(ConsumerError) as e:
        parse_yaml("ok: 1\nbad: [1, 2\nnext: 3\n", "bad.yaml")
    assert e.value.location.file == "bad.yaml"
    assert e.value.location.line is not None and e.value.location.line >= 2
    assert "YAML syntax error" in e.value.message


def test_alias_bomb_is_refused_fast():
    lines = ['a: &a ["lol","lol","lol","lol","lol","lol","lol","lol","lol"]']
    for i in range(1, 10):
        p, n = chr(ord("a") + i - 1), chr(ord("a") + i)
        lines.append(f"{n}: &{n} [" + ",".join([f"*{p}"] * 9) + "]")
    work, error = counted(parse_yaml, "\n".join(lines) + "\n", "bomb.yaml")
    assert isinstance(error, ConsumerError), error
    # refused before expanding: 9**10 nodes would be billions of calls (counted, not timed)
    assert work.calls < 200_000 and work.peak_bytes < 32 * 1024 * 1024, (work.calls, work.peak_bytes)
    assert "bomb" in error.message or "alias" in error.message
    assert error.location.line is not None


def test_recursive_alias_is_refused():
    with pytest.raises(ConsumerError, match="itself"):
        parse_yaml("a: &r [1, *r]\n", "r.yaml")


def test_deep_nesting_does_not_crash():
    with pytest.raises(ConsumerError):
        parse_yaml("[" * 20000 + "]" * 20000, "deep.yaml")
    with pytest.raises(ConsumerError):
        parse_yaml("- " * 5000 + "x\n", "deep2.yaml")


def test_size_cap_and_bad_utf8(tmp_path):
    big = tmp_path / "big.yaml"
    big.write_text("a: " + "x" * 2000 + "\n")
    with pytest.raises(ConsumerError, match="larger"):
        load_yaml(big, max_bytes=1000)
    with pytest.raises(ConsumerError, match="UTF-8"):
        parse_yaml(b"a: \xff\xfe\n", "u.yaml")
    with pytest.raises(ConsumerError, match="cannot read"):
        load_yaml(tmp_path / "missing.yaml")


# --- params --------------------------------------------------------------------------------------------------
ROS2 = """\
/**:
  ros__parameters:
    use_sim_time: false
/ns/driver:
  ros__parameters:
    wheels:
      separation: 0.16
    linear.x.max_velocity: 1.0
    linear:
      x: {min_velocity: -1.0}
ns2:
  other_node:
    ros__parameters:
      frame: base_link
"""


def test_ros2_nodes_flatten_to_dotted_names():
    pf = parse_params(ROS2, "p.yaml")
    assert pf.dialect == "ros2"
    assert set(pf.nodes) == {"/**", "/ns/driver", "/ns2/other_node"}
    drv = pf.nodes["/ns/driver"]
    assert drv.namespace == "/ns" and drv.basename == "driver"
    assert drv.params["wheels.separation"].value == 0.16
    assert drv.params["wheels.separation"].loc.line == 7
    assert drv.params["linear.x.max_velocity"].value == 1.0
    assert drv.params["linear.x.min_velocity"].value == -1.0
    assert lookup([pf], "wheels.separation", "driver").value == 0.16
    assert lookup([pf], "frame").value == "base_link"


def test_ros1_params():
    pf = parse_params("rate: 10\nctrl:\n  type: a/B\n  gains: {p: 1}\n", "r1.yaml")
    assert pf.dialect == "ros1"
    assert pf.nodes["/ctrl"].params["gains.p"].value == 1
    assert pf.nodes["/"].params["rate"].value == 10
    assert lookup([pf], "gains.p", "ctrl").value == 1
    assert lookup([pf], "ctrl.gains.p").value == 1
    assert lookup([pf], "rate").value == 10


def test_list_items_keep_their_locations():
    pf = parse_params("c:\n  ros__parameters:\n    joints:\n      - a\n      - b\n", "l.yaml")
    v = pf.nodes["/c"].params["joints"]
    assert v.value == ["a", "b"]
    assert [loc.line for loc in v.items] == [4, 5]


@pytest.mark.parametrize("key,name,expected", [
    ("/**", "/a/b", True), ("/**/node", "/node", True), ("/**/node", "/a/b/node", True),
    ("/**/node", "/anode", False), ("/*/node", "/a/node", True), ("/*/node", "/node", False),
    ("node", "/node", True), ("/ns/node", "node", True), ("/ns/node", "/other/node", False),
    ("/ns/no*", "node", True),
])
def test_node_key_matching(key, name, expected):
    assert node_key_matches(key, name) is expected


def test_top_level_must_be_a_mapping():
    with pytest.raises(ConsumerError, match="mapping"):
        parse_params("- a\n- b\n", "list.yaml")


def test_every_corpus_parameter_file_reads(corpus):
    files = sorted(p for d in ("ros-controls+ros2_control_demos", "ros-controls+ros_controllers",
                               "ROBOTIS-GIT+turtlebot3")
                   for p in (corpus / d).rglob("*.yaml")
                   if any(part in ("config", "param", "params", "test") for part in p.parts)
                   and p.name != "rosdoc.yaml")
    assert len(files) > 40
    for f in files:
        read_params(f)  # must not raise


def test_turtlebot3_duplicate_wildcard_keys(corpus):
    pf = read_params(corpus / "ROBOTIS-GIT+turtlebot3/turtlebot3_bringup/param/burger.yaml")
    assert set(pf.nodes) == {"/**/turtlebot3_node", "/**/diff_drive_controller"}
    assert lookup([pf], "wheels.separation", "turtlebot3_node").value == 0.16
    assert lookup([pf], "odometry.child_frame_id").value == "base_footprint"
