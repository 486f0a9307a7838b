"""Small pure-Python rigid-transform helpers (4x4 as nested tuples), for the lint path where numpy is not loaded.

URDF conventions: rpy are fixed-axis roll about x, then pitch about y, then yaw about z, i.e. R = Rz(y) Ry(p) Rx(r).
An <origin> (model.robot.Pose) gives its rotation as rpy or, from URDF 1.1, as quat_xyzw; `origin_quaternion`,
`origin_rotation` and `origin_matrix` are the one place that turns either into a rotation.
"""
from __future__ import annotations

import math

Mat = tuple  # 4 rows of 4 floats


def identity() -> Mat:
    return ((1.0, 0.0, 0.0, 0.0), (0.0, 1.0, 0.0, 0.0), (0.0, 0.0, 1.0, 0.0), (0.0, 0.0, 0.0, 1.0))


def rpy_matrix(r: float, p: float, y: float) -> tuple:
    cr, sr = math.cos(r), math.sin(r)
    cp, sp = math.cos(p), math.sin(p)
    cy, sy = math.cos(y), math.sin(y)
    return (
        (cy * cp, cy * sp * sr - sy * cr, cy * sp * cr + sy * sr),
        (sy * cp, sy * sp * sr + cy * cr, sy * sp * cr - cy * sr),
        (-sp, cp * sr, cp * cr),
    )


def from_rt(rot, xyz) -> Mat:
    return (
        (rot[0][0], rot[0][1], rot[0][2], float(xyz[0])),
        (rot[1][0], rot[1][1], rot[1][2], float(xyz[1])),
        (rot[2][0], rot[2][1], rot[2][2], float(xyz[2])),
        (0.0, 0.0, 0.0, 1.0),
    )


def quat_from_rpy(r: float, p: float, y: float) -> tuple[float, float, float, float]:
    """urdfdom's Rotation::setFromRPY (then normalised), as (x, y, z, w)."""
    phi, the, psi = r / 2.0, p / 2.0, y / 2.0
    sphi, cphi = math.sin(phi), math.cos(phi)
    sthe, cthe = math.sin(the), math.cos(the)
    spsi, cpsi = math.sin(psi), math.cos(psi)
    x = sphi * cthe * cpsi - cphi * sthe * spsi
    yy = cphi * sthe * cpsi + sphi * cthe * spsi
    z = cphi * cthe * spsi - sphi * sthe * cpsi
    w = cphi * cthe * cpsi + sphi * sthe * spsi
    return normalized_quaternion(x, yy, z, w)


def normalized_quaternion(x: float, y: float, z: float, w: float) -> tuple[float, float, float, float]:
    """urdfdom's Rotation::normalize: divided by its norm, no tolerance; a zero quaternion becomes identity
    (urdfdom_headers pose.h, `if (squared_norm <= 0.0)`); NaN stays NaN."""
    sq = x * x + y * y + z * z + w * w
    if sq <= 0.0:
        return (0.0, 0.0, 0.0, 1.0)
    s = math.sqrt(sq)
    return (x / s, y / s, z / s, w / s)


def quat_matrix(x: float, y: float, z: float, w: float) -> tuple:
    """3x3 rotation of a unit quaternion (KDL::Rotation::Quaternion)."""
    x2, y2, z2, w2 = x * x, y * y, z * z, w * w
    return (
        (w2 + x2 - y2 - z2, 2 * x * y - 2 * w * z, 2 * x * z + 2 * w * y),
        (2 * x * y + 2 * w * z, w2 - x2 + y2 - z2, 2 * y * z - 2 * w * x),
        (2 * x * z - 2 * w * y, 2 * y * z + 2 * w * x, w2 - x2 - y2 + z2),
    )


def matrix_from_tq(t, q) -> Mat:
    """4x4 from a translation and a quaternion (x, y, z, w)."""
    r = quat_matrix(*q)
    return (
        (r[0][0], r[0][1], r[0][2], float(t[0])),
        (r[1][0], r[1][1], r[1][2], float(t[1])),
        (r[2][0], r[2][1], r[2][2], float(t[2])),
        (0.0, 0.0, 0.0, 1.0),
    )


def origin_quaternion(pose) -> tuple[float, float, float, float]:
    """The rotation urdfdom holds for an <origin>: quat_xyzw normalised when the model's URDF version read
    one (the builder leaves `quat` None otherwise), else setFromRPY(rpy)."""
    q = pose.quat
    if q is not None:
        return normalized_quaternion(*q)
    return quat_from_rpy(*pose.rpy)


def origin_rotation(pose) -> tuple:
    """3x3 rotation of an <origin>."""
    q = pose.quat
    if q is not None:
        return quat_matrix(*normalized_quaternion(*q))
    return rpy_matrix(*pose.rpy)


def origin_matrix(pose) -> Mat:
    """4x4 transform of an <origin>."""
    return from_rt(origin_rotation(pose), pose.xyz)


def compose(a: Mat, b: Mat) -> Mat:
    return tuple(
        tuple(sum(a[i][k] * b[k][j] for k in range(4)) for j in range(4)) for i in range(4)
    )


def inverse(m: Mat) -> Mat:
    r = [[m[j][i] for j in range(3)] for i in range(3)]  # transpose
    t = [-(r[i][0] * m[0][3] + r[i][1] * m[1][3] + r[i][2] * m[2][3]) for i in range(3)]
    return from_rt(r, t)


def translation(m: Mat) -> tuple[float, float, float]:
    return (m[0][3], m[1][3], m[2][3])


def rotate(m: Mat, v) -> tuple[float, float, float]:
    return tuple(m[i][0] * v[0] + m[i][1] * v[1] + m[i][2] * v[2] for i in range(3))


def norm(v) -> float:
    return math.sqrt(sum(c * c for c in v))


def quaternion(m: Mat) -> tuple[float, float, float, float]:
    """(x, y, z, w) of the rotation part, w >= 0."""
    tr = m[0][0] + m[1][1] + m[2][2]
    if tr > 0:
        s = math.sqrt(tr + 1.0) * 2
        w, x = 0.25 * s, (m[2][1] - m[1][2]) / s
        y, z = (m[0][2] - m[2][0]) / s, (m[1][0] - m[0][1]) / s
    elif m[0][0] > m[1][1] and m[0][0] > m[2][2]:
        s = math.sqrt(1.0 + m[0][0] - m[1][1] - m[2][2]) * 2
        w, x = (m[2][1] - m[1][2]) / s, 0.25 * s
        y, z = (m[0][1] + m[1][0]) / s, (m[0][2] + m[2][0]) / s
    elif m[1][1] > m[2][2]:
        s = math.sqrt(1.0 + m[1][1] - m[0][0] - m[2][2]) * 2
        w, x = (m[0][2] - m[2][0]) / s, (m[0][1] + m[1][0]) / s
        y, z = 0.25 * s, (m[1][2] + m[2][1]) / s
    else:
        s = math.sqrt(1.0 + m[2][2] - m[0][0] - m[1][1]) * 2
        w, x = (m[1][0] - m[0][1]) / s, (m[0][2] + m[2][0]) / s
        y, z = (m[1][2] + m[2][1]) / s, 0.25 * s
    if w < 0:
        x, y, z, w = -x, -y, -z, -w
    return (x, y, z, w)


def rpy(m: Mat) -> tuple[float, float, float]:
    """Roll, pitch, yaw of the rotation part (URDF convention)."""
    pitch = math.atan2(-m[2][0], math.hypot(m[0][0], m[1][0]))
    if abs(math.cos(pitch)) < 1e-12:
        return (0.0, pitch, math.atan2(-m[0][1], m[1][1]))
    return (math.atan2(m[2][1], m[2][2]), pitch, math.atan2(m[1][0], m[0][0]))
