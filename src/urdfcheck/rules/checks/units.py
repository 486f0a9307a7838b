"""U011: angles written in degrees where URDF reads radians (issue 41). Only values no one writes in radians:
an rpy component or a revolute limit of exactly 90, 180, 270 or 360 (either sign)."""
from __future__ import annotations

import math

from urdfcheck.core.findings import Problem
from urdfcheck.core.records import TYPE_CHECKING
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


# --- U012 ------------------------------------------------------------------------------------------
MM_LOW, MM_HIGH = 250.0, 4000.0  # 1000x, within a factor of 4 either way
METRE_LOW, METRE_HIGH = 0.25, 4.0  # a reference this close says the mesh is in metres already
MM_FLOOR = 5.0  # a mesh under 5 "metres" across as written is never called millimetres


def _primitive_diagonal(g) -> float | None:
    """The diagonal of the box that holds a primitive."""
    try:
        if g.kind == "box" and g.size and min(g.size) > 0:
            return math.sqrt(sum(float(x) ** 2 for x in g.size))
        if g.kind in ("cylinder", "capsule") and g.radius and g.length and g.radius > 0 and g.length > 0:
            h = float(g.length) + (2 * float(g.radius) if g.kind == "capsule" else 0.0)
            return math.sqrt(8 * float(g.radius) ** 2 + h * h)
        if g.kind == "sphere" and g.radius and g.radius > 0:
            return 2 * float(g.radius) * math.sqrt(3)
    except (TypeError, ValueError, OverflowError):
        return None
    return None


def _inertia_diagonal(inertial) -> float | None:
    """The diagonal of the solid box of the link's mass and inertia: a box a x b x c has ixx + iyy + izz =
    m (a² + b² + c²) / 6."""
    if inertial is None or not inertial.mass or inertial.mass <= 0 or inertial.inertia is None:
        return None
    ixx, _, _, iyy, _, izz = inertial.inertia
    if ixx == iyy == izz:
        return None  # equal moments: a placeholder far more often than a solid cube or sphere, no size to trust
    trace = ixx + iyy + izz
    if not (math.isfinite(trace) and trace > 0 and math.isfinite(inertial.mass)):
        return None
    return math.sqrt(6 * trace / inertial.mass)


def _mesh_diagonal(mesh, scale=None) -> float:
    lo, hi = mesh.bounds()
    s = scale or (1.0, 1.0, 1.0)
    return math.sqrt(sum(((hi[k] - lo[k]) * abs(s[k])) ** 2 for k in range(3)))


def _unscaled(g) -> bool:
    """A <mesh> with no scale (the model reads it as 1 1 1) or scale="1 1 1"."""
    return g is not None and g.kind == "mesh" and (g.scale is None or tuple(g.scale) == (1.0, 1.0, 1.0))


@check("U012")
def mesh_in_millimetres(model: Model, ctx: Context) -> Iterator[Problem]:
    """A mesh without `scale` about 1000x the size its link's other geometry or inertia gives it."""
    if not any(_unscaled(s.geometry) for link in model.link_list for s in (*link.visuals, *link.collisions)):
        return
    from urdfcheck.rules.meshes import reader

    read = reader(model, ctx)
    for link in model.link_list:
        shapes = (*link.visuals, *link.collisions)
        unscaled = [s for s in shapes if _unscaled(s.geometry)]
        if not unscaled:
            continue
        refs = []  # (diagonal in metres, what gives it)
        for s in shapes:
            g = s.geometry
            d = _primitive_diagonal(g) if g is not None else None
            if d is None and g is not None and g.kind == "mesh" and not _unscaled(g):
                m = read(g)
                d = _mesh_diagonal(m, g.scale) if m is not None else None
                what = f"the scaled mesh of its {s.kind}"
            else:
                what = f"its {s.kind} {g.kind}" if g is not None else ""
            if d:
                refs.append((d, what))
        d = _inertia_diagonal(link.inertial)
        if d:
            refs.append((d, "its inertia"))
        if not refs:
            continue
        for s in unscaled:
            mesh = read(s.geometry)
            if mesh is None:
                continue
            lo, hi = mesh.bounds()
            size = [hi[k] - lo[k] for k in range(3)]
            diag = math.sqrt(sum(x * x for x in size))
            if max(size) < MM_FLOOR:
                continue
            ratios = [(diag / r, what, r) for r, what in refs]
            if any(METRE_LOW <= q <= METRE_HIGH for q, _, _ in ratios):
                continue
            hit = next(((q, what, r) for q, what, r in ratios if MM_LOW <= q <= MM_HIGH), None)
            if hit is None:
                continue
            q, what, r = hit
            shown = " x ".join(f"{x:.4g}" for x in size)
            filename = s.geometry.filename  # type: ignore[union-attr]  # an unscaled mesh (_unscaled)
            yield Problem(f"mesh {filename!r} of the {s.kind} of link {link.name!r} is {shown} m as "
                          f"written ({q:.0f}x the {r:.3g} m that {what} gives the link) and has no scale: the file "
                          f"is in millimetres and URDF reads metres; add scale=\"0.001 0.001 0.001\"",
                          at=s.geometry, data={"ratio": round(q, 1), "size": [round(x, 6) for x in size]})
