"""PyBullet: Bullet's URDF importer (bulletphysics/bullet3 examples/Importers/ImportURDFDemo/UrdfParser.cpp,
BulletUrdfImporter.cpp, URDF2Bullet.cpp).

UrdfParser::parseLink: a link without <inertial> gets mass 1 and inertia 1 1 1 ("No inertial data for link,
using mass=1, localinertiadiagonal = 1,1,1, identity local inertial frame"); the root of a fixed-base load keeps
mass 0. BulletURDFImporter::getMassAndInertia: unless loadURDF is given flags=URDF_USE_INERTIA_FROM_FILE, the
inertia tensor is recomputed from the collision shapes (calculateLocalInertia) and the URDF's <inertia> is
ignored."""
from __future__ import annotations

from urdfcheck.rules.catalogue import check
from urdfcheck.rules.checks.profiles.common import names, speak


@check("P050")
def default_mass(model, ctx):
    if "pybullet" not in ctx.profiles:
        return
    root = model.root
    bare = [lk for lk in model.link_list if lk.inertial is None and lk.name != root and lk.name != "world"]
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
