"""The robot model: immutable, built from the parsed XML, every part carrying its source location.

Parts are tuple records (`core.records.TupleRecord`): immutable and cheap to create (a 10,000-link model builds
~150,000 of them).

Only plain Python here (no numpy) so that `lint` stays fast; poses are composed with `urdfcheck.core.geometry`.
"""
from __future__ import annotations

from collections.abc import Mapping
from types import MappingProxyType

from urdfcheck.core.findings import Location, Severity
from urdfcheck.core.records import FrozenRecord, TupleRecord

Vec3 = tuple[float, float, float]

JOINT_TYPES = ("revolute", "continuous", "prismatic", "fixed", "floating", "planar")
MOVABLE_TYPES = ("revolute", "continuous", "prismatic")


class Pose(TupleRecord):
    """An <origin> as written: rpy, or (URDF >= 1.1) a quaternion. `core.geometry.origin_quaternion` and
    `origin_matrix` turn it into the rotation urdfdom reads; nothing else should interpret rpy or quat."""

    xyz: Vec3 = (0.0, 0.0, 0.0)
    rpy: Vec3 = (0.0, 0.0, 0.0)
    loc: Location | None = None
    quat: tuple[float, float, float, float] | None = None  # quat_xyzw as written (x, y, z, w), not normalised


class Inertial(TupleRecord):
    loc: Location
    origin: Pose = Pose()
    mass: float | None = None  # None: no <mass> element or no value
    mass_loc: Location | None = None
    # ixx, ixy, ixz, iyy, iyz, izz; None: no <inertia> element
    inertia: tuple[float, float, float, float, float, float] | None = None
    inertia_loc: Location | None = None


class Geometry(TupleRecord):
    kind: str  # box, cylinder, sphere, mesh, capsule, or the unknown tag name; "" when empty
    loc: Location
    size: Vec3 | None = None  # box
    radius: float | None = None  # cylinder, sphere, capsule
    length: float | None = None  # cylinder, capsule
    filename: str | None = None  # mesh
    scale: Vec3 | None = None  # mesh


class MaterialRef(TupleRecord):
    name: str
    loc: Location
    rgba: tuple[float, ...] | None = None  # given inline
    texture: str | None = None


class Shape(TupleRecord):
    """A <visual> or <collision>."""

    kind: str  # "visual" or "collision"
    loc: Location
    name: str = ""
    origin: Pose = Pose()
    geometry: Geometry | None = None
    material: MaterialRef | None = None  # visual only


class Link(TupleRecord):
    name: str
    loc: Location
    inertial: Inertial | None = None
    visuals: tuple[Shape, ...] = ()
    collisions: tuple[Shape, ...] = ()


class Limit(TupleRecord):
    """A <limit> as written (None: not given, or not read by the model's URDF version)."""

    loc: Location
    lower: float | None = None
    upper: float | None = None
    effort: float | None = None
    velocity: float | None = None
    acceleration: float | None = None  # URDF 1.2
    deceleration: float | None = None  # URDF 1.2
    jerk: float | None = None  # URDF 1.2


class Mimic(TupleRecord):
    loc: Location
    joint: str
    multiplier: float = 1.0
    offset: float = 0.0


class Joint(TupleRecord):
    name: str
    type: str
    loc: Location
    parent: str | None
    child: str | None
    origin: Pose = Pose()
    axis: Vec3 = (1.0, 0.0, 0.0)
    axis_loc: Location | None = None  # None: no <axis> element (the default x axis)
    limit: Limit | None = None
    mimic: Mimic | None = None
    dynamics: Mapping[str, float] = MappingProxyType({})
    parent_loc: Location | None = None
    child_loc: Location | None = None
    # the first <safety_controller>'s soft_lower_limit and soft_upper_limit as written (None: not written);
    # None: no <safety_controller>. MoveIt plans within them (rules/checks/profiles/moveit.py)
    safety: tuple[str | None, str | None] | None = None
    dont_collapse: bool = False  # dont_collapse="true" (an extension: sdformat, Isaac Sim keep the fixed joint)

    @property
    def movable(self) -> bool:
        return self.type in MOVABLE_TYPES


class Material(TupleRecord):
    name: str
    loc: Location
    rgba: tuple[float, ...] | None = None
    texture: str | None = None


class Block(TupleRecord):
    """A raw extension block (<ros2_control>, <transmission>, <gazebo>) kept for later rules."""

    tag: str
    loc: Location
    attrib: Mapping[str, str]
    xml: str  # serialized element, without source markers
    parent_tag: str = "robot"


class Interface(TupleRecord):
    name: str
    loc: Location


class HardwareItem(TupleRecord):
    """A <joint>, <sensor> or <gpio> inside <ros2_control>."""

    kind: str
    name: str
    loc: Location
    command: tuple[Interface, ...] = ()
    state: tuple[Interface, ...] = ()
    # a ros2_control mimic joint: <param name="mimic"> (Humble, Iron) or mimic="true" (Jazzy and later)
    mimic: bool = False


class Ros2Control(TupleRecord):
    name: str
    type: str
    loc: Location
    plugin: str = ""
    joints: tuple[HardwareItem, ...] = ()
    sensors: tuple[HardwareItem, ...] = ()
    gpios: tuple[HardwareItem, ...] = ()
    in_gazebo: bool = False  # written inside a <gazebo> block, where ros2_control never reads it


class PluginParam(TupleRecord):
    tag: str
    text: str
    loc: Location


class GazeboPlugin(TupleRecord):
    """A <plugin> directly inside a <gazebo> block (Gazebo classic model plugins, gz-sim systems)."""

    filename: str
    name: str
    loc: Location
    params: tuple[PluginParam, ...] = ()  # its child elements in document order (repeated tags kept)
    reference: str = ""  # the <gazebo reference=...> it sits in

    def get(self, *tags: str) -> PluginParam | None:
        """The first child element with one of `tags`, also inside <ros> (gazebo_ros plugins)."""
        for t in tags:
            for p in self.params:
                if p.tag == t:
                    return p
        return None

    def all(self, *tags: str) -> tuple[PluginParam, ...]:
        return tuple(p for p in self.params if p.tag in tags)


class FrameRef(TupleRecord):
    """A frame a <gazebo> sensor stamps its data with (<frame_name>, <frameName>, <gz_frame_id>...), as written."""

    tag: str
    name: str
    loc: Location
    sensor: str = ""  # the <sensor name>
    reference: str = ""  # the <gazebo reference> it sits in


class Transmission(TupleRecord):
    name: str
    loc: Location
    joints: tuple[Interface, ...] = ()  # joint names with their locations


class Issue(TupleRecord):
    """A problem found while building the model (bad number, unknown element...), reported by its rule."""

    code: str
    message: str
    loc: Location
    severity: Severity | None = None  # None: the rule's; lower where nothing anyone reads is lost


class Model(FrozenRecord):
    # links: first definition wins on duplicates
    # link_list: in document order, duplicates included
    # source: the entry file
    # version: the URDF version the model is read as (the declared one; 1.0 when none is declared; the newest
    #   when the declared one is one no urdfdom reads); declared_version: <robot version> as written
    _fields = ('name', 'loc', 'links', 'joints', 'materials', 'link_list', 'joint_list', 'material_list', 'blocks',
               'issues', 'source', 'ros2_control', 'transmissions', 'version', 'declared_version', 'plugins',
               'repeated', 'frame_refs')

    _defaults = {"ros2_control": (), "transmissions": (), "version": (1, 0), "declared_version": None,
                 "plugins": (), "repeated": (), "frame_refs": ()}
    name: str
    loc: Location
    links: Mapping[str, Link]
    joints: Mapping[str, Joint]
    materials: Mapping[str, Material]
    link_list: tuple[Link, ...]
    joint_list: tuple[Joint, ...]
    material_list: tuple[Material, ...]
    blocks: tuple
    issues: tuple
    source: str
    ros2_control: tuple
    transmissions: tuple
    version: tuple[int, int]
    declared_version: str | None
    plugins: tuple  # the <gazebo> plugins (consumers/gazebo.py)
    # per element that holds a sub-element twice where readers take one, (owner kind, owner name, its path such as
    # "link/collision/geometry", the repeated tags sorted), in reading order
    repeated: tuple
    frame_refs: tuple

    # --- derived structure -------------------------------------------------
    @property
    def parent_joint(self) -> Mapping[str, Joint]:
        """child link -> the joint that makes it a child (first one on conflicts)."""
        return self._derived()["parent_joint"]

    @property
    def child_joints(self) -> Mapping[str, tuple[Joint, ...]]:
        """link -> joints whose parent it is, in document order."""
        return self._derived()["child_joints"]

    @property
    def roots(self) -> tuple[str, ...]:
        """Links that are no joint's child, in document order."""
        return self._derived()["roots"]

    @property
    def root(self) -> str | None:
        r = self.roots
        return r[0] if len(r) == 1 else None

    def _derived(self) -> dict:
        cache = self.__dict__.get("_cache")
        if cache is None:
            parent: dict[str, Joint] = {}
            children: dict[str, list[Joint]] = {}
            for j in self.joint_list:
                if j.child is not None and j.child not in parent:
                    parent[j.child] = j
                if j.parent is not None:
                    children.setdefault(j.parent, []).append(j)
            roots = tuple(n for n in self.links if n not in parent)
            cache = {
                "parent_joint": MappingProxyType(parent),
                "child_joints": MappingProxyType({k: tuple(v) for k, v in children.items()}),
                "roots": roots,
            }
            object.__setattr__(self, "_cache", cache)
        return cache

    def chain_to_root(self, link: str) -> list[Joint]:
        """Joints from `link` up to its root (stops on a cycle)."""
        out: list[Joint] = []
        seen = {link}
        j = self.parent_joint.get(link)
        while j is not None and j.parent is not None:
            out.append(j)
            if j.parent in seen:
                break
            seen.add(j.parent)
            j = self.parent_joint.get(j.parent)
        return out

    def path(self, source: str, target: str) -> tuple[list[Joint], list[Joint]] | None:
        """Joints to walk from `source` up to the common ancestor, and from there down to `target`.

        Returns (up, down): `up` is ordered from source upwards, `down` from the ancestor downwards.
        None when the two links are not in one tree.
        """
        up = self.chain_to_root(source)
        down = self.chain_to_root(target)
        src_anc = [source] + [j.parent for j in up]
        tgt_anc = [target] + [j.parent for j in down]
        common = next((a for a in src_anc if a in set(tgt_anc)), None)
        if common is None:
            return None
        up = up[: src_anc.index(common)]
        down = list(reversed(down[: tgt_anc.index(common)]))
        return up, down

    def descendants_in_order(self, root: str) -> tuple[str, ...]:
        """Depth-first, children in document order (cycle-safe). Computed once per root: several rules walk the
        whole tree from its root (0.03 s a walk on 10,000 links)."""
        walks = self._derived().setdefault("descendants", {})
        got = walks.get(root)
        if got is None:
            got = walks[root] = tuple(self._descendants(root))
        return got

    def _descendants(self, root: str) -> list[str]:
        out, seen, stack = [], set(), [root]
        while stack:
            name = stack.pop()
            if name in seen:
                continue
            seen.add(name)
            out.append(name)
            for j in reversed(self.child_joints.get(name, ())):
                if j.child is not None:
                    stack.append(j.child)
        return out

    def movable_joints(self) -> list[Joint]:
        return [j for j in self.joint_list if j.movable]

    def world_poses(self) -> dict[str, tuple]:
        """Pose of every link reachable from the roots at zero configuration, as 4x4 nested tuples (computed once per
        model: the wheel checks ask for it once per rule and drive; a copy, so that no caller changes it for the
        next)."""
        derived = self._derived()
        got = derived.get("world_poses")
        if got is None:
            got = derived["world_poses"] = self._world_poses()
        return dict(got)

    def _world_poses(self) -> dict[str, tuple]:
        from urdfcheck.core.geometry import compose, identity, origin_matrix

        out: dict[str, tuple] = {}
        for root in self.roots:
            out[root] = identity()
            for name in self.descendants_in_order(root):
                for j in self.child_joints.get(name, ()):
                    if j.child is not None and j.child not in out:
                        out[j.child] = compose(out[name], origin_matrix(j.origin))
        return out
