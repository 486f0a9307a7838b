"""Small recordings for the tests, written with rosbags' writers: ROS 1 .bag, ROS 2 sqlite3 and MCAP.

A recording is a list of events: ("js", t, names, positions[, velocities[, stamp[, topic]]]) for /joint_states
(stamped t unless `stamp` is given), ("tf", t, [(parent, child, xyz, xyzw)], topic[, callerid[, msgtype[,
stamp]]]) for /tf or /tf_static (msgtype: tf2_msgs/msg/TFMessage unless given, e.g. ROS 1's tf/msg/tfMessage).
"""
from __future__ import annotations

from pathlib import Path

FORMATS = ("ros1", "sqlite3", "mcap")
NS = 1_000_000_000


def write(path: Path, fmt: str, events) -> Path:
    import numpy as np
    from rosbags.typesys import Stores, get_typestore

    ros1 = fmt == "ros1"
    ts = get_typestore(Stores.ROS1_NOETIC if ros1 else Stores.ROS2_HUMBLE)
    if "tf2_msgs/msg/TFMessage" not in ts.types:  # not in rosbags' Noetic store: as tf2_msgs defines it
        from rosbags.typesys import get_types_from_msg

        ts.register(get_types_from_msg("geometry_msgs/TransformStamped[] transforms", "tf2_msgs/msg/TFMessage"))
    if "tf/msg/tfMessage" not in ts.types:  # ROS 1's pre-tf2 type, the same fields
        from rosbags.typesys import get_types_from_msg

        ts.register(get_types_from_msg("geometry_msgs/TransformStamped[] transforms", "tf/msg/tfMessage"))
    T = ts.types
    JS, TFM = T["sensor_msgs/msg/JointState"], T["tf2_msgs/msg/TFMessage"]
    H, Time, TS = T["std_msgs/msg/Header"], T["builtin_interfaces/msg/Time"], T["geometry_msgs/msg/TransformStamped"]
    Tr, V3, Q = T["geometry_msgs/msg/Transform"], T["geometry_msgs/msg/Vector3"], T["geometry_msgs/msg/Quaternion"]

    def header(t, frame=""):
        sec, nsec = divmod(int(round(t * NS)), NS)
        kw = dict(stamp=Time(sec=sec, nanosec=nsec), frame_id=frame)
        return H(seq=0, **kw) if ros1 else H(**kw)

    def ser(msg, typ):
        return ts.serialize_ros1(msg, typ) if ros1 else ts.serialize_cdr(msg, typ)

    if ros1:
        from rosbags.rosbag1 import Writer

        path = path.with_suffix(".bag")
        writer = Writer(path)
    else:
        from rosbags.rosbag2 import StoragePlugin, Writer

        plugin = StoragePlugin.MCAP if fmt == "mcap" else StoragePlugin.SQLITE3
        writer = Writer(path, version=8, storage_plugin=plugin)
    conns = {}
    with writer as w:
        def conn(topic, typ, caller=None):
            key = (topic, caller)
            if key not in conns:
                kw = dict(typestore=ts)
                if ros1 and caller:
                    kw["callerid"] = caller
                if ros1 and topic == "/tf_static":
                    kw["latching"] = 1
                conns[key] = w.add_connection(topic, typ, **kw)
            return conns[key]

        for ev in events:
            if ev[0] == "js":
                _, t, names, pos, *rest = ev
                vel = rest[0] if rest else []
                stamp = rest[1] if len(rest) > 1 else t
                topic = rest[2] if len(rest) > 2 else "/joint_states"
                msg = JS(header=header(stamp), name=list(names), position=np.array(pos, dtype=float),
                         velocity=np.array(vel, dtype=float), effort=np.array([], dtype=float))
                w.write(conn(topic, JS.__msgtype__), int(round(t * NS)), ser(msg, JS.__msgtype__))
            else:
                _, t, edges, topic, *rest = ev
                caller = rest[0] if rest else None
                typ = T[rest[1]] if len(rest) > 1 and rest[1] else TFM
                stamp = rest[2] if len(rest) > 2 else t
                tfs = [TS(header=header(stamp, p), child_frame_id=c,
                          transform=Tr(translation=V3(x=xyz[0], y=xyz[1], z=xyz[2]),
                                       rotation=Q(x=q[0], y=q[1], z=q[2], w=q[3])))
                       for p, c, xyz, q in edges]
                w.write(conn(topic, typ.__msgtype__, caller), int(round(t * NS)), ser(typ(transforms=tfs),
                                                                                     typ.__msgtype__))
    return path
