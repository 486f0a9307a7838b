"""The rule scaffold writes an entry the catalogue reads and a check the registry accepts."""
import shutil
import subprocess
import sys
from pathlib import Path

import pytest

from urdfcheck.rules.catalogue import read_entries
from urdfcheck.rules.scaffold import scaffold

REPO = Path(__file__).resolve().parents[2]


@pytest.fixture
def checkout(tmp_path):
    (tmp_path / "rules").mkdir()
    shutil.copy(REPO / "rules" / "J007.yaml", tmp_path / "rules")
    checks = tmp_path / "src" / "urdfcheck" / "rules" / "checks"
    checks.mkdir(parents=True)
    shutil.copy(REPO / "src" / "urdfcheck" / "rules" / "checks" / "joints.py", checks)
    return tmp_path


def test_scaffold_writes_a_readable_entry_and_a_check(checkout):
    scaffold(checkout, "J099", "joint-name-too-long", "joints")
    entries = read_entries(checkout / "rules")
    assert entries["J099"]["name"] == "joint-name-too-long" and entries["J099"]["family"] == "joints"
    source = (checkout / "src/urdfcheck/rules/checks/joints.py").read_text()
    assert '@check("J099")\ndef joint_name_too_long(model: Model, ctx: Context) -> Iterator[Problem]:' in source
    compile(source, "joints.py", "exec")


@pytest.mark.parametrize("code,name,module,why", [
    ("J007", "again", "joints", "exists already"),
    ("Q001", "x", "joints", "family letter"),
    ("J098", "Bad_Name", "joints", "lower-case"),
    ("J098", "ok", "nosuch", "no check module"),
])
def test_scaffold_refuses(checkout, code, name, module, why):
    with pytest.raises(ValueError, match=why):
        scaffold(checkout, code, name, module)


def test_scaffold_command_exit_codes(checkout):
    run = [sys.executable, "-m", "urdfcheck.rules.scaffold", "--root", str(checkout), "--module", "joints"]
    assert subprocess.run(run + ["J097", "fine-name"], capture_output=True).returncode == 0
    bad = subprocess.run(run + ["J097", "fine-name"], capture_output=True, text=True)
    assert bad.returncode == 2 and "exists already" in bad.stderr
