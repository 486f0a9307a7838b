"""What the tests of git-backed commands share: the CLI in a subprocess (temp files in the test's folder), git with
the runner's GIT_* variables removed and a fixed author, and an in-place edit that must find its text."""
from __future__ import annotations

import os
import subprocess
import sys
from pathlib import Path

SRC = str(Path(__file__).resolve().parents[1] / "src")


def lint(*args, cwd, tmp):
    env = {**os.environ, "PYTHONPATH": SRC + os.pathsep + os.environ.get("PYTHONPATH", ""), "TMPDIR": str(tmp)}
    return subprocess.run([sys.executable, "-m", "urdfcheck", "lint", *map(str, args)], capture_output=True,
                          text=True, cwd=cwd, env=env, timeout=180)


def git(*args, cwd):
    env = {**{k: v for k, v in os.environ.items() if not k.startswith("GIT_")}, "GIT_AUTHOR_NAME": "t",
           "GIT_AUTHOR_EMAIL": "t@t", "GIT_COMMITTER_NAME": "t", "GIT_COMMITTER_EMAIL": "t@t"}
    subprocess.run(["git", *args], cwd=cwd, check=True, capture_output=True, env=env)


def edit(path: Path, old: str, new: str) -> None:
    text = path.read_text()
    assert old in text, old
    path.write_text(text.replace(old, new))
