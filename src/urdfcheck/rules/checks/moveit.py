"""M rules: the MoveIt configuration paired with the model (consumers.moveit) names links, joints and groups that
must exist, and limits that must agree with the model's (issue 41).

Every problem rests on the config's pairing with the model (`MoveItConfig.step`): a config paired only by a guess
(the SRDF's robot name) gives infos (the evidence rule, core.evidence).
"""
from __future__ import annotations

import math

from urdfcheck.core.findings import Problem, closest
from urdfcheck.core.records import TYPE_CHECKING
from urdfcheck.rules.catalogue import check

if TYPE_CHECKING:  # the checks' argument types (no import at run time)
    from collections.abc import Iterator

    from urdfcheck.model.robot import Model
    from urdfcheck.rules.engine import Context

# MoveIt lets a start state stray this far outside the bounds (move_group's start_state_max_bounds_error default)
START_STATE_SLACK = 0.05
# faster than any arm joint turns: 10 turns a second; a velocity above it is taken for degrees per second
MAX_RAD_S = 2 * math.pi * 10
# a position limit beyond this many turns is taken for degrees (multi-turn joints stay well below)
MAX_TURNS = 4


def _configs(ctx):
    """The MoveIt configs of the model, as the checked variant of the model sees them. A model expanded with
    arguments other than its defaults (a launch file's, an explored variant such as gripper=false) meets an SRDF
    written as xacro expanded with the same arguments when it declares them; an SRDF that cannot follow them (a
    plain one, or one without those arguments) may be meant for another variant: its pairing is then a guess."""
    found = tuple(getattr(getattr(ctx, "contracts", None), "moveit", ()) or ())
    changed = _changed_args(ctx) if found else {}
    if not changed:
        return found
    from urdfcheck.consumers.common import ConsumerError
    from urdfcheck.consumers.moveit import read_srdf
    from urdfcheck.core.evidence import Step

    out = []
    for cfg in found:
        srdf = cfg.srdf
        mine = {k: v for k, v in changed.items() if k in srdf.declared}
        if mine:
            try:
                srdf = read_srdf(srdf.file, None, mine)
            except ConsumerError:
                continue
        step = cfg.step if mine else Step(cfg.step.what, cfg.step.subject, "guess",
                                          "the SRDF does not take the model's arguments "
                                          f"({', '.join(f'{k}:={v}' for k, v in sorted(changed.items()))})")
        out.append(_Variant(cfg, srdf, step))
    return tuple(out)


def _changed_args(ctx) -> dict:
    """The xacro arguments the model was expanded with that differ from its declared defaults."""
    exp = getattr(ctx, "expanded", None)
    args = getattr(exp, "args", None) or {}
    if not args or not getattr(exp, "entry", None):
        return {}
    from urdfcheck.load.variants import defaulted_args

    try:
        defaults = {**{k: v for k, v in (getattr(exp, "declared_args", None) or {}).items() if v is not None},
                    # (type: ignore below) inside the try: no expansion, no defaults
                    **defaulted_args(exp.entry, None)}  # type: ignore[union-attr]
    except Exception:  # noqa: BLE001 - defaults not told: every argument counts as changed
        defaults = {}
    return {k: str(v) for k, v in args.items() if str(defaults.get(k)) != str(v)}


class _Variant:
    """A MoveIt config seen from one variant of the model: its SRDF and pairing step replaced."""

    def __init__(self, cfg, srdf, step):
        self._cfg, self.srdf, self.step = cfg, srdf, step

    def __getattr__(self, name):
        return getattr(self._cfg, name)


def _hint(name: str, options) -> str:
    near = closest(name, options)
    return f" (did you mean {near!r}?)" if near else ""


@check("M001", "M002", "M003", "M004", "M005")
def srdf_names(model: Model, ctx: Context) -> Iterator[Problem]:
    links = set(model.links)
    for cfg in _configs(ctx):
        s, why = cfg.srdf, (cfg.step,)
        joints = set(model.joints) | {v[0] for v in s.virtual}  # srdfdom accepts a virtual joint's name too
        for g in s.groups.values():
            for base, tip in g.chains:
                for end, n in (("base", base), ("tip", tip)):
                    if n.name not in links:
                        yield Problem(f"SRDF group {g.name!r}: the chain's {end} link {n.name!r} is not a link of the "
                                      f"model{_hint(n.name, links)}; MoveIt leaves the chain out of the group",
                                      at=n.loc,
                                      code="M001", rests_on=why)
            for n in g.links:
                if n.name not in links:
                    yield Problem(f"SRDF group {g.name!r} names link {n.name!r}, which the model does not have"
                                  f"{_hint(n.name, links)}; MoveIt leaves it out of the group", at=n.loc, code="M001",
                                  rests_on=why)
            for n in g.joints:
                if n.name not in joints:
                    yield Problem(f"SRDF group {g.name!r} names joint {n.name!r}, which the model does not have"
                                  f"{_hint(n.name, joints)}; MoveIt leaves it out of the group", at=n.loc, code="M002",
                                  rests_on=why)
        for name, parent, _ in s.end_effectors:
            if parent is not None and parent.name not in links:
                yield Problem(f"SRDF end effector {name!r}: parent link {parent.name!r} is not a link of the model"
                              f"{_hint(parent.name, links)}", at=parent.loc, code="M001", rests_on=why)
        for name, group, _, values in s.states:
            for n, _ in values:
                if n.name not in joints:
                    yield Problem(f"SRDF group_state {name!r} ({group}) names joint {n.name!r}, which the model does "
                                  f"not have{_hint(n.name, joints)}; the named pose does not set it", at=n.loc,
                                  code="M002", rests_on=why)
        for pair in s.disabled:
            for n in pair:
                if n.name not in links:
                    yield Problem(f"collision entry names link {n.name!r}, which the model does not have"
                                  f"{_hint(n.name, links)}; MoveIt skips it, so the pair meant here is still checked "
                                  "for collisions", at=n.loc, code="M003", rests_on=why)
        roots = model.roots
        for name, parent_frame, child, _ in s.virtual:
            if child is None or len(roots) != 1:
                continue
            if child.name != roots[0] and parent_frame != roots[0]:
                # (a virtual joint from the URDF's own root, world -> base as Gazebo setups write it, repeats a joint
                # the URDF has: MoveIt skips it and plans from that root, as meant)
                known = "a link of the model, but not its root" if child.name in links else "not a link of the model"
                yield Problem(f"SRDF virtual joint {name!r} attaches {child.name!r} to {parent_frame!r}: {known} "
                              f"(the root is {roots[0]!r}); MoveIt skips the virtual joint", at=child.loc,
                              code="M004", rests_on=why)
        moved = _moved(cfg, ctx)
        for n in s.passive:
            j = model.joints.get(n.name)
            if j is None and n.name in joints:
                continue  # the virtual joint
            if j is None:
                yield Problem(f"SRDF passive joint {n.name!r} is not a joint of the model{_hint(n.name, joints)}",
                              at=n.loc, code="M005", rests_on=why)
            elif not j.movable:
                yield Problem(f"SRDF passive joint {n.name!r} is a {j.type} joint: only a movable joint can be "
                              "passive", at=n.loc, related=(j,), code="M005", rests_on=why)
            elif n.name in moved:
                yield Problem(f"SRDF passive joint {n.name!r} is moved by controller {moved[n.name][0]!r}: MoveIt "
                              "never plans a passive joint, so the trajectories it sends leave it out",
                              at=n.loc, related=(moved[n.name][1],), code="M005", rests_on=why)


def _moved(cfg, ctx) -> dict:
    """joint -> (controller, Location) for every joint a MoveIt or ros2_control controller commands."""
    out: dict = {}
    for name, joints, _ in cfg.controllers:
        for n in joints:
            out.setdefault(n.name, (name, n.loc))
    contracts = getattr(ctx, "contracts", None)
    for c in (*tuple(getattr(contracts, "controllers", ()) or ()), *cfg.ros2_controllers):
        for u in getattr(c, "joints", ()):
            if getattr(c, "kind", "") not in ("joint_state_broadcaster", "joint_state_controller"):
                out.setdefault(u.joint, (c.name, u.loc))
    return out


def _num(v):
    if isinstance(v, bool) or not isinstance(v, (int, float)):
        return None
    return float(v) if math.isfinite(v) else None


def _angular(j) -> bool:
    return j.type in ("revolute", "continuous")


@check("M010", "M011", "M012")
def joint_limits(model: Model, ctx: Context) -> Iterator[Problem]:
    joints = set(model.joints)
    for cfg in _configs(ctx):
        doc, why = cfg.joint_limits, (cfg.step,)
        if doc is None:
            continue
        body = doc.get("joint_limits")
        if not isinstance(body, dict):
            continue
        for name, lim in body.items():
            if not isinstance(lim, dict):
                continue
            j = model.joints.get(name)
            if j is None:
                yield Problem(f"joint_limits.yaml names joint {name!r}, which the model does not have"
                              f"{_hint(str(name), joints)}; MoveIt ignores its limits",
                              at=doc.key_loc("joint_limits", name), code="M010", rests_on=why)
                continue
            yield from _limit_values(doc, name, lim, j, why)


def _limit_values(doc, name, lim, j, why):
    degrees = set()
    vel = _num(lim.get("max_velocity"))
    if vel is not None and _angular(j) and lim.get("has_velocity_limits") is not False and vel > MAX_RAD_S:
        degrees.add("max_velocity")
        yield Problem(f"joint_limits.yaml: max_velocity {vel:g} of {j.type} joint {name!r} is more than 10 turns a "
                      f"second; it looks like degrees per second ({math.radians(vel):.4g} rad/s); MoveIt reads "
                      "rad/s", at=doc.loc("joint_limits", name, "max_velocity"), related=(j,), code="M012",
                      rests_on=why)
    if j.type == "revolute":
        for key in ("min_position", "max_position"):
            v = _num(lim.get(key))
            if v is not None and abs(v) > 2 * math.pi * MAX_TURNS and lim.get("has_position_limits") is not False:
                degrees.add(key)
                yield Problem(f"joint_limits.yaml: {key} {v:g} of revolute joint {name!r} is more than {MAX_TURNS} "
                              f"turns; it looks like degrees ({math.radians(v):.4g} rad); MoveIt reads radians",
                              at=doc.loc("joint_limits", name, key), related=(j,), code="M012", rests_on=why)
    limit = j.limit
    if limit is None:
        return
    checks = []
    if lim.get("has_position_limits") is not False and j.type in ("revolute", "prismatic"):
        checks += [("min_position", limit.lower, lambda y, u: y < u), ("max_position", limit.upper, lambda y, u: y > u)]
    if lim.get("has_velocity_limits") is not False and limit.velocity is not None and limit.velocity > 0:
        checks.append(("max_velocity", limit.velocity, lambda y, u: y > u))
    for key, urdf, wider in checks:
        y = _num(lim.get(key))
        if key in degrees or y is None or urdf is None:
            continue
        if wider(y, urdf) and abs(y - urdf) > 1e-6 * max(1.0, abs(urdf)):
            yield Problem(f"joint_limits.yaml: {key} {y:g} of joint {name!r} is beyond the model's {urdf:g}: MoveIt "
                          "plans with the YAML value, which the controllers and the hardware, holding the model's "
                          "limit, refuse or clip", at=doc.loc("joint_limits", name, key), related=(j,), code="M011",
                          rests_on=why)


@check("M013")
def kinematics_groups(model: Model, ctx: Context) -> Iterator[Problem]:
    for cfg in _configs(ctx):
        doc, why = cfg.kinematics, (cfg.step,)
        if doc is None or not cfg.srdf.groups:
            continue
        path, body = _solver_map(doc)
        if body is None:
            continue
        for group, v in body.items():
            if isinstance(v, dict) and "kinematics_solver" in v and group not in cfg.srdf.groups:
                yield Problem(f"kinematics.yaml configures a solver for group {group!r}, which the SRDF "
                              f"({_base(cfg.srdf.file)}) does not define{_hint(str(group), cfg.srdf.groups)}; "
                              "MoveIt gives the group it meant no solver", at=doc.key_loc(*path, group),
                              code="M013", rests_on=why)


def _solver_map(doc):
    """The mapping group -> solver settings: at the top, or under ros__parameters/robot_description_kinematics."""
    data = doc.data
    if not isinstance(data, dict):
        return (), None
    if any(isinstance(v, dict) and "kinematics_solver" in v for v in data.values()):
        return (), data
    for node, body in data.items():
        rk = body.get("ros__parameters", {}).get("robot_description_kinematics") \
            if isinstance(body, dict) and isinstance(body.get("ros__parameters"), dict) else None
        if isinstance(rk, dict):
            return (node, "ros__parameters", "robot_description_kinematics"), rk
    return (), None


def _base(path: str) -> str:
    import os

    return os.path.basename(path)


@check("M014")
def moveit_controllers(model: Model, ctx: Context) -> Iterator[Problem]:
    joints = set(model.joints)
    for cfg in _configs(ctx):
        why = (cfg.step,)
        grouped = cfg.srdf.group_joints(model)
        contracts = getattr(ctx, "contracts", None)
        ros2 = [*tuple(getattr(contracts, "controllers", ()) or ()), *cfg.ros2_controllers]
        by_name = {c.name: c for c in ros2}
        controlled = {u.joint for c in ros2 for u in getattr(c, "joints", ())
                      if getattr(c, "kind", "") not in ("joint_state_broadcaster", "joint_state_controller")}
        passive = {n.name for n in cfg.srdf.passive}
        for name, names, _ in cfg.controllers:
            same = by_name.get(name)
            theirs = {u.joint for u in same.joints} if same is not None else None
            for n in names:
                if n.name not in joints:
                    yield Problem(f"MoveIt controller {name!r} names joint {n.name!r}, which the model does not have"
                                  f"{_hint(n.name, joints)}", at=n.loc, code="M014", rests_on=why)
                    continue
                if model.joints[n.name].mimic is not None or n.name in passive:
                    continue  # never in a trajectory MoveIt sends: the controller need not command it
                if grouped is None:
                    continue  # a chain of the SRDF does not resolve (M001): what its groups plan is unknown
                if theirs is not None and theirs and n.name not in theirs and n.name in grouped:
                    yield Problem(f"MoveIt controller {name!r} names joint {n.name!r}, which the ros2_control "
                                  f"controller {name!r} does not command: it refuses MoveIt's trajectories",
                                  at=n.loc,
                                  # (type: ignore below) same has a loc (getattr)
                                  related=(same.loc,) if getattr(same, "loc", None) else (),  # type: ignore[union-attr]
                                  code="M014", rests_on=why)
                elif n.name not in grouped and n.name not in controlled and cfg.srdf.groups:
                    yield Problem(f"MoveIt controller {name!r} names joint {n.name!r}, which no SRDF group plans and "
                                  "no ros2_control controller commands", at=n.loc, code="M014", rests_on=why,
                                  severity=_warning())


def _warning():
    from urdfcheck.core.findings import Severity

    return Severity.WARNING


@check("M015")
def initial_positions(model: Model, ctx: Context) -> Iterator[Problem]:
    for cfg in _configs(ctx):
        doc, why = cfg.initial_positions, (cfg.step,)
        if doc is None:
            continue
        body = doc.get("initial_positions")
        if not isinstance(body, dict):
            continue
        for name, v in body.items():
            j = model.joints.get(name)
            x = _num(v)
            if j is None or x is None or j.type not in ("revolute", "prismatic") or j.limit is None:
                continue
            lo, hi = j.limit.lower, j.limit.upper
            if lo is None or hi is None or lo > hi:
                continue
            if x < lo - START_STATE_SLACK or x > hi + START_STATE_SLACK:
                yield Problem(f"initial_positions.yaml starts joint {name!r} at {x:g}, outside its limits "
                              f"[{lo:g}, {hi:g}]: the mock hardware starts there and MoveIt refuses to plan from a "
                              "start state out of bounds", at=doc.loc("initial_positions", name), related=(j,),
                              code="M015", rests_on=why)
