"""mypy on what type-checks ([tool.mypy] in pyproject.toml): core/, model/, and rules/' registry and engine. The
rest of rules/ is not in yet (about 40 errors, mostly the contract readers' records: see [tool.mypy])."""
from __future__ import annotations

import importlib.util
import subprocess
import sys

import pytest
from conftest import REPO

# the rule registry and engine too: a check is a typed `Check` (rules/catalogue.py), whatever module defines it
TYPED = ["src/urdfcheck/core", "src/urdfcheck/model", "src/urdfcheck/rules/catalogue.py",
         "src/urdfcheck/rules/engine.py"]


@pytest.mark.skipif(importlib.util.find_spec("mypy") is None, reason="mypy not installed (the test extra has it)")
def test_typed_folders_type_check(tmp_path):
    proc = subprocess.run([sys.executable, "-m", "mypy", "--config-file", str(REPO / "pyproject.toml"),
                           "--cache-dir", str(tmp_path / "mypy"), *TYPED], cwd=REPO, capture_output=True, text=True,
                          timeout=600, env={"PATH": "/usr/bin:/bin", "MYPYPATH": str(REPO / "src")})
    assert proc.returncode == 0, proc.stdout + proc.stderr
