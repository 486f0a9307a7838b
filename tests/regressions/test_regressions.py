"""Every input that once crashed, hung or leaked (found by fuzz/fuzz_lint.py or by hand) stays fixed.

One file per crash in this folder, named `<id><suffix>`; the suffix says how it is linted:

    .urdf / .urdf.xacro      linted by path, alone in a package
    .controllers.yaml        as config/controllers.yaml of a package with a small two-wheel URDF (`lint DIR`)
    .launch.xml              as launch/bringup.launch.xml of that package (`lint DIR`)

`python3 fuzz/fuzz_lint.py --export CRASH tests/regressions/` writes such a file from a libFuzzer artefact.
Each must lint with exit code 0 or 1, no traceback or internal error, a schema-valid JSON report, within
the time bound, and create nothing in the working directory.
"""
import json
import os
import time
from pathlib import Path

import pytest
from conftest import REPO, run_cli

HERE = Path(__file__).resolve().parent
SUFFIXES = (".urdf.xacro", ".urdf", ".controllers.yaml", ".launch.xml")
BOUND = float(os.environ.get("URDFCHECK_REGRESSION_BOUND", "20"))
BASE_URDF = (REPO / "fuzz" / "base.urdf").read_text(encoding="utf-8")  # the harness's package model


def cases():
    return sorted(p for p in HERE.iterdir() if p.is_file() and p.name.endswith(SUFFIXES))


def _place(case: Path, root: Path) -> Path:
    pkg = root / "ws" / "fuzz_description"
    for d in ("urdf", "config", "launch"):
        (pkg / d).mkdir(parents=True)
    (pkg / "package.xml").write_text("<package format='3'><name>fuzz_description</name></package>\n")
    data = case.read_bytes()
    if case.name.endswith((".urdf", ".urdf.xacro")):
        target = pkg / "urdf" / ("robot.urdf.xacro" if case.name.endswith(".xacro") else "robot.urdf")
        target.write_bytes(data)
        return target
    (pkg / "urdf" / "robot.urdf").write_text(BASE_URDF)
    if case.name.endswith(".controllers.yaml"):
        (pkg / "config" / "controllers.yaml").write_bytes(data)
    else:
        (pkg / "launch" / "bringup.launch.xml").write_bytes(data)
    return pkg


def test_regression_files_are_named_by_kind():
    for p in HERE.iterdir():
        if p.is_file() and p.suffix not in (".py", ".md") and not p.name.endswith(SUFFIXES):
            pytest.fail(f"{p.name}: unknown kind (use one of {', '.join(SUFFIXES)})")


@pytest.mark.parametrize("case", cases(), ids=lambda p: p.name)
def test_regression(case, tmp_path):
    import jsonschema

    schema = json.loads((REPO / "src" / "urdfcheck" / "schemas" / "report.schema.json").read_text())
    target = _place(case, tmp_path)
    before = sorted(os.listdir(tmp_path))
    t0 = time.monotonic()
    code, out, err = run_cli(["lint", "--no-config", "--format", "json", os.path.relpath(target, tmp_path)],
                             cwd=tmp_path)
    took = time.monotonic() - t0
    assert code in (0, 1), err
    assert "Traceback" not in err and "internal error" not in err, err
    assert took <= BOUND, f"{took:.1f} s"
    jsonschema.validate(json.loads(out), schema)
    assert sorted(os.listdir(tmp_path)) == before
    for fmt in ("text", "sarif", "junit", "github", "markdown"):
        code, out, err = run_cli(["lint", "--no-config", "--format", fmt, "--color", "never",
                                  os.path.relpath(target, tmp_path)], cwd=tmp_path)
        assert code in (0, 1) and "internal error" not in err, (fmt, err)
        assert "\x1b" not in out and not any(ln.startswith("::") for ln in out.splitlines() if fmt != "github")
