"""The agreement table of the consumer profiles over the corpus (issue 40): every URDF of /work/shared/corpus*,
every *.urdf.xacro there that expands (urdfcheck's own expansion, default arguments) to a robot of two links or
more, examples/, and the seeded mutants with their clean twins (tests/profile_mutants.py), loaded into each
consumer installable here and compared with the profile prediction on each point (tests/differential.py).

    PYTHONPATH=src python tools/profiles_table.py [--before SRC] [--json OUT] [--limit N]

--before SRC: also the refusal point as the code under SRC (another checkout's src/, e.g. main) predicts it, with
the single `profile` a finding carried there. Prints a markdown table and the disagreements."""
from __future__ import annotations

import argparse
import glob
import hashlib
import json
import os
import shutil
import subprocess
import sys
import tempfile

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(HERE, "..", "tests"))

import differential  # noqa: E402
import profile_mutants  # noqa: E402

CORPORA = ("/work/shared/corpus", "/work/shared/corpus2")


def models(limit: int | None = None) -> list[tuple[str, str]]:
    found = []
    for corpus in CORPORA:
        if not os.path.isdir(corpus):
            continue
        for pattern in ("**/*.urdf", "**/*.urdf.xacro"):
            for p in sorted(glob.glob(os.path.join(corpus, pattern), recursive=True)):
                found.append((os.path.relpath(p, os.path.dirname(corpus)), p))
    for p in sorted(glob.glob(os.path.join(HERE, "..", "examples", "**", "*.urdf*"), recursive=True)):
        found.append((os.path.relpath(p, os.path.join(HERE, "..")), p))
    return found[:limit] if limit else found


def prepare(items, folder):
    """(label, model, copy) of each model that expands to a robot of 2+ links, the same robot once."""
    out, seen = [], set()
    for label, path in items:
        try:
            got = differential.prepared(path, folder)
        except Exception:  # noqa: BLE001 (urdfcheck reports what it cannot expand; the table skips it)
            continue
        if got is None or len(got[0].links) < 2:
            continue
        digest = hashlib.sha256(open(got[1], "rb").read()).hexdigest()
        if digest in seen:
            continue
        seen.add(digest)
        out.append((label, *got))
    return out


BEFORE = r"""
import json, sys, urdfcheck
out = []
for consumer, path in json.loads(sys.stdin.read()):
    import os
    res = urdfcheck.lint([path], profiles=[consumer], no_config=True, root=os.path.dirname(path), select=["ALL"])
    out.append(sorted({f.code for f in res.findings if f.profile == consumer and str(f.severity) == "error"}))
print(json.dumps(out))
"""


def versions() -> dict:
    import importlib.metadata as md

    out = {}
    for c, dist in (("mujoco", "mujoco"), ("pinocchio", "pin"), ("pybullet", "pybullet")):
        try:
            out[c] = md.version(dist)
        except md.PackageNotFoundError:
            pass
    out["gazebo"] = "sdformat " + differential.sdformat_version()
    out["kdl"] = f"kdl_parser {differential.kdl_version()} (urdfdom {differential.urdfdom_version()})"
    return out


def before(src: str, pairs) -> list[list[str]]:
    env = dict(os.environ, PYTHONPATH=src)
    proc = subprocess.run([sys.executable, "-c", BEFORE], input=json.dumps(pairs), capture_output=True, text=True,
                          env=env, timeout=3600)
    return json.loads(proc.stdout.strip().splitlines()[-1])


def main(argv=None) -> int:
    ap = argparse.ArgumentParser()
    ap.add_argument("--before", default=None)
    ap.add_argument("--json", default=None)
    ap.add_argument("--limit", type=int, default=None)
    ns = ap.parse_args(argv)
    folder = tempfile.mkdtemp(prefix="urdfcheck-table-")
    seeds = tempfile.mkdtemp(prefix="urdfcheck-mutants-")
    try:
        return _table(ns, folder, profile_mutants.write(seeds))
    finally:
        shutil.rmtree(folder, ignore_errors=True)
        shutil.rmtree(seeds, ignore_errors=True)


def _table(ns, folder, mutants) -> int:
    real = prepare(models(ns.limit), folder)
    seeded = prepare(mutants, folder)
    ready = real + seeded
    print(f"{len(real)} models from the corpus and examples/ (each robot once), {len(seeded)} mutants and twins; "
          f"consumers: {', '.join(f'{c} {v}' for c, v in versions().items())}\n")
    consumers = [c for c in differential.CONSUMERS if c in differential.installed()]
    rows = {}
    said = [differential.refusals(copy, consumers) for _, _, copy in ready]
    for c in consumers:
        truths = differential.load_many(c, [copy for _, _, copy in ready])
        old = before(ns.before, [(c, copy) for _, _, copy in ready]) if ns.before else None
        row = {"models": len(ready), "agree": 0, "disagree": [], "refusals": 0, "before_refusal_agree": None,
               "after_refusal_agree": 0, "before_disagree": []}
        if old is not None:
            row["before_refusal_agree"] = 0
        for i, ((label, model, copy), truth) in enumerate(zip(ready, truths)):
            pred = differential.predict(c, copy, model, truth.get("version", ""), said[i][c])
            bad = differential.compare(pred, truth)
            row["refusals"] += truth["refused"]
            row["after_refusal_agree"] += pred["refused"] == truth["refused"]
            if bad:
                row["disagree"].append((label, bad[0], differential.explain(pred, truth, bad[0])))
            else:
                row["agree"] += 1
            if old is not None:
                if bool(old[i]) == truth["refused"]:
                    row["before_refusal_agree"] += 1
                else:
                    row["before_disagree"].append((label, ",".join(old[i]) or "load predicted",
                                                   truth.get("why", "loaded")[:120]))
        rows[c] = row
    print(render(rows))
    if ns.json:
        with open(ns.json, "w") as f:
            json.dump(rows, f, indent=1)
    return 0


def render(rows) -> str:
    lines = ["| consumer | models | refused by it | refusal point agrees, before | refusal point agrees, after | "
             "every point agrees, after |", "| --- | ---: | ---: | ---: | ---: | ---: |"]
    for c, r in rows.items():
        b = "n/a" if r["before_refusal_agree"] is None else str(r["before_refusal_agree"])
        lines.append(f"| {c} | {r['models']} | {r['refusals']} | {b} | {r['after_refusal_agree']} | {r['agree']} |")
    lines.append("")
    for c, r in rows.items():
        for label, point, why in r["disagree"]:
            lines.append(f"- {c}, after, `{label}`: {point}: {why}")
        for label, codes, why in r["before_disagree"]:
            lines.append(f"- {c}, before, `{label}`: predicted {codes}; consumer: {why}")
    return "\n".join(lines)


if __name__ == "__main__":
    sys.exit(main())
