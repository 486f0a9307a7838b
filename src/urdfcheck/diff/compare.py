"""`urdfcheck diff`: what a change does to the robot, per model, deployment and variant.

    diff(old_paths, new_paths, old_root, new_root, **request options) -> DiffResult

Both sides are planned exactly as `urdfcheck lint` plans them (same request, same planner: models, variants,
deployments from launch files), each target is loaded and built with `load_target`, and the two models of a
(model, variant) pair are compared: links and joints added, removed, renamed (matched by name, then by
position in the tree), each frame's pose at the zero configuration and at a few seeded random ones, joint
type, axis, limits, mimic, inertial values, shapes, meshes and materials, and the contracts (joints named by
controllers and drivers, TF edges claimed by launch files, controllers and the config).

Values are compared, never source text or locations: a change of comments or formatting is no change.
"""
from __future__ import annotations

import math
import os

from urdfcheck.core.records import Record

SEEDS = 5  # random configurations besides the zero one
SEED = 20260
MOVE_MM = 1e-3  # a frame moved: more than a micrometre ...
MOVE_DEG = 1e-4  # ... or more than this angle
EPS = 1e-9  # two numbers from the model are equal


class Pair(Record):
    """One (model, variant) compared. status: changed, unchanged, added, removed, unloadable.
    errors: the load findings (text) of the side that could not be compared."""

    _fields = ('model', 'variant', 'status', 'links', 'joints', 'moved', 'changes', 'errors', 'tree')

    def __init__(self, model: str, variant: str, status: str = "unchanged", links=None, joints=None, moved=None,
                 changes=None, errors=None, tree=None):
        self.model, self.variant, self.status = model, variant, status
        self.links = links or {"added": [], "removed": [], "renamed": []}
        self.joints = joints or {"added": [], "removed": [], "renamed": []}
        self.moved = moved or []  # {frame, mm, deg, zero_mm, zero_deg, because}
        self.changes = changes or []  # {kind, name, field, old, new}
        self.errors = errors or {}
        self.tree = tree  # new side's tree: [(parent, joint, child)], roots; for the Mermaid view

    @property
    def changed(self) -> bool:
        return self.status != "unchanged"

    def as_dict(self) -> dict:
        return {k: getattr(self, k) for k in self._fields if k != "tree"}


class DiffResult(Record):
    """old, new: how the two sides are named (a revision, "working tree", a path as typed; never a temporary
    folder). notes: what could not be compared and why (a file of the revision with a name no file system holds).
    findings: what the change does to lint's findings (`diff.findings.FindingsDiff`), when asked for."""
    _fields = ('old', 'new', 'pairs', 'notes')
    findings = None

    def __init__(self, old: str, new: str, pairs: list[Pair], notes=None):
        self.old, self.new, self.pairs = old, new, pairs
        self.notes = list(notes or [])

    @property
    def changed(self) -> bool:
        return any(p.changed for p in self.pairs)

    def as_dict(self) -> dict:
        out = {"old": self.old, "new": self.new, "changed": self.changed,
               "models": [p.as_dict() for p in self.pairs], "notes": list(self.notes)}
        if self.findings is not None:
            out["findings"] = self.findings.as_dict()
        return out


# --- loading: the one place to re-point at the pipeline's load(request, path) ---------------------------------
def load_target(t):
    """(model or None, expanded document, load findings) of one planned target, as `lint` loads it."""
    from urdfcheck.load import loader

    opts = t.settings.load_options() if t.settings is not None else {}
    exp = loader.begin(t.path, t.args, packages=t.packages, **opts).result()
    return loader.build_model(exp), exp, list(exp.findings)


def plan_side(paths, root: str, options: dict, cwd: str | None = None):
    """The targets `urdfcheck lint PATHS` plans, with labels relative to `root`. `cwd`: the folder to plan from
    (a launch file's relative paths and what the planner lists read from the working directory: the old side
    of `diff --git` is planned from its own copy of it, so both sides see the same)."""
    from urdfcheck.plan.plan import plan
    from urdfcheck.request.request import make_request

    paths = [os.path.abspath(p) for p in paths]
    request = make_request(paths, root=root, **options)
    here = os.getcwd()
    if cwd is not None:
        os.chdir(cwd)
    try:
        targets = plan(request, here=root)
        for t in targets:  # what the planner made relative to the folder it planned from: absolute, read later
            if not os.path.isabs(str(t.path)):
                t.path = type(t.path)(os.path.abspath(str(t.path))) if hasattr(t.path, "__fspath__") \
                    else os.path.abspath(t.path)
        return [(_key(t, root), t) for t in targets]
    finally:
        os.chdir(here)


def _same_place(old_root: str, new_root: str) -> str | None:
    """The old tree's copy of the working directory, when the working directory lies in the new tree."""
    here = os.path.realpath(os.getcwd())
    rel = os.path.relpath(here, os.path.realpath(new_root))
    if rel == ".." or rel.startswith(".." + os.sep):
        return None
    place = os.path.normpath(os.path.join(old_root, rel))
    return place if os.path.isdir(place) else old_root


def _key(t, root: str) -> tuple[str, str]:
    """What a target is in its tree, the same on both sides: the model's path relative to the tree, and the
    variant; a deployment's variant is its launch file relative to the tree (never the path the planner shows,
    which for a tree outside the working directory holds that tree's location)."""
    variant = t.variant or ""
    d = getattr(t, "deployment", None)
    launch = getattr(getattr(d, "launch", None), "file", None)
    if launch:
        variant = _rel(str(launch), root) + (f" [{d.variant}]" if getattr(d, "variant", "") else "")
    return _rel(str(t.path), root), variant


def _rel(path: str, root: str) -> str:
    return os.path.relpath(os.path.abspath(path), root).replace(os.sep, "/")


def diff(old_paths, new_paths, old_root: str, new_root: str, *, seeds: int = SEEDS, old_label: str | None = None,
         new_label: str | None = None, **options) -> DiffResult:
    """Compare what `old_paths` (under `old_root`) and `new_paths` (under `new_root`) describe. `old_label`,
    `new_label`: how the report names the sides (and what replaces each root in a message)."""
    from urdfcheck.load.budget import run_budget

    old_root, new_root = os.path.abspath(old_root), os.path.abspath(new_root)
    named_old = old_label is not None  # `diff --git REV`: the old side lives in a temporary folder
    old_label = old_label or "old"
    new_label = new_label or "new"
    old_t = dict(plan_side(old_paths, old_root, options, _same_place(old_root, new_root))) if old_paths else {}
    new_t = dict(plan_side(new_paths, new_root, options)) if new_paths else {}
    if not old_t and not new_t:
        from urdfcheck.core.paths import shown
        from urdfcheck.request.request import UsageError

        # never the absolute path of the runner's tree or of the revision's temporary folder
        said = [f"{old_label}:{_rel(p, old_root)}" if named_old else shown(str(p)) for p in old_paths]
        said += [shown(str(p)) for p in new_paths]
        raise UsageError(f"no URDF or xacro model found in {', '.join(said)}")
    if len({m for m, _ in old_t}) == 1 and len({m for m, _ in new_t}) == 1 and set(old_t) != set(new_t):
        # one model each side (two files named differently): pair by variant
        name = next(iter(new_t))[0]
        old_t = {(name, v): t for (_, v), t in old_t.items()}
        # a plain URDF against the variants of a xacro (or the reverse): the one model against each variant
        if len(old_t) == 1 and set(old_t) != set(new_t):
            only = next(iter(old_t.values()))
            old_t = {k: only for k in new_t}
        elif len(new_t) == 1 and set(old_t) != set(new_t):
            only = next(iter(new_t.values()))
            new_t = {k: only for k in old_t}
    renamed = _renamed(old_t, new_t)
    for (old_model, _), key in renamed.items():
        old_t[key + (old_model,)] = old_t.pop((old_model, _))
    pairs = []
    with run_budget(options.get("budget")):
        for key in list(dict.fromkeys([*old_t, *new_t])):
            if len(key) == 3:
                continue
            o, n = old_t.get(key), new_t.get(key)
            moved_from = None
            if o is None:
                moved_from = next((k for k in old_t if len(k) == 3 and k[:2] == key), None)
                o = old_t.get(moved_from) if moved_from else None
            if o is None or n is None:
                pairs.append(Pair(key[0], key[1], "added" if o is None else "removed"))
                continue
            pair = compare_targets(key, o, n, seeds=seeds, roots=(old_root, new_root))
            if moved_from is not None:  # the model's file was renamed (git mv): compared with its old self
                pair.changes.insert(0, {"kind": "model", "name": key[0], "field": "file", "old": moved_from[2],
                                        "new": key[0]})
                pair.status = "changed"
            pairs.append(pair)
    for p in pairs:  # load errors name files by path: the side's label, never its folder
        p.errors = {side: [_scrub(e, ((old_root, old_label), (new_root, new_label))) for e in errs]
                    for side, errs in p.errors.items()}
    return DiffResult(old_label, new_label, pairs)


def _where(loc, root: str | None) -> str:
    """A location with its file relative to the compared tree (the report adds which side it is)."""
    if loc is None:
        return "?"
    file = str(loc.file)
    if root is not None:  # loaders show a file relative to the working directory, or absolute
        full = os.path.abspath(file)
        if (full + os.sep).startswith(root.rstrip(os.sep) + os.sep):
            file = _rel(full, root)
    return str(type(loc)(file, loc.line, loc.column))


def _renamed(old_t: dict, new_t: dict) -> dict:
    """old key -> new key for a model whose file was renamed: exactly one model only on the old side and one only
    on the new side, in the same folder, whose variants match once the old file name is read as the new one."""
    gone = {m for m, _ in old_t} - {m for m, _ in new_t}
    came = {m for m, _ in new_t} - {m for m, _ in old_t}
    if len(gone) != 1 or len(came) != 1:
        return {}
    a, b = next(iter(gone)), next(iter(came))
    if os.path.dirname(a) != os.path.dirname(b):
        return {}
    base_a, base_b = os.path.basename(a), os.path.basename(b)
    out = {}
    for m, v in old_t:
        if m != a:
            continue
        key = (b, v.replace(base_a, base_b))
        if key not in new_t:
            return {}
        out[(m, v)] = key
    return out


def _scrub(text: str, roots) -> str:
    """`text` with each root's absolute path (and its real path) replaced by the side's label."""
    for root, label in roots:
        for r in dict.fromkeys((root, os.path.realpath(root))):
            text = text.replace(r.rstrip(os.sep) + os.sep, f"{label}:").replace(r, label)
    return text


def compare_targets(key, old_t, new_t, *, seeds: int = SEEDS, roots=(None, None)) -> Pair:
    from urdfcheck.core.findings import Severity

    sides = []
    errors = {}
    for (label, t), root in zip((("old", old_t), ("new", new_t)), roots):
        model, exp, findings = load_target(t)
        bad = [f for f in findings if f.severity >= Severity.ERROR]
        if model is None or bad:
            errors[label] = [f"{_where(f.location, root)}: {f.code} {f.message}"
                             for f in (bad or findings)] or ["not loaded"]
        sides.append((model, exp, t))
    if errors:
        return Pair(key[0], key[1], "unloadable", errors=errors)
    (om, oexp, ot), (nm, nexp, nt) = sides
    pair = compare_models(om, nm, seeds=seeds, roots=roots)
    pair.model, pair.variant = key
    pair.changes.extend(compare_contracts(_consumers(ot, om, oexp), _consumers(nt, nm, nexp), pair, (om, nm)))
    pair.status = "changed" if (pair.changes or pair.moved or any(pair.links.values())
                                or any(pair.joints.values())) else "unchanged"
    return pair


def _consumers(t, model, exp):
    config = t.settings.config if t.settings is not None else None
    try:
        return t.consumers(model, exp, config)
    except Exception:  # noqa: BLE001 - a consumer that cannot be read is lint's business (C007), not diff's
        return None


# --- matching ----------------------------------------------------------------------------------------------
def match(old, new) -> tuple[dict, dict]:
    """(old link -> new link, old joint -> new joint): by name, then an unmatched old link is the unmatched new
    link hanging from the same (matched) parent with the same joint type and the nearest origin; an unmatched
    old joint is the unmatched new joint between the same matched links."""
    links = {n: n for n in old.links if n in new.links}
    if len(old.roots) == 1 and len(new.roots) == 1 and old.roots[0] not in links \
            and new.roots[0] not in set(links.values()):
        links[old.roots[0]] = new.roots[0]
    taken = set(links.values())
    for root in old.roots:
        for name in old.descendants_in_order(root):
            if name in links or name not in old.links:  # a joint may name a link nobody defines (S003)
                continue
            j = old.parent_joint.get(name)
            if j is None or j.parent not in links:
                continue
            cands = [c for c in new.child_joints.get(links[j.parent], ())
                     if c.child in new.links and c.child not in taken and c.child not in old.links
                     and c.type == j.type]
            if not cands:
                continue
            best = min(cands, key=lambda c: _distance(c.origin.xyz, j.origin.xyz))
            links[name] = best.child
            taken.add(best.child)
    joints = {n: n for n in old.joints if n in new.joints}
    used = set(joints.values())
    by_edge = {(j.parent, j.child): j.name for j in new.joint_list if j.name not in used}
    for j in old.joint_list:
        if j.name in joints:
            continue
        got = by_edge.get((links.get(j.parent), links.get(j.child)))
        if got is not None and got not in used:
            joints[j.name] = got
            used.add(got)
    return links, joints


def _distance(a, b) -> float:
    return math.dist(tuple(a or (0, 0, 0)), tuple(b or (0, 0, 0)))


# --- comparison of two models ----------------------------------------------------------------------------------
def compare_models(old, new, *, seeds: int = SEEDS, roots=(None, None)) -> Pair:
    links, joints = match(old, new)
    pair = Pair("", "")
    new_links, new_joints = set(links.values()), set(joints.values())
    pair.links = {
        "added": [n for n in new.links if n not in new_links],
        "removed": [n for n in old.links if n not in links],
        "renamed": [[o, n] for o, n in links.items() if o != n],
    }
    pair.joints = {
        "added": [n for n in new.joints if n not in new_joints],
        "removed": [n for n in old.joints if n not in joints],
        "renamed": [[o, n] for o, n in joints.items() if o != n],
    }
    for o, n in joints.items():
        pair.changes.extend(_joint_changes(old.joints[o], new.joints[n], links, joints))
    for o, n in links.items():
        pair.changes.extend(_link_changes(old, new, old.links[o], new.links[n], roots))
    pair.changes.extend(_material_changes(old, new))
    pair.moved = moved_frames(old, new, links, joints, pair, seeds=seeds)
    pair.tree = ([(j.parent, j.name, j.child) for j in new.joint_list], list(new.roots),
                 [(j.parent, j.name, j.child) for j in old.joint_list if j.name not in joints],
                 {o: n for o, n in links.items()})
    return pair


def _num(v):
    if isinstance(v, float):
        if not math.isfinite(v):
            return str(v)  # JSON has no NaN or inf
        return round(v, 9) + 0.0  # -0.0 is 0.0
    if isinstance(v, (tuple, list)):
        return [_num(x) for x in v]
    return v


def _same(a, b) -> bool:
    if isinstance(a, (int, float)) and isinstance(b, (int, float)):
        return abs(a - b) <= EPS * max(1.0, abs(a), abs(b)) or (a != a and b != b)
    if isinstance(a, (tuple, list)) and isinstance(b, (tuple, list)):
        return len(a) == len(b) and all(_same(x, y) for x, y in zip(a, b))
    return a == b


def _change(kind, name, field, a, b) -> list[dict]:
    return [] if _same(a, b) else [{"kind": kind, "name": name, "field": field, "old": _num(a), "new": _num(b)}]


def _joint_changes(a, b, links: dict, joints: dict) -> list[dict]:
    out = []
    out += _change("joint", b.name, "type", a.type, b.type)
    out += _change("joint", b.name, "parent", links.get(a.parent, a.parent), b.parent)
    out += _change("joint", b.name, "child", links.get(a.child, a.child), b.child)
    out += _change("joint", b.name, "origin.xyz", tuple(a.origin.xyz), tuple(b.origin.xyz))
    out += _change("joint", b.name, "origin.rotation", _rotation(a.origin), _rotation(b.origin))
    if a.movable or b.movable:
        out += _change("joint", b.name, "axis", tuple(a.axis), tuple(b.axis))
    la, lb = a.limit, b.limit
    for f in ("lower", "upper", "effort", "velocity", "acceleration", "deceleration", "jerk"):
        out += _change("joint", b.name, f"limit.{f}", getattr(la, f, None), getattr(lb, f, None))
    ma, mb = a.mimic, b.mimic
    out += _change("joint", b.name, "mimic",
                   None if ma is None else [joints.get(ma.joint, ma.joint), ma.multiplier, ma.offset],
                   None if mb is None else [mb.joint, mb.multiplier, mb.offset])
    for f in sorted(set(a.dynamics) | set(b.dynamics)):
        out += _change("joint", b.name, f"dynamics.{f}", a.dynamics.get(f), b.dynamics.get(f))
    return out


def _rotation(pose) -> list:
    """The rotation urdfdom reads, as a quaternion with w >= 0 (rpy and quat_xyzw written differently compare
    equal)."""
    from urdfcheck.core.geometry import origin_quaternion

    q = origin_quaternion(pose)
    return [-v for v in q] if q[3] < 0 else list(q)


def _link_changes(old, new, a, b, roots=(None, None)) -> list[dict]:
    out = []
    ia, ib = a.inertial, b.inertial
    out += _change("link", b.name, "mass", getattr(ia, "mass", None), getattr(ib, "mass", None))
    out += _change("link", b.name, "com", tuple(ia.origin.xyz) if ia else None, tuple(ib.origin.xyz) if ib else None)
    out += _change("link", b.name, "inertia.frame", _rotation(ia.origin) if ia else None,
                   _rotation(ib.origin) if ib else None)
    out += _change("link", b.name, "inertia", ia.inertia if ia else None, ib.inertia if ib else None)
    for kind in ("visuals", "collisions"):
        sa, sb = _shapes(old, getattr(a, kind), roots[0]), _shapes(new, getattr(b, kind), roots[1])
        for label in dict.fromkeys([*sa, *sb]):
            x, y = sa.get(label), sb.get(label)
            if x is None or y is None:  # a shape added or removed: one line
                out += _change("link", b.name, f"{kind[:-1]}[{label}]", x and _brief(x), y and _brief(y))
                continue
            for f in ("geometry", "mesh", "origin", "material"):
                out += _change("link", b.name, f"{kind[:-1]}[{label}].{f}", x.get(f), y.get(f))
    return out


def _shapes(model, shapes, root: str | None = None) -> dict:
    """Shapes by name (their index when unnamed or the name repeats): an inserted shape changes only itself."""
    names = [s.name for s in shapes]
    return {(s.name if s.name and names.count(s.name) == 1 else f"#{i}"): _shape(model, s, root)
            for i, s in enumerate(shapes)}


def _brief(shape: dict) -> list:
    return [shape["mesh"][0] if shape["mesh"] else shape["geometry"], shape["material"] and shape["material"][0]]


def _shape(model, s, root: str | None = None) -> dict:
    g = s.geometry
    geo = None
    mesh = None
    if g is not None:
        if g.kind == "mesh":
            mesh = [mesh_name(g.filename, root), list(g.scale) if g.scale else None]
            geo = "mesh"
        else:
            geo = [g.kind] + [_num(v) for v in (g.size, g.radius, g.length) if v is not None]
    material = None
    if s.material is not None:
        m = s.material
        known = model.materials.get(m.name)
        rgba = m.rgba if m.rgba is not None else getattr(known, "rgba", None)
        texture = m.texture if m.texture is not None else getattr(known, "texture", None)
        material = [m.name, list(rgba) if rgba else None, texture]
    return {"name": s.name, "geometry": geo, "mesh": mesh, "origin": list(s.origin.xyz) + _rotation(s.origin),
            "material": material}


def mesh_name(uri, root: str | None) -> str | None:
    """A mesh's file as the repository knows it, whatever way the model writes it: `package://pkg/rel` for a file
    inside a package (from `package://`, `file:///abs/...`, an absolute path, `$(find pkg)` already expanded to
    one), else relative to the compared tree. Two checkouts at different places name one mesh alike."""
    if not isinstance(uri, str):
        return uri
    path = uri[len("file://"):] if uri.startswith("file://") else uri
    if not os.path.isabs(path):
        return uri
    from urdfcheck.load.packages import own_package

    path = os.path.normpath(path)
    name, folder = own_package(path)
    if name and folder is not None:
        return f"package://{name}/{os.path.relpath(path, folder).replace(os.sep, '/')}"
    if root is not None and (path + os.sep).startswith(root.rstrip(os.sep) + os.sep):
        return os.path.relpath(path, root).replace(os.sep, "/")
    return uri


def _material_changes(old, new) -> list[dict]:
    out = []
    for name in dict.fromkeys([*old.materials, *new.materials]):
        a, b = old.materials.get(name), new.materials.get(name)
        out += _change("material", name, "rgba", getattr(a, "rgba", None), getattr(b, "rgba", None))
        out += _change("material", name, "texture", getattr(a, "texture", None), getattr(b, "texture", None))
    return out


# --- poses ------------------------------------------------------------------------------------------------------
def configurations(model, seeds: int, seed: int = SEED) -> list[dict]:
    """The zero configuration and `seeds` random ones (within each joint's limits; seeded: the same every run)."""
    import random

    rng = random.Random(seed)
    out = [{}]
    movable = [j for j in model.joint_list if j.movable and j.mimic is None]
    for _ in range(seeds):
        values = {}
        for j in movable:
            lo, hi = _range(j)
            values[j.name] = rng.uniform(lo, hi)
        out.append(values)
    return out


def _range(j) -> tuple[float, float]:
    if j.type == "continuous":
        return -math.pi, math.pi
    lim = j.limit
    lo, hi = getattr(lim, "lower", None), getattr(lim, "upper", None)
    if lo is None or hi is None or not (math.isfinite(lo) and math.isfinite(hi)) or hi < lo:
        return (-1.0, 1.0) if j.type == "revolute" else (-0.1, 0.1)
    return lo, hi


def frame_poses(model, values: dict) -> dict:
    """Every link's pose (4x4) in its tree's root for joint values (mimic joints follow their source)."""
    from urdfcheck.core.geometry import compose, identity
    from urdfcheck.publisher.kinematics import kinematic_tree

    tree = kinematic_tree(model)
    values = tree.resolve_mimic(dict(values), transitive=True)
    out = {r: identity() for r in tree.roots}
    for s in tree.segments:
        if s.parent in out and s.child not in out:
            q = values.get(s.name, 0.0) if s.kind == "movable" else 0.0
            out[s.child] = compose(out[s.parent], s.matrix(q))
    return out


def pose_delta(a, b) -> tuple[float, float]:
    """(translation in mm, rotation in degrees) between two 4x4 poses."""
    dt = math.sqrt(sum((a[i][3] - b[i][3]) ** 2 for i in range(3))) * 1000.0
    # angle of a^T b: trace = 1 + 2 cos(angle)
    tr = sum(a[k][i] * b[k][i] for i in range(3) for k in range(3))
    c = max(-1.0, min(1.0, (tr - 1.0) / 2.0))
    return dt, math.degrees(math.acos(c))


def moved_frames(old, new, links: dict, joints: dict, pair: Pair, *, seeds: int = SEEDS) -> list[dict]:
    """Frames whose pose in the root differs, at the zero configuration or at one of the random ones (the same
    joint values on both sides, a renamed joint keeping its value)."""
    configs = configurations(old, seeds)
    rename = {o: n for o, n in joints.items()}
    worst: dict[str, list] = {}
    for k, values in enumerate(configs):
        po = frame_poses(old, values)
        pn = frame_poses(new, {rename.get(j, j): v for j, v in values.items()})
        for o, n in links.items():
            if o not in po or n not in pn:
                continue
            mm, deg = pose_delta(po[o], pn[n])
            if not (math.isfinite(mm) and math.isfinite(deg)):
                continue
            w = worst.setdefault(n, [0.0, 0.0, 0.0, 0.0])
            if k == 0:
                w[2], w[3] = mm, deg
            w[0], w[1] = max(w[0], mm), max(w[1], deg)
    changed_joints = {c["name"] for c in pair.changes if c["kind"] == "joint"}
    changed_joints |= {n for _, n in pair.joints["renamed"]} | set(pair.joints["added"])
    out = []
    for name in new.links:
        w = worst.get(name)
        if w is None or (w[0] <= MOVE_MM and w[1] <= MOVE_DEG):
            continue
        out.append({"frame": name, "mm": round(w[0], 3), "deg": round(w[1], 4), "zero_mm": round(w[2], 3),
                    "zero_deg": round(w[3], 4), "because": _cause(new, name, changed_joints)})
    return out


def _cause(model, link: str, changed: set) -> str | None:
    """The nearest joint on the way to the root that changed (its own joint first)."""
    for j in model.chain_to_root(link):
        if j.name in changed:
            return j.name
    return None


# --- contracts ----------------------------------------------------------------------------------------------------
def contract_facts(c, model=None) -> dict:
    """What a change of the description can break in its consumers: the joints each controller and driver
    names, and the TF edges others claim (launch files, controllers, drivers, localization, the config); and,
    from the model itself, what its Gazebo plugins are told (consumers.gazebo reads them as the contracts do)."""
    out: dict[str, object] = {}
    if model is not None:
        _plugin_facts(out, model)
    if c is None:
        return out
    for ctrl in c.controllers:
        out[f"controller {ctrl.name} joints"] = sorted({u.joint for u in ctrl.joints + ctrl.state_joints})
        _reader_facts(out, f"controller {ctrl.name}", ctrl)
    for d in c.drivers:
        out[f"driver {d.name} joints"] = sorted({u.joint for u in d.joints})
        _reader_facts(out, f"driver {d.name}", d)
    from urdfcheck.consumers.tfclaims import claims_from_localization, claims_from_odom, claims_from_static_tfs

    claims = []
    for li in c.launch:
        claims += claims_from_static_tfs(li.static_tfs, [])
    base = c.frames.get("base", "base_link")
    claims += claims_from_odom((ctrl.odom_tf for ctrl in c.controllers), base, "controller")
    claims += claims_from_odom((d.odom_tf for d in c.drivers), base, "driver")
    claims += claims_from_localization(c.localization)
    claims += list(c.tf_owners)
    for cl in claims:
        key = f"tf {cl.parent} -> {cl.child}"
        owners = out.setdefault(key, [])
        who = f"{cl.owner} ({cl.kind})"
        if who not in owners:
            owners.append(who)
    return out


def _plugin_facts(out: dict, model) -> None:
    """A Gazebo plugin is a controller or driver written inside the model (a diff drive's wheel separation, the
    odometry transform it broadcasts, the joint states it publishes): the same facts, keyed by its label."""
    from urdfcheck.consumers.gazebo import read_plugins

    for o in read_plugins(model):
        _reader_facts(out, o.label, o, odom=o.odom)
        if o.drive is not None:
            out[f"{o.label} wheel tf"] = "on" if o.wheel_tf else "off"
        if o.state_joints is not None:
            out[f"{o.label} joint states"] = sorted(o.state_joints) or "all joints"


def _reader_facts(out: dict, who: str, r, odom=None) -> None:
    """The parameters of a controller or driver (as consumers.controllers read them) that a contract with the
    model reads: wheel geometry and wheel joints, the odom transform and its switch, the frame ids."""
    from urdfcheck.consumers.controllers import number

    drive = getattr(r, "drive", None)
    if drive is not None:
        out[f"{who} {drive.separation_key}"] = _num(drive.separation)
        out[f"{who} {drive.radius_key}"] = _num(number(drive.wheel_radius))
        for side in ("left", "right"):
            if drive.radius(side) != number(drive.wheel_radius):
                out[f"{who} {side} wheel radius"] = _num(drive.radius(side))
            out[f"{who} {side} wheels"] = [u.joint for u in getattr(drive, side)]
    odom = getattr(r, "odom_tf", None) if odom is None else odom
    if odom is not None:
        out[f"{who} odom tf {odom.parent} -> {odom.child}"] = "on" if odom.enabled else "off"
    frames = sorted({str(v.value) for v in getattr(r, "frames", ()) or () if v is not None})
    if frames:
        out[f"{who} frames"] = frames


def compare_contracts(old_c, new_c, pair: Pair, models=(None, None)) -> list[dict]:
    a, b = contract_facts(old_c, models[0]), contract_facts(new_c, models[1])
    out = []
    for key in dict.fromkeys([*a, *b]):
        x, y = a.get(key), b.get(key)
        if isinstance(x, list) and isinstance(y, list) and sorted(x) == sorted(y):
            continue
        if not isinstance(x, list) and _same(x, y):
            continue
        out.append({"kind": "contract", "name": key, "field": "", "old": x, "new": y})
    return out
