"""What the profile rules share: the profile names, when a rule speaks and how loudly, and which general rules a
profile reads as its consumer's own rejection (`annotates`)."""
from __future__ import annotations

from urdfcheck.core.findings import Problem, Severity

# profile -> how findings name the consumer
PROFILES = {
    "mujoco": "MuJoCo",
    "gazebo": "Gazebo",
    "isaac": "Isaac Sim",
    "kdl": "KDL",
    "pinocchio": "Pinocchio",
    "pybullet": "PyBullet",
    "moveit": "MoveIt",
}

# General rules whose findings are, for a profile's consumer, the consumer's own refusal of the model: with the
# profile on, those findings carry the profile (JSON "profile"), so a report filtered by profile is complete.
# Each entry was checked by loading a model with the defect into the consumer (tests/consumers_diff.py).
ANNOTATES = {
    # urdfdom refuses these while parsing; Pinocchio reads URDF through urdfdom (parsers/urdf/model.cxx)
    "pinocchio": frozenset(("U001", "U004", "U005", "U006", "U007", "S001", "S002", "S003", "S004", "S005", "S006",
                            "S007", "S008", "S011", "J001", "J002", "I001")),
    # MuJoCo: "axis too small in joint" (user_objects.cc mjCJoint::Compile); xml_urdf.cc: a joint naming a missing
    # link, a body with two parents, a cycle or no root ("URDF body not found"), a repeated link name; a value
    # that is no number or has the wrong count ("bad format in attribute", "too much data": ReadAttr)
    "mujoco": frozenset(("J006", "S002", "S003", "S004", "S005", "S007", "U004", "U005")),
    # kdl_parser's root inertia warning is this profile's own subject
    "kdl": frozenset(("I005",)),
}


def annotates(code: str, active) -> str:
    for name in active:
        if code in ANNOTATES.get(name, ()):
            return name
    return ""


def speak(ctx, profiles: tuple[str, ...], message: str, at, *, quiet: bool = False, related=()):
    """A Problem from a profile rule, or None. With one of `profiles` active: the catalogue severity, naming the
    first active one. Without: an info naming the consumers (what only a profile would fail stays visible), or
    nothing when `quiet` (a general rule already reports the same defect, or the behaviour is only a change)."""
    active = [p for p in profiles if p in getattr(ctx, "profiles", ())]
    if active:
        return Problem(message, at=at, related=related, data={"profile": active[0]})
    if quiet:
        return None
    flags = " or ".join(f"--profile {p}" for p in profiles)
    return Problem(f"{message} (info here; {flags} reports it at the rule's severity)", at=at, related=related,
                   severity=Severity.INFO, data={"profile": profiles[0]})


def is_tree(model) -> bool:
    """One root, every link reached once: the structure the profile rules reason about (S rules report the rest)."""
    if len(model.roots) != 1 or len(model.joint_list) != len(model.links) - 1:
        return False
    return len(model.descendants_in_order(model.roots[0])) == len(model.links)


def dynamic(model) -> bool:
    """Does the model carry dynamics at all? A model without a single <inertial> is kinematic by intent (a MoveIt
    test robot, a tutorial): without a profile, its missing masses are nobody's mistake."""
    return any(lk.inertial is not None for lk in model.link_list)


def names(items, limit: int = 6) -> str:
    items = [f"'{i}'" for i in items]
    if len(items) <= limit:
        return ", ".join(items)
    return ", ".join(items[:limit]) + f" and {len(items) - limit} more"


def actuated(model) -> set[str]:
    """Joints something can drive: named by a <transmission> or a <ros2_control> <joint>."""
    out = {i.name for t in model.transmissions for i in t.joints}
    out.update(j.name for rc in model.ros2_control for j in rc.joints)
    return out


def fixed_groups(model, keep=frozenset()) -> dict[str, str]:
    """link -> the link it is lumped into when fixed joints are merged (itself when its parent joint moves, it
    is a root, or its fixed joint is in `keep`). Cycle-safe."""
    out: dict[str, str] = {}
    children = model.child_joints.get  # a property: read once, not once per link
    for root in model.roots:
        out[root] = root
        for name in model.descendants_in_order(root):
            for j in children(name, ()):
                if j.child is None or j.child in out:
                    continue
                lumped = j.type == "fixed" and j.name not in keep
                out[j.child] = out.get(name, name) if lumped else j.child
    return out
