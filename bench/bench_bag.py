"""`urdfcheck bag` on long recordings: time and peak memory against rosbags reading the same bag alone (issue 39).

    python bench/bench_bag.py [--messages 1000000] [--robots pr2,agv] [--formats mcap,ros1] [--keep DIR]

For each robot (the PR2: 45 movable joints, a /tf of 45 transforms; the AGV of examples/agv: two wheels), writes
a ROS 2 MCAP bag and a ROS 1 .bag of N JointState messages (every movable joint of the model, 100 Hz, with the
matching /tf every 10th message: N + N/10 messages in all) to a folder (`--keep DIR` writes them once and reuses
them: writing a million messages with rosbags takes minutes), then runs, as separate processes, in pairs:
  ours:  urdfcheck bag MODEL BAG --format json --no-config
  peer:  a plain rosbags loop that reads and deserialises every message (the floor any bag checker on rosbags pays)
and prints the median wall and CPU times, the median ratio of the pairs, and both peak resident sizes (ru_maxrss
of each child, from wait4). Run with N and N/10 (the default): memory must not grow with the recording's length.
Issue 39's goal: ours >= 5x as fast (a ratio <= 0.2). The PR2 model is example-robot-data's, else the corpus's
pr2_description xacro expanded once by `urdfcheck expand` (one model, not its four argument variants).
"""
from __future__ import annotations

import argparse
import math
import os
import subprocess
import sys
import tempfile
import time
from pathlib import Path

HERE = Path(__file__).resolve().parent
PEER = """
import sys
from pathlib import Path
from rosbags.highlevel import AnyReader
from rosbags.typesys import Stores, get_typestore
n = 0
with AnyReader([Path(sys.argv[1])], default_typestore=get_typestore(Stores.ROS2_HUMBLE)) as r:
    for c, t, raw in r.messages(connections=r.connections):
        r.deserialize(raw, c.msgtype)
        n += 1
print(n)
"""


CORPUS_PR2 = Path("/work/shared/corpus/PR2+pr2_common/pr2_description/robots/pr2.urdf.xacro")


def default_model(robot: str = "pr2", folder: Path | None = None) -> str:
    if robot == "agv":
        return str(HERE.parent / "examples" / "agv" / "urdf" / "agv.urdf")
    prefix = Path(sys.prefix) / "lib"
    hits = sorted(prefix.glob("python3*/site-packages/cmeel.prefix/share/example-robot-data/robots/"
                              "pr2_description/urdf/pr2.urdf"))
    if hits:
        return str(hits[0])
    if CORPUS_PR2.exists() and folder is not None:
        flat = folder / "pr2.urdf"
        if not flat.exists():
            env = dict(os.environ, PYTHONPATH=str(HERE.parent / "src"))
            out = subprocess.run([sys.executable, "-m", "urdfcheck", "expand", str(CORPUS_PR2)], capture_output=True,
                                 text=True, env=env)
            flat.write_text(out.stdout)
        return str(flat)
    sys.exit("no PR2 model: pip install example-robot-data, or pass --model")


def write_bag(model_path: str, n: int, out: Path, fmt: str = "mcap") -> Path:
    import numpy as np
    from rosbags.rosbag2 import StoragePlugin, Writer
    from rosbags.typesys import Stores, get_types_from_msg, get_typestore

    from urdfcheck.load import loader
    from urdfcheck.publisher import StatePublisher

    model = loader.load_model(model_path, {})
    pub = StatePublisher(model)
    joints = sorted(pub.tree.movable)
    limits = {}
    for name in joints:
        lim = model.joints[name].limit
        lo, hi = (lim.lower, lim.upper) if lim is not None and lim.lower is not None else (-1.0, 1.0)
        limits[name] = (lo, hi) if hi > lo else (-1.0, 1.0)
    ros1 = fmt == "ros1"
    ts = get_typestore(Stores.ROS1_NOETIC if ros1 else Stores.ROS2_HUMBLE)
    if "tf2_msgs/msg/TFMessage" not in ts.types:
        ts.register(get_types_from_msg("geometry_msgs/TransformStamped[] transforms", "tf2_msgs/msg/TFMessage"))
    T = ts.types
    JS, H, Tm = T["sensor_msgs/msg/JointState"], T["std_msgs/msg/Header"], T["builtin_interfaces/msg/Time"]
    ser = ts.serialize_ros1 if ros1 else ts.serialize_cdr
    hdr = (lambda **kw: H(seq=0, **kw)) if ros1 else H
    TFM, TS = T["tf2_msgs/msg/TFMessage"], T["geometry_msgs/msg/TransformStamped"]
    Tr, V3, Q = T["geometry_msgs/msg/Transform"], T["geometry_msgs/msg/Vector3"], T["geometry_msgs/msg/Quaternion"]
    path = out / (f"pr2_{n}.bag" if ros1 else f"pr2_{n}")
    empty = np.array([], dtype=float)
    if ros1:
        from rosbags.rosbag1 import Writer as Writer1

        writer = Writer1(path)
    else:
        writer = Writer(path, version=8, storage_plugin=StoragePlugin.MCAP)
    with writer as w:
        cj = w.add_connection("/joint_states", JS.__msgtype__, typestore=ts)
        ct = w.add_connection("/tf", TFM.__msgtype__, typestore=ts)
        for i in range(n):
            t_ns = 1_000_000_000 + i * 10_000_000
            stamp = Tm(sec=t_ns // 1_000_000_000, nanosec=t_ns % 1_000_000_000)
            pos = [lo + (hi - lo) * (0.5 + 0.4 * math.sin(i * 1e-3 + k)) for k, (lo, hi) in
                   enumerate(limits[j] for j in joints)]
            msg = JS(header=hdr(stamp=stamp, frame_id=""), name=joints, position=np.array(pos), velocity=empty,
                     effort=empty)
            w.write(cj, t_ns, ser(msg, JS.__msgtype__))
            if i % 10 == 0:
                tfs = [TS(header=hdr(stamp=stamp, frame_id=t.parent), child_frame_id=t.child,
                          transform=Tr(translation=V3(x=t.translation[0], y=t.translation[1], z=t.translation[2]),
                                       rotation=Q(x=t.rotation[0], y=t.rotation[1], z=t.rotation[2],
                                                  w=t.rotation[3])))
                       for t in pub.transforms_for(dict(zip(joints, pos)), (stamp.sec, stamp.nanosec))]
                w.write(ct, t_ns, ser(TFM(transforms=tfs), TFM.__msgtype__))
    return path


def main() -> None:
    ap = argparse.ArgumentParser()
    ap.add_argument("--messages", type=int, default=1_000_000)
    ap.add_argument("--model", default=None, help="one model instead of the robots' own")
    ap.add_argument("--robots", default="pr2,agv", help="pr2, agv or both (comma-separated)")
    ap.add_argument("--runs", type=int, default=3, help="pairs (ours, peer) per recording")
    ap.add_argument("--warm", action="store_true", help="one untimed run of each side first")
    ap.add_argument("--keep", metavar="DIR", help="write (or reuse) the bags here")
    ap.add_argument("--formats", default="mcap,ros1", help="mcap, ros1 or both (comma-separated)")
    ap.add_argument("--sizes", default=None, help="message counts, comma-separated (default: N/10,N)")
    ns = ap.parse_args()
    folder = Path(ns.keep) if ns.keep else Path(tempfile.mkdtemp(prefix="urdfcheck-bench-bag-"))
    folder.mkdir(parents=True, exist_ok=True)
    sizes = [int(x) for x in ns.sizes.split(",")] if ns.sizes else [ns.messages // 10, ns.messages]
    for robot in ns.robots.split(","):
        model = ns.model or default_model(robot, folder)
        for fmt in ns.formats.split(","):
            for n in sizes:
                run_one(model, folder, fmt, n, ns.runs, robot, ns.warm)


def run_one(model: str, folder: Path, fmt: str, n: int, runs: int, robot: str = "pr2", warm: bool = False) -> None:
    bag = folder / (f"{robot}_{n}.bag" if fmt == "ros1" else f"{robot}_{n}")
    if not bag.exists():
        t0 = time.perf_counter()
        scratch = Path(tempfile.mkdtemp(prefix="write-", dir=folder))
        write_bag(model, n, scratch, fmt).rename(bag)
        scratch.rmdir()
        print(f"wrote {n:,} JointState messages (+{n // 10:,} /tf) of the {robot} as {fmt} in "
              f"{time.perf_counter() - t0:.1f} s", flush=True)
    env = dict(os.environ, PYTHONPATH=str(HERE.parent / "src"))
    ours = [sys.executable, "-m", "urdfcheck", "bag", model, str(bag), "--format", "json", "--no-config"]
    peer = [sys.executable, "-c", PEER, str(bag)]
    sys.path.insert(0, str(HERE))
    from timing import paired, paired_line

    tail = subprocess.run(ours, capture_output=True, text=True, env=env).stdout[-400:] if warm else ""
    r = paired(ours, peer, runs, env=env, warm=False)  # A B A B: a shared machine's drift hits both sides of a pair
    total = n + n // 10
    paired_line(f"{robot} {fmt} {total:,} messages vs rosbags read+deserialise", r, 0.2)  # issue 39: >= 5x
    print(f"  {total / r['wall_a']:,.0f} msg/s against {total / r['wall_b']:,.0f} msg/s (wall); "
          f"{r['cpu_b'] / r['cpu_a']:.2f}x as fast in CPU (medians); peak memory {r['rss_a'] / 1024:.0f} MiB vs "
          f"{r['rss_b'] / 1024:.0f} MiB", flush=True)
    if tail and '"findings": []' not in tail and "findings" in tail:
        print("  (the recording is clean by construction; the run reported:", tail.strip()[-300:], ")")


if __name__ == "__main__":
    main()
