"""S rules: the links and joints must form exactly one tree, with unique names.

One problem, one finding. The structure rules share one view of the joint graph (`_Graph`: every joint
definition as written, duplicates included, as edges parent -> child) and split the ways a model can fail to
be a tree between them so that a single mistake is not reported three times:

* S003 owns joints that name an undefined link. Such a name becomes a *phantom* node of the graph, so a
  joint `world -> base_link` with `world` undefined still makes `base_link` a child: no second root, no
  "no root" report. A defined link that S003 proposes as the intended name ("did you mean") is left out of
  S001/S006, since it only looks separate because of the typo.
* S002 owns the case where no node at all is left as a root (a cycle through everything, a self-loop on
  the only link); its message names the cycles. S005 owns cycles when a root exists (beside the tree, or
  reachable from it), each strongly connected set of links once, self-loops separately.
* S004 owns links with two parent joints (two definitions of one joint name are S008's, not S004's). Two
  roots joined through such a link are one component, so S001 does not report them again.
* S006 owns links no joint touches at all; S001 owns separate trees (roots of different components that
  have at least one joint), and the degenerate "several links, no joint at all" model.

Behaviour of the tools quoted in the messages was checked against urdfdom 3.0.1 (check_urdf), Pinocchio
4.1 and yourdfpy 0.0.60; see the rationale in each rule's catalogue entry.
"""
from __future__ import annotations

import weakref

from urdfcheck.core.findings import Problem, Severity, closest
from urdfcheck.core.records import TYPE_CHECKING, Record
from urdfcheck.rules.catalogue import check

if TYPE_CHECKING:  # the checks' argument types (no import at run time)
    from collections.abc import Iterable, Iterator

    from urdfcheck.model.robot import Model
    from urdfcheck.rules.engine import Context

_RGBA_TOL = 1e-6


def _first_joints(model) -> list:
    """The first definition of every joint name, in document order (later ones are S008's business)."""
    return [j for j in model.joint_list if model.joints.get(j.name) is j]


def _suggest(name: str, candidates: list[str]) -> str | None:
    return closest(name, candidates)


def _q(name) -> str:
    return repr(name)


class _Cycle(Record):
    # joints: in parent -> child order; the last one closes the loop in document order
    # scc_size: links in the strongly connected set the cycle was taken from
    # reachable: a root leads into it (tree walkers recurse forever)
    _fields = ('joints', 'scc_size', 'reachable')

    def __init__(self, joints: list, scc_size: int, reachable: bool):
        self.joints = joints
        self.scc_size = scc_size
        self.reachable = reachable

    @property
    def closing(self):
        return self.joints[-1]

    @property
    def self_loop(self) -> bool:
        return len(self.joints) == 1

    def path(self) -> str:
        if self.self_loop:
            j = self.joints[0]
            return f"{j.parent} -> {j.child}"
        names = [self.joints[0].parent] + [j.child for j in self.joints]
        return " -> ".join(names)

    def describe(self) -> str:
        if self.self_loop:
            j = self.joints[0]
            return f"joint {_q(j.name)} makes link {_q(j.child)} its own parent"
        text = f"kinematic cycle {self.path()} (joints {', '.join(_q(j.name) for j in self.joints)})"
        if self.scc_size > len(self.joints):
            text += f"; {self.scc_size} links in all are caught in interlocking loops"
        return text


class _Graph:
    """Links as nodes (plus a phantom node per undefined name), every joint definition with both ends named as an
    edge parent -> child."""

    def __init__(self, model):
        self.defined = set(model.links)
        self.joints = list(model.joint_list)
        self.order = {id(j): i for i, j in enumerate(model.joint_list)}
        self.edges = [j for j in self.joints if j.parent is not None and j.child is not None]
        nodes = list(model.links)
        self.parents: dict[str, list] = {}
        self.children: dict[str, list] = {}
        self.touched: set[str] = {j.parent for j in self.joints} | {j.child for j in self.joints}
        self.touched.discard(None)
        if not self.touched <= self.defined:
            seen = set(nodes)
            for j in self.joints:
                for end in (j.parent, j.child):
                    if end is not None and end not in seen:  # phantom node for an undefined link (S003)
                        seen.add(end)
                        nodes.append(end)
        for j in self.edges:
            self.parents.setdefault(j.child, []).append(j)
            self.children.setdefault(j.parent, []).append(j)
        self.nodes = nodes
        self.roots = [n for n in nodes if not self.parents.get(n)]
        self.defined_roots = [n for n in self.roots if n in self.defined]
        # defined links S003 proposes for a misspelt end: they only look disconnected because of the typo
        self.suggestion: dict[str, str | None] = {}
        phantoms = nodes[len(model.links):]
        candidates = sorted(self.defined) if phantoms else []
        for n in phantoms:
            self.suggestion[n] = _suggest(n, candidates)
        self.suggested = {s for s in self.suggestion.values() if s is not None}
        self._cycles = None

    # --- connectivity ------------------------------------------------------------
    def components(self) -> dict[str, int]:
        """Weakly connected components (phantom nodes included): node -> component id."""
        parent = {n: n for n in self.nodes}

        def find(x):
            while parent[x] != x:
                parent[x] = parent[parent[x]]
                x = parent[x]
            return x

        for j in self.edges:
            a, b = find(j.parent), find(j.child)
            if a != b:
                parent[b] = a
        ids: dict[str, int] = {}
        out = {}
        for n in self.nodes:
            out[n] = ids.setdefault(find(n), len(ids))
        return out

    def reachable_from_roots(self) -> set[str]:
        out, stack = set(), list(self.roots)
        children = self.children
        while stack:
            n = stack.pop()
            if n in out:
                continue
            out.add(n)
            for j in children.get(n, ()):
                stack.append(j.child)
        return out

    # --- cycles ------------------------------------------------------------------
    def _sccs(self) -> list[list[str]]:
        """Tarjan's strongly connected components, iterative (models can be deep)."""
        succ = {n: [j.child for j in self.children.get(n, ())] for n in self.nodes}
        index: dict[str, int] = {}
        low: dict[str, int] = {}
        on_stack: set[str] = set()
        stack: list[str] = []
        out: list[list[str]] = []
        counter = 0
        for start in self.nodes:
            if start in index:
                continue
            index[start] = low[start] = counter
            counter += 1
            stack.append(start)
            on_stack.add(start)
            work = [(start, iter(succ[start]))]
            while work:
                v, it = work[-1]
                pushed = False
                for w in it:
                    if w not in index:
                        index[w] = low[w] = counter
                        counter += 1
                        stack.append(w)
                        on_stack.add(w)
                        work.append((w, iter(succ[w])))
                        pushed = True
                        break
                    if w in on_stack:
                        low[v] = min(low[v], index[w])
                if pushed:
                    continue
                work.pop()
                if work:
                    u = work[-1][0]
                    low[u] = min(low[u], low[v])
                if low[v] == index[v]:
                    comp = []
                    while True:
                        w = stack.pop()
                        on_stack.discard(w)
                        comp.append(w)
                        if w == v:
                            break
                    out.append(comp)
        return out

    def cycles(self) -> list[_Cycle]:
        """One cycle per strongly connected set of two or more links, plus every self-loop joint."""
        if self._cycles is not None:
            return self._cycles
        reach = self.reachable_from_roots()
        if len(reach) == len(self.nodes) and all(len(ups) == 1 for ups in self.parents.values()):
            # the common case, a tree: a link on a loop has its one parent on the loop too, so walking
            # back along the path from a root that reaches it would never arrive at that root
            self._cycles = []
            return self._cycles
        position = {n: i for i, n in enumerate(self.nodes)}
        found: list[_Cycle] = []
        for comp in self._sccs():
            members = set(comp)
            entered = any(n in reach for n in comp)
            if len(comp) >= 2:
                start = min(comp, key=position.__getitem__)
                walk: list = []
                visited: dict = {}
                cur = start
                while cur not in visited:
                    visited[cur] = len(walk)
                    up = next(j for j in self.parents[cur] if j.parent in members and j.parent != cur)
                    walk.append(up)
                    cur = up.parent
                loop = list(reversed(walk[visited[cur]:]))  # parent -> child order
                last = max(range(len(loop)), key=lambda i: self.order[id(loop[i])])
                loop = loop[last + 1:] + loop[: last + 1]
                found.append(_Cycle(loop, len(comp), entered))
            for n in comp:
                for j in self.parents.get(n, ()):
                    if j.parent == n:
                        found.append(_Cycle([j], 1, n in reach))
        found.sort(key=lambda c: self.order[id(c.closing)])
        self._cycles = found
        return found


_last: tuple = (None, None)  # (weakref to the model, its _Graph): S001..S006 run one after another on one model


def _forget(ref) -> None:
    """The model is gone: so goes its graph, which holds its joints. Kept until the interpreter exits, a
    large model would be traced by each of the collections that run at exit (half a second at 10,000 links)."""
    global _last
    if _last[0] is ref:
        _last = (None, None)


def _graph(model) -> _Graph:
    global _last
    ref, g = _last
    if ref is not None and ref() is model:
        return g
    g = _Graph(model)
    try:
        _last = (weakref.ref(model, _forget), g)
    except TypeError:  # a model type without weak references: just do not cache
        pass
    return g


# --- S001 .. S006: one tree ----------------------------------------------------------


@check("S001")
def multiple_roots(model: Model, ctx: Context) -> Iterator[Problem]:
    g = _graph(model)
    if len(model.links) < 2:
        return
    if not (g.touched & g.defined):
        # several links and not one joint between them: every link is a root
        roots = [n for n in model.links if n not in g.suggested]
        if len(roots) >= 2:
            yield Problem(
                f"{len(roots)} root links and no joint connecting them: {', '.join(map(_q, roots))}. A URDF must be "
                f"one tree with a single root (urdfdom: 'Two root links found')",
                at=model.links[roots[1]], related=tuple(model.links[r] for r in roots if r != roots[1]))
        return
    candidates = [r for r in g.defined_roots if r in g.touched and r not in g.suggested]
    if len(candidates) < 2:
        return
    comp = g.components()
    firsts: dict[int, str] = {}
    for r in candidates:
        firsts.setdefault(comp[r], r)
    roots = list(firsts.values())
    if len(roots) < 2:
        return
    sizes = {c: 0 for c in firsts}
    for n in g.defined:
        if comp[n] in sizes:
            sizes[comp[n]] += 1
    trees = ", ".join(f"{_q(r)} ({sizes[comp[r]]} links)" for r in roots)
    yield Problem(
        f"the links form {len(roots)} separate trees, rooted at {trees}: a URDF must have exactly one root link. "
        f"urdfdom refuses the model ('Two root links found'), so robot_state_publisher and MoveIt do not start",
        at=model.links[roots[1]], related=tuple(model.links[r] for r in roots if r != roots[1]))


@check("S002")
def no_root(model: Model, ctx: Context) -> Iterator[Problem]:
    g = _graph(model)
    if not model.links or g.roots:
        return
    cycles = g.cycles()
    if not cycles:  # cannot happen: without a root every link has a parent, so the parents loop
        yield Problem("no root link: every link is the child of a joint (urdfdom: 'No root link found')", at=model)
        return
    first = cycles[0]
    others = [j for c in cycles for j in c.joints if j is not first.closing]
    because = "; ".join(c.describe() if c.self_loop else f"of the {c.describe()}" for c in cycles)
    yield Problem(
        f"no root link: every link is the child of a joint, because {because}. urdfdom refuses the model "
        f"('No root link found. The robot xml is not a valid tree')",
        at=first.closing, related=tuple(others))


def _attach_point(model, g) -> str | None:
    """The link an attachable fragment (an end effector, a sensor mount) hangs from: the only undefined name of
    the model is the parent of exactly one joint, no defined link resembles it, and that joint's child is the
    root of everything else (issue 20). None when the model is not such a fragment."""
    dangling = [(j, end, name) for j in model.joint_list for end, name in (("parent", j.parent), ("child", j.child))
                if name is not None and name not in model.links]
    if len(dangling) != 1:
        return None
    j, end, name = dangling[0]
    # `world` is no attach point: a robot fixed to it must define it (urdfdom refuses it; only Gazebo knows it)
    if end != "parent" or name == "world" or g.suggestion.get(name) or j.child not in model.links:
        return None
    children = {x.child for x in model.joint_list}
    roots = [n for n in model.links if n not in children]
    return name if not roots else None


@check("S003")
def missing_link(model: Model, ctx: Context) -> Iterator[Problem]:
    links = model.links
    g = _graph(model)
    attach = _attach_point(model, g)
    for j in model.joint_list:
        for end, name, loc in (("parent", j.parent, j.parent_loc), ("child", j.child, j.child_loc)):
            if name is None or name in links:
                continue
            if name == attach:
                yield Problem(f"joint {_q(j.name)} attaches this model to link {_q(name)}, which it does not define: "
                              f"an attachable fragment (an end effector, a sensor mount), complete only in the robot "
                              f"that defines {_q(name)}; urdfdom refuses it alone ('parent link [{name}] of joint "
                              f"[{j.name}] not found')", at=loc or j, severity=Severity.INFO)
                continue
            hint = g.suggestion.get(name)
            hint = f" (did you mean {hint!r}?)" if hint else ""
            yield Problem(
                f"joint {_q(j.name)} names {end} link {_q(name)}, which is not defined{hint}: urdfdom refuses the "
                f"model ('{end} link [{name}] of joint [{j.name}] not found')",
                at=loc or j)


@check("S004")
def multiple_parents(model: Model, ctx: Context) -> Iterator[Problem]:
    g = _graph(model)
    for child in g.nodes:
        if child not in g.defined:
            continue
        ups, names = [], set()
        for j in g.parents.get(child, ()):
            if j.parent != j.child and j.name not in names:  # self-loops are S005/S002, redefinitions S008
                names.add(j.name)
                ups.append(j)
        if len(ups) < 2:
            continue
        first = ups[0]
        for j in ups[1:]:
            yield Problem(
                f"link {_q(child)} is the child of joint {_q(j.name)} (parent {_q(j.parent)}) and already of joint "
                f"{_q(first.name)} (parent {_q(first.parent)}): a link has exactly one parent. urdfdom keeps one of "
                f"them depending on joint names, Pinocchio silently drops the other, and a tree walk visits "
                f"{_q(child)} twice",
                at=j.child_loc or j, related=(first.child_loc or first,))


@check("S005")
def kinematic_cycle(model: Model, ctx: Context) -> Iterator[Problem]:
    g = _graph(model)
    if not g.roots:  # no root at all: S002 names the cycles
        return
    for c in g.cycles():
        if c.reachable:
            effect = ("the root leads into the loop, so tree walkers never finish (check_urdf recurses "
                      "until it crashes; Pinocchio refuses the model)")
        else:
            effect = ("urdfdom still loads the model, but no root leads to these links, so KDL, "
                      "robot_state_publisher and Pinocchio silently leave them out")
        if c.self_loop:
            j = c.closing
            msg = f"joint {_q(j.name)} has link {_q(j.child)} as both parent and child: {effect}"
        else:
            msg = f"{c.describe()}: {effect}"
        yield Problem(msg, at=c.closing, related=tuple(j for j in c.joints if j is not c.closing))


@check("S006")
def disconnected_link(model: Model, ctx: Context) -> Iterator[Problem]:
    g = _graph(model)
    if len(model.links) < 2 or not (g.touched & g.defined):
        return  # a single link is a valid model; links without any joint at all are S001
    if not any(r in g.touched for r in g.roots):
        return  # no rooted tree to be disconnected from (only cycles, reported by S005): this link is the root
    for link in model.links.values():
        if link.name in g.touched or link.name in g.suggested:
            continue
        yield Problem(
            f"link {_q(link.name)} is attached to no joint, so it is not part of the robot's tree: urdfdom refuses "
            f"a model with a second root link ('Two root links found'), and no TF frame is ever published for it",
            at=link)


# --- S007 .. S011: names ------------------------------------------------------------


def _redefined(parts, by_name, kind: str):
    for part in parts:
        first = by_name[part.name]
        if first is not part:
            yield Problem(
                f"{kind} {_q(part.name)} is defined again: urdfdom refuses the model ('{kind} '{part.name}' is not "
                f"unique'); parsers that accept it keep one definition and silently drop the other",
                at=part, related=(first,))


@check("S007")
def duplicate_link(model: Model, ctx: Context) -> Iterable[Problem]:
    return _redefined(model.link_list, model.links, "link")


@check("S008")
def duplicate_joint(model: Model, ctx: Context) -> Iterable[Problem]:
    return _redefined(model.joint_list, model.joints, "joint")


def _same_look(a_rgba, a_tex, b_rgba, b_tex) -> bool:
    if (a_tex or None) != (b_tex or None):
        return False
    if a_rgba is None or b_rgba is None:
        return a_rgba is None and b_rgba is None
    return len(a_rgba) == len(b_rgba) and all(abs(x - y) <= _RGBA_TOL for x, y in zip(a_rgba, b_rgba))


def _look(rgba, texture) -> str:
    parts = []
    if rgba is not None:
        parts.append("rgba " + " ".join(f"{v:g}" for v in rgba))
    if texture:
        parts.append(f"texture {texture!r}")
    return " with ".join(parts) or "no colour"


@check("S009")
def duplicate_material(model: Model, ctx: Context) -> Iterator[Problem]:
    # 1. a top-level <material> name twice: urdfdom refuses the model even when both are identical
    for m in model.material_list:
        first = model.materials[m.name]
        if first is m:
            continue
        if _same_look(m.rgba, m.texture, first.rgba, first.texture):
            how = "identically"
        else:
            how = f"as {_look(m.rgba, m.texture)} after {_look(first.rgba, first.texture)}"
        yield Problem(
            f"material {_q(m.name)} is defined again at the top level ({how}): urdfdom refuses any repeated "
            f"top-level material ('material '{m.name}' is not unique'), even an identical one",
            at=m, related=(first,))
    # 2. a colour given inside a <visual> for a name that already has another look: urdfdom (and so RViz,
    #    MoveIt, Pinocchio) silently uses the earlier definition; yourdfpy uses the inline one
    known: dict = dict(model.materials)
    for link in model.link_list:
        for v in link.visuals:
            ref = v.material
            if ref is None or not ref.name or (ref.rgba is None and not ref.texture):
                continue
            prev = known.get(ref.name)
            if prev is None:
                known[ref.name] = ref
                continue
            if _same_look(ref.rgba, ref.texture, prev.rgba, prev.texture):
                continue
            yield Problem(
                f"link {_q(link.name)} gives material {_q(ref.name)} {_look(ref.rgba, ref.texture)}, but "
                f"{_q(ref.name)} is already {_look(prev.rgba, prev.texture)}: urdfdom-based tools (RViz, MoveIt, "
                f"Pinocchio) silently use the earlier definition, yourdfpy this one",
                at=ref, related=(prev,), severity=Severity.WARNING)


@check("S010")
def link_joint_name_clash(model: Model, ctx: Context) -> Iterator[Problem]:
    for j in _first_joints(model):
        link = model.links.get(j.name)
        if link is None:
            continue
        yield Problem(
            f"joint {_q(j.name)} has the same name as a link: URDF allows it, but Pinocchio creates a frame for "
            f"each and getFrameId({j.name!r}) fails ('Several frames match'), and SDFormat (Gazebo) requires "
            f"links and joints of a model to have distinct names",
            at=j, related=(link,))


@check("S011")
def empty_model(model: Model, ctx: Context) -> Iterator[Problem]:
    if model.link_list or any(i.code == "U001" for i in model.issues):
        return
    extra = ""
    if model.materials or model.joint_list:
        extra = " If this file is only a fragment included by another description, leave it out of the lint targets"
    yield Problem(
        f"the model defines no <link>: urdfdom refuses it ('No link elements found in urdf file'), so nothing "
        f"can load it.{extra}",
        at=model)
