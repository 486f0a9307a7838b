#!/usr/bin/env python3
"""Grammar fuzzer for issue 11's class: guarded functions and bound methods handed to other functions as values.

    python3 fuzz/callables.py --count 50000 --seed 1 [--cli-every 50] [--hang 5] [--report FILE]

Each input is a tiny xacro (and sometimes a YAML file it loads) built from a grammar of

  producers  callables that leave the evaluator as values: str.format/format_map with attribute-walking templates
             (to os.environ, sys.argv, module files), ljust/center/zfill/join/replace/expandtabs, math.factorial/comb/
             perm/prod, sum, round, xacro.tokenize, list/sorted/frozenset, python.type/vars, xacro helpers ...
  targets    what they are applied to: every xacro helper closure and class (their __globals__ reach os and sys),
             namespaces, huge integers, backtracking regexes, ranges, files outside the package ...
  carriers   how C code gets to call them: map, python.map, nested maps, filter, sorted/min/max(key=), a property,
             a dict or a list holding the callable, comprehensions/enumerate/zip/join over a map, $(eval) with split
             underscores, a YAML unit tag (!degrees) ...

and is expanded by the sandbox (`load.xacro.expand`, exactly as the worker runs it) in a forked child that keeps a
secret environment variable and an argv marker (the evaluator is tested on its own, without the worker's scrubbed
environment). Every `--cli-every`-th input also goes through the whole CLI (worker, rules, reports).

Counted: leaks (the secret, the argv marker, the outside file's text, a module file path or the workspace's absolute
path in any output), tracebacks (an exception out of `expand`, an internal name in a message, a CLI exit code other
than 0/1 or an "internal error"), hangs (an input taking longer than --hang seconds: the child is killed, the run goes
on). Exit status 1 when any is non-zero. tests/project/test_fuzz.py runs a few hundred of the same inputs through
hypothesis.
"""
from __future__ import annotations

import json
import os
import random
import shutil
import sys
import tempfile
import time
from pathlib import Path

HERE = Path(__file__).resolve().parent
sys.path.insert(0, str(HERE.parent / "src"))
sys.path.insert(0, str(HERE))
import harness  # noqa: E402

SECRET_VAR = harness.SECRET_VAR
SECRET = harness.SECRET  # what harness.run_batches puts in a child's environment
ARGV_MARK = "FUZZ_ARGV_MARK_71c3"
FILE_SECRET = "fuzz-file-s3cr3t-5a1b"
NS = 'xmlns:xacro="http://www.ros.org/wiki/xacro"'
LEAK_MARKERS = (SECRET, ARGV_MARK, FILE_SECRET, "site-packages", "/src/urdfcheck/", "__init__.py", "safeeval.py",
                "expand.py", "/usr/lib/python")
INTERNAL = ("Traceback", "'Passed'", "_invoke", "_screen", "object has no attribute '_fn'", "internal error")

# templates as properties: '}' cannot appear inside ${...}
TEMPLATES = {
    "T": "{0.__globals__[os].environ[" + SECRET_VAR + "]}",
    "A": "{0.__globals__[sys].argv}",
    "F": "{0.__globals__[__file__]}",
    "M": "{arg.__globals__[os].environ[" + SECRET_VAR + "]}",
    "G": "{0.__getattr__.__globals__[os].environ[" + SECRET_VAR + "]}",
    "C": "{0.__class__.__mro__[1].__subclasses__}",
    "I": "{0.__init__.__globals__[sys].argv}",
    "W": "{:>999999999}",
    "WM": "{a:>999999999}",
    "N": "{0:{1}}",
    "P": "plain {0} text",
}
PRELUDE = "".join(f'  <xacro:property name="{k}" value="{v}"/>\n' for k, v in TEMPLATES.items())

PRODUCERS = [
    "T.format", "A.format", "F.format", "G.format", "C.format", "I.format", "W.format", "N.format", "P.format",
    "M.format_map", "WM.format_map", "'x'.ljust", "'x'.rjust", "'x'.center", "'1'.zfill", "('x'*1000).join",
    "('a'*10000).replace", "('\\t'*10000).expandtabs", "'a b'.split", "'abc'.count", "math.factorial", "factorial",
    "math.comb", "math.perm", "math.prod", "math.lcm", "math.isqrt", "math.pow", "python.sum", "round",
    "python.round", "xacro.tokenize", "list", "python.list", "python.sorted", "sorted", "python.frozenset",
    "python.set", "python.tuple", "str", "python.repr", "python.map", "python.filter", "python.type", "python.vars",
    "python.get('type')", "python.get('vars')", "xacro.load_yaml", "xacro.abs_filename", "xacro.arg", "xacro.fatal",
    "xacro.message", "xacro.warning", "xacro.print_location", "xacro.dotify", "range", "python.range",
    "python.enumerate", "python.zip", "python.isinstance", "python.divmod", "python.hash", "python.abs", "int",
    "float", "dict", "python.dict", "python.all", "python.any", "python.max", "python.min", "len",
    "dict(a=1).get", "[1, 2].index", "python.values", "xacro.get", "python.slice", "python.reversed", "math.gcd",
    "math.fsum", "math.dist", "math.hypot", "math.ldexp",
]
TARGETS = [
    "xacro.arg", "xacro.fatal", "xacro.load_yaml", "xacro.tokenize", "xacro.dotify", "xacro.message",
    "xacro.abs_filename", "sorted", "range", "python", "xacro", "math", "python.map", "T.format", "python.type",
    "10**9", "10**7", "5*10**6", "3*10**6", "-10**8", "10**5000", "2**99999", "1", "0", "-1", "1.5", "1e308", "'x'",
    "''", "'a'*40+'!'", "',]|(a|aa)+$|[,'", "'((a+)+)+$'", "['y'*1000]*10000", "[[0]*10000]*3000",
    "range(10**8)", "python.range(10**18)", "'../../../outside/secret.yaml'", "'/etc/passwd'",
    "'../config/u.yaml'", "dict(a=1)", "dict(a=T.format)", "[T.format]", "[xacro.arg]", "[1, 2, 3]", "None",
    "True", "(1, 2)", "python.values()", "xacro.values()", "'{0}'",
]


def _call_shapes(p: str, x: str, y: str) -> list[str]:
    return [
        f"list(map({p}, [{x}]))",
        f"list(map({p}, [{x}], [{y}]))",
        f"list(python.map({p}, [{x}]))[0]",
        f"sorted([{x}, {y}], key={p})",
        f"python.sorted([{x}], key={p})",
        f"min([{x}, {y}], key={p})",
        f"max([{x}], key={p})",
        f"list(python.filter({p}, [{x}]))",
        f"list(list(map(python.map, [{p}], [[{x}]]))[0])",
        f"list(list(list(map(python.map, [python.map], [[{p}]], [[[{x}]]]))[0])[0])",
        f"dict(f={p})['f']({x})",
        f"[{p}][0]({x})",
        f"''.join(map(str, map({p}, [{x}])))",
        f"[s for s in map({p}, [{x}])]",
        f"python.tuple(map({p}, [{x}]))",
        f"list(python.enumerate(map({p}, [{x}])))",
        f"dict(python.zip([1], map({p}, [{x}])))",
        f"python.sum(map(len, map(str, map({p}, [{x}]))))",
        f"{p}({x})",
        f"{p}({x}, {y})",
        f"list(map(python.map, [{p}], [[{x}], [{y}]]))",
        f"str({p})",
        f"[f({x}) for f in [{p}]]",
        f"python.any(map({p}, [{x}]))",
    ]


# producers with the targets that make them bite (half of the inputs): walks from helper closures, costs from sizes
PAIRED = [
    (["T.format", "A.format", "F.format", "I.format"], ["xacro.arg", "xacro.fatal", "xacro.load_yaml",
                                                         "xacro.tokenize", "xacro.message", "sorted", "range"]),
    (["G.format"], ["xacro.dotify"]), (["M.format_map"], ["xacro", "dict(arg=xacro.arg)"]),
    (["C.format"], ["1", "'x'", "xacro.arg"]), (["W.format", "N.format"], ["1", "10**9"]),
    (["'x'.ljust", "'x'.rjust", "'x'.center", "'1'.zfill", "('\\t'*10000).expandtabs"], ["10**9", "10**8"]),
    (["math.factorial", "factorial", "math.isqrt"], ["10**7", "5*10**6", "10**5000"]),
    (["math.comb", "math.perm"], ["10**7", "3*10**6"]), (["round", "python.round"], ["1"]),
    (["python.sum"], ["[[0]*10000]*3000"]), (["('x'*1000).join"], ["['y'*1000]*10000"]),
    (["xacro.tokenize"], ["'a'*40+'!'"]), (["list", "python.sorted", "python.frozenset", "python.set"],
                                           ["range(10**8)", "python.range(10**18)"]),
    (["python.type", "python.vars", "python.get('type')", "python.get('vars')"], ["xacro", "1", "xacro.arg"]),
    (["xacro.load_yaml"], ["'../../../outside/secret.yaml'", "'/etc/passwd'"]),
    (["xacro.abs_filename"], ["'x.yaml'", "'../config/u.yaml'"]),
]
SECOND = {"math.comb": ["5*10**6", "3*10**6"], "math.perm": ["3*10**6"], "round": ["-10**8", "-10**9"],
          "python.round": ["-10**8"], "xacro.tokenize": ["',]|(a|aa)+$|[,'", "'((a+)+)+$'"], "python.sum": ["[]"],
          "N.format": ["999999999", "'>999999999'"]}


def generate(rng: random.Random) -> dict:
    """One input: {"xacro": text, "yaml": text or None, "line": the payload's line}."""
    p, x, y = rng.choice(PRODUCERS), rng.choice(TARGETS), rng.choice(TARGETS)
    if rng.random() < 0.5:
        ps, xs = rng.choice(PAIRED)
        p, x = rng.choice(ps), rng.choice(xs)
        y = rng.choice(SECOND.get(p, [x]))
    expr = rng.choice(_call_shapes(p, x, y))
    how = rng.random()
    yaml_text = None
    head = f'<robot name="v" {NS}>\n  <link name="a"/>\n{PRELUDE}'
    if how < 0.12:  # the callable stored in a property first
        body = (f'  <xacro:property name="f" value="${{{p}}}"/>\n'
                f'  <link name="l${{{rng.choice(_call_shapes("f", x, y))}}}"/>\n')
    elif how < 0.22:  # $(eval): the expression smuggled through a property (it ends at the first ')')
        e = expr.replace("T.format", "('{0._' '_globals_' '_[os].environ[" + SECRET_VAR + "]}').format")
        e = e.replace("A.format", "('{0._' '_globals_' '_[sys].argv}').format").replace('"', "'")
        e = e.replace("xacro.", "").replace("python.", "").replace("math.", "")
        e = e.replace("arg", rng.choice(["arg", "dirname", "env", "optenv", "find"]))
        body = (f'  <xacro:property name="E" value="{_attr(e)}"/>\n'
                f'  <link name="l$(eval ${{E}})"/>\n')
    elif how < 0.30:  # a YAML unit tag evaluates its scalar
        tag = rng.choice(["!degrees", "!radians", "!meters", "!millimeters", "!foot", "!inches"])
        e = expr
        for k, v in TEMPLATES.items():
            e = e.replace(f"{k}.format", f"'{v}'.format")
        yaml_text = f"# unit tag\nangle: {tag} {json.dumps(e)}\n"
        body = '  <link name="l${xacro.load_yaml(\'../config/u.yaml\').angle}"/>\n'
    else:
        body = f'  <link name="l${{{_attr(expr)}}}"/>\n'
    text = head + body + "</robot>\n"
    return {"xacro": text, "yaml": yaml_text, "line": text.count("\n", 0, text.rfind("<link name=\"l")) + 1}


def _attr(s: str) -> str:
    return s.replace("&", "&amp;").replace("<", "&lt;").replace('"', "&quot;")


# ---- running ----------------------------------------------------------------------------------------------------

class Workspace:
    def __init__(self):
        self.root = Path(tempfile.mkdtemp(prefix="urdfcheck-callables-"))
        self.pkg = self.root / "ws" / "fuzz_description"
        for d in ("urdf", "config"):
            (self.pkg / d).mkdir(parents=True)
        (self.pkg / "package.xml").write_text("<package format='3'><name>fuzz_description</name></package>\n")
        out = self.root / "outside"
        out.mkdir()
        (out / "secret.yaml").write_text(f"x: {FILE_SECRET}\n")
        self.entry = self.pkg / "urdf" / "p.urdf.xacro"

    def place(self, case: dict) -> Path:
        self.entry.write_text(case["xacro"], encoding="utf-8")
        u = self.pkg / "config" / "u.yaml"
        if case.get("yaml") is not None:
            u.write_text(case["yaml"], encoding="utf-8")
        elif u.exists():
            u.unlink()
        return self.entry


def leaks(text: str, ws: Workspace) -> list[str]:
    return [m for m in LEAK_MARKERS + (str(ws.root),) if m in text]


def do_one_factory(ws_root: str):
    """`do_one(case)` for harness.run_batches: in its forked child, the sandbox's expander in-process (xacro's
    module state restored after each input); the child's first input sets it up (the argv marker, the resolver)."""
    state: dict = {}

    def setup() -> None:
        sys.argv.append(ARGV_MARK)
        import xacrostate

        from urdfcheck.load.packages import Resolver
        from urdfcheck.load.xacro import expand as xexpand

        ws = Workspace.__new__(Workspace)
        ws.root = Path(ws_root)
        ws.pkg = ws.root / "ws" / "fuzz_description"
        ws.entry = ws.pkg / "urdf" / "p.urdf.xacro"
        os.chdir(ws.root)
        state.update(ws=ws, expand=xexpand, restore=xacrostate.snapshot(),
                     resolver=Resolver({}, near=ws.entry.resolve()))

    def do_one(case: dict) -> dict:
        if not state:
            setup()
        ws, xexpand = state["ws"], state["expand"]
        entry = ws.place(case)
        err = sys.stderr
        try:
            res = xexpand.expand(os.path.relpath(entry, ws.root), xexpand.Options(resolver=state["resolver"]))
            text = res.get("xml") or ""
            error = res.get("error") or {}
            msg = str(error.get("message", ""))
            code = error.get("code") or "ok"
            # whole outputs are checked for leaks here; only a bounded excerpt travels to the parent
            found = [m for m in LEAK_MARKERS + (str(ws.root),) if m in text or m in msg]
            ok, shown = True, text[-2000:] + " " + msg[:2000]
        except BaseException as e:  # noqa: BLE001 - this is what is counted
            code, found, ok, shown = "EXC", [], False, f"{type(e).__name__}: {e}"[:2000]
        finally:
            sys.stderr = err
            state["restore"]()
        bad = []
        if found:
            bad.append("leaks")
        if not ok or any(m in shown for m in INTERNAL):
            bad.append("tracebacks")
        return {"bad": bad, "outcome": code, "detail": f"{found} {shown[:500]}" if bad else ""}

    return do_one


def run(count: int, seed: int, hang: float, cli_every: int, batch: int = 400) -> tuple[dict, list]:
    """(figures, failing examples): every input expanded in forked children (harness.run_batches), then every
    `cli_every`-th through the whole CLI."""
    from urdfcheck.load.xacro import expand as xexpand

    xexpand.preload()
    rng = random.Random(seed)
    cases = [generate(rng) for _ in range(count)]
    ws = Workspace()
    stats, examples = harness.new_stats(), []
    stats["cli_runs"] = 0
    t0 = time.monotonic()
    try:
        harness.run_batches(cases, do_one_factory(str(ws.root)), hang, batch, stats, examples,
                            show=lambda case: case["xacro"][-400:])
        if cli_every:
            stats["cli_runs"] = _cli_runs(cases[::cli_every], ws, stats, examples, hang)
    finally:
        shutil.rmtree(ws.root, ignore_errors=True)
    stats["seconds"] = round(time.monotonic() - t0, 1)
    return stats, examples


def _cli_runs(cases: list[dict], ws: Workspace, stats: dict, examples: list, hang: float) -> int:
    """The same inputs through the real CLI in a subprocess-free way: the CLI entry point, the forked worker."""
    import contextlib
    import gc
    import io

    from urdfcheck.cli.main import main

    old_env, old_argv = os.environ.get(SECRET_VAR), list(sys.argv)
    os.environ[SECRET_VAR] = SECRET
    sys.argv.append(ARGV_MARK)
    old = os.getcwd()
    os.chdir(ws.root)
    try:
        for i, case in enumerate(cases):
            entry = ws.place(case)
            out, err = io.StringIO(), io.StringIO()
            t = time.monotonic()
            # every other run as the console runs: with the spare xacro worker forked before the planner
            with contextlib.redirect_stdout(out), contextlib.redirect_stderr(err):
                code = main(["lint", "--no-config", "--format", "json", "--timeout", "5",
                             os.path.relpath(entry, ws.root)], one_shot=bool(i % 2))
            gc.enable()  # a console run pauses the collector for the rest of its process
            took = time.monotonic() - t
            text = out.getvalue() + err.getvalue()
            if code not in (0, 1) or any(m in text for m in INTERNAL):
                stats["tracebacks"] += 1
                examples.append(("cli", code, text[:500], case["xacro"][-400:]))
            found = leaks(text, ws)
            if found:
                stats["leaks"] += 1
                examples.append(("cli-leak", found, case["xacro"][-400:]))
            if took > hang + 5:  # the worker's own limit is 5 s
                stats["hangs"] += 1
                examples.append(("cli-slow", round(took, 1), case["xacro"][-400:]))
    finally:
        os.chdir(old)
        sys.argv[:] = old_argv
        if old_env is None:
            os.environ.pop(SECRET_VAR, None)
        else:
            os.environ[SECRET_VAR] = old_env
    return len(cases)


def main(argv=None) -> int:
    ap = harness.parser(__doc__, count=5000, seed=1, hang=5.0, batch=400)
    ap.add_argument("--cli-every", type=int, default=50, help="every N-th input also through the whole CLI (0: none)")
    ns = ap.parse_args(argv)
    t0 = time.monotonic()
    stats, examples = run(ns.count, ns.seed, ns.hang, ns.cli_every, ns.batch)
    stats.pop("seconds")
    harness.finish(stats, examples, t0, ns.report)
    return 1 if stats["leaks"] or stats["tracebacks"] or stats["hangs"] else 0


if __name__ == "__main__":
    sys.exit(main())
