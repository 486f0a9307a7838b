#!/usr/bin/env python3
"""Grammar fuzzer for issue 19: the pull request writes the configuration and chooses which files exist.

    python3 fuzz/trust.py --count 50000 --seed 19 [--full-every 100] [--hang 20] [--report FILE]

Each input is a throw-away checkout built from two grammars:

  config     where a config lives (urdfcheck.yaml, .urdfcheck.yaml, [tool.urdfcheck] in pyproject.toml, a nested
             sub/urdfcheck.yaml or sub/pyproject.toml, a file named with --config), its keys (trusted, allow_env
             naming the secret variables, limits above and below the defaults, ignore/select/severity hiding load
             findings, packages, models with launch/controllers/localization/drivers files, unknown keys, odd
             types) and paths (/, .., ../../.., ~, an absolute folder outside the checkout holding a secret file, a
             symlink out, a symlink in, missing files), nested deeply at times;
  discovery  file layouts (a package or none, sub-packages, the robot at the root, in urdf/ or deep), how the robot
             writes its links (plain, xacro:element, an included body, a macro from a library, inside xacro:if),
             decoys that claim to include it (in a comment, in xacro:if false, in an uncalled macro, by $(find)
             path tail), macro libraries, SRDF look-alikes, filler files sorting first (with a small --max-files),
             comments and processing instructions around everything, a launch file that deploys it.

The robot always holds an expression the sandbox refuses (X011), so it cannot load: any run that reaches it must
fail, whatever the config says. Counted:

  leaks        the secret environment values or the outside file's text in any output; or, on the fast path, a
               config found in the checkout whose settings come out trusted, with allow_env, or with a package
               outside the checkout;
  tracebacks   an exception out of the planner or the CLI, "internal error" or "Traceback" in any output, an exit
               code other than 0, 1, 2;
  hangs        an input slower than --hang seconds (SIGALRM; the run goes on);
  silent       an exit 0 (full path), or a plan that neither holds the robot (as a target, a probe or a library
               the run checks was read) nor says why (X019, a usage or config error) (fast path).

The fast path plans in-process (config reading, trust screening, discovery: no expansion); every --full-every-th
input runs the whole CLI in-process (expansion in its worker, every report format in turn). Exit status 1 when any
count is non-zero.
"""
from __future__ import annotations

import argparse
import contextlib
import io
import json
import os
import random
import shutil
import signal
import sys
import tempfile
import time
from pathlib import Path

HERE = Path(__file__).resolve().parent
sys.path.insert(0, str(HERE.parent / "src"))

SECRET = "fuzz-trust-s3cr3t-4e1f"
FILE_SECRET = "fuzz-trust-file-s3cr3t-77a0"
SECRET_VARS = ("GITHUB_TOKEN", "AWS_SECRET_ACCESS_KEY", "URDFCHECK_FUZZ_SECRET")
NS = 'xmlns:xacro="http://www.ros.org/wiki/xacro"'
PAYLOAD = "${''.__class__}"  # refused by the sandbox (X011); a config cannot make that a pass
FORMATS = ("text", "json", "sarif", "github", "markdown", "junit")
INTERNAL = ("Traceback", "internal error")


class Hang(Exception):
    pass


class Raw(str):
    """Config text written as it is (deep nesting the generator itself could not build as data)."""


def _dump(v) -> str:
    return str(v) if isinstance(v, Raw) else json.dumps(v)


# --- discovery grammar ---------------------------------------------------------------------------------
def _noise(r: random.Random) -> str:
    return r.choice(["", "<!-- just a comment -->", "<?pi data?>", "<!-- <link name='ghost'/> -->",
                     "<!-- <xacro:include filename='robot.urdf.xacro'/> -->", "\n\n", "<!---->"])


def robot_text(r: random.Random, style: str) -> tuple[str, dict]:
    """The robot entry file and the files it needs."""
    joint = '<joint name="j" type="fixed"><parent link="base_link"/><child link="tool"/></joint>'
    extra: dict[str, str] = {}
    if style == "plain":
        body = f'<link name="base_{PAYLOAD}"/><link name="tool"/>{joint}'
    elif style == "element":
        body = (f'<xacro:element xacro:name="link" name="base_{PAYLOAD}"/>'
                '<xacro:element xacro:name="link" name="tool"/>' + joint)
    elif style == "body":
        body = f'<xacro:property name="p" value="{PAYLOAD}"/><xacro:include filename="body.xacro"/>'
        extra["body.xacro"] = f'<robot {NS}><link name="base_${{p}}"/><link name="tool"/>{joint}</robot>'
    elif style == "macro":
        body = f'<xacro:include filename="lib_arm.xacro"/><xacro:arm name="{PAYLOAD}"/>'
        extra["lib_arm.xacro"] = (f'<robot {NS}><xacro:macro name="arm" params="name">'
                                  f'<link name="base_${{name}}"/><link name="tool"/>{joint}</xacro:macro></robot>')
    else:  # "if"
        body = f'<xacro:if value="true"><link name="base_{PAYLOAD}"/><link name="tool"/>{joint}</xacro:if>'
    return f'<?xml version="1.0"?>{_noise(r)}\n<robot name="r" {NS}>{_noise(r)}\n  {body}\n{_noise(r)}</robot>\n', extra


def decoy_text(r: random.Random, kind: str, target: str) -> str:
    inc = f'<xacro:include filename="{target}"/>'
    inner = {
        "comment": f"<!-- {inc} -->",
        "if-false": f'<xacro:if value="false">{inc}</xacro:if>',
        "unless-true": f'<xacro:unless value="true">{inc}</xacro:unless>',
        "macro": f'<xacro:macro name="never">{inc}</xacro:macro>',
        "real": inc,
        "cdata": f"<![CDATA[ {inc} ]]>",
    }[kind]
    return f'<robot name="d" {NS}>\n  {inner}\n  <link name="base_link"/>\n</robot>\n'


def layout(r: random.Random) -> tuple[dict[str, str], str, list[str]]:
    """(files, the robot's path, CLI extras) of one checkout."""
    files: dict[str, str] = {}
    pkg = r.choice(["", "", "pkg/", "src/pkg/"])
    if r.random() < 0.8:
        files[pkg + "package.xml"] = "<package format='3'><name>pkg</name></package>"
    folder = pkg + r.choice(["urdf/", "", "description/urdf/", "models/deep/er/"])
    style = r.choice(["plain", "element", "body", "macro", "if"])
    name = r.choice(["robot.urdf.xacro", "a.xacro", "zz_robot.xacro", "robot.xacro"])
    text, extra = robot_text(r, style)
    robot = folder + name
    files[robot] = text
    for k, v in extra.items():
        files[folder + k] = v
    for i in range(r.randrange(0, 4)):
        kind = r.choice(["comment", "if-false", "unless-true", "macro", "real", "cdata"])
        up = folder.rstrip("/").split("/")[-1]
        target = r.choice([name, f"$(find pkg)/{robot[len(pkg):]}", f"./{name}", f"../{up}/{name}"])
        files[folder + f"decoy{i}.urdf.xacro"] = decoy_text(r, kind, target)
    for i in range(r.randrange(0, 3)):
        files[folder + f"lib{i}.xacro"] = (f'<robot {NS}><xacro:macro name="m{i}"><link name="x"/></xacro:macro>'
                                           "</robot>")
    if r.random() < 0.2:
        files[folder + "moveit.xacro"] = (f'<robot name="r" {NS}><group name="arm"/>'
                                          '<disable_collisions link1="a"/></robot>')
    if r.random() < 0.15:  # a skipped folder with a clean decoy: never the only thing linted
        skipped = r.choice([".hidden/", "build/", "install/"])
        files[skipped + "clean.urdf"] = "<robot name='c'><link name='base_link'/></robot>"
    cli: list[str] = []
    if r.random() < 0.25:
        for i in range(r.randrange(1, 40)):
            files[pkg + f"0000_filler/{i:04}.txt"] = "x"
        cli += ["--max-files", str(r.randrange(2, 30))]
    if r.random() < 0.2 and pkg:
        files[pkg + "launch/bringup.launch.xml"] = (
            '<launch><node pkg="robot_state_publisher" exec="robot_state_publisher"><param name="robot_description" '
            f'value="$(command \'xacro $(find-pkg-share pkg)/{robot[len(pkg):]}\')"/></node></launch>')
    return files, robot, cli


# --- config grammar ------------------------------------------------------------------------------------
def _path(r: random.Random, outside: str, robot: str) -> str:
    if r.random() < 0.5:  # inside the checkout: the plan goes on past the config
        return r.choice([".", robot, "./" + robot, "config/c.yaml", "link_in", "sub/.."])
    return r.choice([".", "..", "../..", "../../..", "/", "/etc", outside, outside + "/secret.yaml", "link_out",
                     "link_out/secret.yaml", "link_in", "~", "~/x", "sub/..", "a/../../outside", robot, "urdf",
                     "missing.yaml", "config/c.yaml", "", "./" + robot, outside + "/../" + os.path.basename(outside)])


def config_body(r: random.Random, outside: str, robot: str) -> dict:
    body: dict = {}
    keys = r.sample(["trusted", "allow_env", "max_elements", "ignore", "select", "severity", "fail_on", "packages",
                     "models"], r.randrange(1, 6))
    keys += [k for k in ("target", "unknown", "rules") if r.random() < 0.08]  # each ends most runs at exit 2
    for key in keys:
        if key == "trusted":
            body[key] = r.choice([True, True, False, "yes", 1])
        elif key == "allow_env":
            body[key] = r.sample(list(SECRET_VARS) + ["HOME", "PATH"], r.randrange(1, 4))
        elif key == "max_elements":
            body[key] = r.choice([1, 500, 2_000_000, 2_000_001, 10**12, -1])
        elif key in ("ignore", "select"):
            body[key] = r.sample(["X", "X0", "X01", "X011", "ALL", "S", "S003", "F002", "J", "X017"], r.randrange(1, 4))
        elif key == "severity":
            body[key] = {r.choice(["X", "X011", "X0", "S", "ALL"]): r.choice(["info", "warning", "error"])}
        elif key == "fail_on":
            body[key] = r.choice(["error", "warning", "info"])
        elif key == "packages":
            body[key] = {r.choice(["sys", "pkg", "x"]): _path(r, outside, robot) for _ in range(r.randrange(1, 3))}
        elif key == "models":
            m: dict = {"path": r.choice([robot, robot, _path(r, outside, robot)])}
            for sub in r.sample(["launch", "controllers", "localization", "drivers", "args"], r.randrange(0, 3)):
                if sub == "drivers":
                    m[sub] = [{"file": _path(r, outside, robot), "joints": ["a"]}]
                elif sub == "args":
                    m[sub] = {"x": "y"}
                else:
                    m[sub] = [_path(r, outside, robot)]
            body[key] = [m]
        elif key == "target":
            body[key] = r.choice(["humble", "nope"])
        elif key == "unknown":
            body["trusted_" + r.choice(["x", ""])] = True
        else:
            depth = r.choice([1, 5, 200, 5000])
            body[key] = Raw("[" * depth + "]" * depth)
    return body


def _yaml(body: dict) -> str:
    return "".join(f"{k}: {_dump(v)}\n" for k, v in body.items())


def _toml(body: dict) -> str:
    out = ["[tool.urdfcheck]"]
    tables = []
    for k, v in body.items():
        if isinstance(v, list) and v and isinstance(v[0], dict):
            for item in v:
                tables.append(f"[[tool.urdfcheck.{k}]]")
                tables += [f"{kk} = {json.dumps(vv)}" for kk, vv in item.items() if not isinstance(vv, (dict, list))
                           or (isinstance(vv, list) and not any(isinstance(x, dict) for x in vv))]
        elif isinstance(v, dict):
            out.append(f"{k} = {{ " + ", ".join(f'"{kk}" = {json.dumps(vv)}' for kk, vv in v.items()) + " }")
        else:
            out.append(f"{k} = {_dump(v)}")
    return "\n".join(out + tables) + "\n"


def place_config(r: random.Random, files: dict, robot: str, outside: str) -> tuple[list[str], dict]:
    """Adds config files; returns (CLI extras, the body)."""
    body = config_body(r, outside, robot)
    where = r.choice(["urdfcheck.yaml", ".urdfcheck.yaml", "pyproject.toml", "sub", "sub-pyproject", "named"])
    if where == "pyproject.toml":
        files["pyproject.toml"] = _toml(body)
    elif where in ("sub", "sub-pyproject"):
        sub = os.path.dirname(robot) or "."
        name = "pyproject.toml" if where == "sub-pyproject" else "urdfcheck.yaml"
        files[os.path.normpath(os.path.join(sub, name))] = _toml(body) if name.endswith("toml") else _yaml(body)
        if r.random() < 0.5:
            files["urdfcheck.yaml"] = "select: [ALL]\n"
    elif where == "named":
        files["cfg/ci.yaml"] = _yaml(body)
        return ["--config", "cfg/ci.yaml"], body
    else:
        files[where] = _yaml(body)
    return [], body


# --- running -------------------------------------------------------------------------------------------
def build(root: Path, files: dict, outside: Path) -> None:
    for name, text in files.items():
        p = root / name
        p.parent.mkdir(parents=True, exist_ok=True)
        p.write_text(text, encoding="utf-8")
    with contextlib.suppress(OSError):
        os.symlink(outside, root / "link_out")
    with contextlib.suppress(OSError):
        (root / "config").mkdir(exist_ok=True)
        (root / "config" / "c.yaml").write_text("a: 1\n")
        os.symlink(root / "config", root / "link_in")


def fast(root: Path, robot: str, cli: list[str]) -> tuple[str | None, str]:
    """Plan in-process: (problem kind or None, detail)."""
    from urdfcheck.plan.plan import Planner
    from urdfcheck.request.request import UsageError, make_request

    opts: dict = {}
    if "--config" in cli:
        opts["config"] = cli[cli.index("--config") + 1]
    if "--max-files" in cli:
        opts["max_files"] = int(cli[cli.index("--max-files") + 1])
    try:
        request = make_request([], **opts)
        planner = Planner(request, ".")
        targets = planner.plan()
    except UsageError as e:
        text = str(e)
        if SECRET in text or FILE_SECRET in text:
            return "leak", text
        return None, "usage"
    for cfg in planner._configs.values():
        if cfg is None:
            continue
        s = request.settings(cfg)
        if s.trusted or set(s.allow_env) & set(SECRET_VARS):
            return "leak", f"settings from {cfg.path}: trusted={s.trusted} allow_env={s.allow_env}"
        here = os.path.realpath(".")
        for name, p in s.packages.items():
            real = os.path.realpath(p)
            if not (real == here or real.startswith(here + os.sep)):
                return "leak", f"package {name} -> {p}"
    real = os.path.realpath(robot)
    declared = [m.path for c in planner._configs.values() if c is not None for m in c.models]
    if declared and real not in {os.path.realpath(p) for p in declared}:
        return None, "declared"  # the config's models are linted instead (not probed: see the changes note)
    covered = {os.path.realpath(t.path) for t in targets} | {os.path.realpath(p) for p in targets.included}
    if real in covered or any(f.code == "X019" for f in targets.findings):
        return None, "ok"
    # linted through a model that includes it (a decoy with a real include, a library's robot): the run's
    # backstop expands it when no model read it; what the plan holds is a robot of the tree
    return "silent", f"robot {robot} not planned; targets {[str(t.path) for t in targets]}"


# what a run that reached the robot says, in every format: the refusal (sandbox or stock xacro), a walk cut short,
# the budget, a missing package on the way
REACHED = ("X011", "X010", "X019", "X017", "X013")


def full(root: Path, cli: list[str], fmt: str, robot: str) -> tuple[str | None, str]:
    from urdfcheck.cli.main import main

    planned, _ = fast(root, robot, cli)  # the plan alone: does a config's models: list leave the robot out?
    strict = planned is None and _ == "ok"

    out, err = io.StringIO(), io.StringIO()
    with contextlib.redirect_stdout(out), contextlib.redirect_stderr(err):
        code = main(["lint", "--format", fmt, *cli])
    text = out.getvalue() + err.getvalue()
    if SECRET in text or FILE_SECRET in text:
        return "leak", text[:500]
    if any(m in text for m in INTERNAL) or code not in (0, 1, 2):
        return "traceback", f"exit {code}: {text[-500:]}"
    if code == 0:
        return "silent", text[-500:]
    named = robot in text or robot.replace("_", "\\_") in text  # Markdown escapes underscores
    if strict and code == 1 and not named and not any(c in text for c in REACHED):  # failed elsewhere
        return "silent", f"exit 1 without reaching the robot: {text[-500:]}"
    return None, f"exit {code}"


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--count", type=int, default=1000)
    ap.add_argument("--seed", type=int, default=19)
    ap.add_argument("--full-every", type=int, default=100, help="every N-th input runs the whole CLI")
    ap.add_argument("--hang", type=float, default=20.0)
    ap.add_argument("--report", help="write the counts and the first examples as JSON here")
    ns = ap.parse_args(argv)
    os.environ["URDFCHECK_DEBUG"] = "1"  # an internal error is raised, not hidden behind exit 2
    for v in SECRET_VARS:
        os.environ[v] = SECRET
    r = random.Random(ns.seed)
    counts = {"inputs": 0, "full": 0, "leaks": 0, "tracebacks": 0, "hangs": 0, "silent": 0}
    examples: list[dict] = []
    outcomes: dict[str, int] = {}  # how the inputs ended: planned, a usage/config error, exit 1 ...
    shm = "/dev/shm" if os.path.isdir("/dev/shm") and os.access("/dev/shm", os.W_OK) else None
    base = Path(tempfile.mkdtemp(prefix="urdfcheck-trust-", dir=shm))  # in memory: thousands of small trees
    outside = base / "outside"
    outside.mkdir()
    (outside / "secret.yaml").write_text(f"token: {FILE_SECRET}\n")
    old = os.getcwd()

    def alarm(*_):
        raise Hang()

    signal.signal(signal.SIGALRM, alarm)
    t0 = time.monotonic()
    try:
        for i in range(ns.count):
            root = base / f"c{i % 4}"
            shutil.rmtree(root, ignore_errors=True)
            root.mkdir()
            files, robot, cli = layout(r)
            if r.random() < 0.6:
                more, _ = place_config(r, files, robot, str(outside))
                cli += more
            build(root, files, outside)
            os.chdir(root)
            is_full = ns.full_every > 0 and i % ns.full_every == 0
            signal.setitimer(signal.ITIMER_REAL, ns.hang)
            try:
                kind, detail = (full(root, cli, FORMATS[(i // ns.full_every) % len(FORMATS)], robot) if is_full
                                else fast(root, robot, cli))
            except Hang:
                kind, detail = "hang", ""
            except BaseException as e:  # noqa: BLE001 - every escape is a finding of the fuzzer
                if isinstance(e, KeyboardInterrupt):
                    raise
                kind, detail = "traceback", f"{type(e).__name__}: {str(e)[:300]}"
            finally:
                signal.setitimer(signal.ITIMER_REAL, 0)
                os.chdir(old)
            counts["inputs"] += 1
            counts["full"] += is_full
            outcome = ("full " if is_full else "fast ") + (kind or detail)
            outcomes[outcome] = outcomes.get(outcome, 0) + 1
            if ns.report and counts["inputs"] % 500 == 0:  # a run stopped early still has its figures
                Path(ns.report).write_text(json.dumps({"counts": counts, "outcomes": outcomes, "examples": examples,
                                                       "seconds": round(time.monotonic() - t0, 1)}, indent=1))
            if kind is not None:
                counts[{"leak": "leaks", "traceback": "tracebacks", "hang": "hangs", "silent": "silent"}[kind]] += 1
                if len(examples) < 20:
                    examples.append({"input": i, "kind": kind, "full": is_full, "detail": detail, "cli": cli,
                                     "files": {k: v[:400] for k, v in files.items()
                                               if not k.startswith("0000") and "filler" not in k}})
    finally:
        shutil.rmtree(base, ignore_errors=True)
    counts["seconds"] = round(time.monotonic() - t0, 1)
    import resource

    counts["cpu_seconds"] = round(time.process_time(), 1)
    kids = resource.getrusage(resource.RUSAGE_CHILDREN)
    counts["cpu_seconds_children"] = round(kids.ru_utime + kids.ru_stime, 1)
    print(json.dumps(counts))
    if ns.report:
        Path(ns.report).write_text(json.dumps({"counts": counts, "outcomes": outcomes, "examples": examples}, indent=1))
    bad = counts["leaks"] + counts["tracebacks"] + counts["hangs"] + counts["silent"]
    return 1 if bad else 0


if __name__ == "__main__":
    sys.exit(main())
