"""Build the Model from a parsed (and expanded) URDF document.

Values that cannot be read do not stop the build: they become `Issue`s (reported by the U rules) and
the part gets the value URDF parsers default to, so later rules see a usable model.
"""
from __future__ import annotations

import difflib
import math
import re
from types import MappingProxyType
from typing import Callable

from lxml import etree

from .findings import Location
from .model import (Block, Geometry, HardwareItem, Inertial, Interface, Issue, Joint, Limit, Link, Material,
                    MaterialRef, Mimic, Model, Pose, Ros2Control, Shape, Transmission)

SRC_ATTR = "__ucsrc"
_NUM = re.compile(r"^\s*[-+]?(\d+\.?\d*|\.\d+)([eE][-+]?\d+)?\s*$")

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
# children that real-world packages carry and URDF parsers ignore without harm
_TOLERATED = {"robot": {"sensor"}, "collision": {"verbose"}, "link": {"self_collision_checking"}}


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
        if not _NUM.match(raw):
            self.issue("U005", f"<{el.tag} {attr}={raw!r}> is not a number", el)
            return default
        value = float(raw)
        if not math.isfinite(value):
            self.issue("U005", f"<{el.tag} {attr}={raw!r}> is not a finite number", el)
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
            self.issue("U004", f"<{el.tag} {attr}={raw!r}> has {len(parts)} values; {n} expected", el)
            return default
        out = []
        for p in parts:
            if not _NUM.match(p) or not math.isfinite(float(p)):
                self.issue("U005", f"<{el.tag} {attr}={raw!r}>: {p!r} is not a finite number", el)
                return default
            out.append(float(p))
        return tuple(out)

    def check_shape(self, el) -> None:
        """Unknown attributes and child elements of URDF core elements (typos such as <orign>)."""
        spec = SCHEMA.get(el.tag)
        if spec is None:
            return
        attrs, children = spec
        for a in el.attrib:
            if a == SRC_ATTR or a.startswith("{") or a in attrs:
                continue
            hint = _hint(a, attrs)
            self.issue("U003", f"<{el.tag}> has unknown attribute {a!r}{hint}", el)
        tolerated = _TOLERATED.get(el.tag, set())
        for c in el:
            if not isinstance(c.tag, str) or c.tag.startswith("{") or c.tag in children or c.tag in tolerated:
                continue
            if not children and el.tag != "robot":
                self.issue("U002", f"<{el.tag}> takes no child elements; <{c.tag}> is ignored", c)
            else:
                self.issue("U002", f"unknown element <{c.tag}> in <{el.tag}>{_hint(c.tag, children)}; "
                                   "URDF parsers ignore it", c)

    # --- parts -------------------------------------------------------------------
    def pose(self, parent) -> Pose:
        el = parent.find("origin")
        if el is None:
            return Pose()
        self.check_shape(el)
        return Pose(self.vector(el, "xyz", 3, (0.0, 0.0, 0.0)), self.vector(el, "rpy", 3, (0.0, 0.0, 0.0)),
                    self.locate(el))

    def geometry(self, parent) -> Geometry | None:
        g = parent.find("geometry")
        if g is None:
            return None
        self.check_shape(g)
        shapes = [c for c in g if isinstance(c.tag, str)]
        if not shapes:
            return Geometry("", self.locate(g))
        if len(shapes) > 1:
            self.issue("U002", f"<geometry> holds {len(shapes)} shapes; URDF parsers use only the first", shapes[1])
        s = shapes[0]
        self.check_shape(s)
        loc = self.locate(s)
        if s.tag == "box":
            return Geometry("box", loc, size=self.vector(s, "size", 3, None, required=True))
        if s.tag in ("cylinder", "capsule"):
            return Geometry(s.tag, loc, radius=self.number(s, "radius", None, required=True),
                            length=self.number(s, "length", None, required=True))
        if s.tag == "sphere":
            return Geometry("sphere", loc, radius=self.number(s, "radius", None, required=True))
        if s.tag == "mesh":
            fn = s.get("filename")
            if not fn:
                self.issue("U006", "<mesh> has no 'filename' attribute", s)
            return Geometry("mesh", loc, filename=fn or None, scale=self.vector(s, "scale", 3, (1.0, 1.0, 1.0)))
        return Geometry(s.tag, loc)

    def color(self, mat) -> tuple | None:
        c = mat.find("color")
        if c is None:
            return None
        self.check_shape(c)
        return self.vector(c, "rgba", 4, None, required=True)

    def texture(self, mat) -> str | None:
        t = mat.find("texture")
        return t.get("filename") if t is not None else None

    def material(self, el) -> Material | None:
        self.check_shape(el)
        name = el.get("name")
        if not name:
            self.issue("U006", "<material> has no 'name' attribute", el)
            return None
        return Material(name, self.locate(el), self.color(el), self.texture(el))

    def shape(self, el, kind: str) -> Shape:
        self.check_shape(el)
        mat = None
        m = el.find("material") if kind == "visual" else None
        if m is not None:
            self.check_shape(m)
            mat = MaterialRef(m.get("name") or "", self.locate(m), self.color(m), self.texture(m))
        return Shape(kind, self.locate(el), el.get("name") or "", self.pose(el), self.geometry(el), mat)

    def inertial(self, el) -> Inertial:
        self.check_shape(el)
        mass_el = el.find("mass")
        mass = mass_loc = None
        if mass_el is not None:
            self.check_shape(mass_el)
            mass = self.number(mass_el, "value", None, required=True)
            mass_loc = self.locate(mass_el)
        inertia = inertia_loc = None
        i_el = el.find("inertia")
        if i_el is not None:
            self.check_shape(i_el)
            vals = [self.number(i_el, k, None, required=True) for k in ("ixx", "ixy", "ixz", "iyy", "iyz", "izz")]
            inertia = tuple(v if v is not None else 0.0 for v in vals)
            inertia_loc = self.locate(i_el)
        return Inertial(self.locate(el), self.pose(el), mass, mass_loc, inertia, inertia_loc)

    def link(self, el) -> Link | None:
        self.check_shape(el)
        name = el.get("name")
        if not name:
            self.issue("U006", "<link> has no 'name' attribute", el)
            return None
        inertials = el.findall("inertial")
        if len(inertials) > 1:
            self.issue("U002", f"link {name!r} has {len(inertials)} <inertial> elements; only the first is used",
                       inertials[1])
        return Link(
            name, self.locate(el),
            self.inertial(inertials[0]) if inertials else None,
            tuple(self.shape(v, "visual") for v in el.findall("visual")),
            tuple(self.shape(c, "collision") for c in el.findall("collision")),
        )

    def joint(self, el) -> Joint | None:
        self.check_shape(el)
        name = el.get("name")
        if not name:
            self.issue("U006", "<joint> has no 'name' attribute", el)
            return None
        jtype = el.get("type")
        if jtype is None:
            self.issue("U006", f"joint {name!r} has no 'type' attribute", el)
            jtype = ""
        ends = {}
        for end in ("parent", "child"):
            e = el.find(end)
            if e is None:
                self.issue("U006", f"joint {name!r} has no <{end}> element", el)
                ends[end] = (None, None)
                continue
            self.check_shape(e)
            link = e.get("link")
            if not link:
                self.issue("U006", f"<{end}> of joint {name!r} has no 'link' attribute", e)
            ends[end] = (link or None, self.locate(e))
        axis, axis_loc = (1.0, 0.0, 0.0), None
        a = el.find("axis")
        if a is not None:
            self.check_shape(a)
            axis = self.vector(a, "xyz", 3, (1.0, 0.0, 0.0), required=True)
            axis_loc = self.locate(a)
        limit = None
        lim = el.find("limit")
        if lim is not None:
            self.check_shape(lim)
            needs = jtype in ("revolute", "prismatic")
            limit = Limit(self.locate(lim), self.number(lim, "lower"), self.number(lim, "upper"),
                          self.number(lim, "effort", required=needs), self.number(lim, "velocity", required=needs))
        mimic = None
        mi = el.find("mimic")
        if mi is not None:
            self.check_shape(mi)
            target = mi.get("joint")
            if not target:
                self.issue("U006", f"<mimic> of joint {name!r} has no 'joint' attribute", mi)
            else:
                mimic = Mimic(self.locate(mi), target, self.number(mi, "multiplier", 1.0),
                              self.number(mi, "offset", 0.0))
        dyn = {}
        d = el.find("dynamics")
        if d is not None:
            self.check_shape(d)
            for k in ("damping", "friction"):
                v = self.number(d, k)
                if v is not None:
                    dyn[k] = v
        for tag in ("calibration", "safety_controller"):
            sub = el.find(tag)
            if sub is not None:
                self.check_shape(sub)
                for k in SCHEMA[tag][0]:
                    self.number(sub, k)
        return Joint(name, jtype, self.locate(el), ends["parent"][0], ends["child"][0], self.pose(el), axis,
                     axis_loc, limit, mimic, MappingProxyType(dyn), ends["parent"][1], ends["child"][1])

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
                items[c.tag].append(HardwareItem(c.tag, c.get("name") or "", self.locate(c), cmd, st))
        return Ros2Control(el.get("name") or "", el.get("type") or "", self.locate(el), plugin,
                           tuple(items["joint"]), tuple(items["sensor"]), tuple(items["gpio"]), in_gazebo)

    def transmission(self, el) -> Transmission:
        joints = tuple(Interface(j.get("name") or "", self.locate(j)) for j in el.findall("joint"))
        return Transmission(el.get("name") or "", self.locate(el), joints)


def _hint(word: str, options) -> str:
    close = difflib.get_close_matches(word, sorted(options), n=1, cutoff=0.75)
    return f" (did you mean {close[0]!r}?)" if close else ""


def _raw_xml(el) -> str:
    text = etree.tostring(el, encoding="unicode", with_tail=False)
    return re.sub(r' __ucsrc="[^"]*"', "", text)


def build(root, locate: Callable[[object], Location], source: str) -> Model:
    b = _Builder(locate, source)
    if root.tag != "robot":
        b.issue("U001", f"the root element is <{root.tag}>, not <robot>", root)
    b.check_shape(root)
    links, joints, materials, blocks, r2c, trans = [], [], [], [], [], []
    for el in root:
        if not isinstance(el.tag, str):
            continue
        if el.tag == "link":
            part = b.link(el)
            if part:
                links.append(part)
        elif el.tag == "joint":
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
    from . import xmlfront

    data = xml.encode("utf-8") if isinstance(xml, str) else xml
    root, _ = xmlfront.parse(data)
    return build(root, lambda el: Location(path, el.sourceline), path)
