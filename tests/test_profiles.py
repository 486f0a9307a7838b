"""Consumer profiles (issue 25): --profile / profiles:, the JSON profile field, info without a profile, and the
profile predictions against the real consumers on a sample (the whole set: tests/consumers_diff.py --full)."""
import json
import textwrap

import pytest
from conftest import lint_json

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
