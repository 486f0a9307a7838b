"""C rules: what a model's consumers (controllers, drivers, launch files) say about it, against the model.

Ordinary `@check` rules with `needs="consumers"`: the engine imports this module, and the readers behind it, only
for a model that can have consumers (`consumers.reach`); C004 and C006 read nothing but the model's
<ros2_control> blocks (`needs="ros2_control"`).

The consumers come from `ctx.contracts` (a `consumers.consumers.Consumers`), which the planner gives every
target (`plan.plan`): a config's declared consumers, a launch file's deployment, or, with zero config,
those beside the model (`consumers.consumers.consumers_near`: the enclosing ROS package's config/ and launch/ files),
computed once per target when its model is built. Options come from the engine (`ctx.options`, catalogue
defaults filled in). The checks never change the context.
"""
from __future__ import annotations

import os
import re
from collections.abc import Iterator

from urdfcheck.consumers.common import as_bool
from urdfcheck.consumers.consumers import Consumers
from urdfcheck.consumers.consumers import consumers_of as consumers
from urdfcheck.consumers.controllers import JSB, JSC
from urdfcheck.core import lazyre
from urdfcheck.core.findings import Location, Problem, closest
from urdfcheck.core.paths import shown
from urdfcheck.core.records import TYPE_CHECKING
from urdfcheck.core.walk import real as realpath  # remembered for the run
from urdfcheck.rules.catalogue import check
from urdfcheck.rules.checks.tf.graph import claim_only, untrusted_hint
from urdfcheck.rules.checks.tf.graph import deployment_graph as _graph
from urdfcheck.rules.checks.tf.graph import distinct_locations as _dedupe_locs
from urdfcheck.rules.contracts.wheels import check_drive

if TYPE_CHECKING:  # the checks' argument types (no import at run time)
    from urdfcheck.model.robot import Model
    from urdfcheck.rules.engine import Context

_UNRESOLVED = lazyre.compile(r"\$\(|\$\{")


# --- context helpers ---------------------------------------------------------------------------------------
def _suggest(name: str, options) -> str:
    close = closest(name, options, cutoff=0.6)
    return f" (did you mean '{close}'?)" if close else ""


_FRAME_SUFFIX = lazyre.compile(r"(_link|_frame)$")


def _suggest_frame(name: str, options) -> str:
    """A near miss of a frame that exists: the same name without its _link/_frame suffix ('imu' -> 'imu_link'),
    or a typo (a letter or two wrong: 'lazer_link', 'base_lnk'). A frame that merely resembles one ('laser' and
    'base_link', a driver's own 'os_imu' and 'imu_link', 'camera_color_optical_frame' and 'camera_color_frame')
    is no evidence of a typo: the driver may publish it itself."""
    stem = _FRAME_SUFFIX.sub("", name)
    stems: dict[str, str] = {}
    for o in options:
        stems.setdefault(_FRAME_SUFFIX.sub("", o), o)
    if stem in stems and stems[stem] != name:
        return f" (did you mean '{stems[stem]}'?)"
    best = None
    for o in options:
        d = _edits(name, o, 2)
        if d <= _typo_edits(name) and (best is None or d < best[0]):
            best = (d, o)
    return f" (did you mean '{best[1]}'?)" if best else ""


def _typo_edits(name: str) -> int:
    """Edits a typo of `name` may take: one, two for names of ten letters or more."""
    return 1 if len(name) < 10 else 2


def _edits(a: str, b: str, cap: int) -> int:
    """Levenshtein distance with adjacent transpositions, or cap + 1 once it exceeds `cap`."""
    if abs(len(a) - len(b)) > cap:
        return cap + 1
    prev2, prev = None, list(range(len(b) + 1))
    for i, ca in enumerate(a, 1):
        cur = [i] + [0] * len(b)
        for k, cb in enumerate(b, 1):
            cur[k] = min(prev[k] + 1, cur[k - 1] + 1, prev[k - 1] + (ca != cb))
            if prev2 is not None and i > 1 and k > 1 and ca == b[k - 2] and a[i - 2] == cb:
                cur[k] = min(cur[k], prev2[k - 2] + 1)
        if min(cur) > cap:
            return cap + 1
        prev2, prev = prev, cur
    return prev[-1]


def _unresolved(name: str) -> bool:
    return bool(_UNRESOLVED.search(name))


def _WARNING():
    from urdfcheck.core.findings import Severity

    return Severity.WARNING


def _inferred(owner):
    """A driver whose keys were read by their shape (zero config, pipeline/deployments): its findings warn."""
    return _WARNING() if getattr(owner, "inferred", False) else None


def _shape_note(owner) -> str:
    """What a finding of a controller of no catalogued type says about how it was read."""
    if getattr(owner, "inferred", False) and getattr(owner, "type", None):
        return (f" (type {owner.type} is not in urdfcheck's controller catalogue: the key was read as a joint "
                f"name by its shape)")
    return ""


def _idle(owner) -> tuple:
    """A controller the deployment configures but does not spawn (`Controller.idle`): another launch-argument
    choice may start it with another model, so what it says of this one is a guess (issue 37)."""
    if not getattr(owner, "idle", False):
        return ()
    from urdfcheck.core.evidence import Step

    return (Step("controller", owner.name, "idle", f"spawn {owner.name} in the launch file that runs this model, "
                 "or name its model in urdfcheck.yaml"),)


def _owner_desc(owner_kind: str, owner) -> str:
    if owner_kind == "controller":
        return f"controller {owner.name}"
    return f"driver {owner.name}"


# --- C001 / C002: joint names ----------------------------------------------------------------------------
@check("C001", needs="consumers")
def unknown_joint(model: Model, ctx: Context) -> Iterator[Problem]:
    """A controller or driver names a joint the model does not have."""
    c = consumers(model, ctx)
    seen = set()
    hw_items = {h.name for r in model.ros2_control for h in r.joints + r.sensors + r.gpios}
    for u, kind, owner in c.joint_uses():
        if _unresolved(u.joint) or u.joint in model.joints:
            continue
        if u.role == "dof" and (u.joint in hw_items or not model.ros2_control):
            continue  # pid_controller's degrees of freedom may be any hardware item's interfaces
        key = (u.joint, u.loc, owner.name)
        if key in seen:
            continue
        seen.add(key)
        via = f" (through chained controller {u.via}: '{u.written}')" if u.via else ""
        hint = ""
        if u.joint in model.links:
            hint = f"; {u.joint!r} is a link, not a joint"
        else:
            hint = _suggest(u.joint, model.joints)
        yield Problem(f"{_owner_desc(kind, owner)} names joint {u.joint!r}{via}, which the model does not "
                      f"have{hint}{_shape_note(owner)}", at=u.loc, data={"joint": u.joint}, severity=_inferred(owner),
                      rests_on=_idle(owner))


@check("C002", needs="consumers")
def joint_not_movable(model: Model, ctx: Context) -> Iterator[Problem]:
    """A controller or driver commands a fixed (or floating/planar) joint."""
    c = consumers(model, ctx)
    seen: set = set()
    for ctrl in c.controllers:
        if ctrl.kind in (JSB, JSC):
            continue
        for u in ctrl.joints:
            yield from _not_movable(model, u, f"controller {ctrl.name}", seen)
    for d in c.drivers:
        for u in d.joints:
            for p in _not_movable(model, u, f"driver {d.name}", seen):
                p.severity = p.severity or _inferred(d)
                yield p


def _not_movable(model, u, who: str, seen: set):
    j = model.joints.get(u.joint)
    if j is None or j.movable or (u.joint, u.loc) in seen or u.role == "state":
        return
    seen.add((u.joint, u.loc))
    role = {"left_wheel": "drives wheel", "right_wheel": "drives wheel"}.get(u.role, "commands")
    yield Problem(f"{who} {role} {u.joint!r}, but it is a {j.type} joint: robot_state_publisher never moves "
                  f"it and the command has no effect", at=u.loc, related=(j,), data={"joint": u.joint})


# --- C003: joint state sources ---------------------------------------------------------------------------
def _gazebo_state_joints(model) -> tuple[bool, set[str]]:
    """(all joints covered, named joints) from Gazebo joint-state / diff-drive plugins."""
    all_cov, named = False, set()
    for b in model.blocks:
        if b.tag != "gazebo" or "plugin" not in b.xml:
            continue
        for m in re.finditer(r"<plugin\b[^>]*filename\s*=\s*[\"']([^\"']+)[\"'][^>]*>(.*?)</plugin>", b.xml, re.S):
            fname, body = m.group(1).lower(), m.group(2)
            if "joint_state" in fname:
                joints = re.findall(r"<joint_?[Nn]ame>\s*([^<\s]+)\s*</joint_?[Nn]ame>", body)
                if joints:
                    named.update(joints)
                else:
                    all_cov = True
            elif "diff_drive" in fname and re.search(
                    r"<publish_?[Ww]heel_?(?:[Jj]oint_?[Ss]tate|[Tt][Ff])>\s*(true|1)\s*<", body):
                # wheel joint states (ROS 1 publishWheelJointState), or the wheel-to-base transforms themselves
                # (gazebo_ros_diff_drive publish_wheel_tf): either way the wheels are in TF
                named.update(re.findall(r"<(?:left|right)_?[Jj]oint>\s*([^<\s]+)\s*<", body))
    if model.plugins:  # gz-sim's JointStatePublisher and the catalogue's other joint-state plugins
        from urdfcheck.consumers.gazebo import state_joints

        every, more = state_joints(model)
        all_cov, named = all_cov or every, named | more
    return all_cov, named


@check("C003", needs="consumers")
def joint_without_state_source(model: Model, ctx: Context) -> Iterator[Problem]:
    """A movable joint nothing publishes a state for, in a deployment we know something about."""
    c = consumers(model, ctx)
    bringup = any(li.state_publishers for li in c.launch)  # a launch file that brings the robot up
    if not len(c.controllers) and not c.drivers and not bringup:
        return
    if _no_state_publisher(c, model, ctx):
        # nothing known turns these joint states into TF: the launch files read start no robot_state_publisher,
        # and the model's package has launch files, none of which is known to start one (ros_controllers' test
        # robots run none)
        return
    movable = [j for j in model.joint_list if j.movable and j.mimic is None]
    if not movable:
        return
    if any(li.joint_state_publishers for li in c.launch):
        return
    gz_all, covered = _gazebo_state_joints(model)
    if gz_all:
        return
    hw_joints = {h.name for r in model.ros2_control if not r.in_gazebo for h in r.joints}
    trans_joints = {i.name for t in model.transmissions for i in t.joints}
    # a supplier whose file only an unvouched config makes run supplies nothing (consumers.run_with, issue 36)
    ctrls, drivers = [x for x in c.controllers if c.runs(x.file)], [d for d in c.drivers if c.runs(d.file)]
    unrun = [x for x in (*c.controllers, *c.drivers) if not c.runs(x.file)]
    sources, got, everything = _state_cover(ctrls, drivers, hw_joints, trans_joints, local=True)
    if everything:
        return  # a broadcaster of hardware described elsewhere: assume it covers the model
    covered |= got
    missing = [j for j in movable if j.name not in covered]
    if not missing:
        return
    # suppliers not known to run in this deployment: the package's unread files, then the workspace's
    far, far_covered, everything = _state_cover(ctrls, drivers, hw_joints, trans_joints, local=False)
    workspace = False
    if not far:  # a broadcaster in a workspace file that names these joints (a `*_control` package)
        from urdfcheck.consumers.openworld import workspace_broadcasters

        found = workspace_broadcasters(c, set(model.joints))
        far = [b for b, _ in found]
        far_covered = set().union(set(), *(named | hw_joints for _, named in found))
        everything = False
        workspace = bool(far)
    if everything:
        far_covered = {j.name for j in missing}
    supplied = [j for j in missing if j.name in far_covered]
    if supplied:
        names = ", ".join(j.name for j in supplied[:6]) + (", ..." if len(supplied) > 6 else "")
        who = ", ".join(dict.fromkeys(s.name + ("" if os.path.basename(s.file) in s.name else
                                                f" ({os.path.basename(s.file)})") for s in far[:3]))
        yield Problem(f"the state of {len(supplied)} movable joint(s) ({names}) comes from {who}, which this "
                      f"deployment does not start ({_elsewhere(far[0])}): not failed; run it with this model",
                      at=far[0].loc, related=_dedupe_locs(supplied[:6], far[0].loc), severity=_INFO())
    missing = [j for j in missing if j.name not in far_covered]
    if not missing:
        return
    if not sources and not far:
        names = ", ".join(j.name for j in missing[:6]) + (", ..." if len(missing) > 6 else "")
        where = _consumer_anchor(c) or model.loc
        yield Problem(f"nothing publishes joint states for the model's {len(missing)} movable joint(s) ({names}): "
                      f"no joint_state_broadcaster/joint_state_controller, joint_state_publisher or driver; "
                      f"robot_state_publisher cannot place their child links", at=where,
                      related=_dedupe_locs(missing[:6], where), absent="publish them")
        return
    # evidence cuts both ways: the suppliers found cover other joints, not these; when none of them runs here,
    # the claim rests on how their files were paired with the model (a workspace file: by joint names, a guess)
    rests = () if sources else _far_pairing(c, far, model, workspace)
    for j in missing:
        yield Problem(f"nothing publishes the state of joint {j.name!r} (the joint state broadcaster does not "
                      f"cover it and no driver names it); robot_state_publisher will not publish "
                      f"{j.child!r}{_unrun_hint(unrun, j.name)}", at=j, data={"joint": j.name}, rests_on=rests)


def _unrun_hint(unrun, joint: str) -> str:
    """What to say when a supplier only an unvouched config makes run names the joint (issue 36)."""
    for x in unrun:
        if any(u.joint == joint for u in (*getattr(x, "state_joints", ()), *x.joints)):
            return (f"; {x.name} ({shown(x.file)}) names it, but only the config makes its file run with the model "
                    "(no launch file that starts robot_state_publisher loads it), which counts only in a config the "
                    "runner names with --config FILE --trust-config (or --config-from REV)")
    return ""


def _far_pairing(c, far, model, workspace: bool) -> tuple:
    """The pairing steps (core.evidence) of the suppliers not known to run here that a C003 claim rests on."""
    from urdfcheck.consumers.pairing import step

    pairing = getattr(c, "pairing", None) or {}
    out = []
    for s in far[:3]:
        f = getattr(s, "file", "") or ""
        got = pairing.get(realpath(f)) if f else None
        if got is None and f:
            got = step(f, "overlap" if workspace else "package", getattr(model, "source", "") or "")
        if got is not None and got not in out:
            out.append(got)
    return tuple(out)


def _elsewhere(item) -> str:
    return getattr(item, "elsewhere", None) or "it is configured in another package of the workspace"


def _state_cover(controllers, drivers, hw_joints: set, trans_joints: set, local: bool):
    """(sources, joints covered, everything) by the joint state suppliers that run here (`local`) or are not
    known to (`elsewhere`, issue 20); everything: a broadcaster of hardware described outside the model
    (assumed to cover every joint)."""
    sources, covered, everything = [], set(), False
    for ctrl in controllers:
        if bool(getattr(ctrl, "elsewhere", None)) == local:
            continue
        if ctrl.broadcasts_all:
            sources.append(ctrl)
            joints = hw_joints if ctrl.ros == 2 else trans_joints
            everything = everything or not joints
            covered |= joints
        for u in ctrl.state_joints:
            covered.add(u.joint)
            sources.append(ctrl)
    for d in drivers:
        if bool(getattr(d, "elsewhere", None)) == local:
            continue
        for u in d.joints:
            covered.add(u.joint)
            sources.append(d)
    return sources, covered, everything


def _INFO():
    from urdfcheck.core.findings import Severity

    return Severity.INFO


def _package_launches(c: Consumers, model, ctx) -> list:
    """The launch files of the model's package (zero-config discovery lists them; for a config, which may
    declare none, they are looked up)."""
    known = (c.files or {}).get("package_launch")
    if known is not None or c.origin != "config":
        return known or []
    from urdfcheck.consumers.consumers import _package_root
    from urdfcheck.load.discover import LAUNCH_SUFFIXES, _walk

    entry = getattr(getattr(ctx, "expanded", None), "entry", None) or model.source
    root = _package_root(entry) if entry else None
    if root is None:
        return []
    # any launch file of the package, wherever it lies (ros_controllers keeps its test launch files in test/)
    return [os.path.join(d, f) for d, f in _walk(str(root), 5000) if f.lower().endswith(LAUNCH_SUFFIXES)]


def _consumer_anchor(c: Consumers) -> Location | None:
    for ctrl in c.controllers:
        return ctrl.loc
    for li in c.launch:
        return Location(li.path, 1)
    for d in c.drivers:
        return d.loc
    return None


# --- C004..C006: <ros2_control> ----------------------------------------------------------------------------
@check("C004", needs="ros2_control")
def ros2_control_joint_invalid(model: Model, ctx: Context) -> Iterator[Problem]:
    """A <ros2_control> <joint> that is not a movable joint of the model, or declared twice."""
    seen: dict[tuple, tuple] = {}
    for r in model.ros2_control:
        if r.in_gazebo:
            continue
        for h in r.joints:
            j = model.joints.get(h.name)
            if _unresolved(h.name):
                continue
            if j is None:
                hint = (f"; {h.name!r} is a link, not a joint" if h.name in model.links
                        else _suggest(h.name, model.joints))
                yield Problem(f"<ros2_control name={r.name!r}> declares joint {h.name!r}, which the model does not "
                              f"have{hint}", at=h)
            elif not j.movable:
                yield Problem(f"<ros2_control name={r.name!r}> declares joint {h.name!r}, but it is a {j.type} "
                              f"joint: its state is ignored by robot_state_publisher and commands do nothing",
                              at=h, related=(j,))
            if not h.command and not h.state and not h.mimic:  # a mimic joint may follow its leader unexported
                yield Problem(f"<ros2_control name={r.name!r}> joint {h.name!r} has no command or state "
                              f"interface", at=h)
            # one joint may appear in several components (an actuator and a position sensor), but each
            # interface may be exported once
            for kind, ifaces in (("command", h.command), ("state", h.state)):
                for i in ifaces:
                    key = (h.name, kind, i.name)
                    prev = seen.get(key)
                    if prev is not None:
                        yield Problem(f"{kind} interface {h.name}/{i.name} is declared twice in <ros2_control> "
                                      f"(components {prev[0]!r} and {r.name!r}); the resource manager refuses "
                                      f"the second", at=i, related=(prev[1],))
                    else:
                        seen[key] = (r.name, i)


@check("C005", needs="consumers")
def missing_interface(model: Model, ctx: Context) -> Iterator[Problem]:
    """A ROS 2 controller needs a command/state interface the <ros2_control> block does not offer."""
    blocks = [r for r in model.ros2_control if not r.in_gazebo]
    if not blocks:
        return
    hw: dict[str, tuple[set, set, object]] = {}  # joint -> (command names, state names, first item)
    for r in blocks:
        for h in r.joints:
            cmd, st, first = hw.setdefault(h.name, (set(), set(), h))
            cmd.update(i.name for i in h.command)
            st.update(i.name for i in h.state)
    c = consumers(model, ctx)
    for ctrl in c.controllers:
        if ctrl.ros != 2:
            continue
        for u in ctrl.joints + ctrl.state_joints:
            if u.via or _unresolved(u.joint) or u.joint not in model.joints:
                continue
            if not u.command and not u.state:
                continue
            entry = hw.get(u.joint)
            if entry is None:
                need = ", ".join(f"command {i}" for i in u.command) or ", ".join(f"state {i}" for i in u.state)
                yield Problem(f"controller {ctrl.name} needs {need} on joint {u.joint!r}, which no <ros2_control> "
                              f"block declares", at=u.loc, related=tuple(blocks[:1]))
                continue
            cmd, st, h = entry
            for i in u.command:
                if i not in cmd:
                    yield Problem(f"controller {ctrl.name} commands {u.joint!r} through the {i!r} interface, but "
                                  f"<ros2_control> offers {_list(cmd)} as command interfaces", at=u.loc, related=(h,))
            for i in u.state:
                if i not in st:
                    yield Problem(f"controller {ctrl.name} reads the {i!r} state of {u.joint!r}, but "
                                  f"<ros2_control> offers {_list(st)} as state interfaces", at=u.loc, related=(h,))


def _list(names) -> str:
    return ", ".join(sorted(names)) if names else "none"


@check("C006", needs="ros2_control")
def ros2_control_in_gazebo(model: Model, ctx: Context) -> Iterator[Problem]:
    for r in model.ros2_control:
        if r.in_gazebo:
            yield Problem(f"<ros2_control name={r.name!r}> is written inside <gazebo>, where neither the "
                          f"controller manager nor the Gazebo plugin reads it; its hardware has no joints",
                          at=r)


# --- C007: unreadable consumers --------------------------------------------------------------------------
@check("C007", needs="consumers")
def unreadable_consumer(model: Model, ctx: Context) -> Iterator[Problem]:
    c = consumers(model, ctx)
    for e in c.errors:
        yield Problem(e.message, at=e.location)
    for d in c.drivers:
        for key, loc in d.missing:
            yield Problem(f"driver {d.name}: key {key!r} is not in {shown(d.file)}", at=loc)
    yield from _home_parameter_files(model)


# a home folder: /home/<user>/, /Users/<user>/ (macOS), /root/, ~/
_HOME = lazyre.compile(r"^(?:/home/[^/]+/|/Users/[^/]+/|/root/|~/)")


def _home_parameter_files(model) -> Iterator[Problem]:
    """A Gazebo ros2_control plugin whose <parameters> names a file in someone's home folder: it exists on the
    author's machine only, so everywhere else (CI, a colleague, the robot) the controller manager in the simulator
    starts with no controllers. A `$(find pkg)` that xacro resolved to this checkout is not one."""
    here = [realpath(os.getcwd())]
    if model.source:
        here.append(os.path.dirname(os.path.dirname(realpath(model.source))))
    for p in model.plugins or ():
        if "ros2_control" not in f"{p.filename} {p.name}":
            continue
        for par in p.all("parameters"):
            path = par.text.strip()
            if not _HOME.match(path):
                continue
            real = realpath(os.path.expanduser(path)) if path.startswith("/") else path
            if any(real == h or real.startswith(h.rstrip("/") + "/") for h in here):
                continue
            yield Problem(f"{os.path.basename(p.filename) or p.name} <parameters> names {path}, a file in someone's "
                          f"home folder: on every other machine (CI, a colleague's, the robot) the controller manager "
                          f"in the simulator finds no such file and starts no controllers; write "
                          f"$(find <package>)/config/<file>.yaml", at=par.loc)


# --- C010..C014: wheels ------------------------------------------------------------------------------------
def _drives(c: Consumers, model=None):
    for ctrl in c.controllers:
        base = ctrl.odom_tf.child if ctrl.odom_tf is not None else None
        if ctrl.drive is not None:
            yield ctrl.drive, base
        if ctrl.wheels is not None and model is not None:
            from urdfcheck.rules.contracts.drives import drive_of

            drive = drive_of(model, ctrl.wheels, _base_in_model(model, c, base))
            if drive is not None:
                yield drive, base
    for d in c.drivers:
        if d.drive is not None:
            yield d.drive, None
    for drive, base in _plugin_drives(model, c):
        yield drive, base


def _base_in_model(model, c: Consumers, base: str | None) -> str | None:
    prefix = c.rsp_prefix
    b = base[len(prefix):] if base and prefix and base.startswith(prefix) else base
    if b not in model.links:
        b = c.frames.get("base") if c.frames.get("base") in model.links else None
    return b


def _plugin_drives(model, c: Consumers):
    """Gazebo diff-drive plugins and gz-sim systems in the model: wheel geometry the simulator is told."""
    if model is None or not model.plugins:
        return
    from urdfcheck.consumers.gazebo import plugin_drives

    yield from plugin_drives(model)


def _drive_reports(model, c: Consumers, tol: float, ang: float) -> list:
    """`check_drive` of each drive of the model's consumers, worked out once for the six rules that read it
    (C010-C015 with the same options: ~2 ms a model each time). Kept on the consumers, for this model only."""
    memo = c.__dict__.get("_drive_reports")
    if memo is not None and memo[0] is model and memo[1] == (tol, ang):
        return memo[2]
    reports = [(drive, check_drive(model, drive, base_frame=_base_in_model(model, c, base), tolerance=tol,
                                   angle_tolerance=ang))
               for drive, base in _drives(c, model)]
    c.__dict__["_drive_reports"] = (model, (tol, ang), reports)
    return reports


def _wheel_problems(model, ctx, code: str) -> Iterator[Problem]:
    c = consumers(model, ctx)
    tol = float(ctx.options["tolerance"])  # typed and defaulted by the catalogue (rules/C010.yaml ...)
    ang = float(ctx.options["angle_tolerance"])
    inferred = {d.name for d in c.drivers if _inferred(d)}
    for drive, rep in _drive_reports(model, c, tol, ang):
        for p in rep.problems():
            if p.code == code:
                related = _dedupe_locs(p.related, p.at)
                yield Problem(p.message, at=p.at, related=related, data=p.data,
                              severity=_WARNING() if drive.owner in inferred else p.severity, rests_on=p.rests_on)


@check("C010", needs="consumers")
def wheel_separation_mismatch(model: Model, ctx: Context) -> Iterator[Problem]:
    yield from _wheel_problems(model, ctx, "C010")


@check("C011", needs="consumers")
def wheel_radius_mismatch(model: Model, ctx: Context) -> Iterator[Problem]:
    yield from _wheel_problems(model, ctx, "C011")


@check("C012", needs="consumers")
def wheel_axes_not_parallel(model: Model, ctx: Context) -> Iterator[Problem]:
    yield from _wheel_problems(model, ctx, "C012")


@check("C013", needs="consumers")
def unequal_wheel_count(model: Model, ctx: Context) -> Iterator[Problem]:
    yield from _wheel_problems(model, ctx, "C013")


@check("C014", needs="consumers")
def wheel_sides_swapped(model: Model, ctx: Context) -> Iterator[Problem]:
    yield from _wheel_problems(model, ctx, "C014")


@check("C015", needs="consumers")
def wheel_direction_reversed(model: Model, ctx: Context) -> Iterator[Problem]:
    yield from _wheel_problems(model, ctx, "C015")


@check("C016", needs="consumers")
def drive_geometry_mismatch(model: Model, ctx: Context) -> Iterator[Problem]:
    """C016: wheelbase (steering controllers, tricycle) and mecanum lx + ly against the model."""
    from urdfcheck.rules.contracts.drives import geometry_problems

    c = consumers(model, ctx)
    tol = float(ctx.options["tolerance"])
    for ctrl in c.controllers:
        if ctrl.wheels is None:
            continue
        base = _base_in_model(model, c, ctrl.odom_tf.child if ctrl.odom_tf is not None else None)
        for p in geometry_problems(model, ctrl.wheels, base, tol):
            yield Problem(p.message, at=p.at, related=_dedupe_locs(p.related, p.at), data=p.data,
                          severity=p.severity)


# --- C017: <ros2_control> sensors and GPIOs ------------------------------------------------------------------
@check("C017", needs="consumers")
def unknown_hardware_component(model: Model, ctx: Context) -> Iterator[Problem]:
    """A controller names a <ros2_control> sensor or GPIO (sensor_name, gpios, ft_sensor.name) the model's
    <ros2_control> blocks do not declare."""
    blocks = [r for r in model.ros2_control if not r.in_gazebo]
    if not blocks:
        return  # hardware described elsewhere (or not at all): nothing to compare with
    c = consumers(model, ctx)
    items = {"sensor": {h.name for r in blocks for h in r.sensors}, "gpio": {h.name for r in blocks for h in r.gpios}}
    every = items["sensor"] | items["gpio"] | {h.name for r in blocks for h in r.joints}
    for ctrl in c.controllers:
        if ctrl.ros != 2:
            continue
        # a broadcaster told to put the node's namespace before the name (husarion's imu_sensor_broadcaster:
        # use_namespace_as_sensor_name_prefix) names `<namespace>/imu` at run time: compared by the last segment
        spaced = any("namespace" in k and "prefix" in k and as_bool(v.value) for k, v in ctrl.params.items())
        for comp in getattr(ctrl, "components", ()):
            known = items.get(comp.kind, every)
            if _unresolved(comp.name) or comp.name in known or comp.name in every:
                continue
            if spaced and any(n.rsplit("/", 1)[-1] == comp.name.rsplit("/", 1)[-1] for n in known | every):
                continue
            what = {"sensor": "<sensor>", "gpio": "<gpio>"}.get(comp.kind, "item")
            yield Problem(f"controller {ctrl.name} ({ctrl.type}) names {what} {comp.name!r}, which no <ros2_control> "
                          f"block of the model declares{_suggest(comp.name, sorted(known))}: the controller finds "
                          f"no interfaces to read or write and fails to activate", at=comp.loc,
                          related=tuple(blocks[:1]), data={"name": comp.name})


# --- C020: frame ids -----------------------------------------------------------------------------------
@check("C020", needs="consumers")
def unknown_frame(model: Model, ctx: Context) -> Iterator[Problem]:
    """A driver, controller or localization node uses a frame id that is not in the TF tree."""
    c = consumers(model, ctx)
    if not (len(c.controllers) or c.drivers or c.localization):
        return
    g = _graph(model, c)
    prefix = c.rsp_prefix
    links = {prefix + n for n in model.links}
    items: list = []
    for ctrl in c.controllers:
        items.extend((v, f"controller {ctrl.name}", ctrl.name) for v in ctrl.frames)
    for d in c.drivers:
        items.extend((v, f"driver {d.name}", d.name) for v in d.frames)
    inferred = {d.name for d in c.drivers if _inferred(d)} | {x.name for x in c.controllers if _inferred(x)}
    for n in [*c.localization, *c.elsewhere_localization]:
        items.append((n.base_frame, f"{n.kind} {n.node}", f" {n.node}"))
    seen = set()
    for v, who, owner in items:
        name = str(v.value).strip().lstrip("/")
        if not name or _unresolved(name) or name in links or (name, v.loc) in seen:
            continue
        # a frame somebody else publishes is in the tree; the user's own odometry claim does not count, nor an
        # untrusted config's declaration or a file only it names (rules.checks.tf.graph.claim_only)
        others = {f for cl in g.claims if cl.owner != owner and not cl.owner.endswith(owner)
                  and not claim_only(g, cl) for f in (cl.parent, cl.child)}
        if name in others:
            continue
        seen.add((name, v.loc))
        hint = _suggest_frame(name, sorted(links | others))
        # a near miss of a frame that exists is evidence of a typo; without one, the claim is that nothing
        # publishes the frame, which holds only where the whole deployment was understood (issue 20)
        yield Problem(f"{who} uses frame {name!r}, which is neither a link of the model nor published by "
                      f"anything else{hint}{untrusted_hint(g, (name,), owner)}", at=v.loc, data={"frame": name},
                      severity=_WARNING() if owner in inferred else None, absent=None if hint else "publish it")


def _no_state_publisher(c: Consumers, model, ctx) -> bool:
    """The launch files known start no robot_state_publisher, and the model's package has launch files:
    nothing publishes the model's own frames (ros_controllers' test robots)."""
    bringup = any(li.state_publishers for li in c.launch)
    return not bringup and bool(c.launch or _package_launches(c, model, ctx))
