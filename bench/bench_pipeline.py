"""A cold `urdfcheck lint` of a package against the pipeline a user would otherwise run for the same variants
(issue 38, answering issue 21): stock `xacro` then Debian's `check_urdf`, once per model and argument set.

    python bench/bench_pipeline.py [PACKAGE ...] [--runs 7]

For each package (default: examples/agv and, when the shared corpus is present, a few of its description
packages), the plan of `urdfcheck lint PACKAGE` (the models, variants and deployments' xacro arguments it would
lint) is turned into a shell script: for each target, the xacro CLI (with `$(find)` answered from the plan's
package map, as ament would) into a temporary file, then `check_urdf` on it. Ours is `urdfcheck lint --no-cache
PACKAGE`. Both run in turn (A B A B ...), medians of the pair ratios of CPU and wall time; the goal is CPU <= 1.0x.
Nothing is asserted: this prints. Skipped without check_urdf (Debian liburdfdom-tools).
"""
from __future__ import annotations

import argparse
import os
import shlex
import shutil
import sys
import tempfile
from pathlib import Path

HERE = Path(__file__).resolve().parent
REPO = HERE.parent
sys.path.insert(0, str(HERE))

from timing import paired, paired_line  # noqa: E402

PY = sys.executable
CORPUS = REPO.parent / "shared" / "corpus"
DEFAULTS = [REPO / "examples" / "agv",
            CORPUS / "ROBOTIS-GIT+turtlebot3" / "turtlebot3_description",
            CORPUS / "linorobot+linorobot2" / "linorobot2_description",
            CORPUS / "ros+urdf_tutorial"]


def plan_targets(pkg: Path) -> list:
    sys.path.insert(0, str(REPO / "src"))
    from urdfcheck.plan.plan import plan
    from urdfcheck.request.request import make_request

    cwd = os.getcwd()
    try:
        os.chdir(pkg)
        return [t for t in plan(make_request(["."])) if not getattr(t, "library", False)]
    finally:
        os.chdir(cwd)


def peer_script(targets, pkg: Path, tmp: Path, check_urdf: str) -> Path:
    """One shell script: xacro then check_urdf for every planned target (a plain URDF: check_urdf alone)."""
    lines = ["set -u"]
    for i, t in enumerate(targets):
        path = Path(pkg, t.path) if not os.path.isabs(t.path) else Path(t.path)
        out = tmp / f"variant{i}.urdf"
        if str(path).endswith(".xacro"):
            finds = {str(k): str(v) for k, v in dict(t.packages).items()}
            code = ("import sys, xacro, xacro.substitution_args as s;"
                    f"m={finds!r};"
                    f"s._eval_find=lambda p: m.get(p, {str(pkg)!r});"
                    f"sys.argv=['xacro', {str(path)!r}, *{[f'{k}:={v}' for k, v in dict(t.args).items()]!r}];"
                    "xacro.main()")
            lines.append(f"{shlex.quote(PY)} -c {shlex.quote(code)} > {shlex.quote(str(out))} 2>/dev/null "
                         f"&& {shlex.quote(check_urdf)} {shlex.quote(str(out))} > /dev/null 2>&1")
        else:
            lines.append(f"{shlex.quote(check_urdf)} {shlex.quote(str(path))} > /dev/null 2>&1")
    lines.append("exit 0")
    script = tmp / "pipeline.sh"
    script.write_text("\n".join(lines) + "\n")
    return script


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("packages", nargs="*", type=Path)
    ap.add_argument("--runs", type=int, default=7)
    ns = ap.parse_args()
    # Debian's C++ check_urdf by absolute path first: in an activated venv the first on PATH is the pin wheel's
    # Python wrapper (~80 ms a call), which would make the peer look 2.5x slower than the one users run.
    check_urdf = "/usr/bin/check_urdf" if os.path.exists("/usr/bin/check_urdf") else shutil.which("check_urdf")
    if check_urdf is None:
        print("skipped: check_urdf (Debian liburdfdom-tools) is not installed")
        return 0
    env = dict(os.environ)
    env["PYTHONPATH"] = os.pathsep.join(p for p in (str(REPO / "src"), env.get("PYTHONPATH")) if p)
    env.pop("PYTHONDONTWRITEBYTECODE", None)
    pycache = tempfile.TemporaryDirectory(prefix="urdfcheck-bench-pyc-")
    env["PYTHONPYCACHEPREFIX"] = pycache.name
    print(f"{ns.runs} pairs (A B A B ...) after a warm-up each; load average {os.getloadavg()[0]:.1f} on "
          f"{os.cpu_count()} cores; goal: CPU <= 1.0x")
    for pkg in ns.packages or DEFAULTS:
        if not pkg.is_dir():
            print(f"{pkg}: absent, skipped")
            continue
        targets = plan_targets(pkg)
        with tempfile.TemporaryDirectory(prefix="urdfcheck-bench-pipeline-") as tmp:
            script = peer_script(targets, pkg, Path(tmp), check_urdf)
            ours = [PY, "-m", "urdfcheck", "lint", "--no-cache", "--quiet", "."]
            label = f"{pkg.name} ({len(targets)} variants) vs xacro+check_urdf"
            cwd = os.getcwd()
            try:
                os.chdir(pkg)
                paired_line(label, paired(ours, ["bash", str(script)], ns.runs, env=env), None, 1.0)
            finally:
                os.chdir(cwd)
    return 0


if __name__ == "__main__":
    sys.exit(main())
