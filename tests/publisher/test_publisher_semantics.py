"""robot_state_publisher semantics, rule by rule (robot_state_publisher.cpp / joint_state_listener.cpp)."""
import math

import pytest

from urdfcheck.model.build import model_from_string
from urdfcheck.publisher import (
    ROS1,
    ROS2,
    JointState,
    JointStateError,
    Stamp,
    StatePublisher,
    TransformLookupError,
    lookup,
    lookup_matrix,
)
from urdfcheck.publisher.kinematics import kdl_sign, quat_from_matrix, rot_from_quat

ARM = """<robot name="arm">
  <link name="base"/><link name="l1"/><link name="l2"/><link name="l3"/><link name="tool"/>
  <link name="cam"/><link name="m1"/><link name="m2"/>
  <joint name="j1" type="revolute"><parent link="base"/><child link="l1"/><origin xyz="0 0 0.5"/>
    <axis xyz="0 0 1"/><limit lower="-3" upper="3" effort="1" velocity="1"/></joint>
  <joint name="j2" type="continuous"><parent link="l1"/><child link="l2"/><origin xyz="0.1 0 0" rpy="0 1.5707963 0"/>
    <axis xyz="0 2 0"/></joint>
  <joint name="j3" type="prismatic"><parent link="l2"/><child link="l3"/><axis xyz="1 0 0"/>
    <limit lower="0" upper="1" effort="1" velocity="1"/></joint>
  <joint name="tool_joint" type="fixed"><parent link="l3"/><child link="tool"/><origin xyz="0 0 0.2"/></joint>
  <joint name="cam_joint" type="fixed"><parent link="base"/><child link="cam"/>
    <origin xyz="1 0 1" rpy="0 0 3.0"/></joint>
  <joint name="b_mimic" type="revolute"><parent link="base"/><child link="m1"/><axis xyz="0 0 1"/>
    <limit lower="-3" upper="3" effort="1" velocity="1"/><mimic joint="j1" multiplier="2" offset="0.1"/></joint>
  <joint name="a_mimic" type="revolute"><parent link="base"/><child link="m2"/><axis xyz="0 0 1"/>
    <limit lower="-3" upper="3" effort="1" velocity="1"/><mimic joint="b_mimic" multiplier="-1" offset="0"/></joint>
</robot>"""


@pytest.fixture(scope="module")
def arm():
    return model_from_string(ARM)


def flat(rows):
    return [x for r in rows for x in r]


def names(transforms):
    return [(t.parent, t.child) for t in transforms]


# --- fixed / static ---------------------------------------------------------------------------------------------
def test_static_transforms_are_fixed_joints_in_name_order(arm):
    pub = StatePublisher(arm)
    st = pub.static_transforms(stamp=(3, 5))
    assert names(st) == [("base", "cam"), ("l3", "tool")]  # cam_joint < tool_joint
    assert all(t.stamp == Stamp(3, 5) for t in st)
    cam = st[0]
    assert cam.translation == (1.0, 0.0, 1.0)
    assert cam.rotation == pytest.approx((0, 0, math.sin(1.5), math.cos(1.5)), abs=1e-15)
    assert pub.startup(0.0) == {"/tf_static": pub.static_transforms(0.0)}
    assert pub.tick(10.0) == []  # ROS 2 never re-publishes fixed transforms


def test_movable_only_for_joints_in_the_message(arm):
    pub = StatePublisher(arm)
    out = pub.on_joint_state(JointState(["j2"], [0.3], 1.0))
    assert names(out) == [("l1", "l2")]
    assert out[0].stamp == Stamp(1, 0)


# --- message validation -----------------------------------------------------------------------------------------
def test_length_mismatch_is_rejected_and_leaves_state_untouched(arm):
    pub = StatePublisher(arm)
    with pytest.raises(JointStateError, match="2 names but 1 positions"):
        pub.on_joint_state(JointState(["j1", "j2"], [0.1], 1.0))
    with pytest.raises(JointStateError, match="position member was empty"):
        pub.on_joint_state(JointState(["j1"], [], 1.0))
    # nothing was recorded: the next message at the same stamp still publishes (j1 and its mimic b_mimic)
    assert names(pub.on_joint_state(JointState(["j1"], [0.1], 1.0))) == [("base", "m1"), ("base", "l1")]


def test_unknown_and_non_movable_names_are_ignored_but_reported(arm):
    pub = StatePublisher(arm)
    out = pub.on_joint_state(JointState(["nope", "j1", "tool_joint"], [1.0, 0.2, 3.0], 1.0))
    # name order: b_mimic (filled from j1), j1; a_mimic is not filled (see the mimic tests)
    assert names(out) == [("base", "m1"), ("base", "l1")]
    assert pub.last_unknown == ("nope",)
    assert pub.last_ignored == ("tool_joint",)
    assert pub.unknown_names == {"nope"}


def test_duplicate_names_first_value_wins(arm):
    pub = StatePublisher(arm)
    out = pub.on_joint_state(JointState(["j3", "j3"], [0.25, 0.75], 1.0))
    assert out[0].translation == pytest.approx((0.25, 0.0, 0.0))


# --- throttling -------------------------------------------------------------------------------------------------
def test_throttle_by_header_stamps_ros2_integer_milliseconds(arm):
    pub = StatePublisher(arm, publish_frequency=30.0)
    assert pub.publish_interval_ns == 33_000_000  # int(1000 / 30) ms, as the C++ computes it
    assert pub.on_joint_state(JointState(["j1"], [0.0], 10.0))
    assert pub.on_joint_state(JointState(["j1"], [0.0], 10.032)) == []
    assert pub.last_throttled
    assert pub.on_joint_state(JointState(["j1"], [0.0], (10, 33_000_000)))
    assert not pub.last_throttled


def test_throttle_uses_least_recently_published_joint(arm):
    pub = StatePublisher(arm)  # 20 Hz: 50 ms
    assert pub.on_joint_state(JointState(["j1"], [0.0], 1.0))
    assert pub.on_joint_state(JointState(["j1"], [0.0], 1.001)) == []
    # j2 was never published (time 0): a message naming j1 and j2 goes through 1 ms later
    assert names(pub.on_joint_state(JointState(["j1", "j2"], [0.0, 0.0], 1.001))) == [
        ("base", "m1"), ("base", "l1"), ("l1", "l2")]
    # now both were published at 1.001
    assert pub.on_joint_state(JointState(["j1", "j2"], [0.0, 0.0], 1.002)) == []
    assert pub.on_joint_state(JointState(["j2"], [0.0], 1.051))


def test_ignore_timestamp_publishes_everything(arm):
    pub = StatePublisher(arm, ignore_timestamp=True)
    for s in (1.0, 1.0, 0.5, 1.001):
        assert pub.on_joint_state(JointState(["j1"], [0.0], s))


def test_time_going_backwards_clears_the_throttle(arm):
    pub = StatePublisher(arm)
    assert pub.on_joint_state(JointState(["j1"], [0.0], 100.0))
    assert pub.on_joint_state(JointState(["j1"], [0.0], 100.01)) == []
    # a bag restarts: the clock (here the stamp) jumps back; publish times are forgotten
    assert pub.on_joint_state(JointState(["j1"], [0.0], 5.0))
    assert pub.time_jumps == 1


def test_explicit_node_clock(arm):
    pub = StatePublisher(arm)
    assert pub.on_joint_state(JointState(["j1"], [0.0], 100.0), now=200.0)
    # stamp goes back but the node clock does not: still throttled (stamp < last publish + interval)
    assert pub.on_joint_state(JointState(["j1"], [0.0], 50.0), now=201.0) == []
    assert pub.time_jumps == 0
    assert pub.on_joint_state(JointState(["j1"], [0.0], 50.0), now=1.0)  # the clock went back
    assert pub.time_jumps == 1


def test_publish_frequency_validation():
    m = model_from_string(ARM)
    for bad in (0.0, -1.0, 1000.5):
        with pytest.raises(ValueError, match="between 0"):
            StatePublisher(m, publish_frequency=bad)
    assert StatePublisher(m, publish_frequency=1000.0).publish_interval_ns == 1_000_000
    # ROS 1 clamps below 1 Hz and keeps nanoseconds: Duration(1.0 / max(f, 1.0))
    assert StatePublisher(m, profile="ros1", publish_frequency=0.0).publish_interval_ns == 1_000_000_000
    assert StatePublisher(m, profile="ros1", publish_frequency=30.0).publish_interval_ns == 33_333_333
    assert StatePublisher(m, profile="ros1").publish_interval_ns == 20_000_000  # 50 Hz default
    assert StatePublisher(m).publish_interval_ns == 50_000_000  # 20 Hz default


# --- mimic ------------------------------------------------------------------------------------------------------
def test_mimic_from_direct_source_and_name_order(arm):
    pub = StatePublisher(arm, ignore_timestamp=True)
    out = {t.child: t for t in pub.on_joint_state(JointState(["j1"], [0.5], 1.0))}
    # b_mimic = 2 * 0.5 + 0.1 = 1.1 about z
    assert out["m1"].rotation == pytest.approx((0, 0, math.sin(0.55), math.cos(0.55)))
    # a_mimic follows b_mimic, but 'a_mimic' < 'b_mimic': when a_mimic is considered b_mimic is not filled yet
    assert "m2" not in out
    assert any(n.code == "mimic-order" and n.joint == "a_mimic" for n in pub.notes)
    # naming b_mimic in the message makes a_mimic computable from it (direct source)
    out = {t.child: t for t in pub.on_joint_state(JointState(["j1", "b_mimic"], [0.5, 0.4], 1.0))}
    assert out["m2"].rotation == pytest.approx(kdl_sign(0, 0, math.sin(-0.2), math.cos(-0.2)))


def test_mimic_explicit_value_wins(arm):
    pub = StatePublisher(arm, ignore_timestamp=True)
    out = {t.child: t for t in pub.on_joint_state(JointState(["b_mimic", "j1"], [0.2, 0.5], 1.0))}
    assert out["m1"].rotation == pytest.approx((0, 0, math.sin(0.1), math.cos(0.1)))


def test_mimic_on_fixed_joints_does_nothing():
    # robot_state_publisher's own test model: fixed joints with <mimic>
    xml = """<robot name="test"><link name="base_link"/><link name="second_link"/><link name="third_link"/>
      <joint name="base_to_second_joint" type="fixed"><origin rpy="1 0 0" xyz="0 1 0"/>
        <parent link="base_link"/><child link="second_link"/></joint>
      <joint name="base_to_third_joint" type="fixed"><origin rpy="1 0 0" xyz="0 1 0"/>
        <parent link="base_link"/><child link="third_link"/>
        <mimic joint="base_to_second_joint" multiplier="1" offset="0"/></joint></robot>"""
    pub = StatePublisher(model_from_string(xml))
    assert names(pub.static_transforms()) == [("base_link", "second_link"), ("base_link", "third_link")]
    assert pub.on_joint_state(JointState(["base_to_second_joint"], [1.0], 1.0)) == []
    # the mimic value is filled in, then ignored like its fixed source (ROS 1 warns about both names)
    assert pub.last_ignored == ("base_to_second_joint", "base_to_third_joint")


# --- kinematics details -----------------------------------------------------------------------------------------
def test_axis_is_normalised_like_kdl(arm):
    pub = StatePublisher(arm, ignore_timestamp=True)
    (t,) = pub.on_joint_state(JointState(["j2"], [0.7], 1.0))
    # origin rpy (0, ~pi/2, 0) then 0.7 rad about the unit y axis (the axis was written as 0 2 0)
    expected = lookup_matrix(arm, "l1", "l2", {"j2": 0.7})
    r = rot_from_quat(*t.rotation)
    assert flat(r) == pytest.approx(flat(row[:3] for row in expected[:3]), abs=1e-15)
    assert r[0][0] == pytest.approx(math.cos(1.5707963 + 0.7), abs=1e-12)


def test_quaternion_sign_follows_kdl():
    # rotation by pi about x: trace -1, KDL picks x > 0
    assert kdl_sign(-1.0, 0.0, 0.0, 0.0) == (1.0, -0.0, -0.0, -0.0)
    m = ((1, 0, 0), (0, -1, 0), (0, 0, -1))
    assert quat_from_matrix(m) == (1.0, 0.0, 0.0, 0.0)
    # a revolute joint at q = 2*pi - 0.1 gives w < 0 from the half-angle product; KDL gives w > 0
    xml = """<robot name="r"><link name="a"/><link name="b"/><joint name="j" type="continuous">
      <parent link="a"/><child link="b"/><axis xyz="0 0 1"/></joint></robot>"""
    pub = StatePublisher(model_from_string(xml), ignore_timestamp=True)
    (t,) = pub.on_joint_state(JointState(["j"], [2 * math.pi - 0.1], 1.0))
    assert t.rotation[3] > 0
    assert t.rotation == pytest.approx((0, 0, math.sin(-0.05), math.cos(-0.05)))


SPECIAL = """<robot name="special">
  <link name="base"/><link name="p"/><link name="f"/><link name="f2"/><link name="z"/><link name="zp"/>
  <joint name="planar_j" type="planar"><parent link="base"/><child link="p"/><origin xyz="1 2 3"/>
    <axis xyz="0 0 1"/></joint>
  <joint name="float_j" type="floating"><parent link="base"/><child link="f"/><origin xyz="0 0 1"/></joint>
  <joint name="under_float" type="fixed"><parent link="f"/><child link="f2"/><origin xyz="0 0 1"/></joint>
  <joint name="zero_rev" type="revolute"><parent link="base"/><child link="z"/><axis xyz="0 0 0"/>
    <limit lower="-1" upper="1" effort="1" velocity="1"/></joint>
  <joint name="zero_pri" type="prismatic"><parent link="base"/><child link="zp"/><origin xyz="1 0 0"/>
    <axis xyz="0 0 0"/><limit lower="-1" upper="1" effort="1" velocity="1"/></joint>
</robot>"""


def test_planar_static_floating_skipped_zero_axis_nan():
    pub = StatePublisher(model_from_string(SPECIAL), ignore_timestamp=True)
    codes = {(n.code, n.joint) for n in pub.notes}
    assert {("planar", "planar_j"), ("floating", "float_j"), ("zero-axis", "zero_rev"),
            ("zero-axis", "zero_pri")} <= codes
    st = {t.child: t for t in pub.static_transforms()}
    assert set(st) == {"p", "f2"}  # planar is static at its origin; the floating joint is not published
    assert st["p"].translation == (1.0, 2.0, 3.0)
    out = {t.child: t for t in pub.on_joint_state(
        JointState(["planar_j", "float_j", "zero_rev", "zero_pri"], [1.0, 1.0, 0.5, 0.5], 1.0))}
    assert set(out) == {"z", "zp"}
    assert all(math.isnan(v) for v in out["z"].translation + out["z"].rotation)
    assert all(math.isnan(v) for v in out["zp"].translation)
    assert out["zp"].rotation == (0.0, 0.0, 0.0, 1.0)  # KDL: prismatic keeps the origin rotation
    assert set(pub.last_ignored) == {"planar_j", "float_j"}


def test_lookup_is_tf2_echo_semantics(arm):
    # tf2_echo base cam: the pose of cam in base
    t = lookup(arm, "base", "cam")
    assert t.parent == "base" and t.child == "cam"
    assert t.translation == pytest.approx((1.0, 0.0, 1.0))
    back = lookup(arm, "cam", "base")
    m = lookup_matrix(arm, "cam", "base")
    assert back.translation == pytest.approx((m[0][3], m[1][3], m[2][3]))
    # (cam in base) * (base in cam) = identity
    from urdfcheck.core.geometry import compose

    ident = compose(lookup_matrix(arm, "base", "cam"), m)
    assert flat(ident) == pytest.approx(flat([[1, 0, 0, 0], [0, 1, 0, 0], [0, 0, 1, 0], [0, 0, 0, 1]]), abs=1e-12)
    with pytest.raises(TransformLookupError, match="no value for joint 'j1'"):
        lookup(arm, "base", "tool", {})
    # tool is 0.2 along l2's z, which the pitch of ~pi/2 turns into base x
    assert lookup(arm, "base", "tool", {}, default=0.0).translation == pytest.approx((0.3, 0.0, 0.5), abs=1e-7)
    with pytest.raises(TransformLookupError, match="does not exist"):
        lookup(arm, "base", "nope")
    special = model_from_string(SPECIAL)
    with pytest.raises(TransformLookupError, match="floating joint 'float_j'"):
        lookup(special, "base", "f2")
    assert lookup(special, "f", "f2").translation == (0.0, 0.0, 1.0)


# --- frame prefix and ROS 1 -------------------------------------------------------------------------------------
def test_frame_prefix_ros2_is_verbatim(arm):
    pub = StatePublisher(arm, frame_prefix="my_prefix/")
    assert ("my_prefix/base", "my_prefix/cam") in names(pub.static_transforms())
    pub = StatePublisher(arm, frame_prefix="robot_")
    assert ("robot_base", "robot_l1") in names(pub.on_joint_state(JointState(["j1"], [0.0], 1.0)))


def test_ros1_tf_prefix_and_profile_defaults(arm):
    assert ROS1.prefixed("/robot", "base") == "robot/base"
    assert ROS1.prefixed("robot", "/world") == "world"
    assert ROS1.prefixed("", "base") == "base"
    assert ROS2.prefixed("/robot", "base") == "/robotbase"
    pub = StatePublisher(arm, profile="ros1", frame_prefix="r1")
    assert pub.publish_frequency == 50.0
    assert ("r1/base", "r1/cam") in names(pub.static_transforms())
    assert pub.fixed_topic == "/tf_static"  # Noetic's default use_tf_static: true


def test_ros1_without_tf_static_republishes_fixed_transforms_on_tf(arm):
    pub = StatePublisher(arm, profile="ros1", use_tf_static=False)
    assert pub.fixed_topic == "/tf"
    assert pub.startup(0.0) == {}
    first = pub.tick(10.0)
    assert names(first) == [("base", "cam"), ("l3", "tool")]
    assert first[0].stamp == Stamp(10, 500_000_000)  # future-dated by 0.5 s
    assert pub.tick(10.01) == []  # one interval (20 ms at 50 Hz) not yet over
    again = pub.tick(10.02)
    assert names(again) == names(first) and again[0].stamp == Stamp(10, 520_000_000)


def test_joint_state_from_dict_and_stamps():
    js = JointState.from_dict({"header": {"stamp": {"sec": 3, "nanosec": 7}}, "name": ["a"], "position": [1]})
    assert js.stamp_ns == 3_000_000_007
    assert JointState.from_dict({"names": ["a"], "positions": [1.5], "stamp": [1, 2]}).stamp_ns == 1_000_000_002
    assert JointState.from_dict({"name": ["a"], "position": [1.5], "stamp": 1.25}).stamp_ns == 1_250_000_000
    with pytest.raises(TypeError):
        JointState.from_dict({"name": "a", "position": [1]})
    with pytest.raises(TypeError):
        JointState.from_dict({"name": ["a"], "position": ["x"]})
