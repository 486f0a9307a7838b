#!/usr/bin/env python3
"""Config-grammar fuzzer (issue 36): the pull request's urdfcheck.yaml / .urdfcheck.yaml / [tool.urdfcheck] never
makes a broken robot pass, never crashes, never leaks.

    python3 fuzz/configs.py --count 30000 --seed 3636 [--hang 20] [--report FILE]

Each input is a throw-away checkout: a package holding a broken robot (`urdf/robot.urdf`: a joint whose lower limit
lies above its upper one (J003) and a joint naming a missing link (S003), both errors), a clean decoy beside it,
a controllers file, a launch file, a recording folder, and a config in one of its places (urdfcheck.yaml,
.urdfcheck.yaml, pyproject.toml [tool.urdfcheck], the package's own urdfcheck.yaml, or several at once) whose keys
come from src/urdfcheck/schemas/config.schema.json and request/config.py (models with path/args/variants/
controllers/drivers/launch/launch_args/localization/frame_prefix/bags, frames, tf_owners, packages, select, ignore,
fail_on, severity, rules with options, trusted, cache, max_elements, target, profiles, allow_env, unknown keys) with
hostile values: huge numbers (1e309, 400-digit integers, negative), deep nesting, YAML aliases and alias bombs,
merge keys, tags, paths out of the checkout (`..`, absolute, `~`, links out, /proc/self/environ, the canary file),
every code and family, every severity, the secret variables in allow_env and in $(env ...) args.

`urdfcheck lint` runs in-process in a forked child (harness.py) in the checkout, in a report format in turn, with
`--budget 5`. Counted: silent (exit 0, or "All checks passed": the broken robot must always fail), tracebacks
(an exception, "Traceback"/"internal error", exit codes other than 0/1/2, exit 2 without a reason), leaks (the
secret of the environment, the canary file's text, an absolute temp path), hangs, writes into the checkout. Exit 1
when any count is non-zero.
"""
from __future__ import annotations

import json
import os
import random
import shutil
import sys
from pathlib import Path

HERE = Path(__file__).resolve().parent
sys.path.insert(0, str(HERE))
import harness  # noqa: E402

FORMATS = ("text", "json", "sarif", "markdown", "github", "junit")
BROKEN = harness.BROKEN  # J003 and S003, both errors
CLEAN = '<robot name="c"><link name="base_link"/><link name="b"/>' \
        '<joint name="f" type="fixed"><parent link="base_link"/><child link="b"/></joint></robot>\n'
CONTROLLERS = "controller_manager:\n  ros__parameters:\n    update_rate: 100\n" \
              "arm:\n  ros__parameters:\n    joints: [j, nope]\n"
LAUNCH = ('<launch><node pkg="robot_state_publisher" exec="robot_state_publisher"><param name="robot_description" '
          'value="$(command \'cat $(find-pkg-share pkg)/urdf/robot.urdf\')"/></node></launch>\n')
VALID_CODES = ["ALL", "B", "F", "G", "J", "S", "X", "J003", "S003", "S0", "J0", "X018", "X011", "X0", "X01", "B014",
               "S001"]
CODES = ["ALL", "A", "B", "C", "D", "F", "G", "I", "J", "K", "L", "M", "P", "R", "S", "T", "X", "J003", "S003",
         "S0", "J0", "X018", "X011", "X0", "X01", "B014", "S001", "Z999", "", "j003", "ALL ", "*", "J003,S003"]
SEVERITIES = ["info", "warning", "error", "off", "none", "INFO", "", None, 0, "ignore"]


def pick(r: random.Random, valid, hostile, p: float = 0.85):
    """Mostly a value the schema takes (so the run gets past the config to the gate), at times a hostile one."""
    return r.choice(valid) if r.random() < p else r.choice(hostile)


def _num(r: random.Random):
    if r.random() < 0.8:
        return r.choice([1, 1000, 2_000_000, 10**12, 2**63 - 1, 10**9, 0, -1])
    return r.choice([0, -1, 1, 1e309, -1e309, 10**400, 2**63, -(2**63), 1e-320, 0.5, "1e9", "nan", float("nan"),
                     True, None, "", 10**9, 3, 1e9])


def _path(r: random.Random) -> str:
    if r.random() < 0.6:
        return r.choice(["pkg/urdf/robot.urdf", "pkg/urdf/clean.urdf", "pkg/config/c.yaml", "pkg/launch/l.launch.xml",
                         "pkg", "rec", "link_out/secret.yaml", "../outside/secret.yaml", "/proc/self/environ"])
    return r.choice(["urdf/robot.urdf", "pkg/urdf/robot.urdf", "pkg/urdf/clean.urdf", "urdf/clean.urdf", ".", "..",
                     "../..", "../outside/secret.yaml", "../../outside/secret.yaml", "../../../outside", "/",
                     "/etc/passwd", "/proc/self/environ", "~", "~/.ssh/id_rsa", "link_out/secret.yaml", "link_out",
                     "pkg", "pkg/config/c.yaml", "pkg/launch/l.launch.xml", "rec", "pkg/rec", "", "\x00", "a" * 300,
                     "pkg/urdf/../../../outside/secret.txt", "fifo", "$(env URDFCHECK_FUZZ_SECRET)", "*", "**/*.urdf",
                     "pkg/urdf/robot.urdf\nx: 1", "C:\\\\windows", "file:///etc/passwd"])


def _paths(r: random.Random):
    return [_path(r) for _ in range(r.randrange(0, 3))] if r.random() < 0.9 else _path(r)


def _args(r: random.Random) -> dict:
    return {r.choice(["x", "prefix", "use_sim", "GITHUB_TOKEN", "a b", "__proto__", "1x"]):
            r.choice(["$(env GITHUB_TOKEN)", "$(env URDFCHECK_FUZZ_SECRET)", "$(optenv AWS_SECRET_ACCESS_KEY)",
                      "${''.__class__}", "true", 1, 1e309, "../outside/secret.yaml", "$(find pkg)"])
            for _ in range(r.randrange(1, 4))}


def _model(r: random.Random) -> dict:
    m: dict = {"path": r.choice(["pkg/urdf/clean.urdf", "pkg/urdf/robot.urdf", _path(r)])}
    for k in r.sample(["args", "variants", "controllers", "drivers", "launch", "launch_args", "localization",
                       "frame_prefix", "bags", "unknown"], r.randrange(0, 4)):
        if k in ("args", "launch_args"):
            m[k] = _args(r)
        elif k == "variants":
            m[k] = pick(r, ["auto", {"a": _args(r)}, {"b": {}, "c": {"x": "1"}}], [{"": {}}, "all", [1]])
        elif k == "drivers":
            m[k] = [{"file": _path(r), "joints": r.choice([["j"], "a.b", ["x"] * 3]),
                     r.choice(["odom_tf", "frames", "wheel_radius", "bogus"]): "a.b"}]
        elif k == "frame_prefix":
            m[k] = pick(r, ["", "robot1/", "a/b/"], ["\x1b]52;c;x\x07", "a" * 1000, "/", "../"])
        elif k == "unknown":
            if r.random() < 0.3:
                m["trusted"] = True
        else:
            m[k] = _paths(r)
    return m


def body(r: random.Random) -> dict:
    b: dict = {}
    keys = ["models", "frames", "tf_owners", "packages", "select", "ignore", "fail_on", "severity", "rules",
            "trusted", "cache", "max_elements", "target", "profiles", "allow_env", "unknown"]
    for k in r.sample(keys, r.randrange(1, 7)):
        if k == "models":
            b[k] = [_model(r) for _ in range(r.randrange(0, 3))] if r.random() < 0.9 else _model(r)
        elif k == "frames":
            b[k] = {pick(r, ["map", "odom", "base"], ["world"]): pick(r, ["base_link", "tool"], ["", 1])}
        elif k == "tf_owners":
            b[k] = {pick(r, ["map -> odom", "odom -> base_link", "base_link -> tool"], ["->", "a->"]):
                    pick(r, ["slam", "/robot_state_publisher", "ekf"], ["", 1])}
        elif k == "packages":
            b[k] = {r.choice(["pkg", "other", "robot_state_publisher", "", "..", "sys"]): _path(r)
                    for _ in range(r.randrange(1, 3))}
        elif k in ("select", "ignore"):
            b[k] = r.sample(VALID_CODES, r.randrange(0, 4)) if r.random() < 0.85 else (
                r.sample(CODES, r.randrange(0, 4)) if r.random() < 0.5 else r.choice(CODES))
        elif k == "fail_on":
            b[k] = pick(r, ["info", "warning", "error"], SEVERITIES)
        elif k == "severity":
            b[k] = {pick(r, VALID_CODES, CODES): pick(r, ["info", "warning", "error"], SEVERITIES)
                    for _ in range(r.randrange(1, 4))}
        elif k == "rules":
            b[k] = {pick(r, ["B005", "B013", "B011"], ["X011", "J0", "J003", "S003"]):
                    {pick(r, ["tolerance"], ["enabled", "severity", "max", "min", "ratio"]): pick(
                        r, [1e9, 1e300, 0.0, 1e-3, 10**400, float("inf")], [-1, "1e9", None, True, float("nan")])}
                    for _ in range(r.randrange(1, 3))}
        elif k == "trusted":
            b[k] = pick(r, [True, False], ["true", 1, "yes", [True], {"a": True}])
        elif k == "cache":
            b[k] = pick(r, [False, True], ["../outside", "/tmp", "link_out", ".urdfcheck-cache", {"dir": "/"}])
        elif k == "max_elements":
            b[k] = _num(r)
        elif k == "target":
            b[k] = pick(r, ["humble", "jazzy", "noetic"], ["nope", "", 1])
        elif k == "profiles":
            b[k] = pick(r, [["mujoco"], ["gazebo"], []], [["ros2"], {"x": {"select": ["J"]}}, "all", [1e309]])
        elif k == "allow_env":
            b[k] = r.sample(list(harness.SECRET_VARS) + ["HOME", "PATH", "*"], r.randrange(1, 3))
        elif r.random() < 0.2:
            b[r.choice(["trusted_", "Trusted", "ignore ", "x-gate", "fail-on"])] = r.choice([True, "ALL", "info"])
    return b


def _yaml(r: random.Random, b: dict) -> str:
    lines = [f"{k}: {json.dumps(v, allow_nan=True)}" for k, v in b.items()]
    extra = r.random()
    if extra < 0.06:  # an alias bomb under an unknown-to-the-gate key, or under ignore
        lines.append('a0: &a0 ["ALL","ALL","ALL","ALL","ALL","ALL","ALL","ALL","ALL"]')
        for i in range(1, 9):
            lines.append(f"a{i}: &a{i} [" + ",".join([f"*a{i - 1}"] * 9) + "]")
        lines.append(f"{r.choice(['ignore', 'select', 'models', 'x'])}: *a8")
    elif extra < 0.12:
        n = r.choice([50, 1000, 60000])
        lines.append(f"{r.choice(['ignore', 'models', 'rules', 'severity'])}: " + "[" * n + "]" * n)
    elif extra < 0.18:  # anchors and merge keys carrying the lowering
        lines = ["ignore: &b [ALL]", "select: *b", "severity: &s {ALL: info}", "rules: {J003: &o {tolerance: 1e9}, "
                 "S003: *o}", "fail_on: &f error"] + [ln for ln in lines if ln.split(":")[0] not in
                                                      ("ignore", "select", "severity", "rules", "fail_on")]
    elif extra < 0.22:
        lines.append(r.choice(["ignore: !!python/object/apply:os.system ['touch pwned']", "x: !!binary AAAA",
                               "fail_on: !custom info", "? [a, b]\n: c", "severity: {J: info, S: info, X: info}",
                               "ignore: [J, S, X]", "select: [B]"]))
    elif extra < 0.26:
        lines.append("max_elements: " + "9" * r.choice([400, 5000]))
    elif extra < 0.28:
        lines = ["\ufeff" + lines[0]] + lines[1:] if lines else lines
    elif extra < 0.30:
        lines.append("--- \nignore: [ALL]\n...")
    return "\n".join(lines) + "\n"


def _toml_value(v) -> str:
    if isinstance(v, bool):
        return "true" if v else "false"
    if v is None:
        return '""'
    if isinstance(v, float):
        return "inf" if v == float("inf") else "-inf" if v == float("-inf") else "nan" if v != v else repr(v)
    if isinstance(v, int):
        return str(v)
    if isinstance(v, str):
        return json.dumps(v)
    if isinstance(v, list):
        return "[" + ", ".join(_toml_value(x) for x in v) + "]"
    return "{ " + ", ".join(f"{json.dumps(str(k))} = {_toml_value(x)}" for k, x in v.items()) + " }"


def _toml(b: dict) -> str:
    return "[tool.urdfcheck]\n" + "".join(f"{json.dumps(k)} = {_toml_value(v)}\n" for k, v in b.items())


def generate(r: random.Random, i: int) -> dict:
    files: dict = {}
    places = r.sample(["urdfcheck.yaml", ".urdfcheck.yaml", "pyproject.toml"], 1)
    if r.random() < 0.3:
        places += r.sample(["pkg/urdfcheck.yaml", "pkg/pyproject.toml", "pkg/urdf/urdfcheck.yaml"], r.choice([1, 2]))
    for p in places:
        b = body(r)
        files[p] = _toml(b) if p.endswith(".toml") else _yaml(r, b)
    argv = ["lint", "--format", FORMATS[i % len(FORMATS)], "--budget", "5"]
    if r.random() < 0.15:
        argv += r.choice([["pkg"], ["pkg/urdf/robot.urdf"], ["."], ["pkg/urdf"]])
    return {"i": i, "files": files, "argv": argv}


def build(ws: Path, out: Path) -> None:
    (ws / "pkg" / "urdf").mkdir(parents=True)
    (ws / "pkg" / "config").mkdir()
    (ws / "pkg" / "launch").mkdir()
    (ws / "pkg" / "package.xml").write_text("<package format='3'><name>pkg</name></package>\n")
    (ws / "pkg" / "urdf" / "robot.urdf").write_text(BROKEN)
    (ws / "pkg" / "urdf" / "clean.urdf").write_text(CLEAN)
    (ws / "pkg" / "config" / "c.yaml").write_text(CONTROLLERS)
    (ws / "pkg" / "launch" / "l.launch.xml").write_text(LAUNCH)
    os.symlink(out, ws / "link_out")
    os.mkfifo(ws / "fifo")


def do_one_factory(base: Path, out: Path, marks):
    ws = base / "ws"

    def do_one(case: dict) -> dict:
        if ws.exists():
            shutil.rmtree(ws)
        build(ws, out)
        for rel, text in case["files"].items():
            (ws / rel).write_text(text, encoding="utf-8", errors="surrogatepass")
        code, text, bad = harness.in_checkout(ws, base, case["argv"], marks, must_fail=True)
        return {"bad": bad, "outcome": f"exit {code}", "detail": harness.detail(code, text)}

    return do_one


def run(count: int, seed: int, hang: float, batch: int, report: str | None, seconds: float | None = None):
    r = random.Random(seed)
    with harness.Session("urdfcheck-fuzzcfg-") as run_:
        do_one = do_one_factory(run_.base, run_.out, run_.marks)
        run_.steps(count, 1000, seconds, report, lambda done, n: [generate(r, done + k) for k in range(n)], do_one,
                   hang, batch)
    return run_.result()


def main(argv=None) -> int:
    ap = harness.parser(__doc__, count=1000, seed=3636, hang=20.0, batch=100)
    ns = ap.parse_args(argv)
    stats, examples, t0 = run(ns.count, ns.seed, ns.hang, ns.batch, ns.report, seconds=ns.seconds)
    return harness.finish(stats, examples, t0, ns.report)


if __name__ == "__main__":
    sys.exit(main())
