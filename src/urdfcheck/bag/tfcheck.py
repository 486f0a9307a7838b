"""Checks over the /tf and /tf_static messages of a recording, against the model's robot_state_publisher.

robot_state_publisher publishes one transform per movable joint on /tf, stamped with the JointState's stamp,
and one per fixed joint on /tf_static. So every recorded /tf transform of a movable joint's edge must equal
what the built-in publisher computes from the JointState with the same stamp (the replay); a difference means
the URDF running on the robot is not the URDF in the repository, or another node publishes that edge too.
"""
from __future__ import annotations

import math
from collections import OrderedDict

from urdfcheck.bag.jointstates import Issue
from urdfcheck.bag.source import NS, Edge, Message
from urdfcheck.publisher.state import StatePublisher


class _Worst:
    __slots__ = ("count", "first", "first_diff", "worst", "worst_diff", "edge_first", "edge_worst")

    def __init__(self):
        self.count = 0
        self.first = self.worst = None
        self.first_diff = self.worst_diff = (0.0, 0.0)
        self.edge_first = self.edge_worst = None

    def add(self, m: Message, edge: Edge, diff: tuple[float, float], scale: float) -> None:
        self.count += 1
        if self.first is None:
            self.first, self.first_diff, self.edge_first = m, diff, edge
        if self.worst is None or diff[0] + diff[1] * scale > self.worst_diff[0] + self.worst_diff[1] * scale:
            self.worst, self.worst_diff, self.edge_worst = m, diff, edge


class TfChecks:
    """Feed the joint states with `joint_state` and the TF messages with `add`; `issues()` at the end."""

    KEEP_STATES = 2048  # joint states kept for the replay, by stamp (TF follows its JointState closely)

    def __init__(self, model, profile: str = "ros2", frame_prefix: str = "", tolerance: float = 1e-6,
                 static_tolerance: float = 1e-4):
        self.model = model
        self.pub = StatePublisher(model, profile=profile, frame_prefix=frame_prefix, ignore_timestamp=True)
        tree = self.pub.tree
        f = self.pub.frame
        self.movable = {(f(s.parent), f(s.child)): s for s in tree.movable.values()}
        self.fixed = {(f(s.parent), f(s.child)): s for s in tree.fixed.values()}
        self.fixed_tq = {k: s.tq(0.0) for k, s in self.fixed.items()}
        self.profile = profile
        self.tolerance = tolerance
        self.static_tolerance = static_tolerance
        self.count = 0
        self.states: OrderedDict[int, dict] = OrderedDict()
        self.predicted: OrderedDict[int, dict] = OrderedDict()
        self.parents: dict[str, dict[str, Message]] = {}
        self.callers: dict[tuple, dict[str, Message]] = {}
        self.last_value: dict[tuple, tuple] = {}
        self.second: dict[tuple, tuple[Message, str]] = {}
        self.replay = _Worst()
        self.replayed = 0
        self.static_off: dict[tuple, tuple[Message, Edge, tuple]] = {}

    def joint_state(self, m: Message) -> None:
        js = m.data
        if len(js.names) != len(js.position):
            return
        self.states[js.stamp_ns] = dict(zip(js.names, js.position))
        while len(self.states) > self.KEEP_STATES:
            self.states.popitem(last=False)

    def add(self, m: Message) -> None:
        self.count += 1
        for e in m.data:
            key = (e.parent, e.child)
            ps = self.parents.setdefault(e.child, {})
            if e.parent not in ps and len(ps) < 8:
                ps[e.parent] = m
            if m.callerid:
                cs = self.callers.setdefault(key, {})
                if m.callerid not in cs and len(cs) < 8:
                    cs[m.callerid] = m
            seg = self.movable.get(key)
            if seg is not None:
                self._movable(m, e, key, seg)
            elif key in self.fixed:
                self._fixed(m, e, key)

    def _movable(self, m: Message, e: Edge, key, seg) -> None:
        if m.kind == "tf_static" and key not in self.second:
            self.second[key] = (m, f"it is published on /tf_static, while robot_state_publisher publishes joint "
                                   f"{seg.name!r} ({seg.type}) on /tf")
        prev = self.last_value.get(key)
        if prev is not None and prev[0] == e.stamp_ns and key not in self.second and \
                sum(_diff(prev[1], prev[2], e)) > 10 * self.tolerance:
            self.second[key] = (m, "two different transforms carry the same stamp")
        self.last_value[key] = (e.stamp_ns, e.translation, e.rotation)
        expected = self._expected(e.stamp_ns, seg)
        if expected is None:
            return
        self.replayed += 1
        d = _diff(expected[0], expected[1], e)
        if d[0] > self.tolerance or d[1] > self.tolerance:
            self.replay.add(m, e, d, 0.1)

    def _expected(self, stamp: int, seg):
        pos = self.states.get(stamp)
        if pos is None:
            return None
        cache = self.predicted.get(stamp)
        if cache is None:
            cache = {t.child: (t.translation, t.rotation) for t in self.pub.transforms_for(
                {k: v for k, v in pos.items() if math.isfinite(v)}, (stamp // NS, stamp % NS))}
            self.predicted[stamp] = cache
            while len(self.predicted) > 64:
                self.predicted.popitem(last=False)
        return cache.get(self.pub.frame(seg.child))

    def _fixed(self, m: Message, e: Edge, key) -> None:
        if m.kind == "tf" and self.profile == "ros2" and key not in self.second:
            seg = self.fixed[key]
            self.second[key] = (m, f"it is published on /tf, while robot_state_publisher publishes fixed joint "
                                   f"{seg.name!r} on /tf_static")
        t, q = self.fixed_tq[key]
        d = _diff(t, q, e)
        if (d[0] > self.static_tolerance or d[1] > self.static_tolerance) and key not in self.static_off:
            self.static_off[key] = (m, e, d)

    # --- the verdict -----------------------------------------------------------------------------------------
    def issues(self) -> list[Issue]:
        out: list[Issue] = []
        joints = self.model.joints
        for key, callers in sorted(self.callers.items()):
            if len(callers) > 1 and (key in self.movable or key in self.fixed):
                seg = self.movable.get(key) or self.fixed[key]
                names = sorted(callers)
                first = min(callers.values(), key=lambda m: m.time_ns)
                out.append(Issue("B010", f"the edge {key[0]} -> {key[1]} (joint {seg.name!r}) has "
                                 f"{len(names)} publishers: {', '.join(names)}; robot_state_publisher publishes it "
                                 "from the model, so TF alternates between their values", first,
                                 (joints[seg.name].loc,) if seg.name in joints else ()))
        for key, (m, why) in sorted(self.second.items()):
            seg = self.movable.get(key) or self.fixed.get(key)
            out.append(Issue("B010", f"the edge {key[0]} -> {key[1]} (joint {seg.name!r}) comes from another "
                             f"publisher as well: {why} (first {m.where()})", m,
                             (joints[seg.name].loc,) if seg.name in joints else ()))
        for key, (m, _edge, d) in sorted(self.static_off.items()):
            seg = self.fixed[key]
            out.append(Issue("B011", f"/tf_static has {key[0]} -> {key[1]} {d[0] * 1000:.1f} mm and "
                             f"{math.degrees(d[1]):.2f} deg away from fixed joint {seg.name!r} in the model "
                             f"({m.where()}): a calibration that was never written back to the URDF, or the "
                             "URDF changed after the recording", m,
                             (joints[seg.name].loc,) if seg.name in joints else ()))
        for child, parents in sorted(self.parents.items()):
            if len(parents) > 1:
                names = sorted(parents)
                first = max(parents.values(), key=lambda m: m.time_ns)
                out.append(Issue("B012", f"frame {child!r} has {len(names)} parents in the recording: "
                                 f"{', '.join(repr(p) for p in names)}; tf2 keeps only the latest, so lookups "
                                 "through it jump between two trees", first))
        w = self.replay
        if w.count:
            sep = (f" (first {w.edge_first.parent} -> {w.edge_first.child} at {w.first.where()}: "
                   f"{w.first_diff[0] * 1000:.3f} mm, {math.degrees(w.first_diff[1]):.3f} deg)")
            out.append(Issue("B013", f"{w.count} of {self.replayed} recorded /tf transforms of robot_state_publisher's "
                             "edges differ from the replay of the recorded joint states through the model; the "
                             f"largest: {w.edge_worst.parent} -> {w.edge_worst.child} "
                             f"{w.worst_diff[0] * 1000:.3f} mm, {math.degrees(w.worst_diff[1]):.3f} deg at "
                             f"{w.worst.where()}{sep if w.first is not w.worst else ''}: the URDF on the robot is not "
                             "the URDF in the repository", w.first))
        return out


def _diff(t, q, e: Edge) -> tuple[float, float]:
    """(translation distance in m, rotation angle in rad) between (t, q) and the recorded edge."""
    dt = math.sqrt(sum((a - b) ** 2 for a, b in zip(t, e.translation)))
    n1 = math.sqrt(sum(x * x for x in q)) or 1.0
    n2 = math.sqrt(sum(x * x for x in e.rotation)) or 1.0
    dot = abs(sum(a * b for a, b in zip(q, e.rotation))) / (n1 * n2)
    ang = 2.0 * math.acos(min(1.0, dot))
    if not (math.isfinite(dt) and math.isfinite(ang)):
        return (math.inf, math.inf)
    return (dt, ang)
