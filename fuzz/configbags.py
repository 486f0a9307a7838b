#!/usr/bin/env python3
"""Config-declared recordings fuzzer (issue 36): `models: [{path: ..., bags: [...]}]` in the pull request's own
config, read by `urdfcheck lint` with no recording on the command line (nothing the runner typed: every file is
the checkout's, the door confines them all).

    python3 fuzz/configbags.py --count 10000 --seed 3639 [--hang 20] [--report FILE]

Each input is a checkout holding a broken robot (the fixture robot of tests/fixtures/ros1 with its arm joint's
limits the wrong way round: J003, an error) and one recording from recordings.py's grammar (ROS 1 bags, rosbag2
sqlite3 and MCAP folders, MCAP and .db3 files alone, YAML/JSON lists: mutated, bombs, 2-million-message MCAPs,
hostile sqlite, members linked out of the checkout or to /proc and /dev, FIFOs, metadata naming `../` files) and a
config (urdfcheck.yaml, .urdfcheck.yaml or pyproject.toml) whose `bags:` names it in one of its spellings (the
folder, `./folder`, its metadata.yaml, its storage file, the file) among hostile entries: a folder link out of the
checkout, the canary file through it, `../`, absolute paths, /proc/self/environ, a FIFO, a folder, a missing path,
the checkout itself, the same recording 40 times, non-strings, a NUL. The config sometimes adds `trusted: true`
(which the checkout cannot grant itself) or a second model.

`urdfcheck lint` runs in-process in a forked child (harness.py) with `--budget 3`, in a report format in turn.
Counted as in harness.py: the broken robot must fail every time (exit 0 or "All checks passed" is a silent pass),
no leak of the canary file or of an absolute temp path, no traceback, no hang past the budget, no write into the
checkout; and **unread**: a run that went past the config (exit 1) whose report names no B rule (the declared
recording neither checked nor said unreadable). Exit 1 when any count is non-zero.
"""
from __future__ import annotations

import json
import os
import random
import re
import sys
from pathlib import Path

HERE = Path(__file__).resolve().parent
sys.path.insert(0, str(HERE))
import harness  # noqa: E402
import recordings  # noqa: E402

FORMATS = ("text", "json", "sarif", "markdown", "github", "junit")
BROKEN = recordings.FIXTURES.joinpath("robot.urdf").read_text().replace('lower="-2" upper="2"', 'lower="2" upper="-2"')
assert BROKEN != recordings.FIXTURES.joinpath("robot.urdf").read_text()
HOSTILE = ["link_out", "link_out/secret.yaml", "link_out/secret.txt", "../outside/secret.yaml", "../outside",
           "/proc/self/environ", "/etc", "/dev/zero", "fifo", "emptydir", "nothere.bag", ".", "..", "robot.urdf",
           "~/.ssh/id_rsa", "rec/../../outside/secret.yaml", "$(env URDFCHECK_FUZZ_SECRET)", "*.bag", "**",
           "a" * 300, "\x1b]52;c;aGk=\x07.bag", "rec\u202e.bag", "file:///etc/passwd", "\\\\host\\share"]


def spellings(case: dict) -> list[str]:
    """How the config may name the recording the grammar made."""
    rec = case["rec"]
    out = [rec, "./" + rec]
    files = case["files"]
    if any(k.startswith(rec + "/") for k in files):  # a folder
        out += [rec + "/", rec + "/metadata.yaml"] + [k for k in files if k.startswith(rec + "/")]
    return out


def _yaml(v) -> str:
    return json.dumps(v, ensure_ascii=False)


def config_text(r: random.Random, case: dict) -> tuple[str, str]:
    """(where, text) of the pull request's config."""
    names = spellings(case)
    bags: list = [r.choice(names) for _ in range(r.randrange(1, 3))]
    k = r.random()
    if k < 0.15:
        bags.insert(r.randrange(len(bags) + 1), r.choice(HOSTILE))
    elif k < 0.20:
        bags = [r.choice(names)] * 40
    elif k < 0.23:
        bags = r.choice([[1], [None], [[names[0]]], [{"path": names[0]}], names[0], "\x00", [True], [1e309]])
    model: dict = {"path": r.choice(["robot.urdf", "robot.urdf", "./robot.urdf"]), "bags": bags}
    body: dict = {"models": [model]}
    if r.random() < 0.1:
        body["models"].append({"path": "robot.urdf", "bags": [r.choice(HOSTILE + names)]})
    if r.random() < 0.1:
        body["trusted"] = True
    if r.random() < 0.1:
        body[r.choice(["ignore", "select", "severity"])] = r.choice([["B"], ["J003"], {"B014": "info"}, ["ALL"]])
    where = r.choice(["urdfcheck.yaml", "urdfcheck.yaml", ".urdfcheck.yaml", "pyproject.toml"])
    if where == "pyproject.toml":
        from configs import _toml

        return where, _toml(body)
    lines = [f"{k}: {_yaml(v)}" for k, v in body.items()]
    if r.random() < 0.05:  # the recording list through an alias, or an alias bomb beside it
        lines = ['models: [{"path": "robot.urdf", "bags": &b ' + _yaml(bags) + '}, {"path": "./robot.urdf", '
                 '"bags": *b}]']
    return where, "\n".join(lines) + "\n"


def generate(r: random.Random, seeds, bombs, dbs, i: int, small: bool = False) -> dict:
    case = recordings.generate(r, seeds, bombs, dbs, i, small)
    where, text = config_text(r, case)
    argv = ["lint", "--format", FORMATS[i % len(FORMATS)], "--budget", "3", "--no-cache"]
    if r.random() < 0.3:
        argv.append(r.choice(["robot.urdf", ".", "./robot.urdf"]))
    return {"i": i, "kind": case["kind"], "name": case["name"], "files": case["files"], "rec": case["rec"],
            "config": (where, text), "argv": argv}


def place(ws: Path, case: dict, out: Path) -> None:
    recordings.place(ws, case, out)
    (ws / "robot.urdf").write_text(BROKEN)
    where, text = case["config"]
    (ws / where).write_text(text, encoding="utf-8", errors="surrogatepass")
    os.symlink(out, ws / "link_out")
    os.mkfifo(ws / "fifo")
    (ws / "emptydir").mkdir()


def do_one_factory(base: Path, out: Path, marks):
    ws = base / "ws"

    def do_one(case: dict) -> dict:
        place(ws, case, out)
        code, text, bad = harness.in_checkout(ws, base, case["argv"], marks, must_fail=True)
        if code == 1 and not re.search(r"\bB0\d\d\b", text):
            bad.append("unread")  # the config's recording neither checked nor said unreadable
        return {"bad": bad, "outcome": f"{case['kind'].split('-')[0]} exit {code}",
                "detail": harness.detail(code, text)}

    return do_one


def show(case: dict) -> dict:
    return {**recordings.show(case), "config": list(case["config"])}


def run(count: int, seed: int, hang: float, batch: int, report: str | None, seconds: float | None = None,
        small: bool = False):
    r = random.Random(seed)
    with harness.Session("urdfcheck-fuzzcfgbag-", "unread") as run_:
        seeds, bombs, dbs = recordings.pieces(run_.base / "seeds", small)
        do_one = do_one_factory(run_.base, run_.out, run_.marks)
        run_.steps(count, 500, seconds, report,
                   lambda done, n: [generate(r, seeds, bombs, dbs, done + k, small) for k in range(n)], do_one,
                   hang, batch, show=show)
    return run_.result()


def main(argv=None) -> int:
    ap = harness.parser(__doc__, count=1000, seed=3639, hang=20.0, batch=100)
    ns = ap.parse_args(argv)
    stats, examples, t0 = run(ns.count, ns.seed, ns.hang, ns.batch, ns.report, seconds=ns.seconds)
    return harness.finish(stats, examples, t0, ns.report) or (1 if stats["unread"] else 0)


if __name__ == "__main__":
    sys.exit(main())
