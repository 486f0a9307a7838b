"""KDL: kdl_parser (ros/kdl_parser kdl_parser/src/kdl_parser.cpp), used by robot_state_publisher and KDL solvers.

toKdl(joint): FLOATING and PLANAR (and any other type) fall to the default branch, "Converting unknown joint type
of joint '%s' into a fixed joint": the tree has no degree of freedom there. treeFromUrdfModel: a root link with
inertia gets "The root link %s has an inertia specified in the URDF, but KDL does not support a root link with an
inertia" (I005)."""
from __future__ import annotations

from urdfcheck.core.records import TYPE_CHECKING
from urdfcheck.rules.catalogue import check
from urdfcheck.rules.checks.profiles.common import speak

if TYPE_CHECKING:  # the checks' argument types (no import at run time)
    from collections.abc import Iterator

    from urdfcheck.core.findings import Problem
    from urdfcheck.model.robot import Model
    from urdfcheck.rules.engine import Context


@check("P030")
def floating_or_planar_fixed(model: Model, ctx: Context) -> Iterator[Problem]:
    for j in model.joint_list:
        if j.type == "floating":
            # PyBullet too (UrdfParser.cpp parseJoint, "joint unsupported, creating a fixed joint instead";
            # measured: getJointInfo type JOINT_FIXED); a planar joint it keeps (JOINT_PLANAR)
            p = speak(ctx, ("kdl", "pybullet"),
                      f"KDL and PyBullet make floating joint '{j.name}' a fixed joint (kdl_parser: \"Converting "
                      f"unknown joint type of joint '{j.name}' into a fixed joint\"; Bullet's UrdfParser: \"joint "
                      "unsupported, creating a fixed joint instead\"): no degree of freedom there", j, quiet=True)
        elif j.type == "planar":
            p = speak(ctx, ("kdl",),
                      f"KDL makes planar joint '{j.name}' a fixed joint (kdl_parser: \"Converting unknown joint "
                      f"type of joint '{j.name}' into a fixed joint\"): KDL solvers see no degree of freedom there",
                      j, quiet=True)  # J010/J011 report it for robot_state_publisher
        else:
            continue
        if p is not None:
            yield p
