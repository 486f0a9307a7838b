"""What every subcommand shares: exit codes, the usage error, load options and printing findings.

`cli.main` (lint, expand, rules) and `cli.publish` (tf, publish, tree, verify) both import this module and
never each other's internals (main only calls `publish.add_parsers`).
"""
from __future__ import annotations

import sys

from urdfcheck.request.request import UsageError  # noqa: F401  (the one usage error: API and CLI)

EXIT_CLEAN, EXIT_FINDINGS, EXIT_USAGE = 0, 1, 2

EPILOG = """exit codes:
  0  no findings at or above --fail-on
  1  findings at or above --fail-on (a malformed or hostile model is a finding too)
  2  unusable invocation: missing path, bad flag, unknown rule code, invalid config file; or an internal error
"""


def load_one(ns, path: str, build: bool = True):
    """The model at `path` as `urdfcheck lint` loads it (the same request: config, packages, limits),
    the load flags over the config: a `run.Loaded`. Raises UsageError."""
    from urdfcheck.cli.options import request_fields
    from urdfcheck.request.request import make_request
    from urdfcheck.run import load

    request = make_request([path], **request_fields(ns, getattr(ns, "command", None) or "expand"))
    return load(request, path, build=build)


def print_findings(findings, stream=None) -> None:
    """Loader findings on stderr, one line each (commands that print a model, not a report)."""
    from urdfcheck.core.findings import clean_text, escape_bidi

    for f in findings:  # a file name may hold bidi controls (the pull request names its files)
        print(escape_bidi(f"{clean_text(str(f.location), 4096)}: {f.code} {clean_text(f.message)}"),
              file=stream or sys.stderr)


def usage_message(command: str, error: Exception) -> str:
    """The one line of an unusable invocation; the paths it names may be the pull request's file names, so
    control and bidi characters are shown, not obeyed (lines kept: some reasons list choices one a line)."""
    from urdfcheck.core.findings import clean_text, escape_bidi

    text = "\n".join(escape_bidi(clean_text(line, 4096)) for line in str(error).split("\n"))
    return f"urdfcheck {command}: error: {text}"
