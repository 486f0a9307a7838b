"""Every option that fills a lint request, declared once: its flags, what it takes, its help, the `LintRequest`
field it fills and the commands that take it (as sqlfluff's option groups do).

The argparse set-up (`cli.parsing.add_options`), the request mapping (`request_fields`), the cache fast path's list
of flags that take a value (cli/cache.py) and `urdfcheck bag`'s reading of its command line (cli/main.py) are all
made from `OPTIONS`. Pure data and plain functions: the cache fast path imports this module before argparse.

Choices are named, not copied: "formats" is report.FORMATS, "targets" model.grammar.TARGETS, "severities"
core.findings.Severity (`choices`); the config and report schemas' enums are written from the same lists
(`python tools/schemas.py --write`, with core.evidence.HOW for the evidence steps).
"""
from __future__ import annotations

# command groups: the sub-commands that load a model the way lint does
LINT = "lint"
LOADERS = ("lint", "expand", "tf", "publish", "tree", "verify", "consumers", "diff", "ament")
CONFIGURED = ("lint", "expand", "tf", "publish", "tree", "verify", "consumers", "diff", "ament", "server")


class Option:
    """`flags`: the spellings; `dest`: the parsed name; `field`: the LintRequest field it fills (None: the command
    uses it itself); `value`: "flag" (no value), "one", "append" (repeatable); `type`: a name `cli.parsing` turns into
    an argparse type ("codes", "severity", "kv:=", "kv=", "float", "int") or None (text); `choices`: a named list
    (`choices`) or None; `commands`: the commands that take it."""

    __slots__ = ("flags", "dest", "field", "value", "type", "choices", "default", "metavar", "help", "commands")

    def __init__(self, flags, dest, field, value="one", type=None, choices=None, default=None, metavar=None,
                 help=None, commands=(LINT,)):
        self.flags, self.dest, self.field, self.value, self.type = tuple(flags), dest, field, value, type
        self.choices, self.default, self.metavar, self.help = choices, default, metavar, help
        self.commands = frozenset(commands)

    @property
    def takes_value(self) -> bool:
        return self.value != "flag"

    @property
    def unset(self):
        """What the parsed option holds when the command line does not give it (argparse's default, and
        `plain_lint`'s): None for the flags a config may also set (the config then decides), False for other
        flags, else the table's default."""
        if self.value == "flag":
            return None if self.dest in ("trusted", "trust_config") else False
        return self.default


OPTIONS = (
    # loading a model
    Option(["--arg"], "args", "args", "append", "kv:=", default=[], metavar="NAME:=VALUE",
           help="xacro argument (repeatable)", commands=LOADERS),
    Option(["--package"], "packages", "packages", "append", "kv=", default=[], metavar="NAME=PATH",
           help="where a ROS package lives, for $(find) and package:// (repeatable)", commands=LOADERS),
    Option(["--trusted"], "trusted", "trusted", "flag",
           help="evaluate xacro with stock Python eval and allow $(env): only for your own files",
           commands=LOADERS[:-1]),
    Option(["--allow-env"], "allow_env", "allow_env", "append", default=[], metavar="VAR",
           help="environment variable that $(env)/$(optenv) may read in the sandbox (repeatable)",
           commands=LOADERS[:-1]),
    Option(["--timeout"], "timeout", "timeout", type="float", default=20.0, metavar="SECONDS",
           help="wall-clock limit for one xacro expansion (default 20)", commands=LOADERS[:-1]),
    Option(["--max-elements"], "max_elements", "max_elements", type="int", metavar="N",
           help="xacro elements one expansion may evaluate (default 20000; 400000 with --trusted); a macro bomb "
                "stops here", commands=LOADERS[:-1]),
    Option(["--budget"], "budget", "budget", type="float", metavar="SECONDS",
           help="wall-clock budget for the whole run, all models and variants (default 300, or "
                "URDFCHECK_RUN_BUDGET); what it leaves unlinted is an X017 finding", commands=LOADERS[:-1]),
    # the config
    Option(["--config"], "config", "config", metavar="FILE",
           help="config file (default: urdfcheck.yaml found upward)", commands=CONFIGURED),
    Option(["--no-config"], "no_config", "use_config", "flag", help="ignore config files",
           commands=CONFIGURED[:-2] + ("server",)),
    Option(["--trust-config"], "trust_config", "trust_config", "flag",
           help="the --config FILE is yours: honour what lowers the guard there (trusted, allow_env, higher limits, "
                "paths outside the checkout, ignore, select, severity, fail_on, rule options, packages, models as "
                "the only ones); a config found in the checkout, or named without this flag, may only add checks"),
    # what is checked and how strictly
    Option(["--select"], "select", "select", "append", "codes", default=[], metavar="CODES",
           help="only these rule codes or prefixes, comma-separated (e.g. S,J002)"),
    Option(["--ignore"], "ignore", "ignore", "append", "codes", default=[], metavar="CODES",
           help="skip these rule codes or prefixes"),
    Option(["--fail-on"], "fail_on", "fail_on", type="severity", metavar="LEVEL",
           help="exit 1 when a finding is at least this severe: error, warning (default), info",
           commands=(LINT, "ament", "pytest")),
    Option(["--max-files"], "max_files", "max_files", type="int", metavar="N",
           help="files the walk of one package looks at (default 20000); a walk cut short is X019"),
    Option(["--target"], "target", "target", choices="targets",
           help="ROS distribution whose urdfdom must read the models (URDF versions, U007): one of %(choices)s; "
                "default: the config's target, else noetic for a catkin package, else what the workspace names "
                "(ROS_DISTRO in CI files, .repos, Dockerfile FROM ros:..., branch), else humble"),
    Option(["--profile"], "profile", "profiles", metavar="NAMES",
           help="consumer profiles, comma-separated: mujoco, gazebo, isaac, kdl, pinocchio, pybullet, moveit (what "
                "each will reject or silently change; config key profiles)"),
    Option(["--root"], "root", "root", metavar="DIR",
           help="show paths relative to DIR (default: the working directory)"),
    Option(["--baseline"], "baseline", "baseline", metavar="FILE", help="only fail on findings not in this baseline",
           commands=(LINT, "pytest")),
    Option(["--bag"], "bags", "bags", "append", default=[], metavar="RECORDING",
           help="also check a recording against the model: a ROS 1 .bag, a ROS 2 bag folder, a .db3 or .mcap file, "
                "or a YAML/JSON list of messages (repeatable; `urdfcheck bag` is the short form)"),
    Option(["--joint-states"], "joint_states", "joint_states", metavar="TOPIC",
           help="the recordings' JointState topic (default /joint_states, else the only one)"),
    # lint's own: what it prints and where
    Option(["--format"], "format", None, choices="formats", default="text",
           help="report format on stdout (default text)"),
    Option(["--output", "-o"], "output", None, metavar="FILE", help="write the report to FILE instead of stdout"),
    Option(["--report"], "report", None, "append", "kv=", default=[], metavar="FORMAT=FILE",
           help="also write another format to a file (repeatable)"),
    Option(["--color"], "color", None, choices="colors", default="auto"),
    Option(["--list"], "list", None, "flag",
           help="print what would be linted (models, variants, deployments from launch files) and exit"),
    Option(["--write-baseline"], "write_baseline", None, metavar="FILE",
           help="write current findings as a baseline and exit 0"),
    Option(["--diff-base"], "diff_base", None, metavar="REV",
           help="also lint git revision REV (read with git into a temporary folder, nothing checked out) and tell "
                "new, fixed and unchanged findings; --fail-on then applies to new ones only"),
    Option(["--config-from"], "config_from", None, metavar="REV",
           help="use the config file of git revision REV (e.g. the pull request's base), trusted, instead of the "
                "checkout's; say whether the checkout's config differs from it"),
    Option(["--no-cache"], "no_cache", None, "flag", help="neither read nor write the lint cache (cli/cache.py)"),
    Option(["--cache-dir"], "cache_dir", None, metavar="DIR",
           help="the lint cache's folder (default: the user's cache folder)"),
    Option(["--quiet", "-q"], "quiet", None, "flag", help="no progress on a terminal"),
)


def for_command(command: str) -> list[Option]:
    return [o for o in OPTIONS if command in o.commands]


def valued_flags(command: str = LINT) -> frozenset[str]:
    """The spellings of `command`'s options that take a value (the next word is that value, not a path)."""
    return frozenset(f for o in for_command(command) if o.takes_value for f in o.flags)


def plain_flags(command: str = LINT) -> frozenset[str]:
    return frozenset(f for o in for_command(command) if not o.takes_value for f in o.flags)


def plain_lint(argv: list[str]) -> dict | None:
    """The parsed `lint` command line when it is `lint`, flags that take no value and one run of paths (in any
    order argparse accepts: the flags before, after or on both sides of the paths), as argparse's namespace would
    hold it (`cli.main._plain_lint`); None for anything else: a valued option, an abbreviation, `-h`, `--`, a
    word starting with "-" that is no flag, or paths split by a flag (argparse refuses those)."""
    if not argv or argv[0] != LINT:
        return None
    opts = for_command(LINT)
    plain = {f: o.dest for o in opts if not o.takes_value for f in o.flags}
    out: dict = {"command": LINT, "paths": []}
    for o in opts:
        out[o.dest] = list(o.unset) if isinstance(o.unset, list) else o.unset  # argparse copies a list it appends to
    runs = 0
    previous_was_path = False
    for word in argv[1:]:
        if word.startswith("-"):
            dest = plain.get(word)
            if dest is None:
                return None
            out[dest] = True
            previous_was_path = False
        else:
            if not previous_was_path:
                runs += 1
            out["paths"].append(word)
            previous_was_path = True
    return out if runs <= 1 else None


def choices(name: str) -> tuple[str, ...]:
    """The one list behind each named choice (imported on use: the cache fast path never needs them)."""
    if name == "formats":
        from urdfcheck.report import FORMATS

        return tuple(FORMATS)
    if name == "targets":
        from urdfcheck.model.grammar import TARGETS

        return tuple(TARGETS)
    if name == "profiles":
        from urdfcheck.rules.checks.profiles.common import PROFILES

        return tuple(PROFILES)
    if name == "severities":
        from urdfcheck.core.findings import Severity

        return tuple(str(s) for s in sorted(Severity, reverse=True))
    if name == "colors":
        return ("auto", "always", "never")
    raise KeyError(name)


def request_fields(ns, command: str = LINT) -> dict:
    """The `make_request` keyword arguments `command`'s parsed options give (an option not given is None or
    absent: the config decides)."""
    out: dict = {}
    for o in for_command(command):
        if o.field is None or not hasattr(ns, o.dest):
            continue
        value = getattr(ns, o.dest)
        if o.dest in ("args", "packages"):
            value = dict(value or [])
        elif o.type == "codes":  # appended groups of codes
            value = [c for group in value or () for c in group] or None
            if value is None and o.dest == "ignore":
                value = []
        elif o.dest == "no_config":
            value = not value
        elif o.value == "flag":
            value = True if value else None
        elif o.dest == "allow_env":
            value = tuple(value or ())
        elif o.dest == "bags":
            value = value or None
        out[o.field] = value
    return out
