"""The differential test of the consumer profiles (issue 25): every model it finds, and mutants of them, through
the profile predictions (`urdfcheck lint --profile NAME`) and through the real consumer (`urdfcheck consumers`).
Per consumer: recall (refusals the profile predicted) and false alarms (predicted refusals of models the consumer
loads). `python tests/consumers_diff.py [--full]` prints the table committed to docs/consumers.md."""
from __future__ import annotations

import glob
import os
import random
import re
import sys
import tempfile

CORPUS = os.path.join(os.path.dirname(__file__), "..", "..", "..", "shared", "corpus")
if not os.path.isdir(CORPUS):
    CORPUS = "/work/shared/corpus"
HERE = os.path.dirname(os.path.abspath(__file__))

MUTANTS = {
    "zero mass": (r'(<mass\s+value=")[^"]*(")', r"\g<1>0\2"),
    "zero inertia": (r'(<inertia\s)[^>]*?(/?>)', r'\1ixx="0" ixy="0" ixz="0" iyy="0" iyz="0" izz="0"\2'),
    "no inertial": (r"<inertial>.*?</inertial>", ""),
    "triangle": (r'(<inertia\s)[^>]*?(/?>)', r'\1ixx="0.001" ixy="0" ixz="0" iyy="0.001" iyz="0" izz="0.01"\2'),
    "zero axis": (r'(<axis\s+xyz=")[^"]*(")', r"\g<1>0 0 0\2"),
    "negative effort": (r'(effort=")([0-9.]+)(")', r"\1-\2\3"),
    "negative velocity": (r'(velocity=")([0-9.]+)(")', r"\1-\2\3"),
    "no limit": (r"<limit\b[^>]*/>", ""),
    "second root": (r"(</robot>\s*)$", r'<link name="urdfcheck_stray_link"/>\n\1'),
    "duplicate link": (r'(<link\s+name="[^"]*"\s*/>)', r"\1\1"),
}


def models(full: bool) -> list[str]:
    found = sorted(glob.glob(os.path.join(CORPUS, "**", "*.urdf"), recursive=True))
    found += sorted(glob.glob(os.path.join(HERE, "..", "examples", "**", "*.urdf"), recursive=True))
    try:
        import pybullet_data

        found += sorted(glob.glob(os.path.join(pybullet_data.getDataPath(), "**", "*.urdf"), recursive=True))
    except ImportError:
        pass
    erd = glob.glob(os.path.join(sys.prefix, "lib", "python3*", "site-packages", "cmeel.prefix", "share",
                                 "example-robot-data", "robots", "**", "*.urdf"), recursive=True)
    found += sorted(erd)
    found = [f for f in found if os.path.getsize(f) < 2_000_000]
    rng = random.Random(25)
    return rng.sample(found, min(int(full) if full and full is not True else (len(found) if full else 12),
                                 len(found)))


def mutants(paths, full: bool, folder: str) -> list[tuple[str, str]]:
    """(label, path) of each model mutated in one way (the first place the pattern matches, or every place)."""
    out = []
    rng = random.Random(7)
    base = paths[:40] if full else paths[:6]
    for p in base:
        text = open(p, encoding="utf-8", errors="replace").read()
        for name, (pattern, repl) in MUTANTS.items():
            new, n = re.subn(pattern, repl, text, count=0 if name in ("no inertial",) else 1, flags=re.S)
            if n == 0 or new == text:
                continue
            if not full and rng.random() < 0.5:
                continue
            path = os.path.join(folder, f"{len(out):04d}-{os.path.basename(p)}")
            with open(path, "w", encoding="utf-8") as f:
                f.write(new)
            out.append((f"{os.path.basename(p)} [{name}]", path))
    return out


def predict(path: str, consumer: str) -> tuple[bool, list[str]] | None:
    """(the profile predicts a refusal, the codes behind it), None when the model does not load for urdfcheck."""
    import urdfcheck

    folder = os.path.dirname(path)
    here = os.getcwd()
    os.chdir(folder)  # the copy's folder is the run's root: the box meshes written next to it are inside
    try:
        res = urdfcheck.lint([path], profiles=[consumer], no_config=True, root=folder, select=["ALL"])
    finally:
        os.chdir(here)
    if any(f.code.startswith("X") and str(f.severity) == "error" for f in res.findings):
        return None
    # the consumers load copies whose meshes are boxes (truths): what a finding says of the mesh files themselves
    # (P008, G001) is not compared here; tests/differential.py's mesh mutants load them as written
    codes = sorted({f.code for f in res.findings if f.profile == consumer and str(f.severity) == "error"
                    and f.code not in ("P008", "G001")})
    return bool(codes), codes


def _batch_job(consumer: str, paths: list[str]) -> list[dict]:
    from urdfcheck.verify import consumers as C

    return [C.JOBS[consumer](p) for p in paths]


def truths(paths: list[str], consumer: str, folder: str, batch: int = 40) -> dict[str, object]:
    """path -> "loaded" | the refusal message | a Failure: the consumer run on copies without meshes, many models
    per sandboxed worker (one import of the consumer per batch; a batch that crashes is run model by model)."""
    from urdfcheck.core import worker
    from urdfcheck.load import loader
    from urdfcheck.verify import consumers as C

    copies = {}
    for i, p in enumerate(paths):
        exp = loader.expand(p, {})
        if exp.root is None:
            continue
        text, _ = C.without_meshes(exp.clean_text(), folder)
        copy = os.path.join(folder, f"{consumer}-{i:05d}.urdf")
        with open(copy, "w", encoding="utf-8") as f:
            f.write(text)
        copies[p] = copy
    out: dict[str, object] = {}
    todo = list(copies)
    while todo:
        chunk, todo = todo[:batch], todo[batch:]
        lim = worker.Limits(memory=C.DEFAULT_MEMORY, timeout=30.0 * len(chunk), result=64 * 1024 * 1024)
        job = worker.prepare(_batch_job, limits=lim, preload=(C.MODULE[consumer],), capture="output")
        job.send(consumer, [copies[p] for p in chunk])
        got = job.result()
        if isinstance(got, worker.Failure):
            if len(chunk) == 1:
                out[chunk[0]] = got
            else:
                for p in chunk:  # one by one: find the model that crashed the consumer
                    one = worker.prepare(_batch_job, limits=worker.Limits(memory=C.DEFAULT_MEMORY, timeout=30.0),
                                         preload=(C.MODULE[consumer],), capture="output")
                    one.send(consumer, [copies[p]])
                    r = one.result()
                    out[p] = r if isinstance(r, worker.Failure) else (r[0].get("rejected") or "loaded")
            continue
        for p, r in zip(chunk, got):
            out[p] = r.get("rejected") or "loaded"
    return out


def measure(full=False, consumers=("mujoco", "pinocchio")) -> dict:
    from urdfcheck.core import worker

    with tempfile.TemporaryDirectory() as folder:
        base = models(full)
        items = [(os.path.relpath(p, CORPUS) if p.startswith(CORPUS) else os.path.basename(p), p) for p in base]
        items += mutants(base, full, folder)
        table = {}
        for consumer in consumers:
            row = {"models": 0, "refused": 0, "predicted": 0, "false_alarms": [], "missed": [], "failed": []}
            predicted = {path: predict(path, consumer) for _, path in items}
            truth = truths([path for _, path in items if predicted[path] is not None], consumer, folder)
            for label, path in items:
                p, t = predicted[path], truth.get(path)
                if p is None or t is None:
                    continue
                row["models"] += 1
                if isinstance(t, worker.Failure):
                    row["failed"].append((label, t.message))
                    continue
                refused = t != "loaded"
                row["refused"] += refused
                if refused and p[0]:
                    row["predicted"] += 1
                elif refused:
                    row["missed"].append((label, str(t).replace("\n", " ")[:160]))
                elif p[0]:
                    row["false_alarms"].append((label, ",".join(p[1])))
            table[consumer] = row
        return table


def render(table: dict) -> str:
    lines = ["| consumer | models | refused | predicted | recall | false alarms | consumer failed |",
             "| --- | ---: | ---: | ---: | ---: | ---: | ---: |"]
    for c, r in table.items():
        recall = f"{100.0 * r['predicted'] / r['refused']:.1f} %" if r["refused"] else "n/a"
        lines.append(f"| {c} | {r['models']} | {r['refused']} | {r['predicted']} | {recall} | "
                     f"{len(r['false_alarms'])} | {len(r['failed'])} |")
    lines.append("")
    for c, r in table.items():
        for label, why in r["missed"]:
            lines.append(f"- {c} refused, not predicted: `{label}`: {why}")
        for label, codes in r["false_alarms"]:
            lines.append(f"- {c} loaded, refusal predicted: `{label}` ({codes})")
        for label, why in r["failed"]:
            lines.append(f"- {c} failed on `{label}`: {why}")
    return "\n".join(lines) + "\n"


if __name__ == "__main__":
    size = next((int(a.split("=")[1]) for a in sys.argv if a.startswith("--sample=")), None)
    print(render(measure(full=size or ("--full" in sys.argv))))
