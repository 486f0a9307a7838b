"""Seeded mutants of one small arm, each with its clean twin: the condition of every P rule and of the general
rules a consumer refuses on, and their exclusions (tests/rules/test_profiles_diff.py, tools/profiles_table.py)."""
from __future__ import annotations

INR = ('<inertial><origin xyz="0 0 0"/><mass value="{m}"/><inertia ixx="{a}" ixy="0" ixz="0" iyy="{b}" iyz="0" '
       'izz="{c}"/></inertial>')
BOX = '<collision><geometry><box size="0.1 0.1 0.1"/></geometry></collision>'


def inertial(m="1", a="0.01", b="0.01", c="0.01") -> str:
    return INR.format(m=m, a=a, b=b, c=c)


def link(name: str, body: str | None = None) -> str:
    return f'<link name="{name}">{inertial() + BOX if body is None else body}</link>'


def joint(name, parent, child, kind="revolute", limit='<limit lower="-1" upper="1" effort="10" velocity="1"/>',
          axis='<axis xyz="0 0 1"/>', extra="") -> str:
    body = f'<parent link="{parent}"/><child link="{child}"/><origin xyz="0 0 0.1"/>'
    if kind not in ("fixed", "floating"):
        body += axis + (limit if kind != "continuous" or "limit" not in limit else "")
    return f'<joint name="{name}" type="{kind}">{body}{extra}</joint>'


def robot(*parts) -> str:
    return '<?xml version="1.0"?>\n<robot name="r">\n  ' + "\n  ".join(parts) + "\n</robot>\n"


def arm(base=None, upper=None, fore=None, shoulder=None, elbow=None, tail=()) -> str:
    return robot(link("base_link", base), link("upper", upper), link("fore", fore),
                 shoulder or joint("shoulder", "base_link", "upper"), elbow or joint("elbow", "upper", "fore"), *tail)


def gripper(mimic='<mimic joint="left"/>', right="revolute") -> str:
    return robot(link("base_link"), link("left_finger"), link("right_finger"),
                 joint("left", "base_link", "left_finger"),
                 joint("right", "base_link", "right_finger", right, extra=mimic))


BARE = ""
# an SDFormat joint written into the model by a <gazebo> block (PR2's gripper linkage)
PARALLEL = ('<gazebo><joint name="parallel" type="revolute"><parent>finger</parent><child>palm</child>'
            '<axis><xyz>0 0 1</xyz></axis></joint></gazebo>')
EMPTY_COLLISION = BOX  # no <inertial>, a collision box (MuJoCo gives it mass from the box)

# label -> (mutant, clean twin)
MUTANTS = {
    "root without inertial, moving child": (arm(base=BARE), arm()),
    "root without inertial, fixed child with mass": (
        robot(link("base_footprint", BARE), link("base_link"), link("upper"),
              joint("footprint", "base_footprint", "base_link", "fixed"), joint("shoulder", "base_link", "upper")),
        robot(link("base_footprint"), link("base_link"), link("upper"),
              joint("footprint", "base_footprint", "base_link", "fixed"), joint("shoulder", "base_link", "upper"))),
    "moving link without inertial": (arm(upper=BARE), arm()),
    "moving link without inertial, collision only": (arm(upper=EMPTY_COLLISION), arm()),
    "fixed leaf without inertial": (arm(tail=(link("tool0", BARE), joint("tool", "fore", "tool0", "fixed"))),
                                    arm(tail=(link("tool0"), joint("tool", "fore", "tool0", "fixed")))),
    "fixed leaf kept by preserveFixedJoint": (
        arm(tail=(link("tool0"), joint("tool", "fore", "tool0", "fixed"),
                  '<gazebo reference="tool"><preserveFixedJoint>true</preserveFixedJoint></gazebo>')),
        arm(tail=(link("tool0"), joint("tool", "fore", "tool0", "fixed")))),
    "massless link fixed between moving links": (
        arm(elbow=joint("elbow", "ft_sensor", "fore"),
            tail=(link("ft_sensor", BARE), joint("sensor", "upper", "ft_sensor", "fixed"))),
        arm(elbow=joint("elbow", "ft_sensor", "fore"),
            tail=(link("ft_sensor"), joint("sensor", "upper", "ft_sensor", "fixed")))),
    "massless fixed link carrying a massive fixed link": (
        arm(elbow=joint("elbow", "pad", "fore"),
            tail=(link("mount", BARE), link("pad"), joint("mount_joint", "upper", "mount", "fixed"),
                  joint("pad_joint", "mount", "pad", "fixed"))),
        arm(elbow=joint("elbow", "pad", "fore"),
            tail=(link("mount"), link("pad"), joint("mount_joint", "upper", "mount", "fixed"),
                  joint("pad_joint", "mount", "pad", "fixed")))),
    "zero mass": (arm(upper=inertial(m="0") + BOX), arm()),
    "mass 1e-6 (sdformat's zero)": (arm(upper=inertial(m="1e-6", a="1e-9", b="1e-9", c="1e-9") + BOX),
                                    arm(upper=inertial(m="1.01e-6", a="1e-9", b="1e-9", c="1e-9") + BOX)),
    "negative mass": (arm(upper=inertial(m="-1") + BOX), arm()),
    "inertia not positive definite": (arm(upper=inertial(a="-0.01") + BOX), arm()),
    "inertia breaks triangle": (arm(upper=inertial(a="0.001", b="0.001", c="0.01") + BOX), arm()),
    "zero axis": (arm(elbow=joint("elbow", "upper", "fore", axis='<axis xyz="0 0 0"/>')), arm()),
    "floating joint": (arm(elbow=joint("elbow", "upper", "fore", "floating")), arm()),
    "planar joint": (arm(elbow=joint("elbow", "upper", "fore", "planar")), arm()),
    "continuous joint": (arm(elbow=joint("elbow", "upper", "fore", "continuous")), arm()),
    "prismatic joint": (arm(elbow=joint("elbow", "upper", "fore", "prismatic")), arm()),
    "mimic": (gripper(), gripper(mimic="")),
    "mimic on a fixed joint": (gripper(right="fixed"), gripper(mimic="", right="fixed")),
    "self mimic": (gripper(mimic='<mimic joint="right"/>'), gripper(mimic="")),
    "negative effort": (arm(elbow=joint("elbow", "upper", "fore",
                                        limit='<limit lower="-1" upper="1" effort="-10" velocity="1"/>')), arm()),
    "negative velocity": (arm(elbow=joint("elbow", "upper", "fore",
                                          limit='<limit lower="-1" upper="1" effort="10" velocity="-1"/>')), arm()),
    "inverted limits": (arm(elbow=joint("elbow", "upper", "fore",
                                        limit='<limit lower="1" upper="-1" effort="10" velocity="1"/>')), arm()),
    "revolute without limit": (arm(elbow=joint("elbow", "upper", "fore", limit="")), arm()),
    "zero effort, no actuator": (arm(elbow=joint("elbow", "upper", "fore",
                                                 limit='<limit lower="-1" upper="1" effort="0" velocity="1"/>')),
                                 arm()),
    "gazebo joint naming a lumped link": (
        arm(tail=(link("palm"), joint("palm_joint", "fore", "palm", "fixed"), link("finger"),
                  joint("finger_joint", "fore", "finger"), PARALLEL)),
        arm(tail=(link("palm"), joint("palm_joint", "fore", "palm", "fixed"), link("finger"),
                  joint("finger_joint", "fore", "finger"), PARALLEL,
                  '<gazebo reference="palm_joint"><preserveFixedJoint>true</preserveFixedJoint></gazebo>'))),
    "floating joint from the root": (
        robot(link("base_link"), link("body"), joint("free", "base_link", "body", "floating")),
        robot(link("base_link"), link("body"), joint("free", "base_link", "body", "fixed"))),
    "two trees": (arm(tail=(link("stray"), link("stray_child"), joint("stray_joint", "stray", "stray_child"))),
                  arm(tail=(link("stray"), link("stray_child"), joint("stray_joint", "stray", "stray_child"),
                            joint("stray_anchor", "fore", "stray", "fixed")))),
    "two roots": (arm(tail=(link("stray"),)), arm()),
    "loop": (arm(tail=(joint("back", "fore", "base_link"),)), arm()),
    "duplicate link": (arm(tail=(link("upper"),)), arm()),
    "duplicate joint": (arm(tail=(link("extra"), joint("elbow", "fore", "extra"))),
                        arm(tail=(link("extra"), joint("wrist", "fore", "extra")))),
    "fixed to world": (robot('<link name="world"/>', link("base_link"), link("upper"),
                             joint("anchor", "world", "base_link", "fixed"), joint("shoulder", "base_link", "upper")),
                       robot(link("base_link"), link("upper"), joint("shoulder", "base_link", "upper"))),
    "root with inertial, fixed to world": (
        robot('<link name="world"/>', link("base_link", BARE), link("upper"),
              joint("anchor", "world", "base_link", "fixed"), joint("shoulder", "base_link", "upper")),
        robot('<link name="world"/>', link("base_link"), link("upper"),
              joint("anchor", "world", "base_link", "fixed"), joint("shoulder", "base_link", "upper"))),
}


KEEP_MESHES = "<!-- urdfcheck-diff: keep meshes -->"  # loaded as written, next to the mesh files write() makes


def keep(text: str) -> str:
    return text.replace('<robot name="r">', '<robot name="r">' + KEEP_MESHES, 1)


def meshed(filename: str) -> str:
    return keep(arm(upper=inertial() + f'<collision><geometry><mesh filename="{filename}"/></geometry>'
                             '</collision>'))


MUTANTS.update({
    "collada collision mesh": (meshed("box.dae"), meshed("box.stl")),
    "missing collision mesh": (meshed("missing.stl"), meshed("box.stl")),
    "package:// collision mesh": (meshed("package://r_description/box.stl"), meshed("box.stl")),
    "missing visual mesh": (keep(arm(upper=inertial() + BOX + '<visual><geometry><mesh filename="missing.stl"/>'
                                     '</geometry></visual>')), meshed("box.stl")),
})


def write(folder: str) -> list[tuple[str, str]]:
    """(label, path) for every mutant and twin, written into `folder`, with the mesh files they name."""
    import os
    import shutil

    from urdfcheck.verify.consumers import _box_stl

    stl = _box_stl(folder, [0.1, 0.1, 0.1], 0)
    os.replace(stl, os.path.join(folder, "box.stl"))
    shutil.copy(os.path.join(os.path.dirname(os.path.abspath(__file__)), "data", "box.dae"), folder)
    out = []
    for i, (label, pair) in enumerate(MUTANTS.items()):
        for kind, text in zip(("mutant", "twin"), pair):
            path = os.path.join(folder, f"{i:02d}-{kind}.urdf")
            with open(path, "w", encoding="utf-8") as f:
                f.write(text)
            out.append((f"{label} [{kind}]", path))
    return out
