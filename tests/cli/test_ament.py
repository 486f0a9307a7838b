"""`ament_urdfcheck` (ament_lint conventions) and the CMake side `ament_cmake_urdfcheck/` (issue 22)."""
from __future__ import annotations

import os
import shutil
import subprocess
import sys
import xml.etree.ElementTree as ET
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]
SRC = str(ROOT / "src")
AGV = ROOT / "examples" / "agv"
CMAKE_PKG = ROOT / "ament_cmake_urdfcheck"


def env():
    return {**os.environ, "PYTHONPATH": SRC + os.pathsep + os.environ.get("PYTHONPATH", "")}


def ament(*args, cwd):
    return subprocess.run([sys.executable, "-m", "urdfcheck.cli.ament", *map(str, args)], cwd=cwd, env=env(),
                          capture_output=True, text=True, timeout=180)


def colcon_counts(path) -> dict:
    """What colcon-test-result's parse_xunit_xml reads (colcon_test_result/test_result/xunit.py): the root tag is
    testsuite or testsuites; `tests` and `failures` are required non-negative integers on the root."""
    root = ET.parse(path).getroot()
    assert root.tag in ("testsuite", "testsuites")
    out = {}
    for attr, required in (("tests", True), ("failures", True), ("errors", False), ("skipped", False)):
        if required:
            assert attr in root.attrib, attr
        value = int(root.attrib.get(attr, 0))
        assert value >= 0
        out[attr] = value
    return out


def junit_cases(path):
    from junitparser import Failure, JUnitXml

    xml = JUnitXml.fromfile(str(path))
    cases = [(suite.name, case.name, any(isinstance(r, Failure) for r in case.result))
             for suite in xml for case in suite]
    return xml, cases


def test_clean_package_passes(tmp_path):
    pkg = tmp_path / "agv_description"
    shutil.copytree(AGV, pkg)
    xunit = tmp_path / "results" / "agv_description" / "urdfcheck.xunit.xml"
    res = ament("--xunit-file", xunit, cwd=pkg)
    assert res.returncode == 0, res.stdout + res.stderr
    counts = colcon_counts(xunit)
    assert counts["tests"] > 0 and counts["failures"] == 0
    xml, cases = junit_cases(xunit)
    assert xml.name == "agv_description.urdfcheck"  # ament_lint's '<folder>.<test name>'
    assert {s for s, _, _ in cases} >= {"urdf/agv.urdf.xacro [camera]", "urdf/agv.urdf.xacro [no_camera]"}
    assert not any(failed for _, _, failed in cases)


def test_findings_fail_and_are_in_the_junit_file(tmp_path):
    pkg = tmp_path / "joint_limits"
    shutil.copytree(ROOT / "examples/broken/joint_limits", pkg)
    xunit = tmp_path / "out" / "joint_limits" / "urdfcheck.xunit.xml"
    res = ament("--xunit-file", xunit, cwd=pkg)
    assert res.returncode == 1, res.stdout + res.stderr
    counts = colcon_counts(xunit)
    assert counts["failures"] >= 1
    _, cases = junit_cases(xunit)
    assert ("urdf/agv.urdf", "joints", True) in set(cases)
    assert "J00" in xunit.read_text()


def test_exclude_and_usage(tmp_path):
    pkg = tmp_path / "joint_limits"
    shutil.copytree(ROOT / "examples/broken/joint_limits", pkg)
    names = [p.name for p in (pkg / "urdf").iterdir()]
    res = ament("--exclude", *names, "--", ".", cwd=pkg)
    assert res.returncode == 1 and "No files found" in res.stderr  # ament_lint's answer to nothing to check
    res = ament("--exclude", "build", "--", ".", cwd=pkg)
    assert res.returncode == 1  # the broken model is still checked
    assert ament("missing_dir", cwd=pkg).returncode == 2


# --- the CMake side -------------------------------------------------------------------------------------
STUBS = r"""
# what ament_cmake would provide, recorded instead
macro(find_package)
endmacro()
function(ament_register_extension)
  file(APPEND "${RECORD}" "extension=${ARGN}\n")
endfunction()
function(ament_add_test name)
  cmake_parse_arguments(A "" "OUTPUT_FILE;RESULT_FILE;WORKING_DIRECTORY;TIMEOUT" "COMMAND" ${ARGN})
  file(APPEND "${RECORD}" "test=${name}\nresult=${A_RESULT_FILE}\ncwd=${A_WORKING_DIRECTORY}\n")
  file(APPEND "${RECORD}" "timeout=${A_TIMEOUT}\ncommand=${A_COMMAND}\n")
  execute_process(COMMAND ${A_COMMAND} WORKING_DIRECTORY "${A_WORKING_DIRECTORY}" RESULT_VARIABLE rc
                  OUTPUT_QUIET ERROR_QUIET)
  file(APPEND "${RECORD}" "rc=${rc}\n")
endfunction()
function(set_tests_properties name)
  file(APPEND "${RECORD}" "properties=${ARGN}\n")
endfunction()
"""


@pytest.mark.skipif(shutil.which("cmake") is None, reason="cmake not installed")
@pytest.mark.parametrize("example,rc", [("examples/agv", "0"), ("examples/broken/joint_limits", "1")])
def test_cmake_hook_registers_the_linter_test(tmp_path, example, rc):
    pkg = tmp_path / "pkg"
    shutil.copytree(ROOT / example, pkg)
    bin_dir = tmp_path / "bin"
    bin_dir.mkdir()
    tool = bin_dir / "ament_urdfcheck"
    tool.write_text(f'#!/bin/sh\nexec "{sys.executable}" -m urdfcheck.cli.ament "$@"\n')
    tool.chmod(0o755)
    record = tmp_path / "record.txt"
    script = tmp_path / "configure.cmake"
    script.write_text(f'set(RECORD "{record}")\n' + STUBS + f"""
set(PROJECT_NAME "my_description")
set(CMAKE_CURRENT_SOURCE_DIR "{pkg}")
set(CMAKE_BINARY_DIR "{tmp_path / 'build'}")
set(AMENT_TEST_RESULTS_DIR "{tmp_path / 'test_results'}")
set(ament_cmake_urdfcheck_DIR "{CMAKE_PKG / 'cmake'}")
include("{CMAKE_PKG / 'ament_cmake_urdfcheck-extras.cmake'}")
# ament_lint_auto runs the hook in the package's source folder
set(_hook "{CMAKE_PKG / 'cmake' / 'ament_cmake_urdfcheck_lint_hook.cmake'}")
set(CMAKE_CURRENT_LIST_DIR "{pkg}")
include("${{_hook}}")
""")
    e = {**env(), "PATH": f"{bin_dir}{os.pathsep}{os.environ['PATH']}"}
    res = subprocess.run(["cmake", "-P", str(script)], cwd=pkg, env=e, capture_output=True, text=True, timeout=300)
    assert res.returncode == 0, res.stdout + res.stderr
    assert "Added test 'urdfcheck'" in res.stdout + res.stderr
    rec = dict(line.split("=", 1) for line in record.read_text().splitlines())
    assert rec["extension"] == "ament_lint_auto;ament_cmake_urdfcheck;ament_cmake_urdfcheck_lint_hook.cmake"
    assert rec["test"] == "urdfcheck" and rec["cwd"] == str(pkg)
    assert rec["properties"] == "PROPERTIES;LABELS;urdfcheck;linter"
    xunit = tmp_path / "test_results" / "my_description" / "urdfcheck.xunit.xml"
    assert rec["result"] == str(xunit)
    assert f"--xunit-file;{xunit}" in rec["command"] and f"--package;my_description={pkg}" in rec["command"]
    assert rec["rc"] == rc  # the command it registered ran: clean package 0, broken one 1
    counts = colcon_counts(xunit)
    assert (counts["failures"] > 0) == (rc == "1")


@pytest.mark.skipif(shutil.which("cmake") is None, reason="cmake not installed")
def test_cmake_hook_without_models_adds_nothing(tmp_path):
    (tmp_path / "pkg").mkdir()
    record = tmp_path / "record.txt"
    script = tmp_path / "configure.cmake"
    record.write_text("")
    script.write_text(f'set(RECORD "{record}")\n' + STUBS + f"""
set(ament_cmake_urdfcheck_DIR "{CMAKE_PKG / 'cmake'}")
include("{CMAKE_PKG / 'ament_cmake_urdfcheck-extras.cmake'}")
include("{CMAKE_PKG / 'cmake' / 'ament_cmake_urdfcheck_lint_hook.cmake'}")
""")
    res = subprocess.run(["cmake", "-P", str(script)], cwd=tmp_path / "pkg", capture_output=True, text=True,
                         timeout=60)
    assert res.returncode == 0, res.stderr
    assert "test=" not in record.read_text()


def test_cmake_package_files():
    manifest = ET.parse(CMAKE_PKG / "package.xml").getroot()
    assert manifest.findtext("name") == "ament_cmake_urdfcheck"
    assert manifest.find("export/build_type").text == "ament_cmake"
    text = (CMAKE_PKG / "CMakeLists.txt").read_text()
    assert 'CONFIG_EXTRAS "ament_cmake_urdfcheck-extras.cmake"' in text
    tomllib = pytest.importorskip("tomllib")  # Python 3.11+
    scripts = tomllib.loads((ROOT / "pyproject.toml").read_text())["project"]["scripts"]
    assert scripts["ament_urdfcheck"] == "urdfcheck.cli.ament:run"
