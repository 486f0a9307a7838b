"""G006: links whose collision geometry interpenetrates at the zero configuration (issue 41).

MoveIt refuses to plan from a start state in collision and Gazebo (with self_collide) pushes the links apart on
spawn. The shapes are tested with coal (hpp-fcl, the library Pinocchio and MoveIt's FCL successor use), imported
only here and only when the model has two collision primitives that could touch: without coal installed the rule
says nothing.

What is compared: boxes, cylinders, spheres and capsules (meshes are not loaded), every link at the pose of
`Robot.world_poses` (all joints at zero, mimic offsets ignored); a pair with a joint between them whose limits
exclude zero is left out (that pose is never reached). Pairs MoveIt's setup assistant calls adjacent are
left out, as `collision_detection::AllowedCollisionMatrix` defaults do: links joined by a joint, and links held
together by fixed joints (they never move relative to each other; Gazebo lumps them into one body). So are pairs an
SRDF of the same robot (its `<robot name>`, in the model's package or a sibling `*moveit*` package) already
disables. Only penetration deeper than `depth` (5 mm by default) is reported: primitives that touch or overlap
by a rounding error are how links are drawn flush against each other.
"""
from __future__ import annotations

import os
import re
from collections.abc import Iterator

from urdfcheck.core.findings import Problem, Severity

_PRIMITIVES = ("box", "cylinder", "sphere", "capsule")
_SRDF_NAME = re.compile(r"<robot\b[^>]*\bname\s*=\s*[\"']([^\"']+)[\"']")
_DISABLE = re.compile(r"<disable_collisions\b([^>]*)/?>")
_ATTR = re.compile(r"\b(link1|link2)\s*=\s*[\"']([^\"']*)[\"']")
_SUBST = re.compile(r"\$\{[^}]*\}|\$\([^)]*\)")
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
            return coal.Box(*map(float, g.size)), max(g.size) * 0.87
        if g.kind == "cylinder" and g.radius and g.length and g.radius > 0 and g.length > 0:
            return coal.Cylinder(float(g.radius), float(g.length)), (g.radius ** 2 + (g.length / 2) ** 2) ** 0.5
        if g.kind == "sphere" and g.radius and g.radius > 0:
            return coal.Sphere(float(g.radius)), g.radius
        if g.kind == "capsule" and g.radius and g.length and g.radius > 0 and g.length > 0:
            return coal.Capsule(float(g.radius), float(g.length)), g.radius + g.length / 2
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


def self_collisions(model, entry: str, depth: float) -> Iterator[Problem]:
    from urdfcheck.core.geometry import compose, origin_matrix

    bodies = []  # (link, Shape)
    for link in model.link_list:
        for s in link.collisions:
            if s.geometry is not None and s.geometry.kind in _PRIMITIVES:
                bodies.append((link, s))
    if len({link.name for link, _ in bodies}) < 2:
        return
    poses = model.world_poses()
    groups = _rigid_groups(model)
    adjacent = _adjacent(model, groups)
    coal, np = _coal()
    if coal is None:
        return
    placed = []  # (link name, shape loc, coal geometry, transform, centre, radius)
    for link, s in bodies:
        if link.name not in poses:
            continue
        got = _shape(coal, s.geometry)
        if got is None:
            continue
        m = compose(poses[link.name], origin_matrix(s.origin))
        if not _finite(m):
            continue
        rot = np.array([row[:3] for row in m[:3]], dtype=float)
        t = np.array([m[0][3], m[1][3], m[2][3]], dtype=float)
        placed.append((link, s, got[0], coal.Transform3s(rot, t), t, got[1]))
    chains: dict[str, set] = {}
    hits: dict[frozenset, tuple] = {}
    req = coal.CollisionRequest(coal.CollisionRequestFlag.CONTACT, 1)
    for i, (la, sa, ga, ta, ca, ra) in enumerate(placed):
        for lb, sb, gb, tb, cb, rb in placed[i + 1:]:
            if la.name == lb.name or groups[la.name] == groups[lb.name]:
                continue
            if frozenset((groups[la.name], groups[lb.name])) in adjacent:
                continue
            if float(np.linalg.norm(ca - cb)) > ra + rb:
                continue
            if _unreachable(model, la.name, lb.name, chains):
                continue
            res = coal.CollisionResult()
            if not coal.collide(ga, ta, gb, tb, req, res):
                continue
            pen = max((abs(c.penetration_depth) for c in res.getContacts()), default=0.0)
            if pen <= depth:
                continue
            key = frozenset((la.name, lb.name))
            if key not in hits or pen > hits[key][0]:
                hits[key] = (pen, la, sa, lb, sb)
    if not hits:
        return
    disabled, srdf = srdf_disabled(model, entry)
    from urdfcheck.core.paths import shown

    for key, (pen, la, sa, lb, sb) in sorted(hits.items(), key=lambda kv: (kv[1][4].loc.line, kv[1][2].loc.line)):
        if key in disabled:
            continue
        entry_text = f'<disable_collisions link1="{la.name}" link2="{lb.name}" reason="Default"/>'
        where = (f"; {shown(srdf)} describes this robot and does not disable the pair: MoveIt reports the start "
                 f"state in collision" if srdf else "")
        yield Problem(f"links {la.name!r} and {lb.name!r} interpenetrate by {pen * 1000:.0f} mm at the zero "
                      f"configuration (collision geometry){where}; an SRDF needs {entry_text}, or move the shapes "
                      f"apart", at=sb, related=(sa,), severity=Severity.WARNING if srdf else None,
                      data={"links": [la.name, lb.name], "depth": round(pen, 6),
                            "disable_collisions": entry_text})
