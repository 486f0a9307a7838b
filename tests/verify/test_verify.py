"""urdfcheck.verify.compare: publisher vs Pinocchio / yourdfpy, deltas, and peers that crash, run out of memory
or hang."""
import math
import os
import signal
import time

import pytest

np = pytest.importorskip("numpy")

from conftest import run_cli  # noqa: E402

from urdfcheck.core.findings import Severity  # noqa: E402
from urdfcheck.model.build import model_from_string  # noqa: E402
from urdfcheck.verify import compare as V  # noqa: E402

pytest.importorskip("pinocchio")

ARM = """<robot name="arm">
  <link name="base"/><link name="l1"/><link name="l2"/><link name="l3"/><link name="tool"/><link name="m"/>
  <joint name="j1" type="revolute"><parent link="base"/><child link="l1"/><origin xyz="0 0 0.5" rpy="0.1 0 0"/>
    <axis xyz="0 0 1"/><limit lower="-3" upper="3" effort="1" velocity="1"/></joint>
  <joint name="j2" type="continuous"><parent link="l1"/><child link="l2"/><origin xyz="0.1 0 0" rpy="0 1.2 0"/>
    <axis xyz="0 2 1"/></joint>
  <joint name="j3" type="prismatic"><parent link="l2"/><child link="l3"/><axis xyz="1 0 0"/>
    <limit lower="0" upper="1" effort="1" velocity="1"/></joint>
  <joint name="tool_joint" type="fixed"><parent link="l3"/><child link="tool"/><origin xyz="0 0 0.2"/></joint>
  <joint name="finger" type="prismatic"><parent link="tool"/><child link="m"/><axis xyz="0 1 0"/>
    <limit lower="0" upper="0.1" effort="1" velocity="1"/><mimic joint="j3" multiplier="-0.5" offset="0.01"/></joint>
</robot>"""

SPECIAL = """<robot name="special">
  <link name="base"/><link name="p"/><link name="f"/><link name="f2"/><link name="z"/><link name="z2"/>
  <link name="s"/><link name="a"/><link name="b"/><link name="c"/>
  <joint name="planar_j" type="planar"><parent link="base"/><child link="p"/><origin xyz="1 2 3"/>
    <axis xyz="0 0 1"/></joint>
  <joint name="float_j" type="floating"><parent link="base"/><child link="f"/><origin xyz="0 0 1"/></joint>
  <joint name="under_float" type="revolute"><parent link="f"/><child link="f2"/><origin xyz="0 0 1"/>
    <axis xyz="1 0 0"/><limit lower="-1" upper="1" effort="1" velocity="1"/></joint>
  <joint name="zero_rev" type="revolute"><parent link="base"/><child link="z"/><axis xyz="0 0 0"/>
    <limit lower="-1" upper="1" effort="1" velocity="1"/></joint>
  <joint name="below_zero" type="fixed"><parent link="z"/><child link="z2"/><origin xyz="1 0 0"/></joint>
  <joint name="slide" type="prismatic"><parent link="base"/><child link="s"/><axis xyz="0 3 0"/>
    <limit lower="-1" upper="1" effort="1" velocity="1"/></joint>
  <joint name="src" type="revolute"><parent link="base"/><child link="a"/><axis xyz="0 0 1"/>
    <limit lower="-1" upper="1" effort="1" velocity="1"/></joint>
  <joint name="b_follow" type="revolute"><parent link="a"/><child link="b"/><axis xyz="0 0 1"/>
    <limit lower="-1" upper="1" effort="1" velocity="1"/><mimic joint="src" multiplier="2"/></joint>
  <joint name="a_follow" type="revolute"><parent link="b"/><child link="c"/><axis xyz="0 0 1"/>
    <limit lower="-1" upper="1" effort="1" velocity="1"/><mimic joint="b_follow" multiplier="1"/></joint>
</robot>"""


def test_sampling_inside_limits_and_continuous_beyond_pi():
    m = model_from_string(ARM)
    names, q = V.sample_configurations(m, 2000, seed=3)
    assert names == ["j1", "j2", "j3"]  # mimic joints are not sampled
    assert q[:, 0].min() >= -3 and q[:, 0].max() <= 3
    assert q[:, 1].min() < -math.pi and q[:, 1].max() > math.pi
    assert q[:, 2].min() >= 0 and q[:, 2].max() <= 1
    assert np.array_equal(q, V.sample_configurations(m, 2000, seed=3)[1])  # seeded


def test_verify_passes_and_reports_per_link_errors():
    m = model_from_string(ARM)
    calls = []
    r = V.verify(m, n=200, seed=1, progress=lambda *a: calls.append(a))
    assert r.status == "pass" and r.passed, [(p.name, p.status, p.detail) for p in r.peers]
    assert [p.name for p in r.peers] == ["batch", "pinocchio", "yourdfpy"]
    for p in r.peers:
        assert p.status == "ok"
        assert set(p.links) == {"base", "l1", "l2", "l3", "tool", "m"}
        assert p.max_translation < 1e-12 and p.max_rotation < 1e-12
    assert r.peer("yourdfpy").configurations == 50  # sampled subset by default
    assert {c[0] for c in calls} >= {"publisher", "pinocchio", "yourdfpy"}
    assert [f.code for f in r.findings()] == []
    d = r.to_dict()
    assert d["status"] == "pass" and d["peers"][1]["compared_links"] == 6


def test_deltas_are_stated_and_excluded_links_named():
    m = model_from_string(SPECIAL)
    r = V.verify(m, n=100)
    assert r.status == "pass", [(p.name, p.status, p.detail) for p in r.peers]
    codes = {(d.code, d.joint) for d in r.deltas}
    assert {("planar", "planar_j"), ("floating", "float_j"), ("zero-axis", "zero_rev"),
            ("non-unit-prismatic-axis", "slide"), ("mimic-order", "a_follow"),
            ("yourdfpy-mimic", "a_follow")} <= codes
    pin_ex = r.peer("pinocchio").excluded
    assert set(pin_ex) == {"z", "z2", "c"}  # zero axis subtree and the unpublished mimic joint
    # yourdfpy: also the non-unit prismatic axis, and b_follow (its source comes after the floating joint in
    # yourdfpy's actuated list, so yourdfpy reads the wrong slot of its configuration vector)
    assert ("yourdfpy-mimic", "b_follow") in codes
    assert set(r.peer("yourdfpy").excluded) == {"z", "z2", "c", "s", "b"}
    # links under the floating joint are compared relative to its child
    assert "f2" in r.peer("pinocchio").links
    findings = r.findings()
    assert findings and all(f.code == "V002" and f.severity == Severity.INFO for f in findings)
    assert any(f.location.line for f in findings)


def test_a_real_disagreement_fails_with_v001():
    m = model_from_string(ARM)
    # the peers parse a document whose second joint sits 1 mm further along x
    other = ARM.replace('origin xyz="0.1 0 0" rpy="0 1.2 0"', 'origin xyz="0.101 0 0" rpy="0 1.2 0"')
    r = V.verify(m, n=20, xml=other)
    assert r.status == "fail" and not r.passed
    pin = r.peer("pinocchio")
    assert pin.status == "mismatch"
    assert {e.link for e in pin.failing()} == {"l2", "l3", "tool", "m"}
    assert pin.max_translation == pytest.approx(0.001, rel=1e-6)
    assert any(f.code == "V001" and "l2" in f.message for f in r.findings())


def test_axis_without_xyz_is_a_parser_delta():
    xml = """<robot name="r"><link name="a"/><link name="b"/><joint name="j" type="revolute"><parent link="a"/>
      <child link="b"/><axis/><limit lower="-1" upper="1" effort="1" velocity="1"/></joint></robot>"""
    r = V.verify(model_from_string(xml), n=20, xml=xml, peers=("pinocchio",))
    assert any(d.code == "axis-without-xyz" for d in r.deltas)
    assert any(d.code == "zero-axis" for d in r.deltas)
    # urdfcheck reads the zero axis urdfdom reads: the zero-axis subtree is excluded and stated, not a mismatch
    assert r.peer("pinocchio").status != "mismatch"


# --- peers that fail --------------------------------------------------------------------------------------------
def _crash(progress, *a):
    os.write(2, b"pinocchio: about to fall over\n")
    os.kill(os.getpid(), signal.SIGSEGV)


def _hog(progress, *a):
    blocks = []
    while True:
        blocks.append(np.ones(50_000_000))  # 400 MB each, far beyond the budget below


def _hang(progress, *a):
    time.sleep(60)


def _boom(progress, *a):
    raise RuntimeError("URDF parse error: joint 'x' has no parent")


@pytest.mark.parametrize("job,status,kwargs", [
    (_crash, "crashed", {}),
    (_hog, "out of memory", {"memory": 512 * 1024**2}),
    (_hang, "timed out", {"timeout": 1.0}),
    (_boom, "error", {}),
])
def test_failing_peer_is_reported_never_passed(monkeypatch, job, status, kwargs):
    monkeypatch.setattr(V, "_pinocchio_job", job)
    r = V.verify(model_from_string(ARM), n=10, peers=("pinocchio",), **kwargs)
    pin = r.peer("pinocchio")
    assert pin.status == status, (pin.status, pin.detail)
    assert r.status == "incomplete" and not r.passed
    assert any(f.code == "V001" and status in f.message for f in r.findings())
    if job is _crash:
        assert "about to fall over" in pin.stderr  # the child's C-level stderr is captured
        assert "SIGSEGV" in pin.detail
    if job is _boom:
        assert "no parent" in pin.detail


def test_real_pinocchio_out_of_memory_on_many_dof():
    n = 400  # createData grows with the cube of the DoF: GBs at this size
    parts = ['<robot name="chain">'] + [f'<link name="l{i}"/>' for i in range(n + 1)]
    for i in range(n):
        parts.append(f'<joint name="j{i}" type="revolute"><parent link="l{i}"/><child link="l{i + 1}"/>'
                     '<axis xyz="0 0 1"/><limit lower="-1" upper="1" effort="1" velocity="1"/></joint>')
    xml = "".join(parts) + "</robot>"
    m = model_from_string(xml)
    refused = V.verify(m, n=2, peers=("pinocchio",))
    assert refused.peer("pinocchio").status == "refused" and "400 DoF" in refused.peer("pinocchio").detail
    assert refused.status == "incomplete"
    r = V.verify(m, n=2, peers=("pinocchio",), max_dof=10_000, memory=768 * 1024**2, timeout=60)
    assert r.peer("pinocchio").status in ("out of memory", "crashed")
    assert r.status == "incomplete"


def test_depth_cap_refuses_pinocchio():
    n = 30
    parts = ['<robot name="deep">'] + [f'<link name="l{i}"/>' for i in range(n + 1)]
    parts += [f'<joint name="j{i}" type="fixed"><parent link="l{i}"/><child link="l{i + 1}"/></joint>'
              for i in range(n)]
    r = V.verify(model_from_string("".join(parts) + "</robot>"), n=2, peers=("pinocchio",), max_depth=10)
    assert r.peer("pinocchio").status == "refused" and "depth 30" in r.peer("pinocchio").detail


# --- CLI --------------------------------------------------------------------------------------------------------
def test_cli_verify_exit_codes(tmp_path):
    good = tmp_path / "arm.urdf"
    good.write_text(ARM)
    code, out, err = run_cli(["verify", good, "-n", "50", "--no-yourdfpy"])
    assert code == 0, (out, err)
    assert "pinocchio" in out and "result: pass" in out
    code, out, err = run_cli(["verify", good, "-n", "50", "--format", "json"])
    import json

    data = json.loads(out)
    assert code == 0 and data["status"] == "pass" and len(data["peers"]) == 3
    bad = tmp_path / "empty_axis.urdf"
    bad.write_text("""<robot name="r"><link name="a"/><link name="b"/><joint name="j" type="revolute">
      <parent link="a"/><child link="b"/><axis/><limit lower="-1" upper="1" effort="1" velocity="1"/></joint>
      </robot>""")
    code, out, err = run_cli(["verify", bad, "-n", "20"])
    # urdfcheck reads <axis/> as urdfdom does (zero): the subtree is excluded and the delta stated
    assert code == 0 and "has no xyz" in out and "zero axis" in out


def test_cli_verify_exits_1_on_a_disagreement(tmp_path, monkeypatch):
    import urdfcheck.verify.compare as verify_mod

    good = tmp_path / "arm.urdf"
    good.write_text(ARM)
    real = verify_mod.verify
    shifted = ARM.replace('origin xyz="0.1 0 0" rpy="0 1.2 0"', 'origin xyz="0.101 0 0" rpy="0 1.2 0"')
    # the peers read a document whose joint sits 1 mm off: what a parser disagreement looks like
    monkeypatch.setattr(verify_mod, "verify", lambda model, *a, xml=None, **k: real(model, *a, xml=shifted, **k))
    code, out, err = run_cli(["verify", good, "-n", "20", "--no-yourdfpy"])
    assert code == 1 and "mismatch" in out, (out, err)
    code, out, err = run_cli(["verify", tmp_path / "missing.urdf"])
    assert code == 2
    broken = tmp_path / "broken.urdf"
    broken.write_text("<robot name='r'><link name='a'>")
    code, out, err = run_cli(["verify", broken])
    assert code == 1 and "X001" in err


def test_pr2_from_the_corpus(corpus):
    path = corpus / "ros+urdf" / "urdf" / "test" / "pr2_desc.urdf"
    if not path.is_file():
        pytest.skip("pr2_desc.urdf not in the corpus")
    xml = path.read_text()
    r = V.verify(model_from_string(xml, str(path)), n=300, xml=xml)
    assert r.status == "pass", [(p.name, p.status, p.detail) for p in r.peers]
    assert len(r.peer("pinocchio").links) == 80
