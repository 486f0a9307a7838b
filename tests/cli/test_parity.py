"""One pipeline: every front end gives the same findings.

Each package under examples/ and a sample of corpus repositories goes through
* the CLI, run from inside the package (`urdfcheck lint --format json`),
* the Python API, twice in one process (`urdfcheck.lint(["."])`),
* the pytest plugin (`pytest --urdfcheck` with the package as rootdir, every finding listed),
* a workspace run from above (`urdfcheck lint <folder holding the packages>`),
and the findings, compared as (code, file, line) with files made absolute, must agree. The workspace run is
compared with the union over its packages (a shared macro file seen from two packages is one finding there).
"""
from __future__ import annotations

import json
import os
import re
from collections import Counter
from pathlib import Path

import pytest
from conftest import CORPUS, REPO, run_cli

import urdfcheck

EXAMPLES = REPO / "examples"
EXAMPLE_PACKAGES = sorted(p.parent for p in EXAMPLES.rglob("package.xml"))
# corpus repositories, each a small workspace of packages; a sample that keeps this test to seconds
CORPUS_SAMPLE = ("ROBOTIS-GIT+turtlebot3", "ros+urdf_tutorial", "PickNikRobotics+ros2_robotiq_gripper",
                 "linorobot+linorobot2")  # the last: launch files in one package deploy models of another
SRC = str(Path(urdfcheck.__file__).resolve().parent.parent)


def _key(code: str, file: str, line, base: Path) -> tuple:
    return code, os.path.realpath(os.path.join(base, file)), line


def cli_findings(folder: Path, *paths) -> Counter | None:
    """None when the CLI finds nothing to lint there (exit 2, 'no ... model found')."""
    code, out, err = run_cli(["lint", "--format", "json", *paths], cwd=folder)
    if code == 2 and "model found" in err:
        return None
    assert code in (0, 1), (folder, code, err)
    data = json.loads(out)
    for m in data["models"]:
        assert not os.path.isabs(m["path"]) or not m["path"].startswith(str(folder)), m["path"]
    return Counter(_key(f["code"], f["location"]["file"], f["location"]["line"], folder)
                   for f in data["findings"])


def api_findings(folder: Path) -> Counter | None:
    old = os.getcwd()
    os.chdir(folder)
    try:
        try:
            result = urdfcheck.lint(["."])
        except urdfcheck.UsageError as e:
            assert "model found" in str(e)
            return None
        return Counter(_key(f.code, f.location.file, f.location.line, folder) for f in result.findings)
    finally:
        os.chdir(old)


_PLUGIN_LINE = re.compile(r"^(?P<file>\S.*?)(?::(?P<line>\d+))?(?::\d+)?: (?P<code>[A-Z]\d{3}) "
                          r"\[(?:error|warning|info)\] ")


def plugin_findings(folder: Path, tmp: Path, capsys, monkeypatch) -> set:
    """The plugin in a pytest session of its own (rootdir = the package, in this process: a subprocess per
    package costs more than the lint), every finding at or above info listed."""
    ini = tmp / "pytest.ini"
    ini.write_text("[pytest]\n")
    monkeypatch.setenv("PYTEST_DISABLE_PLUGIN_AUTOLOAD", "1")  # only the plugin under test, loaded once
    monkeypatch.chdir(folder)
    capsys.readouterr()
    code = pytest.main(["-p", "urdfcheck.pytest_plugin", "-p", "no:cacheprovider", "--urdfcheck",
                        "--urdfcheck-fail-on", "info", "-c", str(ini), "--rootdir", str(folder), "-q",
                        "-m", "urdfcheck", "-p", "no:randomly", str(folder)])
    out = capsys.readouterr().out
    monkeypatch.undo()
    assert "Traceback" not in out and "internal error" not in out, out
    assert code in (0, 1, 5), out  # 5: nothing collected (no model in the package)
    found = set()
    for line in out.splitlines():
        m = _PLUGIN_LINE.match(line.strip())
        if m:
            found.add(_key(m["code"], m["file"], int(m["line"]) if m["line"] else None, folder))
    return found


def _packages_below(folder: Path) -> list[Path]:
    return sorted(p.parent for p in folder.rglob("package.xml"))


def check_parity(workspace: Path, packages: list[Path], tmp: Path, capsys=None, monkeypatch=None) -> None:
    union: set = set()
    for pkg in packages:
        cli = cli_findings(pkg)
        api1, api2 = api_findings(pkg), api_findings(pkg)
        assert api1 == cli, pkg
        assert api2 == cli, pkg
        if capsys is not None:
            assert plugin_findings(pkg, tmp, capsys, monkeypatch) == set(cli or ()), pkg
        union |= set(cli or ())
    from_above = cli_findings(workspace.parent, workspace.name)
    assert set(from_above or ()) == union, workspace


def test_examples_parity(tmp_path, capsys, monkeypatch):
    assert len(EXAMPLE_PACKAGES) > 10
    check_parity(EXAMPLES, EXAMPLE_PACKAGES, tmp_path, capsys, monkeypatch)


@pytest.mark.parametrize("repo", CORPUS_SAMPLE)
def test_corpus_parity(repo, tmp_path, capsys, monkeypatch):
    if not (CORPUS / repo).is_dir():
        pytest.skip("shared corpus not present")
    check_parity(CORPUS / repo, _packages_below(CORPUS / repo), tmp_path, capsys, monkeypatch)


def test_a_config_finding_is_found_by_the_api_too():
    # the API reads urdfcheck.yaml like the CLI: the declared driver makes C010
    pkg = EXAMPLES / "broken" / "contract_wheel_separation"
    codes = [k[0] for k in api_findings(pkg)]
    assert codes == ["C010"]
