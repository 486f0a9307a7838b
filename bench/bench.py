"""Lint benchmarks: urdfcheck against its peers, measured in the same run on this machine.

    python bench/bench.py [--runs 11]

Each comparison runs ours and the peer in turn (A B A B ..., after one warm-up each) and prints the medians of
wall and CPU time and the median of the pair ratios: on a shared machine the pairs keep the ratio meaningful.
Goals from issue 21 (cold runs: --no-cache):
  (a) `urdfcheck lint` on the AGV xacro vs the xacro CLI on the same file     wall <= 1.3x, CPU <= 1.8x
  (a') the AGV package with its config, three models (information only)
  (b) `urdfcheck lint` on a plain UR5 URDF vs `python -c pass`               <= 3x
  (b') the same UR5 inside its package (contracts)                            <= 3x
  (c) `urdfcheck lint` on a generated 10,000-link URDF vs Debian's check_urdf <= 1.5x; peak memory per link
      (10,000 minus 1,000 links) <= check_urdf's
  (d) 10,000 links vs 1,000 links (linear growth)                            <= 12x
  (f) the lint cache: a hit on the unchanged AGV xacro vs `python -c pass`    <= 2x
  (f') 20 edit-and-lint runs of the AGV xacro (each a miss) vs the xacro CLI per run  <= 1.5x
  (f'') 20 runs that each follow an edit of the AGV's controller file: a miss that reuses the expansions
      (information only)
"""
from __future__ import annotations

import argparse
import importlib.metadata
import os
import shutil
import sys
import tempfile
from pathlib import Path

HERE = Path(__file__).resolve().parent
REPO = HERE.parent
sys.path.insert(0, str(HERE))

from gen_urdf import generate  # noqa: E402
from timing import paired, paired_line, peak_kib  # noqa: E402

PY = sys.executable
LINT = [PY, "-m", "urdfcheck", "lint", "--no-config", "--no-cache"]


def ur5_urdf() -> Path | None:
    try:
        dist = importlib.metadata.distribution("example-robot-data")
    except importlib.metadata.PackageNotFoundError:
        return None
    for f in dist.files or ():
        if str(f).endswith("ur_description/urdf/ur5_robot.urdf"):
            return Path(f.locate())
    return None


def xacro_cli(path: Path, pkg_dir: Path) -> list[str]:
    """The stock xacro command line, with $(find agv_description) answered the way ament would."""
    code = ("import sys, xacro, xacro.substitution_args as s;"
            f"s._eval_find=lambda p: {str(pkg_dir)!r};"
            f"sys.argv=['xacro', {str(path)!r}]; xacro.main()")
    return [PY, "-c", code]


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--runs", type=int, default=11, help="pairs per comparison (default 11)")
    ns = ap.parse_args()
    n = ns.runs
    env = dict(os.environ)
    env["PYTHONPATH"] = str(REPO / "src") + os.pathsep + env.get("PYTHONPATH", "")
    # An installed tool runs from compiled bytecode (pip compiles at install). With
    # PYTHONDONTWRITEBYTECODE set, every run would recompile our sources but not the peers'
    # (theirs ship .pyc), so bytecode goes to a private cache for both sides, never into the repo.
    env.pop("PYTHONDONTWRITEBYTECODE", None)
    env.pop("URDFCHECK_NO_CACHE", None)
    pycache = tempfile.TemporaryDirectory(prefix="urdfcheck-bench-pyc-")
    cache_dir = tempfile.TemporaryDirectory(prefix="urdfcheck-bench-cache-")  # never the user's lint cache
    env["PYTHONPYCACHEPREFIX"] = pycache.name
    env["URDFCHECK_CACHE_DIR"] = cache_dir.name
    print(f"python: {PY}; {n} pairs (A B A B ...) after a warm-up each, medians; load average "
          f"{os.getloadavg()[0]:.1f} on {os.cpu_count()} cores; bytecode cache {pycache.name}")
    python_pass = [PY, "-c", "pass"]

    agv = REPO / "examples" / "agv" / "urdf" / "agv.urdf.xacro"
    xacro_agv = xacro_cli(agv, REPO / "examples" / "agv")
    paired_line("(a) lint AGV xacro vs xacro CLI", paired(LINT + [str(agv)], xacro_agv, n, env=env), 1.3, 1.8)

    # not a goal of the issue, but the usual way to run: the package with its urdfcheck.yaml (two camera
    # variants of the xacro, the plain URDF, controller and driver YAML, a launch file)
    paired_line("(a') AGV package with config (3 models) vs xacro",
                paired([PY, "-m", "urdfcheck", "lint", "--no-cache", str(agv.parents[1])], xacro_agv, n, env=env),
                None)

    ur5 = ur5_urdf()
    if ur5 is None:
        print("(b) skipped: example-robot-data is not installed")
    else:
        with tempfile.TemporaryDirectory() as tmp:  # the plain file on its own: model rules only
            alone = Path(tmp) / "ur5_robot.urdf"
            shutil.copy(ur5, alone)
            paired_line("(b) lint plain UR5 URDF vs python -c pass",
                        paired(LINT + ["--ignore", "G001", str(alone)], python_pass, n, env=env), 3.0)
        # where it is installed it sits in a package with launch files: contract checks run too
        paired_line("(b') same, inside its package (contracts)",
                    paired(LINT + ["--ignore", "G001", str(ur5)], python_pass, n, env=env), 3.0)

    check_urdf = "/usr/bin/check_urdf" if os.path.exists("/usr/bin/check_urdf") else shutil.which("check_urdf")
    with tempfile.TemporaryDirectory() as tmp:
        big, small = Path(tmp) / "big.urdf", Path(tmp) / "small.urdf"
        big.write_text(generate(10_000))
        small.write_text(generate(1_000))
        m = max(3, n // 2)
        if check_urdf:
            paired_line("(c) lint 10,000 links vs check_urdf",
                        paired(LINT + [str(big)], [check_urdf, str(big)], m, env=env), 1.5)
            ours = (peak_kib(LINT + [str(big)], env) - peak_kib(LINT + [str(small)], env)) / 9000
            peer = (peak_kib([check_urdf, str(big)]) - peak_kib([check_urdf, str(small)])) / 9000
            verdict = "PASS" if ours <= peer else "FAIL"
            print(f"{'(c) peak memory per link (10k - 1k links)':<44} {ours:7.1f} KiB vs {peer:7.1f} KiB = "
                  f"{ours / peer:.2f}x (goal <= 1x) {verdict}", flush=True)
        else:
            print("(c) skipped: check_urdf (Debian liburdfdom-tools) is not installed")
        paired_line("(d) lint 10,000 links vs 1,000 links",
                    paired(LINT + [str(big)], LINT + [str(small)], m, env=env), 12.0)

    # (f) the lint cache, as pre-commit runs it: the AGV package copied, the cache in a folder of our own
    with tempfile.TemporaryDirectory() as tmp:
        pkg = Path(tmp) / "agv"
        shutil.copytree(REPO / "examples" / "agv", pkg)
        model = pkg / "urdf" / "agv.urdf.xacro"
        cached = [PY, "-m", "urdfcheck", "lint", "--no-config", str(model)]
        paired_line("(f) cache hit, AGV xacro vs python -c pass", paired(cached, python_pass, n, env=env), 2.0)
        text = model.read_text()
        edits = iter(range(10**6))

        def edit():  # what a user does between two commits: the model changes, so each run is a miss
            model.write_text(text + f"<!-- edit {next(edits)} -->\n")

        paired_line("(f') 20 edit-and-lint runs vs xacro CLI each",
                    paired(cached, xacro_cli(model, pkg), 20, env=env, before_a=edit), 1.5)
        params = pkg / "config" / "agv_controllers.yaml"
        params_text = params.read_text()

        def edit_params():  # a controller tuned between two commits: the model's expansions are reused
            params.write_text(params_text + f"# edit {next(edits)}\n")

        paired_line("(f'') 20 parameter-edit-and-lint runs vs xacro CLI",
                    paired(cached, xacro_cli(model, pkg), 20, env=env, before_a=edit_params), None)
    return 0


if __name__ == "__main__":
    sys.exit(main())
