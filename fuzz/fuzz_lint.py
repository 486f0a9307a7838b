#!/usr/bin/env python3
"""Coverage-guided fuzzing of `urdfcheck lint` with atheris (libFuzzer for Python).

Each input is one byte that picks the kind of file and the report format, followed by the file's bytes:

    kind = data[0] % 4:  0 .urdf   1 .urdf.xacro   2 controller .yaml   3 launch .xml
    format = (data[0] // 4) % 6: text, json, sarif, junit, github, markdown

The file is written into a throw-away package (package.xml + a small plain URDF for the YAML/launch kinds, which
are linted as `urdfcheck lint PACKAGE_DIR` so the contracts readers see them) and the real CLI runs in-process with
URDFCHECK_DEBUG=1, so an internal error surfaces as the Python exception (a crash for libFuzzer) instead of exit 2.
xacro expansion runs in the forked, rlimited worker exactly as in production (its code is not coverage-guided);
`--inprocess-xacro` expands in-process instead (coverage of the expander and the evaluator; libFuzzer's -timeout
and -rss_limit_mb stand in for the worker's limits).

Properties checked on every input (a violation raises, which libFuzzer records as a crash):
  exit code 0 or 1; JSON/SARIF parse and the JSON report validates against report.schema.json; no ESC/BEL/CR byte
  and no line starting with `::`/`##vso[`/`##[` other than our own GitHub annotations; nothing is created in the
  working directory; the canary command of code-execution payloads never ran.

Usage (see fuzz/README.md):
    python3 fuzz/fuzz_lint.py --make-corpus fuzz/corpus            # seeds from examples/ and the shared corpus
    python3 fuzz/fuzz_lint.py fuzz/corpus -dict=fuzz/urdf.dict -artifact_prefix=fuzz/crashes/ \\
        -max_len=65536 -timeout=30 -rss_limit_mb=4096 -max_total_time=600
    python3 fuzz/fuzz_lint.py --export fuzz/crashes/crash-<sha1> tests/regressions/   # crash -> regression file
    python3 fuzz/fuzz_lint.py --replay FILE...                      # run inputs once, without libFuzzer
"""
from __future__ import annotations

import contextlib
import hashlib
import io
import json
import os
import re
import shutil
import sys
import tempfile
from pathlib import Path

HERE = Path(__file__).resolve().parent
REPO = HERE.parent
sys.path.insert(0, str(REPO / "src"))

KINDS = ("urdf", "xacro", "yaml", "launch")
SUFFIX = {"urdf": ".urdf", "xacro": ".urdf.xacro", "yaml": ".controllers.yaml", "launch": ".launch.xml"}
FORMATS = ("text", "json", "sarif", "junit", "github", "markdown")
MARKER = "URDFCHECK_FUZZ_PWNED"
BASE_URDF = (Path(__file__).resolve().parent / "base.urdf").read_bytes()  # also seeds tests/regressions
OUR_ANNOTATION = re.compile(r"^::(error|warning|notice) [^\n]*::[^\n]*$")


def split(data: bytes) -> tuple[str, str, bytes]:
    if not data:
        return "urdf", "json", b""
    return KINDS[data[0] % len(KINDS)], FORMATS[(data[0] // len(KINDS)) % len(FORMATS)], data[1:]


def join(kind: str, payload: bytes, fmt: str = "json") -> bytes:
    return bytes([KINDS.index(kind) + len(KINDS) * FORMATS.index(fmt)]) + payload


class Workspace:
    """One temp folder reused for every input: <root>/ws/fuzz_description/{package.xml, urdf/, config/, launch/}."""

    def __init__(self):
        self.root = Path(tempfile.mkdtemp(prefix="urdfcheck-atheris-"))
        self.pkg = self.root / "ws" / "fuzz_description"

    def reset(self) -> None:
        shutil.rmtree(self.root / "ws", ignore_errors=True)
        for d in ("urdf", "config", "launch"):
            (self.pkg / d).mkdir(parents=True)
        (self.pkg / "package.xml").write_text("<package format='3'><name>fuzz_description</name></package>\n")

    def place(self, kind: str, payload: bytes) -> Path:
        """Write the input; returns the path to lint (the file, or the package for YAML/launch)."""
        self.reset()
        if kind in ("urdf", "xacro"):
            f = self.pkg / "urdf" / ("robot" + SUFFIX[kind])
            f.write_bytes(payload)
            return f
        (self.pkg / "urdf" / "robot.urdf").write_bytes(BASE_URDF)
        if kind == "yaml":
            (self.pkg / "config" / "controllers.yaml").write_bytes(payload)
        else:
            (self.pkg / "launch" / "bringup.launch.xml").write_bytes(payload)
        return self.pkg


_WS: Workspace | None = None


def _inprocess_worker():
    """Replace the forked worker by a direct call that restores xacro's pristine module state afterwards."""
    sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))  # this folder: the shared harness helpers
    import xacrostate

    from urdfcheck.core import worker

    restore = xacrostate.snapshot()

    def run(fn, *args, timeout=None, memory=None, capture_fd2=False, env_keep=(), scrub_env=True, grace=None,
            **kwargs):
        err = sys.stderr
        try:
            return fn(*args, **kwargs)
        except MemoryError:
            return worker.Failure("memory", "out of memory")
        except RecursionError:
            return worker.Failure("error", "recursion too deep")
        finally:
            sys.stderr = err
            restore()

    def start(fn, *args, **kwargs):  # what the loader calls: a Job that is already done
        return worker.Job(None, None, None, None, value=run(fn, *args, **kwargs))

    worker.run = run
    worker.start = start


def check_output(fmt: str, out: str) -> None:
    if "\x1b" in out or "\x07" in out or "\r" in out:
        raise AssertionError(f"{fmt}: control character in the report")
    for ln in out.splitlines():
        s = ln.lstrip()
        if s.startswith("::") and not (fmt == "github" and OUR_ANNOTATION.match(ln)):
            raise AssertionError(f"{fmt}: injected workflow command {ln[:200]!r}")
        if s.startswith(("##vso[", "##[")):
            raise AssertionError(f"{fmt}: injected logging command {ln[:200]!r}")
    if fmt in ("json", "sarif"):
        doc = json.loads(out)
        if fmt == "json":
            from jsonschema import Draft202012Validator

            schema = json.loads((REPO / "src" / "urdfcheck" / "schemas" / "report.schema.json").read_text())
            errors = list(Draft202012Validator(schema).iter_errors(doc))
            if errors:
                raise AssertionError(f"report does not match the schema: {errors[0].message}")


def run_one(data: bytes) -> None:
    """One input through the CLI; raises on any property violation."""
    global _WS
    from urdfcheck.cli.main import main

    if _WS is None:
        _WS = Workspace()
    kind, fmt, payload = split(data)
    target = _WS.place(kind, payload)
    before = sorted(os.listdir(_WS.root))
    out, err = io.StringIO(), io.StringIO()
    old = os.getcwd()
    os.chdir(_WS.root)
    try:
        with contextlib.redirect_stdout(out), contextlib.redirect_stderr(err):
            code = main(["lint", "--no-config", "--format", fmt, "--color", "never", "--timeout", "10",
                         os.path.relpath(target, _WS.root)])
    finally:
        os.chdir(old)
    if code not in (0, 1):
        raise AssertionError(f"exit code {code}: {err.getvalue()[:2000]}")
    if "Traceback" in err.getvalue() or "internal error" in err.getvalue():
        raise AssertionError(err.getvalue()[:2000])
    check_output(fmt, out.getvalue())
    if sorted(os.listdir(_WS.root)) != before or (_WS.root / MARKER).exists():
        raise AssertionError("the input created files in the working directory")


def TestOneInput(data: bytes) -> None:  # noqa: N802 - atheris' name
    run_one(data)


# ---- corpus and crash helpers -----------------------------------------------------------------------

def make_corpus(dest: Path) -> int:
    """Seed inputs: every URDF/xacro/YAML/launch XML of examples/ and the shared corpus, tagged with its kind."""
    corpus = Path(os.environ.get("URDFCHECK_CORPUS", REPO.parent / "shared" / "corpus"))
    dest.mkdir(parents=True, exist_ok=True)
    n = 0
    for base in (REPO / "examples", corpus, REPO / "tests" / "hostile" / "data", REPO / "tests" / "regressions"):
        if not base.is_dir():
            continue
        for f in sorted(base.rglob("*")):
            name = f.name
            kind = ("xacro" if name.endswith(".xacro") else "urdf" if name.endswith(".urdf")
                    else "yaml" if name.endswith((".yaml", ".yml"))
                    else "launch" if name.endswith((".launch.xml", ".launch"))
                    else None)
            if kind is None or not f.is_file() or f.stat().st_size > 65536:
                continue
            payload = f.read_bytes().replace(b"@MARKER@", MARKER.encode()).replace(b"@PKG@", b"fuzz_description")
            payload = payload.replace(b"@OUTSIDE@", b"/tmp").replace(b"@CANARY_VAR@", b"HOME")
            for fmt in ("json", FORMATS[n % len(FORMATS)]):
                data = join(kind, payload, fmt)
                (dest / hashlib.sha1(data).hexdigest()).write_bytes(data)
            n += 1
    # issue 11: callables handed out as values (fuzz/callables.py's grammar), as xacro seeds for libFuzzer to mutate
    sys.path.insert(0, str(HERE))
    import random

    from callables import generate

    rng = random.Random(11)
    for _ in range(200):
        data = join("xacro", generate(rng)["xacro"].encode("utf-8"), "json")
        (dest / hashlib.sha1(data).hexdigest()).write_bytes(data)
        n += 1
    return n


def export(crash: Path, dest_dir: Path) -> Path:
    """Turn a libFuzzer artefact into a regression file named by kind (tests/regressions/README.md)."""
    kind, _fmt, payload = split(crash.read_bytes())
    dest_dir.mkdir(parents=True, exist_ok=True)
    what, _, digest = crash.name.rpartition("-")  # crash-<sha1>, slow-unit-<sha1>, timeout-<sha1>, oom-<sha1>
    out = dest_dir / f"{what or 'input'}-{digest[:12]}{SUFFIX[kind]}"
    out.write_bytes(payload)
    return out


def main(argv: list[str]) -> int:
    if argv[1:2] == ["--make-corpus"]:
        print(f"{make_corpus(Path(argv[2]))} seed files written to {argv[2]}")
        return 0
    if argv[1:2] == ["--export"]:
        print(export(Path(argv[2]), Path(argv[3])))
        return 0
    if "--inprocess-xacro" in argv:
        argv = [a for a in argv if a != "--inprocess-xacro"]
        _inprocess_worker()
    os.environ["URDFCHECK_DEBUG"] = "1"  # internal errors raise instead of becoming exit code 2
    os.environ.setdefault("NO_COLOR", "1")
    if argv[1:2] == ["--replay"]:
        bad = 0
        for f in argv[2:]:
            try:
                run_one(Path(f).read_bytes())
                print(f"ok    {f}")
            except Exception as e:  # noqa: BLE001 - report every failing input
                bad += 1
                print(f"FAIL  {f}: {type(e).__name__}: {e}")
        return 1 if bad else 0
    import atheris

    with atheris.instrument_imports(include=["urdfcheck"]):
        import urdfcheck.cli.main  # noqa: F401
        import urdfcheck.core.xmlfront  # noqa: F401
        import urdfcheck.load.loader  # noqa: F401
        import urdfcheck.load.xacro.expand  # noqa: F401
        import urdfcheck.load.xacro.safeeval  # noqa: F401
        import urdfcheck.model.build  # noqa: F401
        import urdfcheck.report  # noqa: F401
        import urdfcheck.run  # noqa: F401
        for mod in ("urdfcheck.load.discover", "urdfcheck.consumers.consumers", "urdfcheck.consumers.launch.xml",
                    "urdfcheck.consumers.yamlsrc", "urdfcheck.consumers.controllers", "urdfcheck.rules.engine",
                    "urdfcheck.rules.checks.structure", "urdfcheck.rules.checks.joints",
                    "urdfcheck.rules.checks.geometry",
                    "urdfcheck.rules.checks.inertial", "urdfcheck.rules.checks.frames", "urdfcheck.rules.checks.values",
                    "urdfcheck.report.text", "urdfcheck.report.jsonout", "urdfcheck.report.sarif",
                    "urdfcheck.report.junit", "urdfcheck.report.github", "urdfcheck.report.markdown"):
            with contextlib.suppress(ImportError):
                __import__(mod)
    atheris.Setup(argv, TestOneInput)
    atheris.Fuzz()
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
