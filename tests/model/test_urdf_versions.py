"""URDF 1.1 (<origin quat_xyzw>, urdfdom 5.1) and URDF 1.2 (<limit acceleration|deceleration|jerk>, urdfdom 6.0).

What urdfdom does was read in its sources and run with check_urdf of urdfdom 3.0.1, 4.0.1 and 6.0.0; the
expected values below restate those runs (the rule pages quote them).
"""
from __future__ import annotations

import json
import math
import os

import pytest
from conftest import lint_json, run_cli

from urdfcheck.core import geometry
from urdfcheck.model import grammar as G
from urdfcheck.model.build import model_from_string
from urdfcheck.publisher import JointState, StatePublisher, link_poses, lookup_matrix
from urdfcheck.rules import engine

Q90 = "0 0 0.7071068 0.7071068"


@pytest.fixture(autouse=True)
def _rolling_without_target(monkeypatch):
    """These tests are about what Rolling's urdfdom reads; without a target the default is Humble (issue 25,
    tests/rules/test_profiles.py), which reads URDF 1.0 only."""
    monkeypatch.setattr(G, "DEFAULT_TARGET", "rolling")


def robot(version: str | None, origin: str, limit: str = 'lower="-1" upper="1" effort="1" velocity="1"',
          jtype: str = "revolute") -> str:
    v = f' version="{version}"' if version is not None else ""
    return (f'<robot name="r"{v}>\n  <link name="base_link"/>\n  <link name="arm"/>\n'
            f'  <joint name="j" type="{jtype}">\n    <origin {origin}/>\n'
            f'    <parent link="base_link"/><child link="arm"/><axis xyz="0 0 1"/>\n'
            f'    <limit {limit}/>\n  </joint>\n</robot>\n')


MODEL = robot("1.1", f'xyz="0 0 0.1" quat_xyzw="{Q90}"')


def codes(xml: str, tmp_path, *flags) -> dict[str, list[dict]]:
    p = tmp_path / "r.urdf"
    p.write_text(xml)
    _, report = lint_json([str(p), *flags], cwd=tmp_path)
    out: dict[str, list[dict]] = {}
    for f in report["findings"]:
        out.setdefault(f["code"], []).append(f)
    return out


# --- the issue's "done when" -----------------------------------------------------------------------------------------
def test_quaternion_origin_is_read_and_lint_is_clean(tmp_path):
    m = model_from_string(MODEL)
    assert m.version == (1, 1) and m.declared_version == "1.1"
    assert m.joints["j"].origin.quat == (0.0, 0.0, 0.7071068, 0.7071068)
    assert m.issues == ()
    assert codes(MODEL, tmp_path) == {}


def test_tf_prints_the_90_degree_yaw(tmp_path):
    p = tmp_path / "r.urdf"
    p.write_text(MODEL)
    code, out, err = run_cli(["tf", str(p), "base_link", "arm", "--joint", "j=0", "--format", "json"])
    assert code == 0, err
    doc = json.loads(out)
    assert doc["rpy_degrees"][2] == pytest.approx(90.0, abs=1e-4)
    assert doc["translation"] == pytest.approx([0.0, 0.0, 0.1])


def test_publisher_and_batch_fk_use_the_quaternion():
    m = model_from_string(MODEL)
    pub = StatePublisher(m)
    (t,) = pub.on_joint_state(JointState(["j"], [0.0], stamp=1.0))
    assert t.rotation == pytest.approx((0.0, 0.0, math.sqrt(0.5), math.sqrt(0.5)), abs=1e-7)
    (t,) = pub.on_joint_state(JointState(["j"], [math.pi / 2], stamp=2.0))  # 90 + 90 degrees about z
    assert abs(t.rotation[2]) == pytest.approx(1.0, abs=1e-7)
    np = pytest.importorskip("numpy")
    world = link_poses(m, np.zeros((1, 1)))
    assert world["arm"][0][:3, :3] == pytest.approx(np.array([[0, -1, 0], [1, 0, 0], [0, 0, 1]]), abs=1e-7)
    assert lookup_matrix(m, "base_link", "arm", {"j": 0.0})[1][0] == pytest.approx(1.0, abs=1e-7)


def test_publish_command_uses_the_quaternion(tmp_path):
    p = tmp_path / "r.urdf"
    p.write_text(MODEL)
    js = tmp_path / "js.json"
    js.write_text(json.dumps([{"name": ["j"], "position": [0.0], "stamp": 1.0}]))
    code, out, err = run_cli(["publish", str(p), "--joint-states", str(js)])
    assert code == 0, err
    rotations = [t["rotation"] for t in _transforms(json.loads(out)) if t.get("child") == "arm"]
    assert rotations and all(r == pytest.approx([0.0, 0.0, math.sqrt(0.5), math.sqrt(0.5)], abs=1e-7)
                             for r in rotations), out


def _transforms(doc):
    """Every transform dict in publish's output, wherever it nests them."""
    if isinstance(doc, dict):
        if "rotation" in doc and "child" in doc:
            yield doc
        for v in doc.values():
            yield from _transforms(v)
    elif isinstance(doc, list):
        for v in doc:
            yield from _transforms(v)


def test_same_origin_in_a_1_0_model_is_a_finding(tmp_path):
    for version in (None, "1.0"):
        xml = robot(version, f'xyz="0 0 0.1" quat_xyzw="{Q90}"')
        m = model_from_string(xml)
        assert m.joints["j"].origin.quat is None  # urdfdom ignores it: identity
        assert geometry.origin_quaternion(m.joints["j"].origin) == (0.0, 0.0, 0.0, 1.0)
        found = codes(xml, tmp_path)
        assert list(found) == ["U008"]
        assert found["U008"][0]["location"]["line"] == 5 and found["U008"][0]["severity"] == "error"


def test_both_rpy_and_quaternion_is_an_error(tmp_path):
    found = codes(robot("1.1", f'xyz="0 0 0.1" rpy="0 0 1.5707963" quat_xyzw="{Q90}"'), tmp_path)
    assert list(found) == ["U009"] and "whole model is rejected" in found["U009"][0]["message"]
    # in a 1.0 model the quaternion is ignored instead (urdfdom test parse_rot_both_quat_ignored_version_1_0)
    assert list(codes(robot("1.0", f'rpy="0 0 1" quat_xyzw="{Q90}"'), tmp_path)) == ["U008"]


@pytest.mark.parametrize("version,message", [
    ("2.0", "no URDF version 2.0"),
    ("1.3", "no URDF version 1.3"),
    ("0.9", "no URDF version 0.9"),
    ("1", "should be in the form 'x.y'"),
    ("1.0.0", "should be in the form 'x.y'"),
    ("1.0 ", "Extra characters after the version number"),
    ("a.c", "not an integer"),
    (".1", "is blank"),
    ("-1.0", "must be positive"),
    ("1.010", "no URDF version 1.10"),
])
def test_unsupported_version_is_an_error(version, message, tmp_path):
    found = codes(robot(version, 'xyz="0 0 0.1"'), tmp_path)
    assert list(found) == ["U007"], found
    assert message in found["U007"][0]["message"] and found["U007"][0]["location"]["line"] == 1


@pytest.mark.parametrize("raw,want", [
    (None, (1, 0)), ("1.0", (1, 0)), ("+1.0", (1, 0)), (" 1.0", (1, 0)), ("1.00", (1, 0)), ("1.-0", (1, 0)),
    ("01.01", (1, 1)), (" 1.1", (1, 1)), ("1. 1", (1, 1)), ("1.2", (1, 2)),
])
def test_versions_urdfdom_accepts(raw, want):
    assert G.parse_version(raw) == (want, "")


def test_1_2_limits_are_read_not_unknown(tmp_path):
    lim = 'lower="-1" upper="1" effort="1" velocity="1" acceleration="2" deceleration="3" jerk="40"'
    xml = robot("1.2", 'xyz="0 0 0.1"', lim)
    m = model_from_string(xml)
    assert m.joints["j"].limit[1:] == (-1.0, 1.0, 1.0, 1.0, 2.0, 3.0, 40.0)
    assert codes(xml, tmp_path) == {}
    # the same limits in a 1.0 model: ignored by urdfdom, a finding each, never "unknown attribute"
    found = codes(robot(None, 'xyz="0 0 0.1"', lim), tmp_path)
    assert list(found) == ["U008"] and len(found["U008"]) == 3
    assert model_from_string(robot(None, 'xyz="0 0 0.1"', lim)).joints["j"].limit.acceleration is None


def test_1_2_effort_and_velocity_are_optional():
    m = model_from_string(robot("1.2", "", 'lower="-1" upper="1"'))
    assert m.issues == ()
    m = model_from_string(robot("1.1", "", 'lower="-1" upper="1"'))
    assert sorted(i.code for i in m.issues) == ["U006", "U006"]


@pytest.mark.parametrize("attr,code,severity", [
    ('acceleration="-1"', "J012", "error"), ('jerk="-0.5"', "J012", "error"), ('deceleration="0"', "J012", "warning"),
    ('acceleration="nan"', "U005", "error"), ('jerk="inf"', "U005", "error"),
])
def test_inconsistent_1_2_limits(attr, code, severity, tmp_path):
    found = codes(robot("1.2", "", f'lower="-1" upper="1" effort="1" velocity="1" {attr}'), tmp_path)
    assert list(found) == [code] and found[code][0]["severity"] == severity


def test_1_2_revolute_needs_both_bounds_and_rejects_negative_effort(tmp_path):
    found = codes(robot("1.2", "", 'upper="1" effort="1" velocity="1"'), tmp_path)
    assert found["J002"][0]["severity"] == "error" and "1.2" in found["J002"][0]["message"]
    found = codes(robot("1.2", "", 'lower="-1" upper="1" effort="-1" velocity="1"'), tmp_path)
    assert found["J004"][0]["severity"] == "error"
    found = codes(robot("1.0", "", 'upper="1" effort="1" velocity="1"'), tmp_path)
    assert found["J002"][0]["severity"] == "warning"


def test_quaternion_length(tmp_path):
    found = codes(robot("1.1", 'quat_xyzw="0 0 2 2"'), tmp_path)
    assert list(found) == ["U010"] and found["U010"][0]["severity"] == "warning"
    assert "0.707106781" in found["U010"][0]["message"]
    m = model_from_string(robot("1.1", 'quat_xyzw="0 0 2 2"'))
    assert geometry.origin_quaternion(m.joints["j"].origin) == pytest.approx((0, 0, math.sqrt(.5), math.sqrt(.5)))
    found = codes(robot("1.1", 'quat_xyzw="0 0 0 0"'), tmp_path)
    assert list(found) == ["U010"] and found["U010"][0]["severity"] == "error"
    m = model_from_string(robot("1.1", 'quat_xyzw="0 0 0 0"'))
    assert geometry.origin_quaternion(m.joints["j"].origin) == (0.0, 0.0, 0.0, 1.0)  # urdfdom: identity
    found = codes(robot("1.1", 'quat_xyzw="0 0 nan 1"'), tmp_path)
    assert list(found) == ["U005"]


def test_target_decides_which_versions_load(tmp_path):
    # a catkin package is ROS 1: Noetic's urdfdom 1.0.4 reads URDF 1.0 only
    pkg = tmp_path / "pkg"
    (pkg / "urdf").mkdir(parents=True)
    (pkg / "package.xml").write_text('<package format="2"><name>pkg</name><version>1.0.0</version>'
                                     '<buildtool_depend>catkin</buildtool_depend></package>')
    (pkg / "urdf" / "r.urdf").write_text(MODEL)
    _, report = lint_json([str(pkg / "urdf" / "r.urdf"), "--select", "U"], cwd=tmp_path)
    hits = [f for f in report["findings"] if f["code"] == "U007"]
    assert hits and "noetic" in hits[0]["message"] and "does not start" in hits[0]["message"]


def test_target_option_from_the_context():
    m = model_from_string(MODEL)

    class Cfg:
        target = "humble"

    ctx = engine.Context(config=Cfg()) if "config" in engine.Context._fields else None
    if ctx is None:
        pytest.skip("engine.Context takes no config")
    from urdfcheck.rules.checks.values import urdf_version

    (p,) = list(urdf_version(m, ctx))
    assert "humble ships urdfdom 3.0" in p.message
    Cfg.target = "rolling"
    assert list(urdf_version(m, ctx)) == []


def test_xacro_passes_the_new_attributes_through(tmp_path):
    p = tmp_path / "r.urdf.xacro"
    p.write_text('<robot name="r" version="1.2" xmlns:xacro="http://www.ros.org/wiki/xacro">\n'
                 '  <xacro:property name="q" value="0 0 0.7071068 0.7071068"/>\n'
                 '  <link name="base_link"/><link name="arm"/>\n'
                 '  <joint name="j" type="revolute"><origin xyz="0 0 0.1" quat_xyzw="${q}"/>\n'
                 '    <parent link="base_link"/><child link="arm"/><axis xyz="0 0 1"/>\n'
                 '    <limit lower="-1" upper="1" effort="1" velocity="1" acceleration="2" jerk="${2*20}"/>\n'
                 '  </joint>\n</robot>\n')
    code, out, err = run_cli(["expand", str(p)])
    assert code == 0, err
    assert 'quat_xyzw="0 0 0.7071068 0.7071068"' in out and 'jerk="40"' in out and 'version="1.2"' in out
    _, report = lint_json([str(p)], cwd=tmp_path)
    assert report["findings"] == []


# --- property: rpy and the equivalent quaternion give identical transforms -----------------------------------------
hypothesis = pytest.importorskip("hypothesis")
from hypothesis import HealthCheck, given, settings  # noqa: E402
from hypothesis import strategies as st  # noqa: E402

TYPES = ("revolute", "continuous", "prismatic", "fixed")
EXAMPLES = int(os.environ.get("URDFCHECK_HYPOTHESIS_EXAMPLES", "60"))


def finite(lo, hi):
    return st.floats(lo, hi, allow_nan=False, allow_infinity=False)


@st.composite
def trees(draw):
    n = draw(st.integers(1, 7))
    joints = []
    for i in range(n):
        axis = draw(st.sampled_from([(1.0, 0.0, 0.0), (0.0, 1.0, 0.0), (0.0, 0.0, 1.0), (0.6, 0.0, 0.8)]))
        joints.append({"name": f"j{i}", "type": draw(st.sampled_from(TYPES)), "parent": f"l{draw(st.integers(0, i))}",
                       "child": f"l{i + 1}", "xyz": draw(st.tuples(finite(-2, 2), finite(-2, 2), finite(-2, 2))),
                       "rpy": draw(st.tuples(finite(-4, 4), finite(-4, 4), finite(-4, 4))), "axis": axis,
                       # the same rotation written as -q, or scaled: urdfdom normalises, KDL fixes the sign
                       "sign": draw(st.sampled_from([1.0, -1.0])), "scale": draw(st.sampled_from([1.0, 1.0, 3.0]))})
    values = {j["name"]: draw(finite(-3, 3)) for j in joints if j["type"] != "fixed"}
    return joints, values


def tree_xml(joints, quaternion: bool) -> str:
    r = repr
    version = ' version="1.1"' if quaternion else ""
    out = [f'<robot name="t"{version}>'] + [f'<link name="l{i}"/>' for i in range(len(joints) + 1)]
    for j in joints:
        if quaternion:
            q = geometry.quat_from_rpy(*j["rpy"])
            k = j["sign"] * j["scale"]
            rot = f'quat_xyzw="{" ".join(r(v * k) for v in q)}"'
        else:
            rot = f'rpy="{" ".join(map(r, j["rpy"]))}"'
        out.append(f'<joint name="{j["name"]}" type="{j["type"]}"><origin xyz="{" ".join(map(r, j["xyz"]))}" {rot}/>'
                   f'<parent link="{j["parent"]}"/><child link="{j["child"]}"/>'
                   f'<axis xyz="{" ".join(map(r, j["axis"]))}"/>'
                   f'<limit lower="-3" upper="3" effort="1" velocity="1"/></joint>')
    return "".join(out) + "</robot>"


def published(model, values) -> dict:
    pub = StatePublisher(model)
    out = {(t.parent, t.child): t for t in pub.static_transforms()}
    names = sorted(values)
    out.update({(t.parent, t.child): t for t in pub.on_joint_state(JointState(names, [values[n] for n in names],
                                                                              stamp=1.0))})
    return out


@settings(max_examples=EXAMPLES, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(trees())
def test_rpy_and_equivalent_quaternion_publish_the_same_transforms(case):
    joints, values = case
    a = model_from_string(tree_xml(joints, False))
    b = model_from_string(tree_xml(joints, True))
    assert a.issues == () and b.issues == () and b.version == (1, 1)
    ta, tb = published(a, values), published(b, values)
    assert ta.keys() == tb.keys()
    for key in ta:
        assert ta[key].translation == pytest.approx(tb[key].translation, abs=1e-12, rel=0)
        assert ta[key].rotation == pytest.approx(tb[key].rotation, abs=1e-12, rel=0), key


@settings(max_examples=max(10, EXAMPLES // 3), deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(trees())
def test_quaternion_trees_agree_with_pinocchio(case):
    """Where Pinocchio's urdfdom reads URDF 1.1 (cmeel-urdfdom >= 5.1), its world poses equal the publisher's."""
    pytest.importorskip("numpy")
    pin = pytest.importorskip("pinocchio")
    from urdfcheck.verify.compare import _urdf_read_by_pinocchio

    if _urdf_read_by_pinocchio() < (1, 1):
        pytest.skip("Pinocchio's urdfdom does not read URDF 1.1")
    joints, values = case
    xml = tree_xml(joints, True)
    model = model_from_string(xml)
    pm = pin.buildModelFromXML(xml)
    data = pm.createData()
    q = pin.neutral(pm)
    for jid in range(1, pm.njoints):
        v = values.get(pm.names[jid])
        jm = pm.joints[jid]
        if v is None:
            continue
        if jm.nq == 1:
            q[jm.idx_q] = v
        else:  # continuous: (cos, sin)
            q[jm.idx_q], q[jm.idx_q + 1] = math.cos(v), math.sin(v)
    pin.framesForwardKinematics(pm, data, q)
    world = link_poses(model, [values])
    for link, pose in world.items():
        fid = pm.getFrameId(link, pin.FrameType.BODY)
        assert pose[0] == pytest.approx(data.oMf[fid].homogeneous, abs=1e-9), link


# --- verify: a reference that cannot read URDF 1.1 is a documented delta, not a mismatch ---------------------------
def test_verify_documents_yourdfpy_ignoring_the_quaternion():
    pytest.importorskip("numpy")
    pytest.importorskip("yourdfpy")
    pytest.importorskip("pinocchio")
    from urdfcheck.verify import compare as V

    m = model_from_string(MODEL, "r.urdf")
    report = V.verify(m, 20, xml=MODEL, yourdfpy_samples=5, timeout=60)
    assert report.status == "pass", report.to_dict()
    (d,) = [d for d in report.deltas if d.code == "quaternion-origin"]
    assert d.peers == ("yourdfpy",) and d.excluded_links == ("arm",) and d.loc.line == 5
    assert report.peer("pinocchio").status == "ok" and "arm" in report.peer("pinocchio").links
    assert any(f.code == "V002" and "quat_xyzw" in f.message for f in report.findings())


def test_verify_skips_a_pinocchio_that_cannot_read_the_version(monkeypatch):
    pytest.importorskip("numpy")
    pytest.importorskip("pinocchio")  # verify builds Pinocchio's model before it compares versions
    from urdfcheck.verify import compare as V

    monkeypatch.setattr(V, "_urdf_read_by_pinocchio", lambda: (1, 0))
    m = model_from_string(MODEL, "r.urdf")
    report = V.verify(m, 5, xml=MODEL, peers=("pinocchio",), timeout=60)
    assert report.peer("pinocchio").status == "skipped"
    assert report.status != "fail" and not any(f.code == "V001" and "disagrees" in f.message
                                               for f in report.findings())
    assert [d.code for d in report.deltas] == ["urdf-version"]


# --- the wheel-geometry contract and the URDF writer use the quaternion --------------------------------------------
def _wheels(version: str, joint_rot: str, shape_rot: str):
    from urdfcheck.consumers.common import Value
    from urdfcheck.consumers.controllers import DriveSpec, JointUse
    from urdfcheck.core.findings import Location
    from urdfcheck.rules.contracts.wheels import check_drive

    def wheel(name, y):
        return (f'<link name="{name}_link"><collision><origin {shape_rot}/><geometry><cylinder radius="0.1" '
                f'length="0.05"/></geometry></collision></link><joint name="{name}_joint" type="continuous">'
                f'<parent link="base_link"/><child link="{name}_link"/><origin xyz="0 {y} 0" {joint_rot}/>'
                f'<axis xyz="0 0 1"/></joint>')

    m = model_from_string(f'<robot name="r" version="{version}"><link name="base_link"/>{wheel("left", 0.25)}'
                          f'{wheel("right", -0.25)}</robot>', "r.urdf")
    assert m.issues == ()
    loc = Location("d.yaml", 1)
    uses = lambda n, side: (JointUse(n, loc, "ddc", role=f"{side}_wheel"),)  # noqa: E731
    spec = DriveSpec("ddc", loc, uses("left_joint", "left"), uses("right_joint", "right"), loc, loc,
                     Value(0.5, loc), Value(0.1, loc), None, None, None)
    return sorted(p.code for p in check_drive(m, spec).problems())


def test_wheel_contract_uses_quaternion_origins():
    # wheel frames turned -90 degrees about x, written as a quaternion: both turn about base_link's y
    q = f'quat_xyzw="{-math.sqrt(0.5)!r} 0 0 {math.sqrt(0.5)!r}"'
    assert _wheels("1.1", q, 'rpy="0 0 0"') == []
    assert _wheels("1.0", 'rpy="-1.5707963267948966 0 0"', 'rpy="0 0 0"') == []
    # a cylinder lying the wrong way, written as a quaternion (90 degrees about x again): C011
    assert "C011" in _wheels("1.1", q, q)


def test_model_to_urdf_writes_the_quaternion_as_rpy():
    from urdfcheck.publisher.urdfxml import model_to_urdf

    m = model_from_string(MODEL)
    back = model_from_string(model_to_urdf(m))
    assert back.version == (1, 0) and back.issues == ()
    a = geometry.origin_matrix(m.joints["j"].origin)
    b = geometry.origin_matrix(back.joints["j"].origin)
    assert all(x == pytest.approx(y, abs=1e-12) for ra, rb in zip(a, b) for x, y in zip(ra, rb))


# --- differential: the real urdfdom (the cmeel-urdfdom wheel Pinocchio depends on), when it is 6.x ---------------
def _urdfdom6():
    import importlib.metadata as md

    try:
        dist = md.distribution("cmeel-urdfdom")
    except md.PackageNotFoundError:
        return None
    if int(dist.version.split(".")[0]) < 6:
        return None
    exe = dist.locate_file("cmeel.prefix/bin/check_urdf")
    return (str(exe), str(dist.locate_file("cmeel.prefix/lib"))) if os.path.exists(str(exe)) else None


def _urdfdom_accepts(xml: str, tmp_path) -> tuple[bool, str]:
    import subprocess

    exe, lib = URDFDOM6
    p = tmp_path / "d.urdf"
    p.write_text(xml)
    r = subprocess.run([exe, str(p)], capture_output=True, text=True, timeout=30,
                       env={**os.environ, "LD_LIBRARY_PATH": lib})
    return r.returncode == 0, r.stdout + r.stderr


URDFDOM6 = _urdfdom6()
needs_urdfdom6 = pytest.mark.skipif(URDFDOM6 is None, reason="urdfdom 6 (cmeel-urdfdom) is not installed")
VERSION_TEXTS = ["1.0", "1.1", "1.2", "1.3", "2.0", "0.9", "1", "1.0.0", "", "foo", "1,1", "1.0 ", " 1.0", "+1.0",
                 "1.00", "1.-0", "01.01", "1. 1", "1.010", "a.c", ".1", "1.", "2.-1", "-1.0", "-0.1", "0x1.1",
                 "1.1e0", "1.+1", " 1.1", "\t1.2"]


@needs_urdfdom6
@pytest.mark.parametrize("text", VERSION_TEXTS)
def test_version_reading_matches_urdfdom(text, tmp_path):
    xml = f'<robot name="r" version="{text}"><link name="a"/></robot>'
    ok, out = _urdfdom_accepts(xml, tmp_path)
    version, error = G.parse_version(text)
    assert ok == (version in G.VERSIONS), (text, version, error, out)
    if error:
        assert error in out
    found = [i.code for i in model_from_string(xml).issues]
    assert found == []  # the version is the U007 check's (target dependent), not a build issue


@needs_urdfdom6
@pytest.mark.parametrize("origin,limit,rejected", [
    (f'quat_xyzw="{Q90}"', "", False),
    (f'rpy="0 0 1" quat_xyzw="{Q90}"', "", True),
    ('quat_xyzw="0 0 0 0"', "", False),
    ('quat_xyzw="0 0 nan 1"', "", True),
    ('quat_xyzw="0 0 1"', "", True),
    ("", 'acceleration="-1"', True),
    ("", 'jerk="0"', False),
    ("", 'deceleration="inf"', True),
])
def test_findings_that_say_urdfdom_refuses_match_urdfdom(origin, limit, rejected, tmp_path):
    xml = robot("1.2", f'xyz="0 0 0.1" {origin}', f'lower="-1" upper="1" effort="1" velocity="1" {limit}')
    ok, out = _urdfdom_accepts(xml, tmp_path)
    assert ok is not rejected, out
    found = codes(xml, tmp_path)
    errors = [c for c, fs in found.items() if any(f["severity"] == "error" for f in fs)]
    assert bool(errors) is rejected or origin == 'quat_xyzw="0 0 0 0"', found  # zero: loads, but an error


@needs_urdfdom6
@pytest.mark.parametrize("version,origin,limit,geometry", [
    ("1.0", f'quat_xyzw="{Q90}"', "", "box"),
    ("1.1", f'quat_xyzw="{Q90}"', "", "box"),
    ("1.1", "", 'acceleration="2"', "box"),
    ("1.2", "", 'acceleration="2" jerk="3"', "box"),
    (None, "", 'deceleration="2"', "box"),
    ("1.0", "", "", "capsule"),
    ("1.1", "", "", "capsule"),
])
def test_u008_exactly_where_urdfdom_ignores_a_newer_construct(version, origin, limit, geometry, tmp_path):
    shape = '<box size="1 1 1"/>' if geometry == "box" else '<capsule radius="0.1" length="0.5"/>'
    xml = robot(version, f'xyz="0 0 0.1" {origin}', f'lower="-1" upper="1" effort="1" velocity="1" {limit}')
    xml = xml.replace('<link name="arm"/>', f'<link name="arm"><visual><geometry>{shape}</geometry></visual></link>')
    ok, out = _urdfdom_accepts(xml, tmp_path)
    assert ok, out
    ignored = out.count("Ignoring")
    assert ignored == len([i for i in model_from_string(xml).issues if i.code == "U008"]), out


def _has_target_flag() -> bool:
    from urdfcheck.cli.main import build_parser

    ns, _ = build_parser(with_publish=False).parse_known_args(["lint", "x.urdf"])
    return hasattr(ns, "target")


def test_target_flag_humble_rejects_a_1_1_model(tmp_path):
    if not _has_target_flag():
        pytest.skip("lint has no --target flag yet")
    p = tmp_path / "r.urdf"
    p.write_text(MODEL)
    _, report = lint_json([str(p), "--target", "humble"], cwd=tmp_path)
    (f,) = [f for f in report["findings"] if f["code"] == "U007"]
    assert f["severity"] == "error" and "humble ships urdfdom 3.0" in f["message"]
    assert "robot_state_publisher does not start" in f["message"]
    _, report = lint_json([str(p), "--target", "rolling"], cwd=tmp_path)
    assert report["findings"] == []


def test_target_config_key(tmp_path):
    if not _has_target_flag():
        pytest.skip("no target setting yet")
    (tmp_path / "r.urdf").write_text(MODEL)
    (tmp_path / "urdfcheck.yaml").write_text("target: jazzy\n")
    code, out, err = run_cli(["lint", "--format", "json", "--config", "urdfcheck.yaml", "--trust-config",
                              str(tmp_path / "r.urdf")], cwd=tmp_path)
    assert code == 1, err
    assert [f["code"] for f in json.loads(out)["findings"]] == ["U007"]
    # found in the checkout, the target is the runner's to choose (issue 36): refused at its line
    code, out, err = run_cli(["lint", "--format", "json", str(tmp_path / "r.urdf")], cwd=tmp_path)
    assert code == 1, err
    assert [(f["code"], f["severity"]) for f in json.loads(out)["findings"]] == [("X018", "error")]


@needs_urdfdom6
@pytest.mark.parametrize("version,limit,code", [
    ("1.2", 'upper="1" effort="1" velocity="1"', "J002"),
    ("1.2", 'lower="1" upper="-1" effort="1" velocity="1"', "J003"),
    ("1.2", 'lower="-1" upper="1" effort="-1" velocity="1"', "J004"),
    ("1.2", 'lower="-1" upper="1" velocity="-2"', "J004"),
    ("1.1", 'lower="-1" upper="1" velocity="1"', "U006"),
    ("1.2", 'lower="-1" upper="1"', None),
    ("1.0", 'upper="1" effort="1" velocity="1"', None),
])
def test_1_2_limit_errors_match_urdfdom(version, limit, code, tmp_path):
    xml = robot(version, 'xyz="0 0 0.1"', limit)
    ok, out = _urdfdom_accepts(xml, tmp_path)
    assert ok is (code is None), out
    errors = sorted(c for c, fs in codes(xml, tmp_path).items() if any(f["severity"] == "error" for f in fs))
    assert errors == ([code] if code else []), errors
