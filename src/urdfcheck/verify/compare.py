"""Verification: the publisher's transforms against Pinocchio and yourdfpy on seeded configurations.

``verify(model)`` samples N configurations inside the joint limits (continuous joints: any angle, well beyond
+-pi), feeds each to :class:`~urdfcheck.publisher.StatePublisher` as a JointState naming the independent
joints (exactly what robot_state_publisher receives from ros2_control), composes the published transforms
into link poses, and compares them with

* the batch FK (``link_poses``: same rules, numpy, a consistency check of the message path),
* Pinocchio (``buildModelFromXML``; continuous joints given as (cos, sin); mimic joints evaluated here,
  transitively, and set explicitly, since Pinocchio's own mimic support refuses continuous sources),
* yourdfpy, on a subset of the configurations (it is ~100x slower),

per link, relative to the root of the link's TF tree (a floating joint, which robot_state_publisher never
publishes, starts a new tree). Where the tools genuinely disagree the affected links are left out of that
comparison and the disagreement is reported as a :class:`Delta` (finding V002) instead.

Pinocchio and yourdfpy run in urdfcheck's sandboxed worker (``urdfcheck.core.worker``: forked children with an
address-space limit, CPU and wall-clock limits and a scrubbed environment), so a crash, an
out-of-memory or a hang is reported as that peer's result ("crashed", "out of memory", "timed out") and never
as a pass. Their C-level stdout/stderr is captured and returned. Models above the size caps (DoF, chain
depth) are refused for Pinocchio, whose URDF parser recurses per link (it overflows the C stack on chains of a
few thousand links) and whose ``createData`` grows with the cube of the DoF. ``prestart`` forks the children
before the model is loaded, so that their imports overlap with the caller's work.

yourdfpy's trimesh scene graph ignores a transform update within 1e-8 (per element) of the stored one; the
yourdfpy job invalidates the joints' edges before each update so that the comparison sees yourdfpy's
kinematics, not that cache.
"""
from __future__ import annotations

import math
import time
from dataclasses import dataclass, field

from urdfcheck.core.findings import Finding, Location, Severity, clean_text
from urdfcheck.publisher.kinematics import KinematicTree, kinematic_tree

DEFAULT_TIMEOUT = 120.0
DEFAULT_MEMORY = 2 * 1024**3  # address space a peer may add to what it inherits
MAX_DOF = 256
MAX_DEPTH = 1000
YOURDFPY_SAMPLES = 50


# --- report ---------------------------------------------------------------------------------------------------
@dataclass(frozen=True)
class Delta:
    """A place where robot_state_publisher and a peer genuinely differ (not a bug in either)."""

    code: str  # planar, floating, zero-axis, non-unit-prismatic-axis, mimic-order, mimic-source, ...
    joint: str
    message: str
    peers: tuple[str, ...]  # which comparisons it affects
    loc: object = None
    excluded_links: tuple[str, ...] = ()  # links left out of the affected comparisons


@dataclass
class LinkError:
    link: str
    translation: float  # metres, max over configurations
    rotation: float  # radians
    configuration: int  # index of the worst configuration


@dataclass
class PeerResult:
    name: str  # "batch", "pinocchio", "yourdfpy"
    status: str  # ok, mismatch, crashed, out of memory, timed out, refused, error, unavailable, skipped
    detail: str = ""
    version: str = ""
    configurations: int = 0
    links: dict = field(default_factory=dict)  # link -> LinkError (compared links)
    excluded: dict = field(default_factory=dict)  # link -> reason
    stderr: str = ""
    seconds: float = 0.0
    tolerance: float = 1e-9

    @property
    def ran(self) -> bool:
        return self.status in ("ok", "mismatch")

    @property
    def max_translation(self) -> float:
        return max((e.translation for e in self.links.values()), default=0.0)

    @property
    def max_rotation(self) -> float:
        return max((e.rotation for e in self.links.values()), default=0.0)

    @property
    def worst(self) -> LinkError | None:
        if not self.links:
            return None
        return max(self.links.values(), key=lambda e: max(e.translation, e.rotation))

    def failing(self) -> list[LinkError]:
        return sorted((e for e in self.links.values()
                       if not (e.translation <= self.tolerance and e.rotation <= self.tolerance)),
                      key=lambda e: -max(e.translation, e.rotation))

    def to_dict(self) -> dict:
        w = self.worst
        return {
            "name": self.name, "status": self.status, "detail": self.detail, "version": self.version,
            "configurations": self.configurations, "compared_links": len(self.links),
            "max_translation_error": _num(self.max_translation), "max_rotation_error": _num(self.max_rotation),
            "worst_link": w.link if w else None,
            "links": {k: {"translation": _num(e.translation), "rotation": _num(e.rotation),
                          "configuration": e.configuration} for k, e in self.links.items()},
            "excluded": dict(self.excluded), "stderr": self.stderr, "seconds": round(self.seconds, 3),
        }


def _num(x: float):
    return x if math.isfinite(x) else str(x)


REQUIRED = ("batch", "pinocchio")  # peers whose failure to run makes the verification incomplete


@dataclass
class VerifyReport:
    model: str
    source: str
    configurations: int
    seed: int
    tolerance: float
    joints: list
    peers: list = field(default_factory=list)
    deltas: list = field(default_factory=list)
    seconds: float = 0.0
    loc: object = None

    def peer(self, name: str) -> PeerResult | None:
        return next((p for p in self.peers if p.name == name), None)

    @property
    def status(self) -> str:
        """"pass", "fail" (a peer disagrees beyond the tolerance) or "incomplete" (a required peer did not
        run to completion: never a pass)."""
        if any(p.status == "mismatch" for p in self.peers):
            return "fail"
        for p in self.peers:
            if p.name in REQUIRED and p.status != "ok":
                return "incomplete"
            if p.status in ("crashed", "out of memory", "timed out", "error", "refused"):
                return "incomplete"
        return "pass"

    @property
    def passed(self) -> bool:
        return self.status == "pass"

    def findings(self) -> list[Finding]:
        out = []
        where = self.loc if isinstance(self.loc, Location) else Location(self.source)
        for p in self.peers:
            if p.status == "mismatch":
                for e in p.failing()[:20]:
                    out.append(Finding("V001", Severity.ERROR, clean_text(
                        f"{p.name} disagrees with the publisher on link {e.link!r}: {e.translation:.3g} m, "
                        f"{e.rotation:.3g} rad (configuration {e.configuration}; tolerance {self.tolerance:g})"),
                        where, name="verify-mismatch"))
            elif not p.ran and p.status not in ("unavailable", "skipped"):
                out.append(Finding("V001", Severity.ERROR, clean_text(
                    f"{p.name}: {p.status}" + (f" ({p.detail})" if p.detail else "") +
                    ": the model is not verified against it"), where, name="verify-mismatch"))
            elif p.status == "unavailable" and p.name in REQUIRED:
                out.append(Finding("V001", Severity.ERROR, clean_text(f"{p.name}: {p.status} ({p.detail})"),
                                   where, name="verify-mismatch"))
        for d in self.deltas:
            loc = d.loc if isinstance(d.loc, Location) else where
            out.append(Finding("V002", Severity.INFO, clean_text(d.message), loc, name="semantic-delta"))
        return out

    def to_dict(self) -> dict:
        return {
            "model": self.model, "source": self.source, "status": self.status,
            "configurations": self.configurations, "seed": self.seed, "tolerance": self.tolerance,
            "joints": list(self.joints), "seconds": round(self.seconds, 3),
            "peers": [p.to_dict() for p in self.peers],
            "deltas": [{"code": d.code, "joint": d.joint, "message": d.message, "peers": list(d.peers),
                        "location": str(d.loc) if d.loc is not None else None,
                        "excluded_links": list(d.excluded_links)} for d in self.deltas],
        }


# --- sampling -------------------------------------------------------------------------------------------------
def sample_configurations(model, n: int, seed: int = 0):
    """(joint names, N x k array): independent movable joints inside their limits; continuous in [-3pi, 3pi]."""
    import numpy as np

    tree = kinematic_tree(model)
    names = tree.active_joints()
    rng = np.random.default_rng(seed)
    cols = []
    for name in names:
        j = model.joints[name]
        if j.type == "continuous":
            lo, hi = -3 * math.pi, 3 * math.pi
        else:
            lim = j.limit
            lo = lim.lower if lim is not None and lim.lower is not None else 0.0
            hi = lim.upper if lim is not None and lim.upper is not None else 0.0
            if not (math.isfinite(lo) and math.isfinite(hi)):
                lo, hi = -math.pi, math.pi
            if lo > hi:
                lo, hi = hi, lo
        cols.append(rng.uniform(lo, hi, n))
    arr = np.stack(cols, axis=1) if cols else np.zeros((n, 0))
    return names, arr


# --- deltas ---------------------------------------------------------------------------------------------------
def _subtree(tree: KinematicTree, seg) -> tuple[str, ...]:
    out = {seg.child}
    for s in tree.segments:  # parents first
        if s.parent in out:
            out.add(s.child)
    return tuple(link for link in tree.links if link in out)


def semantic_deltas(model, tree: KinematicTree | None = None, peers=("pinocchio", "yourdfpy")) -> list[Delta]:
    tree = tree or kinematic_tree(model)
    out: list[Delta] = []
    notes = {(n.code, n.joint): n for n in tree.notes}
    for s in tree.segments:
        j = s.joint
        if s.zero_axis:
            n = notes.get(("zero-axis", s.name))
            out.append(Delta("zero-axis", s.name, (n.message if n else f"joint {s.name!r} has a zero axis") +
                             "; Pinocchio keeps the zero axis (the 'rotation' becomes cos(q)*I, a prismatic joint "
                             "does not move) and yourdfpy gives NaN; links below are not compared",
                             ("batch", "pinocchio", "yourdfpy"), j.axis_loc or j.loc, _subtree(tree, s)))
        elif s.type == "planar":
            out.append(Delta("planar", s.name, f"planar joint {s.name!r}: robot_state_publisher publishes it "
                             "static at its origin (kdl_parser makes it fixed); Pinocchio models 3 DOF and is "
                             "compared at its neutral configuration; yourdfpy also keeps it at its origin",
                             ("pinocchio",), j.loc))
        elif s.type == "floating":
            out.append(Delta("floating", s.name, f"floating joint {s.name!r}: robot_state_publisher publishes "
                             f"nothing for it, so {s.child!r} roots a separate TF tree; Pinocchio (free-flyer, "
                             "at neutral) and yourdfpy (origin) are compared on poses relative to "
                             f"{s.child!r}", ("pinocchio", "yourdfpy"), j.loc))
        elif s.kind == "movable" and s.type == "prismatic" and "yourdfpy" in peers:
            norm = math.sqrt(sum(v * v for v in s.raw_axis))
            if abs(norm - 1.0) > 1e-12:
                out.append(Delta("non-unit-prismatic-axis", s.name, f"prismatic joint {s.name!r} has a non-unit "
                                 f"axis (norm {norm:.6g}): KDL and Pinocchio normalise it, yourdfpy translates by "
                                 "q * axis; links below are not compared with yourdfpy", ("yourdfpy",),
                                 j.axis_loc or j.loc, _subtree(tree, s)))
        elif s.type not in ("revolute", "continuous", "prismatic", "fixed"):
            out.append(Delta("unknown-type", s.name, f"joint {s.name!r} has unknown type {s.type!r}: urdfdom "
                             "refuses the model; urdfcheck treats it as fixed", ("pinocchio", "yourdfpy"), j.loc))
    # URDF 1.1 quat_xyzw: yourdfpy reads only xyz and rpy (its _parse_origin), so it uses the identity rotation
    if "yourdfpy" in peers:
        for s in tree.segments:
            if s.joint.origin.quat is not None:
                out.append(Delta("quaternion-origin", s.name, f"joint {s.name!r}: its <origin> gives the rotation "
                                 "as quat_xyzw (URDF 1.1), which yourdfpy does not read (it uses the identity); "
                                 "links below are not compared with yourdfpy", ("yourdfpy",),
                                 s.joint.origin.loc or s.joint.loc, _subtree(tree, s)))
    # <axis> without xyz: the model reads it as urdfdom does (a zero axis), so the zero-axis delta above
    # covers it; yourdfpy alone uses the default 1 0 0
    for s in tree.segments:
        j = s.joint
        if s.kind == "movable" and j.axis_loc is not None and any(
                i.code == "U006" and i.loc == j.axis_loc and "xyz" in i.message for i in model.issues):
            out.append(Delta("axis-without-xyz", s.name, f"joint {s.name!r}: <axis> has no xyz; urdfdom (used by "
                             "robot_state_publisher and Pinocchio) and urdfcheck read a zero axis, so "
                             "robot_state_publisher publishes NaN for it, while yourdfpy uses the default 1 0 0",
                             ("yourdfpy",), j.axis_loc))
    # mimic joints robot_state_publisher does not publish from a message naming the independent joints
    for n in tree.notes:
        if n.code in ("mimic-order", "mimic-source"):
            seg = tree.by_joint.get(n.joint)
            links = _subtree(tree, seg) if seg is not None and seg.kind == "movable" else ()
            out.append(Delta(n.code, n.joint, n.message + ("; links below are not compared" if links else ""),
                             ("batch", "pinocchio", "yourdfpy"), n.loc, links))
        elif n.code == "mimic-not-movable":
            out.append(Delta(n.code, n.joint, n.message, (), n.loc))
        elif n.code == "multiple-roots":
            out.append(Delta(n.code, "", n.message, ("pinocchio", "yourdfpy"), n.loc))
    if "yourdfpy" in peers:
        out.extend(_yourdfpy_mimic_deltas(model, tree))
    return out


def _yourdfpy_mimic_deltas(model, tree):
    """yourdfpy evaluates a mimic joint from its source's slot in the configuration vector: only actuated
    (non-mimic, non-fixed) sources work, and the slot is the source's joint index, not its DOF index."""
    actuated = [j for j in model.joint_list if j.mimic is None and j.type != "fixed"]
    names = [j.name for j in actuated]
    multi_before = {}
    count = 0
    for j in actuated:
        multi_before[j.name] = count
        if j.type in ("floating", "planar"):
            count += 1
    for name, src, _m, _o in tree.mimics:
        seg = tree.by_joint.get(name)
        if seg is None or seg.kind != "movable":
            continue
        j = model.joints[name]
        reason = None
        if src in model.joints and model.joints[src].mimic is not None:
            reason = (f"mimic joint {name!r} follows mimic joint {src!r}: yourdfpy only follows actuated joints "
                      "and uses offset alone")
        elif src in names and multi_before.get(src, 0):
            reason = (f"mimic joint {name!r}: yourdfpy reads its source {src!r} from the wrong slot of its "
                      "configuration vector (a floating or planar joint comes before it)")
        if reason:
            yield Delta("yourdfpy-mimic", name, reason + "; links below are not compared with yourdfpy",
                        ("yourdfpy",), j.mimic.loc, _subtree(tree, seg))


# --- forked peers ---------------------------------------------------------------------------------------------
# The peers run in the one sandboxed worker (urdfcheck.core.worker), with its limits; what verify adds are
# options of it: the child imports its library before the job arrives, and reports progress.
PRELOAD = {"pinocchio": ("numpy", "pinocchio"), "yourdfpy": ("numpy", "yourdfpy")}


def _limits(timeout: float, memory: int | None):
    from urdfcheck.core import worker

    # result: pose arrays whose size verify chose itself (configurations x links), so no cap
    return worker.Limits(memory=memory, timeout=timeout, result=None)


def _peer(name: str, timeout: float, memory: int | None, preload=()):
    from urdfcheck.core import worker

    fn = {"pinocchio": _pinocchio_job, "yourdfpy": _yourdfpy_job}[name]  # looked up now: tests swap them
    return worker.prepare(fn, limits=_limits(timeout, memory), preload=preload, progress=True, name=name)


def _wait(children, progress):
    from urdfcheck.core import worker

    def moved(job):
        if progress and job.progress[1]:
            progress(job.name, *job.progress)

    def done(job):
        if progress:
            progress(job.name, 1, 1)

    worker.wait(children, on_progress=moved, on_done=done)


def _outcome(job):
    """(kind, value, output, seconds): kind ok/memory/error/timeout/crashed/output."""
    from urdfcheck.core import worker

    res = job.result()
    if isinstance(res, worker.Failure):
        return res.kind, res.message, res.stderr, job.seconds
    return "ok", res, job.stderr, job.seconds


def prestart(peers=("pinocchio", "yourdfpy"), *, timeout: float = DEFAULT_TIMEOUT,
             memory: int | None = DEFAULT_MEMORY) -> dict:
    """Fork the peer processes early so that they import their libraries while the caller loads the model.

    Pass the result to ``verify(..., workers=...)``; call ``cancel(workers)`` if verify is not reached."""
    out = {}
    for name in ("yourdfpy", "pinocchio"):  # the slowest first
        if name in peers and _available(name):
            out[name] = _peer(name, timeout, memory, PRELOAD[name])
    return out


def cancel(workers: dict | None) -> None:
    for c in (workers or {}).values():
        c.cancel()
    if workers:
        workers.clear()


def _status_of(kind: str) -> str:
    return {"memory": "out of memory", "timeout": "timed out", "crashed": "crashed", "error": "error",
            "output": "error"}.get(kind, kind)


def _pinocchio_job(progress, xml: str, links: list, values: dict, n: int):
    import numpy as np
    import pinocchio as pin

    model = pin.buildModelFromXML(xml)
    data = model.createData()
    q = np.tile(pin.neutral(model), (n, 1))
    used = []
    for jid in range(1, model.njoints):
        name = model.names[jid]
        v = values.get(name)
        if v is None:
            continue
        jm = model.joints[jid]
        if jm.nq == 1 and jm.nv == 1:
            q[:, jm.idx_q] = v
            used.append(name)
        elif jm.nq == 2 and jm.nv == 1:  # unbounded revolute: (cos, sin)
            q[:, jm.idx_q] = np.cos(v)
            q[:, jm.idx_q + 1] = np.sin(v)
            used.append(name)
    body = pin.FrameType.BODY
    ids, missing = [], []
    for k, link in enumerate(links):
        if model.existFrame(link, body):
            ids.append((k, model.getFrameId(link, body)))
        else:
            missing.append(link)
    out = np.full((n, len(links), 3, 4), np.nan)
    cols = [k for k, _ in ids]
    fids = [f for _, f in ids]
    fk, upd = pin.forwardKinematics, pin.updateFramePlacements
    step = max(1, n // 50)
    for i in range(n):
        fk(model, data, q[i])
        upd(model, data)
        omf = data.oMf
        out[i, cols] = np.array([omf[f].homogeneous[:3] for f in fids]) if fids else out[i, cols]
        if i % step == 0:
            progress(i, n)
    progress(n, n)
    return {"poses": out, "missing": missing, "version": pin.__version__, "nq": model.nq, "nv": model.nv,
            "used": used}


def _yourdfpy_job(progress, xml: str, links: list, values: dict, n: int):
    import io
    import logging

    import numpy as np

    logging.disable(logging.CRITICAL)
    import yourdfpy

    u = yourdfpy.URDF.load(io.BytesIO(xml.encode("utf-8")), build_scene_graph=True, load_meshes=False,
                           build_collision_scene_graph=False, load_collision_meshes=False)
    actuated = [j.name for j in u.actuated_joints if j.type in ("revolute", "continuous", "prismatic")]
    edges = u.scene.graph.transforms.edge_data
    joints = [(j.parent, j.child) for j in u.robot.joints]
    kids: dict = {}
    for p, c in joints:
        kids.setdefault(p, []).append(c)
    order, stack = [], [u.base_link]
    seen = set()
    while stack:
        f = stack.pop()
        if f in seen:
            continue
        seen.add(f)
        order.append(f)
        stack.extend(reversed(kids.get(f, [])))
    # per configuration only update yourdfpy and read its joint transforms; compose afterwards, vectorised
    pairs = [(p, c) for f in order for p, c in ((f, c) for c in kids.get(f, []))]
    pairs = [pc for pc in pairs if pc in edges]
    mats = np.empty((n, len(pairs), 4, 4))
    step = max(1, n // 50)
    stale = np.full((4, 4), np.nan)
    given = [name for name in actuated if name in values]
    touched = [(j.parent, j.child) for j in u.robot.joints
               if (j.name in given or j.mimic is not None) and (j.parent, j.child) in edges]
    for i in range(n):
        # trimesh's scene graph ignores an update within 1e-8 of the stored matrix: invalidate what
        # update_cfg recomputes, so that what is compared is yourdfpy's kinematics, not that cache
        for pc in touched:
            edges[pc]["matrix"] = stale
        u.update_cfg({name: float(values[name][i]) for name in given})
        if pairs:
            mats[i] = [edges[pc]["matrix"] for pc in pairs]
        if i % step == 0:
            progress(i, n)
    world = {u.base_link: np.broadcast_to(np.eye(4), (n, 4, 4))}
    for k, (p, c) in enumerate(pairs):
        if p in world and c not in world:
            world[c] = world[p] @ mats[:, k]
    out = np.full((n, len(links), 3, 4), np.nan)
    for k, link in enumerate(links):
        if link in world:
            out[:, k] = world[link][:, :3]
    progress(n, n)
    return {"poses": out, "version": getattr(yourdfpy, "__version__", ""), "base": u.base_link}


def _urdf_read_by_pinocchio() -> tuple[int, int]:
    """The newest URDF version the urdfdom beside Pinocchio reads (cmeel-urdfdom wheel; unknown: the newest)."""
    v = _dist_version("cmeel-urdfdom")
    try:
        major, minor = (int(x) for x in v.split(".")[:2])
    except ValueError:
        return (1, 2)
    return (1, 2) if major >= 6 else (1, 1) if (major, minor) >= (5, 1) else (1, 0)


def _available(module: str) -> bool:
    import importlib.util

    return importlib.util.find_spec(module) is not None


def _dist_version(name: str) -> str:
    try:
        from importlib.metadata import version

        return version(name)
    except Exception:
        return ""


# --- comparison -----------------------------------------------------------------------------------------------
def _compare(name, ref: dict, other: dict, configs, excluded: dict, tolerance: float) -> PeerResult:
    """ref/other: {link: (M,4,4)} relative to TF roots, over the same M configurations."""
    import numpy as np

    from urdfcheck.publisher.batch import pose_errors

    res = PeerResult(name, "ok", tolerance=tolerance)
    res.excluded = dict(excluded)
    names = []
    for link in ref:
        if link in excluded:
            continue
        if other.get(link) is None:
            res.excluded[link] = f"{name} has no frame for this link"
            continue
        names.append(link)
    m = len(configs)
    if names and m:
        a = np.stack([ref[k] for k in names])  # (L, M, 4, 4)
        b = np.stack([other[k] for k in names])
        dt, dr = pose_errors(a, b)
        both_nan = np.isnan(a[..., :3, :]).any(axis=(-1, -2)) & np.isnan(b[..., :3, :]).any(axis=(-1, -2))
        dt = np.where(both_nan, np.inf, dt)
        dr = np.where(both_nan, np.inf, dr)
        worst = np.argmax(np.maximum(dt, dr), axis=1)
        tmax, rmax = dt.max(axis=1), dr.max(axis=1)
        for i, link in enumerate(names):
            res.links[link] = LinkError(link, float(tmax[i]), float(rmax[i]), int(configs[int(worst[i])]))
    res.configurations = len(configs)
    if res.failing():
        res.status = "mismatch"
        w = res.failing()[0]
        res.detail = (f"{len(res.failing())} link(s) beyond {tolerance:g}; worst {w.link!r}: "
                      f"{w.translation:.3g} m, {w.rotation:.3g} rad")
    return res


def _to_poses(arr, links):
    """(N, L, 3, 4) -> {link: (N,4,4)}."""
    import numpy as np

    n = arr.shape[0]
    out = {}
    for k, link in enumerate(links):
        m = np.zeros((n, 4, 4))
        m[:, :3, :] = arr[:, k]
        m[:, 3, 3] = 1.0
        out[link] = m
    return out


def chain_depth(tree: KinematicTree) -> int:
    depth = {r: 0 for r in tree.roots}
    best = 0
    for s in tree.segments:
        d = depth.get(s.parent, 0) + 1
        depth[s.child] = d
        best = max(best, d)
    return best


def pinocchio_dof(tree: KinematicTree) -> int:
    return sum(1 if s.kind == "movable" else 6 if s.type == "floating" else 3 if s.type == "planar" else 0
               for s in tree.segments)


def publisher_poses(model, names, configs, progress=None):
    """Poses from the message path: every configuration as one JointState through StatePublisher."""
    import numpy as np

    from urdfcheck.publisher.batch import compose_published
    from urdfcheck.publisher.messages import JointState
    from urdfcheck.publisher.state import StatePublisher

    tree = kinematic_tree(model)
    pub = StatePublisher(model, ignore_timestamp=True)
    n = configs.shape[0]
    seg_of_child = {pub.frame(s.child): s.name for s in tree.movable.values()}
    mov = sorted(tree.movable)
    col = {name: k for k, name in enumerate(mov)}
    trans = np.full((len(mov), n, 3), np.nan)
    rots = np.full((len(mov), n, 4), np.nan)
    rows = configs.tolist()
    step = max(1, n // 50)
    flat, counts = [], []
    on = pub.on_joint_state
    for i, row in enumerate(rows):
        ts = on(JointState(names, row, float(i)))
        flat.extend(ts)
        counts.append(len(ts))
        if progress and i % step == 0:
            progress("publisher", i, n)
    if flat:
        idx_s = [col[seg_of_child[t[1]]] for t in flat]
        idx_c = np.repeat(np.arange(n), counts)
        trans[idx_s, idx_c] = np.array([t[2] for t in flat])
        rots[idx_s, idx_c] = np.array([t[3] for t in flat])
    edges = {name: (trans[col[name]], rots[col[name]]) for name in mov}
    fixed_of_child = {pub.frame(s.child): s.name for s in tree.fixed.values()}
    for t in pub.static_transforms():
        edges[fixed_of_child[t.child]] = (np.array(t.translation), np.array(t.rotation))
    if progress:
        progress("publisher", n, n)
    return compose_published(tree, edges, n)


def verify(model, n: int = 1000, seed: int = 0, tolerance: float = 1e-9, *, xml: str | None = None,
           peers=("pinocchio", "yourdfpy"), yourdfpy_samples: int | None = YOURDFPY_SAMPLES,
           timeout: float = DEFAULT_TIMEOUT, memory: int | None = DEFAULT_MEMORY, max_dof: int = MAX_DOF,
           max_depth: int = MAX_DEPTH, progress=None, workers: dict | None = None) -> VerifyReport:
    """Verify `model` (see module docstring). `xml`: the URDF text the peers should parse (default: the
    model written back by ``model_to_urdf``). `progress(stage, done, total)` is called as work advances.
    `workers`: peer processes from ``prestart`` (consumed; those not needed are cancelled)."""
    workers = workers if workers is not None else {}
    try:
        return _verify(model, n, seed, tolerance, xml, peers, yourdfpy_samples, timeout, memory, max_dof,
                       max_depth, progress, workers)
    finally:
        cancel(workers)


def _verify(model, n, seed, tolerance, xml, peers, yourdfpy_samples, timeout, memory, max_dof, max_depth,
            progress, workers) -> VerifyReport:
    import numpy as np

    from urdfcheck.publisher.batch import link_poses, relative_to_tf_roots
    from urdfcheck.publisher.urdfxml import model_to_urdf

    t0 = time.monotonic()
    tree = kinematic_tree(model)
    names, configs = sample_configurations(model, n, seed)
    report = VerifyReport(model.name, model.source, n, seed, tolerance, names, loc=model.loc)
    deltas = semantic_deltas(model, tree, peers)
    report.deltas = deltas
    links = list(tree.links)
    given = {name: configs[:, k] for k, name in enumerate(names)}
    values = tree.resolve_mimic(given, transitive=True)
    peer_xml = xml if xml is not None else model_to_urdf(model)

    def excluded_for(peer):
        out = {}
        for d in deltas:
            if peer in d.peers:
                for link in d.excluded_links:
                    out.setdefault(link, f"{d.code} ({d.joint})")
        return out

    # start the peers first: they run while the publisher side is computed here
    children = []
    pre = []
    ysel = None
    if "yourdfpy" in peers:
        if not _available("yourdfpy"):
            pre.append(PeerResult("yourdfpy", "unavailable", "yourdfpy is not installed", tolerance=tolerance))
        else:
            m = n if not yourdfpy_samples or yourdfpy_samples >= n else int(yourdfpy_samples)
            ysel = np.linspace(0, n - 1, m).astype(int) if m < n else np.arange(n)
            yvalues = {k: v[ysel] for k, v in values.items()}
            c = workers.pop("yourdfpy", None) or _peer("yourdfpy", timeout, memory)
            c.send(peer_xml, links, yvalues, len(ysel))
            children.append(c)

    if "pinocchio" in peers:
        dof, depth = pinocchio_dof(tree), chain_depth(tree)
        if not _available("pinocchio"):
            pre.append(PeerResult("pinocchio", "unavailable", "the 'pin' package is not installed "
                                  "(pip install urdfcheck[verify])", tolerance=tolerance))
        elif _urdf_read_by_pinocchio() < model.version:
            newest = ".".join(map(str, _urdf_read_by_pinocchio()))
            declared = ".".join(map(str, model.version))
            report.deltas.append(Delta("urdf-version", "", f"the model is URDF {declared}, but the urdfdom Pinocchio "
                                       f"uses reads URDF up to {newest} (urdfdom 5.1 reads 1.1, 6.0 reads 1.2): "
                                       "Pinocchio cannot load it, so it is not compared", ("pinocchio",), model.loc))
            pre.append(PeerResult("pinocchio", "skipped", f"its urdfdom reads URDF up to {newest}, the model is "
                                  f"{declared}", tolerance=tolerance))
        elif dof > max_dof or depth > max_depth:
            pre.append(PeerResult("pinocchio", "refused", f"model too large for a safe run: {dof} DoF "
                                  f"(cap {max_dof}), chain depth {depth} (cap {max_depth})", tolerance=tolerance))
        else:
            c = workers.pop("pinocchio", None) or _peer("pinocchio", timeout, memory)
            c.send(peer_xml, links, values, n)
            children.append(c)
    try:
        # publisher: message path, and the batch FK as a consistency check
        ref = publisher_poses(model, names, configs, progress)
        t_batch = time.monotonic()
        world = link_poses(model, configs)
        batch = relative_to_tf_roots(tree, world)
        res = _compare("batch", ref, batch, np.arange(n), excluded_for("batch"), tolerance)
        res.detail = res.detail or "publisher message path vs batch FK (numpy)"
        res.seconds = time.monotonic() - t_batch
        report.peers.append(res)
        _wait(children, progress)
    except BaseException:  # never leave a peer running behind us
        for c in children:
            c.cancel()
        raise
    for c in children:
        kind, value, output, elapsed = _outcome(c)
        if kind != "ok":
            pr = PeerResult(c.name, _status_of(kind), clean_text(value), tolerance=tolerance)
            pr.stderr, pr.seconds = output, elapsed
            pr.version = _dist_version("pin" if c.name == "pinocchio" else c.name)
            report.peers.append(pr)
            continue
        other = relative_to_tf_roots(tree, _to_poses(value["poses"], links))
        idx = np.arange(n) if c.name == "pinocchio" else ysel
        sub = {k: v[idx] for k, v in ref.items()}
        excl = excluded_for(c.name)
        for link in value.get("missing", ()):
            excl.setdefault(link, f"{c.name} has no frame for this link")
        pr = _compare(c.name, sub, other, idx, excl, tolerance)
        pr.version, pr.stderr, pr.seconds = value.get("version", ""), output, elapsed
        if c.name == "yourdfpy" and len(idx) < n:
            pr.detail = (pr.detail + "; " if pr.detail else "") + f"{len(idx)} of {n} configurations"
        report.peers.append(pr)
    report.peers.extend(pre)
    order = {"batch": 0, "pinocchio": 1, "yourdfpy": 2}
    report.peers.sort(key=lambda p: order.get(p.name, 9))
    report.seconds = time.monotonic() - t0
    return report
