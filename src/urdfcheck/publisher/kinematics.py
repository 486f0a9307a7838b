"""The model seen the way kdl_parser and robot_state_publisher see it. Pure Python (no numpy).

kdl_parser turns every URDF joint into a KDL segment whose pose for a joint value ``q`` is

    origin * motion(q)

where ``origin`` is the joint's <origin> (rpy -> quaternion as urdfdom's ``Rotation::setFromRPY`` does, or, from
URDF 1.1, quat_xyzw normalised as ``Rotation::initQuaternion`` does; then ``KDL::Rotation::Quaternion``) and
``motion`` is a rotation by ``q`` about the *normalised* axis (revolute, continuous) or a translation by ``q``
along it (prismatic): ``KDL::Joint`` divides the axis by its norm, so a zero axis gives NaN everywhere
(revolute) or a NaN translation (prismatic). Every other type (fixed,
planar, floating, unknown) becomes ``KDL::Joint::None``; robot_state_publisher then publishes it as a fixed
transform at the origin, except floating joints, which it skips (no transform at all).

Quaternions come out with the sign ``KDL::Rotation::GetQuaternion`` gives them (w > 0 when the trace is
positive, otherwise the largest of x, y, z positive), so that transforms match robot_state_publisher's
messages value for value.
"""
from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass, field

from urdfcheck.core import geometry
from urdfcheck.publisher.messages import Stamp, Transform

MOVABLE = ("revolute", "continuous", "prismatic")
KNOWN_TYPES = ("revolute", "continuous", "prismatic", "fixed", "floating", "planar")
NAN = float("nan")


# --- small rotation helpers ---------------------------------------------------------------------------------
# urdfdom's setFromRPY and KDL::Rotation::Quaternion; an <origin>'s rotation (rpy or quat_xyzw) is turned into a
# quaternion in one place, core.geometry.origin_quaternion
quat_from_rpy = geometry.quat_from_rpy
rot_from_quat = geometry.quat_matrix
matrix_from_tq = geometry.matrix_from_tq


def kdl_sign(x: float, y: float, z: float, w: float) -> tuple[float, float, float, float]:
    """Flip a unit quaternion to the sign KDL::Rotation::GetQuaternion would produce."""
    if 4.0 * w * w - 1.0 > 1e-12:  # trace of the matrix > epsilon
        neg = w < 0.0
    else:
        xx, yy, zz = x * x, y * y, z * z
        if xx > yy and xx > zz:
            neg = x < 0.0
        elif yy > zz:
            neg = y < 0.0
        else:
            neg = z < 0.0
    if neg:
        return (-x, -y, -z, -w)
    return (x, y, z, w)


def quat_from_matrix(m) -> tuple[float, float, float, float]:
    """KDL::Rotation::GetQuaternion of the rotation part of a 3x3 or 4x4 matrix."""
    trace = m[0][0] + m[1][1] + m[2][2]
    if trace > 1e-12:
        s = 0.5 / math.sqrt(trace + 1.0)
        return ((m[2][1] - m[1][2]) * s, (m[0][2] - m[2][0]) * s, (m[1][0] - m[0][1]) * s, 0.25 / s)
    if m[0][0] > m[1][1] and m[0][0] > m[2][2]:
        s = 2.0 * math.sqrt(1.0 + m[0][0] - m[1][1] - m[2][2])
        return (0.25 * s, (m[0][1] + m[1][0]) / s, (m[0][2] + m[2][0]) / s, (m[2][1] - m[1][2]) / s)
    if m[1][1] > m[2][2]:
        s = 2.0 * math.sqrt(1.0 + m[1][1] - m[0][0] - m[2][2])
        return ((m[0][1] + m[1][0]) / s, 0.25 * s, (m[1][2] + m[2][1]) / s, (m[0][2] - m[2][0]) / s)
    s = 2.0 * math.sqrt(1.0 + m[2][2] - m[0][0] - m[1][1])
    if s == 0.0 or s != s:
        return (NAN, NAN, NAN, NAN)
    return ((m[0][2] + m[2][0]) / s, (m[1][2] + m[2][1]) / s, 0.25 * s, (m[1][0] - m[0][1]) / s)


def rpy_from_matrix(m) -> tuple[float, float, float]:
    """Roll, pitch, yaw (fixed axes x, y, z; the convention of URDF and tf2's getRPY). At gimbal lock yaw = 0."""
    if abs(m[2][0]) >= 1.0:
        yaw = 0.0
        if m[2][0] < 0:
            delta = math.atan2(m[0][1], m[0][2])
            return (delta, math.pi / 2, yaw)
        delta = math.atan2(-m[0][1], -m[0][2])
        return (delta, -math.pi / 2, yaw)
    pitch = -math.asin(m[2][0])
    cp = math.cos(pitch)
    return (math.atan2(m[2][1] / cp, m[2][2] / cp), pitch, math.atan2(m[1][0] / cp, m[0][0] / cp))


# --- segments ---------------------------------------------------------------------------------------------
@dataclass
class Segment:
    """One URDF joint as a KDL segment (parent link -> child link)."""

    joint: object  # urdfcheck.model.robot.Joint
    name: str
    parent: str
    child: str
    type: str
    kind: str  # "movable" (published on /tf), "fixed" (static), "skipped" (floating: not published)
    origin_t: tuple
    origin_q: tuple  # (x, y, z, w), KDL sign
    origin_r: tuple  # 3x3
    axis: tuple | None  # normalised axis in the joint frame; None: zero (or non-finite) axis -> NaN
    raw_axis: tuple

    @property
    def zero_axis(self) -> bool:
        return self.kind == "movable" and self.axis is None

    def tq(self, q: float) -> tuple[tuple, tuple]:
        """(translation, quaternion) of the child in the parent for joint value q (fixed: q ignored)."""
        if self.kind != "movable":
            return self.origin_t, self.origin_q
        return self._motion(q)

    def _motion(self, q: float):
        t0, (x0, y0, z0, w0) = self.origin_t, self.origin_q
        if self.axis is None:
            if self.type == "prismatic":
                return (NAN, NAN, NAN), self.origin_q
            return (NAN, NAN, NAN), (NAN, NAN, NAN, NAN)
        ax, ay, az = self.axis
        if self.type == "prismatic":
            r = self.origin_r
            return (
                t0[0] + (r[0][0] * ax + r[0][1] * ay + r[0][2] * az) * q,
                t0[1] + (r[1][0] * ax + r[1][1] * ay + r[1][2] * az) * q,
                t0[2] + (r[2][0] * ax + r[2][1] * ay + r[2][2] * az) * q,
            ), self.origin_q
        s, c = _sincos(0.5 * q)
        quat = (
            x0 * c + (w0 * ax + y0 * az - z0 * ay) * s,
            y0 * c + (w0 * ay + z0 * ax - x0 * az) * s,
            z0 * c + (w0 * az + x0 * ay - y0 * ax) * s,
            w0 * c - (x0 * ax + y0 * ay + z0 * az) * s,
        )
        return t0, kdl_sign(*quat)

    def matrix(self, q: float = 0.0) -> tuple:
        t, quat = self.tq(q)
        return matrix_from_tq(t, quat)

    def publisher_fn(self, parent_frame: str, child_frame: str) -> Callable[[float, Stamp], Transform]:
        """A fast closure q, stamp -> Transform for the hot path of StatePublisher."""
        new = tuple.__new__
        T = Transform
        if self.kind != "movable":
            t, quat = self.origin_t, self.origin_q

            def fixed(q, stamp):
                return new(T, (parent_frame, child_frame, t, quat, stamp))

            return fixed
        if self.axis is None:
            t, quat = self._motion(0.0)

            def nan(q, stamp):
                return new(T, (parent_frame, child_frame, t, quat, stamp))

            return nan
        t0 = self.origin_t
        x0, y0, z0, w0 = self.origin_q
        ax, ay, az = self.axis
        if self.type == "prismatic":
            r = self.origin_r
            px, py, pz = t0
            dx = r[0][0] * ax + r[0][1] * ay + r[0][2] * az
            dy = r[1][0] * ax + r[1][1] * ay + r[1][2] * az
            dz = r[2][0] * ax + r[2][1] * ay + r[2][2] * az
            quat = self.origin_q

            def prismatic(q, stamp):
                return new(T, (parent_frame, child_frame, (px + dx * q, py + dy * q, pz + dz * q), quat, stamp))

            return prismatic
        kx = w0 * ax + y0 * az - z0 * ay
        ky = w0 * ay + z0 * ax - x0 * az
        kz = w0 * az + x0 * ay - y0 * ax
        kw = -(x0 * ax + y0 * ay + z0 * az)
        sin, cos = math.sin, math.cos

        def revolute(q, stamp):
            h = 0.5 * q
            try:
                s = sin(h)
                c = cos(h)
            except ValueError:  # an infinite position: C's sin gives NaN, as KDL then publishes
                s = c = NAN
            x = x0 * c + kx * s
            y = y0 * c + ky * s
            z = z0 * c + kz * s
            w = w0 * c + kw * s
            # KDL::Rotation::GetQuaternion sign (see kdl_sign), inlined for speed
            if 4.0 * w * w - 1.0 > 1e-12:
                neg = w < 0.0
            else:
                xx, yy, zz = x * x, y * y, z * z
                if xx > yy and xx > zz:
                    neg = x < 0.0
                elif yy > zz:
                    neg = y < 0.0
                else:
                    neg = z < 0.0
            if neg:
                return new(T, (parent_frame, child_frame, t0, (-x, -y, -z, -w), stamp))
            return new(T, (parent_frame, child_frame, t0, (x, y, z, w), stamp))

        return revolute


def make_segment(joint) -> Segment:
    xyz = tuple(float(v) for v in (joint.origin.xyz or (0.0, 0.0, 0.0)))
    q0 = kdl_sign(*geometry.origin_quaternion(joint.origin))
    r0 = rot_from_quat(*q0)
    jtype = joint.type
    if jtype in MOVABLE:
        kind = "movable"
    elif jtype == "floating":
        kind = "skipped"
    else:
        kind = "fixed"
    raw = tuple(float(v) for v in (joint.axis or (1.0, 0.0, 0.0)))
    axis = None
    n = math.hypot(*raw)  # scaled like KDL::Vector::Norm: no underflow for tiny axes; exactly 0 only for 0
    if n != 0.0 and math.isfinite(n):
        axis = (raw[0] / n, raw[1] / n, raw[2] / n)
    return Segment(joint, joint.name, joint.parent, joint.child, jtype, kind, xyz, q0, r0, axis, raw)


# --- the tree ---------------------------------------------------------------------------------------------
@dataclass(frozen=True)
class Note:
    """Something robot_state_publisher does with this model that a reader may not expect."""

    code: str  # "zero-axis", "floating", "planar", "unknown-type", "mimic-order", "mimic-source", ...
    joint: str
    message: str
    loc: object = None


@dataclass
class KinematicTree:
    model: object
    roots: tuple[str, ...]
    segments: list[Segment]  # depth first from the roots, document order
    by_joint: dict[str, Segment]
    by_child: dict[str, Segment]
    movable: dict[str, Segment]
    fixed: dict[str, Segment]
    skipped: dict[str, Segment]
    links: list[str]  # every link reached, parents before children
    mimics: list[tuple[str, str, float, float]]  # (joint, source, multiplier, offset), sorted by joint name
    notes: list[Note] = field(default_factory=list)
    unreachable: tuple[str, ...] = ()  # joints not reached from any root

    @property
    def tf_roots(self) -> list[str]:
        """Roots of the trees robot_state_publisher's TF output forms (a floating joint starts a new one)."""
        out = list(self.roots)
        out += [s.child for s in self.segments if s.kind == "skipped"]
        return out

    def tf_root_of(self, link: str) -> str:
        """The root of `link`'s tree in robot_state_publisher's TF output."""
        roots = self.__dict__.get("_tf_root_map")
        if roots is None:
            roots = {r: r for r in self.roots}
            for s in self.segments:  # parents first
                roots[s.child] = s.child if s.kind == "skipped" else roots.get(s.parent, s.parent)
            self.__dict__["_tf_root_map"] = roots
        return roots.get(link, link)

    def chain(self, link: str) -> list[Segment]:
        """Segments from the model root down to `link` (across floating joints)."""
        out = []
        seg = self.by_child.get(link)
        seen = set()
        while seg is not None and seg.name not in seen:
            seen.add(seg.name)
            out.append(seg)
            seg = self.by_child.get(seg.parent)
        out.reverse()
        return out

    def active_joints(self) -> list[str]:
        """Movable joints without <mimic>, in document order: the independent configuration variables."""
        return [s.name for s in self._doc_order() if s.kind == "movable" and s.joint.mimic is None]

    def movable_joints(self) -> list[str]:
        return [s.name for s in self._doc_order() if s.kind == "movable"]

    def _doc_order(self) -> list[Segment]:
        order = {j.name: i for i, j in reversed(list(enumerate(self.model.joint_list)))}
        return sorted(self.segments, key=lambda s: order.get(s.name, 0))

    def resolve_mimic(self, values: dict, *, transitive: bool = True) -> dict:
        """Joint values with mimic joints filled in.

        ``transitive=False``: robot_state_publisher's rule: in the order of the mimic joints' names, a mimic
        joint absent from `values` gets ``source * multiplier + offset`` if its *direct* source is present
        (given, or filled earlier in that order). ``transitive=True``: the source is resolved first, however
        deep the chain (the kinematic meaning of the URDF); unresolvable joints (cycle, source that is not a
        joint or not movable and not given) are left out.
        """
        out = dict(values)
        if not transitive:
            for name, src, mult, off in self.mimics:
                if name not in out and src in out:
                    out[name] = out[src] * mult + off
            return out
        info = {name: (src, mult, off) for name, src, mult, off in self.mimics}
        state: dict[str, int] = {}

        def get(name):
            if name in out:
                return out[name]
            if name not in info or state.get(name) == 1:
                return None
            state[name] = 1
            src, mult, off = info[name]
            v = get(src)
            state[name] = 2
            if v is None:
                return None
            out[name] = v * mult + off
            return out[name]

        for name in info:
            get(name)
        return out


def kinematic_tree(model) -> KinematicTree:
    """The (cached) KDL view of a Model."""
    cache = model.__dict__.get("_publisher_tree")
    if cache is not None:
        return cache
    tree = _build_tree(model)
    try:
        object.__setattr__(model, "_publisher_tree", tree)
    except (AttributeError, TypeError):  # pragma: no cover - models without a __dict__
        pass
    return tree


def _build_tree(model) -> KinematicTree:
    roots = tuple(model.roots)
    parent_joint = model.parent_joint
    segments: list[Segment] = []
    links: list[str] = []
    seen_links: set[str] = set()
    reached: set[str] = set()
    for root in roots:
        stack = [root]
        while stack:
            name = stack.pop()
            if name in seen_links:
                continue
            seen_links.add(name)
            links.append(name)
            kids = []
            for j in model.child_joints.get(name, ()):
                if j.child is None or parent_joint.get(j.child) is not j or j.child in seen_links:
                    continue
                if j.name in reached:
                    continue
                reached.add(j.name)
                seg = make_segment(j)
                segments.append(seg)
                kids.append(j.child)
            stack.extend(reversed(kids))
    # depth-first order of segments (parents before children) follows the link order
    pos = {name: i for i, name in enumerate(links)}
    segments.sort(key=lambda s: pos.get(s.child, 0))
    by_joint = {s.name: s for s in segments}
    by_child = {s.child: s for s in segments}
    movable = {s.name: s for s in segments if s.kind == "movable"}
    fixed = {s.name: s for s in segments if s.kind == "fixed"}
    skipped = {s.name: s for s in segments if s.kind == "skipped"}
    mimics = sorted(
        (j.name, j.mimic.joint, float(j.mimic.multiplier if j.mimic.multiplier is not None else 1.0),
         float(j.mimic.offset if j.mimic.offset is not None else 0.0))
        for j in model.joints.values() if j.mimic is not None
    )
    unreachable = tuple(j.name for j in model.joints.values() if j.name not in by_joint)
    tree = KinematicTree(model, roots, segments, by_joint, by_child, movable, fixed, skipped, links, mimics,
                         [], unreachable)
    tree.notes.extend(_notes(model, tree))
    return tree


def _notes(model, tree: KinematicTree):
    if len(tree.roots) > 1:
        yield Note("multiple-roots", "", f"the model has {len(tree.roots)} root links "
                   f"({', '.join(tree.roots[:4])}); urdfdom refuses it, so robot_state_publisher would not start",
                   model.loc)
    for s in tree.segments:
        j = s.joint
        if s.zero_axis:
            yield Note("zero-axis", s.name, f"joint {s.name!r} has a zero axis: KDL normalises it to NaN, so "
                       "robot_state_publisher publishes " +
                       ("a NaN translation" if s.type == "prismatic" else "NaN translation and rotation") +
                       f" for {s.child!r}", j.axis_loc or j.loc)
        elif s.type == "floating":
            yield Note("floating", s.name, f"floating joint {s.name!r}: robot_state_publisher publishes no "
                       f"transform for it, so {s.child!r} and its subtree form a separate TF tree", j.loc)
        elif s.type == "planar":
            yield Note("planar", s.name, f"planar joint {s.name!r}: kdl_parser makes it fixed, so "
                       "robot_state_publisher publishes it once as a static transform at its origin and "
                       "ignores joint states for it", j.loc)
        elif s.type not in KNOWN_TYPES:
            yield Note("unknown-type", s.name, f"joint {s.name!r} has unknown type {s.type!r}: urdfdom "
                       "refuses the model (robot_state_publisher would not start); treated as fixed", j.loc)
    # mimic joints robot_state_publisher can never publish from a message naming only independent joints
    available = set(tree.active_joints())
    for name, src, _m, _o in tree.mimics:
        j = model.joints.get(name)
        seg = tree.by_joint.get(name)
        if seg is not None and seg.kind != "movable":
            yield Note("mimic-not-movable", name, f"joint {name!r} is {seg.type} but has <mimic>: "
                       "robot_state_publisher never publishes a transform for it from joint states",
                       j.mimic.loc if j is not None else None)
            continue
        if src not in model.joints:
            yield Note("mimic-source", name, f"mimic joint {name!r} follows {src!r}, which is not a joint: "
                       "robot_state_publisher never publishes it", j.mimic.loc if j is not None else None)
            continue
        src_seg = tree.by_joint.get(src)
        if src_seg is not None and src_seg.kind != "movable":
            yield Note("mimic-source", name, f"mimic joint {name!r} follows {src_seg.type} joint {src!r}, which "
                       "never appears in joint states: robot_state_publisher never publishes it",
                       j.mimic.loc if j is not None else None)
    # ordering: with only the independent joints in the message, which mimic joints get a value?
    got = tree.resolve_mimic({n: 0.0 for n in available}, transitive=False)
    full = tree.resolve_mimic({n: 0.0 for n in available}, transitive=True)
    for name, src, _m, _o in tree.mimics:
        if name in full and name not in got:
            j = model.joints.get(name)
            yield Note("mimic-order", name, f"mimic joint {name!r} follows mimic joint {src!r}, whose name sorts "
                       "after it: robot_state_publisher fills mimic joints in name order from the message "
                       f"and values filled before, so {name!r} is never published (unless the message names it)",
                       j.mimic.loc if j is not None else None)


def _sincos(h: float) -> tuple[float, float]:
    """sin and cos as C gives them: NaN for an infinite angle (Python raises ValueError)."""
    try:
        return math.sin(h), math.cos(h)
    except ValueError:
        return NAN, NAN
