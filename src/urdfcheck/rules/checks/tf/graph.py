"""The deployment TF graph: the claims (`consumers.tfclaims`) of one deployment, and what is wrong with it.

Analyses return `TFProblem`s (never findings): the T rules beside this module (`rules.checks.tf`) turn them into
T001..T006, and `deployment_graph` builds the graph of a model and its consumers for them and for C020/C024.
"""
from __future__ import annotations

from collections.abc import Iterable, Mapping, Sequence

from urdfcheck.consumers.tfclaims import (
    DECLARED,
    DYNAMIC,
    STATIC,
    UNTRUSTED,
    TFClaim,
    claims_from_localization,
    claims_from_model,
    claims_from_odom,
    claims_from_static_tfs,
    norm,
)
from urdfcheck.core.findings import Location
from urdfcheck.core.records import Record, TupleRecord


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


class TFGraph(Record):
    # notes: (message, Location): claims left out (conditional launch nodes)
    _fields = ('claims', 'notes')
    claim_only: frozenset = frozenset()  # claims that may conflict, never publish (`claim_only`; issue 36)

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


READ = ("launch", "controller", "driver", "localization")  # the claims read from consumer files


def claim_only(g: TFGraph, c: TFClaim) -> bool:
    """Does `c` only claim (a conflict), never publish? An untrusted config's `tf_owners` declaration, or the
    transform of a file such a config names that nothing known to run with the model starts (consumers.run_with)."""
    return c.source == UNTRUSTED or c in g.claim_only


def vouched_claims(g: TFGraph) -> TFGraph:
    """`g` without the declarations of a config the runner did not vouch for: what may count as published."""
    if not any(claim_only(g, c) for c in g.claims):
        return g
    return TFGraph([c for c in g.claims if not claim_only(g, c)])


def untrusted_hint(g: TFGraph, frames, owner: str = "") -> str:
    """What to say when a frame is published only by an untrusted config's declaration (`owner`: the node the
    finding is about, whose own claim never counts for it)."""
    said = [c for c in g.claims if claim_only(g, c) and ({c.parent, c.child} & set(frames))
            and not (owner and (c.owner == owner or c.owner.endswith(owner)))]
    if not said:
        return ""
    c = said[0]
    how = ("counts only in a config the runner names with --config FILE --trust-config (or --config-from REV): one "
           "found in the checkout may add a publisher, never publish a frame")
    if c.source != UNTRUSTED:
        return (f"; {c.owner} ({c.loc.shown()}) would publish {c.parent} -> {c.child}, but only the config makes its "
                f"file run with the model (no launch file that starts robot_state_publisher runs it), which {how}")
    return f"; the config's tf_owners declares {c.parent} -> {c.child} ({c.owner}, {c.loc.shown()}), which {how}"


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
        if any(x.edge == edge and x.source not in DECLARED and declared_matches(c.owner, x) for x in g.claims):
            continue
        g.add(c)
    return g


def deployment_graph(model, c) -> TFGraph:
    """The TF graph of a model and its consumers (kept on the consumers for the model last asked about)."""
    cache = getattr(c, "_graph_cache", None)
    key = id(model)
    if cache is not None and cache[0] == key:
        return cache[1]
    g = TFGraph()
    g.extend(claims_from_model(model, c.rsp_prefix))
    for li in c.launch:
        g.extend(claims_from_static_tfs(li.static_tfs, g.notes))
    base = c.frames.get("base", "base_link")
    # files no launch file of this deployment reads claim no transform in it (issue 20)
    g.extend(claims_from_odom((ctrl.odom_tf for ctrl in c.controllers if not getattr(ctrl, "elsewhere", None)),
                              base, "controller"))
    g.extend(claims_from_odom((d.odom_tf for d in c.drivers if not getattr(d, "elsewhere", None)), base, "driver"))
    g.extend(claims_from_localization(c.localization))
    if model.plugins:  # Gazebo plugins' odometry transforms (consumers/gazebo.py)
        from urdfcheck.consumers.gazebo import plugin_claims

        g.extend(plugin_claims(model))
    add_declared(g, c.tf_owners)  # after the claims read from files: a declaration may name one of them
    if getattr(c, "run_files", None) is not None:  # an unvouched config's reading (consumers.run_with)
        g.claim_only = frozenset(cl for cl in g.claims if cl.source in READ and not c.runs(cl.loc.file))
    c._graph_cache = (key, g)
    return g


def distinct_locations(locs, at=None) -> tuple:
    """Each location (or part with a .loc) once, in order, leaving out `at`: a finding's related places."""
    out: dict[str, Location] = {}
    for loc in locs:
        loc = getattr(loc, "loc", loc)
        if loc is None or (at is not None and str(loc) == str(at)):
            continue
        out.setdefault(str(loc), loc)
    return tuple(out.values())


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
