"""The lint cache on a miss (cli/cache.py, load/reuse.py): each stored xacro expansion whose own files are all
unchanged is taken instead of expanding again, whatever the command line; the report is the same as without
the cache."""
from __future__ import annotations

import json
import shutil

import pytest
from test_cache import AGV, cli, entries, expansions

from urdfcheck.load import reuse, stored


@pytest.fixture
def pkg(tmp_path):
    dst = tmp_path / "agv"
    shutil.copytree(AGV, dst)
    return dst


def _edit_wheel_radius(pkg, value: str) -> None:
    yaml_file = pkg / "config" / "agv_controllers.yaml"
    text = yaml_file.read_text()
    assert "wheel_radius: 0.1" in text
    yaml_file.write_text(text.replace("wheel_radius: 0.1", f"wheel_radius: {value}", 1))


def test_a_parameter_edit_reuses_every_expansion_and_starts_no_worker(pkg, tmp_path):
    c = tmp_path / "cache"
    cold = cli(["lint", "."], pkg, c, raw=True)
    assert cold[0] == 0 and cold[3][-1] == "urdfcheck: cache stored (xacro expansions: 0 reused, 2 expanded)"
    _edit_wheel_radius(pkg, "0.12")
    edited = cli(["lint", "."], pkg, c, raw=True, flags=("-X", "importtime"))
    assert edited[3][0].endswith("; its 2 expansion(s) are stored, no xacro worker"), edited[3]
    assert edited[3][-1] == "urdfcheck: cache stored (xacro expansions: 2 reused, 0 expanded)"
    imported = [ln.rsplit("|", 1)[-1].strip() for ln in edited[2].splitlines() if ln.startswith("import time:")]
    assert "urdfcheck.run" in imported and "xacro" not in imported  # no process of the run imported xacro
    plain = cli(["lint", "."], pkg, c, env={"URDFCHECK_NO_CACHE": "1"})
    assert edited[0] == plain[0] == 1 and "C011" in plain[1]  # the wheel radius no longer matches the URDF
    assert edited[1] == plain[1]


def test_a_macro_edit_expands_again_only_the_models_that_include_it(tmp_path):
    pkg = tmp_path / "two"
    (pkg / "urdf" / "macros").mkdir(parents=True)
    (pkg / "package.xml").write_text("<package format='3'><name>two</name></package>")
    xmlns = "xmlns:xacro='http://www.ros.org/wiki/xacro'"
    (pkg / "urdf" / "macros" / "arm.xacro").write_text(
        f"<robot {xmlns}><xacro:macro name='arm'><link name='arm_link'/></xacro:macro></robot>")
    (pkg / "urdf" / "a.urdf.xacro").write_text(
        f"<robot name='a' {xmlns}><xacro:include filename='macros/arm.xacro'/>"
        "<link name='base'/><xacro:arm/><joint name='j' type='fixed'><parent link='base'/>"
        "<child link='arm_link'/></joint></robot>")
    (pkg / "urdf" / "b.urdf.xacro").write_text(
        f"<robot name='b' {xmlns}><xacro:property name='n' value='base'/><link name='${{n}}'/></robot>")
    c = tmp_path / "cache"
    cold = cli(["lint", "."], pkg, c, raw=True)
    assert cold[3][-1] == "urdfcheck: cache stored (xacro expansions: 0 reused, 2 expanded)", cold
    arm = pkg / "urdf" / "macros" / "arm.xacro"
    arm.write_text(arm.read_text().replace("arm_link", "tool_link"))  # a.urdf.xacro now names a missing link
    edited = cli(["lint", "."], pkg, c, raw=True)
    assert edited[3][0].endswith("; 1 of its 2 expansion(s) are stored"), edited[3]
    assert edited[3][-1] == "urdfcheck: cache stored (xacro expansions: 1 reused, 1 expanded)"
    plain = cli(["lint", "."], pkg, c, env={"URDFCHECK_NO_CACHE": "1"})
    assert edited[:3] == plain[:3] and edited[0] == 1 and "arm_link" in plain[1]


def _module_changed(entry) -> None:
    for item in entry["observed"]:
        if item[0] == "m" and "/xacro/" in item[1]:
            item[2] = "0:0"
            return
    raise AssertionError("no xacro module in the stored expansion")


def _not_a_result(entry) -> None:
    entry["result"]["suppressions"] = [[7, 1, 2, ["G001"], 1]]  # names a file the result lacks


def _damaged(entry) -> None:
    entry["result"]["xml"] = "<robot name='other'/>"  # the checksum no longer matches


@pytest.mark.parametrize("change", [_module_changed, _not_a_result, _damaged],
                         ids=["installed-xacro-changed", "malformed", "damaged"])
def test_a_stored_expansion_is_not_taken_when(pkg, tmp_path, change):
    c = tmp_path / "cache"
    cli(["lint", "."], pkg, c)
    stored = expansions(c)
    assert len(stored) == 2
    for path in stored:
        entry = json.loads(path.read_text())
        change(entry)
        if change is not _damaged:  # well-formed, so only the reuse checks can refuse it
            entry["sum"] = reuse._checksum(entry)
        path.write_text(json.dumps(entry))
    _edit_wheel_radius(pkg, "0.12")
    edited = cli(["lint", "."], pkg, c, raw=True)
    assert "no xacro worker" not in edited[3][0], edited[3]
    assert edited[3][-1] == "urdfcheck: cache stored (xacro expansions: 0 reused, 2 expanded)"
    assert edited[:3] == cli(["lint", "."], pkg, c, env={"URDFCHECK_NO_CACHE": "1"})[:3]


def test_another_command_line_takes_the_stored_expansions(pkg, tmp_path):
    """pre-commit names the files a commit changed: each commit is another command line, and so another report
    key, but the expansions are the same."""
    c = tmp_path / "cache"
    cli(["lint", "."], pkg, c)
    (report,) = entries(c)
    _edit_wheel_radius(pkg, "0.12")
    named = cli(["lint", "config/agv_controllers.yaml"], pkg, c, raw=True)
    assert named[3][0] == "urdfcheck: cache miss", named[3]  # a new key: no report to replay
    assert named[3][-1].startswith("urdfcheck: cache stored (xacro expansions: 2 reused, 0 expanded)"), named[3]
    assert named[:3] == cli(["lint", "config/agv_controllers.yaml"], pkg, c, env={"URDFCHECK_NO_CACHE": "1"})[:3]
    assert "C011" in named[1]


def test_a_result_reads_back_as_the_worker_returned_it():
    result = {"xml": "<robot name='r'/>", "files": ["/p/a.urdf.xacro", "/p/m.xacro"], "deps": ["/p/m.xacro"],
              "suppressions": [(1, 3, 9, ("G001", "J002"), 2)], "warnings": [("warning", "deprecated", "1:4"),
                                                                             ("error", "x", None)],
              "args": {"use_camera": "true", "prefix": None}, "xml_warnings": [(0, "X003", "BOM", 1)],
              "observed": [("r", "/p/a.urdf.xacro"), ("l", "/p")]}
    back = stored.from_json(json.loads(json.dumps(stored.to_json(result))))
    assert back == result
    failed = {"error": {"code": "X010", "message": "undefined macro", "marker": "0:3"}, "files": ["/p/a.urdf.xacro"],
              "suppressions": [], "warnings": [], "args": {}, "xml_warnings": [], "observed": []}
    assert stored.from_json(json.loads(json.dumps(stored.to_json(failed)))) == failed
    assert stored.from_json({**stored.to_json(failed), "xml": "<robot/>"}) is None  # an error has no text
    assert stored.from_json({**stored.to_json(result), "code": "import os"}) is None  # no field of its own
