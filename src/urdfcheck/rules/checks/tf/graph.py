"""The deployment TF graph: who publishes which parent -> child transform, and what is wrong with it.

Claims (`TFClaim(parent, child, owner, kind, loc)`) come from

* the model, published by robot_state_publisher (`claims_from_model`): fixed and planar joints are static
  (/tf_static; RSP publishes a planar joint at its zero position), revolute/continuous/prismatic joints are
  dynamic (/tf), floating joints are skipped (RSP does not publish them). Only the first joint per child
  link is used (a second parent is the model's own structure error);
* static_transform_publisher nodes in launch files (static);
* controllers and drivers that broadcast odometry (dynamic odom -> base);
* localization, SLAM and drivers that broadcast frames (robot_localization, AMCL, slam_toolbox, cartographer,
  realsense2_camera: `localization.py`, data in `tfowners.yaml`);
* Gazebo plugins and gz-sim systems in the model's <gazebo> blocks (`consumers.gazebo.plugin_claims`, source
  "gazebo"): their odometry transforms (dynamic), counted against the controllers' only when the controllers run
  in the simulator (rules_impl `_apart`);
* owners declared in the config (`tf_owners: {"map->odom": amcl}`) (dynamic). A declaration that names the
  publisher already read for that edge (`add_declared`: the same owner, its node name, or its kind, e.g.
  `map_to_odom`, `static_transform_publisher`, `diff_drive_controller`) documents that publisher and adds no
  second claim; one naming somebody else is a second publisher (T001/T002).

Frame names are compared without a leading "/". Analyses return `TFProblem`s (never findings): the check
layer turns them into T001..T006.
"""
from __future__ import annotations

from collections.abc import Iterable, Mapping, Sequence

from urdfcheck.core.findings import Location
from urdfcheck.core.records import Record, TupleRecord

STATIC = "static"
DYNAMIC = "dynamic"
RSP = "robot_state_publisher"


class TFClaim(TupleRecord):
    parent: str
    child: str
    owner: str  # "robot_state_publisher", "static_transform_publisher <name>", a controller name, "amcl", ...
    kind: str  # "static" or "dynamic"
    loc: Location
    source: str = ""  # "model", "launch", "controller", "driver", "localization", "config"

    @property
    def edge(self) -> tuple[str, str]:
        return (self.parent, self.child)


class TFProblem(TupleRecord):
    code: str  # T001..T006
    message: str
    claims: tuple[TFClaim, ...] = ()
    frames: tuple[str, ...] = ()
    loc: Location | None = None  # the primary location (first claim's when None)

    @property
    def at(self) -> Location | None:
        if self.loc is not None:
            return self.loc
        return self.claims[0].loc if self.claims else None

    @property
    def related(self) -> tuple[Location, ...]:
        first = self.at
        out = []
        for c in self.claims:
            if c.loc != first and c.loc not in out:
                out.append(c.loc)
        return tuple(out)


def norm(frame: str) -> str:
    return str(frame).strip().lstrip("/")


class TFGraph(Record):
    # notes: (message, Location): claims left out (conditional launch nodes)
    _fields = ('claims', 'notes')

    def __init__(self, claims: list[TFClaim] | None = None, notes: list | None = None, _seen: set | None = None):
        self.claims = [] if claims is None else claims
        self.notes = [] if notes is None else notes
        self._seen = set() if _seen is None else _seen

    def add(self, claim: TFClaim) -> None:
        c = TFClaim(norm(claim.parent), norm(claim.child), claim.owner, claim.kind, claim.loc, claim.source)
        if not self._seen:
            self._seen.update(self.claims)
        if c not in self._seen:  # a set: a 10,000-link model makes 10,000 claims
            self._seen.add(c)
            self.claims.append(c)

    def extend(self, claims: Iterable[TFClaim]) -> TFGraph:
        for c in claims:
            self.add(c)
        return self

    @property
    def frames(self) -> list[str]:
        out: dict[str, None] = {}
        for c in self.claims:
            out.setdefault(c.parent)
            out.setdefault(c.child)
        return list(out)

    def by_child(self) -> dict[str, list[TFClaim]]:
        out: dict[str, list[TFClaim]] = {}
        for c in self.claims:
            out.setdefault(c.child, []).append(c)
        return out

    def children(self) -> dict[str, list[str]]:
        out: dict[str, list[str]] = {}
        for c in self.claims:
            lst = out.setdefault(c.parent, [])
            if c.child not in lst:
                lst.append(c.child)
        return out

    def roots(self) -> list[str]:
        kids = {c.child for c in self.claims}
        return [f for f in self.frames if f not in kids]

    def has_frame(self, frame: str) -> bool:
        f = norm(frame)
        return any(c.parent == f or c.child == f for c in self.claims)


# --- claim sources -----------------------------------------------------------------------------------
def claims_from_model(model, prefix: str = "", owner: str = RSP) -> list[TFClaim]:
    """robot_state_publisher's transforms for a Model (frame_prefix applied)."""
    out = []
    seen: set[str] = set()
    for j in model.joint_list:
        if j.parent is None or j.child is None or j.child in seen:
            continue
        seen.add(j.child)
        if j.type == "floating":
            continue
        kind = STATIC if j.type in ("fixed", "planar") else DYNAMIC
        out.append(TFClaim(prefix + j.parent, prefix + j.child, owner, kind, j.loc, "model"))
    return out


def claims_from_static_tfs(static_tfs: Iterable, notes: list | None = None) -> list[TFClaim]:
    out = []
    for s in static_tfs:
        if getattr(s, "condition", None):
            if notes is not None:
                notes.append((f"static transform {s.parent} -> {s.child} is conditional ({s.condition}); "
                               f"left out of the TF graph", s.loc))
            continue
        owner = "static_transform_publisher" + (f" {s.node_name}" if getattr(s, "node_name", "") else "")
        out.append(TFClaim(s.parent, s.child, owner, STATIC, s.loc, "launch"))
    return out


def claims_from_odom(odom_tfs: Iterable, base_frame: str = "base_link", source: str = "controller") -> list[TFClaim]:
    """From `controllers.OdomTF`s (enabled ones); an empty child means the configured base frame."""
    out = []
    for o in odom_tfs:
        if o is None or not o.enabled:
            continue
        out.append(TFClaim(o.parent, o.child or base_frame, o.owner, DYNAMIC, o.loc, source))
    return out


def claims_from_localization(nodes: Iterable) -> list[TFClaim]:
    out = []
    for n in nodes:
        owner = {"ekf": "robot_localization (ekf)", "ukf": "robot_localization (ukf)"}.get(n.kind, n.kind)
        for e in n.edges():  # localization, SLAM and drivers: every edge the node's parameters turn on
            kind = STATIC if e.kind == STATIC else DYNAMIC
            out.append(TFClaim(e.parent, e.child, f"{owner} {n.node}", kind, e.loc, "localization"))
    return out


def parse_edge(text: str) -> tuple[str, str] | None:
    """"map->odom", "map -> odom", "map/odom"? only the arrow forms."""
    for sep in ("->", "→", " to "):
        if sep in text:
            a, b = text.split(sep, 1)
            a, b = norm(a), norm(b)
            if a and b:
                return a, b
    return None


def claims_from_owners(owners: Mapping[str, str], locs: Mapping[str, Location] | None = None,
                       default_loc: Location | None = None) -> list[TFClaim]:
    out = []
    for edge_text, owner in owners.items():
        e = parse_edge(edge_text)
        if e is None:
            continue
        loc = (locs or {}).get(edge_text) or default_loc or Location("<config>")
        out.append(TFClaim(e[0], e[1], str(owner), DYNAMIC, loc, "config"))
    return out


def declared_matches(owner: str, claim: TFClaim) -> bool:
    """Does the owner written in the config's `tf_owners` name the publisher of `claim`?

    "static_transform_publisher map_to_odom" is named by itself, by "map_to_odom" and by
    "static_transform_publisher"; a controller claim by the controller name.
    """
    d = str(owner).strip()
    o = claim.owner
    return bool(d) and (d == o or o.endswith(" " + d) or o.split(" ", 1)[0] == d)


def add_declared(g: TFGraph, declared: Iterable[TFClaim]) -> TFGraph:
    """Add the config's `tf_owners` claims after everything read from files: a declaration naming a publisher
    already seen on the same edge is that publisher, not a second one."""
    for c in declared:
        edge = (norm(c.parent), norm(c.child))
        if any(x.edge == edge and x.source != "config" and declared_matches(c.owner, x) for x in g.claims):
            continue
        g.add(c)
    return g


# --- analyses ----------------------------------------------------------------------------------------
def _who(c: TFClaim) -> str:
    return f"{c.owner} ({c.kind}, {c.loc.shown()})"


def duplicate_owners(g: TFGraph) -> list[TFProblem]:
    """T001: the same parent -> child edge claimed by two publishers (even with equal values)."""
    out = []
    for parent, child, cs in _edges(g):
        kinds = {c.kind for c in cs}
        if len(cs) < 2 or len(kinds) > 1:
            continue  # mixed kinds: T002
        names = " and ".join(_who(c) for c in cs)
        out.append(TFProblem("T001", f"{parent} -> {child} is published by {len(cs)} publishers: {names}; "
                                     f"tf2 sees the transform flip between them", tuple(cs), (parent, child)))
    return out


def _edges(g: TFGraph):
    """(parent, child, claims of that edge), for every edge claimed at least once."""
    for child, claims in g.by_child().items():
        by_parent: dict[str, list[TFClaim]] = {}
        for c in claims:
            by_parent.setdefault(c.parent, []).append(c)
        for parent, cs in by_parent.items():
            yield parent, child, cs


def static_and_dynamic(g: TFGraph) -> list[TFProblem]:
    """T002: the same parent -> child edge published both static (/tf_static) and dynamic (/tf).

    (Claims with different parents are T003; the three analyses T001/T002/T003 do not overlap.)
    """
    out = []
    for parent, child, cs in _edges(g):
        st = [c for c in cs if c.kind == STATIC]
        dy = [c for c in cs if c.kind == DYNAMIC]
        if st and dy:
            out.append(TFProblem(
                "T002",
                f"{parent} -> {child} is published both on /tf (by {', '.join(_who(c) for c in dy)}) and on "
                f"/tf_static (by {', '.join(_who(c) for c in st)}); the static one never expires and masks "
                f"the other", tuple(dy + st), (parent, child)))
    return out


def multiple_parents(g: TFGraph) -> list[TFProblem]:
    """T003: a frame given two different parents (a TF tree allows one)."""
    out = []
    for child, claims in g.by_child().items():
        parents: dict[str, TFClaim] = {}
        for c in claims:
            parents.setdefault(c.parent, c)
        if len(parents) > 1:
            cs = tuple(parents.values())
            desc = ", ".join(f"{p} (by {_who(c)})" for p, c in parents.items())
            out.append(TFProblem("T003", f"frame {child} has {len(parents)} parents: {desc}; tf2 re-parents it "
                                         f"with every message", cs, (child,)))
    return out


def cycles(g: TFGraph) -> list[TFProblem]:
    """T004: parent -> child chains that come back to where they started (each cycle reported once)."""
    adj: dict[str, list[TFClaim]] = {}
    for c in g.claims:
        adj.setdefault(c.parent, []).append(c)
    out, seen_cycles = [], set()
    color: dict[str, int] = {}
    for start in g.frames:
        if color.get(start):
            continue
        # iterative DFS keeping the path
        stack = [(start, iter(adj.get(start, ())))]
        path: list[TFClaim] = []
        color[start] = 1
        while stack:
            frame, it = stack[-1]
            nxt = next(it, None)
            if nxt is None:
                stack.pop()
                color[frame] = 2
                if path:
                    path.pop()
                continue
            if color.get(nxt.child) == 1:  # back edge: a cycle
                frames_on = [s[0] for s in stack]
                i = frames_on.index(nxt.child)
                cyc = path[i:] + [nxt]
                key = frozenset((c.parent, c.child) for c in cyc)
                if key not in seen_cycles:
                    seen_cycles.add(key)
                    ring = " -> ".join([c.parent for c in cyc] + [cyc[0].parent])
                    out.append(TFProblem("T004", f"TF cycle: {ring}", tuple(cyc), tuple(c.parent for c in cyc)))
                continue
            if color.get(nxt.child) == 2:
                continue
            color[nxt.child] = 1
            path.append(nxt)
            stack.append((nxt.child, iter(adj.get(nxt.child, ()))))
    return out


def not_one_tree(g: TFGraph, frames: Mapping[str, str] | None = None, at: Location | None = None) -> list[TFProblem]:
    """T005: the combined graph has several roots. `frames` gives the REP-105 names (map, odom, base)."""
    names = {"map": "map", "odom": "odom", "base": "base_link", **(frames or {})}
    roots = g.roots()
    if len(roots) <= 1:
        return []
    if any(len({c.parent for c in cs}) > 1 for cs in g.by_child().values()):
        return []  # a frame with two parents joins the trees: that is T003, reported there
    kids = g.children()

    def size(r: str) -> int:
        seen, stack = set(), [r]
        while stack:
            f = stack.pop()
            if f in seen:
                continue
            seen.add(f)
            stack.extend(kids.get(f, ()))
        return len(seen)

    def describe(r: str) -> str:
        n = size(r)
        return f"{r} ({n} frame{'s' if n != 1 else ''})"

    parent_of = {c.child: c.parent for c in g.claims}

    def root_of(f: str) -> str:
        seen = set()
        while f in parent_of and f not in seen:
            seen.add(f)
            f = parent_of[f]
        return f

    m, o, b = norm(names["map"]), norm(names["odom"]), norm(names["base"])
    frames_set = set(g.frames)
    if b not in frames_set:  # the robot's tree: the biggest one holding neither map nor odom
        robot_roots = [r for r in roots if r not in (root_of(m) if m in frames_set else None,
                                                     root_of(o) if o in frames_set else None)]
        b = max(robot_roots, key=size) if robot_roots else b
    hint = ""
    if o in frames_set and b in frames_set and root_of(o) != root_of(b):
        hint = (f"; nothing publishes {o} -> {root_of(b)} (the odometry source: a drive controller with "
                f"enable_odom_tf, robot_localization, or a driver)")
    elif m in frames_set and o in frames_set and root_of(m) != root_of(o):
        hint = (f"; nothing publishes {m} -> {root_of(o)} (localization: AMCL, SLAM or robot_localization with "
                f"world_frame={m})")
    elif m in frames_set and b in frames_set and root_of(m) != root_of(b) and o not in frames_set:
        hint = f"; nothing connects {m} to {root_of(b)} (expected {m} -> {o} -> {b})"
    main = max(roots, key=size)
    # point at a claim of a smaller tree: that is usually the odd one
    claims = tuple(next(c for c in g.claims if c.parent == r) for r in roots if r != main)
    return [TFProblem("T005", f"the TF graph is {len(roots)} separate trees rooted at "
                              f"{', '.join(describe(r) for r in roots)}{hint}",
                      claims, tuple(roots), at)]


class PublisherInfo(TupleRecord):
    """A robot_state_publisher instance (from a launch file or the config)."""

    name: str
    frame_prefix: str | None  # None: unknown (not literal)
    loc: Location
    namespace: str = "/"


def prefix_collisions(publishers: Sequence[PublisherInfo]) -> list[TFProblem]:
    """T006: two robot_state_publishers with the same frame_prefix publish the same frames."""
    by_prefix: dict[str, list[PublisherInfo]] = {}
    for p in publishers:
        if p.frame_prefix is None:
            continue
        by_prefix.setdefault(norm(p.frame_prefix), []).append(p)
    out = []
    for prefix, ps in by_prefix.items():
        if len(ps) < 2:
            continue
        what = f"frame_prefix {prefix!r}" if prefix else "no frame_prefix"
        claims = tuple(TFClaim(prefix, "", p.name, STATIC, p.loc, "launch") for p in ps)
        out.append(TFProblem(
            "T006",
            f"{len(ps)} robot_state_publishers run with {what} "
            f"({', '.join(f'{p.name} in {p.namespace} at {p.loc.shown()}' for p in ps)}); their frames collide in /tf",
            claims, (), ps[0].loc))
    return out


def analyze(g: TFGraph, frames: Mapping[str, str] | None = None,
            publishers: Sequence[PublisherInfo] = ()) -> list[TFProblem]:
    return (duplicate_owners(g) + static_and_dynamic(g) + multiple_parents(g) + cycles(g)
            + not_one_tree(g, frames) + prefix_collisions(publishers))
