import json
import os
import sys
from pathlib import Path

import pytest
from hypothesis import settings

# CI must be reproducible: the same examples every run (locally hypothesis explores at random).
settings.register_profile("ci", derandomize=True, print_blob=True)
if os.environ.get("CI"):
    settings.load_profile("ci")

REPO = Path(__file__).resolve().parent.parent

# One folder of tests per stage (tests/<stage>/). A few tests share another test module's helpers by importing
# it (`from test_tf_owners import write`), so each stage folder is importable as tests/ itself is.
STAGE_FOLDERS = ("bag cli consumers core diff finish load model "
                 "plan project publisher report request rules server verify").split()
for _stage in STAGE_FOLDERS:
    if str(REPO / "tests" / _stage) not in sys.path:
        sys.path.append(str(REPO / "tests" / _stage))

# Runs of the console entry (`python -m urdfcheck` in subprocesses) use the lint cache: never the user's own
# cache folder from the test suite, locally or in CI.
if not os.environ.get("URDFCHECK_CACHE_DIR"):
    import tempfile

    os.environ["URDFCHECK_CACHE_DIR"] = tempfile.mkdtemp(prefix="urdfcheck-test-cache-")
CORPUS = Path(os.environ.get("URDFCHECK_CORPUS", REPO.parent / "shared" / "corpus"))


@pytest.fixture
def corpus():
    if not CORPUS.is_dir():
        pytest.skip("shared corpus not present")
    return CORPUS


def run_cli(args, cwd=None):
    """Run the real CLI entry point in-process; returns (exit code, stdout, stderr)."""
    import contextlib
    import io

    from urdfcheck.cli.main import main

    out, err = io.StringIO(), io.StringIO()
    old = os.getcwd()
    try:
        if cwd is not None:
            os.chdir(cwd)
        with contextlib.redirect_stdout(out), contextlib.redirect_stderr(err):
            code = main([str(a) for a in args])
    finally:
        os.chdir(old)
    return code, out.getvalue(), err.getvalue()


def lint_json(args, cwd=None, flat=True):
    """The JSON report. `flat`: the same problem at other lines of a file (`also`, one finding in the report)
    is listed as one finding per line, as the rules found it: what rule tests check."""
    code, out, err = run_cli(["lint", "--format", "json", "--no-config", *args], cwd=cwd)
    assert code in (0, 1), (code, err)
    report = json.loads(out)
    if flat:
        report["findings"] = flatten(report["findings"])
    return code, report


def flatten(findings: list[dict]) -> list[dict]:
    out = []
    for f in findings:
        out.append({k: v for k, v in f.items() if k != "also"})
        out.extend({**out[-1], "location": a["location"], "message": a["message"]} for a in f.get("also", ()))
    return out


def write_example(example: dict, folder: Path) -> Path:
    """Materialise a catalogue example; returns the path to lint."""
    from urdfcheck.rules.catalogue import example_files

    for name, content in example_files(example).items():
        p = folder / name
        p.parent.mkdir(parents=True, exist_ok=True)
        p.write_text(content, encoding="utf-8")
    if example.get("lint"):
        return folder / example["lint"]
    if "urdf" in example:
        return folder / "robot.urdf"
    if "xacro" in example:
        return folder / "robot.urdf.xacro"
    return folder


def example_args(example: dict) -> list[str]:
    out = []
    for k, v in (example.get("args") or {}).items():
        out += ["--arg", f"{k}:={v}"]
    return out + [str(f) for f in example.get("flags") or []]
