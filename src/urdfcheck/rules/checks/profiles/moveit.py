"""MoveIt: moveit_core's RobotModel (moveit/moveit2 moveit_core/robot_model/src/robot_model.cpp).

RobotModel::buildJointModel -> getVariableBoundsFromURDF: a joint with <safety_controller> gets its position
bounds narrowed to soft_lower_limit/soft_upper_limit (max/min with lower/upper), so planning never reaches the
range between the soft and the hard limits; a velocity limit of 0 becomes "no velocity bound"
(velocity_bounded_ = false when the URDF value is 0)."""
from __future__ import annotations

from urdfcheck.core.records import TYPE_CHECKING
from urdfcheck.rules.catalogue import check
from urdfcheck.rules.checks.profiles.common import speak

if TYPE_CHECKING:  # the checks' argument types (no import at run time)
    from collections.abc import Iterator

    from urdfcheck.core.findings import Problem
    from urdfcheck.model.robot import Model
    from urdfcheck.rules.engine import Context


def _number(text):
    try:
        return float(text)
    except (TypeError, ValueError):
        return None


@check("P060")
def soft_limits_narrow_bounds(model: Model, ctx: Context) -> Iterator[Problem]:
    if "moveit" not in ctx.profiles:
        return
    for j in model.joints.values():  # urdfdom keeps the first joint of a name
        if j.safety is None or j.limit is None or j.type not in ("revolute", "prismatic"):
            continue
        lo, hi = _number(j.safety[0]), _number(j.safety[1])
        narrowed = []
        if lo is not None and j.limit.lower is not None and lo > j.limit.lower:
            narrowed.append(f"lower {j.limit.lower:g} -> {lo:g}")
        if hi is not None and j.limit.upper is not None and hi < j.limit.upper:
            narrowed.append(f"upper {j.limit.upper:g} -> {hi:g}")
        if narrowed:
            yield speak(ctx, ("moveit",),
                        f"MoveIt plans joint '{j.name}' within its <safety_controller> soft limits, not <limit> ("
                        + ", ".join(narrowed) + "; robot_model.cpp getVariableBoundsFromURDF)", j.limit)
