"""The per-file pre-commit hook from a monorepo root vs from the file's own repository (issue 38).

    python bench/bench_hook.py [CORPUS] [--runs N] [--repo NAME] [--file REL ...]

The hook runs `urdfcheck lint FILE` for each staged file. From the root of a folder of many repositories (the
22-repository corpus) a parameter file is planned against the robots and deployments that read it; the goal is
that this costs no more than 1.5x the same command run from the repository's own root (same files, same run,
paired A B A B; `timing.paired`). Cold runs: `--no-cache` (nothing is written into the corpus), bytecode in a
private PYTHONPYCACHEPREFIX.
"""
from __future__ import annotations

import argparse
import os
import sys
import tempfile
from pathlib import Path

HERE = Path(__file__).resolve().parent
REPO = HERE.parent
sys.path.insert(0, str(HERE))

from timing import paired  # noqa: E402

DEFAULT_ROOT = REPO.parent / "shared" / "corpus"
GOAL = 1.5
DEFAULT_FILES = {  # what a commit to the repository might change: a controller/driver YAML, a launch file, a macro
    "linorobot+linorobot2": ["linorobot2_base/config/ekf.yaml", "linorobot2_bringup/config/joy.yaml",
                             "linorobot2_bringup/launch/joy_teleop.launch.py",
                             "linorobot2_description/urdf/mech/wheel.urdf.xacro"],
    # a xacro macro file that is MoveIt's semantic description (planned as a file the robots read)
    "UniversalRobots+Universal_Robots_ROS2_Driver": ["ur_moveit_config/srdf/ur_macro.srdf.xacro"],
}


def hook(cwd: Path, files: list[str]) -> list[str]:
    """The hook's command, run in `cwd` (through sh: the same cost on both sides)."""
    return ["sh", "-c", 'cd "$0" && exec "$@"', str(cwd), sys.executable, "-m", "urdfcheck", "lint", "--no-cache",
            "-q", *files]


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("root", nargs="?", default=str(DEFAULT_ROOT))
    ap.add_argument("--runs", type=int, default=7)
    ap.add_argument("--repo", action="append", help="a repository of the folder (repeatable; default: "
                    "those of DEFAULT_FILES)")
    ap.add_argument("--file", action="append", help="a file of the repository, relative to it (repeatable)")
    ns = ap.parse_args(argv)
    root = Path(ns.root).resolve()
    env = dict(os.environ, PYTHONPATH=str(REPO / "src"), NO_COLOR="1",
               PYTHONPYCACHEPREFIX=tempfile.mkdtemp(prefix="urdfcheck-bench-pyc-"))
    env.pop("PYTHONDONTWRITEBYTECODE", None)  # cold runs, not a compilation each run
    worst = 0.0
    for name in ns.repo or list(DEFAULT_FILES):
        repo = root / name
        files = ns.file or DEFAULT_FILES.get(name)
        if not repo.is_dir() or not files:
            print(f"no repository {repo} (or no files named): nothing to measure", file=sys.stderr)
            return 2
        missing = [f for f in files if not (repo / f).is_file()]
        if missing:
            print(f"not in {repo}: {', '.join(missing)}", file=sys.stderr)
            return 2
        print(f"per-file hook, {len(files)} file(s) of {name}; {ns.runs} pairs; load average "
              f"{os.getloadavg()[0]:.1f}")
        for f in files:
            r = paired(hook(root, [f"{name}/{f}"]), hook(repo, [f]), ns.runs, env=env)
            worst = max(worst, r["cpu"], r["wall"])
            print(f"  {f}: from the corpus root {r['wall_a']:.2f} s wall / {r['cpu_a']:.2f} s CPU, from the "
                  f"repository {r['wall_b']:.2f} s / {r['cpu_b']:.2f} s: ratio wall {r['wall']:.2f}x "
                  f"[{r['wall_q'][0]:.2f}-{r['wall_q'][1]:.2f}], CPU {r['cpu']:.2f}x "
                  f"[{r['cpu_q'][0]:.2f}-{r['cpu_q'][1]:.2f}]", flush=True)
        if len(files) > 1:
            all_files = [f"{name}/{f}" for f in files]
            r = paired(hook(root, all_files), hook(repo, files), ns.runs, env=env)
            worst = max(worst, r["cpu"], r["wall"])
            print(f"  all {len(files)} in one hook run: wall {r['wall']:.2f}x, CPU {r['cpu']:.2f}x", flush=True)
    print(f"goal <= {GOAL}x: {'PASS' if worst <= GOAL else 'FAIL'} (worst median ratio {worst:.2f}x)")
    return 0


if __name__ == "__main__":
    sys.exit(main())
