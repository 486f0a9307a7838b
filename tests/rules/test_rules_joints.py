"""J rules (joints): types, limits, axes, mimic relations. Through the real CLI (`conftest.lint_json`, or
`run_cli` with a config file for rule options)."""
from __future__ import annotations

import json
import textwrap

import pytest
from conftest import lint_json, run_cli


def lint(tmp_path, xml: str, name: str = "robot.urdf"):
    path = tmp_path / name
    path.write_text(textwrap.dedent(xml).lstrip(), encoding="utf-8")
    _, report = lint_json([path], cwd=tmp_path)
    return report["findings"]


def lint_with_config(tmp_path, xml: str, config: str):
    (tmp_path / "robot.urdf").write_text(textwrap.dedent(xml).lstrip(), encoding="utf-8")
    (tmp_path / "urdfcheck.yaml").write_text(textwrap.dedent(config), encoding="utf-8")
    code, out, err = run_cli(["lint", "--format", "json", "--config", tmp_path / "urdfcheck.yaml",
                              tmp_path / "robot.urdf"], cwd=tmp_path)
    assert code in (0, 1), (code, err)
    return json.loads(out)["findings"]


def mine(findings, prefix="J"):
    return [(f["code"], f["severity"]) for f in findings if f["code"].startswith(prefix)]


def first(findings, code):
    return next(f for f in findings if f["code"] == code)


def joint(name="j", jtype="revolute", parent="base_link", child="arm_link", body=""):
    return (f'<joint name="{name}" type="{jtype}">\n  <parent link="{parent}"/>\n  <child link="{child}"/>\n'
            f"{textwrap.indent(textwrap.dedent(body).strip(), '  ')}\n</joint>")


def robot(*parts, links=("base_link", "arm_link")):
    return ('<robot name="r">\n' + "\n".join(f'<link name="{n}"/>' for n in links) + "\n" + "\n".join(parts)
            + "\n</robot>\n")


LIMIT = '<limit lower="-1" upper="1" effort="10" velocity="1"/>'


def line_of(xml: str, marker: str, nth: int = 1) -> int:
    seen = 0
    for i, line in enumerate(textwrap.dedent(xml).lstrip().splitlines(), 1):
        if marker in line:
            seen += 1
            if seen == nth:
                return i
    raise AssertionError(marker)


# --- J001 type ----------------------------------------------------------------------------------------------


def test_unknown_type_with_suggestion(tmp_path):
    f = lint(tmp_path, robot(joint(jtype="Revolute", body=LIMIT)))
    assert mine(f) == [("J001", "error")], f
    assert "did you mean 'revolute'" in first(f, "J001")["message"]


def test_missing_type_is_u006_not_j001(tmp_path):
    xml = robot('<joint name="j">\n<parent link="base_link"/>\n<child link="arm_link"/>\n</joint>')
    f = lint(tmp_path, xml)
    assert "U006" in [x["code"] for x in f] and mine(f) == []


# --- J002 / J003 limits ------------------------------------------------------------------------------------


def test_revolute_without_limit(tmp_path):
    assert mine(lint(tmp_path, robot(joint(body='<axis xyz="0 0 1"/>')))) == [("J002", "error")]


def test_limit_without_lower_upper_is_a_warning(tmp_path):
    f = lint(tmp_path, robot(joint(jtype="prismatic", body='<limit effort="10" velocity="1"/>')))
    assert mine(f) == [("J002", "warning")], f
    assert "neither lower nor upper" in first(f, "J002")["message"]


def test_continuous_needs_no_limit(tmp_path):
    assert mine(lint(tmp_path, robot(joint(jtype="continuous")))) == []


def test_inverted_limits_at_the_limit_element(tmp_path):
    xml = robot(joint(body='<limit lower="0.8" upper="-0.8" effort="5" velocity="1"/>'))
    f = lint(tmp_path, xml)
    assert mine(f) == [("J003", "error")], f
    hit = first(f, "J003")
    assert hit["location"]["line"] == line_of(xml, "<limit")


def test_missing_lower_counts_as_zero(tmp_path):
    f = lint(tmp_path, robot(joint(body='<limit upper="-0.5" effort="5" velocity="1"/>')))
    assert sorted(mine(f)) == [("J002", "warning"), ("J003", "error")], f
    assert "counts as 0" in first(f, "J003")["message"]


def test_locked_joint_is_info(tmp_path):
    f = lint(tmp_path, robot(joint(body='<limit lower="0.3" upper="0.3" effort="5" velocity="1"/>')))
    assert mine(f) == [("J003", "info")], f


def test_both_bounds_missing_is_not_a_locked_joint_report(tmp_path):
    f = lint(tmp_path, robot(joint(body='<limit effort="5" velocity="1"/>')))
    assert mine(f) == [("J002", "warning")], f


def test_unreadable_bound_is_u005_only(tmp_path):
    """The builder defaults an unreadable lower to None: that is not a missing or zero bound."""
    f = lint(tmp_path, robot(joint(body='<limit lower="-1,5" upper="-1" effort="5" velocity="1"/>')))
    assert "U005" in [x["code"] for x in f] and mine(f) == [], f


# --- J004 / J005 ---------------------------------------------------------------------------------------------


def test_zero_effort_and_negative_velocity(tmp_path):
    # actuated (a transmission drives it): effort="0" is no un-actuated joint here (issue 15)
    trans = ('<transmission name="t"><type>transmission_interface/SimpleTransmission</type>'
             '<joint name="j"><hardwareInterface>EffortJointInterface</hardwareInterface></joint></transmission>')
    f = lint(tmp_path, robot(joint(body='<limit lower="-1" upper="1" effort="0" velocity="-2"/>'), trans))
    assert mine(f) == [("J004", "warning"), ("J004", "warning")], f
    msgs = " ".join(x["message"] for x in f if x["code"] == "J004")
    assert "effort limit 0" in msgs and "velocity limit -2" in msgs and "Pinocchio" in msgs


def test_fixed_joint_limits_are_not_checked(tmp_path):
    f = lint(tmp_path, robot(joint(jtype="fixed", body='<limit effort="0" velocity="0"/>')))
    assert mine(f) == []


def test_continuous_with_position_limits(tmp_path):
    f = lint(tmp_path, robot(joint(jtype="continuous", body='<limit lower="-3" upper="3" effort="5" velocity="1"/>')))
    assert mine(f) == [("J005", "warning")], f


def test_continuous_zero_placeholder_limits_are_not_reported(tmp_path):
    """kdl_parser_py's test.urdf writes lower="0" upper="0" on its wheels: a template placeholder."""
    f = lint(tmp_path, robot(joint(jtype="continuous", body='<limit lower="0" upper="0" effort="5" velocity="1"/>')))
    assert mine(f) == []


# --- J006 / J007 axes ----------------------------------------------------------------------------------------


def test_zero_axis_at_the_axis_element(tmp_path):
    xml = robot(joint(jtype="continuous", body='<axis xyz="0 0 0"/>'))
    f = lint(tmp_path, xml)
    assert mine(f) == [("J006", "error")], f
    assert first(f, "J006")["location"]["line"] == line_of(xml, "<axis")


@pytest.mark.parametrize("jtype", ["fixed", "floating"])
def test_axis_of_joints_without_motion_is_ignored(tmp_path, jtype):
    f = lint(tmp_path, robot(joint(jtype=jtype, body='<axis xyz="0 0 0"/>')))
    assert [c for c in mine(f) if c[0] in ("J006", "J007")] == []


def test_planar_axis_is_not_j006_but_j011_says_it(tmp_path):
    f = lint(tmp_path, robot(joint(jtype="planar", body='<axis xyz="0 0 0"/>')))
    assert mine(f) == [("J011", "warning")], f
    assert "defines no plane" in first(f, "J011")["message"]


def test_planar_axis_other_than_z(tmp_path):
    f = lint(tmp_path, robot(joint(jtype="planar", body='<axis xyz="1 0 0"/>')))
    assert "asks for another plane" in first(f, "J011")["message"]
    msg = first(lint(tmp_path, robot(joint(jtype="planar", body='<axis xyz="0 0 1"/>'))), "J011")["message"]
    assert "another plane" not in msg and "defines no plane" not in msg


def test_non_unit_axis_gives_the_unit_one(tmp_path):
    f = lint(tmp_path, robot(joint(jtype="prismatic", body='<axis xyz="0 0 2"/>\n' + LIMIT)))
    assert mine(f) == [("J007", "warning")], f
    msg = first(f, "J007")["message"]
    assert "length 2" in msg and "Write 0 0 1" in msg and "yourdfpy" in msg


def test_three_digit_diagonal_axis_is_reported_by_default(tmp_path):
    f = lint(tmp_path, robot(joint(body='<axis xyz="0 0.707 0.707"/>\n' + LIMIT)))
    assert mine(f) == [("J007", "warning")], f
    assert "length 0.999849, not 1" in first(f, "J007")["message"]


@pytest.mark.parametrize("axis", ["0 0.7071 0.7071", "-0.0021817 0 0.99999762", "0 0 1.000003",
                                  "0.57735 0.57735 0.57735", "0 -0.999997 0"])
def test_exporter_rounding_is_not_a_defect(tmp_path, axis):
    """Axes off unit length by 1e-6..1e-5, as CAD exporters and vendors write them: every consumer normalises."""
    assert mine(lint(tmp_path, robot(joint(body=f'<axis xyz="{axis}"/>\n' + LIMIT)))) == []


def test_the_message_shows_the_digits_that_differ(tmp_path):
    xml = robot(joint(body='<axis xyz="0 0 1.000003"/>\n' + LIMIT))
    msg = first(lint_with_config(tmp_path, xml, "rules:\n  J007: {tolerance: 1.0e-7}\n"), "J007")["message"]
    assert "has length 1.000003, not 1" in msg and "axis 0 0 1.000003 " in msg, msg
    xml = robot(joint(body='<axis xyz="-0.0021817 0 0.99999762"/>\n' + LIMIT))
    msg = first(lint_with_config(tmp_path, xml, "rules:\n  J007: {tolerance: 1.0e-12}\n"), "J007")["message"]
    assert "length 1, not 1" not in msg and "0.99999762" in msg, msg


def test_default_axis_is_unit(tmp_path):
    assert mine(lint(tmp_path, robot(joint(body=LIMIT)))) == []


def test_axis_tolerance_option_from_config(tmp_path):
    xml = robot(joint(body='<axis xyz="0 0.7071 0.7071"/>\n' + LIMIT))
    assert mine(lint_with_config(tmp_path, xml, "rules:\n  J007: {tolerance: 1.0e-4}\n")) == []
    assert mine(lint_with_config(tmp_path, xml, "rules:\n  J007: {tolerance: 1.0e-6}\n")) == [("J007", "warning")]


def test_zero_tolerance_still_accepts_exact_unit_axes(tmp_path):
    xml = robot(joint(body='<axis xyz="0 -1 0"/>\n' + LIMIT))
    assert mine(lint_with_config(tmp_path, xml, "rules:\n  J007: {tolerance: 0}\n")) == []


def test_bad_tolerance_is_a_config_error_not_a_traceback(tmp_path):
    # rule options are typed in the catalogue entry: a bad value stops at the config (exit 2, file:line),
    # it never reaches the check (tests/cli/test_api.py has the other option errors)
    (tmp_path / "robot.urdf").write_text(robot(joint(body='<axis xyz="0 0 2"/>\n' + LIMIT)), encoding="utf-8")
    (tmp_path / "urdfcheck.yaml").write_text("rules:\n  J007: {tolerance: loose}\n", encoding="utf-8")
    code, out, err = run_cli(["lint", "robot.urdf"], cwd=tmp_path)
    assert code == 2 and out == "" and "urdfcheck.yaml:2" in err and "tolerance" in err and "Traceback" not in err


# --- J008 / J009 mimic -----------------------------------------------------------------------------------


def gripper(left_body="", right_body="", third_body=None):
    fingers = ("base_link", "left_finger", "right_finger") + (("third_finger",) if third_body is not None else ())
    lim = '<limit lower="0" upper="0.04" effort="20" velocity="0.1"/>'
    parts = [joint("left_joint", "prismatic", child="left_finger", body=lim + "\n" + left_body),
             joint("right_joint", "prismatic", child="right_finger", body=lim + "\n" + right_body)]
    if third_body is not None:
        parts.append(joint("third_joint", "prismatic", child="third_finger", body=lim + "\n" + third_body))
    return robot(*parts, links=fingers)


def test_mimic_of_a_misspelt_joint(tmp_path):
    xml = gripper(right_body='<mimic joint="left_jiont"/>')
    f = lint(tmp_path, xml)
    assert mine(f) == [("J008", "error")], f
    hit = first(f, "J008")
    assert "did you mean 'left_joint'" in hit["message"]
    assert hit["location"]["line"] == line_of(xml, "<mimic")


def test_mimic_of_itself_is_j008_not_j009(tmp_path):
    f = lint(tmp_path, gripper(right_body='<mimic joint="right_joint"/>'))
    assert mine(f) == [("J008", "error")], f
    assert "mimics itself" in first(f, "J008")["message"]


def test_mimic_of_a_fixed_joint(tmp_path):
    xml = robot(joint("mount", "fixed", child="arm_link"),
                joint("finger", "prismatic", parent="arm_link", child="finger",
                      body='<limit lower="0" upper="0.04" effort="20" velocity="0.1"/>\n<mimic joint="mount"/>'),
                links=("base_link", "arm_link", "finger"))
    f = lint(tmp_path, xml)
    assert mine(f) == [("J008", "error")], f
    assert "a fixed joint" in first(f, "J008")["message"]


def test_mimic_on_a_fixed_joint_is_info(tmp_path):
    xml = robot(joint("a", "fixed", child="arm_link"), joint("b", "fixed", child="tool", body='<mimic joint="a"/>'),
                links=("base_link", "arm_link", "tool"))
    assert mine(lint(tmp_path, xml)) == [("J008", "info")]


def test_valid_mimic(tmp_path):
    assert mine(lint(tmp_path, gripper(right_body='<mimic joint="left_joint" multiplier="-1"/>'))) == []


def test_mimic_chain_is_fine(tmp_path):
    """MoveIt and joint_state_publisher resolve a -> b -> c chains."""
    xml = gripper(right_body='<mimic joint="left_joint"/>', third_body='<mimic joint="right_joint"/>')
    assert mine(lint(tmp_path, xml)) == []


def test_mimic_cycle_of_two(tmp_path):
    xml = gripper(left_body='<mimic joint="right_joint"/>', right_body='<mimic joint="left_joint"/>')
    f = lint(tmp_path, xml)
    assert mine(f) == [("J009", "error")], f
    hit = first(f, "J009")
    assert "'left_joint' -> 'right_joint' -> 'left_joint'" in hit["message"]
    assert hit["location"]["line"] == line_of(xml, "<mimic", 1)
    assert [r["line"] for r in hit["related"]] == [line_of(xml, "<mimic", 2)]


def test_mimic_cycle_of_three_with_a_follower_is_reported_once(tmp_path):
    xml = robot(*(joint(f"j{i}", "revolute", child=f"l{i}", body=LIMIT + f'\n<mimic joint="j{(i + 1) % 3}"/>')
                  for i in range(3)),
                joint("j3", "revolute", child="l3", body=LIMIT + '\n<mimic joint="j0"/>'),
                links=("base_link", "l0", "l1", "l2", "l3"))
    f = lint(tmp_path, xml)
    assert mine(f) == [("J009", "error")], f
    assert "'j0' -> 'j1' -> 'j2' -> 'j0'" in first(f, "J009")["message"]


# --- J010 / J011 -------------------------------------------------------------------------------------------


def test_floating_joint_is_info(tmp_path):
    assert mine(lint(tmp_path, robot(joint(jtype="floating")))) == [("J010", "info")]


def test_planar_joint_is_a_warning(tmp_path):
    f = lint(tmp_path, robot(joint(jtype="planar")))
    assert mine(f) == [("J011", "warning")]
    assert "/tf_static" in first(f, "J011")["message"]


# --- duplicates ---------------------------------------------------------------------------------------------


def test_each_definition_of_a_duplicated_joint_is_checked_where_written(tmp_path):
    xml = robot(joint("j", "continuous", body='<axis xyz="0 0 1"/>'),
                joint("j", "continuous", child="tool", body='<axis xyz="0 0 0"/>'),
                links=("base_link", "arm_link", "tool"))
    f = lint(tmp_path, xml)
    assert ("S008", "error") in mine(f, "S")
    hits = [x for x in f if x["code"] == "J006"]
    assert [h["location"]["line"] for h in hits] == [line_of(xml, '<axis xyz="0 0 0"/>')]


# --- the corpus ----------------------------------------------------------------------------------------------


def test_pr2_mimic_grippers_are_clean(corpus):
    path = corpus / "ros+urdf" / "urdf" / "test" / "pr2_desc.urdf"
    _, report = lint_json([path], cwd=path.parent)
    assert [f for f in report["findings"] if f["code"][0] == "J"] == []


def test_rsp_mimic_test_model(corpus):
    """robot_state_publisher's own test puts a <mimic> on a fixed joint: ignored by every consumer, so info."""
    path = corpus / "ros+robot_state_publisher" / "test" / "mimic_joint.urdf"
    _, report = lint_json([path], cwd=path.parent)
    assert mine(report["findings"]) == [("J008", "info")]


def test_negative_pr2_models_without_lower_upper(corpus):
    """The ros/urdf negative tests write revolute casters with <limit effort velocity> only: urdfdom silently
    locks them at [0, 0]; reported as a J002 warning on each."""
    path = corpus / "ros+urdf" / "urdf" / "test" / "fail_pr2_desc_loop.urdf"
    _, report = lint_json([path], cwd=path.parent)
    assert mine(report["findings"]) == [("J002", "warning"), ("J002", "warning")]
