"""I rules: incomplete inertials, masses, inertia tensors, the root link's inertia."""
from __future__ import annotations

import itertools
import math
import random

import pytest

from urdfcheck.core.findings import Severity
from urdfcheck.model.build import model_from_string
from urdfcheck.rules import engine
from urdfcheck.rules.checks.inertial import principal_moments


def run(xml: str, select=("I",), options=None):
    model = model_from_string(xml, "robot.urdf")
    ctx = engine.Context(selection=engine.Selection(select=tuple(select), options=dict(options or {})))
    return engine.run_checks(model, ctx)


def codes(findings):
    return sorted(f.code for f in findings)


def inertial(mass='<mass value="1.0"/>', inertia='ixx="0.01" ixy="0" ixz="0" iyy="0.01" iyz="0" izz="0.01"'):
    tensor = f"<inertia {inertia}/>" if inertia is not None else ""
    return f"<inertial>{mass or ''}{tensor}</inertial>"


def robot(link_body: str, joint_type="revolute", extra="") -> str:
    limit = '<limit lower="-1" upper="1" effort="1" velocity="1"/>' if joint_type in ("revolute", "prismatic") else ""
    return f"""<robot name="r">
  <link name="base_link"/>
  <link name="arm">{link_body}</link>
  <joint name="j" type="{joint_type}">
    <parent link="base_link"/><child link="arm"/><axis xyz="0 0 1"/>{limit}
  </joint>{extra}
</robot>"""


# --- eigenvalues -------------------------------------------------------------------------------------

def _rotate(diag, rot):
    """R diag(d) R^T as (ixx, ixy, ixz, iyy, iyz, izz)."""
    m = [[sum(rot[i][k] * diag[k] * rot[j][k] for k in range(3)) for j in range(3)] for i in range(3)]
    return (m[0][0], m[0][1], m[0][2], m[1][1], m[1][2], m[2][2])


def _random_rotation(rng):
    from urdfcheck.core.geometry import rpy_matrix

    return rpy_matrix(rng.uniform(-math.pi, math.pi), rng.uniform(-1.5, 1.5), rng.uniform(-math.pi, math.pi))


def test_principal_moments_of_diagonal_tensor():
    assert principal_moments((3.0, 0, 0, 1.0, 0, 2.0)) == (1.0, 2.0, 3.0)


def test_principal_moments_recover_rotated_diagonal():
    rng = random.Random(7)
    for _ in range(200):
        d = sorted(rng.uniform(0.0, 2.0) for _ in range(3))
        got = principal_moments(_rotate(d, _random_rotation(rng)))
        for a, b in zip(got, d):
            assert a == pytest.approx(b, abs=1e-12)


def test_principal_moments_with_repeated_eigenvalues():
    got = principal_moments((1.0, 1.0, 1.0, 1.0, 1.0, 1.0))  # rank one: 0, 0, 3
    assert got[2] == pytest.approx(3.0)
    assert abs(got[0]) < 1e-12 and abs(got[1]) < 1e-12


# --- I001 --------------------------------------------------------------------------------------------

def test_i001_missing_mass():
    found = run(robot(inertial(mass=None)))
    assert codes(found) == ["I001"]
    assert "<mass>" in found[0].message and "visuals and collisions" in found[0].message
    assert found[0].location.line == 3


def test_i001_missing_inertia():
    found = run(robot(inertial(inertia=None)))
    assert codes(found) == ["I001"]
    assert "<inertia>" in found[0].message


def test_i001_missing_both():
    found = run(robot("<inertial/>"))
    assert codes(found) == ["I001"]
    assert "<mass> and <inertia>" in found[0].message


def test_i001_not_for_an_unreadable_mass_value():
    found = run(robot(inertial(mass='<mass value="heavy"/>')), select=("I", "U"))
    assert codes(found) == ["U005"]  # the U rule reports the value; the element is there


def test_i001_no_inertial_is_fine():
    assert run(robot("")) == []


# --- I002 --------------------------------------------------------------------------------------------

def test_i002_negative_mass():
    found = run(robot(inertial(mass='<mass value="-1.0"/>')))
    assert codes(found) == ["I002"]
    assert "negative" in found[0].message


def test_i002_zero_mass_with_tensor_is_an_error_even_on_a_fixed_joint():
    found = run(robot(inertial(mass='<mass value="0"/>'), joint_type="fixed"))
    assert codes(found) == ["I002"] and found[0].severity == Severity.ERROR
    assert "non-zero inertia" in found[0].message


def test_i002_massless_zero_tensor_on_moving_joint_is_an_error():
    zeros = 'ixx="0" ixy="0" ixz="0" iyy="0" iyz="0" izz="0"'
    found = run(robot(inertial(mass='<mass value="0"/>', inertia=zeros), joint_type="revolute"))
    assert codes(found) == ["I002"] and found[0].severity == Severity.ERROR
    assert "revolute joint 'j'" in found[0].message


def test_i002_massless_frame_on_fixed_joint_is_not_reported():
    zeros = 'ixx="0" ixy="0" ixz="0" iyy="0" iyz="0" izz="0"'
    assert run(robot(inertial(mass='<mass value="0"/>', inertia=zeros), joint_type="fixed")) == []


def test_i002_massless_root_is_not_reported():
    xml = ('<robot name="r"><link name="base_footprint"><inertial><mass value="0"/>'
           '<inertia ixx="0" ixy="0" ixz="0" iyy="0" iyz="0" izz="0"/></inertial></link></robot>')
    assert [f for f in run(xml) if f.code == "I002"] == []


# --- I003 --------------------------------------------------------------------------------------------

def test_i003_indefinite_tensor_with_healthy_diagonal():
    found = run(robot(inertial(inertia='ixx="0.01" ixy="0.02" ixz="0" iyy="0.01" iyz="0" izz="0.01"')))
    assert codes(found) == ["I003"]
    assert "-0.01" in found[0].message


def test_i003_negative_diagonal():
    found = run(robot(inertial(inertia='ixx="-0.01" ixy="0" ixz="0" iyy="0.01" iyz="0" izz="0.01"')))
    assert "I003" in codes(found)


def test_i003_point_mass_and_thin_rod_accepted_by_default():
    zeros = 'ixx="0" ixy="0" ixz="0" iyy="0" iyz="0" izz="0"'
    rod = 'ixx="0.01" ixy="0" ixz="0" iyy="0.01" iyz="0" izz="0"'
    assert run(robot(inertial(inertia=zeros))) == []
    assert run(robot(inertial(inertia=rod))) == []


def test_i003_singular_reported_when_not_allowed():
    rod = 'ixx="0.01" ixy="0" ixz="0" iyy="0.01" iyz="0" izz="0"'
    found = run(robot(inertial(inertia=rod)), options={"I003": {"allow_singular": False}})
    assert codes(found) == ["I003"] and "singular" in found[0].message


def test_i003_rounding_noise_is_tolerated():
    # a thin plate rotated by 30 degrees about z, printed with 6 significant digits
    d = (0.0, 0.02, 0.02)
    c, s = math.cos(math.pi / 6), math.sin(math.pi / 6)
    t = _rotate(d, ((c, -s, 0), (s, c, 0), (0, 0, 1)))
    text = " ".join(f'{k}="{v:.6g}"' for k, v in zip(("ixx", "ixy", "ixz", "iyy", "iyz", "izz"), t))
    assert run(robot(inertial(inertia=text))) == []


def test_i003_skips_tensor_with_unreadable_values():
    found = run(robot(inertial(inertia='ixx="a" ixy="0" ixz="0" iyy="1" iyz="0" izz="1"')), select=("I", "U"))
    assert codes(found) == ["U005"]


def test_i003_floating_point_noise_is_a_zero_tensor():
    # iCub's exporter writes point masses like this
    found = run(robot(inertial(inertia='ixx="1.10961e-18" ixy="5.42101e-20" ixz="-5.42101e-20" iyy="0" '
                                       'iyz="8.47033e-22" izz="0"')), select=("I003", "I004"))
    assert found == []


def test_placeholder_mass_links_are_skipped():
    placeholder = inertial(mass='<mass value="1e-6"/>',
                           inertia='ixx="1e-6" ixy="1e-6" ixz="1e-6" iyy="1e-6" iyz="1e-6" izz="1e-6"')
    assert run(robot(placeholder), select=("I003", "I004")) == []
    found = run(robot(placeholder), select=("I003", "I004"), options={"I004": {"min_mass": 0}})
    assert codes(found) == ["I004"]


# --- I004 --------------------------------------------------------------------------------------------

def test_i004_wheel_with_thin_ring_formula():
    found = run(robot(inertial(inertia='ixx="0.0040625" ixy="0" ixz="0" iyy="0.015" iyz="0" izz="0.0040625"')))
    assert codes(found) == ["I004"]
    assert "0.008125 < 0.015" in found[0].message


def test_i004_uses_principal_moments_not_the_raw_diagonal():
    # principal moments 1, 1, 3 (violates 1 + 1 >= 3), rotated so the diagonal alone (about 1.67 each) looks fine
    rot = ((1 / math.sqrt(3), 1 / math.sqrt(2), 1 / math.sqrt(6)),
           (1 / math.sqrt(3), -1 / math.sqrt(2), 1 / math.sqrt(6)),
           (1 / math.sqrt(3), 0.0, -2 / math.sqrt(6)))
    t = _rotate((3.0, 1.0, 1.0), rot)
    diag = (t[0], t[3], t[5])
    assert all(diag[i] + diag[j] >= diag[k] for i, j, k in itertools.permutations(range(3)))
    text = " ".join(f'{k}="{v!r}"' for k, v in zip(("ixx", "ixy", "ixz", "iyy", "iyz", "izz"), t))
    found = run(robot(inertial(inertia=text)))
    assert codes(found) == ["I004"] and "principal moments" in found[0].message


def test_i004_thin_disc_on_the_boundary_is_fine():
    # m r^2/4, m r^2/4, m r^2/2 printed with 6 digits: 2.08333e-4 + 2.08333e-4 < 4.16667e-4 in the last digit
    text = 'ixx="0.000208333" ixy="0" ixz="0" iyy="0.000208333" iyz="0" izz="0.000416667"'
    assert run(robot(inertial(inertia=text))) == []


def test_i004_not_reported_for_indefinite_tensor():
    found = run(robot(inertial(inertia='ixx="0.01" ixy="0.02" ixz="0" iyy="0.01" iyz="0" izz="0.01"')))
    assert codes(found) == ["I003"]


def test_i004_rank_one_placeholder_tensor():
    found = run(robot(inertial(inertia='ixx="0.001" ixy="0.001" ixz="0.001" iyy="0.001" iyz="0.001" izz="0.001"')))
    assert codes(found) == ["I004"]
    assert "principal moments 0, 0, 0.003" in found[0].message


# --- I005 --------------------------------------------------------------------------------------------

def test_i005_root_with_inertial():
    xml = f'<robot name="r"><link name="base_link">{inertial()}</link></robot>'
    found = run(xml)
    assert codes(found) == ["I005"] and found[0].severity == Severity.INFO
    assert "KDL" in found[0].message


def test_i005_not_for_massless_root():
    assert run(robot(inertial())) == []


def test_i005_not_with_several_roots():
    xml = f'<robot name="r"><link name="a">{inertial()}</link><link name="b">{inertial()}</link></robot>'
    assert run(xml) == []
