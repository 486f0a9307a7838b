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
from typing import TYPE_CHECKING

from urdfcheck.core.findings import Problem
from urdfcheck.rules.catalogue import check

if TYPE_CHECKING:  # the checks' argument types (no import at run time)
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


def _spawn_groups(c) -> Iterator[tuple[object, list]]:
    """(launch info, [(controller name, spawner node), ...]) of the controllers each launch file spawns active,
    per controller manager (a spawner's `-c` and namespace)."""
    for li in c.launch:
        groups: dict[tuple, list] = {}
        for node in li.nodes:
            if node.package != "controller_manager" or node.executable not in _SPAWNER_EXES:
                continue
            if node.condition or not node.args or any("\x00" in a for a in node.args):
                continue  # alternatives behind a launch argument, or names not literal
            toks = list(node.args)
            if any(t in _NOT_ACTIVE for t in toks):
                continue
            manager, names, i = "", [], 0
            while i < len(toks):
                t = toks[i]
                if t in _VALUE_FLAGS:
                    if t in ("-c", "--controller-manager") and i + 1 < len(toks):
                        manager = toks[i + 1]
                    i += 2
                    continue
                if not t.startswith("-"):
                    names.append(t)
                i += 1
            key = (node.namespace or "", manager)
            groups.setdefault(key, []).extend((n, node) for n in names)
        for members in groups.values():
            yield li, members


def _claims(ctrl) -> dict[str, object]:
    """'joint/interface' -> JointUse of the hardware command interfaces the controller claims."""
    out: dict[str, object] = {}
    for u in ctrl.joints:
        if u.via:
            continue  # a chained controller claims the references of the one it follows, not the hardware
        for iface in u.command:
            if iface and "$" not in u.joint:
                out.setdefault(f"{u.joint}/{iface}", u)
    return out


@check("C022", needs="consumers")
def interface_claimed_twice(model: Model, ctx: Context) -> Iterator[Problem]:
    """Two controllers one launch file spawns active claim the same command interface."""
    from urdfcheck.consumers.consumers import consumers_of as consumers

    c = consumers(model, ctx)
    if not len(c.controllers) or not c.launch:
        return
    for _li, members in _spawn_groups(c):
        holders: dict[str, tuple] = {}  # interface -> (controller, JointUse, spawner node)
        seen: set[str] = set()
        for name, node in members:
            ctrl = c.controllers.by_name(name)
            if ctrl is None or ctrl.ros != 2 or name in seen:
                continue
            seen.add(name)
            taken: dict[str, list] = {}
            for iface, u in _claims(ctrl).items():
                first = holders.get(iface)
                if first is None:
                    holders[iface] = (ctrl, u, node)
                elif first[0].name != ctrl.name:
                    taken.setdefault(first[0].name, []).append((iface, u, first))
            for other, items in taken.items():
                ifaces = [i for i, _, _ in items]
                _, u0, first = items[0]
                shown = ", ".join(ifaces[:6]) + (f" and {len(ifaces) - 6} more" if len(ifaces) > 6 else "")
                yield Problem(
                    f"controllers {other} and {ctrl.name} are both spawned active here and both claim command "
                    f"interface{'s' if len(ifaces) > 1 else ''} {shown}: controller_manager gives a command "
                    f"interface to one active controller and refuses to activate the other ('Resource conflict')",
                    at=node.loc, related=(first[2].loc, first[1].loc, u0.loc),
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
