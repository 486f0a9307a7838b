"""Build the Model from a parsed (and expanded) URDF document: one builder, driven by the grammar.

Every element's attributes are read by a reader generated from `grammar.GRAMMAR` for the model's declared URDF
version (readers.py, written by readergen.py): values that are there and well formed take a short path (one
`get` per attribute, a count against the element's attributes, cached vector texts); anything else (an unknown
attribute, one a newer URDF version introduced, a missing or unreadable value, an unexpected child) calls back
into this builder and becomes a located `Issue`, reported by its rule, and the part gets the value URDF parsers
default to, so later rules see a usable model. There is no second builder to keep in step: what is reported
and what is read come from the same code and the same table.
"""
from __future__ import annotations

import re
from collections.abc import Callable, Iterator, Mapping
from math import isfinite
from types import MappingProxyType

from urdfcheck.core import nogc
from urdfcheck.core.findings import Location, Severity, closest
from urdfcheck.core.lxmlimport import etree
from urdfcheck.model import extensions
from urdfcheck.model import grammar as G
from urdfcheck.model.robot import (
    Block,
    FrameRef,
    GazeboPlugin,
    Geometry,
    HardwareItem,
    Inertial,
    Interface,
    Issue,
    Joint,
    Limit,
    Link,
    Material,
    MaterialRef,
    Mimic,
    Model,
    PluginParam,
    Pose,
    Ros2Control,
    Shape,
    Transmission,
)

SRC_ATTR = G.SRC_ATTR
ZERO, ONE, INERTIA = G.ZERO, G.ONE, G.INERTIA
X_AXIS = (1.0, 0.0, 0.0)
POSE0 = Pose()
NO_DYNAMICS: Mapping[str, float] = MappingProxyType({})
TOLERATED = G.TOLERATED
_SHAPE_SINCE = {tag: G.GRAMMAR[tag].since for tag in G.SHAPES}
_new = tuple.__new__  # parts filled in field order, without namedtuple's keyword handling (half the cost)


class _Reading:
    """An element's attributes as one URDF version reads them (for the messages off the good path)."""

    __slots__ = ("tag", "attrs", "known", "later")

    def __init__(self, tag: str, attrs: tuple, known: frozenset, later: dict):
        self.tag = tag
        self.attrs = attrs  # the attributes this version reads, grammar order (the readers' indexes)
        self.known = known  # their names + the source marker
        self.later = later  # attribute -> Attr, for the ones a newer URDF version introduced


def _reading(tag: str, version: G.Version) -> _Reading:
    el = G.GRAMMAR[tag]
    attrs = tuple(a for a in el.attrs if a.since <= version)
    return _Reading(tag, attrs, frozenset(a.name for a in attrs) | {SRC_ATTR},
                    {a.name: a for a in el.attrs if a.since > version})


# --- readers compiled from the grammar ----------------------------------------------------------------------------
# One function per element and URDF version, `read(builder, el) -> tuple of values in grammar order`, written out
# from the grammar by readergen.py into readers.py (generated, checked by a test): straight-line code (one `get`
# per attribute, a count against the element's attributes, cached vector texts, defaults as constants) is what
# makes the good path cheap on 10,000-link models, and every deviation calls back into the builder (`missing`,
# `bad_number`, `vector`, `odd_attributes`, `exclusive`, `children_of_leaf`), which reports it.
def readers(version: G.Version) -> dict:
    from urdfcheck.model.readers import READERS

    r = READERS.get(version)
    if r is None or len(r) != len(G.GRAMMAR):  # readers.py is stale (the grammar was edited): compile them now
        from urdfcheck.model import readergen

        r = READERS[version] = readergen.compiled(version)
    return r


_READINGS: dict[tuple, _Reading] = {}


def reading(tag: str, version: G.Version) -> _Reading:
    r = _READINGS.get((tag, version))
    if r is None:
        r = _READINGS[(tag, version)] = _reading(tag, version)
    return r


def _unexpanded(raw: str) -> str:
    """A hint for xacro syntax left in a file read as plain URDF (e.g. a .urdf that still says $(optenv ...))."""
    if "$(" in raw or "${" in raw:
        return ("; it is an unexpanded xacro substitution: URDF consumers read it literally (expand the file with "
                "xacro, or name it .xacro and declare xmlns:xacro)")
    return ""


# A URDF element written where no consumer reads it, and where no consumer would do anything with it either: a
# colour on collision geometry. urdfdom, sdformat's parser_urdf, Drake and Pinocchio read <material> only in
# <visual>; MuJoCo's URDF compiler (xml_urdf.cc) colours a collision geom with the link's last visual colour.
# Common in exported models (baxter, solo, tiago in example-robot-data).
_HARMLESS = {("collision", "material"): "consumers read <material> only in <visual> (MuJoCo colours collision "
                                        "geometry like the link's visual), so nothing is lost; remove it to quiet "
                                        "this"}


def _hint(word: str, options) -> str:
    close = closest(word, sorted(options))
    return f" (did you mean {close!r}?)" if close else ""


def _named(el) -> str:
    """`<tag>` with the name of the element, or of its parent, for messages about a missing attribute."""
    name = el.get("name")
    if name:
        return f"<{el.tag} name={name!r}>"
    parent = el.getparent()
    pname = parent.get("name") if parent is not None and isinstance(parent.tag, str) else None
    return f"<{el.tag}> of <{parent.tag} name={pname!r}>" if pname else f"<{el.tag}>"


def _again(twice: set | None, tag: str) -> set:
    """`tag` read a second time where readers take one (urdfdom reads the first; MuJoCo refuses the model):
    noticed by what the first reading left behind, so the common case costs nothing."""
    return (twice or set()) | {tag}


class _Builder:
    def __init__(self, locate: Callable[[object], Location], source: str, version: G.Version, declared: str | None):
        self.locate = locate
        self.source = source
        self.version = version
        self.declared = declared
        self.R = readers(version)
        self.issues: list[Issue] = []
        # sub-elements written twice where one is read: (owner kind, owner name, scope path, tags), per scope
        self.repeated: list[tuple[str, str, str, tuple[str, ...]]] = []
        self.owner = ""  # the link whose parts are being read
        # vector text -> values: real models repeat "0 0 0", "1 0 0" and the shared origin of a link's
        # visual, collision and inertial; splitting and converting is the costly part of reading them
        self.vectors: dict[str, tuple] = {}

    def issue(self, code: str, message: str, el, severity=None) -> None:
        self.issues.append(Issue(code, message, self.locate(el), severity))

    # --- attributes: the compiled readers call these for anything off the good path ---------------------------
    def missing(self, el, tag: str, i: int) -> None:
        a = reading(tag, self.version).attrs[i]
        self.issue("U006", f"{_named(el)} has no {a.name!r} attribute", el)

    def bad_number(self, el, tag: str, i: int, raw: str, parsed: bool):
        a = reading(tag, self.version).attrs[i]
        if parsed:
            self.issue("U005", f"<{el.tag} {a.name}={raw!r}> is not a finite plain number", el)
        else:
            self.issue("U005", f"<{el.tag} {a.name}={raw!r}> is not a number{_unexpanded(raw)}", el)
        return a.default

    def vector(self, el, tag: str, i: int, raw: str, n: int):
        """A vector text not seen before (or seen with another length): read, cached, or reported."""
        parts = raw.split()
        if len(parts) == n:
            try:
                out = tuple(map(float, parts))
            except ValueError:
                out = None
            # a finite sum has no inf or nan among its terms (either would carry into it); a sum that overflows
            # takes the exact test
            if out is not None and "_" not in raw and (isfinite(sum(out)) or all(map(isfinite, out))):
                self.vectors[raw] = out
                return out
        a = reading(tag, self.version).attrs[i]
        if len(parts) != n:
            self.issue("U004", f"<{el.tag} {a.name}={raw!r}> has {len(parts)} values; {n} expected{_unexpanded(raw)}",
                       el)
        else:
            self.issue("U005", f"<{el.tag} {a.name}={raw!r}>: not {n} finite plain numbers{_unexpanded(raw)}", el)
        return a.default

    def odd_attributes(self, el, tag: str) -> None:
        """Attributes outside what the declared version reads: the source marker and namespaced ones are
        fine; one a newer URDF version introduced is U008; anything else is unknown (U003)."""
        r = reading(tag, self.version)
        for k in el.keys():
            if k in r.known or k[:1] == "{":
                continue
            later = r.later.get(k)
            if later is not None:
                self.issue("U008", f"<{r.tag} {k}> needs URDF {G.version_text(later.since)}, but the model declares "
                                   f"{self.declared_text()}: urdfdom ignores it{_IGNORED.get((r.tag, k), '')}", el)
            elif extensions.known("attribute", r.tag, k) is None:  # a known extension is read by its consumer
                hint = _hint(k, G.attributes(r.tag) | extensions.names("attribute", r.tag))
                self.issue("U003", f"<{r.tag}> has unknown attribute {k!r}{hint}", el)

    def declared_text(self) -> str:
        return f'version="{self.declared}"' if self.declared is not None else "no version (URDF 1.0)"

    def exclusive(self, el, names: tuple[str, ...]) -> None:
        """Attributes given together that must not be (U009). urdfdom >= 5.1 (pose.cpp): "Both rpy and
        quat_xyzw orientations are defined. Use either one or the other." and the origin is not read."""
        parent = el.getparent()
        self.issue("U009", _BOTH.get(parent.tag if parent is not None else "", _BOTH[""]), el)

    def children_of_leaf(self, el, tag: str) -> None:
        for c in el:
            if isinstance(c.tag, str) and not c.tag.startswith("{") and extensions.known("element", tag, c.tag) is None:
                self.issue("U002", f"<{tag}> takes no child elements; <{c.tag}> is ignored", c)

    def unknown(self, parent_tag: str, c) -> None:
        tag = c.tag
        if not isinstance(tag, str) or tag.startswith("{") or tag in TOLERATED.get(parent_tag, ()):
            return
        if extensions.known("element", parent_tag, tag) is not None:
            return  # a known extension (model/extensions.yaml): its consumer reads it
        if (parent_tag, tag) in _HARMLESS:  # known elsewhere, read by nobody here, and nothing is lost by that
            self.issue("U002", f"<{tag}> in <{parent_tag}> is ignored: {_HARMLESS[parent_tag, tag]}", c, Severity.INFO)
            return
        hint = _hint(tag, set(G.children(parent_tag)) | extensions.names("element", parent_tag))
        # Gazebo's URDF converter (sdformat and gazebo-classic parser_urdf.cc) reads <gazebo> blocks only as
        # children of <robot>: one nested in a link or joint is lost to the simulator as well
        lost = ("; Gazebo reads <gazebo> only directly under <robot> (with reference=\"…\"), so it ignores it too"
                if tag == "gazebo" else "")
        self.issue("U002", f"unknown element <{tag}> in <{parent_tag}>{hint}; URDF parsers ignore it{lost}", c)

    # --- parts ---------------------------------------------------------------------------------------------
    # Each element's children are walked once with a dispatch on the tag (lxml proxies are costly), taken as a
    # slice: lxml builds the list in C, about two thirds of the time of iterating the element.
    def pose(self, el) -> Pose:
        v = self.R["origin"](self, el)
        # both rpy and quat_xyzw (U009) stay in the model as written; core.geometry prefers the quaternion
        return _new(Pose, (v[0], v[1], self.locate(el), v[2] if len(v) == 3 else None))

    def geometry(self, g, kind: str = "") -> Geometry:
        self.R["geometry"](self, g)
        shapes, tags = [], []  # each child's tag read once: lxml builds a new string at every read
        for c in g[:]:
            t = c.tag
            if isinstance(t, str) and not t.startswith("{"):
                shapes.append(c)
                tags.append(t)
        if not shapes:
            return Geometry("", self.locate(g))
        if len(shapes) > 1:
            self.issue("U002", f"<geometry> holds {len(shapes)} shapes; URDF parsers use only the first", shapes[1])
            self._note_repeats(f"link/{kind}/geometry", {t for t in tags if tags.count(t) > 1})
        s = shapes[0]
        tag = tags[0]
        loc = self.locate(s)
        since = _SHAPE_SINCE.get(tag)
        if since is None:  # an unknown shape is G005's (urdfdom rejects the visual)
            return Geometry(tag, loc)
        if since > self.version:
            self.issue("U008", f"<{tag}> needs URDF {G.version_text(since)}, but the model declares "
                               f"{self.declared_text()}: urdfdom drops this <{g.getparent().tag}> (urdfdom >= 5.1 "
                               f"warns, older ones call it an unknown geometry type); add version=\"1.1\" to "
                               f"<robot> (urdfdom >= 5.1, ROS 2 Rolling only) or use a cylinder", s)
        v = self.R[tag](self, s)
        if tag == "box":
            return _new(Geometry, ("box", loc, v[0], None, None, None, None))
        if tag == "cylinder" or tag == "capsule":
            return _new(Geometry, (tag, loc, None, v[0], v[1], None, None))
        if tag == "sphere":
            return _new(Geometry, ("sphere", loc, None, v[0], None, None, None))
        return _new(Geometry, ("mesh", loc, None, None, None, v[0], v[1]))

    def _colour_texture(self, mat):
        rgba = texture = None
        for c in mat[:]:
            tag = c.tag
            if tag == "color":
                rgba = self.R["color"](self, c)[0]
            elif tag == "texture":
                texture = self.R["texture"](self, c)[0]
            else:
                self.unknown("material", c)
        return rgba, texture

    def material(self, el) -> Material | None:
        name = self.R["material"](self, el)[0]
        if name == "":  # a top-level material is looked up by name: an empty one is none
            self.issue("U006", "<material> has no 'name' attribute", el)
        if not name:
            return None
        rgba, texture = self._colour_texture(el)
        return _new(Material, (name, self.locate(el), rgba, texture))

    def shape(self, el, kind: str) -> Shape:
        R, locate = self.R, self.locate
        name = R[kind](self, el)[0]
        origin, geometry, mat = POSE0, None, None
        twice = None  # the tags seen again, of those read once (a repeat is rare: noticed by the first's trace)
        for c in el[:]:
            tag = c.tag
            if tag == "origin":
                if origin is not POSE0:
                    twice = _again(twice, "origin")
                v = R["origin"](self, c)
                origin = _new(Pose, (v[0], v[1], locate(c), v[2] if len(v) == 3 else None))  # = self.pose(c)
            elif tag == "geometry":
                if geometry is not None:
                    twice = _again(twice, "geometry")
                geometry = self.geometry(c, kind)
            elif tag == "material" and kind == "visual":
                if mat is not None:
                    twice = _again(twice, "material")
                # urdfdom rejects the visual (and stops reading the link) when its material has no name
                mname = R["material"](self, c)[0]
                rgba, texture = self._colour_texture(c) if len(c) else (None, None)
                mat = _new(MaterialRef, (mname or "", locate(c), rgba, texture))
            else:
                self.unknown(kind, c)
        if twice:
            self._note_repeats(f"link/{kind}", twice)
        return _new(Shape, (kind, locate(el), name or "", origin, geometry, mat))

    def inertial(self, el) -> Inertial:
        R, locate = self.R, self.locate
        R["inertial"](self, el)
        origin, mass, mass_loc, inertia, inertia_loc = POSE0, None, None, None, None
        twice = None
        for c in el[:]:
            tag = c.tag
            if tag == "mass":
                if mass_loc is not None:
                    twice = _again(twice, "mass")
                mass, mass_loc = R["mass"](self, c)[0], locate(c)
            elif tag == "inertia":
                if inertia_loc is not None:
                    twice = _again(twice, "inertia")
                inertia, inertia_loc = R["inertia"](self, c), locate(c)
            elif tag == "origin":
                if origin is not POSE0:
                    twice = _again(twice, "origin")
                v = R["origin"](self, c)
                origin = _new(Pose, (v[0], v[1], locate(c), v[2] if len(v) == 3 else None))  # = self.pose(c)
            else:
                self.unknown("inertial", c)
        if twice:
            self._note_repeats("link/inertial", twice)
        return _new(Inertial, (locate(el), origin, mass, mass_loc, inertia, inertia_loc))

    def link(self, el) -> Link | None:
        name = self.R["link"](self, el)[0]
        if not name:
            return None
        inertial, visuals, collisions = None, [], []
        extra_inertial = False
        self.owner = name
        for c in el[:]:
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
                    if not extra_inertial:
                        self._note_repeats("link", {"inertial"})
                    extra_inertial = True
                    tags = [k.tag for k in c if isinstance(k.tag, str)]  # not read here, but other readers look
                    self._note_repeats("link/inertial", {t for t in tags if tags.count(t) > 1})
            else:
                self.unknown("link", c)
        return _new(Link, (name, self.locate(el), inertial, tuple(visuals), tuple(collisions)))

    def _note_repeats(self, path: str, tags: set, kind: str = "link", owner: str | None = None) -> None:
        if tags:
            self.repeated.append((kind, self.owner if owner is None else owner, path, tuple(sorted(tags))))

    def joint(self, el) -> Joint | None:
        R, locate = self.R, self.locate
        name, jtype = R["joint"](self, el)
        if not name:
            return None
        if jtype is None:
            jtype = ""
        parent = child = parent_loc = child_loc = None
        origin, axis, axis_loc, limit, mimic, dyn, safety = POSE0, X_AXIS, None, None, None, None, None
        twice = None  # the tags seen again, of those MuJoCo reads once
        for c in el[:]:
            tag = c.tag
            if tag == "parent":
                if parent_loc is not None:
                    twice = _again(twice, tag)
                parent, parent_loc = R["parent"](self, c)[0], locate(c)
            elif tag == "child":
                if child_loc is not None:
                    twice = _again(twice, tag)
                child, child_loc = R["child"](self, c)[0], locate(c)
            elif tag == "origin":
                if origin is not POSE0:
                    twice = _again(twice, tag)
                v = R["origin"](self, c)
                origin = _new(Pose, (v[0], v[1], locate(c), v[2] if len(v) == 3 else None))  # = self.pose(c)
            elif tag == "axis":
                if axis_loc is not None:
                    twice = _again(twice, tag)
                axis, axis_loc = R["axis"](self, c)[0], locate(c)
            elif tag == "limit":
                if limit is not None:
                    twice = _again(twice, tag)
                v = R["limit"](self, c)
                if len(v) == 4:  # acceleration, deceleration, jerk: not read before URDF 1.2
                    v += (None, None, None)
                limit = _new(Limit, (locate(c), *v))
            elif tag == "mimic":
                target, multiplier, offset = R["mimic"](self, c)
                if target:
                    mimic = _new(Mimic, (locate(c), target, multiplier, offset))
            elif tag == "dynamics":
                if dyn is not None:
                    twice = _again(twice, tag)
                damping, friction = R["dynamics"](self, c)
                dyn = dyn or {}
                if damping is not None:
                    dyn["damping"] = damping
                if friction is not None:
                    dyn["friction"] = friction
            elif tag == "safety_controller":  # read to report unreadable values; the soft limits kept as written
                R[tag](self, c)
                if safety is None:
                    safety = (c.get("soft_lower_limit"), c.get("soft_upper_limit"))
            elif tag == "calibration":  # read only to report unreadable values
                R[tag](self, c)
            else:
                self.unknown("joint", c)
        if twice:
            self._note_repeats("joint", twice, "joint", name)
        if parent_loc is None:
            self.issue("U006", f"joint {name!r} has no <parent> element", el)
        if child_loc is None:
            self.issue("U006", f"joint {name!r} has no <child> element", el)
        keep = el.get("dont_collapse")
        return _new(Joint, (name, jtype, locate(el), parent, child, origin, axis, axis_loc, limit, mimic,
                            MappingProxyType(dyn) if dyn else NO_DYNAMICS, parent_loc, child_loc, safety,
                            keep is not None and keep.lower() == "true"))

    # --- extension blocks kept for the contract rules --------------------------------------------------------
    def ros2_control(self, el, in_gazebo: bool) -> Ros2Control:
        items: dict[str, list] = {"joint": [], "sensor": [], "gpio": []}
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

    def plugins(self, el) -> list[GazeboPlugin]:
        out = []
        for p in el.findall("plugin"):
            params = []
            for c in p.iter():
                if c is p or not isinstance(c.tag, str):
                    continue  # (elements with children are kept too, with no text: <ros> marks a ROS 2 plugin)
                params.append(PluginParam(c.tag, "" if len(c) else (c.text or "").strip(), self.locate(c)))
            out.append(GazeboPlugin(p.get("filename") or "", p.get("name") or "", self.locate(p), tuple(params),
                                    el.get("reference") or ""))
        return out

    def frame_refs(self, el) -> list[FrameRef]:
        """The frames the sensors of a <gazebo> block name (ROS 2 and ROS 1 gazebo_ros plugins, gz-sim)."""
        out = []
        for sensor in el.iter("sensor"):
            for c in sensor.iter(*FRAME_TAGS):
                text = (c.text or "").strip()
                if text and not len(c):
                    out.append(FrameRef(c.tag, text, self.locate(c), sensor.get("name") or "",
                                        el.get("reference") or ""))
        return out

    def transmission(self, el) -> Transmission:
        joints = tuple(Interface(j.get("name") or "", self.locate(j)) for j in el.findall("joint"))
        return Transmission(el.get("name") or "", self.locate(el), joints)


# the elements a Gazebo sensor names its frame with: gazebo_ros (ROS 2), gazebo_plugins (ROS 1), gz-sim, Ignition
FRAME_TAGS = ("frame_name", "frameName", "gz_frame_id", "ignition_frame_id")

# what urdfdom 6.0 then does, by where the <origin> is (run on urdfdom 6.0.0)
_BOTH = {
    "joint": "<origin> gives both rpy and quat_xyzw: urdfdom refuses the joint origin, so the whole model is "
             "rejected (robot_state_publisher does not start); give one of them",
    "visual": "<origin> gives both rpy and quat_xyzw: urdfdom refuses this <visual> and drops it; give one of them",
    "collision": "<origin> gives both rpy and quat_xyzw: urdfdom refuses this <collision> and drops it; give one "
                 "of them",
    "inertial": "<origin> gives both rpy and quat_xyzw: urdfdom refuses this <inertial>, the link then has no "
                "mass and no inertia; give one of them",
    "": "<origin> gives both rpy and quat_xyzw: urdfdom refuses it; give one of them",
}

# what urdfdom reads instead of a construct the declared version does not have (urdfdom 6.0 pose.cpp,
# joint.cpp; urdfdom before 5.1 does not know them at all and ignores them without a word)
_IGNORED = {
    ("origin", "quat_xyzw"): " and uses the rpy rotation (identity without rpy); add version=\"1.1\" to <robot> "
                             "(read by urdfdom >= 5.1, ROS 2 Rolling only) or write the rotation as rpy",
    ("limit", "acceleration"): " (no acceleration limit); add version=\"1.2\" to <robot> (urdfdom >= 6.0)",
    ("limit", "deceleration"): " (no deceleration limit); add version=\"1.2\" to <robot> (urdfdom >= 6.0)",
    ("limit", "jerk"): " (no jerk limit); add version=\"1.2\" to <robot> (urdfdom >= 6.0)",
}


def _raw_xml(el) -> str:
    text = etree.tostring(el, encoding="unicode", with_tail=False)
    return re.sub(r' __ucsrc="[^"]*"', "", text)


def build(root, locate: Callable[[etree._Element], Location], source: str) -> Model:
    return nogc.call(_build, root, iter(root), locate, source, long_lived=True)


def build_streamed(elements: Iterator, locate: Callable[[etree._Element], Location], source: str) -> Model:
    """The model of a document read as it is parsed (`core.xmlfront.stream`: the root element first, then each
    of its children once whole, each dropped once read), so that a large model and its whole libxml2 tree never
    share the memory. The parse's errors propagate (the caller reads the document again, whole, to report them)."""
    root = next(elements)
    return nogc.call(_build, root, elements, locate, source, long_lived=True)


def _build(root, children: Iterator, locate: Callable[[object], Location], source: str) -> Model:
    is_robot = root.tag == "robot"
    declared = root.get("version") if is_robot else None
    parsed, _ = G.parse_version(declared)
    # a version urdfdom cannot read is reported once (U007); the rest is read as the newest URDF reads it,
    # so that one wrong number does not turn every newer construct into a finding of its own
    version = parsed if parsed in G.VERSIONS else G.NEWEST
    b = _Builder(locate, source, version, declared)
    if not is_robot:
        b.issue("U001", f"the root element is <{root.tag}>, not <robot>", root)
    else:
        b.R["robot"](b, root)
    links, joints, materials, blocks, r2c, trans, plugins, frames = [], [], [], [], [], [], [], []
    for el in children:
        tag = el.tag
        if tag == "link":
            part = b.link(el)
            if part:
                links.append(part)
        elif tag == "joint":
            joint = b.joint(el)
            if joint:
                joints.append(joint)
        elif tag == "material":
            material = b.material(el)
            if material:
                materials.append(material)
        elif tag in ("transmission", "gazebo", "ros2_control"):
            blocks.append(Block(tag, locate(el), MappingProxyType(dict(el.attrib)), _raw_xml(el)))
            if tag == "ros2_control":
                r2c.append(b.ros2_control(el, False))
            elif tag == "gazebo":
                for inner in el.iter("ros2_control"):
                    r2c.append(b.ros2_control(inner, True))
                plugins.extend(b.plugins(el))
                frames.extend(b.frame_refs(el))
            else:
                trans.append(b.transmission(el))
        elif is_robot and isinstance(tag, str):
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
        repeated=tuple(b.repeated),
        source=source,
        ros2_control=tuple(r2c),
        transmissions=tuple(trans),
        version=version,
        declared_version=declared,
        plugins=tuple(plugins),
        frame_refs=tuple(frames),
    )


def _first_by_name(parts) -> dict:
    out: dict = {}
    for p in parts:
        out.setdefault(p.name, p)
    return out


def model_from_string(xml: str | bytes, path: str = "<string>") -> Model:
    """Model from URDF text (plain URDF; for xacro use `urdfcheck.load.loader.load_model`)."""
    from urdfcheck.core import xmlfront

    data = xml.encode("utf-8") if isinstance(xml, str) else xml
    root, _ = xmlfront.parse(data)
    return build(root, lambda el: Location(path, el.sourceline), path)
