"""MuJoCo's URDF compiler (google-deepmind/mujoco src/xml/xml_urdf.cc, src/user/user_objects.cc, user_model.cc).

What it does with a URDF, verified by loading models with each defect into mujoco 4.0 (`urdfcheck consumers`):
fixed joints make no joint, and the compiler's default `fusestatic` for URDF fuses such a child into its parent
body; the root is welded to the world; a link without <inertial> gets its mass from its collision geometry
(density 1000, visual geometry has none); an <inertial> whose six moments are all zero is "undefined" and read as
zero; after fusing, a body that moves must have mass and every principal moment >= mjMINVAL (1e-15): "mass and
inertia of moving bodies must be larger than mjMINVAL". An explicit tensor that is not positive definite or
breaks the triangle inequality is refused on any link. <mimic> becomes an equality constraint.
"""
from __future__ import annotations

import math

from urdfcheck.core.findings import Problem
from urdfcheck.core.records import TYPE_CHECKING
from urdfcheck.rules.catalogue import check
from urdfcheck.rules.checks.profiles.common import dynamic, fixed_groups, is_tree, names, speak

if TYPE_CHECKING:  # the checks' argument types (no import at run time)
    from collections.abc import Iterator

    from urdfcheck.model.robot import Model
    from urdfcheck.rules.engine import Context

MJMINVAL = 1e-15
DENSITY = 1000.0  # mjsGeom default density: collision geometry of a link without <inertial> gets mass from it


def _geom_mass(g) -> tuple[float, float] | None:
    """(mass, smallest principal moment) of one collision geometry at MuJoCo's default density; None when it
    cannot be known here (a mesh: its volume is in the file)."""
    if g is None:
        return (0.0, 0.0)
    k = g.kind
    if k == "box" and g.size:
        a, b, c = (abs(x) for x in g.size)
        m = DENSITY * a * b * c
        return m, m / 12.0 * min(b * b + c * c, a * a + c * c, a * a + b * b)
    if k == "sphere" and g.radius is not None:
        r = abs(g.radius)
        m = DENSITY * 4.0 / 3.0 * math.pi * r ** 3
        return m, 0.4 * m * r * r
    if k in ("cylinder", "capsule") and g.radius is not None and g.length is not None:
        r, h = abs(g.radius), abs(g.length)
        m = DENSITY * math.pi * r * r * h + (DENSITY * 4.0 / 3.0 * math.pi * r ** 3 if k == "capsule" else 0.0)
        return m, min(m * r * r / 2.0, m * (3 * r * r + h * h) / 12.0)
    return None


def _part(link) -> tuple[float, float] | None:
    """(mass, smallest principal moment) a link adds to its body; None: unknown (a mesh decides)."""
    from urdfcheck.rules.checks.inertial import principal_moments

    inr = link.inertial
    if inr is not None:
        mass = inr.mass if inr.mass is not None and math.isfinite(inr.mass) else 0.0
        if inr.inertia is None or not all(math.isfinite(v) for v in inr.inertia):
            return None
        low = principal_moments(tuple(inr.inertia))[0]
        return max(mass, 0.0), low
    got = [_geom_mass(shape.geometry) for shape in link.collisions]
    if any(g is None for g in got):
        return None
    mass = sum(g[0] for g in got)  # type: ignore[index, misc]  # no None in got (tested above)
    if len(got) == 1:
        return got[0]
    return mass, mass  # several shapes: apart, they add moments (parallel axes); one alone decides otherwise


def _surely_massive(link) -> bool:
    """Mass and every principal moment >= mjMINVAL, told by Gershgorin's bound on the smallest eigenvalue: no
    eigenvalues computed for the links of a real robot (NaN or inf fail the bound and take the exact path)."""
    inr = link.inertial
    if inr is None or inr.inertia is None or inr.mass is None or not inr.mass >= MJMINVAL:
        return False
    xx, xy, xz, yy, yz, zz = inr.inertia
    return min(xx - abs(xy) - abs(xz), yy - abs(xy) - abs(yz), zz - abs(xz) - abs(yz)) >= MJMINVAL


def moving_bodies(model) -> dict[str, list[str]]:
    """MuJoCo body (the link whose parent joint moves) -> the links fused into it. Links fused into a root are
    welded to the world and never checked."""
    group = fixed_groups(model)
    out: dict[str, list[str]] = {}
    parent_joint = model.parent_joint.get
    for link, body in group.items():
        j = parent_joint(body)
        if j is None:
            continue
        if j.type == "fixed":
            continue
        out.setdefault(body, []).append(link)
    return out


@check("P001")
def massless_moving_body(model: Model, ctx: Context) -> Iterator[Problem]:
    if not is_tree(model):
        return  # S001/S002: no single tree to reason about
    kinematic = not dynamic(model)
    known = model.links
    for body, links in moving_bodies(model).items():
        if any(n in known and _surely_massive(known[n]) for n in links):
            continue  # one such link gives the body mass and inertia enough
        parts = [(n, _part(model.links[n])) for n in links if n in model.links]
        if any(p is None for _, p in parts):
            continue  # a mesh's volume decides: the consumers command measures it
        # (type: ignore below) no None in parts (tested above)
        massive = [(n, p) for n, p in parts if p[0] >= MJMINVAL]  # type: ignore[index]
        mass = sum(p[0] for _, p in massive)  # type: ignore[index, misc]  # no None in parts (tested above)
        # (type: ignore below) no None in parts (tested above)
        if mass >= MJMINVAL and (len(massive) > 1 or massive[0][1][1] >= MJMINVAL):  # type: ignore[index]
            continue
        explicit = any(model.links[n].inertial is not None for n in links)
        what = (f"mass {mass:.3g} kg" if mass < MJMINVAL else
                # (type: ignore below) no None in parts (tested above)
                f"smallest principal moment {massive[0][1][1]:.3g} kg·m²")  # type: ignore[index]
        fused = f" (with fused links {names([n for n in links if n != body])})" if len(links) > 1 else ""
        source = ("from its <inertial>" if explicit else
                  "from its collision geometry (no <inertial>; density 1000)" if any(
                      model.links[n].collisions for n in links) else "(no <inertial>, no collision geometry)")
        gazebo = ("" if "mujoco" in ctx.profiles or any(model.links[n].collisions for n in links) else
                  "; Gazebo drops such a link with everything below it (P011)")
        p = speak(ctx, ("mujoco",),
                  f"MuJoCo refuses the model: link '{body}'{fused} moves (joint "
                  f"'{model.parent_joint[body].name}') but gets {what} {source}: \"mass and inertia of moving "
                  f"bodies must be larger than mjMINVAL\" (1e-15){gazebo}",
                  model.links[body].inertial or model.links[body], quiet=explicit or kinematic)
        if p is not None:
            yield p


@check("P002")
def inertia_refused(model: Model, ctx: Context) -> Iterator[Problem]:
    """An explicit tensor MuJoCo refuses on any link (fixed or root too): not positive definite ("inertia must
    have positive eigenvalues"), or breaking A + B >= C. All six zero is "undefined" and accepted."""
    from urdfcheck.rules.checks.inertial import principal_moments

    if "mujoco" not in ctx.profiles:
        return  # I003/I004 report the same tensors for every consumer
    for link in model.link_list:
        inr = link.inertial
        if inr is None or inr.inertia is None or not all(math.isfinite(v) for v in inr.inertia):
            continue
        if all(v == 0 for v in inr.inertia):
            continue
        a, b, c = principal_moments(tuple(inr.inertia))
        if a <= 0:
            why = "\"inertia must have positive eigenvalues\" (fullinertia)"
        elif a + b < c - MJMINVAL:
            why = "\"inertia must satisfy A + B >= C; use 'balanceinertia' to fix\""
        else:
            continue
        yield Problem(f"MuJoCo refuses the model: the inertia of link '{link.name}' (principal moments "
                      f"{a:.6g}, {b:.6g}, {c:.6g}): {why}", at=inr.inertia_loc or inr, data={"profile": "mujoco"})


_SHAPES = ("box", "cylinder", "sphere", "capsule", "mesh")


@check("P005")
def collision_geometry_refused(model: Model, ctx: Context) -> Iterator[Problem]:
    """xml_urdf.cc mjXURDF::Geom: a <collision> without <geometry> ("missing element: 'geometry'") or with a shape
    other than box, cylinder, sphere, capsule and mesh ("visual geometry specification not found") is refused.
    Visual elements are discarded first (discardvisual, the URDF default), so theirs do not matter."""
    if "mujoco" not in ctx.profiles:
        return  # G005 reports empty and unknown geometry for every consumer
    for link in model.link_list:
        for shape in link.collisions:
            g = shape.geometry
            if g is None or g.kind not in _SHAPES:
                what = "no <geometry>" if g is None or not g.kind else f"a <{g.kind}> shape"
                yield Problem(f"MuJoCo refuses the model: a <collision> of link '{link.name}' has {what} "
                              "(xml_urdf.cc: only box, cylinder, sphere, capsule and mesh are read)",
                              at=g if g is not None else shape, data={"profile": "mujoco"})


# the sub-elements xml_urdf.cc looks up with FindSubElem (xml_util.cc), which throws "repeated element" when one is
# written twice; urdfdom reads the first and carries on
_ONCE = {
    "joint": ("parent", "child", "axis", "dynamics", "limit", "origin"),
    "inertial": ("mass", "inertia", "origin"),
    "collision": ("geometry", "origin"),
    "visual": ("material",),  # read before visuals are discarded
    "geometry": ("box", "cylinder", "sphere", "capsule", "mesh"),
}


# the scopes whose sub-elements MuJoCo reads (the builder notes repeats in visual geometry too, which it drops)
_SCOPES = ("joint", "link", "link/inertial", "link/collision", "link/visual", "link/collision/geometry")


@check("P006")
def repeated_element(model: Model, ctx: Context) -> Iterator[Problem]:
    # the builder noted every repeat while reading (model.repeated): a second walk over the XML cost 0.15 s on
    # 10,000 links, for a finding almost no model has
    parts = {"joint": model.joints, "link": model.links}
    for kind, owner, path, tags in model.repeated:
        scope = path.rsplit("/", 1)[-1]
        once = _ONCE.get(scope, ("inertial",) if scope == "link" else ())
        twice = [t for t in tags if t in once]
        part = parts[kind].get(owner)
        if path not in _SCOPES or not twice or part is None:
            continue
        name = part.name  # type: ignore[attr-defined]  # a link or a joint (parts[kind] maps names to them)
        p = speak(ctx, ("mujoco",),
                  f"MuJoCo refuses the model: <{scope}> of {kind} '{name}' has more than one "
                  f"<{twice[0]}> (xml_util.cc FindSubElem: \"repeated element: '{twice[0]}'\"); urdfdom "
                  "reads the first one only", part)
        if p is not None:
            yield p


@check("P003")
def mimic_becomes_equality(model: Model, ctx: Context) -> Iterator[Problem]:
    if "mujoco" not in ctx.profiles:
        return
    for j in model.joint_list:
        if j.mimic is None:
            continue
        if j.type in ("revolute", "continuous", "prismatic"):
            yield Problem(f"MuJoCo turns <mimic> of joint '{j.name}' into an equality constraint (joint "
                          f"'{j.name}' = {j.mimic.multiplier:g} x '{j.mimic.joint}' + {j.mimic.offset:g}), "
                          "solved softly with the other constraints, not an exact copy of the position",
                          at=j.mimic, data={"profile": "mujoco"})
        else:
            yield Problem(f"MuJoCo ignores <mimic> on {j.type} joint '{j.name}' (\"mimic requires revolute, "
                          "continuous, or prismatic joints\")", at=j.mimic, data={"profile": "mujoco"})


@check("P004")
def fused_links(model: Model, ctx: Context) -> Iterator[Problem]:
    if "mujoco" not in ctx.profiles or len(model.roots) != 1:
        return
    group = fixed_groups(model)
    fused = [n for n, g in group.items() if n != g]
    if fused:
        root = model.roots[0]
        world = [n for n in fused if group[n] == root]
        yield Problem(f"MuJoCo fuses {len(fused)} link(s) attached by fixed joints into their parent bodies "
                      f"(compiler fusestatic, the URDF default): {names(fused)} are no bodies of their own (no "
                      f"xpos/xquat to read, no contact exclusion by name)"
                      + (f"; {names(world)} and the root '{root}' are welded to the world" if world else
                         f"; the root '{root}' is welded to the world (no free joint)"),
                      at=model, data={"profile": "mujoco"})


@check("P007")
def joint_refused(model: Model, ctx: Context) -> Iterator[Problem]:
    """Joints MuJoCo's compiler refuses (measured with mujoco 4.0): a floating joint whose parent is not welded to
    the world becomes a free joint below a moving body ("free joint can only be used on top level"); a <mimic>
    naming its own joint makes an equality constraint on one joint twice ("element 'X' is repeated in equality
    constraint")."""
    if not is_tree(model):
        return
    group = fixed_groups(model)
    top = set(model.roots) | {"world"}
    for j in model.joint_list:
        # (type: ignore below) a floating joint has a parent
        if j.type == "floating" and group.get(j.parent, j.parent) not in top:  # type: ignore[arg-type, operator]
            p = speak(ctx, ("mujoco",),
                      f"MuJoCo refuses the model: floating joint '{j.name}' hangs below a moving body, and MuJoCo "
                      "makes it a free joint: \"free joint can only be used on top level\" (user_objects.cc); "
                      "attach the part to the root, or make it a model of its own", j, quiet=True)  # J010
            if p is not None:
                yield p
        if j.mimic is not None and j.mimic.joint == j.name and j.type in ("revolute", "continuous", "prismatic"):
            p = speak(ctx, ("mujoco",),
                      f"MuJoCo refuses the model: joint '{j.name}' mimics itself, and the equality constraint "
                      f"MuJoCo makes of it names the joint twice: \"element '{j.name}' is repeated in equality "
                      "constraint\" (user_objects.cc mjCEquality)", j.mimic, quiet=True)  # J008
            if p is not None:
                yield p


MESH_DECODERS = (".stl", ".obj", ".msh")  # mujoco 4.0 user_mesh.cc; anything else: "no decoder found for mesh file"


@check("P008")
def collision_mesh_refused(model: Model, ctx: Context) -> Iterator[Problem]:
    """A collision mesh MuJoCo cannot open (measured with mujoco 4.0): it opens the filename as a path, relative to
    the URDF's folder, with no package:// or file:// resolution ("Error opening file 'package:/...'"), and decodes
    only STL, OBJ and MSH ("no decoder found for mesh file"). Visual meshes are discarded first and never opened.
    Whether a plain path exists is said only inside the run's roots (the resolver's, as G001)."""
    from pathlib import Path

    from urdfcheck.rules.checks.geometry import _base_dir, _resolver

    if "mujoco" not in ctx.profiles:
        return  # most ROS robots name meshes by package://: only those who convert for MuJoCo need to hear it
    base = _base_dir(model, ctx)
    resolver = None
    seen: set[str] = set()
    for link in model.link_list:
        for shape in link.collisions:
            g = shape.geometry
            uri = (g.filename or "").strip() if g is not None and g.kind == "mesh" else ""
            if not uri or uri in seen:
                continue
            seen.add(uri)
            why = None
            if "://" in uri:
                why = (f"MuJoCo opens '{uri}' as a file path (no package:// or file:// resolution: \"Error opening "
                       "file\"); write the path relative to the URDF, or set <compiler meshdir> in a MuJoCo "
                       "<mujoco> block")
            elif Path(uri).suffix.lower() not in MESH_DECODERS:
                why = (f"MuJoCo has no decoder for '{Path(uri).suffix or uri}' meshes (\"no decoder found for mesh "
                       "file\"; it reads STL, OBJ and MSH): convert the collision mesh")
            else:
                resolver = resolver or _resolver(model, ctx)
                path = Path(uri) if Path(uri).is_absolute() else base / uri
                if resolver.allowed(path) and not path.is_file():
                    why = f"MuJoCo cannot open '{uri}' (no such file next to the URDF: \"Error opening file\")"
            if why:
                yield Problem(f"MuJoCo refuses the model: the collision mesh of link '{link.name}': {why}", at=g,
                              data={"profile": "mujoco", "profiles": ("mujoco",)})
