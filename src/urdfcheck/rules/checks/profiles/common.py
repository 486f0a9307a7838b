"""What the profile rules share: the profile names, when a rule speaks and how loudly, and which general rules a
profile reads as its consumer's own refusal or change of the model (`annotating`, GENERAL)."""
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

# General rules whose findings are, for a profile's consumer, the consumer's own refusal or change of the model:
# with the profile on, those findings carry the profile (JSON "profile", "profiles"), so a report filtered by
# profile says whether the consumer loads the model and what it does to it. The data, measured per consumer,
# follows (GENERAL; behaviour.py holds the rest of what each consumer does).


# urdfdom (urdf_parser/src/model.cpp, joint.cpp, link.cpp) refuses these while parsing; Pinocchio, sdformat's URDF
# converter and kdl_parser read URDF through it (measured with Debian's urdfdom 3.0). Which urdfdom reads a model
# (3.x up to Humble, 4.x from Jazzy on, which reads URDF 1.1) is the target distribution's (--target, U007, U008)
URDFDOM = ("U001", "U004", "U005", "U006", "U007", "S001", "S002", "S003", "S004", "S005", "S006", "S007", "S008",
           "S011", "J001", "J002", "I001")

# consumer -> general rule -> what the consumer does about that finding's defect. "refuses": it will not load the
# model; anything else says how it changes the model. Each entry was measured on a mutant and its clean twin
# (tests/profile_mutants.py) unless it says "source".
GENERAL = {
    # Pinocchio: urdfdom's refusals, and a mesh it cannot find when it builds the geometry models
    # (buildGeomFromUrdf, as RobotWrapper.BuildFromURDF does: "Mesh X could not be found")
    "pinocchio": {**dict.fromkeys(URDFDOM, "refuses"), "G001": "refuses"},
    "kdl": {**dict.fromkeys(URDFDOM, "refuses"),
            # source: kdl_parser.cpp treeFromUrdfModel (measured too: the root segment's mass is 0)
            "I005": "ignores the root link's inertia"},
    "gazebo": {**dict.fromkeys(URDFDOM, "refuses"),
               # sdformat's validation of the converted model (ign sdf -k; Gazebo loads through the same checks):
               # "The norm of the xyz vector cannot be zero". An invalid inertia is P012's: the tensor sdformat
               # validates is the lumped one, and a link lumped into another is no longer judged alone
               "J006": "refuses",
               # `ign sdf -p` copies <effort>-10</effort> as written; SDFormat's joint axis <effort> and <velocity>
               # are "not enforced if negative" (the spec, sdf/1.9/joint.sdf): the joint has no such limit
               "J004": "reads a negative effort or velocity as no limit"},
    # Bullet's own UrdfParser.cpp: "Expected a single base link", "Joint ... not found", duplicate names
    # (a crash on two roots and on a repeated joint name), a revolute/prismatic joint without <limit>
    "pybullet": {**dict.fromkeys(("U001", "S001", "S002", "S003", "S004", "S005", "S006", "S007", "S008", "S011",
                                  "J002"),
                                 "refuses"),
                 # BulletUrdfImporter.cpp convertURDFToVisualShape/CollisionShape: a mesh file it cannot find
                 # (visual or collision) fails the load, "Cannot load URDF file" (measured)
                 "G001": "refuses",
                 # lower > upper is read as no limit at all (measured: a position motor takes the joint to 2.5
                 # with lower 1, upper -1; btMultiBody's limit constraint is only made when lower <= upper)
                 "J003": "reads inverted limits as no limit (lower > upper disables the joint limit)"},
    # MuJoCo: "axis too small in joint" (user_objects.cc mjCJoint::Compile); xml_urdf.cc: a joint naming a missing
    # link, a body with two parents, a cycle or no root ("URDF body not found"), a repeated link name ("repeated
    # URDF name"); a value that is no number or has the wrong count ("bad format in attribute", "too much data")
    "mujoco": dict.fromkeys(("J006", "S002", "S003", "S004", "S005", "S007", "U004", "U005"), "refuses"),
}

# the profile rules that say the consumer refuses the model (their catalogue severity is error)
REFUSING = {
    "mujoco": ("P001", "P002", "P005", "P006", "P007", "P008"),
    "gazebo": ("P012",),
    "pinocchio": ("P040",),
}


def annotating(code: str, active) -> tuple[str, ...]:
    """Every active profile whose consumer refuses or changes the model for a finding of general rule `code`."""
    return tuple(name for name in active if code in GENERAL.get(name, ()))


def annotates(code: str, active) -> str:
    got = annotating(code, active)
    return got[0] if got else ""


def speak(ctx, profiles: tuple[str, ...], message: str, at, *, quiet: bool = False, related=()):
    """A Problem from a profile rule, or None. With one of `profiles` active: the catalogue severity, naming the
    first active one. Without: an info naming the consumers (what only a profile would fail stays visible), or
    nothing when `quiet` (a general rule already reports the same defect, or the behaviour is only a change)."""
    active = [p for p in profiles if p in getattr(ctx, "profiles", ())]
    if active:
        return Problem(message, at=at, related=related, data={"profile": active[0], "profiles": tuple(active)})
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
