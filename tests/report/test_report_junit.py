"""JUnit XML: testsuites/testsuite/testcase/failure with correct counts; one case per model x rule family."""
import xml.etree.ElementTree as ET
from pathlib import Path

from conftest import run_cli
from samples import BAD, GOOD

from urdfcheck.core.findings import Finding, Location, Place, Severity
from urdfcheck.report import render
from urdfcheck.rules import catalogue as rulebook
from urdfcheck.run import Result, Target

FAMILIES = sorted({r.family for r in rulebook.catalogue().values()})


def check_counts(root):
    """The counts GitLab and Jenkins read must match the cases written."""
    assert root.tag == "testsuites"
    total = failures = 0
    for suite in root.findall("testsuite"):
        cases = suite.findall("testcase")
        failed = [c for c in cases if c.find("failure") is not None]
        assert int(suite.get("tests")) == len(cases)
        assert int(suite.get("failures")) == len(failed)
        assert int(suite.get("errors")) == 0 and int(suite.get("skipped")) == 0
        total += len(cases)
        failures += len(failed)
    assert int(root.get("tests")) == total
    assert int(root.get("failures")) == failures


def junit(args, cwd):
    code, out, err = run_cli(["lint", "--no-config", "--format", "junit", *args], cwd=cwd)
    assert code in (0, 1), err
    assert out.startswith('<?xml version="1.0" encoding="UTF-8"?>')
    root = ET.fromstring(out.encode("utf-8"))
    check_counts(root)
    return code, root


def test_one_suite_per_model_one_case_per_family(tmp_path):
    (tmp_path / "bad.urdf").write_text(BAD)
    (tmp_path / "good.urdf").write_text(GOOD)
    code, root = junit(["bad.urdf", "good.urdf", "--select", "U"], tmp_path)
    assert code == 1
    suites = {s.get("name"): s for s in root.findall("testsuite")}
    assert set(suites) == {"bad.urdf", "good.urdf"}
    for s in suites.values():
        assert sorted(c.get("name") for c in s.findall("testcase")) == FAMILIES
    bad_cases = {c.get("name"): c for c in suites["bad.urdf"].findall("testcase")}
    fam = rulebook.catalogue()["U002"].family
    failure = bad_cases[fam].find("failure")
    assert failure is not None
    assert failure.get("type") == "warning"
    assert "bad.urdf:5: U002 [warning]" in failure.text and "orign" in failure.text
    assert failure.get("message").startswith("1 finding")
    assert all(c.find("failure") is None for n, c in bad_cases.items() if n != fam)
    assert all(c.find("failure") is None for c in suites["good.urdf"].findall("testcase"))
    assert int(root.get("failures")) == 1
    assert bad_cases[fam].get("file") == "bad.urdf"


def test_clean_model_passes_everything(tmp_path):
    (tmp_path / "good.urdf").write_text(GOOD)
    code, root = junit(["good.urdf", "--select", "U"], tmp_path)
    assert code == 0
    assert root.get("failures") == "0" and int(root.get("tests")) == len(FAMILIES)


def test_findings_below_fail_on_pass_but_are_listed(tmp_path):
    (tmp_path / "bad.urdf").write_text(BAD)
    code, root = junit(["bad.urdf", "--select", "U", "--fail-on", "error"], tmp_path)
    assert code == 0
    assert root.get("failures") == "0"
    outs = [c.find("system-out") for c in root.iter("testcase") if c.find("system-out") is not None]
    assert len(outs) == 1 and "U002" in outs[0].text


def test_variants_are_separate_suites_and_unknown_codes_go_to_other():
    t1 = Target(Path("robot.urdf.xacro"), {"cam": "true"}, variant="cam")
    t2 = Target(Path("robot.urdf.xacro"), {"cam": "false"}, variant="nocam")
    findings = [
        Finding("U002", Severity.WARNING, "m", Location("robot.urdf.xacro", 3), "unknown-element",
                model="robot.urdf.xacro", variant="cam",
                where=(Place("robot.urdf.xacro", "cam"), Place("robot.urdf.xacro", "nocam"))),
        Finding("Z123", Severity.ERROR, "z", Location("robot.urdf.xacro", 4), "zed",
                model="robot.urdf.xacro", variant="nocam"),
    ]
    root = ET.fromstring(render("junit", Result(findings, [t1, t2], {}), fail_on=Severity.WARNING))
    check_counts(root)
    suites = {s.get("name"): s for s in root.findall("testsuite")}
    assert set(suites) == {"robot.urdf.xacro [cam]", "robot.urdf.xacro [nocam]"}
    cam = {c.get("name"): c for c in suites["robot.urdf.xacro [cam]"].findall("testcase")}
    nocam = {c.get("name"): c for c in suites["robot.urdf.xacro [nocam]"].findall("testcase")}
    fam = rulebook.catalogue()["U002"].family
    # a finding of several variants is one line (issue 15), in the first suite, naming where it applies
    assert cam[fam].find("failure") is not None and nocam[fam].find("failure") is None
    assert "in all 2 variants" in cam[fam].find("failure").text
    assert "other" not in cam and nocam["other"].find("failure").get("type") == "error"


def test_no_targets_still_valid():
    root = ET.fromstring(render("junit", Result([], [], {})))
    check_counts(root)
    assert root.get("tests") == "0"
