"""The consumer profiles against the real consumers (issue 40): every seeded mutant and its clean twin loaded into
each consumer installable here (MuJoCo, Pinocchio, PyBullet, sdformat's `ign sdf`, kdl_parser through a C++ probe),
compared with the prediction on each point; and the rules the measurements changed, one by one."""
import json

import differential
import profile_mutants
import pytest
from conftest import lint_json, run_cli


@pytest.fixture(scope="module")
def table(tmp_path_factory):
    if not differential.installed():
        pytest.skip("no consumer installed (mujoco, pinocchio, pybullet, ign sdf, kdl_parser)")
    folder = tmp_path_factory.mktemp("mutants")
    return differential.run(profile_mutants.write(str(folder)))


@pytest.mark.parametrize("consumer", differential.CONSUMERS)
def test_mutants_and_twins_agree_on_every_point(table, consumer):
    if consumer not in table:
        pytest.skip(f"{consumer} not installed here")
    row = table[consumer]
    assert not row["disagree"], row["disagree"]
    assert len(row["agree"]) == 2 * len(profile_mutants.MUTANTS)


def _lint(tmp_path, text, profiles, sdformat=None):
    """The findings; with `sdformat`, the Gazebo rules predict for that version (the one measured here: 12.3)."""
    p = tmp_path / "robot.urdf"
    p.write_text(text)
    if sdformat is None:
        _, report = lint_json([str(p), "--profile", profiles], cwd=tmp_path)
        return report["findings"]
    cfg = tmp_path / f"sdformat-{sdformat}.yaml"
    cfg.write_text("rules:\n" + "".join(f"  {c}: {{sdformat: '{sdformat}'}}\n" for c in ("P011", "P012", "P052")))
    _, out, _ = run_cli(["lint", "--format", "json", str(p), "--profile", profiles, "--config", str(cfg),
                         "--trust-config"], cwd=tmp_path)
    return json.loads(out)["findings"]


M = profile_mutants.MUTANTS


def test_gazebo_refuses_a_model_whose_root_has_no_inertial(tmp_path):
    bad, good = M["root without inertial, moving child"]
    hits = [f for f in _lint(tmp_path, bad, "gazebo") if f["code"] == "P012"]
    assert hits and hits[0]["severity"] == "error" and "no link left" in hits[0]["message"]
    assert not [f for f in _lint(tmp_path, good, "gazebo") if f["code"] == "P012"]
    # base_footprint without <inertial> above a massive base_link: lumped, kept
    assert not [f for f in _lint(tmp_path, M["root without inertial, fixed child with mass"][0], "gazebo")
                if f["code"] in ("P011", "P012")]


def test_gazebo_refuses_floating_and_planar_joints_and_negative_mass(tmp_path):
    for label in ("floating joint", "planar joint", "negative mass"):
        assert [f for f in _lint(tmp_path, M[label][0], "gazebo", "12.3") if f["code"] == "P012"], label
        assert not [f for f in _lint(tmp_path, M[label][1], "gazebo", "12.3") if f["code"] == "P012"], label
    # from sdformat 12.7.2 on (pull request 1238) a negative mass drops the link instead (P011)
    newer = tmp_path / "newer"
    newer.mkdir()
    (newer / "urdfcheck.yaml").write_text("rules:\n  P011: {sdformat: '12.7.2'}\n  P012: {sdformat: '12.7.2'}\n")
    p = newer / "robot.urdf"
    p.write_text(M["negative mass"][0])
    _, out, _ = run_cli(["lint", "--format", "json", str(p), "--profile", "gazebo", "--config",
                         str(newer / "urdfcheck.yaml"), "--trust-config"], cwd=newer)
    codes = {f["code"] for f in json.loads(out)["findings"]}
    assert "P011" in codes and "P012" not in codes


def test_p010_does_not_lump_a_link_fixed_to_world(tmp_path):
    assert not [f for f in _lint(tmp_path, M["fixed to world"][0], "gazebo") if f["code"] == "P010"]
    hits = [f for f in _lint(tmp_path, M["fixed leaf without inertial"][0], "gazebo") if f["code"] == "P010"]
    assert hits and "'tool0'" in hits[0]["message"]


def test_mujoco_refuses_a_nested_floating_joint_and_a_self_mimic(tmp_path):
    for label in ("floating joint", "self mimic"):
        hits = [f for f in _lint(tmp_path, M[label][0], "mujoco") if f["code"] == "P007"]
        assert hits and hits[0]["severity"] == "error", label
        assert not [f for f in _lint(tmp_path, M[label][1], "mujoco") if f["code"] == "P007"]


def test_mimic_ignored_names_each_consumer_that_ignores_it(tmp_path):
    hits = [f for f in _lint(tmp_path, M["mimic"][0], "pybullet,gazebo,mujoco") if f["code"] == "P052"]
    assert hits and hits[0]["profiles"] == ["pybullet", "gazebo"]
    assert not [f for f in _lint(tmp_path, M["mimic"][1], "pybullet,gazebo") if f["code"] == "P052"]


def test_pybullet_gives_the_root_1_kg_and_makes_floating_fixed(tmp_path):
    hits = [f for f in _lint(tmp_path, M["root without inertial, moving child"][0], "pybullet")
            if f["code"] == "P050"]
    assert hits and "'base_link'" in hits[0]["message"]
    hits = [f for f in _lint(tmp_path, M["floating joint"][0], "pybullet") if f["code"] == "P030"]
    assert hits and hits[0]["profile"] == "pybullet"


def test_a_defect_every_consumer_refuses_names_every_profile_asked(tmp_path):
    hits = [f for f in _lint(tmp_path, M["revolute without limit"][0], "gazebo,kdl,pybullet,mujoco")
            if f["code"] == "J002"]
    assert hits and hits[0]["profiles"] == ["gazebo", "kdl", "pybullet"]
    hits = [f for f in _lint(tmp_path, M["zero axis"][0], "gazebo,kdl,mujoco") if f["code"] == "J006"]
    assert hits and hits[0]["profiles"] == ["gazebo", "mujoco"]


def test_p051_skips_an_inertia_equal_to_bullets_own(tmp_path):
    # a 0.1 m box of 1 kg: Bullet computes 1/12 * (0.01 + 0.01) = 0.0016667 on each axis (measured, PyBullet 3.2)
    box = '<collision><geometry><box size="0.1 0.1 0.1"/></geometry></collision>'
    same = profile_mutants.inertial(a="0.00166667", b="0.00166667", c="0.00166667") + box
    other = profile_mutants.inertial() + box
    text = profile_mutants.arm(base=same, upper=same, fore=same)
    assert not [f for f in _lint(tmp_path, text, "pybullet") if f["code"] == "P051"]
    text = profile_mutants.arm(base=same, upper=other, fore=same)
    hits = [f for f in _lint(tmp_path, text, "pybullet") if f["code"] == "P051"]
    assert hits and "'upper'" in hits[0]["message"] and "'fore'" not in hits[0]["message"]


def test_changes_carry_the_profile_of_the_consumer_that_makes_them(tmp_path):
    # a negative effort: Pinocchio refuses (P040), Gazebo reads no limit (J004 carries gazebo)
    hits = [f for f in _lint(tmp_path, M["negative effort"][0], "gazebo") if f["code"] == "J004"]
    assert hits and hits[0]["profile"] == "gazebo"
    # inverted limits: PyBullet has no limit at all (J003 carries pybullet), Gazebo is not named
    hits = [f for f in _lint(tmp_path, M["inverted limits"][0], "gazebo,pybullet") if f["code"] == "J003"]
    assert hits and hits[0]["profile"] == "pybullet" and "profiles" not in hits[0]


def test_gazebo_extension_joint_naming_a_lumped_link_is_refused(tmp_path):
    bad, good = M["gazebo joint naming a lumped link"]
    hits = [f for f in _lint(tmp_path, bad, "gazebo") if f["code"] == "P012"]
    assert hits and "'palm'" in hits[0]["message"] and "lumped" in hits[0]["message"]
    assert not [f for f in _lint(tmp_path, good, "gazebo") if f["code"] == "P012"]


def test_gazebo_reads_a_mass_within_1e_6_of_zero_as_none(tmp_path):
    bad, good = M["mass 1e-6 (sdformat's zero)"]
    hits = [f for f in _lint(tmp_path, bad, "gazebo", "12.3") if f["code"] == "P011"]
    assert hits and "'upper'" in hits[0]["message"] and "'fore'" in hits[0]["message"]
    assert not [f for f in _lint(tmp_path, good, "gazebo", "12.3") if f["code"] == "P011"]
    # a massless force-torque link fixed between two moving links takes everything below it
    bad, good = M["massless link fixed between moving links"]
    hits = [f for f in _lint(tmp_path, bad, "gazebo", "12.3") if f["code"] == "P011"]
    assert hits and "'ft_sensor'" in hits[0]["message"] and "'fore'" in hits[0]["message"]
    assert not [f for f in _lint(tmp_path, good, "gazebo", "12.3") if f["code"] == "P011"]


def test_newer_sdformat_keeps_a_massless_link_on_a_reduced_fixed_joint(tmp_path):
    # read from sdformat's source (pull request 1238, 12.7.2 and 13.5 on): the massless sensor link is lumped and
    # the thigh below it kept; 12.3 (measured) drops it all
    bad = M["massless link fixed between moving links"][0]
    (tmp_path / "robot.urdf").write_text(bad)
    for version, dropped in (("12.3", True), ("12.7.2", False), ("14.1", False), ("13.4", True)):
        cfg = tmp_path / f"{version}.yaml"
        cfg.write_text(f"rules:\n  P011: {{sdformat: '{version}'}}\n")
        _, out, _ = run_cli(["lint", "--format", "json", str(tmp_path / "robot.urdf"), "--profile", "gazebo",
                             "--config", str(cfg), "--trust-config"], cwd=tmp_path)
        hits = [f for f in json.loads(out)["findings"] if f["code"] == "P011"]
        assert bool(hits) == dropped, version


def test_sdformat_auto_follows_the_target_distribution(tmp_path):
    # Humble's Fortress reads with sdformat 12.8 (<mimic> ignored), Jazzy's Harmonic with 14.5 (<mimic> kept)
    p = tmp_path / "robot.urdf"
    p.write_text(M["mimic"][0])
    for target, named in (("humble", True), ("jazzy", False)):
        _, report = lint_json([str(p), "--profile", "gazebo", "--target", target], cwd=tmp_path)
        assert bool([f for f in report["findings"] if f["code"] == "P052"]) == named, target
