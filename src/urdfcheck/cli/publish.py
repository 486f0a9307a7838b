"""Subcommands `tf`, `publish`, `tree` and `verify` (wired into cli.py by ``add_parsers``).

Each loads the model with the loader (xacro arguments via ``--arg NAME:=VALUE``); a model that cannot be
loaded prints the loader's findings and exits 1. ``verify`` exits 1 when a peer disagrees beyond the
tolerance or could not run to completion (crash, out of memory, time-out, refused, not installed).
"""
from __future__ import annotations

import argparse
import json
import math
import os
import sys

from urdfcheck.cli.common import (
    EXIT_CLEAN,
    EXIT_FINDINGS,
    EXIT_USAGE,
    UsageError,
    load_one,
    print_findings,
    usage_message,
)
from urdfcheck.cli.parsing import add_options

# --- shared ---------------------------------------------------------------------------------------------------


def _joint_value(text: str):
    sep = ":=" if ":=" in text else "="
    if sep not in text:
        raise argparse.ArgumentTypeError(f"expected NAME=VALUE, got {text!r}")
    k, v = text.split(sep, 1)
    try:
        value = float(v)
    except ValueError:
        raise argparse.ArgumentTypeError(f"joint value {v!r} of {k!r} is not a number") from None
    if not k:
        raise argparse.ArgumentTypeError(f"expected NAME=VALUE, got {text!r}")
    return k, value


class _Deprecated(argparse.Action):
    """An old spelling, still read, with a note on stderr saying the new one."""

    def __call__(self, parser, namespace, values, option_string=None):
        print(f"urdfcheck: warning: {option_string} is deprecated here (it is lint's consumer profiles); "
              "use --ros", file=sys.stderr)
        setattr(namespace, self.dest, values)


def _add_ros(p) -> None:
    """ROS 1 or 2 publisher behaviour. It was `--profile`, which in `lint` names consumer profiles: one meaning
    per word, the old spelling kept as a deprecated alias."""
    p.add_argument("--ros", dest="profile", choices=["ros2", "ros1"], default="ros2",
                   help="robot_state_publisher of ROS 2 (default) or ROS 1")
    p.add_argument("--profile", dest="profile", choices=["ros2", "ros1"], default="ros2", action=_Deprecated,
                   help=argparse.SUPPRESS)


def _load(ns, want_xml: bool = False):
    """(model, xml or None) as `urdfcheck lint` loads the model (config included), or None after printing
    the load findings."""
    from urdfcheck.core.findings import Severity

    model_path = _model_path(ns)
    loaded = load_one(ns, model_path)
    exp = loaded.expanded
    errors = [f for f in exp.findings if f.severity >= Severity.ERROR]
    if loaded.model is None or errors:
        print_findings(errors or exp.findings)
        return None
    xml = None
    if want_xml:
        try:
            xml = exp.clean_text()
        except Exception:
            xml = None
    return loaded.model, xml


def _model_path(ns) -> str:
    """The MODEL argument: a file, or a folder holding exactly one robot (what `urdfcheck lint` plans there)."""
    if os.path.isfile(ns.model):
        return ns.model
    if not os.path.isdir(ns.model):
        raise UsageError(f"no such file: {ns.model}")
    from urdfcheck.core.paths import shown
    from urdfcheck.plan.plan import plan
    from urdfcheck.request.request import make_request

    targets = plan(make_request([ns.model], trusted=True if ns.trusted else None,
                                use_config=not getattr(ns, "no_config", False), config=getattr(ns, "config", None)))
    models = list(dict.fromkeys(str(t.path) for t in targets))
    if len(models) == 1:
        return models[0]
    if not models:
        raise UsageError(f"{ns.model} holds no URDF or xacro robot; name a model file")
    raise UsageError(f"{ns.model} holds {len(models)} robots; name one: "
                 + ", ".join(shown(m) for m in models[:10]) + (" ..." if len(models) > 10 else ""))


def _run(fn):
    def wrapped(ns) -> int:
        from urdfcheck.core import door

        # every read of the command through the door: the checkout, the packages resolved, what is typed
        typed = (getattr(ns, "model", None), getattr(ns, "joint_states", None), getattr(ns, "config", None))
        try:
            with door.guarding(typed):
                return fn(ns)
        except UsageError as e:
            print(usage_message(ns.command, e), file=sys.stderr)
            return EXIT_USAGE

    return wrapped


def add_parsers(subparsers) -> None:
    from urdfcheck.publisher import tree_view

    p = subparsers.add_parser("tf", help="transform between two frames for given joint values (like tf2_echo)",
                              description="Print the pose of TARGET in SOURCE (what `tf2_echo SOURCE TARGET` "
                              "prints) from the transforms robot_state_publisher would publish.")
    p.add_argument("model", metavar="MODEL")
    p.add_argument("source", metavar="SOURCE", help="reference frame (tf2_echo's first argument)")
    p.add_argument("target", metavar="TARGET", help="frame whose pose is printed")
    p.add_argument("--joint", action="append", default=[], type=_joint_value, metavar="NAME=VALUE",
                   help="joint position (rad or m; repeatable)")
    p.add_argument("--zero-missing", action="store_true",
                   help="movable joints without --joint are at 0 (default: an error naming them)")
    p.add_argument("--format", choices=TF_FORMATS, default="text")
    p.add_argument("--precision", type=int, default=6, help="decimals in text output (default 6)")
    add_options(p, "tf")
    p.set_defaults(func=_run(cmd_tf))

    p = subparsers.add_parser("publish", help="what robot_state_publisher would publish for joint states",
                              description="Replay JointState messages (JSON or YAML list, each with name, "
                              "position and stamp) and print, message by message, the transforms "
                              "robot_state_publisher would put on /tf_static and /tf, as JSON.")
    p.add_argument("model", metavar="MODEL")
    p.add_argument("--joint-states", required=True, metavar="FILE",
                   help="JSON or YAML: a list of {name: [...], position: [...], stamp: SECONDS|[sec, nanosec]}")
    _add_ros(p)
    p.add_argument("--publish-frequency", type=float, default=None, metavar="HZ",
                   help="default 20 (ros2) or 50 (ros1)")
    p.add_argument("--ignore-timestamp", action="store_true")
    p.add_argument("--frame-prefix", default="", metavar="PREFIX",
                   help="ros2 frame_prefix (prepended verbatim) or ros1 tf_prefix ('prefix/frame')")
    p.add_argument("--no-tf-static", dest="use_tf_static", action="store_false", default=None,
                   help="ros1 use_tf_static:=false: fixed transforms go on /tf every publish interval")
    add_options(p, "publish")
    p.set_defaults(func=_run(cmd_publish))

    p = subparsers.add_parser("tree", help="the TF tree robot_state_publisher builds (static/dynamic edges)")
    p.add_argument("model", metavar="MODEL")
    p.add_argument("--format", choices=tree_view.FORMATS, default="text")
    p.add_argument("--frame-prefix", default="", metavar="PREFIX")
    _add_ros(p)
    add_options(p, "tree")
    p.set_defaults(func=_run(cmd_tree))

    p = subparsers.add_parser("verify", help="check the publisher against Pinocchio and yourdfpy",
                              description="Sample seeded configurations inside the joint limits and compare the "
                              "link poses from the published transforms with Pinocchio and yourdfpy. Exit 1 when "
                              "a peer disagrees beyond the tolerance or could not run (crash, out of memory, "
                              "time-out, refused; Pinocchio not installed). Where the tools genuinely differ "
                              "(planar, floating, zero axis, ...) the links are left out and a V002 delta says why.")
    p.add_argument("model", metavar="MODEL")
    p.add_argument("-n", "--configurations", dest="n", type=int, default=1000, metavar="N")
    p.add_argument("--seed", type=int, default=0)
    p.add_argument("--tolerance", type=float, default=1e-9, help="metres and radians (default 1e-9)")
    p.add_argument("--format", choices=VERIFY_FORMATS, default="text")
    p.add_argument("--no-yourdfpy", action="store_true", help="compare with Pinocchio only")
    p.add_argument("--yourdfpy-samples", type=int, default=None, metavar="N",
                   help="configurations checked with yourdfpy (slow; default 50, 0 = all)")
    p.add_argument("--peer-timeout", type=float, default=None, metavar="SECONDS",
                   help="wall-clock limit for each peer (default 120)")
    p.add_argument("--peer-memory", type=float, default=None, metavar="GIB",
                   help="address space each peer may add (default 2 GiB)")
    p.add_argument("--max-dof", type=int, default=None, help="refuse Pinocchio above this many DoF (default 256)")
    p.add_argument("--max-depth", type=int, default=None,
                   help="refuse Pinocchio above this chain depth (default 1000)")
    add_options(p, "verify")
    p.set_defaults(func=_run(cmd_verify))


# --- tf ---------------------------------------------------------------------------------------------------------
def cmd_tf(ns) -> int:
    from urdfcheck.core.findings import clean_text
    from urdfcheck.publisher import TransformLookupError, lookup_matrix

    loaded = _load(ns)
    if loaded is None:
        return EXIT_FINDINGS
    model, _ = loaded
    joints = dict(ns.joint)
    unknown = [k for k in joints if k not in model.joints]
    if unknown:
        raise UsageError("not joints of the model: " + ", ".join(clean_text(k) for k in unknown))
    try:
        m = lookup_matrix(model, ns.source, ns.target, joints, default=0.0 if ns.zero_missing else None)
    except TransformLookupError as e:
        raise UsageError(clean_text(str(e))) from None
    sys.stdout.write(render_tf(ns.format, ns.source, ns.target, joints, m, ns.precision))
    if any(x != x for row in m for x in row):
        print("warning: NaN: a joint on the path has a zero axis (robot_state_publisher publishes NaN too)",
              file=sys.stderr)
    return EXIT_CLEAN


TF_FORMATS = ("text", "json")  # what `render_tf` renders: `urdfcheck tf --format` offers these


def render_tf(fmt: str, source: str, target: str, joints: dict, m, precision: int = 6) -> str:
    """The pose of `target` in `source` (matrix `m`) as tf2_echo prints it, or as JSON."""
    from urdfcheck.core.findings import clean_text
    from urdfcheck.publisher.kinematics import quat_from_matrix, rpy_from_matrix

    if fmt not in TF_FORMATS:
        raise ValueError(f"unknown format {fmt!r} (choose from {', '.join(TF_FORMATS)})")
    t = [m[0][3], m[1][3], m[2][3]]
    q = list(quat_from_matrix(m))
    rpy = list(rpy_from_matrix(m))
    if fmt == "json":
        return json.dumps({"source": source, "target": target, "joints": joints, "translation": t,
                           "rotation": q, "rpy": rpy, "rpy_degrees": [math.degrees(a) for a in rpy],
                           "matrix": [list(r) for r in m]}, indent=2) + "\n"
    d = max(0, precision)

    def vec(v):
        return "[" + ", ".join(f"{x:.{d}f}" for x in v) + "]"

    lines = [f"Pose of {clean_text(target)} in {clean_text(source)} (tf2_echo {clean_text(source)} "
             f"{clean_text(target)})",
             f"- Translation: {vec(t)}",
             f"- Rotation: in Quaternion (xyzw) {vec(q)}",
             f"- Rotation: in RPY (radian) {vec(rpy)}",
             f"- Rotation: in RPY (degree) {vec([math.degrees(a) for a in rpy])}",
             "- Matrix:"]
    lines += ["  " + " ".join(f"{x:{d + 4}.{d}f}" for x in row) for row in m]
    return "\n".join(lines) + "\n"


# --- publish ----------------------------------------------------------------------------------------------------
def _read_joint_states(path: str):
    """The runner's joint-state file (urdfcheck.bag.source: through core.door, bounded, YAML guarded), its items
    one at a time (a JSON list is never held whole: a 60 MB file would take gigabytes as objects)."""
    from urdfcheck.bag.source import RecordingError, text_items

    try:
        return iter(text_items(path, runner=True))
    except RecordingError as e:
        raise UsageError(f"{path}: {e}") from None


def _tf_dict(t) -> dict:
    return {"parent": t.parent, "child": t.child, "translation": list(t.translation),
            "rotation": list(t.rotation), "stamp": {"sec": t.stamp.sec, "nanosec": t.stamp.nanosec}}


def _first_stamp(items) -> tuple[float, list]:
    """The stamp of the first readable message, and the items read to find it (to be replayed first)."""
    from urdfcheck.publisher import JointState

    seen = []
    for r in items:
        seen.append(r)
        try:
            return JointState.from_dict(r).stamp, seen
        except (TypeError, ValueError, OverflowError):
            continue
    return 0.0, seen


def cmd_publish(ns) -> int:
    from urdfcheck.load.budget import run_budget

    # the joint-state file may be the pull request's: its messages are replayed within the run's budget
    with run_budget(getattr(ns, "budget", None)) as budget:
        return _publish(ns, budget)


def _publish(ns, budget) -> int:
    import itertools

    from urdfcheck.bag.source import RecordingError
    from urdfcheck.publisher import JointState, JointStateError, StatePublisher

    items = _read_joint_states(ns.joint_states)
    loaded = _load(ns)
    if loaded is None:
        return EXIT_FINDINGS
    model, _ = loaded
    try:
        pub = StatePublisher(model, profile=ns.profile, frame_prefix=ns.frame_prefix,
                             publish_frequency=ns.publish_frequency, ignore_timestamp=ns.ignore_timestamp,
                             use_tf_static=ns.use_tf_static)
    except ValueError as e:
        raise UsageError(str(e)) from None
    try:
        first_stamp, seen = _first_stamp(items)
    except RecordingError as e:
        raise UsageError(f"{ns.joint_states}: {e}") from None
    start = pub.startup(first_stamp)
    out = {
        "model": model.name,
        "profile": pub.profile.name,
        "publish_frequency": pub.publish_frequency,
        "publish_interval_ns": pub.publish_interval_ns,
        "frame_prefix": pub.frame_prefix,
        "ignore_timestamp": pub.ignore_timestamp,
        "use_tf_static": pub.profile.use_tf_static,
        "notes": [{"code": n.code, "joint": n.joint, "message": n.message} for n in pub.notes],
        "startup": {"/tf_static": [_tf_dict(t) for t in start.get("/tf_static", [])], "/tf": []},
        "messages": [],
    }
    # the document as json.dump(out, indent=2) writes it, the messages written as they are made
    head = json.dumps(out, indent=2)  # ends with '"messages": []\n}'
    sys.stdout.write(head[:-len("[]\n}")] + "[")
    errors = written = 0
    stopped = None

    def emit(entry: dict) -> None:
        nonlocal written
        text = json.dumps(entry, indent=2).replace("\n", "\n    ")
        sys.stdout.write(("," if written else "") + "\n    " + text)
        written += 1

    try:
        for i, r in enumerate(itertools.chain(seen, items)):
            if i % 256 == 255 and budget.remaining() < 0:
                stopped = i
                break
            entry = {"index": i}
            try:
                msg = JointState.from_dict(r)
            except (TypeError, ValueError, OverflowError) as e:
                entry.update({"error": f"not a JointState: {e}", "/tf_static": [], "/tf": []})
                emit(entry)
                errors += 1
                continue
            st = msg.stamp_ns
            entry["stamp"] = {"sec": st // 1_000_000_000, "nanosec": st % 1_000_000_000}
            fixed = pub.tick(msg.stamp)
            try:
                tfs = pub.on_joint_state(msg)
            except JointStateError as e:
                entry.update({"error": str(e), "/tf_static": [], "/tf": [_tf_dict(t) for t in fixed]})
                emit(entry)
                errors += 1
                continue
            entry.update({"published": not pub.last_throttled, "throttled": pub.last_throttled,
                          "/tf_static": [], "/tf": [_tf_dict(t) for t in fixed + tfs]})
            if pub.last_unknown:
                entry["unknown_joints"] = list(pub.last_unknown)
            if pub.last_ignored:
                entry["ignored_joints"] = list(pub.last_ignored)
            emit(entry)
    except RecordingError as e:  # a JSON list broken after its first messages
        stopped = f"{e}"
    sys.stdout.write("\n  ]\n}\n" if written else "]\n}\n")
    if errors:
        print(f"urdfcheck publish: {errors} message(s) rejected (see \"error\" in the output)", file=sys.stderr)
    if stopped is not None:
        why = (f"the run's time budget ({budget.seconds:g} s) ran out after {stopped} messages"
               if isinstance(stopped, int) else clean(stopped))
        print(f"urdfcheck publish: the output stops early: {why}", file=sys.stderr)
        return EXIT_FINDINGS
    return EXIT_FINDINGS if _check_states(model, ns.joint_states) else EXIT_CLEAN


def clean(text: str) -> str:
    from urdfcheck.core.findings import clean_text, escape_bidi

    return escape_bidi(clean_text(text))


def _check_states(model, path: str) -> bool:
    """The recording checks of `urdfcheck bag` on the input (a joint 90 rad past its limits, a NaN, a stamp
    going backwards), on stderr; True when one is a warning or an error."""
    from urdfcheck.bag import BagOptions, check_recording
    from urdfcheck.core.findings import Severity

    found = check_recording(model, path, BagOptions(), text=True, runner=True)
    found = [f for f in found if f.code != "B015"]  # a list without JointState fields is said above already
    print_findings(found)
    return any(f.severity >= Severity.WARNING for f in found)


# --- tree -------------------------------------------------------------------------------------------------------
def cmd_tree(ns) -> int:
    from urdfcheck.publisher.tree_view import render

    loaded = _load(ns)
    if loaded is None:
        return EXIT_FINDINGS
    model, _ = loaded
    print(render(model, ns.format, ns.frame_prefix, ns.profile))
    return EXIT_CLEAN


# --- verify -----------------------------------------------------------------------------------------------------
class _Progress:
    """One status line on a terminal, shown only once a run has lasted `delay` seconds."""

    def __init__(self, stream, delay: float = 0.5):
        import time

        self.stream = stream
        self.state: dict[str, float] = {}
        self.shown = False
        self.clock = time.monotonic
        self.start = self.clock()
        self.delay = delay

    def __call__(self, stage: str, done: int, total: int) -> None:
        self.state[stage] = done / total if total else 1.0
        if not self.shown and self.clock() - self.start < self.delay:
            return
        line = "verify: " + "  ".join(f"{k} {int(v * 100):3d}%" for k, v in self.state.items())
        self.stream.write("\r" + line + "\x1b[K")
        self.stream.flush()
        self.shown = True

    def close(self) -> None:
        if self.shown:
            self.stream.write("\r\x1b[K")
            self.stream.flush()


def _fmt_err(x: float) -> str:
    return f"{x:.2e}" if math.isfinite(x) else str(x)


def format_report(report) -> str:
    from urdfcheck.core.findings import clean_text

    lines = [f"verify {clean_text(report.model)} ({clean_text(report.source)}): {report.configurations} "
             f"configurations, seed {report.seed}, tolerance {report.tolerance:g}, "
             f"{len(report.joints)} independent joints"]
    label = {"batch": "publisher vs batch FK", "pinocchio": "pinocchio", "yourdfpy": "yourdfpy"}
    for p in report.peers:
        name = label.get(p.name, p.name) + (f" {p.version}" if p.version else "")
        if p.ran:
            w = p.worst
            lines.append(f"  {name:<28} {p.status:<9} max {_fmt_err(p.max_translation)} m, "
                         f"{_fmt_err(p.max_rotation)} rad over {len(p.links)} links"
                         + (f" (worst {clean_text(w.link)})" if w and p.status != "ok" else "")
                         + (f"; {clean_text(p.detail)}" if p.detail and p.name != "batch" else ""))
            for e in p.failing()[:10]:
                lines.append(f"      {clean_text(e.link)}: {_fmt_err(e.translation)} m, {_fmt_err(e.rotation)} rad "
                             f"(configuration {e.configuration})")
            if p.excluded:
                lines.append(f"      not compared: {len(p.excluded)} link(s): " +
                             ", ".join(f"{clean_text(k)} [{v}]" for k, v in list(p.excluded.items())[:5]) +
                             (" ..." if len(p.excluded) > 5 else ""))
        else:
            lines.append(f"  {name:<28} {p.status}" + (f": {clean_text(p.detail)}" if p.detail else ""))
        if p.stderr.strip() and (not p.ran or p.status == "mismatch"):
            lines.append("      output:")
            out_lines = p.stderr.strip().splitlines()
            for ln in out_lines[:12]:
                lines.append("        " + clean_text(ln))
            if len(out_lines) > 12:
                lines.append(f"        ... ({len(out_lines) - 12} more lines)")
    if report.deltas:
        lines.append("semantic deltas:")
        for d in report.deltas:
            lines.append(f"  {d.loc or report.source}: V002 {clean_text(d.message)}")
    lines.append(f"result: {report.status} ({report.seconds:.2f} s)")
    return "\n".join(lines)


VERIFY_FORMATS = ("text", "json")  # what `render_verify` renders: `urdfcheck verify --format` offers these


def render_verify(fmt: str, report) -> str:
    if fmt not in VERIFY_FORMATS:
        raise ValueError(f"unknown format {fmt!r} (choose from {', '.join(VERIFY_FORMATS)})")
    return json.dumps(report.to_dict(), indent=2) if fmt == "json" else format_report(report)


def cmd_verify(ns) -> int:
    from urdfcheck.verify import compare as V

    if ns.n < 1:
        raise UsageError("-n must be at least 1")
    if not os.path.isfile(ns.model):
        raise UsageError(f"no such file: {ns.model}")
    peers = ("pinocchio",) if ns.no_yourdfpy else ("pinocchio", "yourdfpy")
    # fork the peers now: they import Pinocchio / yourdfpy while this process loads the model
    pre = {}
    if ns.peer_timeout is not None:
        pre["timeout"] = ns.peer_timeout
    if ns.peer_memory is not None:
        pre["memory"] = int(ns.peer_memory * 1024**3)
    workers = V.prestart(peers, **pre)
    try:
        loaded = _load(ns, want_xml=True)
    except BaseException:
        V.cancel(workers)
        raise
    if loaded is None:
        V.cancel(workers)
        return EXIT_FINDINGS
    model, xml = loaded
    kwargs = {"workers": workers}
    if ns.yourdfpy_samples is not None:
        kwargs["yourdfpy_samples"] = ns.yourdfpy_samples
    if ns.peer_timeout is not None:
        kwargs["timeout"] = ns.peer_timeout
    if ns.peer_memory is not None:
        kwargs["memory"] = int(ns.peer_memory * 1024**3)
    if ns.max_dof is not None:
        kwargs["max_dof"] = ns.max_dof
    if ns.max_depth is not None:
        kwargs["max_depth"] = ns.max_depth
    progress = _Progress(sys.stderr) if sys.stderr.isatty() else None
    try:
        report = V.verify(model, ns.n, ns.seed, ns.tolerance, xml=xml, peers=peers, progress=progress, **kwargs)
    finally:
        if progress is not None:
            progress.close()
    print(render_verify(ns.format, report))
    return EXIT_CLEAN if report.passed else EXIT_FINDINGS
