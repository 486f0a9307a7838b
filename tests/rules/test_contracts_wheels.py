"""Wheel geometry (forward kinematics at zero) against differential-drive parameters."""
import sys
from pathlib import Path

SRC = Path(__file__).resolve().parents[2] / "src"
if str(SRC) not in sys.path:  # runnable without an editable install
    sys.path.insert(0, str(SRC))

import pytest  # noqa: E402

from urdfcheck.consumers.common import Value  # noqa: E402
from urdfcheck.consumers.controllers import DriveSpec, JointUse, read_controllers  # noqa: E402
from urdfcheck.consumers.params import parse_params  # noqa: E402
from urdfcheck.core.findings import Location, Severity  # noqa: E402
from urdfcheck.model.build import model_from_string  # noqa: E402
from urdfcheck.rules.contracts.wheels import check_drive  # noqa: E402


def wheel(name, xyz, rpy, axis, shape='<cylinder radius="0.1" length="0.05"/>', shape_rpy="0 0 0", kind="continuous"):
    return f"""
  <link name="{name}_link">
    <collision><origin rpy="{shape_rpy}"/><geometry>{shape}</geometry></collision>
    <visual><geometry><sphere radius="0.5"/></geometry></visual>
  </link>
  <joint name="{name}_joint" type="{kind}">
    <parent link="base_link"/><child link="{name}_link"/>
    <origin xyz="{xyz}" rpy="{rpy}"/><axis xyz="{axis}"/>
  </joint>"""


def robot(*wheels, root="base_link"):
    extra = ""
    if root != "base_link":
        extra = f'<link name="{root}"/><joint name="fp" type="fixed"><parent link="{root}"/><child link="base_link"/>' \
                f'<origin xyz="0 0 0.1" rpy="0 0 0.3"/></joint>'
    return model_from_string(f'<robot name="r"><link name="base_link"/>{extra}{"".join(wheels)}</robot>', "r.urdf")


# wheel frames rotated by -/+90 degrees about x, turning about their z: both axes end up along +y in base_link
LEFT = wheel("left", "0 0.25 0", "-1.5708 0 0", "0 0 1")
RIGHT = wheel("right", "0.01 -0.25 0.02", "1.5708 0 0", "0 0 -1")
YAML = "loc.yaml"


def drive(left=("left_joint",), right=("right_joint",), sep=0.5, radius=0.1, sep_mult=None, lmult=None, rmult=None,
          from_urdf=False):
    def v(x, line):
        return None if x is None else Value(x, Location(YAML, line))
    uses = lambda names, side: tuple(JointUse(n, Location(YAML, 20 + i), "ddc", role=f"{side}_wheel")  # noqa: E731
                                     for i, n in enumerate(names))
    return DriveSpec("ddc", Location(YAML, 1), uses(left, "left"), uses(right, "right"), Location(YAML, 2),
                     Location(YAML, 3), v(sep, 4), v(radius, 5), v(sep_mult, 6), v(lmult, 7), v(rmult, 8),
                     from_urdf=from_urdf)


def codes(rep):
    return sorted(p.code for p in rep.problems())


def test_consistent_drive_is_clean():
    rep = check_drive(robot(LEFT, RIGHT), drive())
    assert codes(rep) == []
    assert rep.measured_separation == pytest.approx(0.5, abs=1e-6)
    assert rep.urdf_distance > 0.5  # the x/z offset is not part of the separation
    assert rep.sides_swapped is False
    assert {w.use.joint: w.radius for w in rep.wheels} == {"left_joint": 0.1, "right_joint": 0.1}
    assert all(w.axis == pytest.approx((0, 1, 0), abs=1e-4) or w.axis == pytest.approx((0, -1, 0), abs=1e-4)
               for w in rep.wheels)


def test_separation_mismatch_and_multiplier():
    rep = check_drive(robot(LEFT, RIGHT), drive(sep=0.52))
    (p,) = rep.problems()
    assert p.code == "C010" and p.at == Location(YAML, 4)
    assert "0.52" in p.message and "0.5 m apart" in p.message
    assert p.data["measured"] == pytest.approx(0.5, abs=1e-6)
    # a multiplier other than 1 is a declared slip factor (issue 15): the base value is compared with the
    # model and the finding is information saying what the multiplier does
    (p,) = check_drive(robot(LEFT, RIGHT), drive(sep=0.5, sep_mult=1.04)).problems()
    assert p.code == "C010" and p.severity == Severity.INFO and p.at == Location(YAML, 6)
    assert "matches" in p.message and "1.04 x 0.5 = 0.52 m" in p.message and len(p.message) < 400
    (p,) = check_drive(robot(LEFT, RIGHT), drive(sep=0.48076923, sep_mult=1.04)).problems()
    assert p.severity == Severity.INFO and "differs" in p.message


def test_tolerance():
    assert codes(check_drive(robot(LEFT, RIGHT), drive(sep=0.5015))) == ["C010"]
    assert codes(check_drive(robot(LEFT, RIGHT), drive(sep=0.5015), tolerance=0.002)) == []


def test_separation_is_frame_independent():
    rep = check_drive(robot(LEFT, RIGHT, root="base_footprint"), drive(), base_frame="base_footprint")
    assert rep.measured_separation == pytest.approx(0.5, abs=1e-6) and codes(rep) == []


def test_radius_mismatch_with_side_multipliers():
    rep = check_drive(robot(LEFT, RIGHT), drive(radius=0.105))
    (p,) = [p for p in rep.problems() if "left_link" in p.message]
    assert p.code == "C011" and p.at == Location(YAML, 5) and p.severity is None
    assert p.related[0].file == "r.urdf"  # the wheel's collision cylinder
    # a radius multiplier other than 1 is a declared correction: information at the multiplier
    (p,) = check_drive(robot(LEFT, RIGHT), drive(radius=0.1, lmult=1.05)).problems()
    assert p.code == "C011" and p.severity == Severity.INFO and p.at == Location(YAML, 7)
    assert "matches" in p.message and "1.05 x 0.1 = 0.105 m" in p.message


def test_sphere_and_visual_fallback_and_mesh():
    sphere = wheel("right", "0 -0.25 0", "1.5708 0 0", "0 0 -1", shape='<sphere radius="0.1"/>')
    assert codes(check_drive(robot(LEFT, sphere), drive())) == []
    mesh = wheel("right", "0 -0.25 0", "1.5708 0 0", "0 0 -1", shape='<mesh filename="w.stl"/>')
    rep = check_drive(robot(LEFT, mesh), drive())
    right = [w for w in rep.wheels if w.side == "right"][0]
    assert right.shape_from == "visual" and right.radius == 0.5  # no usable collision: the visual is used
    assert codes(rep) == ["C011"]
    left = [w for w in rep.wheels if w.side == "left"][0]
    assert left.shape_from == "collision" and left.radius == 0.1  # the collision cylinder wins over the visual


def test_cylinder_lying_the_wrong_way():
    flat = wheel("right", "0 -0.25 0", "1.5708 0 0", "0 0 -1", shape_rpy="1.5708 0 0")
    rep = check_drive(robot(LEFT, flat), drive())
    (p,) = rep.problems()
    assert p.code == "C011" and "cylinder" in p.message and "axis" in p.message


def test_axes_not_parallel():
    tilted = wheel("right", "0 -0.25 0", "0 0 0", "0 0 1")
    rep = check_drive(robot(LEFT, tilted), drive())
    assert "C012" in codes(rep)
    p = [p for p in rep.problems() if p.code == "C012"][0]
    assert "90 degrees" in p.message and p.at.file == "r.urdf"


def test_wheels_one_behind_the_other():
    front = wheel("left", "0.3 0 0", "-1.5708 0 0", "0 0 1")
    back = wheel("right", "-0.3 0 0", "1.5708 0 0", "0 0 -1")
    rep = check_drive(robot(front, back), drive(sep=0.6))
    assert codes(rep) == ["C010"] and "one behind the other" in rep.problems()[0].message


def test_left_on_the_right():
    left = wheel("left", "0 -0.25 0", "-1.5708 0 0", "0 0 1")
    right = wheel("right", "0 0.25 0", "1.5708 0 0", "0 0 -1")
    rep = check_drive(robot(left, right), drive())
    # both axes come out +y in base_link: positive rotation drives forward, so the wheel named left
    # really sits on the right and the robot turns the wrong way (C014)
    assert rep.sides_swapped is True and codes(rep) == ["C014"]


def test_unequal_and_empty_sides():
    rep = check_drive(robot(LEFT, RIGHT), drive(left=("left_joint",), right=("right_joint", "right_joint")))
    (p,) = rep.problems()
    assert p.code == "C013" and p.severity is None
    rep = check_drive(robot(LEFT, RIGHT), drive(left=()))
    c13 = [p for p in rep.problems() if p.code == "C013"]
    assert c13 and c13[0].severity == Severity.ERROR and c13[0].at == Location(YAML, 2)


def test_unknown_and_fixed_joints_are_left_to_other_rules():
    fixed = wheel("right", "0 -0.25 0", "1.5708 0 0", "0 0 -1", kind="fixed")
    assert codes(check_drive(robot(LEFT, fixed), drive())) == []
    assert codes(check_drive(robot(LEFT, RIGHT), drive(right=("nope",)))) == []


def test_ros1_values_from_the_urdf():
    # no wheel_separation / wheel_radius: the ROS 1 controller computes them; only impossible cases are reported
    staggered = wheel("right", "0.1 -0.25 0", "1.5708 0 0", "0 0 -1")  # 0.51 m between origins, 0.5 m along the axis
    assert codes(check_drive(robot(LEFT, staggered), drive(sep=None, radius=None, from_urdf=True))) == ["C010"]
    aligned = wheel("right", "0 -0.25 0", "1.5708 0 0", "0 0 -1")
    assert codes(check_drive(robot(LEFT, aligned), drive(sep=None, radius=None, from_urdf=True))) == []
    box = wheel("right", "0 -0.25 0", "1.5708 0 0", "0 0 -1", shape='<box size="0.1 0.1 0.1"/>')
    box = box.replace('<visual><geometry><sphere radius="0.5"/></geometry></visual>', "")
    rep = check_drive(robot(LEFT, box), drive(sep=None, radius=None, from_urdf=True))
    assert [p.severity for p in rep.problems() if p.code == "C011"] == [Severity.ERROR]
    # ROS 2 without wheel_separation: it defaults to 0
    assert "C010" in codes(check_drive(robot(LEFT, RIGHT), drive(sep=None)))


def test_with_a_real_controller_file():
    cs = read_controllers([parse_params(
        "ddc:\n  ros__parameters:\n    type: diff_drive_controller/DiffDriveController\n"
        "    left_wheel_names: [left_joint]\n    right_wheel_names: [right_joint]\n"
        "    wheel_separation: 0.55\n    wheel_radius: 0.1\n", "c.yaml")])
    (p,) = check_drive(robot(LEFT, RIGHT), cs.by_name("ddc").drive).problems()
    assert p.code == "C010" and (p.at.file, p.at.line) == ("c.yaml", 6)


def test_diffbot_corpus_geometry(corpus):
    from urdfcheck.load.loader import load_model

    d = corpus / "ros-controls+ros2_control_demos"
    pk = {"ros2_control_demo_description": str(d / "ros2_control_demo_description"),
          "ros2_control_demo_example_2": str(d / "example_2/description")}
    model = load_model(d / "example_2/description/urdf/diffbot.urdf.xacro", packages=pk)
    from urdfcheck.consumers.controllers import load_controllers

    cs, _ = load_controllers([d / "example_2/bringup/config/diffbot_controllers.yaml"])
    rep = check_drive(model, cs.by_name("diffbot_base_controller").drive, base_frame="base_link")
    # a real defect of the demo description: left_wheel_joint sits at y = -0.05 with axis +y (C014)
    assert codes(rep) == ["C014"]
    assert rep.measured_separation == pytest.approx(0.10) and rep.sides_swapped is True


def test_world_poses_are_computed_once_per_model(monkeypatch):
    """Six wheel rules ask for the poses once per drive each: one computation per model, and each caller gets a
    copy it may change."""
    from urdfcheck.model.robot import Model

    m = model_from_string('<robot name="r"><link name="a"/><link name="b"/>'
                          '<joint name="j" type="fixed"><parent link="a"/><child link="b"/>'
                          '<origin xyz="1 2 3"/></joint></robot>')
    calls = []
    real = Model._world_poses
    monkeypatch.setattr(Model, "_world_poses", lambda self: calls.append(1) or real(self))
    first = m.world_poses()
    first["b"] = None
    second = m.world_poses()
    assert len(calls) == 1
    assert second["b"][0][3] == 1.0 and second["b"][2][3] == 3.0 and set(second) == {"a", "b"}


# --- the rolling feature (issue 37): hub and tyre, tyre off its joint frame, camber from rpy="3.14 0 0" ----------

def tyre_wheel(name, y, rpy, axis, tyre_y, radius=0.1, rim=None):
    """A wheel link whose first collision cylinder is the hub (r 0.03) and whose tyre sits `tyre_y` along the link's
    y from the joint frame (the joint axis is the link's y)."""
    rim_xml = (f'<collision><origin xyz="0 {tyre_y} 0" rpy="1.5708 0 0"/><geometry><cylinder radius="{rim}" '
               f'length="0.04"/></geometry></collision>') if rim else ""
    return f"""
  <link name="{name}_link">
    <collision><origin rpy="1.5708 0 0"/><geometry><cylinder radius="0.03" length="0.02"/></geometry></collision>
    {rim_xml}
    <collision><origin xyz="0 {tyre_y} 0" rpy="1.5708 0 0"/>
      <geometry><cylinder radius="{radius}" length="0.05"/></geometry></collision>
  </link>
  <joint name="{name}_joint" type="continuous">
    <parent link="base_link"/><child link="{name}_link"/>
    <origin xyz="0 {y} 0" rpy="{rpy}"/><axis xyz="{axis}"/>
  </joint>"""


# hub joints at y = +/-0.22, tyres 0.03 further out; the right wheel mirrored by rpy="3.14 0 0" (0.09 degrees of
# camber left by 3.14 != pi), its axis flipped so that both roll forward alike
HUB_LEFT = tyre_wheel("left", 0.22, "0 0 0", "0 1 0", 0.03)
HUB_RIGHT = tyre_wheel("right", -0.22, "3.14 0 0", "0 -1 0", 0.03)


def test_tyre_not_hub_gives_radius_and_separation_and_camber_is_not_non_parallel():
    rep = check_drive(robot(HUB_LEFT, HUB_RIGHT), drive(sep=0.5, radius=0.1))
    assert codes(rep) == [], [p.message for p in rep.problems()]
    assert {w.use.joint: w.radius for w in rep.wheels} == {"left_joint": 0.1, "right_joint": 0.1}
    assert rep.measured_separation == pytest.approx(0.5, abs=1e-4)


def test_the_hub_radius_in_the_controller_is_reported_at_the_tyre():
    (p,) = [p for p in check_drive(robot(HUB_LEFT, HUB_RIGHT), drive(sep=0.5, radius=0.03)).problems()][:1]
    assert p.code == "C011" and "radius 0.1 m (the largest of its coaxial shapes)" in p.message
    assert p.rests_on == ()  # the hub is not the controller's value: nothing ambiguous to demote


def test_a_radius_matching_another_coaxial_shape_rests_on_the_shape_choice():
    rimmed = robot(tyre_wheel("left", 0.22, "0 0 0", "0 1 0", 0.03, rim=0.08),
                   tyre_wheel("right", -0.22, "3.14 0 0", "0 -1 0", 0.03, rim=0.08))
    probs = [p for p in check_drive(rimmed, drive(sep=0.5, radius=0.08)).problems() if p.code == "C011"]
    assert len(probs) == 2
    assert all(len(p.rests_on) == 1 and p.rests_on[0].how == "shape" and not p.rests_on[0].strong for p in probs)


def test_real_camber_in_heading_is_still_reported():
    yawed = tyre_wheel("right", -0.22, "0 0 0.1", "0 1 0", -0.03)
    rep = check_drive(robot(HUB_LEFT, yawed), drive(sep=0.5, radius=0.1))
    (p,) = [p for p in rep.problems() if p.code == "C012"]
    assert "5.73 degrees" in p.message


def _package(tmp_path, left, right, radius):
    import shutil

    from conftest import REPO
    pkg = tmp_path / "pkg"
    shutil.copytree(REPO / "examples" / "broken" / "contract_wheel_radius", pkg)
    (pkg / "EXPECTED").unlink()
    urdf = pkg / "urdf" / "agv.urdf"
    text = urdf.read_text(encoding="utf-8")
    start, end = text.index('  <link name="left_wheel_link">'), text.index('  <joint name="laser_link_joint"')
    wheels = (left + right).replace('"left_', '"left_wheel_').replace('"right_', '"right_wheel_')
    urdf.write_text(text[:start] + wheels + "\n" + text[end:], encoding="utf-8")
    cfg = pkg / "config" / "agv_controllers.yaml"
    cfg.write_text(cfg.read_text(encoding="utf-8").replace("wheel_radius: 0.12", f"wheel_radius: {radius}"),
                   encoding="utf-8")
    return pkg


def test_hub_and_tyre_robot_is_not_red_through_the_cli(tmp_path):
    from conftest import lint_json
    pkg = _package(tmp_path, HUB_LEFT, HUB_RIGHT, 0.10)
    _, report = lint_json([str(pkg)], cwd=tmp_path)
    assert [f["code"] for f in report["findings"] if f["code"] in ("C010", "C011", "C012", "C015")] == []


def test_an_ambiguous_wheel_feature_is_said_as_info_naming_the_step(tmp_path):
    from conftest import lint_json
    pkg = _package(tmp_path, tyre_wheel("left", 0.22, "0 0 0", "0 1 0", 0.03, rim=0.08),
                   tyre_wheel("right", -0.22, "3.14 0 0", "0 -1 0", 0.03, rim=0.08), 0.08)
    _, report = lint_json([str(pkg)], cwd=tmp_path)
    c011 = [f for f in report["findings"] if f["code"] == "C011"]
    assert c011 and all(f["severity"] == "info" and "picked by its shape" in f["message"] for f in c011), c011


def test_mecanum_projection_is_measured_at_the_tyres():
    """lx + ly from the rollers' centres, not the hub joint frames 0.03 m further in."""
    from urdfcheck.consumers.catalog import WheelSet
    from urdfcheck.rules.contracts.drives import geometry_problems

    def w(name, x, y, tyre_y):
        return tyre_wheel(name, y, "0 0 0", "0 1 0", tyre_y).replace('xyz="0 ' + str(y), f'xyz="{x} {y}')

    model = robot(w("fl", 0.2, 0.22, 0.03), w("fr", 0.2, -0.22, -0.03), w("rl", -0.2, 0.22, 0.03),
                  w("rr", -0.2, -0.22, -0.03))
    uses = tuple(JointUse(f"{n}_joint", Location(YAML, 20 + i), "mecanum", role="wheel")
                 for i, n in enumerate(("fl", "fr", "rl", "rr")))
    ws = WheelSet("mecanum", "mecanum", Location(YAML, 1), uses, (), projection=Value(0.45, Location(YAML, 9)),
                  projection_key="sum_of_robot_center_projection")
    assert geometry_problems(model, ws, "base_link", 0.001) == []
