"""mypy ([tool.mypy] in pyproject.toml) on core/, model/ and rules/: every check is typed
`(model: Model, ctx: Context) -> Iterator[Problem]` (or `Iterable`), the contract and TF rules too."""
from __future__ import annotations

import importlib.util
import subprocess
import sys

import pytest
from conftest import REPO

TYPED = ["src/urdfcheck/core", "src/urdfcheck/model", "src/urdfcheck/rules"]


@pytest.mark.skipif(importlib.util.find_spec("mypy") is None, reason="mypy not installed (the test extra has it)")
def test_typed_folders_type_check(tmp_path):
    proc = subprocess.run([sys.executable, "-m", "mypy", "--config-file", str(REPO / "pyproject.toml"),
                           "--cache-dir", str(tmp_path / "mypy"), *TYPED], cwd=REPO, capture_output=True, text=True,
                          timeout=600, env={"PATH": "/usr/bin:/bin", "MYPYPATH": str(REPO / "src")})
    assert proc.returncode == 0, proc.stdout + proc.stderr
