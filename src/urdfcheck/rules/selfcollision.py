"""G006: links whose collision geometry interpenetrates at the zero configuration (issue 41).

MoveIt refuses to plan from a start state in collision and Gazebo (with self_collide) pushes the links apart on
spawn. The shapes are tested with coal (hpp-fcl, the library Pinocchio and MoveIt's FCL successor use), imported
only here and only for pairs whose bounding boxes (a pure-Python separating-axis test) interpenetrate by more than
`depth`, so a model without such a pair never loads it: without coal installed the rule says nothing.

What is compared: boxes, cylinders, spheres, capsules and meshes, every link at the pose of
`Robot.world_poses` (all joints at zero, mimic offsets ignored); a pair with a joint between them whose limits
exclude zero is left out (that pose is never reached). Pairs MoveIt's setup assistant calls adjacent are
left out, as `collision_detection::AllowedCollisionMatrix` defaults do: links joined by a joint, and links held
together by fixed joints (they never move relative to each other; Gazebo lumps them into one body). So are pairs an
SRDF of the same robot (its `<robot name>`, in the model's package or a sibling `*moveit*` package) already
disables. Only penetration deeper than `depth` (5 mm by default) is reported: primitives that touch or overlap
by a rounding error are how links are drawn flush against each other.

Meshes: the file's vertices and triangles come from core.meshfile (through the door; coal never opens a file),
scaled by the <mesh> scale. Coal measures penetration depth only between convex shapes, so the depth is that of
the mesh's convex hull; and the pair is reported only when the mesh's triangles themselves (a BVH, what MoveIt's
FCL and Gazebo test) touch the other shape, so a concave part whose hull, not its surface, reaches a neighbour is
not. A mesh not read (missing, another format, too large) is left out, and so is a COLLADA mesh whose up axis is
not Z_UP (whether a loader turns it differs between assimp versions).
"""
from __future__ import annotations

import os
from collections.abc import Iterator

from urdfcheck.core import lazyre
from urdfcheck.core.findings import Problem, Severity

_SRDF_NAME = lazyre.compile(r"<robot\b[^>]*\bname\s*=\s*[\"']([^\"']+)[\"']")
_DISABLE = lazyre.compile(r"<disable_collisions\b([^>]*)/?>")
_ATTR = lazyre.compile(r"\b(link1|link2)\s*=\s*[\"']([^\"']*)[\"']")
_SUBST = lazyre.compile(r"\$\{[^}]*\}|\$\([^)]*\)")
_HUGE = 1000.0
_SRDF_FILES = 40  # at most this many SRDF files are read per model
_SRDF_BYTES = 2_000_000


def _coal():
    try:
        import coal  # noqa: PLC0415 (optional: pip install coal; pin brings it)
        import numpy  # noqa: PLC0415
    except ImportError:
        return None, None
    return coal, numpy


def _rigid_groups(model) -> dict[str, str]:
    """link -> the first link of the group it is welded to by fixed joints."""
    group = {name: name for name in model.links}

    def find(x):
        while group[x] != x:
            group[x] = group[group[x]]
            x = group[x]
        return x

    for j in model.joint_list:
        if j.type == "fixed" and j.parent in group and j.child in group:
            a, b = find(j.parent), find(j.child)
            if a != b:
                group[b] = a
    return {name: find(name) for name in model.links}


def _adjacent(model, groups) -> set[frozenset]:
    """Pairs of rigid groups joined by a (movable) joint."""
    out = set()
    for j in model.joint_list:
        if j.parent in groups and j.child in groups:
            out.add(frozenset((groups[j.parent], groups[j.child])))
    return out


def _shape(coal, g):
    try:
        if g.kind == "box" and g.size and min(g.size) > 0:
            return coal.Box(*map(float, g.size))
        if g.kind == "cylinder" and g.radius and g.length and g.radius > 0 and g.length > 0:
            return coal.Cylinder(float(g.radius), float(g.length))
        if g.kind == "sphere" and g.radius and g.radius > 0:
            return coal.Sphere(float(g.radius))
        if g.kind == "capsule" and g.radius and g.length and g.radius > 0 and g.length > 0:
            return coal.Capsule(float(g.radius), float(g.length))
    except (TypeError, ValueError, OverflowError):
        return None
    return None


def _unreachable(model, a: str, b: str, chains: dict) -> bool:
    """A joint between the two links whose limits exclude zero: the zero pose of the pair is never reached (the
    robot's home lies elsewhere, as Franka's joint 4 in [-3.07, -0.07])."""
    for x in (a, b):
        if x not in chains:
            chains[x] = {j.name for j in model.chain_to_root(x)}
    for name in chains[a] ^ chains[b]:
        lim = model.joints[name].limit
        if model.joints[name].type in ("revolute", "prismatic") and lim is not None:
            if (lim.lower is not None and lim.lower > 0) or (lim.upper is not None and lim.upper < 0):
                return True
    return False


def _finite(m) -> bool:
    return all(abs(x) < 1e6 for row in m for x in row)


def srdf_disabled(model, entry: str) -> tuple[set[frozenset], str | None]:
    """(disabled link pairs, the SRDF file) of an SRDF of the same robot near the model; (set(), None) when none.
    A tiny reader on purpose: only `<robot name>` and `<disable_collisions link1 link2>` (a `${prefix}` in a name
    is dropped, as with the default empty prefix)."""
    from pathlib import Path

    from urdfcheck.core import door
    from urdfcheck.load.packages import enclosing_package

    pkg = enclosing_package(Path(entry).resolve()) if entry else None
    if pkg is None:
        return set(), None
    folders = [pkg]
    try:
        folders += [pkg.parent / d for d in sorted(os.listdir(pkg.parent))
                    if "moveit" in d.lower() and (pkg.parent / d).is_dir() and pkg.parent / d != pkg]
    except OSError:
        pass
    found: list[str] = []
    for top in folders:
        base = str(top).count(os.sep)
        for dirpath, dirnames, filenames in os.walk(top):
            dirnames[:] = sorted(d for d in dirnames if not d.startswith("."))
            if dirpath.count(os.sep) - base >= 3:
                dirnames[:] = []
            found += [os.path.join(dirpath, f) for f in sorted(filenames) if f.endswith((".srdf", ".srdf.xacro"))]
            if len(found) >= _SRDF_FILES:
                break
    pairs: set[frozenset] = set()
    used = None
    for path in found[:_SRDF_FILES]:
        try:
            text = door.read_text(path, limit=_SRDF_BYTES)
        except OSError:
            continue
        m = _SRDF_NAME.search(text)
        if not m or _SUBST.sub("", m.group(1)) != model.name:
            continue
        used = used or path
        for d in _DISABLE.finditer(text):
            attrs = dict(_ATTR.findall(d.group(1)))
            if "link1" in attrs and "link2" in attrs:
                pairs.add(frozenset((_SUBST.sub("", attrs["link1"]), _SUBST.sub("", attrs["link2"]))))
    return pairs, used


def _half_extents(g) -> tuple[float, ...] | None:
    """Half sizes of the box that holds the primitive, in its own frame (cylinder and capsule along z); None for
    a shape of no size or of an absurd one (1 km: not a robot part, and no number coal should see)."""
    half = _raw_half_extents(g)
    if half is None or not all(0 < h < _HUGE for h in half):
        return None
    return half


def _raw_half_extents(g) -> tuple[float, ...] | None:
    try:
        if g.kind == "box" and g.size and min(g.size) > 0:
            return tuple(float(x) / 2 for x in g.size)
        if g.kind == "cylinder" and g.radius and g.length and g.radius > 0 and g.length > 0:
            return (float(g.radius), float(g.radius), float(g.length) / 2)
        if g.kind == "sphere" and g.radius and g.radius > 0:
            return (float(g.radius),) * 3
        if g.kind == "capsule" and g.radius and g.length and g.radius > 0 and g.length > 0:
            return (float(g.radius), float(g.radius), float(g.length) / 2 + float(g.radius))
    except (TypeError, ValueError, OverflowError):
        return None
    return None


def _mesh_box(g, read):
    """(half extents, centre of the bounds in the mesh frame, Mesh, scale) of a collision mesh read and scaled,
    or None (not read, or absurd after its scale)."""
    mesh = read(g)
    if mesh is None or mesh.up:
        return None  # a COLLADA mesh with another up axis: where its parts lie depends on the loader
    scale = tuple(float(x) for x in (g.scale or (1.0, 1.0, 1.0)))
    lo, hi = mesh.bounds()
    a = [lo[k] * scale[k] for k in range(3)]
    b = [hi[k] * scale[k] for k in range(3)]
    half = tuple(max(abs(b[k] - a[k]) / 2, 1e-6) for k in range(3))
    if not all(h < _HUGE for h in half):
        return None
    return half, tuple((a[k] + b[k]) / 2 for k in range(3)), mesh, scale


def _coal_mesh(coal, np, mesh, scale):
    """(convex hull, triangles as a BVH or None) of a mesh, from its vertices: coal never opens the file."""
    pts = mesh.points * np.array(scale, dtype=float)
    surface = None
    if len(mesh.triangles):
        surface = coal.BVHModelOBBRSS()
        surface.beginModel(len(mesh.triangles), len(pts))
        surface.addVertices(pts)
        surface.addTriangles(mesh.triangles)
        surface.endModel()
    unique = np.unique(pts, axis=0)  # an STL repeats each vertex once per triangle
    if len(unique) < 4:
        return None, surface
    spread = np.linalg.svd(unique - unique.mean(axis=0), compute_uv=False)
    if not spread[2] > 1e-6 * spread[0]:
        return None, surface  # flat or a line: coal's qhull call crashes the process on such a set
    cloud = coal.BVHModelOBBRSS()
    cloud.beginModel(0, len(unique))
    cloud.addVertices(unique)
    cloud.endModel()
    try:
        # its result says whether every point is a hull vertex (the mesh was convex), not whether it worked
        cloud.buildConvexHull(False, "Qt")
        hull = cloud.convex
    except Exception:  # noqa: BLE001 (qhull refuses flat or degenerate point sets: no hull, no test)
        hull = None
    return (hull if hull is not None and hull.num_points >= 4 else None), surface


def _surfaces_meet(coal, fa, ta, fb, tb) -> bool:
    """The triangles of a mesh touch the other shape (what MoveIt's FCL and Gazebo test); a mesh read without
    triangles is judged by its hull alone."""
    if fa is None or fb is None:
        return True
    return bool(coal.collide(fa, ta, fb, tb, coal.CollisionRequest(), coal.CollisionResult()))


def _obb_overlap(a, b) -> float:
    """How far two oriented boxes (centre, 3 unit axes, half extents) interpenetrate along the separating axes
    (the 15 of the separating axis theorem): 0 when apart. Each box holds its shape, so the shapes
    interpenetrate by no more than this: below `depth`, coal is not needed (nor imported)."""
    (ca, ua, ea), (cb, ub, eb) = a, b
    d = [cb[i] - ca[i] for i in range(3)]
    axes = list(ua) + list(ub)
    for x in ua:
        for y in ub:
            c = (x[1] * y[2] - x[2] * y[1], x[2] * y[0] - x[0] * y[2], x[0] * y[1] - x[1] * y[0])
            n = (c[0] ** 2 + c[1] ** 2 + c[2] ** 2) ** 0.5
            if n > 1e-9:
                axes.append((c[0] / n, c[1] / n, c[2] / n))
    least = float("inf")
    for ax in axes:
        ra = sum(ea[k] * abs(sum(ua[k][i] * ax[i] for i in range(3))) for k in range(3))
        rb = sum(eb[k] * abs(sum(ub[k][i] * ax[i] for i in range(3))) for k in range(3))
        gap = ra + rb - abs(sum(d[i] * ax[i] for i in range(3)))
        if gap <= 0:
            return 0.0
        least = min(least, gap)
    return least


def self_collisions(model, entry: str, depth: float, read=None) -> Iterator[Problem]:
    """`read(geometry) -> core.meshfile.Mesh | None` reads collision meshes (rules.meshes.reader); without it
    meshes are left out."""
    from urdfcheck.core.geometry import compose, origin_matrix

    poses = model.world_poses()
    boxes = []  # (link, Shape, 4x4 pose, oriented box)
    meshes: dict[int, tuple] = {}  # id(Shape) -> (Mesh, scale) of a collision mesh read
    for link in model.link_list:
        if link.name not in poses:
            continue
        for s in link.collisions:
            g = s.geometry
            offset = (0.0, 0.0, 0.0)
            if g is not None and g.kind == "mesh":
                got = _mesh_box(g, read) if read is not None else None
                if got is None:
                    continue
                half, offset, mesh, scale = got
                meshes[id(s)] = (mesh, scale)
            else:
                half = _half_extents(g) if g is not None else None
            if half is None:
                continue
            m = compose(poses[link.name], origin_matrix(s.origin))
            if not _finite(m):
                continue
            # the box that holds a mesh is centred on its vertices' bounds, not on the mesh's origin
            centre = tuple(m[i][3] + sum(m[i][k] * offset[k] for k in range(3)) for i in range(3))
            axes = tuple((m[0][k], m[1][k], m[2][k]) for k in range(3))
            boxes.append((link, s, m, (centre, axes, half)))
    if len({link.name for link, *_ in boxes}) < 2:
        return
    groups = _rigid_groups(model)
    adjacent = _adjacent(model, groups)
    chains: dict[str, set] = {}
    candidates = []
    # sweep along x over bounding spheres: a model of thousands of shapes spread out compares only neighbours
    reach = [sum(h * h for h in ob[2]) ** 0.5 for *_, ob in boxes]
    order = sorted(range(len(boxes)), key=lambda k: boxes[k][3][0][0] - reach[k])
    active: list[int] = []
    for k in order:
        lo = boxes[k][3][0][0] - reach[k]
        active = [i for i in active if boxes[i][3][0][0] + reach[i] >= lo]
        near = list(active)
        active.append(k)
        for i in near:
            a, b = min(i, k), max(i, k)  # document order: the finding is at the later shape
            la, sa, ma, oa = boxes[a]
            lb, sb, mb, ob = boxes[b]
            ca, cb = oa[0], ob[0]
            if sum((ca[n] - cb[n]) ** 2 for n in range(3)) > (reach[a] + reach[b]) ** 2:
                continue
            if la.name == lb.name or groups[la.name] == groups[lb.name]:
                continue
            if frozenset((groups[la.name], groups[lb.name])) in adjacent:
                continue
            if _obb_overlap(oa, ob) <= depth or _unreachable(model, la.name, lb.name, chains):
                continue
            candidates.append((la, sa, ma, lb, sb, mb))
    if not candidates:
        return
    coal, np = _coal()
    if coal is None:
        return
    req = coal.CollisionRequest(coal.CollisionRequestFlag.CONTACT, 1)

    built: dict[int, tuple] = {}

    def placed(s, m):
        """(shape for the depth, shape whose contact decides, transform): a primitive twice; a mesh's convex
        hull (coal's penetration depth needs a convex shape), and its triangles (a BVH) when it has them."""
        if id(s) in meshes:
            if id(s) not in built:
                built[id(s)] = _coal_mesh(coal, np, *meshes[id(s)])
            hull, surface = built[id(s)]
        else:
            hull = surface = _shape(coal, s.geometry)
        rot = np.array([row[:3] for row in m[:3]], dtype=float)
        return hull, surface, coal.Transform3s(rot, np.array([m[0][3], m[1][3], m[2][3]], dtype=float))

    hits: dict[frozenset, tuple] = {}
    for la, sa, ma, lb, sb, mb in candidates:
        ga, fa, ta = placed(sa, ma)
        gb, fb, tb = placed(sb, mb)
        if ga is None or gb is None:
            continue
        res = coal.CollisionResult()
        if not coal.collide(ga, ta, gb, tb, req, res):
            continue
        pen = max((abs(c.penetration_depth) for c in res.getContacts()), default=0.0)
        if pen <= depth:
            continue
        if (fa is not ga or fb is not gb) and not _surfaces_meet(coal, fa, ta, fb, tb):
            continue  # the hulls overlap, the meshes themselves do not (a concave part around the other)
        key = frozenset((la.name, lb.name))
        if key not in hits or pen > hits[key][0]:
            hits[key] = (pen, la, sa, lb, sb)
    if not hits:
        return
    disabled, srdf = srdf_disabled(model, entry)
    from urdfcheck.core.paths import shown

    def by_place(kv):
        _, la, sa, lb, sb = kv[1]
        return (sb.loc.line, sa.loc.line, la.name, lb.name)

    for key, (pen, la, sa, lb, sb) in sorted(hits.items(), key=by_place):
        if key in disabled:
            continue
        entry_text = f'<disable_collisions link1="{la.name}" link2="{lb.name}" reason="Default"/>'
        where = (f"; {shown(srdf)} describes this robot and does not disable the pair: MoveIt reports the start "
                 f"state in collision" if srdf else "")
        hull = ("; meshes measured by their convex hulls" if id(sa) in meshes or id(sb) in meshes else "")
        yield Problem(f"links {la.name!r} and {lb.name!r} interpenetrate by {pen * 1000:.0f} mm at the zero "
                      f"configuration (collision geometry{hull}){where}; an SRDF needs {entry_text}, or move the "
                      f"shapes apart", at=sb, related=(sa,), severity=Severity.WARNING if srdf else None,
                      data={"links": [la.name, lb.name], "depth": round(pen, 6),
                            "disable_collisions": entry_text})
