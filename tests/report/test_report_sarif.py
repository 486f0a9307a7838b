"""SARIF 2.1.0 output: valid against the official schema and shaped the way GitHub code scanning expects."""
import json
from pathlib import Path

import jsonschema
import pytest
from conftest import run_cli
from samples import BAD, MACROS

from urdfcheck.core.findings import Finding, Location, Severity
from urdfcheck.report import render
from urdfcheck.rules import catalogue as rulebook
from urdfcheck.run import Result, Target

SCHEMA = json.loads((Path(__file__).parent.parent / "data" / "sarif-schema-2.1.0.json").read_text(encoding="utf-8"))


def validate(doc):
    jsonschema.Draft4Validator(SCHEMA, format_checker=jsonschema.FormatChecker()).validate(doc)


def sarif(args, cwd):
    code, out, err = run_cli(["lint", "--format", "sarif", "--no-config", *args], cwd=cwd)
    assert code in (0, 1), err
    doc = json.loads(out)
    validate(doc)
    return code, doc


def test_schema_copy_is_the_official_one():
    assert SCHEMA["$schema"].startswith("http://json-schema.org/draft-04/schema")
    assert "2.1.0" in SCHEMA["properties"]["version"]["enum"]


def test_cli_sarif_is_valid_and_complete(tmp_path):
    (tmp_path / "urdf").mkdir()
    (tmp_path / "urdf" / "bad.urdf").write_text(BAD)
    code, doc = sarif(["urdf/bad.urdf", "--select", "U"], tmp_path)
    assert code == 1
    assert doc["version"] == "2.1.0" and len(doc["runs"]) == 1
    run = doc["runs"][0]
    driver = run["tool"]["driver"]
    assert driver["name"] == "urdfcheck" and driver["version"] and driver["informationUri"].startswith("http")
    [res] = [r for r in run["results"] if r["ruleId"] == "U002"]
    assert res["level"] == "warning"
    assert driver["rules"][res["ruleIndex"]]["id"] == "U002"
    loc = res["locations"][0]["physicalLocation"]
    assert loc["artifactLocation"] == {"uri": "urdf/bad.urdf", "uriBaseId": "%SRCROOT%"}
    assert loc["region"]["startLine"] == 5
    assert "orign" in res["message"]["text"]
    assert list(res["partialFingerprints"]) == ["urdfcheck/v1"]


def test_rule_metadata_comes_from_the_catalogue(tmp_path):
    (tmp_path / "bad.urdf").write_text(BAD)
    _, doc = sarif(["bad.urdf"], tmp_path)
    rules = {r["id"]: r for r in doc["runs"][0]["tool"]["driver"]["rules"]}
    cat = rulebook.catalogue()
    assert set(cat) <= set(rules)
    for code, info in cat.items():
        r = rules[code]
        assert r["name"] == info.name
        assert r["shortDescription"]["text"] == " ".join(info.summary.split())
        assert r["fullDescription"]["text"] == " ".join(info.rationale.split())
        assert r["defaultConfiguration"]["level"] == {"error": "error", "warning": "warning", "info": "note"}[
            str(info.severity)]
        assert " ".join(info.fix.split())[:40] in " ".join(r["help"]["text"].split())
        assert "**Use instead.**" in r["help"]["markdown"]
        if info.examples.get("fail"):
            assert "Fails:" in r["help"]["text"] and "```" in r["help"]["markdown"]
    ids = [r["id"] for r in doc["runs"][0]["tool"]["driver"]["rules"]]
    assert len(ids) == len(set(ids))


def test_macro_call_sites_become_related_locations(tmp_path):
    (tmp_path / "robot.urdf.xacro").write_text(MACROS)
    _, doc = sarif(["robot.urdf.xacro", "--trusted", "--select", "U002"], tmp_path)
    results = doc["runs"][0]["results"]
    # one problem in the macro body, expanded by two calls: one result at the body, its first call related
    assert len(results) == 1
    assert results[0]["locations"][0]["physicalLocation"]["region"]["startLine"] == 5
    assert results[0]["relatedLocations"][0]["physicalLocation"]["region"]["startLine"] == 11


def _result(findings, targets=None):
    return Result(findings, targets if targets is not None else [Target(Path("robot.urdf"))], {})


def test_levels_region_and_absolute_paths():
    findings = [
        Finding("U005", Severity.ERROR, "bad", Location("a dir/robot.urdf", 3, 7), "bad-number",
                related=(Location("other.xacro", 9),)),
        Finding("F002", Severity.INFO, "root", Location("robot.urdf"), "unexpected-root-name"),
        Finding("Z999", Severity.WARNING, "no catalogue entry", Location("/abs/pa th/robot.urdf", 1), "zed"),
    ]
    doc = json.loads(render("sarif", _result(findings)))
    validate(doc)
    res = doc["runs"][0]["results"]
    assert [r["level"] for r in res] == ["error", "note", "warning"]
    first = res[0]["locations"][0]["physicalLocation"]
    assert first["artifactLocation"]["uri"] == "a%20dir/robot.urdf"
    assert first["region"] == {"startLine": 3, "startColumn": 7}
    assert res[0]["relatedLocations"][0]["physicalLocation"]["region"]["startLine"] == 9
    assert "region" not in res[1]["locations"][0]["physicalLocation"]  # no line: no region
    third = res[2]["locations"][0]["physicalLocation"]["artifactLocation"]
    assert third == {"uri": "file:///abs/pa%20th/robot.urdf"}
    rules = doc["runs"][0]["tool"]["driver"]["rules"]
    assert rules[res[2]["ruleIndex"]]["id"] == "Z999"


def test_fingerprints_ignore_line_numbers():
    a = Finding("U002", Severity.WARNING, "unknown element <orign> (first seen at line 4)", Location("r.urdf", 5))
    b = Finding("U002", Severity.WARNING, "unknown element <orign> (first seen at line 40)", Location("r.urdf", 50))
    fa = json.loads(render("sarif", _result([a])))["runs"][0]["results"][0]["partialFingerprints"]
    fb = json.loads(render("sarif", _result([b])))["runs"][0]["results"][0]["partialFingerprints"]
    assert fa == fb
    c = Finding("U002", Severity.WARNING, "unknown element <orign>", Location("other.urdf", 5))
    fc = json.loads(render("sarif", _result([c])))["runs"][0]["results"][0]["partialFingerprints"]
    assert fc != fa


def test_empty_run_is_valid(tmp_path):
    (tmp_path / "ok.urdf").write_text('<robot name="r"><link name="base_link"/></robot>\n')
    code, doc = sarif(["ok.urdf", "--select", "U"], tmp_path)
    assert code == 0
    assert doc["runs"][0]["results"] == []


@pytest.mark.parametrize("fmt", ["sarif"])
def test_output_flag_writes_file(tmp_path, fmt):
    (tmp_path / "bad.urdf").write_text(BAD)
    code, out, _ = run_cli(["lint", "--no-config", "--format", fmt, "-o", "r.sarif", "bad.urdf"], cwd=tmp_path)
    assert code == 1 and out == ""
    validate(json.loads((tmp_path / "r.sarif").read_text()))
