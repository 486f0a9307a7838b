"""Inline suppressions end to end through the CLI (XML comments), and YAML comment suppressions."""
import json
import os

import pytest
from conftest import run_cli

from urdfcheck.core import suppress
from urdfcheck.core.findings import Finding, Location, Severity
from urdfcheck.finish.suppressions import finish_target
from urdfcheck.rules import engine


def lint(tmp_path, name, text, *extra):
    (tmp_path / name).write_text(text)
    code, out, err = run_cli(["lint", "--no-config", "--trusted", "--select", "U,R", "--format", "json", name,
                              *extra], cwd=tmp_path)
    assert code in (0, 1), err
    return code, [(f["code"], f["location"]["line"], [v["line"] for v in f["location"].get("via", [])])
                  for f in json.loads(out)["findings"]]


JOINT = """<robot name="r">
  <link name="base_link"/>
  <link name="arm"/>
  {comment}
  <joint name="j" type="fixed">
    <orign xyz="0 0 0.5"/>
    <parent link="base_link"/>
    <child link="arm"/>
  </joint>
</robot>
"""


def test_unsuppressed(tmp_path):
    code, found = lint(tmp_path, "r.urdf", JOINT.format(comment=""))
    assert code == 1 and found == [("U002", 6, [])]


def test_before_an_element_covers_its_children(tmp_path):
    code, found = lint(tmp_path, "r.urdf", JOINT.format(comment="<!-- urdfcheck: ignore[U002] legacy -->"))
    assert code == 0 and found == []


def test_directly_before_the_offending_element(tmp_path):
    text = JOINT.format(comment="").replace('    <orign', '    <!-- urdfcheck: ignore[U002] -->\n    <orign')
    code, found = lint(tmp_path, "r.urdf", text)
    assert code == 0 and found == []


def test_several_codes_and_all(tmp_path):
    code, found = lint(tmp_path, "r.urdf", JOINT.format(comment="<!-- urdfcheck: ignore[J007, u002] -->"))
    assert found == []
    code, found = lint(tmp_path, "r2.urdf", JOINT.format(comment="<!-- urdfcheck: ignore[ALL] -->"))
    assert code == 0 and found == []


def test_only_the_next_element(tmp_path):
    text = JOINT.format(comment="").replace('  <link name="arm"/>',
                                            '  <!-- urdfcheck: ignore[U002] -->\n  <link name="arm"/>')
    code, found = lint(tmp_path, "r.urdf", text)
    assert code == 1
    assert sorted(c for c, _, _ in found) == ["R002", "U002"]  # the joint is not covered; the comment is unused


def test_wrong_code_is_unused(tmp_path):
    code, found = lint(tmp_path, "r.urdf", JOINT.format(comment="<!-- urdfcheck: ignore[U003] -->"))
    assert code == 1 and found == [("R002", 4, []), ("U002", 6, [])]


def test_unused_suppression_is_r002(tmp_path):
    text = '<robot name="r">\n  <!-- urdfcheck: ignore[U002] stale -->\n  <link name="base_link"/>\n</robot>\n'
    code, found = lint(tmp_path, "r.urdf", text)
    assert code == 1 and found == [("R002", 2, [])]
    # R002 itself can be deselected
    code, found = lint(tmp_path, "r.urdf", text, "--ignore", "R002")
    assert code == 0 and found == []


def test_file_level(tmp_path):
    text = "<!-- urdfcheck: ignore-file[U002] generated file -->\n" + JOINT.format(comment="")
    code, found = lint(tmp_path, "r.urdf", text)
    assert code == 0 and found == []
    text = JOINT.format(comment="<!-- urdfcheck: ignore-file[U002] -->")
    code, found = lint(tmp_path, "r2.urdf", text)
    assert code == 0 and found == []


MACRO = """<robot name="r" xmlns:xacro="http://www.ros.org/wiki/xacro">
  <xacro:macro name="leg" params="prefix">
    <link name="${{prefix}}_leg"/>
    {in_macro}
    <joint name="${{prefix}}_j" type="fixed">
      <orign xyz="0 0 0"/>
      <parent link="base_link"/>
      <child link="${{prefix}}_leg"/>
    </joint>
  </xacro:macro>
  <link name="base_link"/>
  {at_call}
  <xacro:leg prefix="l"/>
  <xacro:leg prefix="r"/>
</robot>
"""


def test_macro_unsuppressed(tmp_path):
    _, found = lint(tmp_path, "r.urdf.xacro", MACRO.format(in_macro="", at_call=""))
    assert found == [("U002", 6, [13])]  # one problem in the macro body, shown once (finish.collapse)


def test_inside_a_macro_body_holds_for_every_expansion(tmp_path):
    text = MACRO.format(in_macro="<!-- urdfcheck: ignore[U002] -->", at_call="")
    code, found = lint(tmp_path, "r.urdf.xacro", text)
    assert code == 0 and found == []


def test_before_a_call_site_holds_for_that_expansion_only(tmp_path):
    text = MACRO.format(in_macro="", at_call="<!-- urdfcheck: ignore[U002] left leg is legacy -->")
    code, found = lint(tmp_path, "r.urdf.xacro", text)
    assert code == 1 and found == [("U002", 6, [14])]


def test_macro_in_an_included_file(tmp_path):
    (tmp_path / "leg.xacro").write_text("""<robot xmlns:xacro="http://www.ros.org/wiki/xacro">
  <xacro:macro name="leg" params="prefix">
    <link name="${prefix}_leg"/>
    <!-- urdfcheck: ignore[U002] -->
    <joint name="${prefix}_j" type="fixed">
      <orign xyz="0 0 0"/>
      <parent link="base_link"/>
      <child link="${prefix}_leg"/>
    </joint>
  </xacro:macro>
</robot>
""")
    text = """<robot name="r" xmlns:xacro="http://www.ros.org/wiki/xacro">
  <xacro:include filename="leg.xacro"/>
  <link name="base_link"/>
  <xacro:leg prefix="l"/>
  <xacro:leg prefix="r"/>
</robot>
"""
    code, found = lint(tmp_path, "r.urdf.xacro", text)
    assert code == 0 and found == []


def test_unused_in_macro_is_reported_once_per_comment(tmp_path):
    text = MACRO.format(in_macro="<!-- urdfcheck: ignore[U003] -->", at_call="").replace("orign", "origin")
    code, found = lint(tmp_path, "r.urdf.xacro", text)
    assert code == 1 and found == [("R002", 4, [])]


# --- YAML ------------------------------------------------------------------------------------------

CONTROLLERS = """\
# urdfcheck: ignore-file[C099] whole file
controller_manager:
  ros__parameters:
    update_rate: 100

diff_drive:
  ros__parameters:
    # urdfcheck: ignore[C001] the caster is commanded by another driver
    left_wheel_names:
      - left_wheel_joint
      - caster_joint
    right_wheel_names: ["right_wheel_joint"]   # urdfcheck: ignore[C010, C011]
    wheel_separation: 0.5
    label: "not # urdfcheck: ignore[C012] a comment"
joints:
- a
"""


def test_scan_yaml_comments():
    got = suppress.scan_yaml_comments(CONTROLLERS)
    assert got == [
        (0, 10**9, ("C099",), 1),
        (9, 11, ("C001",), 8),  # the key line and the list under it
        (12, 12, ("C010", "C011"), 12),  # trailing comment: its own line
    ]


def test_scan_yaml_block_rules():
    text = ("a:\n  # urdfcheck: ignore[C001]\n  b:\n    c: 1\n\n    d: 2\n  e: 3\n"
            "# urdfcheck: ignore[C002]\nseq:\n- x\n- y\nz: 1\n")
    got = suppress.scan_yaml_comments(text)
    assert got == [(3, 6, ("C001",), 2), (9, 11, ("C002",), 8)]
    assert suppress.scan_yaml_comments("# urdfcheck: ignore[C001]\n") == []  # nothing follows
    assert suppress.scan_yaml_comments("k: 'it''s # urdfcheck: ignore[C001]'\n") == []


@pytest.fixture
def in_tmp(tmp_path):
    old = os.getcwd()
    os.chdir(tmp_path)
    yield tmp_path
    os.chdir(old)


def _f(code, file, line):
    return Finding(code, Severity.ERROR, f"{code} at {line}", Location(file, line))


def test_engine_consults_yaml_suppressions(in_tmp):
    (in_tmp / "config").mkdir()
    (in_tmp / "config" / "ctrl.yaml").write_text(CONTROLLERS)
    path = "config/ctrl.yaml"
    findings = [_f("C001", path, 10), _f("C001", path, 13), _f("C010", path, 12), _f("C012", path, 14),
                _f("C099", path, 3), _f("C001", "robot.urdf", 10)]
    kept = finish_target(findings, engine.Selection(), [], model="robot.urdf")
    assert [(f.code, f.location.line, f.location.file) for f in kept] == [
        ("C001", 13, path), ("C012", 14, path), ("C001", 10, "robot.urdf")]


def test_yaml_suppressions_are_cached_and_refreshed(in_tmp):
    p = in_tmp / "c.yml"
    p.write_text("a: 1  # urdfcheck: ignore[C001]\n")
    first = suppress.yaml_suppressions("c.yml")
    assert [s.codes for s in first] == [("C001",)]
    assert suppress.yaml_suppressions("c.yml") is first  # read once
    p.write_text("a: 1  # urdfcheck: ignore[C002, C003]\n")
    os.utime(p, ns=(1, 1))  # a different mtime, whatever the clock resolution
    assert [s.codes for s in suppress.yaml_suppressions("c.yml")] == [("C002", "C003")]
    assert suppress.yaml_suppressions("missing.yaml") == []


EXAMPLES = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "examples")


def _package_with_driver_yaml(tmp_path, lines, *extra, example="contract_driver_joint_typo"):
    import shutil

    pkg = tmp_path / f"pkg{len(list(tmp_path.iterdir()))}"
    shutil.copytree(os.path.join(EXAMPLES, "broken", example), pkg)
    drv = pkg / "config" / "agv_driver_ros1.yaml"
    text = drv.read_text().splitlines()
    for before, line in sorted(lines, reverse=True):  # insert bottom-up: earlier line numbers stay valid
        text.insert(before, line)
    drv.write_text("\n".join(text) + "\n")
    code, out, err = run_cli(["lint", "--format", "json", ".", *extra], cwd=pkg)
    assert code in (0, 1), err
    return [(f["code"], os.path.basename(f["location"]["file"]), f["location"]["line"])
            for f in json.loads(out)["findings"]]


def test_a_yaml_suppression_that_hides_nothing_is_reported(tmp_path):
    found = _package_with_driver_yaml(tmp_path, [(4, "# urdfcheck: ignore[C001] the typo is fixed upstream"),
                                                 (6, "# urdfcheck: ignore[C010] old separation")])
    # the C001 is hidden by its comment (line 5); the C010 comment (line 8) above wheel_separation hides nothing
    assert found == [("R002", "agv_driver_ros1.yaml", 8)]


def test_used_yaml_suppressions_and_deselected_codes_raise_nothing(tmp_path):
    assert _package_with_driver_yaml(tmp_path, [(4, "# urdfcheck: ignore[C001]")]) == []
    unused = [(4, "# urdfcheck: ignore[C001]"), (6, "# urdfcheck: ignore[C010]")]
    assert _package_with_driver_yaml(tmp_path, unused, "--ignore", "C010") == []  # the rule is off: not "unused"
    assert _package_with_driver_yaml(tmp_path, unused, "--ignore", "R002") == []


def test_a_yaml_suppression_used_by_one_variant_only_is_used(tmp_path):
    # camera_link exists only with use_camera:=true: the C020 comes from the no_camera variant alone
    assert _package_with_driver_yaml(tmp_path, [(9, "# urdfcheck: ignore[C020] the camera is optional")],
                                     example="variant_camera_off") == []

