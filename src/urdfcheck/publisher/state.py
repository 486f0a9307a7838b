"""robot_state_publisher, message for message.

Behaviour follows ``robot_state_publisher.cpp`` (ROS 2, default profile) and ``joint_state_listener.cpp`` +
``robot_state_publisher.cpp`` of ROS 1 Noetic (1.15):

* fixed joints (and planar ones, which kdl_parser makes fixed) are published at their origin: ROS 2 once on
  the latched ``/tf_static``; ROS 1 on ``/tf_static`` once when ``use_tf_static`` is true (the default),
  otherwise on ``/tf`` every publish interval, stamped *now + 0.5 s*;
* floating joints are skipped (nothing is published for them);
* a JointState whose ``name`` and ``position`` lengths differ is rejected (:class:`JointStateError`);
* throttling: a message is published when ``ignore_timestamp`` is set or when its header stamp is at least
  one publish interval after the *least recently published* joint it names (a joint never published counts
  as time 0). The interval is ``int(1000 / publish_frequency)`` whole milliseconds in ROS 2 and
  ``ros::Duration(1 / max(publish_frequency, 1))`` in ROS 1. The node clock going backwards (a bag restarting)
  clears the publish times. The node clock is the ``now`` argument; without it, the message stamp (as with
  ``use_sim_time`` and a bag's clock);
* mimic joints, in the order of their names: a mimic joint absent from the message gets
  ``source * multiplier + offset`` when its *direct* source is in the message or was filled before it; a
  value the message gives explicitly wins;
* only joints of the message (and filled mimic joints) that are movable are published, in name order;
  other names are ignored (ROS 1 warns about them; here they are reported in ``last_unknown`` /
  ``last_ignored``);
* ``frame_prefix`` (ROS 2) is prepended verbatim to both frame ids; ROS 1's ``tf_prefix`` goes through
  ``prefix_frame`` (a leading '/' of the prefix dropped, '/' added after it, frames starting with '/' left
  unprefixed).
"""
from __future__ import annotations

import math
from dataclasses import dataclass, replace

from urdfcheck.publisher.kinematics import KinematicTree, Note, kinematic_tree
from urdfcheck.publisher.messages import NS, JointState, Stamp, Transform, stamp_from_ns, to_ns


class JointStateError(ValueError):
    """A JointState robot_state_publisher would reject (and log) without publishing anything."""


@dataclass(frozen=True)
class Profile:
    name: str
    publish_frequency: float  # default
    use_tf_static: bool
    prefix_style: str  # "concat" (ROS 2 frame_prefix) or "tf_prefix" (ROS 1 prefix_frame)
    interval_style: str  # "milliseconds" (ROS 2) or "duration" (ROS 1)
    validate_frequency: bool  # ROS 2 refuses a frequency outside (0, 1000]
    fixed_future_ns: int  # ROS 1 publishing fixed joints on /tf: stamp = now + this

    def interval_ns(self, frequency: float) -> int:
        if self.interval_style == "milliseconds":
            return int(1000.0 / frequency) * 1_000_000
        d = 1.0 / max(frequency, 1.0)
        sec = math.floor(d)
        frac = (d - sec) * 1e9
        nsec = int(math.floor(frac + 0.5))  # boost::math::round
        return int(sec) * NS + nsec

    def prefixed(self, prefix: str, frame: str) -> str:
        if self.prefix_style == "concat":
            return prefix + frame
        if frame.startswith("/"):
            return frame[1:]
        out = prefix[1:] if prefix.startswith("/") else prefix
        if prefix:
            out += "/"
        return out + frame


ROS2 = Profile("ros2", 20.0, True, "concat", "milliseconds", True, 0)
ROS1 = Profile("ros1", 50.0, True, "tf_prefix", "duration", False, 500_000_000)
PROFILES = {"ros2": ROS2, "ros1": ROS1}


def get_profile(profile) -> Profile:
    if isinstance(profile, Profile):
        return profile
    try:
        return PROFILES[str(profile).lower()]
    except KeyError:
        raise ValueError(f"unknown profile {profile!r} (use 'ros2' or 'ros1')") from None


class StatePublisher:
    """What robot_state_publisher would publish for a model.

    ``static_transforms()`` is what goes on /tf_static at start; ``on_joint_state(msg)`` returns what one
    JointState makes it put on /tf (an empty list when throttled). See the module docstring for the rules.
    """

    def __init__(self, model, profile="ros2", frame_prefix: str = "", publish_frequency: float | None = None,
                 ignore_timestamp: bool = False, use_tf_static: bool | None = None):
        prof = get_profile(profile)
        if use_tf_static is not None:
            prof = replace(prof, use_tf_static=bool(use_tf_static))
        self.profile = prof
        freq = prof.publish_frequency if publish_frequency is None else float(publish_frequency)
        if prof.validate_frequency and not (0.0 < freq <= 1000.0):
            raise ValueError("publish_frequency must be between 0 (exclusive) and 1000")
        if not math.isfinite(freq) and not prof.validate_frequency:
            raise ValueError("publish_frequency must be finite")
        self.publish_frequency = freq
        self.publish_interval_ns = prof.interval_ns(freq)
        self.frame_prefix = frame_prefix or ""
        self.ignore_timestamp = bool(ignore_timestamp)
        self.tree: KinematicTree = kinematic_tree(model)
        self.model = model
        pf = lambda f: prof.prefixed(self.frame_prefix, f)  # noqa: E731
        self._movable = {name: seg.publisher_fn(pf(seg.parent), pf(seg.child))
                         for name, seg in self.tree.movable.items()}
        self._movable_sorted = sorted(self._movable)
        self._fixed = [(name, self.tree.fixed[name].publisher_fn(pf(self.tree.fixed[name].parent),
                                                                  pf(self.tree.fixed[name].child)))
                       for name in sorted(self.tree.fixed)]
        self._mimics = list(self.tree.mimics)
        self._joint_names = frozenset(model.joints)
        self._last_publish: dict[str, int] = {}
        self._last_callback = 0
        self._next_fixed: int | None = None
        self.last_throttled = False
        self.last_unknown: tuple[str, ...] = ()
        self.last_ignored: tuple[str, ...] = ()
        self.unknown_names: set[str] = set()
        self.time_jumps = 0

    # --- introspection ------------------------------------------------------------------------------------
    @property
    def notes(self) -> list[Note]:
        """Model features robot_state_publisher handles surprisingly (zero axis -> NaN, floating, planar...)."""
        return self.tree.notes

    @property
    def fixed_topic(self) -> str:
        return "/tf_static" if self.profile.use_tf_static else "/tf"

    def frame(self, link: str) -> str:
        return self.profile.prefixed(self.frame_prefix, link)

    # --- fixed joints -------------------------------------------------------------------------------------
    def static_transforms(self, stamp=0.0) -> list[Transform]:
        """The fixed transforms (fixed and planar joints), in joint-name order, stamped `stamp`."""
        st = stamp_from_ns(to_ns(stamp))
        return [fn(0.0, st) for _name, fn in self._fixed]

    def startup(self, now=0.0) -> dict[str, list[Transform]]:
        """What the node publishes when it starts: {topic: transforms}.

        ROS 2, and ROS 1 with use_tf_static: the fixed transforms, once, on /tf_static (ROS 1 does it from a
        one-shot timer one interval after start). ROS 1 without use_tf_static: nothing; see ``tick``.
        """
        if self.profile.use_tf_static:
            return {"/tf_static": self.static_transforms(now)}
        return {}

    def tick(self, now) -> list[Transform]:
        """ROS 1 with use_tf_static false: the fixed transforms its timer re-publishes on /tf (stamped
        now + 0.5 s) when an interval has passed since the last time; [] otherwise (and always for ROS 2)."""
        if self.profile.use_tf_static:
            return []
        now_ns = to_ns(now)
        if self._next_fixed is None:
            self._next_fixed = now_ns
        if now_ns < self._next_fixed:
            return []
        self._next_fixed = now_ns + self.publish_interval_ns
        st = stamp_from_ns(now_ns + self.profile.fixed_future_ns)
        return [fn(0.0, st) for _name, fn in self._fixed]

    # --- joint states -------------------------------------------------------------------------------------
    def on_joint_state(self, msg: JointState, now=None) -> list[Transform]:
        """Transforms robot_state_publisher would put on /tf for this message ([] when throttled).

        Raises JointStateError when name and position lengths differ. `now` is the node clock (defaults to
        the message stamp).
        """
        names = msg[0]
        positions = msg[1]
        n = len(names)
        if n != len(positions):
            if len(positions) == 0:
                raise JointStateError(
                    f"ignored a JointState message about joint(s) {names[0]!r}(,...) whose position member was "
                    f"empty ({n} names, 0 positions)")
            raise JointStateError(
                f"ignored an invalid JointState message: {n} names but {len(positions)} positions")
        stamp = msg[2]
        if stamp.__class__ is float:
            if stamp != stamp or stamp in (math.inf, -math.inf):
                raise JointStateError(f"stamp {stamp!r} is not a time")
            sec = math.floor(stamp)
            stamp_ns = int(sec) * NS + int(round((stamp - sec) * 1e9))
        else:
            stamp_ns = to_ns(stamp)
        now_ns = stamp_ns if now is None else to_ns(now)

        # check if we moved backwards in time (e.g. when playing a bag file)
        lp = self._last_publish
        if self._last_callback > now_ns:
            lp.clear()
            self.time_jumps += 1
        self._last_callback = now_ns

        # determine least recently published joint (a joint seen for the first time counts as 0)
        last_published = now_ns
        for name in names:
            t = lp.get(name)
            if t is None:
                lp[name] = t = 0
            if t < last_published:
                last_published = t
        if not (self.ignore_timestamp or stamp_ns >= last_published + self.publish_interval_ns):
            self.last_throttled = True
            self.last_unknown = self.last_ignored = ()
            return []
        self.last_throttled = False

        pos = dict(zip(names, positions))
        if len(pos) != n:  # duplicate names: std::map::emplace keeps the first
            pos = {}
            for k, v in zip(names, positions):
                pos.setdefault(k, v)
        for mname, src, mult, off in self._mimics:
            if src in pos and mname not in pos:
                pos[mname] = pos[src] * mult + off

        st = Stamp(*divmod(stamp_ns, NS))
        movable = self._movable
        out = []
        ignored = None
        for name in sorted(pos):
            fn = movable.get(name)
            if fn is None:
                if ignored is None:
                    ignored = []
                ignored.append(name)
                continue
            out.append(fn(pos[name], st))
        if ignored:
            known = self._joint_names
            self.last_unknown = tuple(x for x in ignored if x not in known)
            self.last_ignored = tuple(x for x in ignored if x in known)
            self.unknown_names.update(self.last_unknown)
        else:
            self.last_unknown = self.last_ignored = ()

        for name in names:
            lp[name] = stamp_ns
        return out

    def transforms_for(self, joints: dict, stamp=0.0) -> list[Transform]:
        """Dynamic transforms for joint values, without throttling or bookkeeping (mimic rule applied)."""
        pos = dict(joints)
        for mname, src, mult, off in self._mimics:
            if src in pos and mname not in pos:
                pos[mname] = pos[src] * mult + off
        st = stamp_from_ns(to_ns(stamp))
        return [self._movable[name](float(pos[name]), st) for name in sorted(pos) if name in self._movable]
