"""`ruff check` is clean ([tool.ruff] in pyproject.toml).

CI runs `.ci/run`, which runs only pytest, so the style check is part of the test command: a change that breaks
it fails the suite like any other. ruff is in the `test` extras, so its absence is a failure, not a skip.
"""
import subprocess
import sys
from pathlib import Path

REPO = Path(__file__).resolve().parents[2]


def test_ruff_check_is_clean():
    cmd = [sys.executable, "-m", "ruff", "check", "--no-cache", "--output-format", "concise", str(REPO)]
    proc = subprocess.run(cmd, cwd=REPO, capture_output=True, text=True, timeout=300)
    assert proc.returncode == 0, f"ruff check failed (exit {proc.returncode}):\n{proc.stdout}{proc.stderr}"
