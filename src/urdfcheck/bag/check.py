"""One recording against one model: stream it once through the JointState and TF checks, return findings."""
from __future__ import annotations

from urdfcheck.bag import source
from urdfcheck.bag.jointstates import Issue, JointStateChecks
from urdfcheck.bag.tfcheck import TfChecks
from urdfcheck.core.findings import Finding, Location, Severity, clean_text
from urdfcheck.core.records import FrozenRecord

CODES = {
    "B001": "joint-state-unknown-name",
    "B002": "joint-never-published",
    "B003": "joint-state-length-mismatch",
    "B004": "joint-state-not-finite",
    "B005": "joint-state-outside-limits",
    "B006": "joint-state-in-degrees",
    "B007": "joint-state-in-millimetres",
    "B008": "joint-state-stamp",
    "B009": "joint-state-gap",
    "B010": "tf-edge-second-publisher",
    "B011": "tf-static-differs-from-model",
    "B012": "tf-frame-two-parents",
    "B013": "tf-replay-mismatch",
    "B014": "recording-unreadable",
    "B015": "recording-nothing-to-check",
}


class BagOptions(FrozenRecord):
    """joint_topic: the JointState topic (None: /joint_states, else the recording's only one);
    tolerance: how far (rad or m) a position may lie outside its limits; replay_tolerance: metres and radians
    a recorded /tf transform may differ from the replay; static_tolerance: the same for /tf_static against
    the model's fixed joints; profile and frame_prefix: the robot_state_publisher that ran."""

    _fields = ("joint_topic", "tolerance", "replay_tolerance", "static_tolerance", "profile", "frame_prefix")
    # the tolerances' defaults are the B rules' declared options (rules/B005.yaml, B013, B011): lint reads those
    _defaults = {"joint_topic": None, "tolerance": 1e-3, "replay_tolerance": 1e-5, "static_tolerance": 1e-4,
                 "profile": "ros2", "frame_prefix": ""}


def check_recording(model, path: str, options: BagOptions | None = None, progress=None, text: bool | None = None,
                    runner: bool = False) -> list[Finding]:
    """Findings about the recording at `path` (bag, bag folder, .db3, .mcap, or a YAML/JSON message list),
    located in the recording; `related` points at the model's source lines. Never raises for a bad recording:
    that is a B014 finding. `progress(n)` is called every 10,000 messages. `text`: read it as a YAML/JSON list
    whatever its name (None: by its suffix). `runner`: the person running the tool named this path (core.door);
every file inside a recording folder is read as the checkout's, whoever named the folder."""
    opts = options or BagOptions()
    from urdfcheck.core import observe

    observe.taint("a recording was read (its sqlite reads are not observed)")
    states = JointStateChecks(model, tolerance=opts.tolerance)
    tf = None  # made at the first message: by then the recording has said whether it is ROS 1 or 2
    issues: list[Issue] = []
    others: list[str] = []
    facts: dict = {}
    n = 0
    budget = _budget()
    cut = None

    def tf_checks() -> TfChecks:
        return TfChecks(model, profile=opts.profile, frame_prefix=opts.frame_prefix,
                        tolerance=opts.replay_tolerance, static_tolerance=opts.static_tolerance,
                        ros=facts.get("ros"))

    held: list = []  # JointState batches not yet given to `states` (which needs no order with /tf): longer runs
    held_n = [0, 0]  # messages, bytes

    def give():
        if held:
            states.add_batches(held)
            held.clear()
            held_n[:] = [0, 0]

    try:
        for m in source.messages(path, opts.joint_topic, others=others, text=text, facts=facts, runner=runner,
                                 batches=True):
            if tf is None:
                tf = tf_checks()
            if m.kind == "joint_state_batch":
                k = len(m) + len(m.tfs)
                if budget is not None and (n + k) // 2048 != n // 2048 and budget.remaining() <= 0:
                    cut = f"the run's time budget ({budget.seconds:g} s) ran out after {n:,} messages"
                    break
                if progress is not None and (n + k) // 10_000 != n // 10_000:
                    progress((n + k) // 10_000 * 10_000)
                n += k
                if held and (held[0].names is not m.names or held[0].topic != m.topic or
                             held[0].callerid != m.callerid or held[0].position.shape[1:] != m.position.shape[1:]
                             or held[0].velocity.shape[1:] != m.velocity.shape[1:]
                             or held[0].effort.shape[1:] != m.effort.shape[1:]
                             or held_n[0] >= source.MAX_BATCH or held_n[1] >= source.BATCH_BYTES):
                    give()
                held.append(m)
                held_n[0] += k
                held_n[1] += m.position.nbytes + m.velocity.nbytes + m.effort.nbytes
                if not tf.batch(m):
                    lo = 0
                    for j, tm in m.tfs:  # the replay needs the order of joint states and /tf as recorded
                        tf.joint_state_batch(m, lo, j)
                        tf.add(tm)
                        lo = j
                    tf.joint_state_batch(m, lo, len(m))
                continue
            n += 1
            if budget is not None and not n % 2048 and budget.remaining() <= 0:
                cut = f"the run's time budget ({budget.seconds:g} s) ran out after {n:,} messages"
                break
            if m.kind == "joint_state":
                give()
                states.add(m)
                tf.joint_state(m)
            else:
                tf.add(m)
            if progress is not None and n % 10_000 == 0:
                progress(n)
    except source.RecordingError as e:
        issues.append(Issue("B014", f"the recording cannot be read: {e}"))
    except RecursionError:
        issues.append(Issue("B014", "the recording cannot be read: nested too deeply"))
    except MemoryError:
        issues.append(Issue("B014", "the recording cannot be read: the run's memory budget was used up"))
    except ArithmeticError as e:  # a value no arithmetic survives (the readers pass floats through as they are)
        issues.append(Issue("B014", f"the recording cannot be checked after {n:,} messages: a value out of "
                            f"range ({type(e).__name__})"))
    try:
        give()  # what was read before a damaged part, or before the budget ran out, is checked
    except MemoryError:
        issues.append(Issue("B014", "the recording cannot be read: the run's memory budget was used up"))
    if cut is not None:
        issues.append(Issue("B014", f"the recording was read only in part: {cut}; what follows rests on "
                            "the part read"))
    if tf is None:
        tf = tf_checks()
    states.ros = facts.get("ros")
    tf.finish()

    def on_tf(joint: str):
        for key, seg in tf.movable.items():
            if seg.name == joint and tf.on_tf.get(key):
                return key[0], key[1], tf.on_tf[key]
        return None

    issues.extend(states.issues(on_tf=on_tf))
    named = {j for j in states.seen if j in states.movable}
    issues.extend(tf.issues(named=named, js_count=states.count))
    topic = opts.joint_topic or "/joint_states"
    hint = (f" (JointState topics in it: {', '.join(others)}; pass --joint-states TOPIC)" if others else "")
    if not n and not issues:
        issues.append(Issue("B015", f"the recording has no JointState messages on {topic} and no /tf or "
                            "/tf_static messages: nothing was checked" + hint, severity="warning"))
    elif n and not states.count and states.movable and not any(i.code == "B014" for i in issues):
        # /tf or /tf_static alone: no movable joint of the model was checked (a wrong topic passes silently)
        issues.append(Issue("B015", f"the recording has no JointState messages on {topic}: none of the model's "
                            f"{len(states.movable)} movable joints was checked (only "
                            f"{tf.compared()} transform{'s' if tf.compared() != 1 else ''} of its fixed joints "
                            "were compared)" + hint, severity="warning"))
    if others and states.count:
        for i in issues:
            if i.code == "B002":  # an absence claim about a topic we did not read all of: say what we did not see
                i.severity = "info"
                i.message += (f" (the recording also has {', '.join(others)}, not read: a joint_state_publisher "
                              "may merge them; pass --joint-states TOPIC to check one of them)")
    if cut is not None:
        for i in issues:
            if i.code in ("B002", "B015"):  # absence claims about a recording read in part
                i.severity = "info"
    return [_finding(i, path) for i in issues]


def _budget():
    from urdfcheck.load.budget import current

    return current()


def _finding(i: Issue, path: str) -> Finding:
    name = CODES[i.code]
    loc = Location(str(path))
    if i.severity is not None:  # a severity other than the catalogue's (finish.suppressions keeps a named one)
        return Finding(i.code, Severity.parse(i.severity), clean_text(i.message, 2000), loc, name,
                       tuple(i.related))
    return Finding(i.code, _default(i.code), clean_text(i.message, 2000), loc, "", tuple(i.related))


def _default(code: str) -> Severity:
    from urdfcheck.rules import catalogue

    info = catalogue.info(code)
    return info.severity if info is not None else Severity.ERROR
