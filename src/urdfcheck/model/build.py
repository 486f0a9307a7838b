"""Build the Model from a parsed (and expanded) URDF document.

Values that cannot be read do not stop the build: they become `Issue`s (reported by the U rules) and
the part gets the value URDF parsers default to, so later rules see a usable model. Links and joints
written the ordinary way are read by fastbuild.py instead; this builder takes over whatever it refuses.
"""
from __future__ import annotations

import math
import re
from types import MappingProxyType
from typing import Callable

from lxml import etree

from urdfcheck.core import nogc
from urdfcheck.model.fastbuild import INERTIA, NO_DYNAMICS, ONE, POSE0, SRC_ATTR, TOLERATED, X_AXIS, ZERO, FastParts, Irregular
from urdfcheck.core.findings import Location, closest
from urdfcheck.model.robot import Block, Geometry, HardwareItem, Inertial, Interface, Issue, Joint, Limit, Link, Material, MaterialRef, Mimic, Model, Pose, Ros2Control, Shape, Transmission

# element -> (attributes, child elements) of the URDF core; extension blocks are not checked
SCHEMA = {
    "robot": ({"name", "version"}, {"link", "joint", "material", "transmission", "gazebo", "ros2_control"}),
    "link": ({"name", "type"}, {"inertial", "visual", "collision"}),
    "inertial": (set(), {"origin", "mass", "inertia"}),
    "mass": ({"value"}, set()),
    "inertia": ({"ixx", "ixy", "ixz", "iyy", "iyz", "izz"}, set()),
    "visual": ({"name"}, {"origin", "geometry", "material"}),
    "collision": ({"name"}, {"origin", "geometry"}),
    "origin": ({"xyz", "rpy"}, set()),
    "geometry": (set(), {"box", "cylinder", "sphere", "mesh", "capsule"}),
    "box": ({"size"}, set()),
    "cylinder": ({"radius", "length"}, set()),
    "capsule": ({"radius", "length"}, set()),
    "sphere": ({"radius"}, set()),
    "mesh": ({"filename", "scale"}, set()),
    "material": ({"name"}, {"color", "texture"}),
    "color": ({"rgba"}, set()),
    "texture": ({"filename"}, set()),
    "joint": ({"name", "type"}, {"origin", "parent", "child", "axis", "calibration", "dynamics", "limit",
                                  "mimic", "safety_controller"}),
    "parent": ({"link"}, set()),
    "child": ({"link"}, set()),
    "axis": ({"xyz"}, set()),
    "calibration": ({"rising", "falling", "reference_position"}, set()),
    "dynamics": ({"damping", "friction"}, set()),
    "limit": ({"lower", "upper", "effort", "velocity"}, set()),
    "mimic": ({"joint", "multiplier", "offset"}, set()),
    "safety_controller": ({"soft_lower_limit", "soft_upper_limit", "k_position", "k_velocity"}, set()),
}
for _attrs, _ in SCHEMA.values():
    _attrs.add(SRC_ATTR)  # the xacro source marker is ours, never "unknown"


def _unexpanded(raw: str) -> str:
    """A hint for xacro syntax left in a file read as plain URDF (e.g. a .urdf that still says $(optenv ...))."""
    if "$(" in raw or "${" in raw:
        return ("; it is an unexpanded xacro substitution: URDF consumers read it literally (expand the file with "
                "xacro, or name it .xacro and declare xmlns:xacro)")
    return ""


class _Builder:
    def __init__(self, locate: Callable[[object], Location], source: str):
        self.locate = locate
        self.source = source
        self.issues: list[Issue] = []

    # --- reading values ----------------------------------------------------------
    def issue(self, code: str, message: str, el) -> None:
        self.issues.append(Issue(code, message, self.locate(el)))

    def number(self, el, attr: str, default: float | None = None, *, required: bool = False) -> float | None:
        raw = el.get(attr)
        if raw is None:
            if required:
                self.issue("U006", f"<{el.tag}> has no {attr!r} attribute", el)
            return default
        try:
            value = float(raw)
        except ValueError:
            self.issue("U005", f"<{el.tag} {attr}={raw!r}> is not a number{_unexpanded(raw)}", el)
            return default
        if value - value != 0.0 or "_" in raw:  # nan/inf, or Python-only digit separators
            self.issue("U005", f"<{el.tag} {attr}={raw!r}> is not a finite plain number", el)
            return default
        return value

    def vector(self, el, attr: str, n: int, default: tuple | None, *, required: bool = False):
        raw = el.get(attr)
        if raw is None:
            if required:
                self.issue("U006", f"<{el.tag}> has no {attr!r} attribute", el)
            return default
        parts = raw.split()
        if len(parts) != n:
            self.issue("U004", f"<{el.tag} {attr}={raw!r}> has {len(parts)} values; {n} expected{_unexpanded(raw)}", el)
            return default
        try:
            out = tuple(map(float, parts))
        except ValueError:
            out = None
        if out is None or "_" in raw or not all(map(math.isfinite, out)):
            self.issue("U005", f"<{el.tag} {attr}={raw!r}>: not {n} finite plain numbers{_unexpanded(raw)}", el)
            return default
        return out

    # --- parts -------------------------------------------------------------------
    # Each element's children are walked once with a dispatch on the tag (lxml proxies are costly).
    def pose(self, el) -> Pose:
        self.check(el, "origin")
        return Pose(self.vector(el, "xyz", 3, ZERO), self.vector(el, "rpy", 3, ZERO), self.locate(el))

    def geometry(self, g) -> Geometry:
        self.check(g, "geometry")
        shapes = [c for c in g if isinstance(c.tag, str) and not c.tag.startswith("{")]
        if not shapes:
            return Geometry("", self.locate(g))
        if len(shapes) > 1:
            self.issue("U002", f"<geometry> holds {len(shapes)} shapes; URDF parsers use only the first", shapes[1])
        s = shapes[0]
        tag = s.tag
        if tag in _SHAPES:  # an unknown shape is G005's (urdfdom rejects the visual)
            self.check(s, tag)
        loc = self.locate(s)
        if tag == "box":
            return Geometry("box", loc, size=self.vector(s, "size", 3, None, required=True))
        if tag == "cylinder" or tag == "capsule":
            return Geometry(tag, loc, radius=self.number(s, "radius", None, required=True),
                            length=self.number(s, "length", None, required=True))
        if tag == "sphere":
            return Geometry("sphere", loc, radius=self.number(s, "radius", None, required=True))
        if tag == "mesh":
            fn = s.get("filename")
            if not fn:
                self.issue("U006", "<mesh> has no 'filename' attribute", s)
            return Geometry("mesh", loc, filename=fn or None, scale=self.vector(s, "scale", 3, ONE))
        return Geometry(tag, loc)

    def _colour_texture(self, mat):
        rgba = texture = None
        for c in mat:
            if c.tag == "color":
                self.check(c, "color")
                rgba = self.vector(c, "rgba", 4, None, required=True)
            elif c.tag == "texture":
                self.check(c, "texture")
                texture = c.get("filename")
            else:
                self.unknown("material", c)
        return rgba, texture

    def material(self, el) -> Material | None:
        self.check(el, "material")
        name = el.get("name")
        if not name:
            self.issue("U006", "<material> has no 'name' attribute", el)
            return None
        rgba, texture = self._colour_texture(el)
        return Material(name, self.locate(el), rgba, texture)

    def shape(self, el, kind: str) -> Shape:
        self.check(el, kind)
        origin, geometry, mat = POSE0, None, None
        for c in el:
            tag = c.tag
            if tag == "origin":
                origin = self.pose(c)
            elif tag == "geometry":
                geometry = self.geometry(c)
            elif tag == "material" and kind == "visual":
                self.check(c, "material")
                rgba, texture = self._colour_texture(c)
                name = c.get("name")
                if name is None:  # urdfdom then rejects the visual and stops reading the link
                    self.issue("U006", "<material> in a <visual> has no 'name' attribute", c)
                mat = MaterialRef(name or "", self.locate(c), rgba, texture)
            else:
                self.unknown(kind, c)
        return Shape(kind, self.locate(el), el.get("name") or "", origin, geometry, mat)

    def inertial(self, el) -> Inertial:
        self.check(el, "inertial")
        origin, mass, mass_loc, inertia, inertia_loc = POSE0, None, None, None, None
        for c in el:
            tag = c.tag
            if tag == "mass":
                self.check(c, "mass")
                mass = self.number(c, "value", None, required=True)
                mass_loc = self.locate(c)
            elif tag == "inertia":
                self.check(c, "inertia")
                number = self.number
                inertia = tuple(number(c, k, 0.0, required=True) for k in INERTIA)
                inertia_loc = self.locate(c)
            elif tag == "origin":
                origin = self.pose(c)
            else:
                self.unknown("inertial", c)
        return Inertial(self.locate(el), origin, mass, mass_loc, inertia, inertia_loc)

    def link(self, el) -> Link | None:
        self.check(el, "link")
        name = el.get("name")
        if not name:
            self.issue("U006", "<link> has no 'name' attribute", el)
            return None
        inertial, visuals, collisions = None, [], []
        for c in el:
            tag = c.tag
            if tag == "visual":
                visuals.append(self.shape(c, "visual"))
            elif tag == "collision":
                collisions.append(self.shape(c, "collision"))
            elif tag == "inertial":
                if inertial is None:
                    inertial = self.inertial(c)
                else:
                    self.issue("U002", f"link {name!r} has more than one <inertial>; only the first is used", c)
            else:
                self.unknown("link", c)
        return Link(name, self.locate(el), inertial, tuple(visuals), tuple(collisions))

    def joint(self, el) -> Joint | None:
        self.check(el, "joint")
        name = el.get("name")
        if not name:
            self.issue("U006", "<joint> has no 'name' attribute", el)
            return None
        jtype = el.get("type")
        if jtype is None:
            self.issue("U006", f"joint {name!r} has no 'type' attribute", el)
            jtype = ""
        ends = {}
        origin, axis, axis_loc, limit, mimic, dyn = POSE0, X_AXIS, None, None, None, {}
        for c in el:
            tag = c.tag
            if tag == "parent" or tag == "child":
                self.check(c, tag)
                link = c.get("link")
                if not link:
                    self.issue("U006", f"<{tag}> of joint {name!r} has no 'link' attribute", c)
                ends[tag] = (link or None, self.locate(c))
            elif tag == "origin":
                origin = self.pose(c)
            elif tag == "axis":
                self.check(c, "axis")
                # urdfdom reads <axis/> without xyz as a zero vector (robot_state_publisher then
                # publishes NaN), not as the default x axis: model what the robot will do
                axis = self.vector(c, "xyz", 3, ZERO, required=True)
                axis_loc = self.locate(c)
            elif tag == "limit":
                self.check(c, "limit")
                # urdfdom refuses any <limit> without effort and velocity, whatever the joint type
                limit = Limit(self.locate(c), self.number(c, "lower"), self.number(c, "upper"),
                              self.number(c, "effort", required=True), self.number(c, "velocity", required=True))
            elif tag == "mimic":
                self.check(c, "mimic")
                target = c.get("joint")
                if not target:
                    self.issue("U006", f"<mimic> of joint {name!r} has no 'joint' attribute", c)
                else:
                    mimic = Mimic(self.locate(c), target, self.number(c, "multiplier", 1.0),
                                  self.number(c, "offset", 0.0))
            elif tag == "dynamics":
                self.check(c, "dynamics")
                for k in ("damping", "friction"):
                    v = self.number(c, k)
                    if v is not None:
                        dyn[k] = v
            elif tag == "calibration" or tag == "safety_controller":
                self.check(c, tag)
                for k in c.keys():
                    if k in SCHEMA[tag][0] and k != SRC_ATTR:
                        self.number(c, k)
            else:
                self.unknown("joint", c)
        for end in ("parent", "child"):
            if end not in ends:
                self.issue("U006", f"joint {name!r} has no <{end}> element", el)
                ends[end] = (None, None)
        return Joint(name, jtype, self.locate(el), ends["parent"][0], ends["child"][0], origin, axis,
                     axis_loc, limit, mimic, MappingProxyType(dyn) if dyn else NO_DYNAMICS,
                     ends["parent"][1], ends["child"][1])

    def ros2_control(self, el, in_gazebo: bool) -> Ros2Control:
        items = {"joint": [], "sensor": [], "gpio": []}
        plugin = ""
        hw = el.find("hardware")
        if hw is not None:
            p = hw.find("plugin")
            plugin = (p.text or "").strip() if p is not None else ""
        for c in el:
            if c.tag in items:
                cmd = tuple(Interface(i.get("name") or "", self.locate(i)) for i in c.findall("command_interface"))
                st = tuple(Interface(i.get("name") or "", self.locate(i)) for i in c.findall("state_interface"))
                mimic = (c.get("mimic") or "").strip().lower() == "true" or any(
                    (q.get("name") or "").strip() == "mimic" for q in c.findall("param"))
                items[c.tag].append(HardwareItem(c.tag, c.get("name") or "", self.locate(c), cmd, st, mimic))
        return Ros2Control(el.get("name") or "", el.get("type") or "", self.locate(el), plugin,
                           tuple(items["joint"]), tuple(items["sensor"]), tuple(items["gpio"]), in_gazebo)

    def transmission(self, el) -> Transmission:
        joints = tuple(Interface(j.get("name") or "", self.locate(j)) for j in el.findall("joint"))
        return Transmission(el.get("name") or "", self.locate(el), joints)

    # --- unknown elements and attributes (typos such as <orign>) ------------------
    def check(self, el, tag: str) -> None:
        """Unknown attributes of a URDF core element; for leaf elements also any child element."""
        attrs, children = SCHEMA[tag]
        keys = el.keys()
        if keys and not attrs.issuperset(keys):
            for a in keys:
                if a not in attrs and not a.startswith("{"):
                    self.issue("U003", f"<{tag}> has unknown attribute {a!r}{_hint(a, attrs)}", el)
        if not children and len(el):
            for c in el:
                if isinstance(c.tag, str) and not c.tag.startswith("{"):
                    self.issue("U002", f"<{tag}> takes no child elements; <{c.tag}> is ignored", c)

    def unknown(self, parent_tag: str, c) -> None:
        tag = c.tag
        if not isinstance(tag, str) or tag.startswith("{") or tag in TOLERATED.get(parent_tag, ()):
            return
        allowed = SCHEMA[parent_tag][1]
        self.issue("U002", f"unknown element <{tag}> in <{parent_tag}>{_hint(tag, allowed)}; "
                           "URDF parsers ignore it", c)


_SHAPES = ("box", "cylinder", "capsule", "sphere", "mesh")


def _hint(word: str, options) -> str:
    close = closest(word, sorted(options))
    return f" (did you mean {close!r}?)" if close else ""


def _raw_xml(el) -> str:
    text = etree.tostring(el, encoding="unicode", with_tail=False)
    return re.sub(r' __ucsrc="[^"]*"', "", text)


def build(root, locate: Callable[[object], Location], source: str) -> Model:
    return nogc.call(_build, root, locate, source, long_lived=True)


def _build(root, locate: Callable[[object], Location], source: str) -> Model:
    b = _Builder(locate, source)
    fast = FastParts(locate)
    if root.tag != "robot":
        b.issue("U001", f"the root element is <{root.tag}>, not <robot>", root)
    if root.tag == "robot":
        b.check(root, "robot")
    links, joints, materials, blocks, r2c, trans = [], [], [], [], [], []
    for el in root:
        if not isinstance(el.tag, str):
            continue
        if el.tag == "link":
            try:
                links.append(fast.link(el))
            except Irregular:  # something to report or to read with care: the careful builder's
                part = b.link(el)
                if part:
                    links.append(part)
        elif el.tag == "joint":
            try:
                joints.append(fast.joint(el))
            except Irregular:
                part = b.joint(el)
                if part:
                    joints.append(part)
        elif el.tag == "material":
            part = b.material(el)
            if part:
                materials.append(part)
        elif el.tag in ("transmission", "gazebo", "ros2_control"):
            blocks.append(Block(el.tag, locate(el), MappingProxyType(dict(el.attrib)), _raw_xml(el)))
            if el.tag == "ros2_control":
                r2c.append(b.ros2_control(el, False))
            elif el.tag == "gazebo":
                for inner in el.iter("ros2_control"):
                    r2c.append(b.ros2_control(inner, True))
            else:
                trans.append(b.transmission(el))
        elif root.tag == "robot":
            b.unknown("robot", el)
    return Model(
        name=root.get("name") or "",
        loc=locate(root),
        links=MappingProxyType(_first_by_name(links)),
        joints=MappingProxyType(_first_by_name(joints)),
        materials=MappingProxyType(_first_by_name(materials)),
        link_list=tuple(links),
        joint_list=tuple(joints),
        material_list=tuple(materials),
        blocks=tuple(blocks),
        issues=tuple(b.issues),
        source=source,
        ros2_control=tuple(r2c),
        transmissions=tuple(trans),
    )


def _first_by_name(parts) -> dict:
    out = {}
    for p in parts:
        out.setdefault(p.name, p)
    return out


def model_from_string(xml: str | bytes, path: str = "<string>") -> Model:
    """Model from URDF text (plain URDF; for xacro use `urdfcheck.load.load_model`)."""
    from urdfcheck.core import xmlfront

    data = xml.encode("utf-8") if isinstance(xml, str) else xml
    root, _ = xmlfront.parse(data)
    return build(root, lambda el: Location(path, el.sourceline), path)
