"""The pytest plugin: models of a description package become test items in the package's own pytest run."""
import os
from pathlib import Path

import pytest
from samples import BAD, GOOD

import urdfcheck

pytest_plugins = ["pytester"]

XACRO = """<robot name="r" xmlns:xacro="http://www.ros.org/wiki/xacro">
  <xacro:arg name="typo" default="false"/>
  <link name="base_link"/>
  <link name="arm"/>
  <joint name="j" type="fixed">
    <xacro:if value="$(arg typo)"><orign xyz="0 0 1"/></xacro:if>
    <parent link="base_link"/>
    <child link="arm"/>
  </joint>
</robot>
"""


SRC = str(Path(urdfcheck.__file__).resolve().parent.parent)


@pytest.fixture
def pkg(pytester, monkeypatch):
    """A description package. The inner pytest runs in a subprocess (libyaml's C loader does not survive
    pytester's in-process module reset) with only our plugin loaded, whatever else is installed."""
    monkeypatch.setenv("PYTEST_DISABLE_PLUGIN_AUTOLOAD", "1")
    monkeypatch.setenv("PYTHONPATH", os.pathsep.join(filter(None, [SRC, os.environ.get("PYTHONPATH")])))
    # ws/urdfcheck.yaml (above the rootdir: does not turn the plugin on by itself; it may not narrow the rules,
    # issue 36, and BAD, GOOD and XACRO have U002 only); the package ws/pkg is where pytest runs.
    ws = pytester.path / "ws"
    root = ws / "pkg"
    (root / "urdf").mkdir(parents=True)
    (ws / "urdfcheck.yaml").write_text("frames: {base: base_link}\n")
    (root / "test_unit.py").write_text("def test_something():\n    assert True\n")
    monkeypatch.chdir(root)
    pytester.root = root
    return pytester


def run(pytester, *args, plugin=True):
    plugin_args = ("-p", "urdfcheck.pytest_plugin") if plugin else ()
    return pytester.runpytest_subprocess(*plugin_args, "-p", "no:cacheprovider", *args)


def test_inactive_without_config_or_flag(pkg):
    (pkg.root / "urdf" / "bad.urdf").write_text(BAD)
    result = run(pkg, "-v")
    result.assert_outcomes(passed=1)
    assert "urdfcheck" not in result.stdout.str()


def test_flag_discovers_models(pkg):
    (pkg.root / "urdf" / "bad.urdf").write_text(BAD)
    (pkg.root / "urdf" / "good.urdf").write_text(GOOD)
    result = run(pkg, "--urdfcheck", "-v", "--urdfcheck-fail-on", "warning")
    result.assert_outcomes(passed=2, failed=1)
    result.stdout.fnmatch_lines([
        "urdfcheck: 2 model item(s)*",
        "*urdf/bad.urdf::urdfcheck FAILED*",
        "*urdf/good.urdf::urdfcheck PASSED*",
        "*1 urdfcheck finding at or above warning in urdf/bad.urdf",
        "*bad.urdf:5: U002 ?warning? unknown element <orign> in <joint>*",
    ])
    assert "Traceback" not in result.stdout.str()


def test_fail_on_option(pkg):
    (pkg.root / "urdf" / "bad.urdf").write_text(BAD)
    result = run(pkg, "--urdfcheck", "--urdfcheck-fail-on", "error", "-rA")
    result.assert_outcomes(passed=2)
    result.stdout.fnmatch_lines(["*urdfcheck (below the fail level)*", "*bad.urdf:5: U002 ?warning?*"])


def test_config_declares_models_and_variants(pkg):
    (pkg.root / "urdf" / "robot.urdf.xacro").write_text(XACRO)
    (pkg.root / "urdf" / "undeclared.urdf").write_text(BAD)  # not declared: linted all the same (issue 36)
    (pkg.root / "urdfcheck.yaml").write_text(
        "models:\n"
        "  - path: urdf/robot.urdf.xacro\n"
        "    variants:\n"
        "      clean: {typo: 'false'}\n"
        "      typo: {typo: 'true'}\n")
    result = run(pkg, "-v")  # no flag: the config at the rootdir turns the plugin on
    result.assert_outcomes(passed=2, failed=2)
    result.stdout.fnmatch_lines([
        "*urdf/robot.urdf.xacro::urdfcheck?clean? PASSED*",
        "*urdf/robot.urdf.xacro::urdfcheck?typo? FAILED*",
        "*urdf/undeclared.urdf::urdfcheck FAILED*",
        "*robot.urdf.xacro:6: U002 ?warning?*",
        "*undeclared.urdf:5: U002 ?warning?*",
    ])


def test_config_fail_on_and_markers(pkg):
    (pkg.root / "urdf" / "bad.urdf").write_text(BAD)
    # fail_on: error found in the checkout is refused (issue 36): an X018 error on the config's own item, and the
    # model's item fails at warning; the runner's --urdfcheck-fail-on error lets the U002 warning pass, not X018
    (pkg.root / "urdfcheck.yaml").write_text("models:\n  - path: urdf/bad.urdf\nfail_on: error\n")
    result = run(pkg, "-m", "urdfcheck", "-v")
    result.assert_outcomes(failed=2, deselected=1)
    result.stdout.fnmatch_lines(["*urdfcheck.yaml::urdfcheck-config FAILED*", "*X018 ?error? 'fail_on: error'*"])
    result = run(pkg, "-m", "urdfcheck", "--urdfcheck-fail-on", "error")
    result.assert_outcomes(passed=1, failed=1, deselected=1)
    (pkg.root / "urdfcheck.yaml").write_text("models:\n  - path: urdf/bad.urdf\nfail_on: info\n")
    result = run(pkg, "-m", "urdfcheck")
    result.assert_outcomes(failed=1, deselected=1)
    result = run(pkg, "-m", "not urdfcheck")
    result.assert_outcomes(passed=1, deselected=1)


def test_invalid_config_is_a_failing_item(pkg):
    (pkg.root / "urdfcheck.yaml").write_text("models:\n  - path: urdf/missing.urdf\n")
    result = run(pkg, "-v")
    result.assert_outcomes(passed=1, failed=1)
    result.stdout.fnmatch_lines(["*urdfcheck-config FAILED*", "*invalid urdfcheck config*missing.urdf*"])


def test_plugin_can_be_disabled(pkg):
    (pkg.root / "urdf" / "bad.urdf").write_text(BAD)
    (pkg.root / "urdfcheck.yaml").write_text("models:\n  - path: urdf/bad.urdf\nselect: [U]\n")
    result = run(pkg, "-p", "no:urdfcheck.pytest_plugin")  # plugin blocked
    result.assert_outcomes(passed=1)


def test_junit_xml_of_the_package_run(pkg):
    (pkg.root / "urdf" / "bad.urdf").write_text(BAD)
    result = run(pkg, "--urdfcheck", "--junit-xml=out.xml")
    result.assert_outcomes(passed=1, failed=1)
    xml = (pkg.root / "out.xml").read_text()
    assert 'name="urdfcheck"' in xml and "U002" in xml


def test_an_unused_yaml_suppression_fails_the_plugin_like_the_cli(pkg):
    # the suppression bookkeeping runs in the plugin too: one pipeline (R002, as `urdfcheck lint` reports it)
    import shutil

    from conftest import run_cli

    src = Path(__file__).resolve().parents[2] / "examples" / "broken" / "contract_driver_joint_typo"
    for name in ("urdf", "config", "launch"):
        shutil.rmtree(pkg.root / name, ignore_errors=True)
        shutil.copytree(src / name, pkg.root / name)
    shutil.copy(src / "urdfcheck.yaml", pkg.root / "urdfcheck.yaml")
    drv = pkg.root / "config" / "agv_driver_ros1.yaml"
    lines = drv.read_text().splitlines()
    lines[4:4] = ["# urdfcheck: ignore[C001] the typo is fixed upstream"]
    lines[6:6] = ["# urdfcheck: ignore[C010] old separation"]
    drv.write_text("\n".join(lines) + "\n")
    code, out, err = run_cli(["lint", "--select", "C,R"], cwd=pkg.root)
    assert code == 1 and "R002" in out and "agv_driver_ros1.yaml:7" in out, out + err
    result = run(pkg, "-v")
    result.assert_outcomes(passed=1, failed=1)
    result.stdout.fnmatch_lines(["*agv_driver_ros1.yaml:7: R002 ?warning? unused suppression of C010*"])
