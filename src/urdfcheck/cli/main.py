"""Command line: `urdfcheck lint|expand|rules|tree|tf|publish|verify|diff`.

Exit codes: 0 clean; 1 findings at or above --fail-on (a broken or hostile model is a finding too);
2 unusable invocation (missing path, bad flag, invalid config) or an internal error.
"""
from __future__ import annotations

import os
import sys

from urdfcheck.cli.commands import COMMANDS, PUBLISH_COMMANDS  # noqa: F401  (PUBLISH_COMMANDS: read from here)
from urdfcheck.cli.common import (  # noqa: F401  (EXIT_*, UsageError: also read from here)
    EPILOG,
    EXIT_CLEAN,
    EXIT_FINDINGS,
    EXIT_USAGE,
    UsageError,
    load_one,
    usage_message,
)

TYPE_CHECKING = False
if TYPE_CHECKING:
    import argparse


def build_parser(with_publish: bool = True, lint_only: bool = False) -> argparse.ArgumentParser:
    """`lint_only`: the other sub-commands are left out (a lint command line never reaches them; each parser costs
    argparse's message-catalogue lookups, about a millisecond)."""
    import argparse
    import functools

    from urdfcheck import __version__
    from urdfcheck.cli.parsing import Formatter, RawFormatter, add_options

    parser = argparse.ArgumentParser(
        prog="urdfcheck", description="Lint and verify ROS robot descriptions (URDF and xacro).",
        epilog=EPILOG, formatter_class=RawFormatter)
    parser.add_argument("--version", action="version", version=f"urdfcheck {__version__}")
    # every sub-command's parser with our formatter (no shutil import at start-up; see cli.parsing.Formatter)
    sub = parser.add_subparsers(dest="command", metavar="COMMAND",
                                parser_class=functools.partial(argparse.ArgumentParser, formatter_class=Formatter))

    lint = sub.add_parser("lint", help="check models and their contracts", epilog=EPILOG,
                          formatter_class=RawFormatter)
    lint.add_argument("paths", nargs="*", metavar="PATH",
                      help="URDF/xacro files or package folders (default: what the config declares, else .)")
    add_options(lint, "lint")  # every lint option, from the one table (cli/options.py)
    lint.set_defaults(func=cmd_lint)
    if lint_only:
        return parser

    bag = sub.add_parser("bag", help="check a recording (/joint_states, /tf, /tf_static) against the model",
                         description="urdfcheck bag MODEL RECORDING [lint options] is `urdfcheck lint MODEL --bag "
                         "RECORDING --select B,X`: MODEL is anything lint takes (URDF, xacro with --arg, a package "
                         "with its config); RECORDING a ROS 1 .bag, a ROS 2 bag folder, a .db3 or .mcap file, or a "
                         "YAML/JSON list of messages. Every lint option applies (--format, --joint-states, "
                         "--select, --fail-on, ...).", epilog=EPILOG, formatter_class=RawFormatter)
    bag.add_argument("model", metavar="MODEL")
    bag.add_argument("recordings", nargs="+", metavar="RECORDING")

    exp = sub.add_parser("expand", help="print the expanded URDF exactly as the rules see it")
    exp.add_argument("path", metavar="FILE")
    add_options(exp, "expand")
    exp.set_defaults(func=cmd_expand)

    rules = sub.add_parser("rules", help="list the rules, or show one rule's page")
    rules.add_argument("code", nargs="?", metavar="CODE")
    from urdfcheck.rules.docs import FORMATS as RULE_FORMATS

    rules.add_argument("--format", choices=RULE_FORMATS, default="text")
    rules.set_defaults(func=cmd_rules)

    srv = sub.add_parser("server", help="a language server (LSP over stdio) for editors: findings as you type")
    srv.add_argument("--stdio", action="store_true", help="speak over standard input and output (the default)")
    add_options(srv, "server")
    srv.set_defaults(func=cmd_server)

    if with_publish:  # skipped for lint/expand/rules: its import is a measurable part of a lint run
        from urdfcheck.cli import publish as cli_publish

        cli_publish.add_parsers(sub)
        from urdfcheck.cli import diff as cli_diff

        cli_diff.add_parser(sub)

        from urdfcheck.cli import consumers as cli_consumers

        cli_consumers.add_parser(sub)
    return parser


def cmd_server(ns) -> int:
    try:
        from urdfcheck.server import lsp
    except ImportError as e:
        raise UsageError(f"the language server needs the 'server' extra (pip install 'urdfcheck[server]'): {e}"
                         ) from None
    options = {}
    if getattr(ns, "config", None):
        options["config"] = ns.config
    if getattr(ns, "no_config", False):
        options["no_config"] = True
    return lsp.main(options)


def cmd_expand(ns) -> int:
    from urdfcheck.core import door

    with door.guarding((ns.path, getattr(ns, "config", None))):
        return _expand(ns)


def _expand(ns) -> int:
    if not os.path.isfile(ns.path):
        raise UsageError(f"no such file: {ns.path}")
    exp = load_one(ns, ns.path, build=False).expanded
    errors = [f for f in exp.findings if int(f.severity) >= 3]
    for f in exp.findings:
        print(f"{f.location}: {f.code} {f.message}", file=sys.stderr)
    if exp.root is None or errors:
        return EXIT_FINDINGS
    sys.stdout.write(exp.clean_text())
    return EXIT_CLEAN


def cmd_rules(ns) -> int:
    from urdfcheck.rules import docs as ruledocs

    if ns.code:
        text = ruledocs.page(ns.code.upper(), fmt=ns.format)
        if text is None:
            raise UsageError(f"no rule {ns.code!r}; `urdfcheck rules` lists them")
    else:
        text = ruledocs.listing(fmt=ns.format)
    sys.stdout.write(text)
    return EXIT_CLEAN


def cmd_lint(ns) -> int:
    if getattr(ns, "one_shot", False):
        # The process ends after this command (see `run`). The models it builds hold no reference cycles,
        # and the collector would only trace them: on 10,000 links, one full pass costs 80 ms.
        import gc

        gc.disable()
        _fork_xacro_worker(ns)
    from urdfcheck.cli.lint import run

    return run(ns, UsageError)


def _fork_xacro_worker(ns) -> None:
    """Fork the xacro worker before the planner and the rules are imported: it imports xacro on the other core
    meanwhile, and the first expansion is sent to it (load.loader). With other limits than these flags give
    (a config file can set them) it is not used. Only where a path may hold xacro."""
    paths = ns.paths or ["."]
    from urdfcheck.cli.early import may_hold_xacro

    if ns.list or ns.write_baseline or not may_hold_xacro(paths, ns.config or ("" if ns.no_config else None)):
        return
    reuse = sys.modules.get("urdfcheck.load.reuse")  # the lint cache offers every expansion (cli/cache.py)
    if reuse is not None and reuse.all_expected():
        return
    from urdfcheck.core import worker
    from urdfcheck.load.xacro import SPARE, SPARE_PRELOAD, XACRO_TIMEOUT, worker_limits

    worker.keep_spare(SPARE, worker_limits(bool(ns.trusted), ns.allow_env, ns.timeout or XACRO_TIMEOUT), SPARE_PRELOAD)


def bag_argv(rest: list[str]) -> list[str] | None:
    """`bag MODEL RECORDING... [options]` as the lint command it is: the first two positional words are the
    model and a recording, later positional words more recordings; without --select, the B and X rules.
    None when the model or the recording is missing."""
    from urdfcheck.cli.options import valued_flags

    out, positional, skip = ["lint"], [], False
    valued = valued_flags("lint")
    for word in rest:
        if skip:
            out.append(word)
            skip = False
        elif word.startswith("-"):
            out.append(word)
            skip = word in valued
        else:
            positional.append(word)
    if positional:
        out.insert(1, positional[0])
        for rec in positional[1:]:
            out += ["--bag", rec]
    if len(positional) < 2:
        return None
    if not any(w == "--select" or w.startswith("--select=") for w in rest):
        out += ["--select", "B,X"]
    return out


def main(argv: list[str] | None = None, *, one_shot: bool = False) -> int:
    """`one_shot`: the process exits after this call (the console entry), so lint may skip cleanup work."""
    argv = list(sys.argv[1:] if argv is None else argv)
    if argv and argv[0] == "bag" and not {"-h", "--help"} & set(argv):
        lint_argv = bag_argv(argv[1:])
        if lint_argv is None:
            print("urdfcheck bag: error: expected MODEL and RECORDING (`urdfcheck bag --help`)", file=sys.stderr)
            return EXIT_USAGE
        argv = lint_argv
    if argv and not argv[0].startswith("-") and argv[0] not in COMMANDS:
        if not os.path.exists(argv[0]) and os.sep not in argv[0] and "." not in argv[0]:
            from urdfcheck.core.findings import closest

            hint = closest(argv[0], list(COMMANDS), cutoff=0.6)
            print(f"urdfcheck: error: unknown command {argv[0]!r}" + (f" (did you mean {hint!r}?)" if hint else "")
                  + f"; commands: {', '.join(COMMANDS)}, or name files and folders to lint", file=sys.stderr)
            return EXIT_USAGE
        argv = ["lint"] + argv  # `urdfcheck model.urdf` is `urdfcheck lint model.urdf`
    ns = _plain_lint(argv)
    if ns is None:
        parser = build_parser(with_publish=not argv or argv[0] not in ("lint", "expand", "rules"),
                              lint_only=bool(argv) and argv[0] == "lint")
        ns = parser.parse_args(argv)
        if ns.command is None:
            parser.print_help()
            return EXIT_USAGE
    ns.one_shot = one_shot
    try:
        return ns.func(ns)
    except UsageError as e:
        print(usage_message(ns.command, e), file=sys.stderr)
        return EXIT_USAGE
    except KeyboardInterrupt:
        return 130
    except BrokenPipeError:
        return EXIT_CLEAN
    except Exception as e:  # never a traceback for users; URDFCHECK_DEBUG=1 shows it
        if os.environ.get("URDFCHECK_DEBUG"):
            raise
        print(f"urdfcheck {ns.command}: internal error: {type(e).__name__}: {e} "
              "(set URDFCHECK_DEBUG=1 for details and please report it)", file=sys.stderr)
        return EXIT_USAGE
    finally:
        if "urdfcheck.core.worker" in sys.modules:  # a spare worker nobody took (no xacro model after all)
            sys.modules["urdfcheck.core.worker"].drop_spares()


def _plain_lint(argv: list[str]):
    """`lint [FLAG...] [PATH...]` with flags that take no value: the namespace argparse would give, without
    importing argparse (`cli.options.plain_lint`); None for anything else (argparse reads it and says what is
    wrong)."""
    from urdfcheck.cli.options import plain_lint

    values = plain_lint(argv)
    if values is None:
        return None
    import types

    return types.SimpleNamespace(**values, func=cmd_lint)


def run(after=None) -> None:
    """The console entry point: `main`, then exit without tearing the interpreter down.

    Teardown frees a big model object by object (0.1 s for 10,000 links) and nothing needs it: every file
    we write is closed by then, atexit handlers are run and the standard streams are flushed here.
    `after(code) -> code`: the lint cache storing the run (cli/cache.py).
    """
    code = main(one_shot=True)
    if after is not None:
        code = after(code)
    import atexit

    try:
        atexit._run_exitfuncs()  # what others registered still runs (coverage's subprocess mode, logging)
    except Exception:  # noqa: BLE001 - a failing handler must not change the exit code
        pass
    for stream in (sys.stdout, sys.stderr):
        try:
            stream.flush()
        except (BrokenPipeError, ValueError):  # ValueError: closed (the language server's client hung up)
            pass
    os._exit(code)


if __name__ == "__main__":  # pragma: no cover
    run()
