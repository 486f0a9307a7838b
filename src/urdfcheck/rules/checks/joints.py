"""J rules: joint types, limits, axes and mimic relations.

Every joint definition is checked where it is written (duplicates included: S008 reports the duplicate
itself, these rules what is wrong inside it). Mimic targets resolve to the first definition of a name, as
urdfdom would if it accepted the duplicate.

Behaviour quoted in the messages was checked against urdfdom 3.0.1 (check_urdf), Pinocchio 4.1 and
yourdfpy 0.0.60, and read from the sources of kdl_parser, robot_state_publisher, joint_state_publisher and
MoveIt (see each rule's catalogue entry).
"""
from __future__ import annotations

import math

from urdfcheck.core.findings import Problem, Severity, closest
from urdfcheck.core.records import TYPE_CHECKING
from urdfcheck.model.robot import JOINT_TYPES, MOVABLE_TYPES
from urdfcheck.rules.catalogue import check

if TYPE_CHECKING:  # the checks' argument types (no import at run time)
    from collections.abc import Iterator

    from urdfcheck.model.robot import Model
    from urdfcheck.rules.engine import Context

# joint types whose <axis> every consumer uses. A planar joint's axis (the plane normal in the URDF spec) is
# ignored by KDL (planar becomes fixed), MoveIt and Pinocchio (always the joint frame's XY plane): J011 says so
# when it is not z, instead of J006/J007 judging a value nobody reads.
AXIS_TYPES = ("revolute", "continuous", "prismatic")
POSITION_LIMITED = ("revolute", "prismatic")
ZERO_AXIS = 1e-12  # an axis shorter than this cannot be normalised meaningfully


def _q(name) -> str:
    return repr(name)


def _num(v: float) -> str:
    return f"{v:g}"


def _norm(axis) -> float:
    x, y, z = axis
    return math.sqrt(x * x + y * y + z * z)


def _length_text(norm: float) -> str:
    """The length with the digits that differ from 1 shown (1.0000029, never "1" for a length that is not 1)."""
    off = abs(norm - 1.0)
    decimals = 6 if off == 0 or off >= 1e-5 else min(17, math.ceil(-math.log10(off)) + 1)
    text = f"{norm:.{decimals}f}".rstrip("0").rstrip(".")
    return text if off >= 1e-5 or text != "1" else f"{norm:.17g}"


def _axis_text(axis) -> str:
    # as written (shortest round-trip form): "0.99999762" must not read "0.999998"
    return " ".join(repr(float(v)).removesuffix(".0") for v in axis)


def _unreadable(model) -> set:
    """Locations of elements with a value the builder could not read (U004/U005): their fields hold defaults,
    which the J rules must not mistake for values written in the file."""
    return {i.loc for i in model.issues if i.code in ("U004", "U005")}


@check("J001")
def unknown_joint_type(model: Model, ctx: Context) -> Iterator[Problem]:
    for j in model.joint_list:
        if not j.type or j.type in JOINT_TYPES:  # a missing type is U006
            continue
        close = closest(j.type.lower(), JOINT_TYPES, cutoff=0.6)
        hint = f" (did you mean {close!r}?)" if close else ""
        yield Problem(
            f"joint {_q(j.name)} has unknown type {j.type!r}{hint}; URDF knows {', '.join(JOINT_TYPES)}. urdfdom "
            f"refuses the model ('Joint [{j.name}] has no known type [{j.type}]')",
            at=j)


@check("J002")
def missing_limit(model: Model, ctx: Context) -> Iterator[Problem]:
    unreadable = _unreadable(model)
    v12 = model.version >= (1, 2)
    for j in model.joint_list:
        if j.type not in POSITION_LIMITED:
            continue
        if j.limit is None:
            yield Problem(
                f"{j.type} joint {_q(j.name)} has no <limit>: urdfdom refuses the model ('Joint [{j.name}] is of "
                f"type {j.type.upper()} but it does not specify limits')",
                at=j)
            continue
        missing = [k for k in ("lower", "upper") if getattr(j.limit, k) is None]
        if missing and j.limit.loc not in unreadable:
            what = "neither lower nor upper" if len(missing) == 2 else f"no {missing[0]}"
            if v12:  # urdfdom 6.0 joint.cpp parseJointLimits
                yield Problem(
                    f"the <limit> of {j.type} joint {_q(j.name)} gives {what}: in URDF 1.2 urdfdom refuses the "
                    f"model ('joint [{j.name}]: revolute and prismatic joints must have both lower and upper "
                    f"position limits specified in URDF version 1.2 or later')",
                    at=j.limit)
                continue
            yield Problem(
                f"the <limit> of {j.type} joint {_q(j.name)} gives {what}: urdfdom silently uses 0 "
                f"(range [{_num(j.limit.lower or 0.0)}, {_num(j.limit.upper or 0.0)}]), and joint_state_publisher "
                f"(ROS 2) refuses the description ('\"{missing[0]}\" limit must be specified')",
                at=j.limit, severity=Severity.WARNING)


@check("J003")
def inverted_limits(model: Model, ctx: Context) -> Iterator[Problem]:
    unreadable = _unreadable(model)
    for j in model.joint_list:
        if j.type not in POSITION_LIMITED or j.limit is None or j.limit.loc in unreadable:
            continue
        lo, up = j.limit.lower, j.limit.upper
        eff_lo = 0.0 if lo is None else lo
        eff_up = 0.0 if up is None else up
        if model.version >= (1, 2) and (lo is None or up is None):
            continue  # J002: urdfdom refuses the model
        if eff_lo > eff_up:
            given = "" if lo is not None and up is not None else " (a missing bound counts as 0 in urdfdom)"
            effect = ("no position satisfies both, so MoveIt considers every state of this joint out of bounds"
                      if model.version < (1, 2) else
                      f"in URDF 1.2 urdfdom refuses the model ('joint [{j.name}]: upper position limit ... cannot "
                      f"be smaller than lower position limit')")
            yield Problem(
                f"joint {_q(j.name)} has lower limit {_num(eff_lo)} above upper limit {_num(eff_up)}{given}: "
                f"{effect}",
                at=j.limit)
        elif lo is not None and up is not None and lo == up:
            yield Problem(
                f"joint {_q(j.name)} has lower == upper == {_num(lo)}: it cannot move, yet it stays a {j.type} "
                f"joint in /joint_states and in MoveIt; use type=\"fixed\" if it is meant to be locked",
                at=j.limit, severity=Severity.INFO)


@check("J004")
def non_positive_effort_or_velocity(model: Model, ctx: Context) -> Iterator[Problem]:
    # joints the model gives an actuator (<transmission>, <ros2_control>); effort="0" on any other joint is the
    # convention for an un-actuated one (Drake: "<effort>0</effort> for un-actuated joints"; a passive spring
    # such as the Create 3 wheel drop), so its zero limits are not reported
    actuated = {i.name for t in model.transmissions for i in t.joints} | \
        {h.name for r in model.ros2_control for h in r.joints}
    for j in model.joint_list:
        if j.type not in MOVABLE_TYPES or j.limit is None:
            continue
        passive = j.limit.effort == 0 and j.name not in actuated
        for key in ("effort", "velocity"):
            v = getattr(j.limit, key)
            if v is None or v > 0 or (v == 0 and passive):
                continue
            if v < 0 and model.version >= (1, 2):  # urdfdom 6.0 joint.cpp parseJointLimits
                yield Problem(
                    f"joint {_q(j.name)} has {key} limit {_num(v)}: in URDF 1.2 urdfdom refuses the model "
                    f"('joint [{j.name}]: {key} value ({_num(v)}) is negative')",
                    at=j.limit, severity=Severity.ERROR)
                continue
            if v < 0:
                effect = (f"Pinocchio refuses the model ('Some components of min_{key} are greater than "
                          f"max_{key}') and Gazebo (SDFormat) reads a negative limit as 'no limit'")
            elif key == "effort":
                effect = "Gazebo enforces it, so no force can move the joint in simulation"
            else:
                effect = "MoveIt reads a zero velocity limit as 'unbounded' and plans trajectories without one"
            yield Problem(
                f"joint {_q(j.name)} has {key} limit {_num(v)}: urdfdom accepts it, but {effect}",
                at=j.limit)


@check("J012")
def limit_derivatives(model: Model, ctx: Context) -> Iterator[Problem]:
    """URDF 1.2 acceleration, deceleration and jerk limits (urdfdom 6.0 joint.cpp parseJointLimits)."""
    if model.version < (1, 2):
        return  # not read (U008)
    for j in model.joint_list:
        lim = j.limit
        if lim is None:
            continue
        for key in ("acceleration", "deceleration", "jerk"):
            v = getattr(lim, key)
            if v is None or v > 0:
                continue
            if v < 0:
                yield Problem(
                    f"joint {_q(j.name)} has {key} limit {_num(v)}: urdfdom refuses the model ('joint [{j.name}]: "
                    f"{key} value ({_num(v)}) is negative'), so robot_state_publisher does not start",
                    at=lim)
            else:
                inherited = (" (and, with no deceleration given, the deceleration limit too: urdfdom copies the "
                             "acceleration limit)" if key == "acceleration" and lim.deceleration is None else "")
                yield Problem(
                    f"joint {_q(j.name)} has {key} limit 0{inherited}: urdfdom accepts it, but a controller that "
                    f"honours it can never change the joint's speed; leave the attribute out for no limit",
                    at=lim, severity=Severity.WARNING)


@check("J005")
def continuous_with_position_limits(model: Model, ctx: Context) -> Iterator[Problem]:
    for j in model.joint_list:
        if j.type != "continuous" or j.limit is None:
            continue
        lo, up = j.limit.lower, j.limit.upper
        if all(v is None or v == 0 for v in (lo, up)):
            continue  # nothing given, or the lower="0" upper="0" placeholder that restricts nothing anywhere
        given = ", ".join(f"{k}={_num(v)}" for k, v in (("lower", lo), ("upper", up)) if v is not None)
        yield Problem(
            f"continuous joint {_q(j.name)} gives position limits ({given}) that nobody applies: "
            f"robot_state_publisher, MoveIt, joint_state_publisher and Gazebo treat a continuous joint as "
            f"unlimited; use type=\"revolute\" if the range is real",
            at=j.limit)


@check("J006")
def zero_axis(model: Model, ctx: Context) -> Iterator[Problem]:
    for j in model.joint_list:
        if j.type not in AXIS_TYPES or j.axis_loc is None:
            continue
        if _norm(j.axis) > ZERO_AXIS:
            continue
        effect = ("KDL divides by its length, so robot_state_publisher publishes NaN transforms for "
                  f"{_q(j.child)} and everything below it; yourdfpy computes NaN, Pinocchio a joint that "
                  "does not move")
        yield Problem(f"joint {_q(j.name)} has the zero axis {_axis_text(j.axis)}: {effect}", at=j.axis_loc)


@check("J007")
def non_unit_axis(model: Model, ctx: Context) -> Iterator[Problem]:
    tol = float(ctx.options["tolerance"])  # typed and defaulted by the catalogue (rules/J007.yaml)
    for j in model.joint_list:
        if j.type not in AXIS_TYPES or j.axis_loc is None:
            continue
        norm = _norm(j.axis)
        if norm <= ZERO_AXIS or abs(norm - 1.0) <= tol:
            continue  # zero is J006
        unit = " ".join(f"{v / norm:.9g}" for v in j.axis)
        if j.type == "prismatic":
            effect = (f"KDL, MoveIt and Pinocchio normalise it, but yourdfpy moves the child along the axis as "
                      f"written, {_length_text(norm)} times as far")
        else:
            effect = ("KDL, MoveIt, Pinocchio and yourdfpy normalise it, but code that uses the vector as written "
                      "(hand-written kinematics, exporters) gets scaled velocities")
        yield Problem(
            f"axis {_axis_text(j.axis)} of joint {_q(j.name)} has length {_length_text(norm)}, not 1: {effect}. "
            f"Write {unit}",
            at=j.axis_loc)


@check("J008")
def invalid_mimic(model: Model, ctx: Context) -> Iterator[Problem]:
    for j in model.joint_list:
        mi = j.mimic
        if mi is None or j.type not in JOINT_TYPES:  # an unknown type is J001
            continue
        target = model.joints.get(mi.joint)
        if j.type == "fixed":
            # harmless: jsp skips fixed joints before reading <mimic>, RSP publishes them statically, MoveIt
            # pairs two 0-DOF joints, Pinocchio builds the model (checked with the RSP test mimic_joint.urdf)
            yield Problem(
                f"fixed joint {_q(j.name)} has a <mimic>, which every consumer ignores (a fixed joint has no "
                f"position to set); remove it or make the joint movable",
                at=mi, severity=Severity.INFO)
        elif mi.joint == j.name:
            yield Problem(
                f"joint {_q(j.name)} mimics itself: nothing drives it; joint_state_publisher exits ('Found an "
                f"infinite recursive mimic chain') and MoveIt drops every mimic relation of the model",
                at=mi)
        elif target is None:
            close = closest(mi.joint, sorted(model.joints))
            hint = f" (did you mean {close!r}?)" if close else ""
            yield Problem(
                f"joint {_q(j.name)} mimics {_q(mi.joint)}, which is not a joint of this model{hint}: "
                f"joint_state_publisher fails on it (KeyError) and MoveIt ignores the mimic ('cannot mimic "
                f"unknown joint')",
                at=mi)
        elif target.type in JOINT_TYPES and target.type not in MOVABLE_TYPES and j.type in MOVABLE_TYPES:
            yield Problem(
                f"joint {_q(j.name)} mimics {_q(target.name)}, a {target.type} joint without a single position to "
                f"follow: joint_state_publisher fails on it (KeyError, it skips {target.type} joints) and MoveIt "
                f"ignores the mimic ('different number of DOF')",
                at=mi, related=(target,))
        elif j.type not in MOVABLE_TYPES and target.type in JOINT_TYPES and target.type != j.type:
            yield Problem(
                f"{j.type} joint {_q(j.name)} mimics {target.type} joint {_q(target.name)}: only revolute, "
                f"continuous and prismatic joints can follow another joint's position; MoveIt ignores the mimic "
                f"('different number of DOF')",
                at=mi, related=(target,))


@check("J009")
def mimic_cycle(model: Model, ctx: Context) -> Iterator[Problem]:
    follows = {}
    for name, j in model.joints.items():
        if (j.mimic is not None and j.type != "fixed" and j.mimic.joint != name
                and j.mimic.joint in model.joints):
            follows[name] = j.mimic.joint  # self-mimic is J008; a fixed joint's mimic is ignored by everyone
    order = {name: i for i, name in enumerate(model.joints)}
    done: set[str] = set()
    for start in model.joints:
        if start in done or start not in follows:
            continue
        path: list = []
        where: dict = {}
        cur = start
        while cur in follows and cur not in done and cur not in where:
            where[cur] = len(path)
            path.append(cur)
            cur = follows[cur]
        if cur in where:  # closed a new cycle
            loop = path[where[cur]:]
            first = min(loop, key=order.__getitem__)
            k = loop.index(first)
            loop = loop[k:] + loop[:k]
            text = " -> ".join(_q(n) for n in loop + [loop[0]])
            yield Problem(
                f"mimic cycle {text}: no joint in it is driven. joint_state_publisher exits ('Found an infinite "
                f"recursive mimic chain') and MoveIt drops every mimic relation of the model ('Cycle found in "
                f"joint that mimic each other')",
                at=model.joints[first].mimic, related=tuple(model.joints[n].mimic for n in loop[1:]))
        done.update(path)


@check("J010")
def floating_joint(model: Model, ctx: Context) -> Iterator[Problem]:
    for j in model.joint_list:
        if j.type == "floating":
            yield Problem(
                f"joint {_q(j.name)} is floating: robot_state_publisher skips it ('Floating joint. Not adding "
                f"segment'), so the transform {_q(j.parent)} -> {_q(j.child)} must come from another publisher "
                f"(localization, motion capture, a simulator)",
                at=j)


@check("J011")
def planar_joint(model: Model, ctx: Context) -> Iterator[Problem]:
    for j in model.joint_list:
        if j.type != "planar":
            continue
        plane = ""
        x, y, z = j.axis
        if j.axis_loc is not None and not (abs(x) <= 1e-9 and abs(y) <= 1e-9 and abs(z) > 1e-9):
            asks = "defines no plane" if max(map(abs, j.axis)) <= 1e-9 else "asks for another plane"
            plane = (f"; its axis {_axis_text(j.axis)} {asks}, but MoveIt and Pinocchio always move it in the "
                     f"joint frame's XY plane (rotate the joint <origin> instead)")
        yield Problem(
            f"joint {_q(j.name)} is planar: KDL turns it into a fixed joint, so robot_state_publisher publishes "
            f"{_q(j.child)} once on /tf_static at the zero pose and joint_state_publisher offers no position "
            f"for it, while MoveIt and Pinocchio treat it as three degrees of freedom{plane}",
            at=j)
