"""Baselines: --write-baseline records findings without line numbers; --baseline fails only on new ones."""
import json

from conftest import run_cli
from samples import MACROS

from urdfcheck.core.findings import Finding, Location, Severity
from urdfcheck.finish import baseline

ROBOT = """<robot name="r">
  <link name="base_link"/>
  <link name="arm"/>
  <link name="hand"/>
  <joint name="shoulder" type="fixed">
    <orign xyz="0 0 0.5"/>
    <parent link="base_link"/>
    <child link="arm"/>
  </joint>
  <joint name="wrist" type="fixed">
    <origin xyz="0 0 0.5" rpy="0 0 0" rpyy="1"/>
    <parent link="arm"/>
    <child link="hand"/>
  </joint>
</robot>
"""


def lint(args, cwd):
    return run_cli(["lint", "--no-config", "--select", "U", "--trusted", "--format", "json", *args], cwd=cwd)


def codes(out):
    return [(f["code"], f["location"]["line"]) for f in json.loads(out)["findings"]]


def write_baseline(tmp_path, target="robot.urdf", cwd=None):
    code, _, err = run_cli(["lint", "--no-config", "--select", "U", "--trusted", target,
                            "--write-baseline", str(tmp_path / "baseline.json")], cwd=cwd or tmp_path)
    assert code == 0, err
    return json.loads((tmp_path / "baseline.json").read_text())


def test_baseline_file_has_no_line_numbers(tmp_path):
    (tmp_path / "robot.urdf").write_text(ROBOT)
    data = write_baseline(tmp_path)
    assert data["version"] == 1
    assert [e["code"] for e in data["findings"]] == ["U002", "U003"]
    for e in data["findings"]:
        assert set(e) == {"code", "file", "message", "context", "count"}
        assert e["file"] == "robot.urdf" and e["count"] == 1


def test_baselined_findings_pass(tmp_path):
    (tmp_path / "robot.urdf").write_text(ROBOT)
    write_baseline(tmp_path)
    code, out, _ = lint(["robot.urdf", "--baseline", "baseline.json"], tmp_path)
    assert code == 0 and codes(out) == []


def test_moving_lines_keeps_the_baseline_valid(tmp_path):
    (tmp_path / "robot.urdf").write_text(ROBOT)
    write_baseline(tmp_path)
    lines = ROBOT.splitlines()
    # add a comment and blank lines at the top, and swap the two joints
    moved = "\n".join([lines[0], "  <!-- a comment -->", "", ""] + lines[1:4] + lines[9:14] + lines[4:9]
                      + lines[14:]) + "\n"
    (tmp_path / "robot.urdf").write_text(moved)
    code, out, _ = lint(["robot.urdf"], tmp_path)
    assert code == 1 and sorted(c for c, _ in codes(out)) == ["U002", "U003"]  # same findings, new lines
    assert sorted(ln for _, ln in codes(out)) != [6, 11]
    code, out, _ = lint(["robot.urdf", "--baseline", "baseline.json"], tmp_path)
    assert code == 0 and codes(out) == []


def test_a_new_finding_fails(tmp_path):
    (tmp_path / "robot.urdf").write_text(ROBOT)
    write_baseline(tmp_path)
    (tmp_path / "robot.urdf").write_text(ROBOT.replace('<link name="hand"/>',
                                                       '<link name="hand"><visul/></link>'))
    code, out, _ = lint(["robot.urdf", "--baseline", "baseline.json"], tmp_path)
    assert code == 1
    found = json.loads(out)["findings"]
    assert len(found) == 1 and found[0]["code"] == "U002" and "visul" in found[0]["message"]


def test_a_second_identical_finding_is_new(tmp_path):
    (tmp_path / "robot.urdf").write_text(ROBOT)
    write_baseline(tmp_path)
    (tmp_path / "robot.urdf").write_text(ROBOT.replace('<origin xyz="0 0 0.5" rpy="0 0 0" rpyy="1"/>',
                                                       '<orign xyz="0 0 0.25"/>'))
    code, out, _ = lint(["robot.urdf", "--baseline", "baseline.json"], tmp_path)
    assert code == 1
    found = json.loads(out)["findings"]
    # the U003 is fixed; of the two identical-message U002, the one on the new line is reported
    assert [(f["code"], f["location"]["line"]) for f in found] == [("U002", 11)]


def test_fixing_findings_keeps_passing(tmp_path):
    (tmp_path / "robot.urdf").write_text(ROBOT)
    write_baseline(tmp_path)
    (tmp_path / "robot.urdf").write_text(ROBOT.replace("orign", "origin"))
    code, out, _ = lint(["robot.urdf", "--baseline", "baseline.json"], tmp_path)
    assert code == 0 and codes(out) == []


def test_reformatted_line_still_matches(tmp_path):
    (tmp_path / "robot.urdf").write_text(ROBOT)
    write_baseline(tmp_path)
    (tmp_path / "robot.urdf").write_text(ROBOT.replace('<orign xyz="0 0 0.5"/>', '<orign   xyz="0 0 0.75" />'))
    code, out, _ = lint(["robot.urdf", "--baseline", "baseline.json"], tmp_path)
    assert code == 0 and codes(out) == []


def test_macro_expansions_are_counted(tmp_path):
    (tmp_path / "robot.urdf.xacro").write_text(MACROS)
    data = write_baseline(tmp_path, "robot.urdf.xacro")
    assert sum(e["count"] for e in data["findings"]) == 2
    code, out, _ = lint(["robot.urdf.xacro", "--baseline", "baseline.json"], tmp_path)
    assert code == 0 and codes(out) == []
    # a third call of the macro: exactly one new finding, attributed to the new call site
    third = MACROS.replace('<xacro:leg prefix="r"/>', '<xacro:leg prefix="r"/>\n  <xacro:leg prefix="m"/>')
    (tmp_path / "robot.urdf.xacro").write_text("\n\n" + third)
    code, out, _ = lint(["robot.urdf.xacro", "--baseline", "baseline.json"], tmp_path)
    assert code == 1
    [f] = json.loads(out)["findings"]
    assert f["location"]["line"] == 7 and f["location"]["via"] == [{"file": "robot.urdf.xacro", "line": 15}]


def test_paths_are_relative_to_the_baseline_file(tmp_path):
    pkg = tmp_path / "pkg" / "urdf"
    pkg.mkdir(parents=True)
    (pkg / "robot.urdf").write_text(ROBOT)
    data = write_baseline(tmp_path, "pkg/urdf/robot.urdf", cwd=tmp_path)
    assert {e["file"] for e in data["findings"]} == {"pkg/urdf/robot.urdf"}
    # run from another working directory: the display paths differ, the baseline still applies
    code, out, _ = lint(["urdf/robot.urdf", "--baseline", "../baseline.json"], tmp_path / "pkg")
    assert code == 0 and codes(out) == []


def test_bad_baseline_is_a_usage_error(tmp_path):
    (tmp_path / "robot.urdf").write_text(ROBOT)
    (tmp_path / "baseline.json").write_text('{"version": 99}')
    code, _, err = lint(["robot.urdf", "--baseline", "baseline.json"], tmp_path)
    assert code == 2 and "cannot read baseline" in err
    code, _, err = lint(["robot.urdf", "--baseline", "missing.json"], tmp_path)
    assert code == 2


def test_message_normalisation():
    assert baseline.normalise_message("duplicate link 'a' (first at line 12)") == "duplicate link 'a' (first at line N)"
    assert baseline.normalise_message("defined in a.xacro:12:3 and b.urdf:7") == "defined in a.xacro:N and b.urdf:N"
    assert baseline.normalise_message("mass 1.5 is fine") == "mass 1.5 is fine"


def test_filter_new_api(tmp_path):
    f1 = Finding("U002", Severity.WARNING, "m", Location("nowhere.urdf", 3))
    f2 = Finding("U002", Severity.WARNING, "m", Location("nowhere.urdf", 9))
    path = str(tmp_path / "b.json")
    baseline.write(path, [f1])
    assert baseline.filter_new(path, [f1]) == []
    assert baseline.filter_new(path, [f1, f2]) == [f2]


def test_a_second_line_of_a_baselined_problem_is_new(tmp_path):
    """Two wrong joint names in one controller file are one finding with an `also` line in the reports; the
    baseline is matched line by line (before findings are grouped), so the added line is new on its own. A guard:
    `--diff-base` once let the same change pass as "unchanged" (tests/diff/test_diff_base.py)."""
    import shutil

    from conftest import REPO

    pkg = tmp_path / "agv"
    shutil.copytree(REPO / "examples" / "agv", pkg)
    ctrl = pkg / "config" / "agv_controllers.yaml"
    ctrl.write_text(ctrl.read_text().replace("[left_wheel_joint]", "[left_wheel_jointX]"))
    code, _, err = run_cli(["lint", "--write-baseline", "baseline.json"], cwd=pkg)
    assert code == 0, err
    assert run_cli(["lint", "--baseline", "baseline.json"], cwd=pkg)[0] == 0
    ctrl.write_text(ctrl.read_text().replace("[right_wheel_joint]", "[right_wheel_jointX]"))
    code, out, _ = run_cli(["lint", "--baseline", "baseline.json", "--format", "json"], cwd=pkg)
    assert code == 1 and [f["code"] for f in json.loads(out)["findings"]] == ["C001"]
    assert [f["location"]["line"] for f in json.loads(out)["findings"]] == [16]  # the new line only
    # written again, the baseline holds both lines
    assert run_cli(["lint", "--write-baseline", "baseline.json"], cwd=pkg)[0] == 0
    assert run_cli(["lint", "--baseline", "baseline.json"], cwd=pkg)[0] == 0
