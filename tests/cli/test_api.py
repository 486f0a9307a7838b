"""The public Python API (`urdfcheck.lint`) and the request it shares with the CLI: config honoured,
callable any number of times, unusable requests refused with a clear message (exit 2 on the CLI)."""
from __future__ import annotations

import json
import os
from pathlib import Path

import pytest
from conftest import REPO, run_cli
from samples import BAD, GOOD

import urdfcheck

WHEEL = REPO / "examples" / "broken" / "contract_wheel_separation"


def _codes(result) -> list[str]:
    return sorted(f.code for f in result.findings)


def test_lint_honours_the_config_and_can_be_called_again(monkeypatch):
    monkeypatch.chdir(WHEEL)
    first = urdfcheck.lint(".")
    second = urdfcheck.lint(["."])
    assert _codes(first) == _codes(second) == ["C010"]
    assert first.findings == second.findings
    assert first.findings[0].location.file == os.path.join("config", "agv_driver_ros1.yaml")


def test_lint_from_above_uses_the_package_config():
    result = urdfcheck.lint([str(WHEEL)])
    assert _codes(result) == ["C010"]


def test_lint_matches_the_cli(tmp_path):
    (tmp_path / "bad.urdf").write_text(BAD)
    (tmp_path / "good.urdf").write_text(GOOD)
    code, out, _ = run_cli(["lint", "--format", "json", "."], cwd=tmp_path)
    cli = [(f["code"], f["location"]["file"], f["location"]["line"]) for f in json.loads(out)["findings"]]
    old = os.getcwd()
    os.chdir(tmp_path)
    try:
        api = [(f.code, f.location.file, f.location.line) for f in urdfcheck.lint(["."]).findings]
    finally:
        os.chdir(old)
    assert code == 1 and cli and api == cli


def test_options_select_and_rule_options(tmp_path):
    (tmp_path / "bad.urdf").write_text(BAD)
    assert _codes(urdfcheck.lint([tmp_path / "bad.urdf"], select=["U"])) == ["U002"]
    assert _codes(urdfcheck.lint([tmp_path / "bad.urdf"], ignore=["U"])) == []
    with pytest.raises(urdfcheck.UsageError, match="Z999"):
        urdfcheck.lint([tmp_path / "bad.urdf"], select=["Z999"])
    with pytest.raises(urdfcheck.UsageError, match="unknown option"):
        urdfcheck.lint([tmp_path / "bad.urdf"], nonsense=True)
    with pytest.raises(urdfcheck.UsageError, match="tolerance"):
        urdfcheck.lint([tmp_path / "bad.urdf"], rules={"J007": {"tolerence": 1}})


def test_usage_error_is_a_value_error():
    assert issubclass(urdfcheck.UsageError, ValueError)
    with pytest.raises(urdfcheck.UsageError, match="no such file"):
        urdfcheck.lint(["/nonexistent/robot.urdf"])


# --- selection: unknown codes are usage errors --------------------------------------------------------------
@pytest.mark.parametrize("flag", ["--select", "--ignore"])
def test_unknown_code_on_the_command_line_exits_2(tmp_path, flag):
    (tmp_path / "good.urdf").write_text(GOOD)
    code, out, err = run_cli(["lint", "--no-config", flag, "Z999", tmp_path / "good.urdf"])
    assert code == 2 and out == ""
    assert "Z999" in err and "Traceback" not in err


def test_unknown_code_gets_a_did_you_mean(tmp_path):
    (tmp_path / "good.urdf").write_text(GOOD)
    code, _, err = run_cli(["lint", "--no-config", "--select", "J0066", tmp_path / "good.urdf"])
    assert code == 2 and "did you mean 'J006'" in err


def test_known_prefixes_still_select(tmp_path):
    (tmp_path / "bad.urdf").write_text(BAD)
    code, _, err = run_cli(["lint", "--no-config", "--select", "U,J00", tmp_path / "bad.urdf"])
    assert code == 1, err


def test_unknown_code_in_the_config_names_file_and_line(tmp_path):
    (tmp_path / "good.urdf").write_text(GOOD)
    (tmp_path / "urdfcheck.yaml").write_text("fail_on: error\nignore: [S001, Q12]\n")
    code, _, err = run_cli(["lint", "good.urdf"], cwd=tmp_path)
    assert code == 2 and "urdfcheck.yaml:2" in err and "Q12" in err


# --- rule options: declared once, validated where the config is read ----------------------------------------
def test_misspelt_rule_option_exits_2_naming_file_and_line(tmp_path):
    (tmp_path / "good.urdf").write_text(GOOD)
    (tmp_path / "urdfcheck.yaml").write_text("select: [ALL]\nrules:\n  C010:\n    tolerence: 0.002\n")
    code, out, err = run_cli(["lint", "good.urdf"], cwd=tmp_path)
    assert code == 2 and out == ""
    assert "urdfcheck.yaml:4" in err and "tolerence" in err and "did you mean 'tolerance'" in err


def test_rule_option_of_the_wrong_type_exits_2(tmp_path):
    (tmp_path / "good.urdf").write_text(GOOD)
    (tmp_path / "urdfcheck.yaml").write_text("rules:\n  J007:\n    tolerance: wide\n")
    code, _, err = run_cli(["lint", "good.urdf"], cwd=tmp_path)
    assert code == 2 and "urdfcheck.yaml:3" in err and "tolerance" in err


def test_rule_options_of_an_unknown_rule_exit_2(tmp_path):
    (tmp_path / "good.urdf").write_text(GOOD)
    (tmp_path / "urdfcheck.yaml").write_text("rules:\n  J999:\n    tolerance: 1\n")
    code, _, err = run_cli(["lint", "good.urdf"], cwd=tmp_path)
    assert code == 2 and "urdfcheck.yaml:2" in err and "J999" in err


def test_a_valid_rule_option_reaches_the_check(tmp_path):
    # F002 `expected`: the accepted root link names; the default does not accept 'chassis', [chassis] does
    (tmp_path / "r.urdf").write_text('<robot name="r">\n  <link name="chassis"/>\n</robot>\n')
    code, out, err = run_cli(["lint", "--format", "json", "--select", "F002", "r.urdf"], cwd=tmp_path)
    assert [f["code"] for f in json.loads(out)["findings"]] == ["F002"], err
    (tmp_path / "urdfcheck.yaml").write_text("rules:\n  F002:\n    expected: [chassis]\n")
    trust = ["--config", "urdfcheck.yaml", "--trust-config"]  # accepting another name loosens F002: the runner's
    code, out, err = run_cli(["lint", "--format", "json", *trust, "--select", "F002", "r.urdf"], cwd=tmp_path)
    assert code == 0 and json.loads(out)["findings"] == [], err
    code, out, err = run_cli(["lint", "--format", "json", "--select", "F002", "r.urdf"], cwd=tmp_path)
    assert sorted(f["code"] for f in json.loads(out)["findings"]) == ["F002", "X018"], err  # found: refused


def test_every_catalogue_option_is_declared_with_type_default_and_doc():
    from urdfcheck.rules import catalogue

    seen = 0
    for code, info in catalogue.catalogue().items():
        for name, spec in info.option_specs.items():
            seen += 1
            assert spec.type in catalogue.OPTION_TYPES, (code, name)
            assert spec.doc, (code, name)
            assert catalogue.option_ok(spec, spec.default), (code, name)
            assert info.options[name] == spec.default
    assert seen >= 10


# --- workspaces: each package with its own config ------------------------------------------------------------
def _package(folder: Path, name: str, config: str | None) -> None:
    (folder / "urdf").mkdir(parents=True)
    (folder / "package.xml").write_text(f"<package format='3'><name>{name}</name></package>")
    (folder / "urdf" / "robot.urdf").write_text(BAD)
    if config is not None:
        (folder / "urdfcheck.yaml").write_text(config)


def test_workspace_run_uses_each_package_config(tmp_path):
    ws = tmp_path / "ws"
    _package(ws / "src" / "quiet", "quiet", "ignore: [U002]\n")  # hides nothing (issue 36): refused, X018
    _package(ws / "src" / "loud", "loud", None)
    _package(ws / "src" / "strict", "strict", "severity: {U002: error}\n")  # tightening is anyone's right
    code, out, err = run_cli(["lint", "--format", "json", "src"], cwd=ws)
    found = sorted((f["code"], f["location"]["file"], f["severity"]) for f in json.loads(out)["findings"])
    assert ("U002", os.path.join("src", "loud", "urdf", "robot.urdf"), "warning") in found
    assert ("U002", os.path.join("src", "strict", "urdf", "robot.urdf"), "error") in found
    assert ("U002", os.path.join("src", "quiet", "urdf", "robot.urdf"), "warning") in found
    assert ("X018", os.path.join("src", "quiet", "urdfcheck.yaml"), "error") in found
    per_package = []
    for name in ("quiet", "loud", "strict"):
        _, o, _ = run_cli(["lint", "--format", "json"], cwd=ws / "src" / name)
        per_package += [(f["code"], os.path.join("src", name, f["location"]["file"]), f["severity"])
                        for f in json.loads(o)["findings"]]
    assert found == sorted(per_package)


# --- paths in reports --------------------------------------------------------------------------------------
@pytest.mark.parametrize("fmt", ["text", "json", "sarif", "junit", "github", "markdown"])
def test_no_report_prints_an_absolute_path_below_the_working_directory(fmt):
    pkg = REPO / "examples" / "broken" / "contract_wheel_separation"
    code, out, err = run_cli(["lint", "--format", fmt, str(pkg)], cwd=REPO)
    assert code == 1, err
    assert str(REPO) not in out
    code, out, err = run_cli(["lint", "--format", fmt], cwd=pkg)
    assert code == 1, err
    assert str(REPO) not in out


def test_root_flag_sets_where_paths_start(tmp_path):
    (tmp_path / "pkg").mkdir()
    (tmp_path / "pkg" / "bad.urdf").write_text(BAD)
    code, out, _ = run_cli(["lint", "--format", "json", "--root", "pkg", "pkg"], cwd=tmp_path)
    data = json.loads(out)
    assert [m["path"] for m in data["models"]] == ["bad.urdf"]
    assert {f["location"]["file"] for f in data["findings"]} == {"bad.urdf"}


def test_each_package_fails_at_its_own_level(tmp_path):
    # U002 is a warning; a package config may raise its bar (fail_on: info), never lower it: fail_on: error found
    # in the checkout is refused (issue 36)
    ws = tmp_path / "ws"
    _package(ws / "lenient", "lenient", "fail_on: error\n")
    code, out, err = run_cli(["lint", "."], cwd=ws)
    assert code == 1 and "X018" in out, err
    code, _, err = run_cli(["lint", "--config", "lenient/urdfcheck.yaml", "--trust-config", "."], cwd=ws)
    assert code == 0, err  # the runner vouches for it
    code, _, err = run_cli(["lint", "--fail-on", "error", "--no-config", "."], cwd=ws)
    assert code == 0, err
    (ws / "lenient" / "urdfcheck.yaml").write_text("fail_on: info\n")  # raising the bar: kept
    assert urdfcheck.lint([ws], select=["U"], severity={"U002": "info"}).failed()
    (ws / "lenient" / "urdfcheck.yaml").unlink()
    assert urdfcheck.lint([ws], select=["U"], severity={"U002": "info"}).failed() is False


def test_a_launch_file_or_a_yaml_file_lints_the_models_that_use_it():
    pkg = REPO / "examples" / "broken" / "contract_wheel_radius"
    code, out, err = run_cli(["lint", "--format", "json", "launch/agv.launch.xml"], cwd=pkg)
    data = json.loads(out)
    assert code == 1 and [m["path"] for m in data["models"]] == [os.path.join("urdf", "agv.urdf")], err
    assert {f["code"] for f in data["findings"]} == {"C011"}
    code, out, err = run_cli(["lint", "--format", "json", "config/agv_controllers.yaml"], cwd=pkg)
    assert code == 1 and {f["code"] for f in json.loads(out)["findings"]} == {"C011"}, err  # what reads it


def test_a_workspace_config_applies_below_it_unless_a_package_has_its_own(tmp_path):
    ws = tmp_path / "ws"
    _package(ws / "src" / "own", "own", "severity: {U002: warning}\n")  # its own: U002 stays a warning
    _package(ws / "src" / "plain", "plain", None)                      # the workspace config applies
    (ws / "urdfcheck.yaml").write_text("severity: {U002: error}\n")
    code, out, err = run_cli(["lint", "--format", "json", "src"], cwd=ws)
    found = sorted((f["code"], f["location"]["file"], f["severity"]) for f in json.loads(out)["findings"])
    assert found == [("U002", os.path.join("src", "own", "urdf", "robot.urdf"), "warning"),
                     ("U002", os.path.join("src", "plain", "urdf", "robot.urdf"), "error")], err
    _, out2, _ = run_cli(["lint", "--format", "json"], cwd=ws / "src" / "plain")
    assert [(f["code"], f["location"]["file"], f["severity"]) for f in json.loads(out2)["findings"]] == \
        [("U002", os.path.join("urdf", "robot.urdf"), "error")]


def test_no_path_lints_the_folder_here_not_the_whole_workspace_of_the_config(tmp_path):
    ws = tmp_path / "ws"
    _package(ws / "a", "a", None)
    _package(ws / "b", "b", None)
    (ws / "urdfcheck.yaml").write_text("severity: {U002: error}\n")
    _, out, _ = run_cli(["lint", "--format", "json"], cwd=ws / "a")
    assert {f["location"]["file"] for f in json.loads(out)["findings"]} == {os.path.join("urdf", "robot.urdf")}


def test_list_prints_the_plan_without_linting():
    code, out, err = run_cli(["lint", "--list", "examples/agv", "examples/broken/contract_wheel_radius"], cwd=REPO)
    assert code == 0, err
    assert "examples/agv/urdf/agv.urdf.xacro [camera] use_camera:=true  (config examples/agv/urdfcheck.yaml)" in out
    assert "examples/broken/contract_wheel_radius/launch/agv.launch.xml" in out  # a deployment
    assert "4 target(s)" in out and str(REPO) not in out and "C011" not in out
