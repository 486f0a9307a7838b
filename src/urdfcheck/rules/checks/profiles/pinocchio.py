"""Pinocchio's URDF parser (stack-of-tasks/pinocchio include/pinocchio/parsers/urdf/model.hxx, model.cxx).

Pinocchio reads the URDF through urdfdom (a model urdfdom refuses is refused: those general findings carry the
profile, common.ANNOTATES), then builds each joint with its limits: a negative effort or velocity makes the
lower bound greater than the upper one, and the model is refused ("Some components of min_effort are greater
than max_effort"; the same for velocity). Verified with pin 4.1 (`urdfcheck consumers --consumer pinocchio`)."""
from __future__ import annotations

from urdfcheck.core.records import TYPE_CHECKING
from urdfcheck.rules.catalogue import check
from urdfcheck.rules.checks.profiles.common import speak

if TYPE_CHECKING:  # the checks' argument types (no import at run time)
    from collections.abc import Iterator

    from urdfcheck.core.findings import Problem
    from urdfcheck.model.robot import Model
    from urdfcheck.rules.engine import Context


@check("P040")
def negative_effort_or_velocity(model: Model, ctx: Context) -> Iterator[Problem]:
    for j in model.joint_list:
        lim = j.limit
        if lim is None or j.type == "fixed":
            continue
        for field, value in (("effort", lim.effort), ("velocity", lim.velocity)):
            if value is not None and value < 0:
                p = speak(ctx, ("pinocchio",),
                          f"Pinocchio refuses the model: joint '{j.name}' has {field}=\"{value:g}\", so its "
                          f"min_{field} (-{field}) is greater than its max_{field}: \"Some components of min_{field} "
                          f"are greater than max_{field}\"", lim, quiet=True)  # J004 warns for every consumer
                if p is not None:
                    yield p
