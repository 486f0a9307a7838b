"""U011: angles written in degrees where URDF reads radians (issue 41). Only values no one writes in radians:
an rpy component or a revolute limit of exactly 90, 180, 270 or 360 (either sign)."""
from __future__ import annotations

import math
from typing import TYPE_CHECKING

from urdfcheck.core.findings import Problem
from urdfcheck.rules.catalogue import check

if TYPE_CHECKING:  # the checks' argument types (no import at run time)
    from collections.abc import Iterator

    from urdfcheck.model.robot import Model
    from urdfcheck.rules.engine import Context

DEGREE_VALUES = (90.0, 180.0, 270.0, 360.0)


def _degrees(v) -> bool:
    return v is not None and abs(v) in DEGREE_VALUES


def _origins(model):
    for j in model.joint_list:
        yield f"joint {j.name!r}", j.origin
    for link in model.link_list:
        if link.inertial is not None:
            yield f"the inertial of link {link.name!r}", link.inertial.origin
        for s in (*link.visuals, *link.collisions):
            yield f"a {s.kind} of link {link.name!r}", s.origin


@check("U011")
def angle_in_degrees(model: Model, ctx: Context) -> Iterator[Problem]:
    for what, pose in _origins(model):
        if pose is None or pose.quat is not None or not any(_degrees(a) for a in pose.rpy):
            continue
        shown = " ".join(f"{a:g}" for a in pose.rpy)
        fixed = " ".join(f"{math.radians(a):.6g}" if _degrees(a) else f"{a:g}" for a in pose.rpy)
        yield Problem(f"the <origin rpy=\"{shown}\"> of {what} looks like degrees; rpy is in radians: "
                      f"rpy=\"{fixed}\"", at=pose.loc or model.loc)
    for j in model.joint_list:
        lim = j.limit
        if j.type != "revolute" or lim is None or not (_degrees(lim.lower) or _degrees(lim.upper)):
            continue
        vals = [f"{k}={v:g} ({math.radians(v):.6g} rad)"  # type: ignore[arg-type]  # _degrees(v): v is a number
                for k, v in (("lower", lim.lower), ("upper", lim.upper)) if _degrees(v)]
        yield Problem(f"revolute joint {j.name!r}: the <limit> {' and '.join(vals)} looks like degrees; URDF "
                      "limits are in radians", at=lim.loc, related=(j,))
