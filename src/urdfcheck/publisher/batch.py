"""Batch forward kinematics with numpy: many configurations at once, same per-joint rule as the publisher.

numpy is imported inside the functions; importing this module costs nothing.
"""
from __future__ import annotations

from .kinematics import KinematicTree, kinematic_tree, rot_from_quat


def configuration_joints(model) -> list[str]:
    """Column order of an N x dof configuration array: movable joints without <mimic>, document order."""
    return kinematic_tree(model).active_joints()


def _values(tree: KinematicTree, configurations, joint_names):
    """dict joint -> (N,) float array for every movable joint (mimic resolved), and N."""
    import numpy as np

    movable = tree.movable
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
            active = tree.active_joints()
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
    for name in tree.active_joints():
        if name not in given:
            given[name] = np.zeros(n)
    values = tree.resolve_mimic(given, transitive=True)
    return values, n


def _consts(seg, np):
    """Per-segment numpy constants, cached on the segment."""
    c = seg.__dict__.get("_np")
    if c is None:
        r0 = np.array(seg.origin_r, dtype=float)
        t0 = np.array(seg.origin_t, dtype=float)
        c = {"r0": r0, "t0": t0}
        if seg.kind == "movable" and seg.axis is not None:
            a = np.array(seg.axis, dtype=float)
            if seg.type == "prismatic":
                c["d"] = r0 @ a
            else:
                k = np.array([[0.0, -a[2], a[1]], [a[2], 0.0, -a[0]], [-a[1], a[0], 0.0]])
                # R0 * Rot(a, q) = c * R0 + s * (R0 K) + (1 - c) * (R0 a) a^T
                c["k"] = r0 @ k
                c["aa"] = np.outer(r0 @ a, a)
        seg.__dict__["_np"] = c
    return c


def _mul_const(r, m):
    """(N,3,3) @ (3,k) as one BLAS call: (N,3,k)."""
    n = r.shape[0]
    return (r.reshape(n * 3, 3) @ m).reshape(n, 3, m.shape[1])


def _child_pose(seg, rp, pp, q, np, n):
    """(R, p) of the child from the parent's (R (N,3,3), p (N,3)) and joint values q (N,) or None."""
    c = _consts(seg, np)
    if seg.kind != "movable":
        return _mul_const(rp, c["r0"]), pp + _mul_const(rp, c["t0"][:, None])[..., 0]
    if q is None:  # unresolvable mimic joint: robot_state_publisher never publishes it
        q = np.full(n, np.nan)
    if seg.type == "prismatic":
        r = _mul_const(rp, c["r0"])
        if seg.axis is None:
            return r, np.full((n, 3), np.nan)
        tp = _mul_const(rp, np.stack([c["t0"], c["d"]], axis=1))  # (N,3,2)
        return r, pp + tp[..., 0] + q[:, None] * tp[..., 1]
    if seg.axis is None:
        return np.full((n, 3, 3), np.nan), np.full((n, 3), np.nan)
    # three contiguous BLAS products, then c * A + s * B + (1 - c) * C in place
    a = _mul_const(rp, c["r0"])
    b = _mul_const(rp, c["k"])
    cc = _mul_const(rp, c["aa"])
    a -= cc
    a *= np.cos(q)[:, None, None]
    b *= np.sin(q)[:, None, None]
    a += b
    a += cc
    return a, pp + _mul_const(rp, c["t0"][:, None])[..., 0]


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
    index = {link: i for i, link in enumerate(tree.links)}
    rot = np.empty((len(index), n, 3, 3))
    pos = np.empty((len(index), n, 3))
    for r in tree.roots:
        rot[index[r]] = np.eye(3)
        pos[index[r]] = 0.0
    for seg in tree.segments:
        i, c = index[seg.parent], index[seg.child]
        rot[c], pos[c] = _child_pose(seg, rot[i], pos[i], values.get(seg.name), np, n)
    if root_frame is not None:
        if root_frame not in index:
            raise KeyError(f"frame {root_frame!r} is not a link of the model's tree")
        rr, pr = rot[index[root_frame]], pos[index[root_frame]]
        rt = np.swapaxes(rr, 1, 2)
        rot = (rt[None, :, :, :, None] * rot[:, :, None, :, :]).sum(axis=3)
        pos = (rt[None] * (pos - pr[None])[:, :, None, :]).sum(axis=3)
    big = np.empty((len(index), n, 4, 4))
    big[..., :3, :3] = rot
    big[..., :3, 3] = pos
    big[..., 3, :3] = 0.0
    big[..., 3, 3] = 1.0
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
