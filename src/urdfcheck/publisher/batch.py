"""Batch forward kinematics with numpy: many configurations at once, same per-joint rule as the publisher.

numpy is imported inside the functions; importing this module costs nothing.
"""
from __future__ import annotations

from urdfcheck.publisher.kinematics import KinematicTree, kinematic_tree, rot_from_quat


def configuration_joints(model) -> list[str]:
    """Column order of an N x dof configuration array: movable joints without <mimic>, document order."""
    return kinematic_tree(model).active_joints()


def _values(tree: KinematicTree, configurations, joint_names):
    """dict joint -> (N,) float array for every movable joint (mimic resolved), and N."""
    import numpy as np

    movable = tree.movable
    active = tree.active_joints()
    if isinstance(configurations, dict):
        configurations = [configurations]
    if isinstance(configurations, (list, tuple)) and configurations and isinstance(configurations[0], dict):
        n = len(configurations)
        names = []
        seen = set()
        for cfg in configurations:
            for k in cfg:
                if k not in seen:
                    seen.add(k)
                    names.append(k)
        unknown = [k for k in names if k not in tree.model.joints]
        if unknown:
            raise ValueError(f"not joints of the model: {', '.join(map(repr, unknown[:5]))}")
        given = {}
        for k in names:
            if k not in movable:
                continue
            given[k] = np.array([float(cfg.get(k, 0.0)) for cfg in configurations], dtype=float)
    else:
        arr = np.asarray(configurations, dtype=float)
        if arr.ndim == 1:
            arr = arr[None, :]
        if arr.ndim != 2:
            raise ValueError(f"configurations must be N x dof, got shape {arr.shape}")
        n, k = arr.shape
        if joint_names is None:
            if k == len(active):
                joint_names = active
            elif k == len(tree.movable_joints()):
                joint_names = tree.movable_joints()
            else:
                raise ValueError(f"configurations have {k} columns; the model has {len(active)} independent "
                                 f"movable joints ({len(tree.movable)} with mimic joints): pass joint_names")
        if len(joint_names) != k:
            raise ValueError(f"{len(joint_names)} joint names for {k} columns")
        unknown = [j for j in joint_names if j not in tree.model.joints]
        if unknown:
            raise ValueError(f"not joints of the model: {', '.join(map(repr, unknown[:5]))}")
        given = {name: arr[:, i] for i, name in enumerate(joint_names) if name in movable}
    # independent joints not given are at 0; mimic joints follow their source transitively (explicit wins)
    for name in active:
        if name not in given:
            given[name] = np.zeros(n)
    values = tree.resolve_mimic(given, transitive=True)
    return values, n


# Every link's pose is written straight into the (links, N, 4, 4) output by one BLAS product with its parent's
# (4N x 4 @ 4 x 4; stacked 4x4 matmul or per-entry arithmetic is several times slower for tiny matrices), or by a
# copy plus a shift when the joint origin does not rotate. A revolute joint about a coordinate axis then only
# mixes two adjacent columns of each rotation row: a complex multiplication by exp(-iq) on a strided complex
# view. y axes become x axes by a constant quarter turn about z, undone afterwards (times i on columns 0, 1);
# other axes are turned onto z by a constant rotation, undone by a second product.
_QUARTER = ((0.0, -1.0, 0.0), (1.0, 0.0, 0.0), (0.0, 0.0, 1.0))  # Rz(pi/2): Ry(q) = Rz(pi/2) Rx(q) Rz(-pi/2)
_HUGE = 1e300  # joint values and offsets below this cannot overflow when summed down any real chain


class _Step:
    """What link_poses does for one segment; constants precomputed once per tree."""

    __slots__ = ("name", "parent", "child", "kind", "j", "shift", "offset", "pair", "post", "axis", "sign", "repair",
                 "taints")


def _plan(tree: KinematicTree, np):
    """(link index, steps, [(revolute joint, sign)], {mimic joint: source it equals}), cached on the tree."""
    plan = tree.__dict__.get("_batch_plan")
    if plan is not None:
        return plan
    index = {link: i for i, link in enumerate(tree.links)}
    steps, revolute = [], []
    for seg in tree.segments:
        st = _Step()
        st.name, st.parent, st.child = seg.name, index[seg.parent], index[seg.child]
        st.pair = st.post = st.axis = st.sign = None
        j = np.eye(4)
        j[:3, :3] = seg.origin_r
        j[:3, 3] = seg.origin_t
        # a non-finite constant would turn the exact 0 0 0 1 bottom row into NaN (0 * NaN); a non-finite or
        # huge offset must not reach the children's rotations through the 0 * t terms of their products
        st.repair = not np.isfinite(j).all()
        st.taints = st.repair or not (np.abs(j[:3, 3]) <= _HUGE).all()
        st.kind = seg.type if seg.kind == "movable" else "fixed"
        if st.kind == "prismatic":
            st.axis = None if seg.axis is None else np.array(seg.axis, dtype=float)
        elif st.kind != "fixed":
            st.kind = "revolute"
            a = seg.axis
            if a is None:
                st.kind = "nan"
            else:
                # Rot(a, q) = pre @ G(q) @ pre^T, G rotating the column pair (0, 1) (about z) or (1, 2) (about x)
                k = [i for i in range(3) if a[i] != 0.0]
                sign, pre = 1.0, None
                if len(k) == 1:
                    sign = a[k[0]]
                    st.pair = 0 if k[0] == 2 else 1
                    if k[0] == 1:
                        pre, st.post = np.array(_QUARTER), "turn"  # undone: times i on columns (0, 1)
                else:
                    pre = _frame_with_z(np.array(a, dtype=float), np)
                    st.pair, st.post = 0, pre.T.copy()
                if pre is not None:
                    j[:3, :3] = j[:3, :3] @ pre
                st.sign = sign
                revolute.append((seg.name, sign))
        st.j = j
        st.shift = j[:3, 3] if (j[:3, :3] == np.eye(3)).all() else None
        st.offset = bool(j[:3, 3].any())
        steps.append(st)
    aliases = {name: src for name, src, mult, off in tree.mimics if mult == 1.0 and off == 0.0}
    plan = (index, steps, revolute, aliases)
    tree.__dict__["_batch_plan"] = plan
    return plan


def _frame_with_z(a, np):
    """A rotation matrix whose third column is the unit vector a."""
    e = np.array([1.0, 0.0, 0.0]) if abs(a[0]) < 0.9 else np.array([0.0, 1.0, 0.0])
    u = np.cross(e, a)
    u /= np.linalg.norm(u)
    return np.stack([u, np.cross(a, u), a], axis=1)


def link_poses(model, configurations, root_frame: str | None = None, *, joint_names=None,
               links=None) -> dict:
    """Pose of every link for N configurations: {link: (N, 4, 4) numpy array}.

    `configurations`: an N x dof array (columns: ``configuration_joints(model)``, or all movable joints
    including mimic ones, or `joint_names`), or a list of {joint: value} dicts (missing joints are 0).
    Mimic joints not given follow their source, transitively (the URDF's kinematic meaning; robot_state_publisher
    only follows direct sources, see ``KinematicTree.resolve_mimic``); a mimic joint whose source cannot be
    resolved gives NaN poses below it. Planar and floating joints contribute their origin (robot_state_publisher
    cannot move them; it publishes nothing at all for floating joints). A zero axis gives NaN, as in KDL.

    Poses are relative to the model root(s) (identity), or to `root_frame` when given (any link).
    """
    import numpy as np

    tree = kinematic_tree(model)
    values, n = _values(tree, configurations, joint_names)
    index, steps, revolute, aliases = _plan(tree, np)
    big = np.empty((len(index), n, 4, 4))
    for r in tree.roots:
        big[index[r]] = np.eye(4)
    flat = big.reshape(len(index), 4 * n, 4)
    # columns (0, 1) and (1, 2) of the rotation rows of every link, as (links, 3, N) complex views
    pairs = [big[:, :, :3, k:k + 2].view(complex)[..., 0].transpose(0, 2, 1) for k in (0, 1)]
    # exp(-iq) of every revolute joint: sin and cos cost more than anything else per joint, so they are taken
    # in one go, once per distinct joint value (a mimic joint with multiplier 1 and offset 0 equals its source)
    nan = np.full(n, np.nan)  # unresolvable mimic joint
    rows, unique = {}, []
    for name, _ in revolute:
        v, base, seen = values.get(name, nan), name, set()
        while base not in seen and aliases.get(base) in values and np.array_equal(values[aliases[base]], v):
            seen.add(base)
            base = aliases[base]
        if base not in rows:
            rows[base] = len(unique)
            unique.append(v)
        rows[name] = rows[base]
    angles = np.array(unique).reshape(len(unique), n)
    np.negative(angles, out=angles)
    spin = np.empty((len(unique), n), dtype=complex)
    np.cos(angles, out=spin.real)
    np.sin(angles, out=spin.imag)
    finite = np.isfinite(angles).all(axis=1) if not np.isfinite(angles.sum()) else np.ones(len(unique), bool)
    turn = np.full(n, 1j)
    # KDL's Frame product keeps NaN where it would arise: a translation that is not finite under a finite rotation
    # (tainted) must not reach the rotation columns through 0 * t, and a NaN rotation (shaky) must reach the
    # translation even through R * 0
    tainted, shaky = [False] * len(index), [False] * len(index)
    for st in steps:
        a, o = flat[st.parent], flat[st.child]
        if st.shift is not None:
            np.copyto(o, a)
            if st.offset or shaky[st.parent]:
                o[:, 3] += a[:, :3] @ st.shift
        elif tainted[st.parent]:
            np.matmul(a[:, :3], st.j[:3, :3], out=o[:, :3])
            np.matmul(a, st.j[:, 3], out=o[:, 3])
        else:
            np.matmul(a, st.j, out=o)
        if st.repair:
            o[3::4] = (0.0, 0.0, 0.0, 1.0)
        taint, shake = tainted[st.parent] or st.taints, shaky[st.parent] or st.repair
        if st.kind == "revolute":
            k = rows[st.name]
            pair = pairs[st.pair][st.child]
            np.multiply(pair, spin[k] if st.sign > 0 else spin[k].conj(), out=pair, order="C")  # C: 3 long loops
            if st.post is None:
                pass
            elif isinstance(st.post, str):
                pair = pairs[0][st.child]
                np.multiply(pair, turn, out=pair, order="C")
            else:
                np.matmul(o[:, :3], st.post, out=o[:, :3])
            if not finite[k]:  # a non-finite angle makes the whole rotation NaN, as in the Rodrigues form
                big[st.child][~np.isfinite(angles[k]), :3, :3] = np.nan
                shake = True
        elif st.kind == "prismatic":
            q = values.get(st.name)
            if st.axis is None or q is None:
                big[st.child][:, :3, 3] = np.nan
                taint = True
            else:
                along = np.matmul(o[:, :3], st.axis).reshape(n, 4)[:, :3]  # the axis in the root frame
                along *= q[:, None]
                big[st.child][:, :3, 3] += along
                taint = taint or not (np.abs(q) <= _HUGE).all()
        elif st.kind == "nan":
            big[st.child][:, :3, :] = np.nan
        tainted[st.child], shaky[st.child] = taint, shake
    if root_frame is not None:
        if root_frame not in index:
            raise KeyError(f"frame {root_frame!r} is not a link of the model's tree")
        rot, pos = big[..., :3, :3], big[..., :3, 3]
        rr, pr = rot[index[root_frame]].copy(), pos[index[root_frame]].copy()
        rt = np.swapaxes(rr, 1, 2)
        new_rot = (rt[None, :, :, :, None] * rot[:, :, None, :, :]).sum(axis=3)
        pos[...] = (rt[None] * (pos - pr[None])[:, :, None, :]).sum(axis=3)
        rot[...] = new_rot
    wanted = tree.links if links is None else list(links)
    return {k: big[index[k]] for k in wanted}


def rotations_from_quaternions(q):
    """(N,4) quaternions (x, y, z, w) -> (N,3,3), KDL::Rotation::Quaternion."""
    import numpy as np

    x, y, z, w = q[:, 0], q[:, 1], q[:, 2], q[:, 3]
    x2, y2, z2, w2 = x * x, y * y, z * z, w * w
    r = np.empty((q.shape[0], 3, 3))
    r[:, 0, 0] = w2 + x2 - y2 - z2
    r[:, 0, 1] = 2 * x * y - 2 * w * z
    r[:, 0, 2] = 2 * x * z + 2 * w * y
    r[:, 1, 0] = 2 * x * y + 2 * w * z
    r[:, 1, 1] = w2 - x2 + y2 - z2
    r[:, 1, 2] = 2 * y * z - 2 * w * x
    r[:, 2, 0] = 2 * x * z - 2 * w * y
    r[:, 2, 1] = 2 * y * z + 2 * w * x
    r[:, 2, 2] = w2 - x2 - y2 + z2
    return r


def compose_published(tree: KinematicTree, edges: dict, n: int) -> dict:
    """Compose published transforms into poses relative to each link's TF root.

    `edges`: {joint name: (translations (N,3), quaternions (N,4))} for every published segment (fixed ones
    may be given once as ((3,), (4,))); NaN rows mean "not published in that configuration". A link whose
    chain misses a transform gets NaN. Floating joints (never published) start new trees.
    """
    import numpy as np

    poses: dict = {r: np.eye(4) for r in tree.roots}
    for seg in tree.segments:
        if seg.kind == "skipped":
            poses[seg.child] = np.eye(4)
            continue
        t, q = edges.get(seg.name, (None, None))
        if t is None:
            local = np.full((4, 4), np.nan)
        else:
            t = np.asarray(t, dtype=float)
            q = np.asarray(q, dtype=float)
            if t.ndim == 1:
                local = np.eye(4)
                local[:3, :3] = rot_from_quat(*q.tolist())
                local[:3, 3] = t
            else:
                local = np.zeros((n, 4, 4))
                local[:, :3, :3] = rotations_from_quaternions(q)
                local[:, :3, 3] = t
                local[:, 3, 3] = 1.0
        poses[seg.child] = poses[seg.parent] @ local
    return {k: (np.broadcast_to(v, (n, 4, 4)).copy() if v.ndim == 2 else v) for k, v in poses.items()}


def relative_to_tf_roots(tree: KinematicTree, poses: dict) -> dict:
    """World poses {link: (N,4,4)} -> poses relative to each link's TF root (see KinematicTree.tf_root_of)."""
    import numpy as np

    out = {}
    inv_cache = {}
    for link, p in poses.items():
        root = tree.tf_root_of(link)
        if root == link:
            out[link] = np.broadcast_to(np.eye(4), p.shape).copy()
            continue
        ref = poses.get(root)
        if ref is None:
            out[link] = np.full(p.shape, np.nan)
            continue
        inv = inv_cache.get(root)
        if inv is None:
            inv = np.zeros(ref.shape)
            rt = np.swapaxes(ref[..., :3, :3], -1, -2)
            inv[..., :3, :3] = rt
            inv[..., :3, 3] = -(rt @ ref[..., :3, 3:4])[..., 0]
            inv[..., 3, 3] = 1.0
            inv_cache[root] = inv
        out[link] = inv @ p
    return out


def pose_errors(a, b):
    """Translation (m) and rotation (rad) differences between (N,4,4) pose arrays, each (N,).

    The rotation angle uses atan2(|vee(R - R^T)| / 2, (trace - 1) / 2) of R = Ra^T Rb, accurate near 0.
    NaN in either input gives +inf (so it can never pass a tolerance); NaN in both at the same place is
    treated as equal only by the caller (see verify).
    """
    import numpy as np

    dt = np.linalg.norm(a[..., :3, 3] - b[..., :3, 3], axis=-1)
    r = np.swapaxes(a[..., :3, :3], -1, -2) @ b[..., :3, :3]
    vx = r[..., 2, 1] - r[..., 1, 2]
    vy = r[..., 0, 2] - r[..., 2, 0]
    vz = r[..., 1, 0] - r[..., 0, 1]
    sin = 0.5 * np.sqrt(vx * vx + vy * vy + vz * vz)
    cos = 0.5 * (r[..., 0, 0] + r[..., 1, 1] + r[..., 2, 2] - 1.0)
    dr = np.arctan2(sin, cos)
    dt = np.where(np.isnan(dt), np.inf, dt)
    dr = np.where(np.isnan(dr), np.inf, dr)
    return dt, dr
