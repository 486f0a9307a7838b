"""Zero-config lint of a whole workspace vs stock xacro run once per model it lints.

    python bench/bench_workspace.py [ROOT] [--table]

ROOT defaults to the corpus (../shared/corpus). The workspace is planned the way zero config plans it
(plan.plan, as `urdfcheck lint` run there with no flags: deployments found once for the whole tree,
with the launch files' arguments; every other entry model with its boolean variants), then linted in one
process (`--lint-only` runs just that part: the timed command). The peer is the xacro CLI run once per planned
model and argument set, with $(find) answered from the same package map, one process after another. `--table`
prints per repository: robots (models planned), deployments (with a model / all), and what was not understood.
"""
from __future__ import annotations

import argparse
import json
import os
import resource
import subprocess
import sys
import time
from collections import Counter, defaultdict
from pathlib import Path

HERE = Path(__file__).resolve().parent
REPO = HERE.parent
PY = sys.executable
DEFAULT_ROOT = REPO.parent / "shared" / "corpus"


def lint_workspace(root: str) -> dict:
    """Plan and lint; returns a summary (per repository) as JSON-able data."""
    from urdfcheck.core.findings import Severity
    from urdfcheck.load.discover import remembering
    from urdfcheck.rules import engine
    from urdfcheck.run import lint_targets

    with remembering():  # as `run.run` plans and lints: each folder listed and each package walked once
        plan = _plan(root)
        targets = list(plan.models)
        for t in targets:
            t.settings = None  # linted with the selection below
        result = lint_targets(targets, engine.Selection(ignore=("G001",)))  # meshes are absent from the corpus
    by_repo: dict = defaultdict(lambda: {"models": set(), "targets": 0, "deployments": 0, "with_model": 0,
                                         "loaded": 0, "codes": Counter(), "not_understood": []})

    def repo(path: str) -> str:
        rel = os.path.relpath(os.path.abspath(path), root)
        return rel.split(os.sep)[0]

    for m in plan.models:
        r = by_repo[repo(m.path)]
        r["models"].add(m.path)
        r["targets"] += 1
    for (path, _variant), model in result.models.items():
        if model is not None:
            by_repo[repo(path)]["loaded"] += 1
    for d in plan.deployments:
        r = by_repo[repo(d.launch.file)]
        r["deployments"] += 1
        r["with_model"] += d.model is not None
        for msg, _ in d.notes:
            if "not understood" in msg or "decided at launch time" in msg or "not found" in msg:
                r["not_understood"].append(msg)
    for f in result.findings:
        by_repo[repo(f.location.file)]["codes"][f.code] += 1
    out = {}
    for k, v in sorted(by_repo.items()):
        out[k] = {"models": len(v["models"]), "targets": v["targets"], "loaded": v["loaded"],
                  "deployments": v["deployments"], "with_model": v["with_model"],
                  "X": {c: n for c, n in v["codes"].items() if c.startswith("X")},
                  "C/T": {c: n for c, n in v["codes"].items() if c[0] in "CT"},
                  "not_understood": sorted(Counter(v["not_understood"]).items())[:6]}
    out["_total"] = {"targets": len(targets), "deployments": len(plan.deployments),
                     "errors": sum(1 for f in result.findings if f.severity >= Severity.ERROR)}
    return out


class _Plan:
    def __init__(self, models, deployments):
        self.models, self.deployments = models, deployments


def _plan(root: str) -> _Plan:
    """What `urdfcheck lint` run in `root` with no flags plans (plan.plan): the targets, and every
    deployment found (with a model or not)."""
    from urdfcheck.plan.plan import plan
    from urdfcheck.request.request import make_request

    targets = plan(make_request([root]))
    deps = list({id(t.deployment): t.deployment for t in targets if t.deployment is not None}.values())
    return _Plan(list(targets), deps + list(targets.not_understood))


def _cpu() -> float:
    r = resource.getrusage(resource.RUSAGE_CHILDREN)
    return r.ru_utime + r.ru_stime


def stock_xacro_times(root: str) -> tuple[float, int, float]:
    """Sequential wall time (and CPU time) of the xacro CLI once per planned model and argument set."""
    os.chdir(root)
    plan = _plan(root)
    total, n, cpu0 = 0.0, 0, _cpu()
    for m in plan.models:
        code = ("import sys, xacro, xacro.substitution_args as s;"
                f"pk={m.packages!r};"
                "s._eval_find=lambda p: pk[p];"
                f"sys.argv=['xacro', {str(m.path)!r}] + {[f'{k}:={v}' for k, v in m.args.items()]!r}; xacro.main()")
        t0 = time.perf_counter()
        subprocess.run([PY, "-c", code], stdin=subprocess.DEVNULL, stdout=subprocess.DEVNULL,
                       stderr=subprocess.DEVNULL, cwd=root)
        total += time.perf_counter() - t0
        n += 1
    return total, n, _cpu() - cpu0


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("root", nargs="?", default=str(DEFAULT_ROOT))
    ap.add_argument("--lint-only", action="store_true", help="plan and lint only (the timed command)")
    ap.add_argument("--table", action="store_true")
    ns = ap.parse_args()
    root = os.path.abspath(ns.root)
    if ns.lint_only:
        os.chdir(root)
        print(json.dumps(lint_workspace(root)))
        return 0
    env = dict(os.environ)
    env["PYTHONPATH"] = str(REPO / "src") + os.pathsep + env.get("PYTHONPATH", "")
    t0, c0 = time.perf_counter(), _cpu()
    proc = subprocess.run([PY, __file__, root, "--lint-only"], capture_output=True, text=True, env=env)
    ours, ours_cpu = time.perf_counter() - t0, _cpu() - c0
    if proc.returncode != 0:
        print(proc.stderr[-3000:], file=sys.stderr)
        return 1
    summary = json.loads(proc.stdout.strip().splitlines()[-1])
    peer, n, peer_cpu = stock_xacro_times(root)
    total = summary.pop("_total")
    print(f"zero-config lint of {root}: {total['targets']} models/argument sets, {total['deployments']} deployments: "
          f"{ours:.1f} s; stock xacro once per model: {n} runs, {peer:.1f} s; ratio {ours / peer:.2f}x (goal <= 1x); "
          f"CPU time {ours_cpu:.1f} s vs {peer_cpu:.1f} s = {ours_cpu / peer_cpu:.2f}x; load {os.getloadavg()[0]:.1f}")
    if ns.table:
        print("| repository | robots (files) | lint targets | loaded | deployments (with model/all) | X codes "
              "| C/T codes | not understood |")
        print("|---|---|---|---|---|---|---|---|")
        for k, v in summary.items():
            nu = "; ".join(f"{m} ×{c}" for m, c in v["not_understood"])
            print(f"| {k} | {v['models']} | {v['targets']} | {v['loaded']} | {v['with_model']}/{v['deployments']} | "
                  f"{v['X']} | {v['C/T']} | {nu} |")
    return 0


if __name__ == "__main__":
    sys.exit(main())
