"""Zero-config runs over the shared corpora, as a new user would run them: one `urdfcheck lint` per repository,
from inside it, no config, no flags (JSON is asked for on a private temp file, which changes no finding).

    python tools/corpus_runs.py [CORPUS_DIR ...] [--tsv FILE]

Prints, per repository, the exit code and the warnings and errors (missing meshes, G001, aside), and a total per
corpus; `--tsv FILE` writes one row per warning or error (corpus, repository, file:line, code, severity, message):
the rows the triage table (docs/triage.md) judges. Nothing is written into the corpora (`--no-cache`).
"""
from __future__ import annotations

import argparse
import json
import os
import subprocess
import sys
import tempfile

HERE = os.path.dirname(os.path.abspath(__file__))
DEFAULT = [os.path.join(HERE, "..", "..", "shared", c) for c in ("corpus", "corpus2")]
ASIDE = {"G001"}


def run_one(repo: str, timeout: float) -> tuple[int, list[dict]]:
    with tempfile.TemporaryDirectory() as tmp:
        out = os.path.join(tmp, "report.json")
        cmd = [sys.executable, "-m", "urdfcheck", "lint", "--no-cache", "--quiet", "--format", "json", "-o", out]
        try:
            proc = subprocess.run(cmd, cwd=repo, capture_output=True, text=True, timeout=timeout)
        except subprocess.TimeoutExpired:
            return -1, []
        if not os.path.exists(out):
            return proc.returncode, [{"code": "EXIT", "severity": "error", "message": proc.stderr.strip()[-300:],
                                      "location": {"file": "", "line": None}}]
        with open(out, encoding="utf-8") as f:
            data = json.load(f)
    return proc.returncode, data.get("findings", [])


def main(argv=None) -> int:
    ap = argparse.ArgumentParser()
    ap.add_argument("corpora", nargs="*", default=DEFAULT)
    ap.add_argument("--tsv")
    ap.add_argument("--timeout", type=float, default=600)
    ns = ap.parse_args(argv)
    rows = []
    for corpus in ns.corpora:
        corpus = os.path.normpath(corpus)
        if not os.path.isdir(corpus):
            print(f"{corpus}: absent, skipped")
            continue
        name = os.path.basename(corpus)
        total = red = 0
        for repo in sorted(os.listdir(corpus)):
            path = os.path.join(corpus, repo)
            if not os.path.isdir(path):
                continue
            code, findings = run_one(path, ns.timeout)
            hard = [f for f in findings if f["severity"] in ("warning", "error") and f["code"] not in ASIDE]
            total += len(hard)
            red += bool(hard)
            print(f"{name}/{repo}: exit {code}, {len(hard)} warnings/errors", flush=True)
            for f in hard:
                loc = f["location"]
                where = f"{loc.get('file', '')}:{loc.get('line') or ''}"
                rows.append((name, repo, where, f["code"], f["severity"], f["message"].replace("\t", " ")))
        print(f"== {name}: {total} warnings/errors, {red} repositories red (meshes aside)")
    if ns.tsv:
        with open(ns.tsv, "w", encoding="utf-8") as f:
            for r in rows:
                f.write("\t".join(r) + "\n")
    return 0


if __name__ == "__main__":
    sys.exit(main())
