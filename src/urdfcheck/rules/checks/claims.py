"""ros2_control resources (issue 41): command interfaces two active controllers claim, chained references.

controller_manager gives each command interface to one active controller: activating a controller whose
interface is already claimed fails ("Resource conflict for controller '%s'. Command interface '%s' is already
claimed.", ros2_control controller_manager/src/controller_manager.cpp, `switch_controller` ->
`activate_controllers`; `ResourceManager::command_interface_is_claimed`). A chained controller writes to the
reference interfaces the controller it follows exports (`<controller>/<joint>/<interface>`); one that names a
reference the other does not export is never activated ("Unable to activate controller '%s' since the command
interface '%s' is not available.", `check_for_interfaces_availability_to_activate`).

Which controllers run together comes only from a launch file: the controllers one launch file spawns active
(a spawner without `--inactive`, `--stopped` or `--load-only`, under no condition that could not be decided).
A parameter file declares alternatives (a trajectory controller and a forward command controller on the same
joints) that a launch file starts one at a time, so declaring is never running.
"""
from __future__ import annotations

from collections.abc import Iterator

from urdfcheck.core.findings import Problem
from urdfcheck.core.records import TYPE_CHECKING
from urdfcheck.core.walk import real as realpath  # remembered for the run
from urdfcheck.rules.catalogue import check

if TYPE_CHECKING:  # the checks' argument types (no import at run time)
    from typing import Any

    from urdfcheck.model.robot import Model
    from urdfcheck.rules.engine import Context

_SPAWNER_EXES = ("spawner", "spawner.py")
_VALUE_FLAGS = frozenset((
    "-c", "--controller-manager", "-p", "--param-file", "-n", "--namespace", "-t", "--controller-type",
    "--controller-manager-timeout", "--switch-timeout", "--service-call-timeout", "--controller-ros-args",
    "--ns", "--timeout", "--shutdown-timeout", "--fallback_controllers", "--fallback-controllers"))
# spawner.py: `--inactive` ("configure the controller but do not switch it"), `--load-only`; ROS 2 Foxy/Galactic
# named the first `--stopped`
_NOT_ACTIVE = frozenset(("--inactive", "--stopped", "--load-only", "--load_only"))
# chainable controllers whose references are per joint: `<controller>/<joint>/<interface>`
# (admittance_controller `on_export_reference_interfaces`; pid_controller over `dof_names`)
_PER_JOINT_REFERENCES = frozenset(("admittance_controller/AdmittanceController", "pid_controller/PidController"))


def _spawns(li) -> list[tuple[int, str, object]]:
    """(line, controller name, spawner node) of the controllers one launch file's own spawners start active.
    ROS 2 `spawner` (`spawner.py` before Humble) and ROS 1 `spawner` (and `controller_manager spawn NAMES`)."""
    out = []
    for node in li.nodes:
        if node.package != "controller_manager":
            continue
        toks = list(node.args or ())
        if node.executable == "controller_manager" and toks[:1] == ["spawn"]:
            toks = toks[1:]  # ROS 1: `rosrun controller_manager controller_manager spawn a b`
        elif node.executable not in _SPAWNER_EXES:
            continue
        if node.condition or not toks or any("\x00" in a for a in toks):
            continue  # alternatives behind a launch argument, or names not literal
        if any(t in _NOT_ACTIVE for t in toks):
            continue
        i = 0
        while i < len(toks):
            t = toks[i]
            if t in _VALUE_FLAGS:
                i += 2
                continue
            if not t.startswith("-") and ":=" not in t:  # ROS 1 remappings (__name:=x) are no controller
                out.append((node.loc.line or 0, t, node))
            i += 1
    return out


def _manager(node) -> str:
    toks = list(node.args or ())
    for i, t in enumerate(toks[:-1]):
        if t in ("-c", "--controller-manager"):
            return toks[i + 1]
    return ""


def _followed(inc, included) -> bool:
    """An include whose spawners run with the including file's: its file literal and read, under no undecided
    condition, no namespace pushed around it (another controller_manager, another robot), and no argument
    passed that differs from the default the included file was read with (its spawners could name others)."""
    if inc.file is None or inc.condition is not None or included is None:
        return False
    if getattr(inc, "namespace", "").strip("/"):
        return False
    for name, decl in included.declared.items():
        if name in inc.args and inc.args[name] != decl.default:
            return False
    return True


MAX_INCLUDE_DEPTH = 8


def _spawn_groups(c) -> Iterator[tuple[Any, list]]:
    """(launch info, [(controller name, spawner node, include locations), ...]) of the controllers each launch
    file spawns active, its own spawners and those of the launch files it includes (followed as `_followed`
    says), per controller manager (a spawner's `-c` and namespace)."""

    by_path: dict[str, object] = {}
    for li in c.launch:
        by_path.setdefault(realpath(li.path), li)

    def members(li, via: tuple, stack: frozenset) -> list:
        entries = [(line, 0, [(name, node, via)]) for line, name, node in _spawns(li)]
        if len(stack) <= MAX_INCLUDE_DEPTH:
            for inc in li.includes:
                real = realpath(inc.file) if inc.file else ""
                included = by_path.get(real)
                if real in stack or not _followed(inc, included):
                    continue
                entries.append((inc.loc.line or 0, 1, members(included, (*via, inc.loc), stack | {real})))
        return [m for _, _, ms in sorted(entries, key=lambda e: (e[0], e[1])) for m in ms]

    for li in c.launch:
        groups: dict[tuple, list] = {}
        for name, node, via in members(li, (), frozenset({realpath(li.path)})):
            groups.setdefault((node.namespace or "", _manager(node)), []).append((name, node, via))
        for group in groups.values():
            yield li, group


# ROS 1: the controller's package names the hardware interface it claims its joints through (position_controllers/*:
# PositionJointInterface, ...), whatever it commands (effort_controllers/JointPositionController: effort)
_ROS1_INTERFACE = {"position_controllers": "position", "velocity_controllers": "velocity",
                   "effort_controllers": "effort"}


def _claims(ctrl) -> dict[str, object]:
    """'joint/interface' -> JointUse of the hardware command interfaces the controller claims."""
    out: dict[str, object] = {}
    ros1 = _ROS1_INTERFACE.get((ctrl.type or "").partition("/")[0]) if ctrl.ros == 1 else None
    for u in ctrl.joints:
        if u.via:
            continue  # a chained controller claims the references of the one it follows, not the hardware
        for iface in ((ros1,) if ros1 and u.role == "joint" else u.command):
            if iface and "$" not in u.joint:
                out.setdefault(f"{u.joint}/{iface}", u)
    return out


@check("C022", needs="consumers")
def interface_claimed_twice(model: Model, ctx: Context) -> Iterator[Problem]:
    """Two controllers one launch file spawns active, itself or through the files it includes, claim the same
    command interface."""
    from urdfcheck.consumers.consumers import consumers_of as consumers
    from urdfcheck.core.paths import shown as shown_path

    c = consumers(model, ctx)
    if not len(c.controllers) or not c.launch:
        return
    done: set[tuple] = set()
    for li, members in _spawn_groups(c):
        ros = 1 if li.format == "ros1-xml" else 2
        holders: dict[str, tuple] = {}  # interface -> (controller, JointUse, spawner node, include locations)
        seen: set[str] = set()
        for name, node, via in members:
            ctrl = c.controllers.by_name(name)
            if ctrl is None or ctrl.ros != ros or name in seen:
                continue
            seen.add(name)
            taken: dict[str, list] = {}
            for iface, u in _claims(ctrl).items():
                first = holders.get(iface)
                if first is None:
                    holders[iface] = (ctrl, u, node, via)
                elif first[0].name != ctrl.name:
                    taken.setdefault(first[0].name, []).append((iface, u, first))
            for other, items in taken.items():
                ifaces = [i for i, _, _ in items]
                _, u0, first = items[0]
                key = (node.loc.file, node.loc.line, first[2].loc.file, first[2].loc.line, other, ctrl.name)
                if key in done:
                    continue  # the same pair again, from a file that includes both
                done.add(key)
                shown = ", ".join(ifaces[:6]) + (f" and {len(ifaces) - 6} more" if len(ifaces) > 6 else "")
                where = ("here" if not via and not first[3] else
                         f"by {shown_path(li.path)} (through the launch files it includes)")
                yield Problem(
                    f"controllers {other} and {ctrl.name} are both spawned active {where} and both claim command "
                    f"interface{'s' if len(ifaces) > 1 else ''} {shown}: controller_manager gives a command "
                    f"interface to one active controller and refuses to activate the other ('Resource conflict')",
                    at=node.loc, related=(first[2].loc, first[1].loc, u0.loc, *first[3], *via),
                    data={"controllers": [other, ctrl.name], "interfaces": ifaces})


@check("C023", needs="consumers")
def chained_reference_missing(model: Model, ctx: Context) -> Iterator[Problem]:
    """A chained controller names a reference interface the controller it follows does not export."""
    from urdfcheck.consumers.consumers import consumers_of as consumers

    c = consumers(model, ctx)
    if not len(c.controllers):
        return
    for ctrl in c.controllers:
        for u in ctrl.joints:
            if not u.via:
                continue
            leader = c.controllers.by_name(u.via)
            if leader is None or leader.type not in _PER_JOINT_REFERENCES or getattr(leader, "inferred", False):
                continue
            exported = [x.joint for x in leader.joints if not x.via and x.command]
            if not exported:
                continue  # its joints were not read: nothing to compare with
            joint = u.joint.split("/", 1)[0]
            if joint in exported or "$" in joint:
                continue
            yield Problem(
                f"controller {ctrl.name} follows {leader.name} through reference '{u.written or u.joint}', but "
                f"{leader.name} exports references only for {', '.join(exported)}: controller_manager does not "
                f"activate {ctrl.name} (the command interface is not available)",
                at=u.loc, related=(leader.loc,), data={"controller": ctrl.name, "leader": leader.name,
                                                        "reference": u.written or u.joint})
