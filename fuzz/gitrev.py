#!/usr/bin/env python3
"""git-revision fuzzer (issue 36): hostile repositories through `urdfcheck diff --git REV`, `lint --diff-base REV`
and `lint --config-from REV` (src/urdfcheck/core/git.py is the one door to git).

    python3 fuzz/gitrev.py --count 8000 --seed 3637 [--repos 24] [--hang 30] [--report FILE]

A pool of repositories is built in a temp folder from a grammar (each a random mix of): names git holds but a file
system or a report cannot (300-byte components, bytes that are not UTF-8, escape and bidi characters, newlines,
leading dashes), one 8 MiB blob listed 120 times, a blob above the door's 64 MiB cap, links (mode 120000) to the
canary file, /proc/self/environ and `../..`, the robot itself a link out in an old revision, submodule entries
with a `.gitmodules` whose URL is `ext::` and whose update is `!command`, a committed folder that looks like a bare
repository (HEAD, objects/, refs/, a config with core.fsmonitor, a promisor `ext::` remote, hooks) used as the
path or the working directory, a promisor remote in the repository's own config with a missing blob, a base
revision's urdfcheck.yaml that is a link out, an alias bomb, deep nesting, paths out of the checkout, and a config
of the pull request (working tree) that lowers the gate. The working tree's robot (`pkg/urdf/robot.urdf`) is
always broken (J003, S003) where every commit's copy is clean or absent.

Inputs: a repository, a command, a revision (HEAD, HEAD~N, branches, tags, ids, `:/text`, `@{-1}`, `-x`,
`HEAD:path`, `HEAD^{tree}`, 300 characters, control characters, a missing id), paths and a report format.
Each runs the real CLI in-process in a forked child (harness.py) with its TMPDIR inside the run's temp folder.
Counted besides harness.py's leaks/tracebacks/hangs/silent/writes: `exec`, a command the repository asked for ran
(its marker file appeared). Silent: `lint --diff-base`/`--config-from` or `diff --git --fail-on-change` exiting 0
(the broken robot is new against every revision). Writes: anything changed in the repository (its .git too) or a
temporary folder left behind. Exit 1 when any count is non-zero.
"""
from __future__ import annotations

import json
import os
import random
import shutil
import subprocess
import sys
import time
from pathlib import Path

HERE = Path(__file__).resolve().parent
sys.path.insert(0, str(HERE))
import harness  # noqa: E402

BROKEN = harness.BROKEN  # J003 and S003, both errors
CLEAN = """<?xml version="1.0"?>
<robot name="r"><link name="base_link"/><link name="tool"/><link name="ghost"/>
<joint name="j" type="revolute"><parent link="base_link"/><child link="tool"/>
<limit lower="-1" upper="1" effort="1" velocity="1"/></joint>
<joint name="k" type="fixed"><parent link="base_link"/><child link="ghost"/></joint>
</robot>
"""
PKG = "<package format='3'><name>pkg</name></package>\n"
FORMATS_LINT = ("text", "json", "sarif", "markdown", "github", "junit")
FORMATS_DIFF = ("text", "json", "markdown")


class Git:
    def __init__(self, root: Path, home: Path):
        self.root = root
        self.env = {"HOME": str(home), "GIT_CONFIG_NOSYSTEM": "1", "PATH": os.environ.get("PATH", "/usr/bin:/bin"),
                    "GIT_AUTHOR_NAME": "f", "GIT_AUTHOR_EMAIL": "f@x", "GIT_COMMITTER_NAME": "f",
                    "GIT_COMMITTER_EMAIL": "f@x", "GIT_AUTHOR_DATE": "2026-01-01T00:00:00",
                    "GIT_COMMITTER_DATE": "2026-01-01T00:00:00"}

    def __call__(self, *args, data: bytes | None = None) -> bytes:
        return subprocess.run(["git", *args], cwd=self.root, env=self.env, input=data, capture_output=True,
                              check=True).stdout

    def blob(self, data: bytes) -> str:
        return self("hash-object", "-w", "--stdin", data=data).decode().strip()

    def tree(self, entries: list[tuple[str, str, bytes]], missing: bool = False) -> str:
        """entries: (mode, sha, name as bytes) of ONE level; returns the tree id."""
        text = b"".join(f"{m} {'tree' if m == '040000' else 'commit' if m == '160000' else 'blob'} {s}\t".encode()
                        + n + b"\0" for m, s, n in entries)
        return self("mktree", "-z", *(["--missing"] if missing else []), data=text).decode().strip()

    def nested(self, files: dict[bytes, tuple[str, str]], missing: bool = False) -> str:
        """A tree from {path bytes: (mode, sha)}."""
        top: dict = {}
        for path, ms in files.items():
            parts = path.split(b"/")
            d = top
            for p in parts[:-1]:
                d = d.setdefault(p, {})
            d[parts[-1]] = ms

        def build(d) -> str:
            ents = []
            for name, v in d.items():
                if isinstance(v, dict):
                    ents.append(("040000", build(v), name))
                else:
                    ents.append((v[0], v[1], name))
            return self.tree(ents, missing)

        return build(top)

    def commit(self, tree: str, parent: str | None, msg: str) -> str:
        args = ["commit-tree", tree, "-m", msg] + (["-p", parent] if parent else [])
        return self(*args).decode().strip()


def fake_bare(pwned: Path) -> dict[str, bytes]:
    """A folder git's own discovery would take for a bare repository, whose config runs commands."""
    cmd = f"touch {pwned}"
    cfg = (f"[core]\n\trepositoryformatversion = 1\n\tbare = true\n\tfsmonitor = \"{cmd}\"\n\thooksPath = hooks\n"
           f"[remote \"origin\"]\n\turl = ext::sh -c \"{cmd}\"\n\tpromisor = true\n\tuploadpack = {cmd};\n"
           f"[extensions]\n\tpartialClone = origin\n[protocol]\n\tallow = always\n[core]\n\tsshCommand = {cmd}\n"
           f"[diff]\n\texternal = {cmd}\n[filter \"x\"]\n\tsmudge = {cmd}\n\tclean = {cmd}\n")
    return {"HEAD": b"ref: refs/heads/main\n", "config": cfg.encode(), "objects/info/x": b"",
            "refs/heads/main": b"0" * 40 + b"\n", "hooks/post-checkout": f"#!/bin/sh\n{cmd}\n".encode(),
            "description": b"x\n"}


def make_repo(root: Path, r: random.Random, pwned: Path, outside: Path, home: Path) -> dict:
    """One hostile repository; returns what the inputs may name (revisions, paths, features)."""
    root.mkdir(parents=True)
    g = Git(root, home)
    g("init", "-q", "-b", "main")
    feats = set(r.sample(["odd", "dups", "big", "links", "robot-link", "submodule", "fake-bare", "promisor",
                          "cfg-link", "cfg-bomb", "cfg-deep", "cfg-paths", "pr-config", "many-commits", "tags",
                          "deep-tree"], r.randrange(2, 7)))
    files: dict[bytes, tuple[str, str]] = {
        b"pkg/package.xml": ("100644", g.blob(PKG.encode())),
        b"README.md": ("100644", g.blob(b"# r\n")),
    }
    commits = []
    # first commit: no robot at all
    c = g.commit(g.nested(files), None, "start")
    commits.append(c)
    files[b"pkg/urdf/robot.urdf"] = ("100644", g.blob(CLEAN.encode()))
    cfg = b"models:\n  - path: pkg/urdf/robot.urdf\n"
    if "cfg-link" in feats:
        files[b"urdfcheck.yaml"] = ("120000", g.blob(os.fsencode(os.path.relpath(outside / "secret.yaml", root))))
    elif "cfg-bomb" in feats:
        lines = ['a0: &a0 ["x","x","x","x","x","x","x","x","x"]'] + [
            f"a{i}: &a{i} [" + ",".join([f"*a{i - 1}"] * 9) + "]" for i in range(1, 9)] + ["models: *a8"]
        files[b"urdfcheck.yaml"] = ("100644", g.blob(("\n".join(lines) + "\n").encode()))
    elif "cfg-deep" in feats:
        files[b"urdfcheck.yaml"] = ("100644", g.blob(b"models: " + b"[" * 50000 + b"]" * 50000 + b"\n"))
    elif "cfg-paths" in feats:
        files[b"urdfcheck.yaml"] = ("100644", g.blob(
            b"models:\n  - path: pkg/urdf/robot.urdf\n    controllers: [../outside/secret.yaml, /proc/self/environ]\n"
            b"    launch: [link_out/secret.yaml]\n    bags: [/etc]\npackages:\n  pkg: ../outside\n"))
    else:
        files[b"urdfcheck.yaml"] = ("100644", g.blob(cfg))
    if "links" in feats:
        for i, to in enumerate([str(outside / "secret.yaml"), "/proc/self/environ", "../../../../../../etc/passwd",
                                "loop", os.path.relpath(outside / "secret.txt", root / "pkg")]):
            files[f"pkg/l{i}.urdf".encode()] = ("120000", g.blob(to.encode()))
        files[b"loop"] = ("120000", g.blob(b"loop"))
    if "odd" in feats:
        for name in [b"a" * 300 + b".urdf", b"pkg/\xff\xfe.urdf", b"pkg/\x1b]52;c;aGk=\x07.urdf",
                     "pkg/\u202egnp.urdf".encode(), b"pkg/a\nb.urdf", b"-rf", b"--output=x.urdf", b"pkg/ .urdf",
                     b"pkg/x\r.urdf", b"pkg/" + b"d/" * 60 + b"deep.urdf", b"pkg/\xc0\xaf.urdf"]:
            files[name] = ("100644", g.blob(CLEAN.encode()))
    if "dups" in feats:
        b8 = g.blob(bytes(r.randrange(256) for _ in range(256)) * (8 * 4096))  # 8 MiB
        for i in range(120):
            files[f"dup/{i:03}.urdf".encode()] = ("100644", b8)
    if "big" in feats:
        files[b"big.urdf"] = ("100644", g.blob(b"<robot>" + b" " * (65 * 1024**2) + b"</robot>"))
    if "submodule" in feats:
        files[b"sub"] = ("160000", "1" * 40)
        files[b".gitmodules"] = ("100644", g.blob(
            f"[submodule \"sub\"]\n\tpath = sub\n\turl = ext::sh -c \"touch {pwned}\"\n\tupdate = !touch {pwned}\n"
            .encode()))
    if "fake-bare" in feats:
        for k, v in fake_bare(pwned).items():
            files[f"fake/{k}".encode()] = ("100644", g.blob(v))
    if "deep-tree" in feats:
        for i in range(300):
            files[f"many/f{i}.xacro".encode()] = ("100644", g.blob(f"<robot name='m{i}'/>".encode()))
    missing = False
    if "promisor" in feats:
        files[b"pkg/urdf/missing.urdf"] = ("100644", "f" * 40)
        missing = True
    c = g.commit(g.nested(files, missing), c, "robot")
    commits.append(c)
    if "robot-link" in feats:  # an old revision where the robot is a link out of the checkout
        f2 = dict(files)
        f2[b"pkg/urdf/robot.urdf"] = ("120000", g.blob(str(outside / "secret.yaml").encode()))
        c2 = g.commit(g.nested(f2, missing), c, "link")
        g("update-ref", "refs/heads/linked", c2)
    if "many-commits" in feats:
        for i in range(5):
            files[f"n{i}".encode()] = ("100644", g.blob(str(i).encode()))
            c = g.commit(g.nested(files, missing), c, f"c{i}")
            commits.append(c)
    g("update-ref", "refs/heads/main", c)
    g("update-ref", "refs/heads/other", commits[0])
    if "tags" in feats:
        for t in ["v1", "x\u202e", "a" * 200]:
            try:
                g("tag", t, commits[-1])
            except subprocess.CalledProcessError:
                pass
    # the working tree: every file of HEAD that can exist, then the pull request's changes
    g("read-tree", "main")
    try:
        g("checkout-index", "-a", "-f")
    except subprocess.CalledProcessError:
        pass
    (root / "pkg" / "urdf").mkdir(parents=True, exist_ok=True)
    (root / "pkg" / "urdf" / "robot.urdf").write_text(BROKEN)
    if "fake-bare" in feats:
        for k, v in fake_bare(pwned).items():
            p = root / "fake" / k
            p.parent.mkdir(parents=True, exist_ok=True)
            p.write_bytes(v)
    if "promisor" in feats:  # the runner's own clone says the missing blob is on a promisor remote
        with open(root / ".git" / "config", "a") as f:
            f.write(f"[remote \"origin\"]\n\turl = ext::sh -c \"touch {pwned}\"\n\tpromisor = true\n"
                    f"\tpartialclonefilter = blob:none\n[extensions]\n\tpartialClone = origin\n"
                    "[core]\n\trepositoryformatversion = 1\n")
    if "pr-config" in feats:  # the pull request's own config tries to lower the gate
        (root / ".urdfcheck.yaml").write_text(r.choice([
            "ignore: [ALL]\n", "severity: {ALL: info}\nfail_on: error\n", "select: [B]\n",
            "models:\n  - path: pkg/urdf/clean.urdf\n", "trusted: true\nignore: [J, S]\n"]))
        (root / "pkg" / "urdf" / "clean.urdf").write_text("<robot name='c'><link name='base_link'/></robot>\n")
    os.symlink(outside, root / "link_out")
    revs = ["HEAD", "main", "other", "HEAD~1", "HEAD~5", "HEAD^", "HEAD^{tree}", "HEAD:pkg", ":/start", "@{-1}",
            "-x", "--output=/tmp/x", "HEAD~99", "v1", "x\u202e", "a" * 200, "f" * 40, commits[0], commits[0][:7],
            "HEAD\x1b]52;c;aGk=\x07", "refs/heads/../other", "main..other", "HEAD@{1}", "", " ", "HEAD\n",
            "linked" if "robot-link" in feats else "HEAD", "origin/main", "FETCH_HEAD", "HEAD:urdfcheck.yaml"]
    paths = [[], ["."], ["pkg"], ["pkg/urdf/robot.urdf"], ["fake"], ["link_out"], ["/etc"], [".."], ["sub"],
             ["dup"], ["-rf"], ["pkg/urdf"], ["nope"]]
    return {"root": root, "feats": sorted(feats), "revs": revs, "paths": paths}


def generate(r: random.Random, repos: list[dict], i: int) -> dict:
    repo = r.randrange(len(repos))
    info = repos[repo]
    # mostly revisions and paths that resolve (the run goes past the door), at times the odd ones
    rev = r.choice(info["revs"][:4] + info["revs"][17:19]) if r.random() < 0.6 else r.choice(info["revs"])
    cmd = r.choice(["diff", "diff-change", "diff-findings", "diff-base", "config-from", "both"])
    cwd = "."
    if "fake-bare" in info["feats"] and r.random() < 0.25:
        cwd = "fake"
    paths = r.choice(info["paths"][:3]) if r.random() < 0.6 else r.choice(info["paths"])
    if cmd in ("diff", "diff-change", "diff-findings"):
        argv = ["diff", "--git", rev, *paths, "--format", FORMATS_DIFF[i % 3]]
        if cmd == "diff-change":
            argv.append("--fail-on-change")
        elif cmd == "diff-findings":
            argv.append("--findings")
    else:
        argv = ["lint", "--format", FORMATS_LINT[i % 6], "--budget", "10"]
        if cmd in ("diff-base", "both"):
            argv += ["--diff-base", rev]
        if cmd in ("config-from", "both"):
            argv += ["--config-from", rev]
        argv += [p for p in paths if p not in ("sub", "dup", "-rf", "fake")]
    must_fail = cmd in ("diff-base", "config-from", "both") or cmd == "diff-change"
    return {"i": i, "repo": repo, "cwd": cwd, "argv": argv, "must_fail": must_fail, "cmd": cmd}


def _tree_state(root: Path) -> dict:
    return harness.snapshot(root)


def do_one_factory(base: Path, repos: list[dict], marks, pwned: Path, tmp: Path):
    states = {}

    def do_one(case: dict) -> dict:
        info = repos[case["repo"]]
        root = info["root"]
        if case["repo"] not in states:
            states[case["repo"]] = _tree_state(root)
        os.chdir(root / case["cwd"])
        code, text = harness.cli(case["argv"])
        os.chdir(base)
        bad = harness.judge(code, text, marks, must_fail=False)
        if case["must_fail"] and code == 0:
            bad.append("silent")
        if case["cmd"] in ("diff-base", "config-from", "both") and "All checks passed" in text:
            bad.append("silent")
        if pwned.exists():
            bad.append("exec")
            pwned.unlink()
        after = _tree_state(root)
        if after != states[case["repo"]]:
            bad.append("writes")
            changed = sorted(set(after.items()) ^ set(states[case["repo"]].items()))[:5]
            text += f"\n[changed in the repository: {changed}]"
            states[case["repo"]] = after
        left = os.listdir(tmp)
        if left:
            bad.append("writes")
            text += f"\n[left in TMPDIR: {left[:5]}]"
            for n in left:
                shutil.rmtree(tmp / n, ignore_errors=True)
                if (tmp / n).exists():
                    os.unlink(tmp / n)
        return {"bad": bad, "outcome": f"{case['cmd']} exit {code}",
                "detail": text[:4000] if code == "EXC" else text[-1500:]}

    return do_one


def run(count: int, seed: int, nrepos: int, hang: float, batch: int, report: str | None, seconds: float | None = None):
    r = random.Random(seed)
    with harness.Session("urdfcheck-fuzzgit-", "exec") as run_:
        base = run_.base
        pwned, tmp, home = base / "PWNED", base / "tmp", base / "home"
        tmp.mkdir()
        home.mkdir()
        repos = [make_repo(base / f"r{k}", r, pwned, run_.out, home) for k in range(nrepos)]
        print(json.dumps({"repos_built": nrepos, "seconds": round(time.monotonic() - run_.t0, 1)}), flush=True)
        do_one = do_one_factory(base, repos, run_.marks, pwned, tmp)

        def show(case):
            return {**case, "feats": repos[case["repo"]]["feats"]}

        run_.steps(count, 50, seconds, report, lambda done, n: [generate(r, repos, done + k) for k in range(n)],
                   do_one, hang, batch, env={"TMPDIR": str(tmp), "HOME": str(home)}, show=show)
    return run_.result()


def main(argv=None) -> int:
    ap = harness.parser(__doc__, count=500, seed=3637, hang=30.0, batch=50)
    ap.add_argument("--repos", type=int, default=24)
    ns = ap.parse_args(argv)
    stats, examples, t0 = run(ns.count, ns.seed, ns.repos, ns.hang, ns.batch, ns.report, seconds=ns.seconds)
    rc = harness.finish(stats, examples, t0, ns.report)
    return rc or (1 if stats["exec"] else 0)


if __name__ == "__main__":
    sys.exit(main())
