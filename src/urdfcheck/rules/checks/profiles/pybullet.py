"""PyBullet: Bullet's URDF importer (bulletphysics/bullet3 examples/Importers/ImportURDFDemo/UrdfParser.cpp,
BulletUrdfImporter.cpp, URDF2Bullet.cpp).

UrdfParser::parseLink: a link without <inertial> gets mass 1 and inertia 1 1 1 ("No inertial data for link,
using mass=1, localinertiadiagonal = 1,1,1, identity local inertial frame"), the root link too in the default
free-base load (useFixedBase=False); a link named "world" stays massless. BulletURDFImporter::getMassAndInertia:
unless loadURDF is given flags=URDF_USE_INERTIA_FROM_FILE, the inertia tensor is recomputed from the collision
shapes (calculateLocalInertia) and the URDF's <inertia> is ignored. Measured with PyBullet 3.2
(tests/differential.py): <mimic> is never read, a floating joint becomes fixed, inverted limits are no limit."""
from __future__ import annotations

from urdfcheck.core.records import TYPE_CHECKING
from urdfcheck.rules.catalogue import check
from urdfcheck.rules.checks.profiles.common import names, speak

if TYPE_CHECKING:  # the checks' argument types (no import at run time)
    from collections.abc import Iterator

    from urdfcheck.core.findings import Problem
    from urdfcheck.model.robot import Model
    from urdfcheck.rules.engine import Context


@check("P050")
def default_mass(model: Model, ctx: Context) -> Iterator[Problem]:
    if "pybullet" not in ctx.profiles:
        return
    # the root too: loadURDF's default is a free base, and the root's 1 kg moves with the robot (measured); only
    # a link named "world" stays massless
    bare = [lk for lk in model.link_list if lk.inertial is None and lk.name != "world"]
    if bare:
        yield speak(ctx, ("pybullet",),
                    f"PyBullet gives {len(bare)} link(s) without <inertial> a mass of 1 kg and inertia 1, 1, 1 "
                    f"(UrdfParser.cpp: \"No inertial data for link, using mass=1\"): {names([b.name for b in bare])}; "
                    "a massless sensor frame becomes a 1 kg body", bare[0])


@check("P051")
def inertia_recomputed(model: Model, ctx: Context) -> Iterator[Problem]:
    if "pybullet" not in ctx.profiles:
        return
    given = [lk for lk in model.link_list if lk.inertial is not None and lk.inertial.inertia is not None
             and not same_as_bullet(lk)]
    if given:
        yield speak(ctx, ("pybullet",),
                    f"PyBullet ignores the <inertia> of {len(given)} link(s) unless loadURDF gets "
                    "flags=p.URDF_USE_INERTIA_FROM_FILE: it recomputes each tensor from the collision shapes "
                    f"(BulletURDFImporter getMassAndInertia, calculateLocalInertia): {names([g.name for g in given])}",
                    given[0].inertial)


def _still(pose) -> bool:
    return pose.quat is None and not any(pose.xyz) and not any(pose.rpy)


def same_as_bullet(link) -> bool:
    """Is the written tensor what Bullet computes anyway? One box or sphere collision at the link frame, an inertial
    frame without rotation and no products of inertia: Bullet's btBoxShape/btSphereShape calculateLocalInertia is
    the solid's exact tensor (measured with PyBullet 3.2: a 0.1 x 0.2 x 0.3 box of 2 kg gives 0.021667, 0.016667,
    0.008333). Anything else (a cylinder, a mesh, an offset or several shapes: a compound's bounding box with its
    collision margin) differs from the written tensor and is reported."""
    import math

    inr = link.inertial
    if len(link.collisions) != 1 or inr.mass is None or not _still(link.collisions[0].origin):
        return False
    if inr.origin.quat is not None or any(inr.origin.rpy):
        return False
    xx, xy, xz, yy, yz, zz = inr.inertia
    if xy or xz or yz:
        return False
    g, m = link.collisions[0].geometry, inr.mass
    if g is None:
        return False
    if g.kind == "box" and g.size:
        a, b, c = (x * x for x in g.size)
        want = (m / 12 * (b + c), m / 12 * (a + c), m / 12 * (a + b))
    elif g.kind == "sphere" and g.radius is not None:
        want = (0.4 * m * g.radius * g.radius,) * 3
    else:
        return False
    return all(math.isclose(w, v, rel_tol=1e-4, abs_tol=1e-12) for w, v in zip(want, (xx, yy, zz)))


@check("P052")
def mimic_ignored(model: Model, ctx: Context) -> Iterator[Problem]:
    """<mimic> that a consumer drops: PyBullet's UrdfParser never reads it (measured: a joint of its own, with its own
    motor); sdformat's URDF converter only converts it from 14.1 on (parser_urdf.cc; measured with 12.3: no <mimic>
    in the SDFormat joint); Pinocchio's buildModelFromUrdf builds it only when asked (mimic=True gives a
    JointModelMimic, measured with pin 4.1); kdl_parser has no mimic (robot_state_publisher applies it itself)."""
    from urdfcheck.rules.checks.profiles.behaviour import sdformat_of, version_tuple

    mimics = [j for j in model.joint_list if j.mimic is not None and j.type in ("revolute", "continuous",
                                                                                "prismatic")]
    if not mimics:
        return
    who = ["pybullet", "pinocchio", "kdl"]
    if version_tuple(sdformat_of(model, ctx)) < (14, 1):
        who.insert(1, "gazebo")
    shown = {"pybullet": "PyBullet", "gazebo": "Gazebo (sdformat before 14.1)", "pinocchio": "Pinocchio (unless "
             "buildModelFromUrdf(..., mimic=True))", "kdl": "KDL"}
    active = [w for w in who if w in ctx.profiles]
    if not active:
        return  # a change, not a refusal: said only to those who asked
    p = speak(ctx, tuple(active),
              f"{' and '.join(shown[w] for w in active)} ignore <mimic> on joint(s) "
              f"{names([j.name for j in mimics])}: each moves on its own, a gripper's fingers are no longer "
              "coupled; couple them in the simulation (a gear constraint, a controller) or drive every joint",
              mimics[0].mimic)
    if p is not None:
        yield p
