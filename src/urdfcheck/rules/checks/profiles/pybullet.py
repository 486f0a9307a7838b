"""PyBullet: Bullet's URDF importer (bulletphysics/bullet3 examples/Importers/ImportURDFDemo/UrdfParser.cpp,
BulletUrdfImporter.cpp, URDF2Bullet.cpp).

UrdfParser::parseLink: a link without <inertial> gets mass 1 and inertia 1 1 1 ("No inertial data for link,
using mass=1, localinertiadiagonal = 1,1,1, identity local inertial frame"), the root link too in the default free-base
load (useFixedBase=False); a link named "world" stays massless. BulletURDFImporter::getMassAndInertia: unless loadURDF is given flags=URDF_USE_INERTIA_FROM_FILE, the
inertia tensor is recomputed from the collision shapes (calculateLocalInertia) and the URDF's <inertia> is
ignored."""
from __future__ import annotations

from urdfcheck.rules.catalogue import check
from urdfcheck.rules.checks.profiles.common import names, speak


@check("P050")
def default_mass(model, ctx):
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
def inertia_recomputed(model, ctx):
    if "pybullet" not in ctx.profiles:
        return
    given = [lk for lk in model.link_list if lk.inertial is not None and lk.inertial.inertia is not None]
    if given:
        yield speak(ctx, ("pybullet",),
                    f"PyBullet ignores the <inertia> of {len(given)} link(s) unless loadURDF gets "
                    "flags=p.URDF_USE_INERTIA_FROM_FILE: it recomputes each tensor from the collision shapes "
                    "(BulletURDFImporter getMassAndInertia, calculateLocalInertia)", given[0].inertial)


@check("P052")
def mimic_ignored(model, ctx):
    """<mimic> that a consumer drops: PyBullet's UrdfParser never reads it (measured: the joint moves on its own);
    sdformat's URDF converter only converts it from 14.1 on (parser_urdf.cc; measured with 12.3: no <mimic> in the
    SDFormat joint); Pinocchio's buildModelFromUrdf builds it only when asked (mimic=True, pinocchio 3.4 and later);
    kdl_parser has no mimic (robot_state_publisher applies it itself)."""
    from urdfcheck.rules.checks.profiles.behaviour import version_tuple

    mimics = [j for j in model.joint_list if j.mimic is not None and j.type in ("revolute", "continuous",
                                                                                "prismatic")]
    if not mimics:
        return
    who = ["pybullet", "pinocchio", "kdl"]
    if version_tuple(str(ctx.options["sdformat"])) < (14, 1):
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
