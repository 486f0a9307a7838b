"""What each consumer does with a URDF it loads, as data: which findings mean it refuses the model, and, for a model
it loads, the links it keeps, the masses it gives them, what becomes of each joint and which <mimic> it honours.

The profile rules speak from the same facts (kept links, lumping, default masses); tests/differential.py loads
models into the real consumers and compares, point by point, with `predict` (issue 40). Measured with MuJoCo 4.0,
Pinocchio 4.1, PyBullet 3.2 (API 202010061), sdformat 12.3 (`ign sdf -p`, `-k`, Debian bookworm) and kdl_parser
1.14 on urdfdom 3.0; where a consumer's behaviour changed with its version, the version is an argument.
"""
from __future__ import annotations

import re

from urdfcheck.core import lazyre
from urdfcheck.rules.checks.profiles.common import GENERAL, REFUSING, URDFDOM, fixed_groups  # noqa: F401

# sdformat releases where its URDF converter changed what it does (parser_urdf.cc)
# gazebosim/sdformat pull request 1238 ("URDF->SDF handle links with no inertia or small mass"; libsdformat 12.7.2,
# 13.5.0, 14.x): CreateSDF tests `mass <= 0` instead of math::equal(mass, 0), and a massless link whose own fixed
# joint is reduced is lumped, no longer dropped with everything below it
SDFORMAT_DROPS_NEGATIVE_MASS = (12, 7, 2)
SDFORMAT_KEEPS_MIMIC = (14, 1)  # <mimic> converted into the SDFormat joint axis's <mimic>
SDFORMAT_DEFAULT = "12.3"  # Debian bookworm's libsdformat12, the version measured here


def version_tuple(text: str) -> tuple[int, ...]:
    out = []
    for part in str(text or "").split("."):
        digits = "".join(c for c in part if c.isdigit())
        if not digits:
            break
        out.append(int(digits))
    return tuple(out)


def refuses(code: str, consumer: str) -> bool:
    return code in REFUSING.get(consumer, ()) or GENERAL.get(consumer, {}).get(code) == "refuses"


def kind(joint_type: str) -> str:
    return {"revolute": "hinge", "continuous": "hinge", "prismatic": "slide", "fixed": "fixed",
            "floating": "free", "planar": "planar"}.get(joint_type, joint_type)


def _mass(link):
    """(has <inertial>, its mass or None when not a plain number)."""
    inr = link.inertial
    if inr is None:
        return False, 0.0
    return True, inr.mass


# --- Gazebo ---------------------------------------------------------------------------------------------------
_KEEP = lazyre.compile(r"<\s*(preserveFixedJoint|disableFixedJointLumping)\s*>\s*(true|1)\s*<", re.I)


def kept_fixed_joints(model) -> set[str]:
    """Fixed joints sdformat does not lump: <gazebo reference="J"> with preserveFixedJoint/disableFixedJointLumping."""
    return {b.attrib.get("reference", "") for b in model.blocks
            if b.tag == "gazebo" and b.parent_tag == "robot" and _KEEP.search(b.xml)}


def gazebo_keep(model) -> set[str]:
    """Fixed joints sdformat does not lump: <preserveFixedJoint>/<disableFixedJointLumping>, and a joint from the
    link `world`, which is no link in SDFormat but the world itself (parser_urdf.cc: the joint to "world" becomes a
    fixed joint of the model, its child stays a link)."""
    return kept_fixed_joints(model) | {j.name for j in model.joint_list if j.parent == "world"}


SDFORMAT_ZERO = 1e-6  # ignition::math::equal's default tolerance: parser_urdf.cc tests the mass with it


def gazebo_new(version: str) -> bool:
    """Is this an sdformat with pull request 1238 (9.10.1 and later 9.x, 12.7.2 and later 12.x, 13.5 and later)?"""
    v = version_tuple(version)
    return v >= (13, 5) or SDFORMAT_DROPS_NEGATIVE_MASS <= v < (13,) or (9, 10, 1) <= v < (10,)


# the sdformat a distribution's Gazebo reads URDF with, when the `sdformat` option is "auto": Noetic's Gazebo 11
# (sdformat 9), Humble's Fortress (sdformat 12), Jazzy's and later Harmonic/Ionic (sdformat 14/15); the newest
# release of each, as the Gazebo packages ship it (read from sdformat's Changelog, not measured)
SDFORMAT_FOR = {"noetic": "9.10.1", "humble": "12.8.0", "jazzy": "14.5.0", "kilted": "15.0.0", "rolling": "15.0.0"}


def sdformat_of(model, ctx) -> str:
    """The sdformat version the Gazebo rules predict for: the option, or with "auto" the target distribution's."""
    given = str(ctx.options["sdformat"])
    if given != "auto":
        return given
    from urdfcheck.rules.checks.values import target_of

    return SDFORMAT_FOR.get(target_of(model, ctx)[0].name, SDFORMAT_DEFAULT)


def gazebo_massless(total, has_inertial: bool, version: str = SDFORMAT_DEFAULT) -> bool:
    """Does sdformat's CreateSDF skip a link (with the mass gathered from the links fixed below it)? Measured with
    12.3: no <inertial>, or a mass within 1e-6 of 0 (1e-6 and -1e-6 dropped, 1.01e-6 kept: math::equal). From
    pull request 1238 on (read from the source): a mass <= 0."""
    if not has_inertial or total is None:
        return not has_inertial
    if gazebo_new(version):
        return total <= 0.0
    return abs(total) <= SDFORMAT_ZERO


def gazebo_bodies(model, version: str = SDFORMAT_DEFAULT):
    """(group, kept, dropped): link -> the SDFormat link it is lumped into; the SDFormat links kept with their total
    mass (None: not a plain number); the links dropped. `world` is never a link.

    Measured with sdformat 12.3 (`ign sdf -p`): fixed joints are reduced from the leaves up, so a link first takes
    the mass of every link fixed below it; then a link whose mass so gathered is none (no <inertial>) or 0 is
    dropped with everything below it, whether its own joint moves or is fixed. A massless tool0 leaf goes
    harmlessly; a massless force-torque sensor link between a hip and the thigh takes the whole leg with it; a
    massless root takes the model, unless a fixed child brings it mass (base_footprint above base_link). From pull
    request 1238 on (read from the source, not measured), a massless link whose own fixed joint is reduced is lumped
    and kept, and only a mass <= 0 counts as none."""
    keep = gazebo_keep(model)
    group = fixed_groups(model, keep)
    children = model.child_joints.get
    order = [n for root in model.roots for n in model.descendants_in_order(root)]
    gathered: dict[str, tuple[bool, float | None]] = {}
    for name in reversed(order):
        lk = model.links.get(name)
        has, total = _mass(lk) if lk is not None else (False, 0.0)
        for j in children(name, ()):
            if j.type == "fixed" and j.name not in keep and j.child in gathered:
                h, m = gathered[j.child]
                has = has or h
                total = None if total is None or m is None else total + m
        gathered[name] = (has, total)
    dropped: set[str] = set()
    for name in order:
        if name == "world" or name not in model.links:
            continue
        j = model.parent_joint.get(name)
        has, total = gathered[name]
        reduced = j is not None and j.type == "fixed" and j.name not in keep
        if (j is not None and j.parent in dropped) or (gazebo_massless(total, has, version)
                                                       and not (reduced and gazebo_new(version))):
            dropped.add(name)
    kept: dict[str, float | None] = {}
    for name in order:
        head = group.get(name, name)
        if name in dropped or head == "world" or name not in model.links:
            continue
        has, m = _mass(model.links[name])
        if head not in kept:
            kept[head] = 0.0
        if has:
            kept[head] = None if kept[head] is None or m is None else kept[head] + m
    return group, kept, dropped


def gazebo_invalid_inertia(link) -> bool | None:
    """Does sdformat's validation ("A link named X has invalid inertia") refuse this <inertial> as the only one of
    its SDFormat link? gz-math MassMatrix3::IsValid: mass >= 0, the principal moments >= 0 and each pair adding up
    to at least the third, within 10 machine epsilons of half their sum. None: not a tensor to judge."""
    import math

    from urdfcheck.rules.checks.inertial import principal_moments

    inr = link.inertial
    if inr is None or inr.inertia is None or not all(math.isfinite(v) for v in inr.inertia):
        return None
    a, b, c = principal_moments(tuple(inr.inertia))
    eps = 10 * 2.220446049250313e-16 * 0.5 * abs(a + b + c)
    return not (a + eps >= 0 and a + b + eps >= c)


# --- the prediction -------------------------------------------------------------------------------------------
def predict(consumer: str, model, version: str = "") -> dict:
    """links kept, mass per kept link (None: not predicted), URDF joint -> what it becomes ("gone": no joint of that
    name), and the joints whose <mimic> is honoured."""
    return _PREDICT[consumer](model, version)


def _movable(model):
    return [j for j in model.joint_list if j.type != "fixed"]


def _mujoco(model, version):
    group = fixed_groups(model)
    bodies = sorted({g for g in group.values() if g not in model.roots and g != "world"})  # roots: the world
    mass: dict[str, float | None] = {}
    for b in bodies:
        facts = [_mass(model.links[n]) for n, g in group.items() if g == b and n in model.links]
        mass[b] = sum(m for _, m in facts) if all(h and m is not None for h, m in facts) else None
    joints = {j.name: kind(j.type) for j in _movable(model)}
    names = {j.name for j in model.joint_list}
    mimic = [j.name for j in model.joint_list if j.mimic is not None and j.type in ("revolute", "continuous",
                                                                                       "prismatic")
             and j.mimic.joint in names and j.mimic.joint != j.name]
    return {"links": bodies, "mass": mass, "joints": joints, "mimic": mimic}


def _pinocchio(model, version):
    group = fixed_groups(model)
    mass: dict[str, float | None] = {}
    for j in _movable(model):
        facts = [_mass(model.links[n]) for n, g in group.items() if g == j.child and n in model.links]
        mass[j.child] = None if any(h and m is None for h, m in facts) else sum(m for h, m in facts if h)
    return {"links": [lk.name for lk in model.link_list], "mass": mass,
            "joints": {j.name: kind(j.type) for j in _movable(model)}, "mimic": []}


def _pybullet(model, version):
    mass: dict[str, float | None] = {}
    for lk in model.link_list:
        has, m = _mass(lk)
        # UrdfParser.cpp parseLink: no <inertial> is mass 1 (the root too, in the default free-base load), except
        # a link named "world", which stays massless (measured)
        mass[lk.name] = m if has else (0.0 if lk.name == "world" else 1.0)
    joints = {j.name: {"free": "fixed"}.get(kind(j.type), kind(j.type)) for j in model.joint_list}
    return {"links": [lk.name for lk in model.link_list], "mass": mass, "joints": joints, "mimic": []}


def _gazebo(model, version):
    version = version or SDFORMAT_DEFAULT
    group, kept, _ = gazebo_bodies(model, version)
    joints = {}
    for j in model.joint_list:
        if j.child not in kept or group.get(j.child) != j.child:
            joints[j.name] = "gone"  # lumped, or below a dropped link
        elif j.type in ("floating", "planar"):
            joints[j.name] = "gone"  # CreateJoint has no SDFormat type for them
        else:
            joints[j.name] = kind(j.type)
    keeps = version_tuple(version) >= SDFORMAT_KEEPS_MIMIC
    mimic = [j.name for j in model.joint_list if keeps and j.mimic is not None and joints.get(j.name) != "gone"]
    return {"links": sorted(kept), "mass": dict(kept), "joints": joints, "mimic": mimic}


def _kdl(model, version):
    root = model.roots[0] if model.roots else None
    mass = {}
    for lk in model.link_list:
        has, m = _mass(lk)
        mass[lk.name] = 0.0 if lk.name == root or not has else m  # the root segment's inertia is dropped (I005)
    joints = {j.name: {"free": "fixed", "planar": "fixed"}.get(kind(j.type), kind(j.type))
              for j in model.joint_list}
    return {"links": [lk.name for lk in model.link_list], "mass": mass, "joints": joints, "mimic": []}


_PREDICT = {"mujoco": _mujoco, "pinocchio": _pinocchio, "pybullet": _pybullet, "gazebo": _gazebo, "kdl": _kdl}
