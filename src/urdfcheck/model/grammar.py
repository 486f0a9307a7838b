"""The URDF element grammar, written once.

Which elements URDF defines, which attributes and child elements each has, the type of every attribute value
(text, number, vector of n numbers), whether it is required, and the URDF version that introduced it. The
model builder (build.py) reads every element through this table, the unknown-attribute check and the
agreement tests are derived from it, and `attributes(tag, version)` tells other checks what exists in a
given URDF version.

Versions follow urdfdom: 1.0 (every urdfdom), 1.1 (urdfdom 5.1: `quat_xyzw` on <origin>, `<capsule>`),
1.2 (urdfdom 6.0: `acceleration`, `deceleration`, `jerk` on <limit>).
"""
from __future__ import annotations

Version = tuple  # (major, minor)
V1_0: Version = (1, 0)
V1_1: Version = (1, 1)
V1_2: Version = (1, 2)
VERSIONS: tuple[Version, ...] = (V1_0, V1_1, V1_2)  # what the newest urdfdom reads
NEWEST = VERSIONS[-1]

# attribute kinds
TEXT = "text"  # any string; required means present
NAME = "name"  # a string; required means present and not empty
NUMBER = "number"  # one finite number
VECTOR = "vector"  # `size` finite numbers separated by white space

SRC_ATTR = "__ucsrc"  # the xacro source marker (load.xacro.expand.SRC_ATTR); ours, allowed on every element


class Attr:
    """One attribute of a URDF element. (Plain classes here, not NamedTuples: this module is imported by every
    lint run, and each NamedTuple class costs a fraction of a millisecond to create.)"""

    __slots__ = ("name", "kind", "size", "required", "default", "since", "optional_since")

    def __init__(self, name: str, kind: str, size: int = 1, required: bool = False, default: object = None,
                 since: Version = V1_0, optional_since: Version | None = None):
        self.name = name
        self.kind = kind
        self.size = size  # values of a VECTOR
        self.required = required
        self.default = default  # the value when absent (or unreadable)
        self.since = since  # the URDF version that introduced it
        self.optional_since = optional_since  # required only in versions before this one

    def __repr__(self) -> str:
        return f"Attr({self.name!r}, {self.kind!r})"


class Element:
    """A URDF element: its attributes, the child elements it may hold, since when it exists."""

    __slots__ = ("tag", "attrs", "children", "since", "exclusive")

    def __init__(self, tag: str, attrs: tuple[Attr, ...] = (), children: tuple[str, ...] = (),
                 since: Version = V1_0, exclusive: tuple[tuple[str, ...], ...] = ()):
        self.tag = tag
        self.attrs = attrs
        self.children = children  # grammar elements allowed inside
        self.since = since
        self.exclusive = exclusive  # attributes that must not be given together (U009)

    def __repr__(self) -> str:
        return f"Element({self.tag!r})"


ZERO = (0.0, 0.0, 0.0)
ONE = (1.0, 1.0, 1.0)
INERTIA = ("ixx", "ixy", "ixz", "iyy", "iyz", "izz")
SHAPES = ("box", "cylinder", "capsule", "sphere", "mesh")


def _elements(*els: Element) -> dict[str, Element]:
    return {e.tag: e for e in els}


GRAMMAR: dict[str, Element] = _elements(
    Element("robot", (Attr("name", TEXT), Attr("version", TEXT)),
            ("link", "joint", "material", "transmission", "gazebo", "ros2_control")),
    Element("link", (Attr("name", NAME, required=True), Attr("type", TEXT)), ("inertial", "visual", "collision")),
    Element("inertial", (), ("origin", "mass", "inertia")),
    Element("mass", (Attr("value", NUMBER, required=True),)),
    Element("inertia", tuple(Attr(k, NUMBER, required=True, default=0.0) for k in INERTIA)),
    Element("visual", (Attr("name", TEXT),), ("origin", "geometry", "material")),
    Element("collision", (Attr("name", TEXT),), ("origin", "geometry")),
    # rpy and quat_xyzw are kept as written; core.geometry turns them into one rotation
    Element("origin", (Attr("xyz", VECTOR, 3, default=ZERO), Attr("rpy", VECTOR, 3, default=ZERO),
                       Attr("quat_xyzw", VECTOR, 4, since=V1_1)), exclusive=(("rpy", "quat_xyzw"),)),
    Element("geometry", (), SHAPES),
    Element("box", (Attr("size", VECTOR, 3, required=True),)),
    Element("cylinder", (Attr("radius", NUMBER, required=True), Attr("length", NUMBER, required=True))),
    Element("capsule", (Attr("radius", NUMBER, required=True), Attr("length", NUMBER, required=True)), since=V1_1),
    Element("sphere", (Attr("radius", NUMBER, required=True),)),
    Element("mesh", (Attr("filename", NAME, required=True), Attr("scale", VECTOR, 3, default=ONE))),
    Element("material", (Attr("name", TEXT, required=True),), ("color", "texture")),
    Element("color", (Attr("rgba", VECTOR, 4, required=True),)),
    Element("texture", (Attr("filename", TEXT),)),
    Element("joint", (Attr("name", NAME, required=True), Attr("type", TEXT, required=True)),
            ("origin", "parent", "child", "axis", "calibration", "dynamics", "limit", "mimic", "safety_controller")),
    Element("parent", (Attr("link", NAME, required=True),)),
    Element("child", (Attr("link", NAME, required=True),)),
    # urdfdom reads <axis/> without xyz as a zero vector (robot_state_publisher then publishes NaN)
    Element("axis", (Attr("xyz", VECTOR, 3, required=True, default=ZERO),)),
    Element("calibration", (Attr("rising", NUMBER), Attr("falling", NUMBER), Attr("reference_position", NUMBER))),
    Element("dynamics", (Attr("damping", NUMBER), Attr("friction", NUMBER))),
    # urdfdom refuses any <limit> without effort and velocity, whatever the joint type, until URDF 1.2, which
    # makes both default to infinity (urdfdom 6.0 joint.cpp parseJointLimits)
    Element("limit", (Attr("lower", NUMBER), Attr("upper", NUMBER),
                      Attr("effort", NUMBER, required=True, optional_since=V1_2),
                      Attr("velocity", NUMBER, required=True, optional_since=V1_2),
                      Attr("acceleration", NUMBER, since=V1_2),
                      Attr("deceleration", NUMBER, since=V1_2), Attr("jerk", NUMBER, since=V1_2))),
    Element("mimic", (Attr("joint", NAME, required=True), Attr("multiplier", NUMBER, default=1.0),
                      Attr("offset", NUMBER, default=0.0))),
    Element("safety_controller", (Attr("soft_lower_limit", NUMBER), Attr("soft_upper_limit", NUMBER),
                                  Attr("k_position", NUMBER), Attr("k_velocity", NUMBER))),
)

# children that real-world packages carry and URDF parsers ignore without harm; PyBullet reads a link's
# <contact> (friction, restitution), so calling it ignored would be wrong for its users
TOLERATED = {"robot": frozenset({"sensor"}), "collision": frozenset({"verbose"}),
             "link": frozenset({"self_collision_checking", "contact"})}


def attributes(tag: str, version: Version = NEWEST) -> frozenset[str]:
    """The attributes `<tag>` has in URDF `version` (empty for an element URDF does not define)."""
    return _ATTRS.get((tag, version), frozenset())


def introduced(tag: str, attr: str) -> Version | None:
    """The URDF version that introduced `attr` on `<tag>` (None: URDF defines no such attribute)."""
    el = GRAMMAR.get(tag)
    for a in el.attrs if el else ():
        if a.name == attr:
            return a.since
    return None


def children(tag: str) -> tuple[str, ...]:
    """The child elements URDF defines for `<tag>`."""
    el = GRAMMAR.get(tag)
    return el.children if el else ()


_ATTRS = {(e.tag, v): frozenset(a.name for a in e.attrs if a.since <= v) for e in GRAMMAR.values() for v in VERSIONS}


def required(attr: Attr, version: Version) -> bool:
    return attr.required and (attr.optional_since is None or version < attr.optional_since)


def version_text(v: Version) -> str:
    return f"{v[0]}.{v[1]}"


# --- <robot version="x.y">, read the way urdfdom reads it -----------------------------------------------------
# urdfdom >= 1.0.4 (urdf_parser.hpp URDFVersion): split on ".", exactly two fields, each through strtol (leading
# white space and a sign allowed, nothing after the digits), neither negative. Only then is the range checked:
# every urdfdom before 5.1 reads 1.0 only, 5.1 reads 1.0 and 1.1, 6.0 reads 1.0 to 1.2.
def parse_version(raw: str | None) -> tuple[Version | None, str]:
    """(version, "") or (None, urdfdom's error message). No attribute means 1.0."""
    if raw is None:
        return V1_0, ""
    fields = raw.split(".")
    if fields[-1] == "":  # urdfdom's split_string drops a trailing empty field ("1." is one field, "" none)
        fields.pop()
    if len(fields) != 2:
        return None, "The version attribute should be in the form 'x.y'"
    out = []
    for f in fields:
        if f == "":
            return None, "One of the fields of the version attribute is blank"
        s = f.lstrip(" \t\n\r\f\v")
        digits = s[1:] if s[:1] in ("+", "-") else s
        n = len(digits) - len(digits.lstrip("0123456789"))
        if n == 0:
            return None, "Version attribute is not an integer"
        if n != len(digits):
            return None, "Extra characters after the version number"
        d = digits[:n].lstrip("0") or "0"
        value = min(int(d), 2**63 - 1) if len(d) < 20 else 2**63 - 1  # strtol saturates at LONG_MAX
        if s[:1] == "-":
            value = -value
        if value < 0:
            return None, "Version number must be positive"
        out.append(value)
    return (out[0], out[1]), ""


def supported_message(newest: Version) -> str:
    """urdfdom's message for a version it does not read."""
    if newest == V1_0:
        return "Invalid 'version' specified; only version 1.0 is currently supported"
    return f"Invalid 'version' specified; versions from 1.0 upto {version_text(newest)} are currently supported"


# --- which URDF versions a ROS distribution reads ----------------------------------------------------------------
class Target:
    __slots__ = ("name", "urdfdom", "newest")

    def __init__(self, name: str, urdfdom: str, newest: Version):
        self.name = name
        self.urdfdom = urdfdom  # the urdfdom release it ships
        self.newest = newest  # the newest URDF version that urdfdom reads

    def __repr__(self) -> str:
        return f"Target({self.name!r}, urdfdom {self.urdfdom})"


# ROS 1 Noetic: urdfdom 1.0.4; Humble 3.0.2; Jazzy 4.0.x; Kilted 5.0.0: all read URDF 1.0 only ("Invalid 'version'
# specified; only version 1.0 is currently supported"). Rolling: urdfdom 5.1 (URDF 1.1, February 2026), then
# 6.0 (URDF 1.2, April 2026). (rosdistro release PRs; urdfdom model.cpp parseURDF.)
TARGETS: dict[str, Target] = {t.name: t for t in (
    Target("noetic", "1.0.4", V1_0),
    Target("humble", "3.0", V1_0),
    Target("jazzy", "4.0", V1_0),
    Target("kilted", "5.0", V1_0),
    Target("rolling", "6.0", V1_2),
)}
NEWEST_TARGET = "rolling"
DEFAULT_TARGET = "humble"  # without a configured or discoverable target: the oldest supported ROS 2 LTS
