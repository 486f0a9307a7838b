"""The model build for links and joints written the ordinary way: one pass, few lxml calls.

build.py's careful builder reads anything and turns every oddity into a located issue. That care costs a
schema lookup per element and an error path per value, which dominates the run time on large models. Here
a <link> or <joint> is read assuming nothing is wrong, and the first sign of anything the careful builder
would report or treat specially (an unknown attribute or element, a missing or unreadable value, a second
shape...) raises `Irregular`: the careful builder then builds that element from scratch. So issues and
their locations come from build.py alone, and whatever this module returns equals what it would return.
"""
from __future__ import annotations

from math import isfinite
from types import MappingProxyType

from urdfcheck.model.robot import Geometry, Inertial, Joint, Limit, Link, MaterialRef, Mimic, Pose, Shape


class Irregular(Exception):
    """The element needs the careful builder."""


# the parts, filled in field order without the keyword handling of NamedTuple constructors (half the cost)
_new = tuple.__new__
SRC_ATTR = "__ucsrc"  # the xacro source marker (xacro.expand.SRC_ATTR); allowed on every element
# defaults shared with the careful builder
ZERO = (0.0, 0.0, 0.0)
ONE = (1.0, 1.0, 1.0)
X_AXIS = (1.0, 0.0, 0.0)
POSE0 = Pose()
NO_DYNAMICS = MappingProxyType({})
INERTIA = ("ixx", "ixy", "ixz", "iyy", "iyz", "izz")
_LIMIT = ("lower", "upper", "effort", "velocity")
_OPTIONAL = {"calibration": ("rising", "falling", "reference_position"),
             "safety_controller": ("soft_lower_limit", "soft_upper_limit", "k_position", "k_velocity")}
# children that real-world packages carry and URDF parsers ignore without harm; PyBullet reads a link's
# <contact> (friction, restitution), so calling it ignored would be wrong for its users
TOLERATED = {"robot": {"sensor"}, "collision": {"verbose"}, "link": {"self_collision_checking", "contact"}}


def _number(raw: str) -> float:
    try:
        value = float(raw)
    except ValueError:
        raise Irregular from None
    if value - value != 0.0 or "_" in raw:  # nan/inf, or Python-only digit separators
        raise Irregular
    return value


def _opt(raw: str | None, default: float | None = None) -> float | None:
    return default if raw is None else _number(raw)


def _ignored(parent: str, tag) -> None:
    """A child the careful builder skips silently (comments, namespaced extensions); anything else is its."""
    if tag.__class__ is str and tag[:1] != "{" and tag not in TOLERATED.get(parent, ()):
        raise Irregular


class FastParts:
    def __init__(self, locate):
        self.locate = locate
        # vector text -> values: real models repeat "0 0 0", "1 0 0" and the shared origin of a link's
        # visual, collision and inertial; splitting and converting is the costly part of reading them
        self.vectors: dict[str, tuple] = {}

    @staticmethod
    def _attrs(el, known: int) -> None:
        """`known` is how many schema attributes the caller found; any other is unknown (or the source marker)."""
        n = len(el.attrib)
        if n != known and not (n == known + 1 and el.get(SRC_ATTR) is not None):
            raise Irregular

    def _leaf(self, el, known: int) -> None:
        """The same for an element that takes no children."""
        self._attrs(el, known)
        if len(el):  # child elements are reported; comments would be fine, but are rare
            raise Irregular

    def _sole(self, el, name: str) -> str:
        """The value of an element's one required attribute, when it has no other and no children."""
        raw = el.get(name)
        if raw is None:
            raise Irregular
        self._leaf(el, 1)
        return raw

    def _vector(self, raw: str, n: int = 3) -> tuple:
        out = self.vectors.get(raw)
        if out is None:
            parts = raw.split()
            if len(parts) != n:
                raise Irregular
            try:
                out = tuple(map(float, parts))
            except ValueError:
                raise Irregular from None
            if "_" in raw or not all(map(isfinite, out)):
                raise Irregular
            self.vectors[raw] = out
        elif len(out) != n:
            raise Irregular
        return out

    # --- parts ---------------------------------------------------------------------
    def pose(self, el) -> Pose:
        xyz, rpy = el.get("xyz"), el.get("rpy")
        self._leaf(el, (xyz is not None) + (rpy is not None))
        return _new(Pose, (ZERO if xyz is None else self._vector(xyz), ZERO if rpy is None else self._vector(rpy),
                           self.locate(el)))

    def geometry(self, g) -> Geometry:
        self._attrs(g, 0)
        s = None
        for c in g:
            tag = c.tag
            if tag.__class__ is str and tag[:1] != "{":
                if s is not None:
                    raise Irregular  # a second shape
                s = c
        if s is None:
            raise Irregular
        tag = s.tag
        get = s.get
        if tag == "box":
            size = self._sole(s, "size")
            return _new(Geometry, ("box", self.locate(s), self._vector(size), None, None, None, None))
        if tag == "cylinder" or tag == "capsule":
            radius, length = get("radius"), get("length")
            if radius is None or length is None:
                raise Irregular
            self._leaf(s, 2)
            return _new(Geometry, (tag, self.locate(s), None, _number(radius), _number(length), None, None))
        if tag == "sphere":
            radius = self._sole(s, "radius")
            return Geometry("sphere", self.locate(s), radius=_number(radius))
        if tag == "mesh":
            fn, scale = get("filename"), get("scale")
            if not fn:
                raise Irregular
            self._leaf(s, 1 + (scale is not None))
            return Geometry("mesh", self.locate(s), filename=fn, scale=ONE if scale is None else self._vector(scale))
        raise Irregular

    def material(self, el) -> MaterialRef:
        """A <material> inside a <visual>."""
        name = el.get("name")
        if name is None:
            raise Irregular
        self._attrs(el, 1)
        rgba = texture = None
        if len(el):
            for c in el:
                tag = c.tag
                if tag == "color":
                    rgba = self._vector(self._sole(c, "rgba"), 4)
                elif tag == "texture":
                    texture = c.get("filename")
                    self._leaf(c, texture is not None)
                else:
                    _ignored("material", tag)
        return _new(MaterialRef, (name, self.locate(el), rgba, texture))

    def shape(self, el, kind: str) -> Shape:
        name = el.get("name")
        self._attrs(el, name is not None)
        origin, geometry, mat = POSE0, None, None
        for c in el:
            tag = c.tag
            if tag == "origin":
                origin = self.pose(c)
            elif tag == "geometry":
                geometry = self.geometry(c)
            elif tag == "material" and kind == "visual":
                mat = self.material(c)
            else:
                _ignored(kind, tag)
        return _new(Shape, (kind, self.locate(el), name or "", origin, geometry, mat))

    def inertial(self, el) -> Inertial:
        self._attrs(el, 0)
        origin, mass, mass_loc, inertia, inertia_loc = POSE0, None, None, None, None
        for c in el:
            tag = c.tag
            if tag == "mass":
                mass, mass_loc = _number(self._sole(c, "value")), self.locate(c)
            elif tag == "inertia":
                raw = tuple(map(c.get, INERTIA))
                if None in raw:
                    raise Irregular
                self._leaf(c, 6)
                inertia, inertia_loc = tuple(map(_number, raw)), self.locate(c)
            elif tag == "origin":
                origin = self.pose(c)
            else:
                _ignored("inertial", tag)
        return _new(Inertial, (self.locate(el), origin, mass, mass_loc, inertia, inertia_loc))

    def link(self, el) -> Link:
        name = el.get("name")
        if not name:
            raise Irregular
        self._attrs(el, 1 + (el.get("type") is not None))
        inertial, visuals, collisions = None, [], []
        for c in el:
            tag = c.tag
            if tag == "visual":
                visuals.append(self.shape(c, "visual"))
            elif tag == "collision":
                collisions.append(self.shape(c, "collision"))
            elif tag == "inertial" and inertial is None:
                inertial = self.inertial(c)
            else:
                _ignored("link", tag)
        return _new(Link, (name, self.locate(el), inertial, tuple(visuals), tuple(collisions)))

    def joint(self, el) -> Joint:
        name, jtype = el.get("name"), el.get("type")
        if not name or jtype is None:
            raise Irregular
        self._attrs(el, 2)
        parent = child = parent_loc = child_loc = None
        origin, axis, axis_loc, limit, mimic, dyn = POSE0, X_AXIS, None, None, None, {}
        for c in el:
            tag = c.tag
            if tag == "parent" or tag == "child":
                link = self._sole(c, "link")
                if not link:
                    raise Irregular
                if tag == "parent":
                    parent, parent_loc = link, self.locate(c)
                else:
                    child, child_loc = link, self.locate(c)
            elif tag == "origin":
                origin = self.pose(c)
            elif tag == "axis":
                axis, axis_loc = self._vector(self._sole(c, "xyz")), self.locate(c)
            elif tag == "limit":
                lower, upper, effort, velocity = map(c.get, _LIMIT)
                if effort is None or velocity is None:
                    raise Irregular
                self._leaf(c, 2 + (lower is not None) + (upper is not None))
                limit = _new(Limit, (self.locate(c), _opt(lower), _opt(upper), _number(effort), _number(velocity)))
            elif tag == "mimic":
                target, multiplier, offset = c.get("joint"), c.get("multiplier"), c.get("offset")
                if not target:
                    raise Irregular
                self._leaf(c, 1 + (multiplier is not None) + (offset is not None))
                mimic = Mimic(self.locate(c), target, _opt(multiplier, 1.0), _opt(offset, 0.0))
            elif tag == "dynamics":
                damping, friction = c.get("damping"), c.get("friction")
                self._leaf(c, (damping is not None) + (friction is not None))
                if damping is not None:
                    dyn["damping"] = _number(damping)
                if friction is not None:
                    dyn["friction"] = _number(friction)
            elif tag in _OPTIONAL:  # read only to report unreadable values
                given = [raw for raw in map(c.get, _OPTIONAL[tag]) if raw is not None]
                self._leaf(c, len(given))
                for raw in given:
                    _number(raw)
            else:
                _ignored("joint", tag)
        if parent_loc is None or child_loc is None:
            raise Irregular
        return _new(Joint, (name, jtype, self.locate(el), parent, child, origin, axis, axis_loc, limit, mimic,
                            MappingProxyType(dyn) if dyn else NO_DYNAMICS, parent_loc, child_loc))
