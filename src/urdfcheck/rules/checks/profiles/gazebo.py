"""Gazebo: sdformat's URDF converter (gazebosim/sdformat src/parser_urdf.cc), and the Isaac Sim URDF importer
(isaac-sim/urdf-importer-extension, documentation "URDF Importer Extension").

parser_urdf.cc reduces fixed joints from the leaves up (ReduceFixedJoints; a joint is kept with <gazebo
reference="joint"><preserveFixedJoint>true</preserveFixedJoint></gazebo> or <disableFixedJointLumping>, and a
joint from `world` is never reduced), so a link first gathers the mass of the links fixed below it; CreateSDF then
skips a link whose gathered mass is none or within 1e-6 of 0 ("has no inertia, not modeled in sdf"), with every
link and joint below it; `ign sdf -k` (and Gazebo's loader) validates what is left. All of it measured with
sdformat 12.3 (tests/differential.py); behaviour.gazebo_bodies is the one place it is computed.
"""
from __future__ import annotations

import re

from urdfcheck.core import lazyre
from urdfcheck.core.records import TYPE_CHECKING
from urdfcheck.rules.catalogue import check
from urdfcheck.rules.checks.profiles.common import actuated, dynamic, fixed_groups, is_tree, names, speak

if TYPE_CHECKING:  # the checks' argument types (no import at run time)
    from collections.abc import Iterator

    from urdfcheck.core.findings import Problem
    from urdfcheck.model.robot import Model
    from urdfcheck.rules.engine import Context

_JOINT = lazyre.compile(r"<\s*joint\b[^>]*\bname\s*=\s*[\"']([^\"']*)[\"'][^>]*>(.*?)<\s*/\s*joint\s*>", re.S)
_END = lazyre.compile(r"<\s*(parent|child)\s*>\s*([^<\s]+)\s*<")


def _extension_joints(model):
    """(block, joint, "parent"/"child", link) for each SDFormat <joint> written inside a robot-level <gazebo>."""
    for b in model.blocks:
        if b.tag != "gazebo" or b.parent_tag != "robot" or "joint" not in b.xml:
            continue
        for m in _JOINT.finditer(b.xml):
            for end, link in _END.findall(m.group(2)):
                yield b, m.group(1), end, link


@check("P010")
def fixed_joint_lumping(model: Model, ctx: Context) -> Iterator[Problem]:
    if "gazebo" not in ctx.profiles or len(model.roots) != 1:
        return
    from urdfcheck.rules.checks.profiles.behaviour import gazebo_keep

    group = fixed_groups(model, gazebo_keep(model))  # a fixed joint from `world` anchors the model, never lumped
    lumped = [n for n, g in group.items() if n != g and g != "world"]
    if lumped:
        yield speak(ctx, ("gazebo",),
                    f"Gazebo lumps {len(lumped)} link(s) attached by fixed joints into their parents (sdformat "
                    f"parser_urdf.cc ReduceFixedJoints): {names(lumped)} become frames of the parent link, and "
                    "sensors, plugins and <gazebo reference> blocks naming them move to it (keep one with <gazebo "
                    "reference=\"JOINT\"><preserveFixedJoint>true</preserveFixedJoint></gazebo>)", model)


@check("P011")
def massless_link_dropped(model: Model, ctx: Context) -> Iterator[Problem]:
    from urdfcheck.rules.checks.profiles.behaviour import gazebo_bodies, sdformat_of

    if not is_tree(model):
        return
    version = sdformat_of(model, ctx)
    group, kept, dropped = gazebo_bodies(model, version)
    root = model.roots[0]
    if not kept:
        return  # nothing left at all: P012 says Gazebo refuses the model
    known = model.links
    for body in model.descendants_in_order(root):
        j = model.parent_joint.get(body)
        if body not in dropped or j is None or j.parent in dropped:
            continue  # kept, the root (P012), or below a dropped link: already named by its finding
        below = model.descendants_in_order(body)[1:]
        if j.type == "fixed" and not below:
            continue  # a massless frame at a leaf: lumped or dropped, nothing is lost
        inr = known[body].inertial
        why = ("no <inertial>" if inr is None else f"mass {inr.mass:g}" if inr.mass is not None else "no mass")
        fixed = " (fixed joints are lumped from the leaves up: the links fixed below it bring no mass either)" \
            if any(c.type == "fixed" for c in model.child_joints.get(body, ())) else ""
        p = speak(ctx, ("gazebo",),
                  f"Gazebo drops link '{body}'" + (f" and the {len(below)} link(s) below it ({names(below)})"
                                                   if below else "")
                  + f": it has {why}{fixed} (sdformat {version} parser_urdf.cc CreateSDF skips a link without "
                  "<inertial> or with a mass within 1e-6 of 0, from 12.7.2 on a mass <= 0: \"has no inertia, "
                  "not modeled in "
                  f"sdf\"), so joint '{j.name}' and everything attached below it are missing from the simulation, "
                  "even where the joint is fixed; give it an <inertial> with a small positive mass",
                  inr or known[body], quiet=True)  # P001's info names Gazebo too
        if p is not None:
            yield p


@check("P012")
def gazebo_refuses(model: Model, ctx: Context) -> Iterator[Problem]:
    """What sdformat's converter leaves that its own validation (`ign sdf -k`, and Gazebo's loader) refuses, or a
    model with no link left at all. Measured with sdformat 12.3."""
    from urdfcheck.rules.checks.profiles.behaviour import gazebo_bodies, sdformat_of

    if not is_tree(model):
        return  # S rules; urdfdom refuses those models before sdformat converts anything
    version = sdformat_of(model, ctx)
    group, kept, dropped = gazebo_bodies(model, version)
    root = model.roots[0]
    if not kept:
        first = root if root != "world" else next((j.child for j in model.child_joints.get(root, ())), root)
        p = speak(ctx, ("gazebo",),
                  f"Gazebo refuses the model: its root link '{first}' has no <inertial> or a mass within 1e-6 of 0, "
                  "so sdformat's URDF converter drops it with everything below it (parser_urdf.cc CreateSDF: \"has "
                  "no inertia, not modeled in sdf\") and the model has no link left; give the root an <inertial>, "
                  "or attach it by a fixed joint to a link that has one (it is then lumped into that link's mass)",
                  # (type: ignore below) the root of a tree model has a name
                  model.links[first] if first in model.links else model,  # type: ignore[index]
                  quiet=not dynamic(model))  # no <inertial> anywhere: kinematic by intent (a tutorial, MoveIt's)
        if p is not None:
            yield p
        return
    for j in model.joint_list:
        if j.type in ("floating", "planar") and j.child in kept and group.get(j.child) == j.child:
            p = speak(ctx, ("gazebo",),
                      f"Gazebo refuses the model: sdformat's URDF converter has no SDFormat joint for {j.type} "
                      f"joint '{j.name}' (parser_urdf.cc CreateJoint) and drops it, while link '{j.child}' keeps "
                      f"its pose relative to it: \"relative_to name[{j.name}] ... does not match\" (ign sdf -k, "
                      "PoseRelativeToGraph); use a fixed joint, or spawn the part as its own model", j,
                      quiet=True)  # J010/J011 report the joint for every consumer
            if p is not None:
                yield p
    from urdfcheck.rules.checks.profiles.behaviour import gazebo_invalid_inertia, gazebo_new

    massive: dict[str, list[str]] = {}
    for n, g in group.items():
        if g in kept and n in model.links and model.links[n].inertial is not None:
            massive.setdefault(g, []).append(n)
    for body, links in massive.items():
        # one <inertial> in the SDFormat link: lumping moves it but keeps its principal moments; several are summed
        # about their common centre of mass, and only that sum is validated (not judged here)
        if len(links) == 1 and gazebo_invalid_inertia(model.links[links[0]]):
            inr = model.links[links[0]].inertial
            p = speak(ctx, ("gazebo",),
                      f"Gazebo refuses the model: the inertia of link '{links[0]}' (the only one in SDFormat link "
                      f"'{body}') is not a rigid body's: \"A link named {body} has invalid inertia\" (sdformat "
                      "validation, gz-math MassMatrix3::IsValid: principal moments >= 0 and each two adding up to "
                      "the third); I003/I004 say what is wrong with it",
                      inr.inertia_loc or inr,  # type: ignore[union-attr]  # the link's tensor was found invalid
                      quiet=True)  # I003/I004 report the tensor for every consumer
            if p is not None:
                yield p
    for block, joint, end, link in _extension_joints(model):
        if link in model.links and (link in dropped or group.get(link, link) != link):
            how = "dropped (no mass)" if link in dropped else f"lumped into '{group[link]}' (fixed joint)"
            p = speak(ctx, ("gazebo",),
                      f"Gazebo refuses the model: the SDFormat joint '{joint}' of a <gazebo> block names link "
                      f"'{link}' as its <{end}>, and sdformat's URDF converter {how} that link: \"{end} frame with "
                      f"name[{link}] specified by joint with name[{joint}] not found\" (ign sdf -k, measured on "
                      "PR2's grippers); keep the link with <preserveFixedJoint>, or name the link it ends in", block)
            if p is not None:
                yield p
    if not gazebo_new(version):
        for body, total in kept.items():
            if total is not None and total < 0:
                p = speak(ctx, ("gazebo",),
                          f"Gazebo refuses the model: link '{body}' ends with mass {total:g} (sdformat {version} "
                          f"keeps a negative mass, then its validation says \"A link named {body} has invalid "
                          "inertia\"; from 12.7.2 on the link is dropped instead); give it its real, positive mass",
                          model.links[body].inertial or model.links[body], quiet=True)  # I002
                if p is not None:
                    yield p


@check("P013")
def undrivable_joint(model: Model, ctx: Context) -> Iterator[Problem]:
    """effort="0" on a movable joint nothing actuates. Gazebo copies the limit into SDFormat, where 0 clamps every
    commanded force to 0; Isaac Sim's importer reads 0 as no limit (configureDriveAPI: maxForce FLT_MAX). ROS-Industrial
    arms write effort 0 because their driver commands positions: a <transmission> or <ros2_control> joint tells them
    apart (J004 covers those)."""
    driven = actuated(model)
    zero = [j for j in model.joint_list if j.type in ("revolute", "prismatic", "continuous") and j.limit is not None
            and j.limit.effort == 0 and j.mimic is None and j.name not in driven]
    if not zero:
        return
    p = speak(ctx, ("gazebo", "isaac"),
              f"joint(s) {names([j.name for j in zero])} have effort=\"0\" and no actuator (<transmission> or "
              "<ros2_control>): Gazebo copies the limit into SDFormat (<effort>0</effort>), so any force or torque "
              "a plugin or controller commands is clamped to 0 and the joint cannot be driven, while Isaac Sim's "
              "URDF importer reads 0 as no limit at all (drive maxForce FLT_MAX); a position-controlled "
              "ROS-Industrial arm or a passive joint (moved by a spring or gravity) can ignore this, a joint meant "
              "to be driven in simulation needs its real effort limit", zero[0].limit)
    if p is not None:
        yield p


@check("P020")
def isaac_merges_fixed_joints(model: Model, ctx: Context) -> Iterator[Problem]:
    if "isaac" not in ctx.profiles or len(model.roots) != 1:
        return
    keep = _dont_collapse(model)
    group = fixed_groups(model, keep)
    merged = [n for n, g in group.items() if n != g]
    if merged:
        yield speak(ctx, ("isaac",),
                    f"Isaac Sim's URDF importer, with \"Merge Fixed Joints\" on, merges {len(merged)} link(s) into "
                    f"their parents: {names(merged)} are no prims of their own (sensors and TF frames published "
                    "from them are lost); keep one with dont_collapse=\"true\" on its fixed joint", model)


def _dont_collapse(model) -> set[str]:
    """Joints written with dont_collapse="true"."""
    return {j.name for j in model.joint_list if j.dont_collapse}
