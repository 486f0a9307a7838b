"""Recordings, streamed one message at a time (memory does not grow with the recording's length).

Binary recordings go through rosbags (ROS 1 `.bag`, a ROS 2 bag folder, a single `.db3` or `.mcap` file);
a text recording is a YAML or JSON list of messages, the form `urdfcheck publish --joint-states` reads, each
with an optional `topic` (default /joint_states): JointState fields (`name`, `position`, `velocity`,
`effort`, `stamp`), or `transforms: [{parent, child, translation, rotation, stamp}]` for /tf and /tf_static.
"""
from __future__ import annotations

import math
import os
from collections.abc import Iterator

from urdfcheck.core import safeio
from urdfcheck.core.records import TupleRecord

NS = 1_000_000_000
JOINT_STATE = "sensor_msgs/msg/JointState"
TF_MESSAGE = "tf2_msgs/msg/TFMessage"
TEXT_SUFFIXES = (".yaml", ".yml", ".json")
TEXT_LIMIT = 64 * 1024 * 1024


class RecordingError(Exception):
    """The recording cannot be read (missing, corrupt, truncated, not a recording)."""


class JointStateMsg(TupleRecord):
    names: tuple
    position: tuple
    velocity: tuple
    effort: tuple
    stamp_ns: int


class Edge(TupleRecord):
    parent: str
    child: str
    translation: tuple
    rotation: tuple  # x, y, z, w
    stamp_ns: int


class Message(TupleRecord):
    topic: str
    index: int  # 0-based, per topic
    time_ns: int  # when it was recorded (a text recording: its stamp)
    kind: str  # "joint_state", "tf" or "tf_static"
    data: object  # JointStateMsg, or a tuple of Edge
    callerid: str = ""  # ROS 1 only: the publishing node

    def where(self) -> str:
        return f"{self.topic} message {self.index + 1} (t = {self.time_ns / NS:.3f} s)"


def is_text(path: str) -> bool:
    return path.lower().endswith(TEXT_SUFFIXES)


def messages(path: str, joint_topic: str | None = None, tf_topics=("/tf", "/tf_static"), others=None,
             text: bool | None = None) -> Iterator[Message]:
    """Every JointState message of `joint_topic` (default: /joint_states, else the only JointState topic) and
    every TF message of `tf_topics`, in recording order. Raises RecordingError. `others` (a list) receives
    the JointState topics that were not read."""
    others = [] if others is None else others
    if not os.path.exists(path):
        raise RecordingError(f"no such file or folder: {path}")
    if is_text(path) if text is None else text:
        yield from _text_messages(path, joint_topic or "/joint_states", tf_topics, others)
    else:
        yield from _bag_messages(path, joint_topic, tf_topics, others)


# --- binary recordings (rosbags) ----------------------------------------------------------------------------
def _bag_messages(path, joint_topic, tf_topics, others) -> Iterator[Message]:
    try:
        from rosbags.highlevel import AnyReader
        from rosbags.typesys import Stores, get_typestore
    except ImportError:
        raise RecordingError("reading bags needs rosbags: pip install 'urdfcheck[bag]'") from None
    from pathlib import Path

    if not os.path.isdir(path):
        try:
            safeio.check_regular(path)  # a FIFO or device would block the reader
        except OSError as e:
            raise RecordingError(f"cannot read the recording: {e}") from None
    try:
        reader = AnyReader([Path(path)], default_typestore=get_typestore(Stores.ROS2_HUMBLE))
        reader.open()
    except Exception as e:  # noqa: BLE001 - rosbags raises many types for a broken file; all mean the same
        raise RecordingError(f"not a readable ROS bag: {_reason(e)}") from None
    try:
        conns = list(reader.connections)
        every = [c for c in conns if c.msgtype == JOINT_STATE]
        states = every
        if joint_topic is not None:
            states = [c for c in every if c.topic == joint_topic]
        elif len({c.topic for c in every}) > 1:
            states = [c for c in every if c.topic == "/joint_states"]
        others.extend(sorted({c.topic for c in every} - {c.topic for c in states}))
        tfs = [c for c in conns if c.msgtype == TF_MESSAGE and c.topic in tf_topics]
        wanted = states + tfs
        counters: dict[str, int] = {}
        if not wanted:
            return
        it = reader.messages(connections=wanted)
        while True:
            try:
                conn, t, raw = next(it)
                msg = reader.deserialize(raw, conn.msgtype)
            except StopIteration:
                break
            except Exception as e:  # noqa: BLE001 - a truncated chunk or undecodable message
                raise RecordingError(f"the bag is truncated or corrupt after {sum(counters.values())} messages: "
                                     f"{_reason(e)}") from None
            i = counters.get(conn.topic, 0)
            counters[conn.topic] = i + 1
            caller = getattr(conn.ext, "callerid", None) or ""
            if conn.msgtype == JOINT_STATE:
                st = msg.header.stamp
                data = JointStateMsg(tuple(msg.name), _list(msg.position), _list(msg.velocity),
                                     _list(msg.effort), int(st.sec) * NS + int(st.nanosec))
                yield Message(conn.topic, i, int(t), "joint_state", data, caller)
            else:
                edges = tuple(_edge_from_msg(ts) for ts in msg.transforms)
                kind = "tf_static" if conn.topic.endswith("tf_static") else "tf"
                yield Message(conn.topic, i, int(t), kind, edges, caller)
    finally:
        try:
            reader.close()
        except Exception:  # noqa: BLE001,S110 - closing a broken bag must not hide the finding
            pass


def _list(values) -> tuple:
    """A numpy float64 array (what rosbags gives) as a tuple of Python floats, fast."""
    tolist = getattr(values, "tolist", None)
    return tuple(tolist()) if tolist is not None else tuple(float(x) for x in values)


def _edge_from_msg(ts) -> Edge:
    tr, rot, st = ts.transform.translation, ts.transform.rotation, ts.header.stamp
    return Edge(ts.header.frame_id, ts.child_frame_id, (tr.x, tr.y, tr.z), (rot.x, rot.y, rot.z, rot.w),
                int(st.sec) * NS + int(st.nanosec))


def _reason(e: Exception) -> str:
    text = str(e).strip() or type(e).__name__
    return text if len(text) < 300 else text[:299] + "\u2026"


# --- text recordings ----------------------------------------------------------------------------------------
def _text_messages(path, joint_topic, tf_topics, others) -> Iterator[Message]:
    try:
        data = safeio.read_file(path, TEXT_LIMIT)
    except (OSError, ValueError) as e:
        raise RecordingError(f"cannot read the recording: {e}") from None
    if len(data) > TEXT_LIMIT:
        raise RecordingError(f"a text recording is limited to {TEXT_LIMIT >> 20} MiB; record a bag instead")
    text = data.decode("utf-8", "replace")
    import json

    try:
        docs = [json.loads(text)]
    except ValueError:
        from urdfcheck.core.yamlimport import yaml

        try:
            docs = [d for d in yaml.safe_load_all(text) if d is not None]
        except (yaml.YAMLError, RecursionError) as e:
            raise RecordingError(f"neither JSON nor YAML: {_reason(e)}") from None
    items = []
    for d in docs:
        if isinstance(d, dict) and isinstance(d.get("messages"), list):
            d = d["messages"]
        items.extend(d if isinstance(d, list) else [d])
    counters: dict[str, int] = {}
    for n, item in enumerate(items):
        if not isinstance(item, dict):
            raise RecordingError(f"message {n + 1} is not a mapping")
        topic = str(item.get("topic") or ("/tf" if "transforms" in item else "/joint_states"))
        if topic != joint_topic and topic not in tf_topics:
            if "transforms" not in item and topic not in others:
                others.append(topic)
            continue
        i = counters.get(topic, 0)
        counters[topic] = i + 1
        try:
            if "transforms" in item:
                edges = tuple(_edge_from_dict(t, item.get("stamp")) for t in item["transforms"] or ())
                stamp = _ns(item.get("stamp")) if item.get("stamp") is not None else \
                    (edges[0].stamp_ns if edges else 0)
                kind = "tf_static" if topic.endswith("tf_static") else "tf"
                yield Message(topic, i, stamp, kind, edges, str(item.get("callerid") or ""))
            else:
                header = item.get("header")
                st = _ns(item.get("stamp") if "stamp" in item or not isinstance(header, dict)
                         else header.get("stamp"))
                yield Message(topic, i, st, "joint_state", JointStateMsg(
                    tuple(str(x) for x in item.get("name") or ()), _floats(item.get("position")),
                    _floats(item.get("velocity")), _floats(item.get("effort")), st),
                    str(item.get("callerid") or ""))
        except (TypeError, ValueError, KeyError, OverflowError) as e:
            raise RecordingError(f"{topic} message {i + 1} cannot be read: {_reason(e)}") from None


def _floats(v) -> tuple:
    if v is None:
        return ()
    if not isinstance(v, (list, tuple)):
        raise TypeError("expected a list of numbers")
    return tuple(float("nan") if x is None or (isinstance(x, str) and x.lower() == "nan") else float(x)
                 for x in v)


def _ns(stamp) -> int:
    """Integer nanoseconds from float seconds, [sec, nanosec] or {sec, nanosec}."""
    if stamp is None:
        return 0
    if isinstance(stamp, bool):
        raise TypeError("a stamp is not a boolean")
    if isinstance(stamp, (int, float)):
        if not math.isfinite(stamp):
            raise ValueError(f"stamp {stamp!r} is not finite")
        sec = math.floor(stamp)
        return int(sec) * NS + int(round((stamp - sec) * 1e9))
    if isinstance(stamp, dict):
        return int(stamp.get("sec", stamp.get("secs", 0))) * NS + int(stamp.get("nanosec", stamp.get("nsecs", 0)))
    if isinstance(stamp, (list, tuple)) and len(stamp) == 2:
        return int(stamp[0]) * NS + int(stamp[1])
    raise TypeError(f"cannot read a stamp from {stamp!r}")


def _edge_from_dict(t, stamp) -> Edge:
    tr = tuple(float(x) for x in t.get("translation") or (0, 0, 0))
    rot = tuple(float(x) for x in t.get("rotation") or (0, 0, 0, 1))
    if len(tr) != 3 or len(rot) != 4:
        raise ValueError("translation needs 3 numbers and rotation 4 (x, y, z, w)")
    return Edge(str(t["parent"]), str(t["child"]), tr, rot, _ns(t.get("stamp", stamp)))
