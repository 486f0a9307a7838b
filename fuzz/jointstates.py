#!/usr/bin/env python3
"""Joint-states fuzzer (issue 36): the YAML/JSON joint-state file the runner names, as the pull request left it,
through `urdfcheck publish MODEL --joint-states FILE`, `urdfcheck bag MODEL FILE` and `urdfcheck lint MODEL --bag
FILE`.

    python3 fuzz/jointstates.py --count 12000 --seed 3638 [--hang 15] [--report FILE]

Each input is a checkout holding the fixture robot (tests/fixtures/ros1/robot.urdf) and one joint-state file whose
document comes from a grammar of what `publish` reads (bag/source.py `text_items`, publisher/messages.py
`JointState.from_dict`):

  containers  a YAML list, a JSON list, {"messages": [...]} in either, YAML documents after `---`, one JSON object;
  messages    name/names, position/positions/velocity/effort, stamp as seconds, [sec, nanosec], {sec, nanosec},
              {secs, nsecs} or header.stamp, topic, callerid, transforms (parent/child/translation/rotation), with
              hostile values: NaN, infinities, 400-digit and 5000-digit integers, booleans, nulls, nested lists,
              strings where numbers go, terminal escapes and bidi controls in names, 100 KB names, unequal lengths;
  whole files alias bombs, deep nesting, 100,000 messages, 64 MiB and past it, not UTF-8, a BOM, tags
              (!!python/object), NUL bytes, an empty file;
  the file    a link out of the checkout (the canary file, /proc/self/environ, /dev/zero, a folder link), a FIFO,
              a folder, a link loop, odd names (a newline, escapes, bidi, 250 characters, not UTF-8, a leading
              dash, `metadata.yaml`, no suffix).

Every grammar document holds one readable message naming `ghost_joint`, which the robot lacks (B001, a warning) and
not its wheels (B002, an error); anything else in it is either read or said unreadable (B014). So a run that exits
0 is a silent pass, except `publish` of a whole-file shape that holds no JointState at all (the run must still end
with a reason). Counted as in harness.py (leaks, tracebacks, hangs, silent, writes), plus `controls`: a raw escape
or bidi character from the input in what is printed. Exit 1 when any count is non-zero.
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

FIXTURE = HERE.parent / "tests" / "fixtures" / "ros1" / "robot.urdf"
ROBOT_JOINTS = ["left_wheel_joint", "right_wheel_joint", "arm_joint"]
CONTROLS = ("\x1b", "\u202e", "\u2066", "\x07", "\x9b")
FORMATS = ("text", "json", "sarif", "markdown", "github", "junit")


# --- values -----------------------------------------------------------------------------------------------------
def _number(r: random.Random):
    if r.random() < 0.6:
        return r.choice([0.0, 0.1, -1.5, 2.0, 1, 0, 3.14159, 1e-9])
    return r.choice([float("nan"), float("inf"), float("-inf"), 1e308, -1e308, 10**400, -(10**400), 2**63, 2**64,
                     True, False, None, "nan", "NaN", "inf", "1.5", "", "x", [1], {"a": 1}, 1e-320, -0.0,
                     "\x1b]52;c;aGk=\x07"])


def _name(r: random.Random):
    if r.random() < 0.7:
        return r.choice(ROBOT_JOINTS + ["ghost_joint", "laser_joint", "nope"])
    return r.choice(["", " ", "a" * 100_000, "\x1b]52;c;aGk=\x07", "j\u202egnp", "\u2066x\u2069", "a\nb", "a\rb",
                     "::error::x", "<script>", "@someone", "[x](http://e.x)", "\x00", 1, 2.5, None, True, [1],
                     {"a": 1}, "\ud800" if False else "\ufeff", "../../outside", "$(env GITHUB_TOKEN)"])


def _stamp(r: random.Random):
    if r.random() < 0.6:
        return r.choice([0.1, 1.0, 12.5, 0, 3, [1, 500], {"sec": 2, "nanosec": 10}, {"secs": 3, "nsecs": 4}])
    return r.choice([float("nan"), float("inf"), -float("inf"), -1.0, 1e308, 10**400, 10**30, -(10**30), True,
                     None, "1.0", "x", [1], [1, 2, 3], [float("inf"), 0], [1, float("nan")], [10**400, 0],
                     {"sec": float("inf")}, {"sec": 1, "nanosec": float("nan")}, {"sec": "x"}, {"sec": [1]},
                     {"sec": 10**400, "nanosec": -(10**400)}, {"secs": None}, {}, {"nanosec": 2**64},
                     [None, None], ["1", "2"], [True, False]])


def _vector(r: random.Random, n: int):
    if r.random() < 0.75:
        return [_number(r) if r.random() < 0.2 else round(r.uniform(-3, 3), 3) for _ in range(n)]
    return r.choice([[], None, "1, 2", 5, {"a": 1}, [_number(r) for _ in range(r.randrange(0, 6))],
                     [[1, 2]] * n, [0.0] * (n + r.randrange(1, 4)), [0.0] * 10_000])


def _message(r: random.Random) -> dict:
    m: dict = {}
    k = r.random()
    if k < 0.15:  # a TF message
        m["topic"] = r.choice(["/tf", "/tf_static", "/tf", "tf"])
        m["transforms"] = r.choice([
            [{"parent": r.choice(["base_link", "odom", _name(r)]), "child": r.choice(["laser", "arm_link", _name(r)]),
              "translation": _vector(r, 3), "rotation": r.choice([[0, 0, 0, 1], _vector(r, 4)]),
              **({"stamp": _stamp(r)} if r.random() < 0.5 else {})} for _ in range(r.randrange(0, 3))],
            None, [], "x", [1], [{"parent": "a"}], [{"child": "b", "translation": [1, 2]}]])
        if r.random() < 0.5:
            m["stamp"] = _stamp(r)
        return m
    names = [_name(r) for _ in range(r.randrange(0, 5))]
    m[r.choice(["name", "name", "names"])] = names if r.random() < 0.9 else r.choice(["arm_joint", None, 3, {"a": 1}])
    m[r.choice(["position", "position", "positions"])] = _vector(r, len(names))
    for f in ("velocity", "effort"):
        if r.random() < 0.3:
            m[f] = _vector(r, len(names))
    if r.random() < 0.8:
        if r.random() < 0.8:
            m["stamp"] = _stamp(r)
        else:
            m["header"] = r.choice([{"stamp": _stamp(r)}, {"frame_id": "x"}, None, "h", {"stamp": {"sec": 1}}])
    if r.random() < 0.15:
        m["topic"] = r.choice(["/joint_states", "/other", "", None, 7, "/tf", "\x1b[2J", "/j" * 200])
    if r.random() < 0.1:
        m["callerid"] = r.choice(["/rsp", "\x1b]52;c;x\x07", 1, None, "a" * 10_000])
    if r.random() < 0.05:
        m[r.choice(["unknown", "__proto__", "name ", "!!python"])] = _number(r)
    return m


ANCHOR = {"name": ["ghost_joint", "arm_joint"], "position": [0.1, 0.2], "stamp": 0.5}


# --- documents --------------------------------------------------------------------------------------------------
def _yaml_scalar(v) -> str:
    if isinstance(v, float):
        return ".nan" if v != v else ".inf" if v == float("inf") else "-.inf" if v == float("-inf") else repr(v)
    if isinstance(v, bool):
        return "true" if v else "false"
    if v is None:
        return "null"
    if isinstance(v, int):
        return str(v)
    return json.dumps(v)  # a JSON string is a YAML double-quoted scalar


def to_yaml(v, indent: str = "") -> str:
    """Block YAML by hand (PyYAML would refuse nothing we want to write, but this keeps NaN and 400-digit
    integers in the spellings a person would type)."""
    if isinstance(v, dict):
        if not v:
            return "{}"
        return "{" + ", ".join(f"{json.dumps(str(k))}: {to_yaml(x)}" for k, x in v.items()) + "}"
    if isinstance(v, list):
        return "[" + ", ".join(to_yaml(x) for x in v) + "]"
    return _yaml_scalar(v)


def _json(v) -> str:
    return json.dumps(v, allow_nan=True)  # NaN/Infinity: Python's json reads them, as the reader does


def document(r: random.Random, msgs: list) -> bytes:
    form = r.choice(["yaml-list", "json-list", "json-messages", "yaml-messages", "yaml-docs", "yaml-block"])
    if form == "json-list":
        text = "[" + ",".join(_json(m) for m in msgs) + "]"
    elif form == "json-messages":
        text = '{"messages": [' + ", ".join(_json(m) for m in msgs) + "]}"
    elif form == "yaml-messages":
        text = "messages:\n" + "".join(f"  - {to_yaml(m)}\n" for m in msgs)
    elif form == "yaml-docs":
        text = "".join(f"---\n- {to_yaml(m)}\n" for m in msgs)
    elif form == "yaml-block":
        text = ""
        for m in msgs:
            lines = [f"{json.dumps(str(k))}: {to_yaml(v)}" for k, v in m.items()] or ["{}"]
            text += "- " + "\n  ".join(lines) + "\n"
    else:
        text = "".join(f"- {to_yaml(m)}\n" for m in msgs)
    return text.encode("utf-8", "surrogatepass")


def whole_file(r: random.Random, small: bool = False) -> tuple[bytes, bool]:
    """A hostile whole file: (bytes, holds the anchor message). `small` (the test suite's slice): the same shapes
    at sizes that take no time to write (none past the 64 MiB cap)."""
    k = r.choice(["alias", "deep-yaml", "deep-json", "many", "big-json", "past-cap", "bad-utf8", "bom", "tags",
                  "nul", "empty", "scalar", "huge-int", "long-name", "anchors", "crlf", "json-garbage-tail"])
    anchor = "- " + to_yaml(ANCHOR) + "\n"
    if k == "alias":
        lines = ['a: &a ["ghost_joint","x","x","x","x","x","x","x","x"]']
        for i in range(1, 9):
            lines.append(f"a{i}: &a{i} [" + ",".join([f"*a{i - 1}" if i > 1 else "*a"] * 9) + "]")
        lines.append("messages: [{name: *a8, position: [1]}]")
        return ("\n".join(lines) + "\n").encode(), True
    if k == "deep-yaml":
        n = r.choice([100, 5000, 100_000])
        return (anchor + "- {name: " + "[" * n + "]" * n + "}\n").encode(), True
    if k == "deep-json":
        n = r.choice([100, 5000, 200_000])
        return ("[" + _json(ANCHOR) + ', {"name": ' + "[" * n + "]" * n + "}]").encode(), True
    if k == "many":
        item = _json({"name": ["ghost_joint"], "position": [0.1], "stamp": 0.1})
        n = r.choice([1000, 10_000] if small else [10_000, 100_000, 400_000])
        return ("[" + ",".join([item] * n) + "]").encode(), True
    if k == "big-json":  # just under the 64 MiB cap: one huge name
        size = (2 if small else 63) * 1024**2
        return ('[' + _json(ANCHOR) + ', {"name": ["' + "a" * size + '"], "position": [1]}]').encode(), True
    if k == "past-cap" and not small:
        return (anchor + "# " + "x" * (65 * 1024**2) + "\n").encode(), True
    if k == "bad-utf8":
        return anchor.encode() + b"- name: [\xff\xfe\xc3, \xed\xa0\x80]\n  position: [0, 1]\n", True
    if k == "bom":
        return "\ufeff".encode() + r.choice([anchor.encode(), ("[" + _json(ANCHOR) + "]").encode()]), True
    if k == "tags":
        return anchor.encode() + r.choice([b"- !!python/object/apply:os.system ['touch PWNED']\n",
                                           b"- !!python/name:os.system\n", b"- !custom {name: [a]}\n",
                                           b"- {name: !!binary AAAA, position: [1]}\n",
                                           b"- {name: [!!timestamp 2001-12-14], position: [1]}\n"]), True
    if k == "nul":
        return anchor.encode() + b"- {name: [\"a\x00b\"], position: [1]}\n\x00\x00", True
    if k == "empty":
        return r.choice([b"", b"\n", b"---\n", b"[]", b"{}", b"null\n", b"# only a comment\n"]), False
    if k == "scalar":
        return r.choice([b"42\n", b"'x'\n", b"true\n", b"[1, 2, 3]\n", b'"\\u001b]52;c;x\\u0007"\n',
                         b"{messages: 3}\n", b'{"messages": null}']), False
    if k == "huge-int":
        return (anchor + "- {name: [arm_joint], position: [1], stamp: " + "9" * r.choice([400, 5000]) + "}\n"
                ).encode(), True
    if k == "long-name":
        n = r.choice([10_000, 500_000 if small else 5_000_000])
        return (anchor + "- {name: [" + "n" * n + "], position: [1]}\n").encode(), True
    if k == "anchors":
        return (anchor + "- &x {name: [ghost_joint], position: [0.1], stamp: 0.1}\n" + "- *x\n" * 20_000
                ).encode(), True
    if k == "crlf":
        return anchor.replace("\n", "\r\n").encode() + b"- {name: [a], position: [1]}\r", True
    return ("[" + _json(ANCHOR) + "] trailing [garbage").encode(), True


# --- the file ---------------------------------------------------------------------------------------------------
NAMES = ["js.yaml", "js.json", "js.yml", "states.YAML", "js", "js.txt", "metadata.yaml", "sub/js.yaml",
         "a\nb.yaml", "\x1b]52;c;aGk=\x07.yaml", "\u202elmay.json", "-js.yaml", "a" * 250 + ".yaml", "sp ace.json",
         b"\xff\xfejs.yaml", "::error::x.yaml", "js.yaml.bag", ".js.yaml"]


def generate(r: random.Random, i: int, small: bool = False) -> dict:
    name = r.choice(NAMES[:3]) if r.random() < 0.6 else r.choice(NAMES)
    if isinstance(name, bytes):
        name = os.fsdecode(name)
    how = r.random()
    kind, strict, files = "grammar", True, {}
    if how < 0.72:
        msgs = [_message(r) for _ in range(r.randrange(0, 6))]
        msgs.insert(r.randrange(len(msgs) + 1), dict(ANCHOR))
        files[name] = document(r, msgs)
    elif how < 0.87:
        data, strict = whole_file(r, small)
        kind = "whole"
        files[name] = data
    else:
        kind = r.choice(["link-out", "link-secret-txt", "link-environ", "link-zero", "link-folder", "link-loop",
                         "fifo", "folder", "link-inside", "dangling", "link-dir-out"])
        strict = kind in ("link-inside", "fifo", "folder", "dangling", "link-loop") or kind.startswith("link")
        if kind == "link-out":
            files[name] = ("symlink", "OUT/secret.yaml")
        elif kind == "link-secret-txt":
            files[name] = ("symlink", "../OUT/secret.txt")
        elif kind == "link-environ":
            files[name] = ("symlink", "/proc/self/environ")
        elif kind == "link-zero":
            files[name] = ("symlink", r.choice(["/dev/zero", "/dev/urandom", "/dev/stdin", "/proc/self/fd/0"]))
        elif kind == "link-folder":
            files["sub"] = ("symlink", "OUT")
            name = "sub/secret.yaml"
        elif kind == "link-dir-out":
            files["sub"] = ("symlink", "../OUT")
            name = "sub/secret.txt"
        elif kind == "link-loop":
            files[name] = ("symlink", os.path.basename(name))
        elif kind == "fifo":
            files[name] = ("fifo",)
        elif kind == "folder":
            files[name + "/x.yaml"] = document(r, [dict(ANCHOR)])
        elif kind == "link-inside":
            files["real.yaml"] = document(r, [dict(ANCHOR)])
            files[name] = ("symlink", "real.yaml")
        else:
            files[name] = ("symlink", "nothere.yaml")
    cmd = r.choice(["publish", "publish", "bag", "lint"])
    arg = name if not name.startswith("-") else "./" + name
    if cmd == "publish":
        argv = ["publish", "robot.urdf", "--joint-states", arg]
        argv += r.choice([[], [], ["--ros", "ros1"], ["--ignore-timestamp"], ["--frame-prefix", "\x1b[31mp/"],
                          ["--publish-frequency", r.choice(["0.001", "1000", "1e-300"])], ["--no-tf-static",
                                                                                          "--ros", "ros1"]])
    elif cmd == "bag":
        argv = ["bag", "robot.urdf", arg, "--format", FORMATS[i % len(FORMATS)]]
    else:
        argv = ["lint", "robot.urdf", "--bag", arg, "--format", FORMATS[i % len(FORMATS)]]
    argv += ["--budget", "3"] + (["--no-cache"] if cmd != "publish" else [])
    if cmd == "publish" and kind == "whole" and not strict:
        strict = False  # a file without any JointState: publish says so on stderr, the exit code is its own
    return {"i": i, "kind": kind, "files": files, "argv": argv, "strict": strict, "cmd": cmd, "name": name}


def place(ws: Path, case: dict, out: Path) -> None:
    if os.path.lexists(ws):
        shutil.rmtree(ws, ignore_errors=True)
        if os.path.lexists(ws):
            os.system(f"rm -rf '{ws}'")
    ws.mkdir(parents=True)
    shutil.copyfile(FIXTURE, ws / "robot.urdf")
    for rel, v in case["files"].items():
        p = ws / rel
        p.parent.mkdir(parents=True, exist_ok=True)
        if isinstance(v, tuple) and v[0] == "symlink":
            to = v[1]
            if to.startswith("OUT"):
                to = to.replace("OUT", str(out), 1)
            elif to.startswith("../OUT"):
                to = os.path.join(os.path.relpath(out, p.parent), to[len("../OUT/"):])
            os.symlink(to, p)
        elif isinstance(v, tuple):
            os.mkfifo(p)
        else:
            p.write_bytes(v)


def _controls(case: dict, text: str) -> bool:
    """A raw escape or bidi character in what was printed (the input's, never let through as it is)."""
    return any(c in text for c in CONTROLS)


def do_one_factory(base: Path, out: Path, marks):
    ws = base / "ws"

    def do_one(case: dict) -> dict:
        place(ws, case, out)
        code, text, bad = harness.in_checkout(ws, base, case["argv"], marks, must_fail=case["strict"])
        if _controls(case, text):
            bad.append("controls")
        return {"bad": bad, "outcome": f"{case['cmd']} {case['kind']} exit {code}",
                "detail": harness.detail(code, text)}

    return do_one


def show(case: dict) -> dict:
    return {"i": case["i"], "kind": case["kind"], "argv": case["argv"], "name": case["name"],
            "files": {k: (list(v) if isinstance(v, tuple) else v[:600].decode("utf-8", "replace") + (
                f"... ({len(v)} bytes)" if len(v) > 600 else "")) for k, v in case["files"].items()}}


def run(count: int, seed: int, hang: float, batch: int, report: str | None, seconds: float | None = None,
        small: bool = False):
    r = random.Random(seed)
    with harness.Session("urdfcheck-fuzzjs-", "controls") as run_:
        do_one = do_one_factory(run_.base, run_.out, run_.marks)
        run_.steps(count, 500, seconds, report, lambda done, n: [generate(r, done + k, small) for k in range(n)],
                   do_one, hang, batch, show=show)
    return run_.result()


def main(argv=None) -> int:
    ap = harness.parser(__doc__, count=1000, seed=3638, hang=15.0, batch=100)
    ns = ap.parse_args(argv)
    stats, examples, t0 = run(ns.count, ns.seed, ns.hang, ns.batch, ns.report, seconds=ns.seconds)
    rc = harness.finish(stats, examples, t0, ns.report)
    return rc or (1 if stats["controls"] else 0)


if __name__ == "__main__":
    sys.exit(main())
