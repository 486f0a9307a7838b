"""Who may lower the guard: the person running the tool, never the files it checks (issue 19).

In CI on a pull request every file of the checkout is the attacker's, its configuration included. So what
lowers the guard -- `trusted` (stock xacro runs the model's Python), `allow_env` (environment values into the
report), limits raised above the defaults, paths outside the checkout -- counts only when it comes from the
command line, the environment, the Python API, or a config the command line names explicitly with
`--config FILE --trust-config`. A config found on disk (urdfcheck.yaml, .urdfcheck.yaml, [tool.urdfcheck],
a nested sub/urdfcheck.yaml) that asks for one gets an X018 finding at the key, and the key is ignored.

The same holds for the gate itself (issue 36): such a config adds, never hides. `ignore`, a `select` narrower
than ALL, a `severity` below a rule's default, a `fail_on` above warning, a rule option that loosens its check,
`packages` pointing a package the checkout defines elsewhere, `frames` renaming a REP-105 frame, a `target`
distribution: each an X018 error at the key, and ignored. Its `models` add to discovery (plan.plan), `args` that
replace a xacro default add the defaults variant (request.config), `launch_args` and `frame_prefix` add the launch
defaults twin, and `tf_owners`, like a declared file that nothing starting the robot runs, may add a publisher,
never publish a frame (see the list below `_keep_gate`).
A config named with `--config FILE` alone is as untrusted as one found.

    screen(data, path, key_loc, trusted) -> [Finding]   # drops what an untrusted config may not say
    tightens(code, option, value) -> bool               # may an untrusted config set this rule option?
    confine(full, root, trusted) -> str | None          # why a config path leaves the checkout, or None
    repo_root(folder) -> str                            # the repository a config belongs to
"""
from __future__ import annotations

import os

from urdfcheck.core.findings import Finding, Location, Severity
from urdfcheck.core.walk import real as realpath  # remembered for the run

DEFAULT_MAX_ELEMENTS = 2_000_000  # load.loader.MAX_ELEMENTS (not imported: start-up)
GUARD_KEYS = ("trusted", "allow_env")


def _finding(message: str, loc: Location) -> Finding:
    return Finding("X018", Severity.WARNING, message, loc, name="untrusted-config")


def screen(data: dict, path: str, key_loc, trusted: bool) -> list[Finding]:
    """Remove from `data` (a parsed config) what only the person running the tool may set; one finding per key.
    Lower limits stay: tightening the guard is anyone's right."""
    if trusted:
        return []
    out = []
    how = "pass it on the command line, or name this config with --config FILE --trust-config"
    if data.get("trusted"):
        out.append(_finding("'trusted' in a config found in the checkout is ignored (it would run the model's "
                            f"Python with stock xacro); {how}", key_loc("trusted")))
    data.pop("trusted", None)
    if data.get("allow_env"):
        names = ", ".join(str(n) for n in data["allow_env"])[:200]
        out.append(_finding(f"'allow_env' ({names}) in a config found in the checkout is ignored (it would put "
                            f"environment values into the report); {how}", key_loc("allow_env")))
    data.pop("allow_env", None)
    out.extend(_keep_gate(data, key_loc))
    limit = data.get("max_elements")
    if isinstance(limit, int) and limit > DEFAULT_MAX_ELEMENTS:
        out.append(_finding(f"'max_elements: {limit}' above the default ({DEFAULT_MAX_ELEMENTS}) in a config found "
                            f"in the checkout is ignored; {how}", key_loc("max_elements")))
        data.pop("max_elements")
    return out


DEFAULT_FAIL_ON = Severity.WARNING  # request.Settings' default


def _gate(message: str, loc: Location) -> Finding:
    """A refused gate-lowering key: an error, so that the run that ignored it cannot pass silently."""
    return Finding("X018", Severity.ERROR, message, loc, name="untrusted-config")


GATE_HOW = ("the key is ignored (a config found in the checkout, or named without --trust-config, may add checks, "
            "never remove them; pass it on the command line, or name a config the pull request cannot change with "
            "--config FILE --trust-config)")


def _keep_gate(data: dict, key_loc) -> list[Finding]:
    """The gate belongs to the person running the tool (issue 36): an untrusted config may add to what is checked
    and make it stricter, never hide or soften a finding. Each refused key is one X018 error at the key, saying
    what was refused; the key is dropped."""
    out = []
    ignore = [str(p) for p in data.pop("ignore", None) or ()]
    if ignore:
        out.append(_gate(f"'ignore: {', '.join(ignore)[:200]}' would hide findings; {GATE_HOW}", key_loc("ignore")))
    select = [str(p) for p in data.get("select") or ()]
    if select and not any(p.upper() == "ALL" for p in select):
        del data["select"]
        out.append(_gate(f"'select: {', '.join(select)[:200]}' would leave the other rules unchecked; {GATE_HOW}",
                         key_loc("select")))
    lowered = [k for k, v in (data.get("severity") or {}).items() if _lowers(str(k), v)]
    for k in lowered:
        v = data["severity"].pop(k)
        out.append(_gate(f"'severity: {k}: {v}' would lower the default severity of {_what(str(k))}; {GATE_HOW}",
                         key_loc("severity", k)))
    fail_on = data.get("fail_on")
    if isinstance(fail_on, str) and _parse(fail_on) is not None and _parse(fail_on) > DEFAULT_FAIL_ON:
        del data["fail_on"]
        out.append(_gate(f"'fail_on: {fail_on}' would pass a run with {DEFAULT_FAIL_ON} findings; {GATE_HOW}",
                         key_loc("fail_on")))
    for code, opts in list((data.get("rules") or {}).items()):
        for name in list(opts or {}):
            if not tightens(str(code), str(name), opts[name]):
                value = opts.pop(name)
                out.append(_gate(f"'rules: {code}: {name}: {str(value)[:80]}' would loosen {code} (an untrusted "
                                 f"config may only tighten a rule's options); {GATE_HOW}",
                                 key_loc("rules", code, name)))
        if not opts:
            del data["rules"][code]
    frames = data.get("frames") if isinstance(data.get("frames"), dict) else {}
    for role in [r for r, v in frames.items() if str(v) != REP105.get(str(r), str(v))]:
        v = frames.pop(role)
        out.append(_gate(f"'frames: {role}: {str(v)[:80]}' would rename the REP-105 {role} frame "
                         f"({REP105[str(role)]}) that F001, the T rules and C024 judge by; {GATE_HOW}",
                         key_loc("frames", role)))
    target = data.get("target")
    if target:
        del data["target"]
        out.append(_gate(f"'target: {str(target)[:40]}' would choose the ROS distribution whose urdfdom (U007) and "
                         f"SDFormat (the gazebo profile) judge the model; the target is assumed from the workspace "
                         f"instead; {GATE_HOW}", key_loc("target")))
    return out


# The keys an untrusted config keeps, and why none of them can hide a finding (issue 36):
# - `models:` adds to discovery (plan.plan); its consumer files add to those found beside the model (the twin
#   "consumers found beside it", also whenever it declares `localization:` files, whose nodes it makes run);
#   `args`/`variants` that replace a xacro default add the "xacro defaults" variant;
#   `launch_args` and `frame_prefix` add the "launch defaults" twin, its declared launch files read with their own
#   defaults and the prefix they give (plan.plan.declared).
# - `tf_owners` may add a publisher (a conflict: T001..T004), never make a frame published
#   (consumers.tfclaims.UNTRUSTED: T005, C020 and C024 judge the graph without it).
# - `profiles` turns consumer profiles on: a profile's finding goes from info to its rule's severity, and a profile
#   never removes one (rules/checks/profiles/common.speak); `cache: false` only turns the lint cache off.
# - `packages` for a package the checkout does not define adds a place to resolve it (refused for its own: below);
#   `max_elements` below the default tightens; `bags` add recordings to check against the model (B rules).
# - the files `controllers`, `drivers` and `launch` declare run with the model as the config says, but a transform
#   read from them counts as published only when zero config would count it: from the files every declared launch
#   file reaching robot_state_publisher runs (includes and the parameter files they load), else from the model's
#   package. Any other may claim it (a conflict), never publish it (consumers.consumers.run_with,
#   rules.checks.tf.graph.claim_only: T005, C020 and C024 judge the graph without it and say why); a controller or
#   driver in such a file supplies no joint state either (C003 says why).
# Not closed: a `drivers:` spec chooses which keys of a driver file are its wheels, joints and frames; a spec naming a
# decoy key (`wheel_separation: wheel_sep_nominal`, beside the file's real `wheel_separation: 0.52`) replaces the
# driver zero config infers from that file when every file of the package is declared (no twin), hiding its C010.
# Making the twin for every declared driver closes it but lints those models once more (the agv example 3 -> 5).
REP105 = {"map": "map", "odom": "odom", "base": "base_link"}  # request.config.DEFAULT_FRAMES


def _parse(v) -> Severity | None:
    if isinstance(v, Severity):
        return v
    try:
        return Severity.parse(str(v))
    except ValueError:
        return None


def _lowers(pattern: str, value) -> bool:
    """Does `severity: {pattern: value}` put any rule it matches below that rule's default?"""
    from urdfcheck.rules.catalogue import catalogue, matches

    new = _parse(value)
    if new is None:
        return False  # the schema reports it
    return any(info.severity > new for code, info in catalogue().items() if matches(code, [pattern.upper()]))


def _what(pattern: str) -> str:
    from urdfcheck.rules.catalogue import catalogue, matches

    hit = [c for c in catalogue() if matches(c, [pattern.upper()])]
    return hit[0] if len(hit) == 1 else f"{len(hit)} rules"


# How a rule option's value tightens its check, decided per option type (issue 36). A number option is always
# a tolerance or a threshold below which a check does not judge (tolerance, angle_tolerance, atol, rtol, min_mass):
# a smaller value reports more. A list of names tightens when it grows (names reported) or shrinks (names
# accepted or skipped), per option below. A boolean, string or integer option tightens only where named here;
# any other change from an untrusted config is refused: when in doubt, the runner decides.
GROWS_TIGHTER = {("F001", "frames")}                        # names a check reports: more is stricter
SHRINKS_TIGHTER = {("F002", "expected"), ("G001", "ignore")}  # names a check accepts or skips: fewer is stricter
TIGHT_VALUES = {("I003", "allow_singular"): False}          # the value that reports more


def tightens(code: str, name: str, value) -> bool:
    """May an untrusted config set rule option `code.name` to `value`? Only when the check reports at least what
    it reports at the option's default (an unknown option: the schema reports it)."""
    from urdfcheck.rules.catalogue import catalogue

    info = catalogue().get(code)
    spec = info.option_specs.get(name) if info is not None else None
    if spec is None:
        return True
    default = spec.default
    if value == default and type(value) is type(default):
        return True
    if spec.type == "number":
        return isinstance(value, (int, float)) and not isinstance(value, bool) and value <= default
    if spec.type == "strings" and isinstance(value, (list, tuple)):
        if (code, name) in GROWS_TIGHTER:
            return set(default) <= set(value)
        if (code, name) in SHRINKS_TIGHTER:
            return set(value) <= set(default)
        return False
    return (code, name) in TIGHT_VALUES and value == TIGHT_VALUES[(code, name)]


def refuse_package(name: str, given: str, own: list, loc: Location) -> Finding:
    where = ", ".join(sorted({str(p) for p in own}))[:200]
    return _gate(f"'packages: {name}: {given}' would point the checkout's own package {name} (its package.xml is "
                 f"in {where}) at another folder; {GATE_HOW}", loc)


def defaults_kept(model: str, names, loc: Location) -> Finding:
    """A note, not a refusal: the model is linted with its xacro defaults too."""
    return Finding("X018", Severity.INFO, f"the args of {model} replace the default of {', '.join(sorted(names))[:200]}"
                   " in a config the runner did not trust: the model is linted with its defaults too (variant "
                   "'xacro defaults')", loc, name="untrusted-config")


def launch_defaults_kept(model: str, key: str, loc: Location) -> Finding:
    """A note, not a refusal: the model's launch files are read with their own defaults too."""
    return Finding("X018", Severity.INFO, f"'{key}' of {model}, in a config the runner did not trust, changes what its "
                   "launch files run or which frames the model publishes: the model is linted with the launch files' "
                   "own defaults and frame prefix too (variant 'launch defaults')", loc, name="untrusted-config")


_ROOTS: dict[str, str] = {}


def repo_root(folder: str) -> str:
    """The nearest folder at or above `folder` holding `.git` (a repository or a worktree), else `folder`."""
    folder = realpath(folder)
    if folder not in _ROOTS:
        root = folder
        for d in (folder, *_parents(folder)):
            if os.path.exists(os.path.join(d, ".git")):
                root = d
                break
        _ROOTS[folder] = root
    return _ROOTS[folder]


def _parents(p: str):
    while True:
        up = os.path.dirname(p)
        if up == p:
            return
        yield up
        p = up


def _below(path: str, base: str) -> bool:
    return path == base or path.startswith(base.rstrip(os.sep) + os.sep)


def confine(full: str, root: str, trusted: bool) -> str | None:
    """Why `full` (a path a config names, already joined to its folder) may not be read, or None: its real
    path must stay in the config's repository or the working directory, as the loader keeps symlinks."""
    if trusted:
        return None
    real = realpath(full)
    bases = (repo_root(root), realpath(os.getcwd()))
    if any(_below(real, b) for b in bases):
        return None
    return ("leaves the checkout (a config found in the checkout may only name files inside its repository "
            "or the working directory; name it with --config FILE --trust-config to allow this)")
