"""Consumer profiles (issue 25): --profile / profiles:, the JSON profile field, info without a profile, and the
profile predictions against the real consumers on a sample (the whole set: tests/consumers_diff.py --full)."""
import json
import textwrap

import pytest
from conftest import lint_json, run_cli

import urdfcheck

INR = '<inertial><mass value="1"/><inertia ixx="0.01" ixy="0" ixz="0" iyy="0.01" iyz="0" izz="0.01"/></inertial>'


def arm(child: str = "", limit: str = '<limit lower="-1" upper="1" effort="10" velocity="1"/>', extra: str = ""):
    return textwrap.dedent(f"""\
    <robot name="r">
      <link name="base_link">{INR}</link>
      <link name="arm">{child}</link>
      <joint name="shoulder" type="revolute">
        <parent link="base_link"/><child link="arm"/><axis xyz="0 0 1"/>
        {limit}
      </joint>{extra}
    </robot>
    """)


def _write(tmp_path, text):
    p = tmp_path / "robot.urdf"
    p.write_text(text)
    return p


def test_profile_turns_rule_into_error_with_profile_field(tmp_path):
    p = _write(tmp_path, arm(""))
    code, report = lint_json([str(p), "--profile", "mujoco"], cwd=tmp_path)
    hits = [f for f in report["findings"] if f["code"] == "P001"]
    assert code == 1 and hits and hits[0]["severity"] == "error" and hits[0]["profile"] == "mujoco"
    assert "MuJoCo" in hits[0]["message"] and "mjMINVAL" in hits[0]["message"]


def test_without_profile_a_rejection_stays_visible_as_info(tmp_path):
    p = _write(tmp_path, arm(""))
    code, report = lint_json([str(p)], cwd=tmp_path)
    hits = [f for f in report["findings"] if f["code"] == "P001"]
    assert hits and hits[0]["severity"] == "info" and "--profile mujoco" in hits[0]["message"]


def test_effort_zero_without_actuator_names_gazebo_and_isaac(tmp_path):
    p = _write(tmp_path, arm(INR, limit='<limit lower="-1" upper="1" effort="0" velocity="1"/>'))
    _, report = lint_json([str(p)], cwd=tmp_path)
    hit = [f for f in report["findings"] if f["code"] == "P013"]
    assert hit and hit[0]["severity"] == "info"
    assert "Gazebo" in hit[0]["message"] and "Isaac" in hit[0]["message"]
    # an actuated joint is J004's subject (ROS-Industrial vs simulation): no P013
    trans = ('<transmission name="t"><type>transmission_interface/SimpleTransmission</type><joint name="shoulder">'
             '<hardwareInterface>hardware_interface/EffortJointInterface</hardwareInterface></joint></transmission>')
    p = _write(tmp_path, arm(INR, limit='<limit lower="-1" upper="1" effort="0" velocity="1"/>', extra=trans))
    _, report = lint_json([str(p)], cwd=tmp_path)
    assert not [f for f in report["findings"] if f["code"] == "P013"]


def test_profile_annotates_general_rules(tmp_path):
    p = _write(tmp_path, arm(INR).replace('<axis xyz="0 0 1"/>', '<axis xyz="0 0 0"/>'))
    _, report = lint_json([str(p), "--profile", "mujoco"], cwd=tmp_path)
    assert [f for f in report["findings"] if f["code"] == "J006" and f.get("profile") == "mujoco"]
    _, report = lint_json([str(p)], cwd=tmp_path)
    assert not [f for f in report["findings"] if "profile" in f and f["code"] == "J006"]


def test_profile_only_rules_are_silent_without_profile(tmp_path):
    p = _write(tmp_path, arm(INR, limit='<limit lower="-1" upper="1" effort="-10" velocity="1"/>'))
    _, report = lint_json([str(p)], cwd=tmp_path)
    assert not [f for f in report["findings"] if f["code"] == "P040"]
    assert [f for f in report["findings"] if f["code"] == "J004"]
    _, report = lint_json([str(p), "--profile", "pinocchio,mujoco"], cwd=tmp_path)
    assert [f for f in report["findings"] if f["code"] == "P040" and f["profile"] == "pinocchio"]


def test_config_key_and_api(tmp_path):
    (tmp_path / "urdfcheck.yaml").write_text("profiles: [mujoco]\n")
    _write(tmp_path, arm(""))
    res = urdfcheck.lint([str(tmp_path / "robot.urdf")], config=str(tmp_path / "urdfcheck.yaml"))
    assert [f for f in res.findings if f.code == "P001" and str(f.severity) == "error"]
    res = urdfcheck.lint([str(tmp_path / "robot.urdf")], config=str(tmp_path / "urdfcheck.yaml"), profiles=[])
    assert [f for f in res.findings if f.code == "P001" and str(f.severity) == "info"]


def test_unknown_profile_is_a_usage_error(tmp_path):
    _write(tmp_path, arm(INR))
    with pytest.raises(urdfcheck.UsageError, match="unknown profile 'mujoko'"):
        urdfcheck.lint([str(tmp_path / "robot.urdf")], profiles="mujoko")


def test_json_report_with_profile_matches_schema(tmp_path):
    jsonschema = pytest.importorskip("jsonschema")
    from importlib.resources import files

    p = _write(tmp_path, arm(""))
    _, report = lint_json([str(p), "--profile", "mujoco,gazebo,isaac,kdl,pinocchio,pybullet,moveit"], cwd=tmp_path,
                          flat=False)
    schema = json.loads(files("urdfcheck.schemas").joinpath("report.schema.json").read_text())
    jsonschema.validate(report, schema)
    assert {f.get("profile") for f in report["findings"]} >= {"mujoco", "gazebo", "pybullet"}


def test_differential_sample_mujoco_and_pinocchio():
    """A sample of models and mutants: every refusal predicted, no false alarm (the full run: docs/consumers.md)."""
    pytest.importorskip("mujoco")
    pytest.importorskip("pinocchio")
    import consumers_diff

    table = consumers_diff.measure(full=False)
    for consumer in ("mujoco", "pinocchio"):
        row = table[consumer]
        assert row["models"] >= 10
        assert not row["false_alarms"], row["false_alarms"]
        assert not row["missed"], row["missed"]


V11 = ('<robot name="r" version="1.1">\n  <link name="base_link"/>\n  <link name="tool"/>\n'
       '  <joint name="j" type="fixed">\n    <origin xyz="0 0 0.1" quat_xyzw="0 0 0.7071068 0.7071068"/>\n'
       '    <parent link="base_link"/><child link="tool"/>\n  </joint>\n</robot>\n')


def test_default_target_is_humble_and_says_why(tmp_path):
    p = tmp_path / "r.urdf"
    p.write_text(V11)
    _, report = lint_json([str(p), "--select", "U007"], cwd=tmp_path)
    (f,) = report["findings"]
    assert "humble ships urdfdom 3.0" in f["message"] and "oldest supported ROS 2 LTS" in f["message"]


@pytest.mark.parametrize("name,text,expect", [
    (".github/workflows/ci.yml", "jobs:\n  t:\n    strategy:\n      matrix:\n        ROS_DISTRO: [rolling, jazzy]\n",
     "jazzy"),
    ("Dockerfile", "FROM ros:kilted-ros-base\nRUN true\n", "kilted"),
    ("deps.repos", "repositories:\n  x:\n    type: git\n    version: rolling\n", "rolling"),
    (".git/HEAD", "ref: refs/heads/jazzy-devel\n", "jazzy"),
])
def test_target_read_from_the_workspace(tmp_path, name, text, expect):
    (tmp_path / ".git").mkdir()
    f = tmp_path / name
    f.parent.mkdir(parents=True, exist_ok=True)
    f.write_text(text)
    (tmp_path / "pkg" / "urdf").mkdir(parents=True)
    (tmp_path / "pkg" / "urdf" / "r.urdf").write_text(V11)
    code, out, _ = run_cli(["lint", "--list", "pkg/urdf/r.urdf"], cwd=tmp_path)
    assert code == 0 and f"ROS distribution: {expect} (assumed: {expect} named in {name}" in out
    _, report = lint_json(["pkg/urdf/r.urdf", "--select", "U007"], cwd=tmp_path)
    assert bool(report["findings"]) == (expect != "rolling")


def _repeated_cases():
    """One model per (scope, element) of P006's table, that element written twice, and one with none."""
    from urdfcheck.rules.checks.profiles.mujoco import _ONCE

    parts = {
        "joint": ('<joint name="j" type="revolute"><parent link="a"/><child link="b"/><axis xyz="0 0 1"/>'
                  '<dynamics damping="0.1"/><limit lower="-1" upper="1" effort="1" velocity="1"/><origin/></joint>'),
        "inertial": f'<inertial><mass value="1"/>{INR[INR.index("<inertia "):INR.index("</inertial>")]}<origin/>'
                    '</inertial>',
        "collision": '<collision><geometry><box size="1 1 1"/></geometry><origin/></collision>',
        "visual": '<visual><geometry><box size="1 1 1"/></geometry><material name="m"/></visual>',
    }

    def robot(p, extra=""):
        return (f'<robot name="r"><link name="a">{p["inertial"]}{extra}{p["collision"]}{p["visual"]}</link>'
                f'<link name="b">{p["inertial"]}</link>{p["joint"]}</robot>')

    def twice(text, tag):  # the first <tag .../> or <tag>...</tag> written twice
        import re

        start = re.search(rf"<{tag}[\s/>]", text).start()
        close = text.index(">", start)
        end = close + 1 if text[close - 1] == "/" else text.index(f"</{tag}>", start) + len(tag) + 3
        return text[:end] + text[start:end] + text[end:]

    yield "none", robot(parts), False
    yield "link/inertial", robot(parts, extra=parts["inertial"]), True
    for scope, names in _ONCE.items():
        for name in names:
            where = "collision" if scope == "geometry" else scope
            if scope == "geometry" and name != "box":
                continue  # one geometry case: the model's geometry is a box
            yield f"{scope}/{name}", robot({**parts, where: twice(parts[where], name)}), True


@pytest.mark.parametrize("label, text, repeated", list(_repeated_cases()))
def test_every_repeated_element_mujoco_refuses_is_found(tmp_path, label, text, repeated):
    """P006 reads the repeats the model builder noted: every (scope, element) of MuJoCo's table, and nothing in a
    model without one."""
    _, report = lint_json([str(_write(tmp_path, text)), "--select", "P006"], cwd=tmp_path)
    found = [f for f in report["findings"] if f["code"] == "P006"]
    assert bool(found) == repeated, (label, found)


def test_the_quick_mass_bound_never_passes_a_body_mujoco_refuses():
    """P001 skips the eigenvalues of a link when Gershgorin's bound already clears mjMINVAL: wherever the bound
    says so, the exact smallest principal moment says so too."""
    from hypothesis import given, settings
    from hypothesis import strategies as st

    from urdfcheck.model.robot import Inertial, Link
    from urdfcheck.rules.checks.inertial import principal_moments
    from urdfcheck.rules.checks.profiles.mujoco import MJMINVAL, _surely_massive

    scale = st.sampled_from([1e-18, 1e-15, 1e-9, 1e-3, 1.0, 1e3])
    value = st.floats(-1.0, 1.0, allow_nan=False)

    @settings(max_examples=400, deadline=None)
    @given(scale, st.tuples(*[value] * 6), st.floats(0.0, 10.0))
    def check(k, moments, mass):
        xx, xy, xz, yy, yz, zz = (k * v for v in moments)
        inertia = (abs(xx), xy, xz, abs(yy), yz, abs(zz))
        link = Link("l", None, Inertial(None, None, mass, None, inertia, None), (), ())
        if _surely_massive(link):
            assert mass >= MJMINVAL and principal_moments(inertia)[0] >= MJMINVAL * (1 - 1e-9)

    check()
