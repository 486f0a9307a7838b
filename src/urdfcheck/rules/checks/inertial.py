"""I rules: <inertial> blocks that physics engines, dynamics libraries and KDL cannot use.

The tensor checks work on the principal moments (eigenvalues of the symmetric 3x3 inertia tensor), computed
with cyclic Jacobi rotations in plain Python: exact to rounding for 3x3, no numpy on the lint path.
"""
from __future__ import annotations

import functools
import math

from urdfcheck.core.findings import Problem
from urdfcheck.core.records import TYPE_CHECKING
from urdfcheck.rules.catalogue import check, options_for

if TYPE_CHECKING:  # the checks' argument types (no import at run time)
    from collections.abc import Iterator

    from urdfcheck.model.robot import Model
    from urdfcheck.rules.engine import Context

_UNREADABLE = ("U004", "U005", "U006")
# thresholds are rule options (rules/I003.yaml, I004.yaml: rtol, atol, min_mass), defaulted by the catalogue


def _fmt(x: float, scale: float = 0.0) -> str:
    """A number for messages; rounding noise far below `scale` (the largest moment) is shown as 0."""
    if scale and abs(x) <= 1e-12 * abs(scale):
        x = 0.0
    return f"{x:.6g}"


def tensor(inertia) -> list[list[float]]:
    ixx, ixy, ixz, iyy, iyz, izz = inertia
    return [[ixx, ixy, ixz], [ixy, iyy, iyz], [ixz, iyz, izz]]


@functools.lru_cache(maxsize=32768)  # I003 and I004 ask for the same tensors; models repeat them
def principal_moments(inertia) -> tuple[float, float, float]:
    """Eigenvalues of the inertia tensor, ascending (cyclic Jacobi; converges in a handful of sweeps)."""
    inertia = tuple(inertia)
    if inertia[1] == 0.0 and inertia[2] == 0.0 and inertia[4] == 0.0:
        return tuple(sorted((inertia[0], inertia[3], inertia[5])))  # type: ignore[return-value]
    big = max(abs(v) for v in inertia)
    if not math.isfinite(big):
        return (math.nan, math.nan, math.nan)
    # Jacobi squares the entries: ixy="1e200" overflowed (OverflowError from **). Work on the tensor scaled by a
    # power of two (exact), and scale the moments back (they may then be inf: `finite_moments` says so)
    exp = math.frexp(big)[1]
    scaled = principal_moments(tuple(math.ldexp(v, -exp) for v in inertia)) if exp else None
    if scaled is not None:
        return tuple(_ldexp(m, exp) for m in scaled)  # type: ignore[return-value]
    a = tensor(inertia)
    for _ in range(50):
        off = a[0][1] ** 2 + a[0][2] ** 2 + a[1][2] ** 2
        scale = a[0][0] ** 2 + a[1][1] ** 2 + a[2][2] ** 2 + off
        if off == 0.0 or off <= 1e-32 * scale:
            break
        for p, q in ((0, 1), (0, 2), (1, 2)):
            if a[p][q] == 0.0:
                continue
            theta = (a[q][q] - a[p][p]) / (2.0 * a[p][q])
            t = math.copysign(1.0, theta) / (abs(theta) + math.sqrt(theta * theta + 1.0))
            c = 1.0 / math.sqrt(t * t + 1.0)
            s = t * c
            for k in range(3):  # A <- A J
                akp, akq = a[k][p], a[k][q]
                a[k][p] = c * akp - s * akq
                a[k][q] = s * akp + c * akq
            for k in range(3):  # A <- J^T A
                apk, aqk = a[p][k], a[q][k]
                a[p][k] = c * apk - s * aqk
                a[q][k] = s * apk + c * aqk
    return tuple(sorted((a[0][0], a[1][1], a[2][2])))  # type: ignore[return-value]


def _ldexp(x: float, exp: int) -> float:
    try:
        return math.ldexp(x, exp)
    except OverflowError:
        return math.copysign(math.inf, x)


def finite_moments(moments) -> bool:
    return all(math.isfinite(m) for m in moments)


def _too_large(link, inertial) -> Problem:
    big = max((abs(v) for v in inertial.inertia), default=0.0)
    return Problem(f"inertia tensor of link {link.name!r} cannot be judged: its entries (up to {_fmt(big)} kg m²) are "
                   "so large that its principal moments overflow double precision; no rigid body has this inertia "
                   "(check the units)", at=inertial.inertia_loc or inertial)


def _unreadable_locs(model) -> set:
    """Where the builder reported an unreadable value (for <inertia> it substituted 0.0)."""
    return {i.loc for i in model.issues if i.code in _UNREADABLE}


def _inertials(model):
    for link in model.link_list:
        if link.inertial is not None:
            yield link, link.inertial


def _tensors(model, ctx):
    """(link, inertial, ascending principal moments, atol) for the tensors I003/I004 judge."""
    atol = float(ctx.options["atol"])
    min_mass = float(ctx.options["min_mass"])
    unreadable = _unreadable_locs(model)
    for link in model.link_list:
        inertial = link.inertial
        if inertial is None or inertial.inertia is None or (unreadable and inertial.inertia_loc in unreadable):
            continue
        m = inertial.mass
        if m is not None and m <= 0 and not any(inertial.inertia):
            continue  # massless written as zeros: I002's concern
        if m is not None and 0 < m < min_mass:
            continue  # a placeholder mass: its tensor is a placeholder too and cannot affect the dynamics
        yield link, inertial, principal_moments(inertial.inertia), atol


@check("I001")
def incomplete_inertial(model: Model, ctx: Context) -> Iterator[Problem]:
    for link, inertial in _inertials(model):
        missing = []
        if inertial.mass_loc is None:
            missing.append("<mass>")
        if inertial.inertia is None:
            missing.append("<inertia>")
        if not missing:
            continue
        what = " and ".join(missing)
        yield Problem(
            f"<inertial> of link {link.name!r} has no {what}: urdfdom logs an error and stops reading the link "
            "there, so its visuals and collisions are silently lost while the model still loads (check_urdf "
            "exits 0). Give both <mass> and <inertia>, or remove <inertial> for a massless frame",
            at=inertial)


@check("I002")
def non_positive_mass(model: Model, ctx: Context) -> Iterator[Problem]:
    for link, inertial in _inertials(model):
        m = inertial.mass
        if m is None:
            continue
        at = inertial.mass_loc or inertial
        if m < 0:
            yield Problem(f"link {link.name!r} has negative mass {_fmt(m)} kg", at=at)
            continue
        if m > 0:
            continue
        # m == 0
        has_tensor = inertial.inertia is not None and any(v != 0.0 for v in inertial.inertia)
        parent = model.parent_joint.get(link.name)
        if has_tensor:
            yield Problem(
                f"link {link.name!r} has mass 0 but a non-zero inertia tensor: no body has rotational inertia "
                "without mass; give it its real mass, or remove <inertial> if the link is a massless frame",
                at=at)
        elif parent is not None and parent.type != "fixed":
            yield Problem(
                f"link {link.name!r} has mass 0 on {parent.type} joint {parent.name!r}: Gazebo's URDF import drops "
                "a zero-mass link together with its child links and joints, and with nothing massive below it "
                "the joint has no inertia (singular joint-space mass matrix in Pinocchio and KDL dynamics). Give "
                "it its real mass", at=at)
        # zero mass and zero tensor on a fixed joint or on the root: the common "massless frame" idiom (optical
        # frames, tool points, base_footprint). Gazebo, Pinocchio and MuJoCo merge it into its neighbour, so it
        # is harmless and not reported.


@check("I003")
def inertia_not_positive_definite(model: Model, ctx: Context) -> Iterator[Problem]:
    rtol = float(ctx.options["rtol"])
    allow_singular = bool(ctx.options["allow_singular"])
    for link, inertial, moments, atol in _tensors(model, ctx):
        if not finite_moments(moments):
            yield _too_large(link, inertial)
            continue
        lo, hi = moments[0], moments[2]
        scale = max(abs(hi), abs(lo))
        if scale <= atol:
            lo = hi = 0.0  # an all-zero tensor written with floating-point noise: a point mass
        at = inertial.inertia_loc or inertial
        if lo < -max(rtol * scale, atol):
            shown = ", ".join(_fmt(x, scale) for x in moments)
            yield Problem(
                f"inertia tensor of link {link.name!r} is not positive definite: principal moments {shown} "
                "(a negative moment of inertia does not exist; check signs of the products of inertia and the "
                "units)", at=at)
        elif not allow_singular and lo <= max(rtol * abs(hi), atol):
            shown = ", ".join(_fmt(x, scale) for x in moments)
            kind = "all principal moments are zero (a point mass)" if hi <= atol else \
                f"a principal moment is zero ({shown}: a thin rod or plate)"
            yield Problem(f"inertia tensor of link {link.name!r} is singular: {kind}", at=at)


@check("I004")
def inertia_triangle_inequality(model: Model, ctx: Context) -> Iterator[Problem]:
    rtol = float(ctx.options["rtol"])
    i003_rtol = float(options_for(("I003",), ctx.selection.options)["rtol"])  # what I003 reports, skipped here
    for link, inertial, (a, b, c), atol in _tensors(model, ctx):
        if not finite_moments((a, b, c)):
            continue  # I003's finding
        if c <= atol or a < -max(i003_rtol * c, atol):
            continue  # zero tensor or not positive semi-definite: I003's finding
        if a + b >= c - max(rtol * c, atol):
            continue
        diag = (inertial.inertia[0], inertial.inertia[3], inertial.inertia[5])
        on_diag = all(v == 0.0 for v in (inertial.inertia[1], inertial.inertia[2], inertial.inertia[4]))
        where = (f"ixx, iyy, izz = {', '.join(_fmt(x) for x in diag)}" if on_diag
                 else f"principal moments {_fmt(a, c)}, {_fmt(b, c)}, {_fmt(c)}")
        yield Problem(
            f"inertia of link {link.name!r} violates the triangle inequality: {where}; the two smaller principal "
            f"moments add up to {_fmt(a + b, c)} < {_fmt(c)} (no rigid body can have this tensor; MuJoCo, Drake "
            "and gz-sim reject it)", at=inertial.inertia_loc or inertial)


@check("I005")
def root_link_inertia(model: Model, ctx: Context) -> Iterator[Problem]:
    root = model.root
    if root is None:
        return
    link = model.links.get(root)
    if link is None or link.inertial is None:
        return
    yield Problem(
        f"root link {root!r} has an <inertial>: KDL (robot_state_publisher, kdl_parser) warns that it does not "
        "support a root link with an inertia and ignores it. Add a massless root such as base_footprint "
        f"with a fixed joint to {root!r} if a KDL-based dynamics solver needs this mass",
        at=link.inertial)
