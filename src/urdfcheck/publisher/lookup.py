"""tf2-style lookups on the transforms robot_state_publisher would publish. Pure Python.

``lookup(model, source, target, joints)`` follows ``tf2_echo source target`` / ``lookupTransform(source,
target)``: the result's ``parent`` is `source`, its ``child`` is `target`, and its value is **the pose of
`target` expressed in `source`** (the transform that maps points from `target` coordinates to `source`
coordinates).
"""
from __future__ import annotations

from urdfcheck.core.geometry import compose, identity, inverse
from urdfcheck.publisher.kinematics import kinematic_tree, matrix_from_tq, quat_from_matrix
from urdfcheck.publisher.messages import Transform, stamp_from_ns, to_ns


class TransformLookupError(LookupError):
    """The frames are not connected, do not exist, or a joint on the path has no value."""


def _chain_matrix(segs, values, default):
    m = identity()
    for s in segs:
        if s.kind == "skipped":
            raise TransformLookupError(f"floating joint {s.name!r} ({s.parent} -> {s.child}) is never published by "
                               "robot_state_publisher: the frames are not connected in TF")
        if s.kind == "movable":
            if s.name in values:
                q = float(values[s.name])
            elif default is not None:
                q = float(default)
            else:
                raise TransformLookupError(f"no value for joint {s.name!r} ({s.parent} -> {s.child}); give it "
                                   "(robot_state_publisher publishes only joints named in a JointState)")
            t, quat = s.tq(q)
        else:
            t, quat = s.origin_t, s.origin_q
        m = compose(m, matrix_from_tq(t, quat))
    return m


def lookup_matrix(model, source: str, target: str, joints: dict | None = None, *, default: float | None = None):
    """4x4 nested tuples: pose of `target` in `source` (see module docstring)."""
    tree = kinematic_tree(model)
    known = set(tree.links)
    for f in (source, target):
        if f not in known:
            raise TransformLookupError(f"frame {f!r} does not exist in the model's tree" +
                               (f" (known: {', '.join(sorted(known)[:8])}...)" if known else ""))
    cs, ct = tree.chain(source), tree.chain(target)
    i = 0
    while i < len(cs) and i < len(ct) and cs[i] is ct[i]:
        i += 1
    root_s = cs[0].parent if cs else source
    root_t = ct[0].parent if ct else target
    if root_s != root_t:
        raise TransformLookupError(f"{source!r} and {target!r} are in different trees (roots {root_s!r}, {root_t!r})")
    values = tree.resolve_mimic(dict(joints or {}), transitive=False)
    up = _chain_matrix(cs[i:], values, default)
    down = _chain_matrix(ct[i:], values, default)
    return compose(inverse(up), down)


def lookup(model, source: str, target: str, joints: dict | None = None, *, default: float | None = None,
           stamp=0.0) -> Transform:
    """Transform with parent=`source`, child=`target`: the pose of `target` in `source` (``tf2_echo source
    target``). Mimic joints follow robot_state_publisher's rule; movable joints on the path without a value
    raise LookupError unless `default` is given."""
    m = lookup_matrix(model, source, target, joints, default=default)
    return Transform(source, target, (m[0][3], m[1][3], m[2][3]), quat_from_matrix(m),
                     stamp_from_ns(to_ns(stamp)))
