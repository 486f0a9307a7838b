"""S012-S014: the extension blocks that name a part of the model (issue 41): a <gazebo reference>, a <transmission>'s
joint, a Gazebo sensor's frame. Each names it by a string nothing else checks, so a typo loses the block silently."""
from __future__ import annotations

from urdfcheck.core import lazyre
from urdfcheck.core.findings import Problem, Severity, closest
from urdfcheck.core.records import TYPE_CHECKING
from urdfcheck.rules.catalogue import check

if TYPE_CHECKING:  # the checks' argument types (no import at run time)
    from collections.abc import Iterator

    from urdfcheck.model.robot import Model
    from urdfcheck.rules.engine import Context

# (and the old Gazebo 0.x bodies and joints: <body:box name=...>, <joint:hinge name=...>)
_SDF_PART = lazyre.compile(r"<(?:link|joint|body)(?::\w+)?\s[^>]*?\bname=\"([^\"]+)\"")

# frames a sensor may stamp its data with that are not links of a robot
WORLD_FRAMES = ("world", "map", "odom", "earth")


def _unresolved(name: str) -> bool:
    return "$(" in name or "${" in name or "$" in name


def _hint(name: str, options) -> str:
    near = closest(name, options)
    return f" (did you mean {near!r}?)" if near else ""


def _sdf_parts(model) -> set[str]:
    """Links and joints written as SDF inside <gazebo> blocks: Gazebo adds them to the model it simulates."""
    out: set[str] = set()
    for b in model.blocks:
        if b.tag == "gazebo" and ("<link" in b.xml or "<joint" in b.xml or "<body" in b.xml):
            out.update(_SDF_PART.findall(b.xml))
    return out


@check("S012")
def gazebo_reference_unknown(model: Model, ctx: Context) -> Iterator[Problem]:
    names = set(model.links) | set(model.joints)
    sdf = None
    for b in model.blocks:
        if b.tag != "gazebo" or b.parent_tag != "robot":
            continue
        ref = (b.attrib.get("reference") or "").strip()
        if not ref or _unresolved(ref) or ref in names:
            continue
        if sdf is None:
            sdf = _sdf_parts(model)
        if ref in sdf:
            continue  # a link written as SDF in another <gazebo> block; whether Gazebo applies it there is not told
        yield Problem(f"<gazebo reference={ref!r}> names no link or joint of the model{_hint(ref, names)}: Gazebo "
                      "applies the block to nothing, so its settings (material, friction, sensors, plugins) are lost",
                      at=b.loc)


@check("S013")
def transmission_unknown_joint(model: Model, ctx: Context) -> Iterator[Problem]:
    joints = set(model.joints)
    for t in model.transmissions:
        for j in t.joints:
            if not j.name or _unresolved(j.name) or j.name in joints:
                continue
            yield Problem(f"<transmission> {t.name!r} names joint {j.name!r}, which the model does not have"
                          f"{_hint(j.name, joints)}: the transmission loader (ros_control, gazebo_ros_control) "
                          "fails on it and the joint it meant is not actuated", at=j.loc)


@check("S014")
def sensor_frame_unknown(model: Model, ctx: Context) -> Iterator[Problem]:
    links = set(model.links)
    tails = {n.rsplit("/", 1)[1] for n in links if "/" in n}
    sdf = _sdf_parts(model) if model.frame_refs else set()
    for f in model.frame_refs:
        name = f.name.strip().lstrip("/")
        if not name or _unresolved(name) or name in links or name in WORLD_FRAMES or name in sdf:
            continue
        if "/" in name and name.rsplit("/", 1)[1] in links:
            continue  # a link under a frame prefix (a namespaced robot_state_publisher)
        if name in tails:
            continue  # links named NAMESPACE/name: ROS 1 plugins resolve the frame under the tf_prefix
        hint = _hint(name, links)
        # a near miss of a link is evidence of a typo; without one the frame may come from elsewhere (a static
        # transform publisher), which the model alone cannot tell: said as information
        yield Problem(f"sensor {f.sensor!r} stamps its data with frame {name!r} (<{f.tag}>), which is not a link of "
                      f"the model{hint}: TF cannot place its data unless something else publishes that frame",
                      at=f.loc, severity=None if hint else Severity.INFO)
