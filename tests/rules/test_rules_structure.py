"""S rules (structure): one tree, unique names. Everything goes through the real CLI (`conftest.lint_json`).

The split between the rules is part of the contract (one finding per mistake, see checks/structure.py):
S003 owns undefined links, S002 a model without any root, S005 cycles beside or below a root, S004 links with
two parents, S006 links no joint touches, S001 separate trees.
"""
from __future__ import annotations

import shutil
import subprocess
import textwrap

import pytest
from conftest import lint_json

CHECK_URDF = shutil.which("check_urdf") or "/usr/bin/check_urdf"


def lint(tmp_path, xml: str, name: str = "robot.urdf"):
    path = tmp_path / name
    path.write_text(textwrap.dedent(xml).lstrip(), encoding="utf-8")
    _, report = lint_json([path], cwd=tmp_path)
    return report["findings"]


def only(findings, prefix="S"):
    return [f for f in findings if f["code"].startswith(prefix)]


def codes(findings, prefix="S"):
    return sorted(f["code"] for f in only(findings, prefix))


def line_of(xml: str, marker: str, nth: int = 1) -> int:
    """1-based line of the nth line containing marker, in the dedented text written by `lint`."""
    seen = 0
    for i, line in enumerate(textwrap.dedent(xml).lstrip().splitlines(), 1):
        if marker in line:
            seen += 1
            if seen == nth:
                return i
    raise AssertionError(f"{marker!r} not in the test model")


def J(name, parent, child, jtype="fixed"):
    return (f'<joint name="{name}" type="{jtype}"><parent link="{parent}"/><child link="{child}"/></joint>')


def L(*names):
    return "\n".join(f'<link name="{n}"/>' for n in names)


def robot(*parts):
    return '<robot name="r">\n' + "\n".join(parts) + "\n</robot>\n"


# --- cycles and roots ---------------------------------------------------------------------------------


def test_cycle_beside_a_valid_root_is_one_s005(tmp_path):
    xml = robot(L("base_link", "arm", "b", "c"), J("arm_joint", "base_link", "arm"), J("j_bc", "b", "c"),
                J("j_cb", "c", "b"))
    f = lint(tmp_path, xml)
    assert codes(f) == ["S005"], f
    (hit,) = only(f)
    assert "b -> c -> b" in hit["message"] and "'j_bc', 'j_cb'" in hit["message"]
    assert "no root leads to these links" in hit["message"]
    assert hit["location"]["line"] == line_of(xml, 'name="j_cb"')  # the joint that closes the loop
    assert [r["line"] for r in hit["related"]] == [line_of(xml, 'name="j_bc"')]


def test_self_loop_beside_a_root_is_s005(tmp_path):
    xml = robot(L("base_link", "arm", "x"), J("arm_joint", "base_link", "arm"), J("loop", "x", "x"))
    f = lint(tmp_path, xml)
    assert codes(f) == ["S005"], f
    assert "'x' as both parent and child" in only(f)[0]["message"]


def test_self_loop_on_the_only_link_is_s002_not_s005(tmp_path):
    """fail_pr2_desc_parent_itself: check_urdf says 'No root link found'."""
    f = lint(tmp_path, robot(L("base_link"), J("j", "base_link", "base_link", "continuous")))
    assert codes(f) == ["S002"], f
    assert "makes link 'base_link' its own parent" in only(f)[0]["message"]


def test_cycle_through_everything_is_one_s002_naming_the_cycle(tmp_path):
    xml = robot(L("a", "b", "c"), J("j1", "a", "b"), J("j2", "b", "c"), J("j3", "c", "a"))
    f = lint(tmp_path, xml)
    assert codes(f) == ["S002"], f
    (hit,) = only(f)
    assert "a -> b -> c -> a" in hit["message"] and "No root link found" in hit["message"]
    assert hit["location"]["line"] == line_of(xml, 'name="j3"')
    assert len(hit["related"]) == 2


def test_two_disjoint_cycles_beside_a_root_are_two_findings(tmp_path):
    xml = robot(L("base_link", "a", "b", "c", "d"), J("a_b", "a", "b"), J("b_a", "b", "a"), J("c_d", "c", "d"),
                J("d_c", "d", "c"))
    f = lint(tmp_path, xml)
    assert codes(f) == ["S005", "S005"], f  # base_link touches no joint, but it is the only root: no S006


def test_cycle_the_root_leads_into(tmp_path):
    xml = robot(L("base_link", "a", "b"), J("j1", "base_link", "a"), J("j2", "a", "b"), J("j3", "b", "a"))
    f = lint(tmp_path, xml)
    assert codes(f) == ["S004", "S005"], f
    s005 = next(x for x in only(f) if x["code"] == "S005")
    assert "root leads into the loop" in s005["message"]


def test_interlocking_loops_are_reported_once(tmp_path):
    xml = robot(L("base_link", "a", "b", "c"), J("arm", "base_link", "a"), J("ab", "a", "b"), J("ba", "b", "a"),
                J("bc", "b", "c"), J("cb", "c", "b"))
    f = lint(tmp_path, xml)
    s005 = [x for x in only(f) if x["code"] == "S005"]
    assert len(s005) == 1, f
    assert "3 links in all" in s005[0]["message"] and "root leads into the loop" in s005[0]["message"]


# --- roots, trees, disconnected links -------------------------------------------------------------------


def test_two_separate_trees_is_one_s001_at_the_second_root(tmp_path):
    xml = robot(L("base_link", "arm", "laser_link", "laser_optical"), J("arm_joint", "base_link", "arm"),
                J("optical_joint", "laser_link", "laser_optical"))
    f = lint(tmp_path, xml)
    assert codes(f) == ["S001"], f
    (hit,) = only(f)
    assert "'base_link' (2 links), 'laser_link' (2 links)" in hit["message"]
    assert hit["location"]["line"] == line_of(xml, 'name="laser_link"')
    assert [r["line"] for r in hit["related"]] == [line_of(xml, 'name="base_link"')]


def test_three_trees_name_every_root(tmp_path):
    xml = robot(L("a", "a2", "b", "b2", "c", "c2"), J("ja", "a", "a2"), J("jb", "b", "b2"), J("jc", "c", "c2"))
    (hit,) = only(lint(tmp_path, xml))
    assert hit["code"] == "S001" and "3 separate trees" in hit["message"] and len(hit["related"]) == 2


def test_floating_extra_link_is_s006_not_s001(tmp_path):
    xml = robot(L("base_link", "wheel", "imu_link"), J("wheel_joint", "base_link", "wheel"))
    f = lint(tmp_path, xml)
    assert codes(f) == ["S006"], f
    assert only(f)[0]["location"]["line"] == line_of(xml, 'name="imu_link"')


def test_links_without_any_joint_are_s001(tmp_path):
    f = lint(tmp_path, robot(L("base_link", "other")))
    assert codes(f) == ["S001"], f
    assert "no joint connecting them" in only(f)[0]["message"]


def test_a_single_link_is_a_valid_model(tmp_path):
    assert only(lint(tmp_path, robot(L("base_link")))) == []


def test_tree_plus_isolated_link_plus_second_tree(tmp_path):
    xml = robot(L("base_link", "arm", "cam", "cam_optical", "stray"), J("arm_joint", "base_link", "arm"),
                J("cam_optical_joint", "cam", "cam_optical"))
    assert codes(lint(tmp_path, xml)) == ["S001", "S006"]


# --- multiple parents ------------------------------------------------------------------------------------


def test_link_child_of_two_joints_is_s004_at_the_second(tmp_path):
    xml = robot(L("base_link", "mount", "caster"), J("mount_joint", "base_link", "mount"),
                J("caster_joint", "base_link", "caster"), J("caster_mount_joint", "mount", "caster"))
    f = lint(tmp_path, xml)
    assert codes(f) == ["S004"], f
    (hit,) = only(f)
    assert "'caster_mount_joint'" in hit["message"] and "'caster_joint'" in hit["message"]
    assert hit["location"]["line"] == line_of(xml, 'name="caster_mount_joint"')
    assert [r["line"] for r in hit["related"]] == [line_of(xml, 'name="caster_joint"')]


def test_reversed_joint_gives_s004_only_not_a_second_root(tmp_path):
    """urdfdom says 'Two root links found: [b] and [base_link]'; the cause is the joint written backwards."""
    xml = robot(L("base_link", "a", "b"), J("j1", "base_link", "a"), J("j2", "b", "a"))
    f = lint(tmp_path, xml)
    assert codes(f) == ["S004"], f


def test_three_parents_give_two_s004(tmp_path):
    xml = robot(L("base_link", "a", "b", "c"), J("ja", "base_link", "a"), J("jb", "base_link", "b"),
                J("jc1", "base_link", "c"), J("jc2", "a", "c"), J("jc3", "b", "c"))
    f = lint(tmp_path, xml)
    assert codes(f) == ["S004", "S004"], f


# --- missing links ---------------------------------------------------------------------------------------


def test_misspelt_child_is_s003_only(tmp_path):
    xml = robot(L("base_link", "laser_link"), J("laser_joint", "base_link", "laser_lnk"))
    f = lint(tmp_path, xml)
    assert codes(f) == ["S003"], f
    (hit,) = only(f)
    assert "child link 'laser_lnk'" in hit["message"] and "did you mean 'laser_link'" in hit["message"]
    assert hit["location"]["line"] == line_of(xml, 'name="laser_joint"')  # the <child> element, same line here


def test_misspelt_parent_does_not_make_the_real_parent_disconnected(tmp_path):
    xml = robot(L("base_link", "arm"), J("arm_joint", "base_lnik", "arm"))
    assert codes(lint(tmp_path, xml)) == ["S003"]


def test_undefined_world_parent_is_s003_not_no_root(tmp_path):
    f = lint(tmp_path, robot(L("base_link"), J("world_joint", "world", "base_link")))
    assert codes(f) == ["S003"], f
    assert "parent link 'world'" in only(f)[0]["message"]


def test_chains_ending_in_undefined_parents_are_s003_only(tmp_path):
    """fail_pr2_desc_two_trees: both defined links hang under undefined parents."""
    xml = robot(L("fl", "fr"), J("fl_joint", "base_link", "fl", "continuous"), J("fr_joint", "world", "fr"))
    assert codes(lint(tmp_path, xml)) == ["S003", "S003"]


# --- duplicates and names --------------------------------------------------------------------------------


def test_duplicate_link(tmp_path):
    xml = robot(L("base_link", "cam"), J("cam_joint", "base_link", "cam"), L("cam"))
    f = lint(tmp_path, xml)
    assert codes(f) == ["S007"], f
    (hit,) = only(f)
    assert hit["location"]["line"] == line_of(xml, 'name="cam"', 2)
    assert [r["line"] for r in hit["related"]] == [line_of(xml, 'name="cam"', 1)]


def test_copy_pasted_joint_is_s008_only(tmp_path):
    xml = robot(L("base_link", "cam"), J("cam_joint", "base_link", "cam"), J("cam_joint", "base_link", "cam"))
    f = lint(tmp_path, xml)
    assert codes(f) == ["S008"], f


def test_duplicate_joint_with_misspelt_child(tmp_path):
    """fail_pr2_desc_double_joint: the second definition names a link that does not exist."""
    xml = robot(L("base_link", "fl_caster_link", "fr_caster_link"), J("fl_caster_joint", "base_link", "fl_caster_link"),
                J("fl_caster_joint", "fl_caster_link", "fr_caster_joint"))
    f = lint(tmp_path, xml)
    assert codes(f) == ["S003", "S008"], f
    assert "did you mean 'fr_caster_link'" in next(x for x in f if x["code"] == "S003")["message"]


MAT = '<material name="{n}"><color rgba="{c}"/></material>'
VIS = ('<link name="{l}"><visual><geometry><box size="1 1 1"/></geometry>'
       '<material name="{n}">{inner}</material></visual></link>')


def test_identical_top_level_materials_are_an_error(tmp_path):
    """urdfdom: "material 'blue' is not unique" even when both definitions are the same."""
    xml = robot(MAT.format(n="blue", c="0 0 1 1"), MAT.format(n="blue", c="0 0 1 1"),
                VIS.format(l="base_link", n="blue", inner=""))
    f = lint(tmp_path, xml)
    assert [(x["code"], x["severity"]) for x in only(f)] == [("S009", "error")], f
    assert "identically" in only(f)[0]["message"]


def test_conflicting_top_level_materials(tmp_path):
    xml = robot(MAT.format(n="blue", c="0 0 1 1"), MAT.format(n="blue", c="0 0 0.5 1"),
                VIS.format(l="base_link", n="blue", inner=""))
    (hit,) = only(lint(tmp_path, xml))
    assert hit["code"] == "S009" and "rgba 0 0 0.5 1 after rgba 0 0 1 1" in hit["message"]


def test_link_material_with_the_global_colour_is_fine(tmp_path):
    xml = robot(MAT.format(n="blue", c="0 0 1 1"),
                VIS.format(l="base_link", n="blue", inner='<color rgba="0 0 1 1"/>'))
    assert only(lint(tmp_path, xml)) == []


def test_link_material_with_another_colour_is_a_warning(tmp_path):
    xml = robot(MAT.format(n="blue", c="0 0 1 1"),
                VIS.format(l="base_link", n="blue", inner='<color rgba="1 0 0 1"/>'))
    f = lint(tmp_path, xml)
    assert [(x["code"], x["severity"]) for x in only(f)] == [("S009", "warning")], f


def test_two_links_giving_one_material_name_two_colours(tmp_path):
    xml = robot(VIS.format(l="base_link", n="c", inner='<color rgba="1 0 0 1"/>'),
                VIS.format(l="arm", n="c", inner='<color rgba="0 1 0 1"/>'), J("arm_joint", "base_link", "arm"),
                VIS.format(l="tool", n="c", inner='<color rgba="1 0 0 1"/>'), J("tool_joint", "arm", "tool"))
    f = lint(tmp_path, xml)
    assert [(x["code"], x["severity"]) for x in only(f)] == [("S009", "warning")], f
    assert "link 'arm'" in only(f)[0]["message"]


def test_link_joint_name_clash_is_a_warning_at_the_joint(tmp_path):
    xml = robot(L("base_link", "pan"), J("pan", "base_link", "pan"))
    f = lint(tmp_path, xml)
    assert [(x["code"], x["severity"]) for x in only(f)] == [("S010", "warning")], f
    assert only(f)[0]["location"]["line"] == line_of(xml, '<joint name="pan"')


def test_empty_model(tmp_path):
    f = lint(tmp_path, robot(MAT.format(n="grey", c="0.5 0.5 0.5 1")))
    assert codes(f) == ["S011"], f
    assert "fragment" in only(f)[0]["message"]


def test_no_empty_model_report_when_the_root_is_not_a_robot(tmp_path):
    f = lint(tmp_path, '<sdf version="1.7"><model name="r"/></sdf>\n')
    assert "U001" in [x["code"] for x in f] and codes(f) == []


# --- the corpus ------------------------------------------------------------------------------------------

# Every negative test model of ros/urdf, the codes that must be among our *errors*, and what Debian's
# check_urdf (urdfdom 3.0.1) says first. Our verdicts agree with check_urdf on all nine; we usually say more
# because check_urdf stops at its first error (e.g. the bracket file also has an undefined parent link).
FAIL_MODELS = {
    "fail_pr2_desc_bracket.urdf": {"U004"},  # "Unable to parse component [}] to a double"
    "fail_pr2_desc_double.urdf": {"S007"},  # "link 'fl_caster_rotation_link' is not unique"
    "fail_pr2_desc_double_joint.urdf": {"S008"},  # "joint 'fl_caster_rotation_joint' is not unique"
    "fail_pr2_desc_loop.urdf": {"S002"},  # "No root link found"
    "fail_pr2_desc_no_filename_in_mesh.urdf": {"U006", "S003"},  # "Mesh must contain a filename", "[world] not found"
    "fail_pr2_desc_no_joint2.urdf": {"X001"},  # XML error ("Error: empty tag")
    "fail_pr2_desc_parent_itself.urdf": {"S002"},  # "No root link found"
    "fail_pr2_desc_two_trees.urdf": {"S003"},  # "parent link [base_link] of joint [...] not found"
    "fail_three_links_one_joint.urdf": {"X001"},  # "Error reading end tag"
}


def test_every_negative_ros_urdf_model_is_listed(corpus):
    names = {p.name for p in (corpus / "ros+urdf" / "urdf" / "test").glob("fail_*.urdf")}
    assert names == set(FAIL_MODELS)


@pytest.mark.parametrize("name", sorted(FAIL_MODELS))
def test_negative_ros_urdf_models_give_errors(corpus, name):
    path = corpus / "ros+urdf" / "urdf" / "test" / name
    code, report = lint_json([path], cwd=path.parent)
    errors = {f["code"] for f in report["findings"] if f["severity"] == "error"}
    assert errors, report["findings"]
    assert FAIL_MODELS[name] <= errors, (name, errors)
    assert code == 1


@pytest.mark.parametrize("name", sorted(FAIL_MODELS))
def test_check_urdf_rejects_them_too(corpus, name):
    """Cross-check with the reference parser, when Debian's check_urdf is installed."""
    import os

    if not os.access(CHECK_URDF, os.X_OK):
        pytest.skip("check_urdf not installed")
    path = corpus / "ros+urdf" / "urdf" / "test" / name
    out = subprocess.run([CHECK_URDF, str(path)], capture_output=True, text=True, timeout=60)
    assert "Successfully Parsed" not in out.stdout, out.stdout


def _good_models(corpus):
    tb = corpus / "ROBOTIS-GIT+turtlebot3" / "turtlebot3_description" / "urdf"
    return [
        corpus / "ros+urdf" / "urdf" / "test" / "pr2_desc.urdf",
        tb / "turtlebot3_burger.urdf", tb / "turtlebot3_waffle.urdf", tb / "turtlebot3_waffle_pi.urdf",
        corpus / "ANYbotics+anymal_c_simple_description" / "urdf" / "anymal.urdf",
        *sorted((corpus / "ros+kdl_parser").rglob("*.urdf")),
        *sorted((corpus / "ros+robot_state_publisher").rglob("*.urdf")),
    ]


# What our S and J rules say about the good models, exactly. Everything else: nothing.
GOOD_EXPECTED = {
    # ANYmal C: the twelve leg joints share their names with links (LF_HAA joint and LF_HAA link, ...).
    # Genuine: Pinocchio's getFrameId('LF_HAA') raises "Several frames match"; urdfdom/KDL do not care.
    "anymal.urdf": [("S010", "warning")] * 12,
    # robot_state_publisher's own test of a <mimic> on a fixed joint: every consumer ignores it (info).
    "mimic_joint.urdf": [("J008", "info")],
    # The old PR2 test model: two <gazebo reference> blocks name links the sensor macros never made (the stereo
    # pair's link is double_stereo_link, the sensor mount's sensor_mount_link): Gazebo applies them to nothing.
    "pr2_desc.urdf": [("S012", "warning")] * 2,
}


def test_good_corpus_models_have_no_structure_or_joint_errors(corpus):
    for path in _good_models(corpus):
        assert path.is_file(), path
        _, report = lint_json([path], cwd=path.parent)
        mine = sorted((f["code"], f["severity"]) for f in report["findings"] if f["code"][0] in "SJ")
        assert mine == sorted(GOOD_EXPECTED.get(path.name, [])), (path.name, report["findings"])


def test_anymal_name_clashes_are_the_leg_joints(corpus):
    path = corpus / "ANYbotics+anymal_c_simple_description" / "urdf" / "anymal.urdf"
    _, report = lint_json([path], cwd=path.parent)
    names = sorted(f["message"].split("'")[1] for f in report["findings"] if f["code"] == "S010")
    assert names == sorted(f"{leg}_{j}" for leg in ("LF", "RF", "LH", "RH") for j in ("HAA", "HFE", "KFE"))


def test_turtlebot_materials_fragment_is_an_empty_model(corpus):
    """common_properties.urdf only declares materials for inclusion (and uses ${} it never expands): linted
    on its own it has no link, which urdfdom refuses ('No link elements found in urdf file')."""
    path = corpus / "ROBOTIS-GIT+turtlebot3" / "turtlebot3_description" / "urdf" / "common_properties.urdf"
    _, report = lint_json([path], cwd=path.parent)
    assert [f["code"] for f in report["findings"] if f["code"][0] in "SJ"] == ["S011"]
