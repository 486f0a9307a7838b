"""Checks over the /tf and /tf_static messages of a recording, against the model's robot_state_publisher.

robot_state_publisher publishes one transform per movable joint on /tf, stamped with the JointState's stamp,
and one per fixed joint on /tf_static (ROS 1 with `use_tf_static: false`: on /tf, stamped ahead). So every
recorded /tf transform of a movable joint's edge must equal what the built-in publisher computes from the
JointState with the same stamp (the replay); a difference means the URDF running on the robot is not the URDF in
the repository, or another node publishes that edge too.

What real recordings add (issue 39): `rosbag record` often writes a /tf message before the JointState it was
computed from, so a transform waits for its JointState a short while (by receive time) instead of being dropped;
the robot may run under a frame prefix (`tf_prefix`, `frame_prefix`): given by the config or deployment, or
recognised from the recorded names (`robot1/base_link -> robot1/upper_arm` is the model's edge under
`robot1/`); a second publisher of an edge shows by its callerid (ROS 1), or, without callerids, by the edge being
in two different /tf_static messages, or by a movable edge whose stamps match no JointState while the other
edges' do.
"""
from __future__ import annotations

import math
from collections import OrderedDict, deque

from urdfcheck.bag.jointstates import Issue
from urdfcheck.bag.source import NS, Edge, FastEdges, Message
from urdfcheck.publisher.state import StatePublisher

WAIT_NS = NS // 2  # how long (receive time) a /tf transform waits for the JointState it was computed from
MAX_PENDING = 4096
MAX_KEYS = 4096  # distinct edges followed for callerids and /tf_static messages


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
    """Feed the joint states with `joint_state` and the TF messages with `add`; `issues()` at the end.
    `ros`: 1 or 2, what the recording says it is (a ROS 1 `.bag`); None: `profile` decides."""

    KEEP_STATES = 2048  # joint states kept for the replay, by stamp (TF follows its JointState closely)

    def __init__(self, model, profile: str = "ros2", frame_prefix: str = "", tolerance: float = 1e-6,
                 static_tolerance: float = 1e-4, ros: int | None = None):
        self.model = model
        if ros is not None:
            profile = "ros1" if ros == 1 else "ros2"
        self.profile = profile
        self.pub = StatePublisher(model, profile=profile, frame_prefix="", ignore_timestamp=True)
        tree = self.pub.tree
        self.movable = {(s.parent, s.child): s for s in tree.movable.values()}
        self.fixed = {(s.parent, s.child): s for s in tree.fixed.values()}
        self.fixed_tq = {k: s.tq(0.0) for k, s in self.fixed.items()}
        self.child_parent = {c: p for p, c in list(self.movable) + list(self.fixed)}
        self.given_prefix = frame_prefix or ""
        self.prefix: str | None = None  # the prefix the recording shows, once one is seen
        self.names: dict[tuple, tuple | None] = {}
        self.tolerance = tolerance
        self._tol2 = tolerance * tolerance
        self._cos2 = math.cos(tolerance / 2) ** 2
        self._cos4 = math.cos(tolerance / 4) ** 2  # (numpy's first look: half the tolerance, the rest exactly)
        self._fast: dict[tuple, _FastPlan] = {}
        self._jobs: list = []  # comparisons of the replay put off (_replay_fast), made together (_run_jobs)
        self._lv_plan = None  # the plan whose arrays hold the last values of its edges (not yet in last_value)
        self.static_tolerance = static_tolerance
        self.count = 0
        self.tf_messages = 0
        self.states: OrderedDict[int, dict | tuple] = OrderedDict()  # stamp -> positions, or (names, positions)
        self.predicted: OrderedDict[int, dict] = OrderedDict()
        self.pending: deque = deque()
        self.pending_stamps: dict[int, int] = {}
        self.parents: dict[str, dict[str, Message]] = {}
        self.callers: dict[tuple, dict[str, Message]] = {}
        self.static_sets: dict[tuple, dict[frozenset, Message]] = {}
        self.last_value: dict[tuple, tuple] = {}
        self.second: dict[tuple, tuple[Message, str]] = {}
        self.replay = _Worst()
        self.replayed = 0
        self.static_compared = 0
        self.matched: dict[tuple, list] = {}  # model key -> [matched, unmatched, first unmatched message]
        self.on_tf: dict[tuple, int] = {}  # model key -> times seen in the recording
        self.static_off: dict[tuple, tuple[Message, Edge, tuple]] = {}
        self.fixed_on: dict[tuple, dict[str, Message]] = {}  # fixed edge -> {"tf" / "tf_static": first message}
        self.alternating: dict[tuple, list] = {}  # an edge not of the model -> its back-and-forth record

    # --- names ---------------------------------------------------------------------------------------------
    def model_key(self, parent: str, child: str):
        """The model's (parent, child) for a recorded edge, under the frame prefix; None: not the model's."""
        key = (parent, child)
        got = self.names.get(key, False)
        if got is not False:
            return got
        got = None
        if key in self.movable or key in self.fixed:
            got = key  # (a prefix the config gives but the recording does not show: the names decide)
        else:
            for i in range(1, len(child)):
                mc = child[i:]
                mp = self.child_parent.get(mc)
                if mp is not None and parent == child[:i] + mp:
                    pre = child[:i]
                    if self._prefix_ok(pre):
                        got = (mp, mc)
                    break
        if len(self.names) < 65536:
            self.names[key] = got
        return got

    def _prefix_ok(self, pre: str) -> bool:
        if self.given_prefix:
            norm = {self.given_prefix, self.given_prefix.strip("/") + "/", "/" + self.given_prefix.strip("/") + "/"}
            return pre in norm
        if self.prefix is None:
            self.prefix = pre  # the first robot under a prefix is the one checked
        return pre == self.prefix

    # --- messages ------------------------------------------------------------------------------------------
    def joint_state(self, m: Message) -> None:
        js = m.data
        if len(js.names) != len(js.position):
            return
        st = js.stamp_ns
        states = self.states
        have = states.get(st)
        if have is None:  # kept as they came: made a mapping only when a /tf of that stamp asks (_positions)
            states[st] = (js.names, js.position)
        else:  # several drivers, one stamp: robot_state_publisher handles each message; the union replays them
            have = self._positions(st)
            have.update(zip(js.names, js.position))
            self.predicted.pop(st, None)
        if len(states) > self.KEEP_STATES:
            states.popitem(last=False)
        if st in self.pending_stamps:
            self._settle(m.time_ns, st)

    def joint_state_batch(self, b, lo: int = 0, hi: int | None = None) -> None:
        """A JointStateBatch (its messages lo to hi): `joint_state` for each (the positions kept as rows)."""
        names = b.names
        if len(names) != b.position.shape[1]:
            return
        states, pending, keep = self.states, self.pending_stamps, self.KEEP_STATES
        P, times = b.position, b.times
        stamps = b.stamp_list()
        for j in range(lo, len(stamps) if hi is None else hi):
            st = stamps[j]
            have = states.get(st)
            if have is None:  # (a copy of the row: a view would keep the whole batch alive)
                states[st] = (names, P[j].copy(), None)
            else:
                have = self._positions(st)
                have.update(zip(names, P[j].tolist()))
                self.predicted.pop(st, None)
            if len(states) > keep:
                states.popitem(last=False)
            if st in pending:
                self._settle(times[j], st)

    def batch(self, b) -> bool:
        """`joint_state_batch` and `add` for a JointStateBatch and the TF messages riding with it (a TfRun), all
        at once, when their order cannot change what is found: no transform waits for its JointState, every
        stamp of the batch is new and once only, each TF message's edges carry one stamp, found among the joint
        states recorded before it (and still kept), and the message's layout is known (a plan) with only
        movable edges of the model. False: nothing was done (message by message, as recorded)."""
        import numpy as np

        from urdfcheck.bag.source import TfRun

        names = b.names
        run = b.tfs
        if self.pending or self.pending_stamps or len(names) != b.position.shape[1] or \
                (len(run) and type(run) is not TfRun):
            return False
        S = b.stamps
        n = len(S)
        order = np.argsort(S, kind="stable")
        u = S[order]
        if n > 1 and (u[1:] == u[:-1]).any():
            return False
        states = self.states
        if states and not states.keys().isdisjoint(S.tolist()):
            return False
        if len(run):
            plan = self._fast.get((id(run.layout), run.callerid))
            if plan is None or plan.layout is not run.layout or not plan.usable or plan.others or plan.fixed or \
                    not len(plan.mov) or not plan.all_plain or run.kind != "tf":
                return False
            Sm = run.stamps[:, plan.mov]
            st = Sm[:, 0]
            if not (Sm == st[:, None]).all() or len(np.unique(st)) != len(st):
                return False
            r = np.minimum(np.searchsorted(u, st), n - 1)
            inb = u[r] == st
            row = order[r]
            half = self.KEEP_STATES // 2
            if not (~inb | ((row < run.at) & (run.at - row <= half))).all():
                return False
            P = b.position[row]
            for i in np.flatnonzero(~inb).tolist():  # its joint state came in an earlier batch, still kept
                ent = states.get(int(st[i]))
                if type(ent) is not tuple or len(ent) != 3 or ent[0] is not names or run.at[i] > half:
                    return False
                P[i] = _row(ent)
            cols = plan.columns(names)
            if cols is None:
                return False
            Q = P[:, cols]
            if not np.isfinite(Q).all():
                return False
            if self._lv_plan is not plan:
                self._own(plan, np)
            prev = np.concatenate([plan.last_s[None, :], Sm[:-1]])
            if (prev == Sm).any():  # (two transforms of one stamp: told apart message by message)
                return False
        self._insert(b)
        if not len(run):
            return True
        self._run_jobs()  # those put off before, first: mismatches stay in recording order
        m = len(run)
        self.count += m
        self.tf_messages += m
        plan.seen += m
        V = run.values[:, plan.mov]
        plan.last_s, plan.last_v = Sm[-1], V[-1]
        plan.had[:] = True
        ok = self._close(plan, Q, V, np)
        plan.ok_counts += ok.sum(axis=0)
        self.replayed += int(ok.sum())
        if not ok.all():
            for i in np.flatnonzero(~ok.all(axis=1)).tolist():
                tm = run.message(i)
                pos = dict(zip(names, P[i].tolist()))
                for c in np.flatnonzero(~ok[i]).tolist():
                    self._compare(tm, tm.data.edge(int(plan.mov[c])), plan.mkeys[c], plan.msegs[c], pos)
        return True

    def _insert(self, b) -> None:
        """The batch's joint states into `states`, as `joint_state_batch` keeps them (every stamp new): only the
        last KEEP_STATES can stay."""
        from itertools import repeat

        states, keep = self.states, self.KEEP_STATES
        n = len(b.stamps)
        tail = min(n, keep)
        excess = len(states) + tail - keep
        if excess >= len(states):
            states.clear()
        else:
            for _ in range(excess):
                states.popitem(last=False)
        rows = b.position[n - tail:].copy()  # (a copy: a view would keep the whole batch alive)
        states.update(zip(b.stamps[n - tail:].tolist(), zip(repeat(b.names), repeat(rows), range(tail))))

    def add(self, m: Message) -> None:
        d = m.data
        if m.kind == "tf" and type(d) is FastEdges:
            plan = self._fast.get((id(d.layout), m.callerid))
            if plan is not None and plan.layout is d.layout and plan.usable:
                self._add_fast(m, plan)
                return
            self._add_slow(m)
            if len(self._fast) > 256:
                self._fold()
                self._fast.clear()
            self._fast[(id(d.layout), m.callerid)] = _FastPlan(self, d.layout)
            return
        self._add_slow(m)

    def _add_fast(self, m: Message, plan) -> None:
        """`_add_slow` for a /tf message of a layout seen before from the same publisher: its edges' parents and
        publishers are already known; the replay's comparisons are made with numpy, and what numpy finds not
        clearly within tolerance goes through `_compare` itself."""
        import numpy as np

        self.count += 1
        self.tf_messages += 1
        d = m.data
        S, V = d.stamps, d.values
        plan.seen += 1  # (folded into on_tf by _fold)
        for i, raw in plan.others:
            self._jumps(m, raw, tuple(V[i, :3].tolist()))
        for i, key in plan.fixed:
            self._fixed(m, d.edge(i), key)
        mi = plan.mov
        if len(mi):
            Sm, Vm = S[mi], V[mi]
            if self._lv_plan is not plan:  # the last values of these edges, from last_value into the plan's arrays
                self._own(plan, np)
            same = np.flatnonzero(Sm == plan.last_s)
            if len(same):
                second, tol10 = self.second, 10 * self.tolerance
                for c in same.tolist():
                    key = plan.mkeys[c]
                    if key not in second and plan.had[c] and sum(_diff(plan.last_v[c, :3].tolist(),
                                                                      plan.last_v[c, 3:].tolist(),
                                                                      d.edge(int(mi[c])))) > tol10:
                        second[key] = (m, "two different transforms carry the same stamp")
            plan.last_s, plan.last_v = Sm, Vm
            plan.had[:] = True
            Sl = Sm.tolist()
            self._replay_fast(m, plan, Sl, V[mi], np)
        self._expire(m.time_ns)

    def _replay_fast(self, m, plan, Sl, V, np) -> None:
        d = m.data
        st = Sl[0]
        ent = self.states.get(st)
        cols = None
        if ent is not None and type(ent) is tuple and len(ent) == 3 and Sl.count(st) == len(Sl):
            cols = plan.columns(ent[0])
        if cols is None:  # another stamp, a merged state, a state not yet recorded: edge by edge, as before
            for c, key in enumerate(plan.mkeys):
                e = d.edge(int(plan.mov[c]))
                if e.stamp_ns in self.states:
                    self._compare(m, e, key, plan.msegs[c])
                elif len(self.pending) < MAX_PENDING:
                    self.pending.append((m.time_ns, m, e, key, plan.msegs[c]))
                    self.pending_stamps[e.stamp_ns] = self.pending_stamps.get(e.stamp_ns, 0) + 1
                else:
                    self._unmatched(m, key)
            return
        q = _row(ent)[cols]
        if np.isfinite(q).all() and plan.all_plain:  # compared later, with other messages' (_run_jobs)
            self._jobs.append((m, plan, q, V, ent))
            if len(self._jobs) >= 256:
                self._run_jobs()
            return
        with np.errstate(all="ignore"):
            ok = self._close(plan, q, V, np) & plan.plain & np.isfinite(q)
        okl = ok.tolist()
        plan.ok_counts += ok
        self.replayed += okl.count(True)
        if okl.count(True) != len(okl):
            for c, good in enumerate(okl):
                if not good:
                    self._compare(m, d.edge(int(plan.mov[c])), plan.mkeys[c], plan.msegs[c])

    def _run_jobs(self) -> None:
        """The replay's comparisons `_replay_fast` put off, made with numpy for many messages at once; in the
        order of the messages, what is not clearly within tolerance goes through `_compare` with the joint
        state the message was matched with."""
        jobs = self._jobs
        if not jobs:
            return
        self._jobs = []
        import numpy as np

        groups: dict[int, list] = {}
        for i, job in enumerate(jobs):
            groups.setdefault(id(job[1]), []).append(i)
        bad: dict[int, list] = {}
        for idx in groups.values():
            plan = jobs[idx[0]][1]
            Q = np.stack([jobs[i][2] for i in idx])
            V = np.stack([jobs[i][3] for i in idx])
            ok = self._close(plan, Q, V, np)
            plan.ok_counts += ok.sum(axis=0)
            self.replayed += int(ok.sum())
            if not ok.all():
                for row, c in zip(*np.nonzero(~ok)):
                    bad.setdefault(idx[int(row)], []).append(int(c))
        for i in sorted(bad):
            m, plan, _q, _v, ent = jobs[i]
            pos = dict(zip(ent[0], _row(ent).tolist()))
            for c in bad[i]:
                self._compare(m, m.data.edge(int(plan.mov[c])), plan.mkeys[c], plan.msegs[c], pos)

    def _close(self, plan, Q, V, np):
        """Which recorded transforms V (..., E, 7) are clearly within tolerance of what the publisher gives at
        joint values Q (..., E): half the tolerance in translation, a quarter of it in angle (numpy's first look;
        the rest goes through `_compare`)."""
        t, r = plan.expected(Q, np)
        dt = t - V[..., :3]
        qr = V[..., 3:]
        with np.errstate(all="ignore"):
            dt2 = (dt * dt).sum(axis=-1)
            dot = (r * qr).sum(axis=-1)
            n1 = (r * r).sum(axis=-1)
            n2 = (qr * qr).sum(axis=-1)
            return (dt2 <= self._tol2 / 4) & (dot * dot >= n1 * n2 * self._cos4)

    def _own(self, plan, np) -> None:
        """`plan` keeps the last values of its edges in arrays; whoever kept them before writes them back."""
        self._disown()
        lv = self.last_value
        plan.last_s = np.full(len(plan.mkeys), -(1 << 62), dtype=np.int64)
        plan.last_v = np.zeros((len(plan.mkeys), 7))
        plan.had = np.zeros(len(plan.mkeys), dtype=bool)
        for c, key in enumerate(plan.mkeys):
            prev = lv.get(key)
            if prev is not None:
                plan.last_s[c] = prev[0]
                plan.last_v[c] = (*prev[1], *prev[2])
                plan.had[c] = True
        self._lv_plan = plan

    def _disown(self) -> None:
        plan = self._lv_plan
        if plan is None:
            return
        self._lv_plan = None
        lv = self.last_value
        for c, (st, v, had) in enumerate(zip(plan.last_s.tolist(), plan.last_v.tolist(), plan.had.tolist())):
            if had:
                lv[plan.mkeys[c]] = (st, tuple(v[:3]), tuple(v[3:]))

    def _fold(self) -> None:
        """The counts of `_add_fast` into `matched` and `on_tf`."""
        self._run_jobs()
        self._disown()
        for plan in self._fast.values():
            if plan.seen:
                for key in plan.keys:
                    self.on_tf[key] = self.on_tf.get(key, 0) + plan.seen
                plan.seen = 0
            for c in plan.ok_counts.nonzero()[0].tolist():
                rec = self.matched.get(plan.mkeys[c])
                if rec is None:
                    rec = self.matched[plan.mkeys[c]] = [0, 0, None]
                rec[0] += int(plan.ok_counts[c])
            plan.ok_counts[:] = 0

    def _add_slow(self, m: Message) -> None:
        self.count += 1
        if m.kind == "tf":
            self.tf_messages += 1
        keys = []
        for e in m.data:
            raw = (e.parent, e.child)
            ps = self.parents.get(e.child)
            if ps is None and len(self.parents) < 100_000:  # (distinct frames of a hostile recording: bounded)
                ps = self.parents[e.child] = {}
            if ps is not None and e.parent not in ps and len(ps) < 8:
                ps[e.parent] = m
            if m.callerid and (raw in self.callers or len(self.callers) < MAX_KEYS):
                cs = self.callers.setdefault(raw, {})
                if m.callerid not in cs and len(cs) < 8:
                    cs[m.callerid] = m
            key = self.model_key(e.parent, e.child)
            if key is None:
                if m.kind == "tf":
                    self._jumps(m, raw, e.translation)
                continue
            keys.append((key, e))
            self.on_tf[key] = self.on_tf.get(key, 0) + 1
            seg = self.movable.get(key)
            if seg is not None:
                self._movable(m, e, key, seg)
            else:
                self._fixed(m, e, key)
        if m.kind == "tf_static" and keys:
            # a latched /tf_static is recorded once per publisher: the same edge in two messages that differ
            # (in the edges they carry, or in its value) comes from two publishers; a message recorded twice
            # (the same edges, the same values) does not
            shape = frozenset(k for k, _e in keys)
            for key, e in keys:
                if key in self.static_sets or len(self.static_sets) < MAX_KEYS:
                    sets = self.static_sets.setdefault(key, {})
                    sig = (shape, tuple(round(x, 6) for x in e.translation + e.rotation))
                    if sig not in sets and len(sets) < 8:
                        sets[sig] = m
        self._expire(m.time_ns)

    def _jumps(self, m: Message, raw, xyz) -> None:
        """An edge that jumps back and forth (A B A B) comes from two publishers whose values differ, as an EKF and
        a drive controller both publishing odom -> base_link: one node's values move smoothly."""
        rec = self.alternating.get(raw)
        if rec is None:
            if len(self.alternating) >= MAX_KEYS:
                return
            rec = self.alternating[raw] = [None, None, 0, 0, None]  # before last, last, count, back-and-forth, first
        older, last = rec[0], rec[1]
        rec[2] += 1
        if older is not None:
            step = _dist(xyz, last)
            if step > 0.005 and _dist(xyz, older) * 4 < step:
                rec[3] += 1
                if rec[4] is None:
                    rec[4] = m
        rec[0], rec[1] = last, xyz

    def _movable(self, m: Message, e: Edge, key, seg) -> None:
        if self._lv_plan is not None:
            self._disown()
        if m.kind == "tf_static" and key not in self.second:
            self.second[key] = (m, f"it is published on /tf_static, while robot_state_publisher publishes joint "
                                   f"{seg.name!r} ({seg.type}) on /tf")
        prev = self.last_value.get(key)
        if prev is not None and prev[0] == e.stamp_ns and key not in self.second and \
                sum(_diff(prev[1], prev[2], e)) > 10 * self.tolerance:
            self.second[key] = (m, "two different transforms carry the same stamp")
        self.last_value[key] = (e.stamp_ns, e.translation, e.rotation)
        if e.stamp_ns in self.states:
            self._compare(m, e, key, seg)
        elif len(self.pending) < MAX_PENDING:  # its JointState may be written just after it
            self.pending.append((m.time_ns, m, e, key, seg))
            self.pending_stamps[e.stamp_ns] = self.pending_stamps.get(e.stamp_ns, 0) + 1
        else:
            self._unmatched(m, key)

    def _compare(self, m: Message, e: Edge, key, seg, pos=None) -> None:
        """`pos`: the joint state the edge was matched with, when the comparison was put off (_run_jobs)."""
        if pos is None:
            if self._jobs:  # those put off first: the first and the worst mismatch stay in recording order
                self._run_jobs()
            expected = self._expected(e.stamp_ns, seg)
        else:
            expected = self._expected_at(pos, e.stamp_ns, seg)
        rec = self.matched.get(key)
        if rec is None:
            rec = self.matched[key] = [0, 0, None]
        if expected is None:  # the JointState of that stamp does not name this joint
            self._unmatched(m, key)
            return
        rec[0] += 1
        self.replayed += 1
        # within tolerance, told without sqrt or acos (almost every transform of a clean recording):
        # |t - t'|^2 <= tol^2, and the angle 2 acos(|q.q'|) <= tol, i.e. (q.q')^2 >= |q|^2 |q'|^2 cos^2(tol / 2)
        (tx, ty, tz), (a, b, c, d) = expected
        x, y, z = e.translation
        qx, qy, qz, qw = e.rotation
        dx, dy, dz = tx - x, ty - y, tz - z
        if dx * dx + dy * dy + dz * dz <= self._tol2:
            dot = a * qx + b * qy + c * qz + d * qw
            if dot * dot >= (a * a + b * b + c * c + d * d) * (qx * qx + qy * qy + qz * qz + qw * qw) * self._cos2:
                return
        diff = _diff(expected[0], expected[1], e)
        if diff[0] > self.tolerance or diff[1] > self.tolerance:
            self.replay.add(m, e, diff, 0.1)

    def _unmatched(self, m: Message, key) -> None:
        rec = self.matched.setdefault(key, [0, 0, None])
        rec[1] += 1
        if rec[2] is None:
            rec[2] = m

    def _settle(self, now: int, stamp: int) -> None:
        keep = deque()
        for item in self.pending:
            t, m, e, key, seg = item
            if e.stamp_ns == stamp:
                self._compare(m, e, key, seg)
                self._forget(stamp)
            else:
                keep.append(item)
        self.pending = keep

    def _forget(self, stamp: int) -> None:
        n = self.pending_stamps.get(stamp, 0) - 1
        if n > 0:
            self.pending_stamps[stamp] = n
        else:
            self.pending_stamps.pop(stamp, None)

    def _expire(self, now: int | None) -> None:
        while self.pending and (now is None or now - self.pending[0][0] > WAIT_NS):
            _t, m, e, key, _seg = self.pending.popleft()
            self._forget(e.stamp_ns)
            self._unmatched(m, key)

    def _positions(self, stamp: int) -> dict | None:
        pos = self.states.get(stamp)
        if isinstance(pos, tuple):
            if len(pos) == 3:  # (names, a row of a batch's positions, None), or (names, rows, which row)
                pos = self.states[stamp] = dict(zip(pos[0], _row(pos).tolist()))
            else:
                pos = self.states[stamp] = dict(zip(*pos))
        return pos

    def _expected(self, stamp: int, seg):
        pos = self._positions(stamp)
        if pos is None or seg.name not in pos and not _mimic_of(self.model, seg.name, pos):
            return None
        cache = self.predicted.get(stamp)
        if cache is None:
            cache = {t.child: (t.translation, t.rotation) for t in self.pub.transforms_for(
                {k: v for k, v in pos.items() if k in self.model.joints and math.isfinite(v)},
                (stamp // NS, stamp % NS))}
            self.predicted[stamp] = cache
            while len(self.predicted) > 64:
                self.predicted.popitem(last=False)
        return cache.get(seg.child)

    def _expected_at(self, pos: dict, stamp: int, seg):
        """`_expected` from the given joint state, not the one kept now for that stamp."""
        if seg.name not in pos and not _mimic_of(self.model, seg.name, pos):
            return None
        return {t.child: (t.translation, t.rotation) for t in self.pub.transforms_for(
            {k: v for k, v in pos.items() if k in self.model.joints and math.isfinite(v)},
            (stamp // NS, stamp % NS))}.get(seg.child)

    def _fixed(self, m: Message, e: Edge, key) -> None:
        seen = self.fixed_on.setdefault(key, {})
        seen.setdefault(m.kind, m)
        if self.profile == "ros1" and len(seen) > 1 and key not in self.second:
            seg = self.fixed[key]
            self.second[key] = (seen["tf"], f"it is on /tf_static and on /tf, while robot_state_publisher (ROS 1) "
                                            f"publishes fixed joint {seg.name!r} on one of them (use_tf_static)")
        if m.kind == "tf" and self.profile == "ros2" and key not in self.second and \
                not 0.3 * NS < e.stamp_ns - m.time_ns < 0.7 * NS:
            # (stamped half a second ahead of when it was recorded: ROS 1's robot_state_publisher with
            # use_tf_static false, in a recording converted to rosbag2)
            seg = self.fixed[key]
            self.second[key] = (m, f"it is published on /tf, while robot_state_publisher publishes fixed joint "
                                   f"{seg.name!r} on /tf_static")
        self.static_compared += 1
        t, q = self.fixed_tq[key]
        d = _diff(t, q, e)
        if (d[0] > self.static_tolerance or d[1] > self.static_tolerance) and key not in self.static_off:
            self.static_off[key] = (m, e, d)

    # --- the verdict -----------------------------------------------------------------------------------------
    def finish(self) -> None:
        self._expire(None)
        self._fold()

    def compared(self) -> int:
        return self.replayed + self.static_compared

    def issues(self, named=frozenset(), js_count: int = 0) -> list[Issue]:
        """`named`: the joints the JointStates named (robot_state_publisher should have published them)."""
        self.finish()
        out: list[Issue] = []
        joints = self.model.joints

        def loc(seg):
            return (joints[seg.name].loc,) if seg.name in joints else ()

        for raw, callers in sorted(self.callers.items()):
            if len(callers) < 2:
                continue
            key = self.model_key(*raw)
            seg = self.movable.get(key) or self.fixed.get(key) if key is not None else None
            names = sorted(callers)
            first = min(callers.values(), key=lambda m: m.time_ns)
            if seg is not None:
                out.append(Issue("B010", f"the edge {raw[0]} -> {raw[1]} (joint {seg.name!r}) has "
                                 f"{len(names)} publishers: {', '.join(names)}; robot_state_publisher publishes it "
                                 "from the model, so TF alternates between their values", first, loc(seg)))
            else:
                out.append(Issue("B010", f"the edge {raw[0]} -> {raw[1]} has {len(names)} publishers: "
                                 f"{', '.join(names)}; tf2 keeps whichever came last, so the frame jumps between "
                                 "their values (two nodes, e.g. a drive controller and an EKF, both publish it: "
                                 "let one of them)", first))
                self.second.pop(raw, None)
        for raw, (_o, _l, count, back, first) in sorted(self.alternating.items()):
            if back >= 10 and back * 10 >= count and len(self.callers.get(raw, ())) < 2:  # (callerids said it)
                out.append(Issue("B010", f"the edge {raw[0]} -> {raw[1]} jumps back and forth between two values "
                                 f"{back} times in {count} /tf messages (first {first.where()}): two nodes publish "
                                 "it (a drive controller and an EKF both publishing odom -> base_link?); tf2 keeps "
                                 "whichever came last", first))
        have = {k for k in self.second}
        for key, sets in sorted(self.static_sets.items()):
            if len(sets) > 1 and key not in have and not self._by_callers(key):
                seg = self.movable.get(key) or self.fixed[key]
                first = sorted(sets.values(), key=lambda m: (m.time_ns, m.index))[1]
                self.second[key] = (first, f"it is in {len(sets)} different /tf_static messages (a latched topic "
                                           "is recorded once per publisher; robot_state_publisher sends one "
                                           "with every fixed joint)")
        for key, (matched, unmatched, first) in sorted(self.matched.items()):
            if key in self.second or self._by_callers(key) or unmatched < 5 or unmatched * 10 <= matched + unmatched:
                continue
            if any(k != key and v[0] >= 5 and v[1] * 10 <= v[0] for k, v in self.matched.items()):
                self.second[key] = (first, f"{unmatched} of its {matched + unmatched} /tf stamps match no "
                                           "JointState, while robot_state_publisher's other edges match theirs "
                                           "(another node publishes it with stamps of its own)")
        for key, (m, why) in sorted(self.second.items()):
            seg = self.movable.get(key) or self.fixed.get(key)
            out.append(Issue("B010", f"the edge {key[0]} -> {key[1]} (joint {seg.name!r}) comes from another "
                             f"publisher as well: {why} (first {m.where()})", m, loc(seg)))
        for key, (m, edge, d) in sorted(self.static_off.items()):
            seg = self.fixed[key]
            out.append(Issue("B011", f"{m.topic} has {edge.parent} -> {edge.child} {d[0] * 1000:.1f} mm and "
                             f"{math.degrees(d[1]):.2f} deg away from fixed joint {seg.name!r} in the model "
                             f"({m.where()}): a calibration that was never written back to the URDF, or the "
                             "URDF changed after the recording", m, loc(seg)))
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
        out.extend(self._unpublished(named, js_count))
        return out

    def _by_callers(self, key) -> bool:
        return any(len(c) > 1 and self.names.get(raw) == key for raw, c in self.callers.items())

    def _unpublished(self, named, js_count: int) -> list[Issue]:
        """Joints the JointStates name that /tf never carries, while /tf was recorded: robot_state_publisher
        did not hear those joint states (another namespace, a remap)."""
        if self.tf_messages < 10 or js_count < 10:  # a few hand-written messages are no evidence of a node
            return []
        missing = sorted(s.name for k, s in self.movable.items() if s.name in named and k not in self.on_tf)
        if not missing:
            return []
        joints = self.model.joints
        carried = sum(1 for k in self.movable if k in self.on_tf)
        return [Issue("B002", f"robot_state_publisher did not publish joint{'s' if len(missing) > 1 else ''} "
                      f"{', '.join(repr(n) for n in missing[:6])}{' and more' if len(missing) > 6 else ''}: "
                      f"{'it is' if len(missing) == 1 else 'they are'} named in the joint states ({js_count} "
                      f"messages) but /tf ({self.tf_messages} messages"
                      + (f", {carried} other joint{'s' if carried != 1 else ''} of the model" if carried else "")
                      + ") never carries their transforms: the robot_state_publisher that ran does not hear this "
                      "JointState topic (another namespace, a remap) or runs another model", None,
                      tuple(joints[n].loc for n in missing if n in joints))]


class _FastPlan:
    """What `_add_fast` needs of one TF layout: its edges sorted into the model's movable and fixed joints and the
    others, and the movable joints' motion as arrays (the publisher's per-joint rule, kinematics.Segment)."""

    def __init__(self, checks: TfChecks, layout):
        import numpy as np

        self.layout = layout
        self.keys, self.others, self.fixed, mov, self.mkeys, self.msegs = [], [], [], [], [], []
        for i, raw in enumerate(layout.edges):
            key = checks.model_key(*raw)
            if key is None:
                self.others.append((i, raw))
                continue
            self.keys.append(key)
            seg = checks.movable.get(key)
            if seg is None:
                self.fixed.append((i, key))
            else:
                mov.append(i)
                self.mkeys.append(key)
                self.msegs.append(seg)
        self.mov = np.array(mov, dtype=np.intp)
        self.seen = 0
        self.usable = len(set(self.mkeys)) == len(self.mkeys)  # an edge twice in a message: edge by edge
        self.ok_counts = np.zeros(len(mov), dtype=np.int64)
        self._cols: dict = {}
        rows = []
        plain = []
        for seg in self.msegs:
            x0, y0, z0, w0 = seg.origin_q
            t0 = seg.origin_t
            ax, ay, az = seg.axis if seg.axis is not None else (0.0, 0.0, 0.0)
            r = seg.origin_r
            d = (r[0][0] * ax + r[0][1] * ay + r[0][2] * az, r[1][0] * ax + r[1][1] * ay + r[1][2] * az,
                 r[2][0] * ax + r[2][1] * ay + r[2][2] * az)
            k = (w0 * ax + y0 * az - z0 * ay, w0 * ay + z0 * ax - x0 * az, w0 * az + x0 * ay - y0 * ax,
                 -(x0 * ax + y0 * ay + z0 * az))
            prism = seg.type == "prismatic"
            rows.append((*t0, *(d if prism else (0.0, 0.0, 0.0)), x0, y0, z0, w0, *((0.0,) * 4 if prism else k),
                         1.0 if prism else 0.0))
            plain.append(seg.axis is not None)  # a zero axis: the publisher's own rule, through _compare
        a = np.array(rows, dtype=np.float64).reshape(len(rows), 15)
        self.t0, self.d, self.q0, self.k, self.prism = a[:, 0:3], a[:, 3:6], a[:, 6:10], a[:, 10:14], a[:, 14] > 0
        self.plain = np.array(plain, dtype=bool)
        self.all_plain = bool(self.plain.all())
        self.any_prism = bool(self.prism.any())

    def columns(self, names):
        """Where each movable edge's joint is in `names` (the last, as dict(zip()) keeps); None: one is missing."""
        got = self._cols.get(id(names))
        if got is not None and got[0] is names:
            return got[1]
        import numpy as np

        where = {n: i for i, n in enumerate(names)}
        idx = [where.get(seg.name, -1) for seg in self.msegs]
        cols = None if -1 in idx else np.array(idx, dtype=np.intp)
        if len(self._cols) > 64:
            self._cols.clear()
        self._cols[id(names)] = (names, cols)
        return cols

    def expected(self, q, np):
        """Translations (..., E, 3) and rotations (..., E, 4) the publisher gives these edges at joint values
        q (..., E)."""
        h = 0.5 * q
        s = np.sin(h)[..., None]
        c = np.cos(h)[..., None]
        rot = self.q0 * c + self.k * s
        if self.any_prism:
            rot = np.where(self.prism[:, None], self.q0, rot)
        t = self.t0 + self.d * q[..., None]
        return t, rot


def _row(ent):
    """The positions of a kept batch state: (names, row, None) or (names, rows, which row)."""
    return ent[1] if ent[2] is None else ent[1][ent[2]]


def _dist(a, b) -> float:
    dx, dy, dz = a[0] - b[0], a[1] - b[1], a[2] - b[2]
    d = math.sqrt(dx * dx + dy * dy + dz * dz)
    return d if math.isfinite(d) else 0.0


def _mimic_of(model, name: str, pos: dict) -> bool:
    j = model.joints.get(name)
    return j is not None and j.mimic is not None and getattr(j.mimic, "joint", None) in pos


def _diff(t, q, e: Edge) -> tuple[float, float]:
    """(translation distance in m, rotation angle in rad) between (t, q) and the recorded edge."""
    x, y, z = e.translation
    dx, dy, dz = t[0] - x, t[1] - y, t[2] - z
    dt = math.sqrt(dx * dx + dy * dy + dz * dz)  # (products: 1e200 ** 2 raises, 1e200 * 1e200 is inf)
    a, b, c, d = q
    qx, qy, qz, qw = e.rotation
    n1 = math.sqrt(a * a + b * b + c * c + d * d) or 1.0
    n2 = math.sqrt(qx * qx + qy * qy + qz * qz + qw * qw) or 1.0
    dot = abs(a * qx + b * qy + c * qz + d * qw) / (n1 * n2)
    ang = 2.0 * math.acos(min(1.0, dot))
    if not (math.isfinite(dt) and math.isfinite(ang)):
        return (math.inf, math.inf)
    return (dt, ang)
