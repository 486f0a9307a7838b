"""Checks over the JointState messages of a recording, fed one message at a time.

What robot_state_publisher does with each defect (ROS 2 `robot_state_publisher.cpp`, ROS 1
`joint_state_listener.cpp`): a message whose `name` and `position` lengths differ is dropped; a name the model
does not have is ignored; a movable joint that no message names never gets its transform, so its child frame
and everything below it are missing from TF; a stamp that is not at least one publish interval after the
last one for its joints is throttled (a stamp going backwards freezes those frames until it catches up, a
repeated stamp is dropped, or with `ignore_timestamp` published again, which tf2 buffers reject as
TF_REPEATED_DATA); NaN positions become NaN transforms that break every lookup through them.
"""
from __future__ import annotations

import math

from urdfcheck.bag.source import NS, Message

DEG = 180.0 / math.pi
LIMITED = ("revolute", "prismatic")
MOVABLE = ("revolute", "continuous", "prismatic")
MAX_NAMES = 10_000  # distinct names remembered (seen, unknown): memory does not grow with a hostile recording


class Issue:
    """A problem seen in the recording: code, message, where it was first seen, model parts it concerns."""

    __slots__ = ("code", "message", "first", "related", "severity")

    def __init__(self, code: str, message: str, first: Message | None = None, related=(), severity=None):
        self.code, self.message, self.first, self.related, self.severity = code, message, first, related, severity


class _Range:
    __slots__ = ("lo", "hi", "lo_msg", "hi_msg", "ratios")

    def __init__(self):
        self.lo = math.inf
        self.hi = -math.inf
        self.lo_msg = self.hi_msg = None
        self.ratios: list[float] = []  # |d position / dt| / |velocity| samples (unit signature), bounded


class JointStateChecks:
    """Feed every JointState message with `add`; `issues()` at the end."""

    MAX_RATIOS = 512

    def __init__(self, model, tolerance: float = 1e-3, gap_factor: float = 5.0, min_gap: float = 0.5):
        self.model = model
        self.tolerance = tolerance
        self.gap_factor = gap_factor
        self.min_gap_ns = int(min_gap * NS)
        joints = model.joints
        self.movable = {n for n, j in joints.items() if j.type in MOVABLE}
        self.mimic = {n for n, j in joints.items() if j.mimic is not None}
        self.count = 0
        self.seen: set[str] = set()
        self.unknown: dict[str, Message] = {}
        self.length: list = [0, None, 0, None]  # position mismatches (count, first), velocity/effort (count, first)
        self.nonfinite: dict[str, list] = {}  # joint -> [count, first message]
        self.ranges: dict[str, _Range] = {}
        self.prev_pos: dict[str, tuple[int, float]] = {}
        self.stamps = {"zero": [0, None], "repeated": [0, None], "backwards": [0, None]}
        self.worst_back = 0
        # per publisher and joint, as robot_state_publisher throttles per joint: several drivers on one topic,
        # each with its own joints and clock, are not a stamp going backwards
        self.last_stamp: dict[tuple, int] = {}
        self.ros: int | None = None  # 1 or 2 when the recording says
        self.last_time: int | None = None
        self.periods: list[int] = []  # bounded sample of receive periods for the median
        self.median_period = 0.0  # of `periods`, recomputed as the sample grows (sorting per message is slow)
        self.gaps: list = [0, None, 0, None]  # count, first message, largest gap ns, its message
        self._plan_names = None  # the names of the last message read name by name, and its known joints
        self._plan: list = []
        self._ratios_full = False
        self._group: dict[str, tuple] = {}  # publisher -> (names, stamp) of its last message

    # --- one message ----------------------------------------------------------------------------------------
    def add(self, m: Message) -> None:
        js = m.data
        self.count += 1
        names, pos = js.names, js.position
        if len(names) != len(pos):
            self._first(self.length, 0, m)
            return  # robot_state_publisher drops the whole message
        for extra in (js.velocity, js.effort):
            if extra and len(extra) != len(names):
                self._first(self.length, 2, m)
                break
        vel = js.velocity if len(js.velocity) == len(names) else None
        stamp = js.stamp_ns
        if names is self._plan_names and (vel is None or self._ratios_full):
            self._known(m, pos, self._plan)  # the same names as before (the decoder hands the same tuple)
        else:
            self._each(m, names, pos, vel, stamp)
        self._stamp(m, stamp, names)
        self._timing(m)

    def add_batches(self, batches) -> None:
        """JointStateBatch runs of one topic, publisher and layout, in order: the same as `add` for each of their
        messages, with numpy once the steady state holds (the names of the last message, this publisher's last
        stamp known, the sample of periods full, no velocities still to sample)."""
        import numpy as np

        first = batches[0]
        names, caller = first.names, first.callerid
        k, kv, ke = first.position.shape[1], first.velocity.shape[1], first.effort.shape[1]
        at = [0]  # where each batch starts in the concatenation
        for b in batches:
            at.append(at[-1] + len(b))

        def msg(g: int) -> Message:
            i = int(np.searchsorted(at, g, side="right")) - 1
            return batches[i].message(g - at[i])

        n = at[-1]
        j = 0
        if len(names) == k and kv in (0, k) and ke in (0, k):
            while j < n:
                g = self._group.get(caller)
                if names is self._plan_names and g is not None and g[0] is names and len(self.periods) >= 4096 \
                        and (not kv or self._ratios_full):
                    break
                self.add(msg(j))
                j += 1
        else:  # names and positions of different lengths: message by message (each is a finding)
            for g in range(n):
                self.add(msg(g))
            return
        if j >= n:
            return
        cat = np.concatenate
        P = cat([b.position for b in batches])[j:]
        S = cat([b.stamps for b in batches])[j:]
        T = cat([np.asarray(b.times, dtype=np.int64) for b in batches])[j:]
        self.count += n - j
        self._steady_ranges(P, j, msg)
        self._steady_stamps(S, j, msg, names, caller)
        self._steady_timing(T, j, msg)

    def _steady_ranges(self, P, j0: int, msg) -> None:
        import numpy as np

        plan = self._plan
        if not plan:
            return
        cols = [k for k, _n, _r in plan]
        Q = P[:, cols]
        fin = np.isfinite(Q)
        if not fin.all():
            for c, (_k, name, _r) in enumerate(plan):
                bad = np.flatnonzero(~fin[:, c])
                if len(bad):
                    rec = self.nonfinite.get(name)
                    if rec is None:
                        rec = self.nonfinite[name] = [0, msg(j0 + int(bad[0]))]
                    rec[0] += len(bad)
            lo_q = np.where(fin, Q, np.inf)
            hi_q = np.where(fin, Q, -np.inf)
        else:
            lo_q = hi_q = Q
        lo_i = lo_q.argmin(axis=0)
        hi_i = hi_q.argmax(axis=0)
        r_cols = np.arange(len(cols))
        lows = lo_q[lo_i, r_cols]
        highs = hi_q[hi_i, r_cols]
        now_lo = np.array([r.lo for _k, _n, r in plan])
        now_hi = np.array([r.hi for _k, _n, r in plan])
        for c in np.flatnonzero(lows < now_lo).tolist():
            r = plan[c][2]
            r.lo, r.lo_msg = float(lows[c]), msg(j0 + int(lo_i[c]))
        for c in np.flatnonzero(highs > now_hi).tolist():
            r = plan[c][2]
            r.hi, r.hi_msg = float(highs[c]), msg(j0 + int(hi_i[c]))

    def _steady_stamps(self, S, j0: int, msg, names, caller) -> None:
        import numpy as np

        zero = S == 0
        nz = np.flatnonzero(~zero)
        if len(nz) != len(S):
            z = np.flatnonzero(zero)
            rec = self.stamps["zero"]
            rec[0] += len(z)
            if rec[1] is None:
                rec[1] = msg(j0 + int(z[0]))
        if not len(nz):
            return
        Sn = S[nz]
        prev = np.empty_like(Sn)
        prev[0] = self._group[caller][1]
        prev[1:] = Sn[:-1]
        back = np.flatnonzero(Sn < prev)
        if len(back):
            rec = self.stamps["backwards"]
            rec[0] += len(back)
            if rec[1] is None:
                rec[1] = msg(j0 + int(nz[back[0]]))
            self.worst_back = max(self.worst_back, int((prev[back] - Sn[back]).max()))
        rep = np.flatnonzero(Sn == prev)
        if len(rep):
            rec = self.stamps["repeated"]
            rec[0] += len(rep)
            if rec[1] is None:
                rec[1] = msg(j0 + int(nz[rep[0]]))
        self._group[caller] = (names, int(Sn[-1]))

    def _steady_timing(self, T, j0: int, msg) -> None:
        import numpy as np

        prev = np.empty_like(T)
        prev[0] = self.last_time
        prev[1:] = T[:-1]
        period = T - prev
        limit = max(self.gap_factor * self.median_period, self.min_gap_ns)
        gaps = np.flatnonzero((T > prev) & (period > limit))
        if len(gaps):
            self.gaps[0] += len(gaps)
            if self.gaps[1] is None:
                self.gaps[1] = msg(j0 + int(gaps[0]))
            big = int(gaps[int(period[gaps].argmax())])
            if int(period[big]) > self.gaps[2]:
                self.gaps[2], self.gaps[3] = int(period[big]), msg(j0 + big)
        self.last_time = int(T[-1])

    def _known(self, m: Message, pos, plan) -> None:
        """Ranges and non-finite values of the known joints, by their index in the message."""
        for k, name, r in plan:
            q = pos[k]
            if q - q != 0.0:  # NaN or infinite (faster than math.isfinite on the hot path)
                rec = self.nonfinite.setdefault(name, [0, m])
                rec[0] += 1
                continue
            if q < r.lo:
                r.lo, r.lo_msg = q, m
            if q > r.hi:
                r.hi, r.hi_msg = q, m

    def _each(self, m: Message, names, pos, vel, stamp) -> None:
        joints = self.model.joints
        seen, ranges = self.seen, self.ranges
        plan = []
        for k, name in enumerate(names):
            if name not in seen and len(seen) < MAX_NAMES:  # (a hostile recording names millions)
                seen.add(name)
            r = ranges.get(name)
            if r is None:
                if name not in joints:
                    if len(self.unknown) < MAX_NAMES:
                        self.unknown.setdefault(name, m)
                    continue
                r = ranges[name] = _Range()
            plan.append((k, name, r))
        self._known(m, pos, plan)
        if vel is not None:
            for k, name, r in plan:
                q = pos[k]
                if q - q == 0.0:  # (not NaN or infinite)
                    self._unit_sample(name, q, vel[k], stamp, r)
                    self.prev_pos[name] = (stamp, q)
        self._plan_names, self._plan = names, plan
        self._ratios_full = all(len(r.ratios) >= self.MAX_RATIOS for _k, _n, r in plan)

    def _first(self, rec: list, i: int, m: Message) -> None:
        rec[i] += 1
        if rec[i + 1] is None:
            rec[i + 1] = m

    def _unit_sample(self, name, q, v, stamp, r: _Range) -> None:
        prev = self.prev_pos.get(name)
        if prev is None or len(r.ratios) >= self.MAX_RATIOS or not math.isfinite(v) or abs(v) < 1e-3:
            return
        dt = (stamp - prev[0]) / NS
        if dt <= 0:
            return
        rate = abs(q - prev[1]) / dt
        if rate > 0:
            r.ratios.append(rate / abs(v))

    def _stamp(self, m: Message, st: int, names) -> None:
        if st == 0:
            self._first(self.stamps["zero"], 0, m)
            return
        caller = m.callerid
        group = self._group.get(caller)
        if group is not None and group[0] is names:  # the same joints as this publisher's last message
            prev = group[1]
            self._group[caller] = (names, st)
            if st < prev:
                self._first(self.stamps["backwards"], 0, m)
                self.worst_back = max(self.worst_back, prev - st)
            elif st == prev:
                self._first(self.stamps["repeated"], 0, m)
            return
        last = self.last_stamp
        if group is not None:  # its last message's stamp, joint by joint, before these names are compared
            for name in group[0]:
                if name in self.model.joints:
                    last[(caller, name)] = group[1]
        back = repeated = 0
        joints = self.model.joints
        for name in names:
            if name not in joints:
                continue
            key = (caller, name)
            prev = last.get(key)
            if prev is not None:
                if st == prev:
                    repeated = 1
                elif st < prev:
                    back = max(back, prev - st)
            last[key] = st
        self._group[caller] = (names, st)
        if back:
            self._first(self.stamps["backwards"], 0, m)
            self.worst_back = max(self.worst_back, back)
        elif repeated:
            self._first(self.stamps["repeated"], 0, m)

    def _timing(self, m: Message) -> None:
        t = m.time_ns
        if self.last_time is not None and t > self.last_time:
            period = t - self.last_time
            n = len(self.periods)
            if n < 4096:
                self.periods.append(period)
                if n < 64 or n % 256 == 0:
                    self.median_period = _median(self.periods)
            med = self.median_period
            if n >= 10 and period > max(self.gap_factor * med, self.min_gap_ns):
                self._first(self.gaps, 0, m)
                if period > self.gaps[2]:
                    self.gaps[2], self.gaps[3] = period, m
        self.last_time = t

    # --- the verdict ---------------------------------------------------------------------------------------
    def issues(self, on_tf=None) -> list[Issue]:
        """`on_tf(joint)`: (parent, child, times) when the recorded /tf carries that joint's edge, else None."""
        out: list[Issue] = []
        if not self.count:
            return out
        joints = self.model.joints
        if self.unknown:
            names = sorted(self.unknown)
            unseen = [n for n in sorted(self.movable) if n not in self.seen]  # never a fixed joint: not a state
            first = min(self.unknown.values(), key=lambda m: (m.time_ns, m.index))
            one = len(names) == 1
            out.append(Issue("B001", f"{_names(names)} in the joint states {'is' if one else 'are'} not "
                             f"{'a joint' if one else 'joints'} of the model, first in {first.where()} "
                             f"(robot_state_publisher ignores {'it' if one else 'them'}; renamed in firmware or a "
                             "driver's config?)" + _close(names, unseen), first))
        never = sorted(n for n in self.movable - self.seen if n not in self.mimic)
        carried = [(n, on_tf(n)) for n in never] if on_tf is not None else []
        carried = [(n, c) for n, c in carried if c]
        if carried:
            never = [n for n in never if n not in dict(carried)]
            unknown = sorted(self.unknown)
            for n, (parent, child, times) in carried:
                out.append(Issue("B002", f"movable joint {n!r} is never named in {self.count} JointState messages, "
                                 f"yet the recorded /tf carries its edge {parent} -> {child} {times} time"
                                 f"{'s' if times != 1 else ''}: the robot runs a URDF where this joint has another "
                                 "name" + (f" (the joint states name {_names(unknown)}, which this model does not "
                                           "have)" if unknown else ""), None, (joints[n].loc,)))
        if never:
            out.append(Issue("B002", f"movable joint{'s' if len(never) > 1 else ''} {_names(never)} "
                             f"{'is' if len(never) == 1 else 'are'} never named in {self.count} JointState "
                             "messages: robot_state_publisher never publishes "
                             f"{'its' if len(never) == 1 else 'their'} transform, so "
                             f"{_names(sorted({joints[n].child for n in never if joints[n].child}))} and every "
                             "frame below are missing from TF", None, tuple(joints[n].loc for n in never)))
        if self.length[0]:
            out.append(Issue("B003", f"{self.length[0]} JointState message{'s' if self.length[0] > 1 else ''} "
                             "with different numbers of names and positions, first "
                             f"{self.length[1].where()}: robot_state_publisher drops such a message whole",
                             self.length[1]))
        if self.length[2]:
            out.append(Issue("B003", f"{self.length[2]} JointState message{'s' if self.length[2] > 1 else ''} "
                             "whose velocity or effort list is neither empty nor as long as the names, first "
                             f"{self.length[3].where()}: consumers that index them by name read other "
                             "joints' values", self.length[3], severity="warning"))
        for name in sorted(self.nonfinite):
            n, m = self.nonfinite[name]
            j = joints.get(name)
            out.append(Issue("B004", f"joint {name!r} has a NaN or infinite position in {n} message"
                             f"{'s' if n > 1 else ''}, first {m.where()}: robot_state_publisher publishes a NaN "
                             "transform and every TF lookup through it fails", m, (j.loc,) if j else ()))
        for name in sorted(self.ranges):
            out.extend(self._range_issues(name, joints.get(name)))
        out.extend(self._stamp_issues())
        if self.gaps[0]:
            med = _median(self.periods)
            out.append(Issue("B009", f"{self.gaps[0]} gap{'s' if self.gaps[0] > 1 else ''} in the joint states "
                             f"longer than {self.gap_factor:g}x the usual period ({med / 1e6:.1f} ms, "
                             f"{NS / med:.1f} Hz); the largest, {self.gaps[2] / NS:.3f} s, before "
                             f"{self.gaps[3].where()}: TF goes stale meanwhile (lookups extrapolate or fail)",
                             self.gaps[1]))
        return out

    def _range_issues(self, name, j) -> list[Issue]:
        r = self.ranges[name]
        if j is None or j.type not in MOVABLE or r.lo > r.hi:  # (every value was NaN: B004 says so)
            return []
        ratio = _median(r.ratios) if len(r.ratios) >= 5 else None
        limit = j.limit
        lo = getattr(limit, "lower", None) if limit is not None else None
        hi = getattr(limit, "upper", None) if limit is not None else None
        limited = j.type in LIMITED and lo is not None and hi is not None and hi > lo
        where = r.hi_msg if r.hi_msg is not None else r.lo_msg
        if j.type == "prismatic":
            scaled = limited and _outside(r, lo, hi, self.tolerance) and _fits(r, 1e-3, lo, hi, self.tolerance)
            if scaled or (ratio is not None and 900 <= ratio <= 1100):
                return [Issue("B007", f"prismatic joint {name!r} reads {r.lo:g} .. {r.hi:g} "
                              + (f"while its limits are {lo:g} .. {hi:g} m" if limited else "")
                              + (f"{' and' if limited else ''} its positions change ~{ratio:.0f}x faster than its "
                                 "velocities say" if ratio is not None and 900 <= ratio <= 1100 else "")
                              + ": the driver reports millimetres, URDF and robot_state_publisher use metres",
                              where, (j.loc,))]
        else:
            scaled = limited and _outside(r, lo, hi, self.tolerance) and _fits(r, 1 / DEG, lo, hi, self.tolerance)
            if scaled or (ratio is not None and 50 <= ratio <= 65):
                return [Issue("B006", f"joint {name!r} reads {r.lo:g} .. {r.hi:g} "
                              + (f"while its limits are {lo:g} .. {hi:g} rad" if limited else "")
                              + (f"{' and' if limited else ''} its positions change ~{ratio:.1f}x faster than its "
                                 "velocities say (57.3x is degrees)" if ratio is not None and 50 <= ratio <= 65
                                 else "")
                              + ": the driver reports degrees, URDF and robot_state_publisher use radians",
                              where, (j.loc,))]
        if limited and _outside(r, lo, hi, self.tolerance):
            unit = "m" if j.type == "prismatic" else "rad"
            worst = r.hi_msg if r.hi - hi >= lo - r.lo else r.lo_msg
            return [Issue("B005", f"joint {name!r} goes to {r.lo:g} .. {r.hi:g} {unit}, outside its limits "
                          f"{lo:g} .. {hi:g} {unit} (tolerance {self.tolerance:g}), worst at {worst.where()}: "
                          "the model's limits or the driver's calibration are wrong", worst, (j.loc,))]
        return []

    def _stamp_issues(self) -> list[Issue]:
        out = []
        n, m = self.stamps["zero"]
        if n:
            what = ("robot_state_publisher (ROS 1) throttles by stamp: a stamp of 0 is never a publish interval "
                    "after the last, so their transforms are never published" if self.ros == 1 else
                    "robot_state_publisher stamps their transforms 0 and throttles them by that stamp, "
                    "so they are published once and then never again")
            out.append(Issue("B008", f"{n} JointState message{'s' if n > 1 else ''} stamped 0, first {m.where()}: "
                             + what, m))
        n, m = self.stamps["backwards"]
        if n:
            out.append(Issue("B008", f"the JointState stamp of the same joints from the same publisher goes "
                             f"backwards {n} time{'s' if n > 1 else ''} (by up to {self.worst_back / NS:.3f} s), "
                             f"first {m.where()}: robot_state_publisher throttles by stamp and publishes nothing "
                             "for those joints until the stamps catch up (a clock jump, or two publishers of the "
                             "same joints)", m))
        n, m = self.stamps["repeated"]
        if n:
            out.append(Issue("B008", f"{n} JointState message{'s' if n > 1 else ''} repeat the previous stamp, first "
                             f"{m.where()}: robot_state_publisher drops them (throttled), or with ignore_timestamp "
                             "publishes the same stamp again, which tf2 reports as TF_REPEATED_DATA", m,
                             severity="warning"))
        return out


def _outside(r: _Range, lo, hi, tol) -> bool:
    return r.lo < lo - tol or r.hi > hi + tol


def _fits(r: _Range, scale, lo, hi, tol) -> bool:
    """The values, scaled, lie inside the limits, and are far outside them unscaled (not a small overshoot)."""
    a, b = r.lo * scale, r.hi * scale
    span = max(hi - lo, 1e-9)
    far = max(lo - r.lo, r.hi - hi) > 2 * span or max(abs(r.lo), abs(r.hi)) > 3 * max(abs(lo), abs(hi), 1e-9)
    return far and lo - tol <= a and b <= hi + tol


def _median(xs) -> float:
    s = sorted(xs)
    n = len(s)
    if not n:
        return 0.0
    return s[n // 2] if n % 2 else 0.5 * (s[n // 2 - 1] + s[n // 2])


def _name(n: str) -> str:
    """A recorded name as a message quotes it: a name of megabytes (a hostile recording) is cut first, never
    quoted whole to be cut by the report."""
    return repr(n) if len(n) <= 200 else repr(n[:200]) + "…"


def _names(names) -> str:
    names = list(names)
    shown = ", ".join(_name(n) for n in names[:6])
    return shown + (f" and {len(names) - 6} more" if len(names) > 6 else "")


def _close(names, joints) -> str:
    from urdfcheck.core.findings import closest

    hints = []
    for n in names[:3]:
        c = closest(n, list(joints), cutoff=0.6)
        if c:
            hints.append(f"{_name(n)} -> {c!r}")
    return f" (did you mean: {', '.join(hints)}?)" if hints else ""
