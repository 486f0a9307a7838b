"""What every subcommand shares: exit codes, the usage error, load options and printing findings.

`cli.main` (lint, expand, rules) and `cli.publish` (tf, publish, tree, verify) both import this module and
never each other's internals (main only calls `publish.add_parsers`).
"""
from __future__ import annotations

import argparse
import os
import sys

from urdfcheck.request.request import UsageError  # noqa: F401  (the one usage error: API and CLI)

EXIT_CLEAN, EXIT_FINDINGS, EXIT_USAGE = 0, 1, 2

class Formatter(argparse.HelpFormatter):
    """argparse's help formatter, with the terminal width read the way shutil.get_terminal_size reads it but
    without importing shutil: argparse builds a formatter for every add_argument, and that import (with bz2,
    lzma, fnmatch) is 1.7 ms of every start-up."""

    def __init__(self, prog, indent_increment=2, max_help_position=24, width=None):
        super().__init__(prog, indent_increment, max_help_position, _columns() - 2 if width is None else width)


class RawFormatter(argparse.RawDescriptionHelpFormatter, Formatter):
    """The same, with descriptions and epilogs printed as written."""


def _columns() -> int:
    try:
        return int(os.environ["COLUMNS"])
    except (KeyError, ValueError):
        pass
    try:
        return os.get_terminal_size(sys.__stdout__.fileno()).columns
    except (AttributeError, ValueError, OSError):
        return 80


EPILOG = """exit codes:
  0  no findings at or above --fail-on
  1  findings at or above --fail-on (a malformed or hostile model is a finding too)
  2  unusable invocation: missing path, bad flag, unknown rule code, invalid config file; or an internal error
"""


def kv(sep: str, what: str):
    """argparse type for NAME<sep>VALUE."""

    def parse(text: str):
        if sep not in text:
            raise argparse.ArgumentTypeError(f"expected {what}, got {text!r}")
        k, v = text.split(sep, 1)
        if not k:
            raise argparse.ArgumentTypeError(f"expected {what}, got {text!r}")
        return k, v

    return parse


def add_load_options(p: argparse.ArgumentParser) -> None:
    p.add_argument("--arg", dest="args", action="append", default=[], type=kv(":=", "NAME:=VALUE"),
                   metavar="NAME:=VALUE", help="xacro argument (repeatable)")
    p.add_argument("--package", dest="packages", action="append", default=[], type=kv("=", "NAME=PATH"),
                   metavar="NAME=PATH", help="where a ROS package lives, for $(find) and package:// (repeatable)")
    p.add_argument("--trusted", action="store_true", default=None,
                   help="evaluate xacro with stock Python eval and allow $(env): only for your own files")
    p.add_argument("--allow-env", action="append", default=[], metavar="VAR",
                   help="environment variable that $(env)/$(optenv) may read in the sandbox (repeatable)")
    p.add_argument("--timeout", type=float, default=20.0, metavar="SECONDS",
                   help="wall-clock limit for one xacro expansion (default 20)")
    p.add_argument("--max-elements", type=int, default=None, metavar="N",
                   help="xacro elements one expansion may evaluate (default 20000; 400000 with --trusted); "
                        "a macro bomb stops here")
    p.add_argument("--budget", type=float, default=None, metavar="SECONDS",
                   help="wall-clock budget for the whole run, all models and variants (default 300, or "
                        "URDFCHECK_RUN_BUDGET); what it leaves unlinted is an X017 finding")


def add_config_options(p: argparse.ArgumentParser) -> None:
    """The config options of the commands that load one model (expand, tf, publish, tree, verify)."""
    p.add_argument("--config", metavar="FILE", help="config file (default: urdfcheck.yaml found upward)")
    p.add_argument("--no-config", action="store_true", help="ignore config files")


def load_one(ns, path: str, build: bool = True):
    """The model at `path` as `urdfcheck lint` loads it (the same request: config, packages, limits),
    the load flags over the config: a `run.Loaded`. Raises UsageError."""
    from urdfcheck.request.request import make_request
    from urdfcheck.run import load

    request = make_request(
        [path], args=dict(getattr(ns, "args", None) or []), packages=dict(ns.packages),
        trusted=True if ns.trusted else None, allow_env=tuple(ns.allow_env), timeout=ns.timeout,
        max_elements=ns.max_elements, config=getattr(ns, "config", None),
        use_config=not getattr(ns, "no_config", False), budget=getattr(ns, "budget", None))
    return load(request, path, build=build)


def print_findings(findings, stream=None) -> None:
    """Loader findings on stderr, one line each (commands that print a model, not a report)."""
    from urdfcheck.core.findings import clean_text

    for f in findings:
        print(f"{clean_text(str(f.location), 4096)}: {f.code} {clean_text(f.message)}", file=stream or sys.stderr)


def usage_message(command: str, error: Exception) -> str:
    return f"urdfcheck {command}: error: {error}"
