"""S012-S014: the extension blocks that name a part of the model (issue 41): a <gazebo reference>, a <transmission>'s
joint, a Gazebo sensor's frame. Each names it by a string nothing else checks, so a typo loses the block silently."""
from __future__ import annotations

from urdfcheck.core.findings import Problem, Severity, closest
from urdfcheck.rules.catalogue import check

# frames a sensor may stamp its data with that are not links of a robot
WORLD_FRAMES = ("world", "map", "odom", "earth")


def _unresolved(name: str) -> bool:
    return "$(" in name or "${" in name or "$" in name


def _hint(name: str, options) -> str:
    near = closest(name, options)
    return f" (did you mean {near!r}?)" if near else ""


@check("S012")
def gazebo_reference_unknown(model, ctx):
    names = set(model.links) | set(model.joints)
    for b in model.blocks:
        if b.tag != "gazebo" or b.parent_tag != "robot":
            continue
        ref = (b.attrib.get("reference") or "").strip()
        if not ref or _unresolved(ref) or ref in names:
            continue
        yield Problem(f"<gazebo reference={ref!r}> names no link or joint of the model{_hint(ref, names)}: Gazebo "
                      "applies the block to nothing, so its settings (material, friction, sensors, plugins) are lost",
                      at=b.loc)


@check("S013")
def transmission_unknown_joint(model, ctx):
    joints = set(model.joints)
    for t in model.transmissions:
        for j in t.joints:
            if not j.name or _unresolved(j.name) or j.name in joints:
                continue
            yield Problem(f"<transmission> {t.name!r} names joint {j.name!r}, which the model does not have"
                          f"{_hint(j.name, joints)}: the transmission loader (ros_control, gazebo_ros_control) "
                          "fails on it and the joint it meant is not actuated", at=j.loc)


@check("S014")
def sensor_frame_unknown(model, ctx):
    links = set(model.links)
    for f in model.frame_refs:
        name = f.name.strip().lstrip("/")
        if not name or _unresolved(name) or name in links or name in WORLD_FRAMES:
            continue
        if "/" in name and name.rsplit("/", 1)[1] in links:
            continue  # a link under a frame prefix (a namespaced robot_state_publisher)
        hint = _hint(name, links)
        # a near miss of a link is evidence of a typo; without one the frame may come from elsewhere (a static
        # transform publisher), which the model alone cannot tell: said as information
        yield Problem(f"sensor {f.sensor!r} stamps its data with frame {name!r} (<{f.tag}>), which is not a link of "
                      f"the model{hint}: TF cannot place its data unless something else publishes that frame",
                      at=f.loc, severity=None if hint else Severity.INFO)
