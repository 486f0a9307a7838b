"""The fast JointState path (issue 39): decoded in batches with numpy, checked with numpy once steady.

The oracle is rosbags' own deserialiser for the decoder, and urdfcheck's message-by-message path (source.MAX_BATCH
= 1) for the checks: the same findings, word for word, on recordings long enough for the batch path to run.
"""
from __future__ import annotations

import math

import pytest
from bagwriter import write

pytest.importorskip("rosbags")
np = pytest.importorskip("numpy")

NAN, INF = float("nan"), float("inf")


def _rosbags_messages(path):
    from rosbags.highlevel import AnyReader
    from rosbags.typesys import Stores, get_typestore

    with AnyReader([path], default_typestore=get_typestore(Stores.ROS2_HUMBLE)) as r:
        for c, _t, raw in r.messages(connections=r.connections):
            if c.msgtype == "sensor_msgs/msg/JointState":
                yield c.topic, bytes(raw), r.deserialize(raw, c.msgtype), c.msgtype, path.suffix == ".bag"


def _same(ours, theirs):
    """Bit for bit: NaN is NaN, -0.0 is -0.0."""
    a = np.asarray(ours, dtype=np.float64)
    b = np.asarray(theirs, dtype=np.float64)
    assert a.shape == b.shape
    assert a.tobytes() == b.tobytes()


def _check_against_rosbags(path):
    from urdfcheck.bag import decode

    rows = list(_rosbags_messages(path))
    assert rows
    by_layout = {}
    for _topic, raw, msg, _typ, ros1 in rows:
        cdr = not ros1
        st, names, pos, vel, eff = decode.joint_state(raw, cdr)
        assert st == msg.header.stamp.sec * 1_000_000_000 + msg.header.stamp.nanosec
        assert list(names) == list(msg.name)
        for ours, theirs in ((pos, msg.position), (vel, msg.velocity), (eff, msg.effort)):
            _same(ours, theirs)
        lay = decode.js_layout(raw, cdr)
        assert lay.matches(raw)
        assert list(lay.names) == list(msg.name)
        by_layout.setdefault((id(lay.names), lay.length, lay.fixed, lay.words), (lay, []))[1].append((raw, msg))
    for lay, group in by_layout.values():
        members = [(raw, msg) for raw, msg in group if lay.matches(raw)]
        stamps, pos, vel, eff = decode.js_batch(lay, [raw for raw, _m in members])
        for j, (_raw, msg) in enumerate(members):
            assert stamps[j] == msg.header.stamp.sec * 1_000_000_000 + msg.header.stamp.nanosec
            _same(pos[j], msg.position)
            _same(vel[j], msg.velocity)
            _same(eff[j], msg.effort)
    return len(rows)


def test_decoder_equals_rosbags_on_real_ros1_recordings():
    from pathlib import Path

    folder = Path(__file__).parent.parent / "fixtures" / "ros1"
    bags = sorted(folder.glob("*.bag"))
    if not bags:
        pytest.skip("no ROS 1 fixtures")
    assert sum(_check_against_rosbags(b) for b in bags) > 0


EDGES = [
    ("empty", [], [], []),
    ("one", ["a"], [0.5], []),
    ("nan", ["a", "bb", "ccc"], [NAN, INF, -INF], [-0.0, 1e-308, 5e-324]),
    ("odd names", ["j\u00e9", "x" * 7, "yy"], [1.0, -2.0, 3.0], [0.1, 0.2, 0.3]),
    ("big", [f"joint_{i}" for i in range(3000)], [i * 1e-3 for i in range(3000)], []),
    ("positions only, names none", [], [1.0, 2.0], []),
    ("velocities only", ["a", "b"], [], [1.0, 2.0]),
]


@pytest.mark.parametrize("fmt", ["ros1", "mcap", "sqlite3"])
def test_decoder_equals_rosbags_on_edge_cases(fmt, tmp_path):
    events = []
    t = 1.0
    for rep in range(3):  # each layout several times, interleaved: runs, and layouts that change
        for _what, names, pos, vel in EDGES:
            t += 0.01
            events.append(("js", t, names, pos, vel, t + rep * 1e-9))
    # many messages (~4 MB): several chunks, runs across chunk boundaries
    names = [f"joint_{k}" for k in range(60)]
    for i in range(3000):
        t += 0.001
        events.append(("js", t, names, [math.sin(i + k) for k in range(59)] + [NAN if i % 97 == 0 else i * 1.5],
                       [], t))
    path = write(tmp_path / "edges", fmt, events)
    assert _check_against_rosbags(path) == len(events)


def test_decoder_reads_big_endian_cdr():
    """rosbags writes little-endian CDR only: a big-endian message built by hand, read both ways."""
    import struct

    from urdfcheck.bag import decode

    body = b""

    def put(fmt, *values, align=None):
        nonlocal body
        body += b"\0" * ((-len(body)) % (align or struct.calcsize(fmt[1:2] or "I")))
        body += struct.pack(fmt, *values)

    def text(t):
        nonlocal body
        raw = t.encode() + b"\0"
        put(">I", len(raw))
        body += raw

    put(">iI", 7, 8, align=4)
    text("base")
    put(">I", 2)
    text("a")
    text("bc")
    put(">I", 2)
    put(">2d", 1.5, NAN, align=8)
    put(">I", 0)
    put(">I", 0)
    raw = b"\x00\x00\x00\x00" + body
    st, names, pos, vel, eff = decode.joint_state(raw, True)
    lay = decode.js_layout(raw, True)
    stamps, p, v, e = decode.js_batch(lay, [raw, raw])
    assert (st, names, vel, eff) == (7 * 10**9 + 8, ("a", "bc"), (), ())
    assert list(stamps) == [st, st] and v.shape == (2, 0) and e.shape == (2, 0)
    _same(p[1], pos)
    assert pos[0] == 1.5 and math.isnan(pos[1])
    little = b"\x00\x01" + raw[2:]
    assert not lay.matches(little)


ROBOT = """<robot name="arm">
  <link name="base_link"/><link name="upper_arm"/><link name="tool"/>
  <joint name="shoulder" type="revolute"><parent link="base_link"/><child link="upper_arm"/>
    <origin xyz="0 0 0.1"/><axis xyz="0 0 1"/><limit lower="-1.5" upper="1.5" effort="1" velocity="1"/></joint>
  <joint name="elbow" type="revolute"><parent link="upper_arm"/><child link="tool"/>
    <origin xyz="0.3 0 0"/><axis xyz="0 1 0"/><limit lower="-2" upper="2" effort="1" velocity="1"/></joint>
</robot>
"""


def _events(n, defects):
    """n joint states at 100 Hz (and /tf every 10th), with `defects` {index: what} seeded."""
    events = []
    t = 1.0
    for i in range(n):
        t += 0.01
        what = defects.get(i)
        if what == "gap":
            t += 3.0
        q = [0.4 * math.sin(i / 50), 0.5 * math.cos(i / 50)]
        names = ["shoulder", "elbow"]
        stamp = t
        if what == "nan":
            q[1] = NAN
        elif what == "inf":
            q[0] = -INF
        elif what == "high":
            q[0] = 1.9
        elif what == "low":
            q[1] = -2.7
        elif what == "back":
            stamp = t - 0.7
        elif what == "repeat":
            stamp = t - 0.01
        elif what == "zero":
            stamp = 0.0
        elif what == "unknown":
            names = ["shoulder", "elbow_renamed"]
        js = ("js", t, names, q, [], stamp)
        if not all(math.isfinite(x) for x in q):
            events.append(js)
            continue
        s = ("base_link", "upper_arm", (0.0, 0.0, 0.1), (0.0, 0.0, math.sin(q[0] / 2), math.cos(q[0] / 2)))
        e = ("upper_arm", "tool", (0.3, 0.0, 0.0), (0.0, math.sin(q[1] / 2), 0.0, math.cos(q[1] / 2)))
        if what == "tf early":  # recorded before the joint state it was computed from
            events.append(("tf", t, [s, e], "/tf", None, None, stamp))
            events.append(js)
            continue
        events.append(js)
        if what == "tf off":  # the elbow 2 mm away: another URDF on the robot
            events.append(("tf", t, [s, ("upper_arm", "tool", (0.302, 0.0, 0.0), e[3])], "/tf", None, None, stamp))
        elif what == "tf twice":  # the same stamp again, another value: a second publisher
            events.append(("tf", t, [s, e], "/tf", None, None, stamp))
            events.append(("tf", t, [s, ("upper_arm", "tool", (0.3, 0.0, 0.0), (0.0, 0.0, 0.0, 1.0))], "/tf", None,
                           None, stamp))
        elif what == "tf unmatched":  # a stamp no joint state has
            events.append(("tf", t, [s, e], "/tf", None, None, stamp + 0.0033))
        elif what == "tf odom":  # an edge not of the model, in the same message
            events.append(("tf", t, [("odom", "base_link", (i * 1e-3, 0.0, 0.0), (0.0, 0.0, 0.0, 1.0)), s, e],
                           "/tf", None, None, stamp))
        elif i % 10 == 0 and what is None:
            events.append(("tf", t, [s, e], "/tf", None, None, stamp))
    return events


DEFECTS = {
    "clean": {},
    "seeded late": {4500: "nan", 4600: "nan", 4700: "inf", 5000: "high", 5100: "low", 5200: "back", 5300: "repeat",
                    5400: "zero", 5500: "gap", 5600: "unknown", 5700: "high"},
    "seeded early and late": {3: "back", 20: "zero", 4200: "nan", 4201: "back", 5999: "low"},
    "tf defects": {**{i: "tf early" for i in range(4400, 4460)}, 4500: "tf off", 4700: "tf off", 4800: "tf twice",
                   **{i: "tf unmatched" for i in range(4900, 4960, 2)}, **{i: "tf odom" for i in range(5000, 5100)},
                   5200: "nan", 5300: "high"},
}


@pytest.mark.parametrize("fmt", ["mcap", "ros1"])
@pytest.mark.parametrize("case", sorted(DEFECTS))
def test_batches_find_what_message_by_message_finds(case, fmt, tmp_path, monkeypatch):
    from urdfcheck.bag import check_recording, jointstates, source, tfcheck
    from urdfcheck.load import loader

    urdf = tmp_path / "arm.urdf"
    urdf.write_text(ROBOT)
    model = loader.load_model(str(urdf), {})
    bag = write(tmp_path / "run", fmt, _events(6000, DEFECTS[case]))
    steady = []
    real = jointstates.JointStateChecks._steady_timing

    def counted(self, T, *a):
        steady.append(len(T))
        return real(self, T, *a)

    monkeypatch.setattr(jointstates.JointStateChecks, "_steady_timing", counted)
    by_layout = []
    real_tf = tfcheck.TfChecks._add_fast

    def counted_tf(self, m, plan):
        by_layout.append(1)
        return real_tf(self, m, plan)

    monkeypatch.setattr(tfcheck.TfChecks, "_add_fast", counted_tf)
    real_batch = tfcheck.TfChecks.batch

    def counted_batch(self, b):  # a batch's /tf messages replayed at once count as by layout too
        done = real_batch(self, b)
        if done:
            by_layout.extend([1] * len(b.tfs))
        return done

    monkeypatch.setattr(tfcheck.TfChecks, "batch", counted_batch)
    fast = [(f.code, str(f.severity), f.message) for f in check_recording(model, str(bag))]
    assert sum(steady) > 1000 and len(by_layout) > 400  # the numpy paths did run
    whole = source.messages
    monkeypatch.setattr(source, "messages", lambda *a, **kw: whole(*a, **dict(kw, batches=False)))
    slow = [(f.code, str(f.severity), f.message) for f in check_recording(model, str(bag))]
    assert fast == slow
    codes = {c for c, _s, _m in fast}
    if case == "clean":
        assert fast == []
    elif case == "tf defects":
        assert codes >= {"B004", "B005", "B010", "B013"}
    else:
        assert codes >= {"B004", "B005", "B008"}


def _findings(model, bag, monkeypatch, batches: bool):
    from urdfcheck.bag import check_recording, source

    whole = source.messages
    with monkeypatch.context() as mp:
        mp.setattr(source, "messages", lambda *a, **kw: whole(*a, **dict(kw, batches=batches)))
        return [(f.code, str(f.severity), f.message) for f in check_recording(model, str(bag))]


def test_small_bounds_change_nothing(tmp_path, monkeypatch):
    """Runs cut short by the message and byte bounds (as a recording of huge JointStates cuts them) find the same."""
    from urdfcheck.bag import source
    from urdfcheck.load import loader

    urdf = tmp_path / "arm.urdf"
    urdf.write_text(ROBOT)
    model = loader.load_model(str(urdf), {})
    bag = write(tmp_path / "run", "mcap", _events(6000, {**DEFECTS["seeded late"], **DEFECTS["tf defects"]}))
    slow = _findings(model, bag, monkeypatch, False)
    monkeypatch.setattr(source, "MAX_BATCH", 7)
    monkeypatch.setattr(source, "BATCH_BYTES", 900)
    assert _findings(model, bag, monkeypatch, True) == slow
    assert {c for c, _s, _m in slow} >= {"B004", "B005", "B008", "B010", "B013"}


def test_real_ros1_recordings_find_the_same_either_way(monkeypatch):
    from pathlib import Path

    from urdfcheck.load import loader

    folder = Path(__file__).parent.parent / "fixtures" / "ros1"
    if not (folder / "robot.urdf").exists():
        pytest.skip("no ROS 1 fixtures")
    model = loader.load_model(str(folder / "robot.urdf"), {})
    seen = set()
    for bag in sorted(folder.glob("*.bag")):
        fast = _findings(model, bag, monkeypatch, True)
        assert fast == _findings(model, bag, monkeypatch, False), bag.name
        seen.update(c for c, _s, _m in fast)
    assert seen  # the fixtures carry seeded defects


def _stream(path, batches: bool) -> list:
    """Every message source.messages gives, batches taken apart, as plain tuples (bit for bit comparable)."""
    from urdfcheck.bag import source

    def plain(m):
        d = m.data
        if m.kind == "joint_state":
            data = (d.names, d.position, d.velocity, d.effort, d.stamp_ns)
        else:
            data = tuple(tuple(e) for e in d)
        return repr((m.topic, m.index, m.time_ns, m.kind, m.callerid, m.start, data))

    out = []
    for m in source.messages(str(path), batches=batches):
        if m.kind != "joint_state_batch":
            out.append(plain(m))
            continue
        tfs = list(m.tfs)
        k = 0
        for j in range(len(m)):
            while k < len(tfs) and tfs[k][0] == j:
                out.append(plain(tfs[k][1]))
                k += 1
            out.append(plain(m.message(j)))
        out.extend(plain(tm) for _j, tm in tfs[k:])
    return out


@pytest.mark.parametrize("fmt", ["mcap", "ros1"])
def test_layout_changes_inside_a_chunk(fmt, tmp_path, monkeypatch):
    """Whole chunks read at once (containers.Block, source._runs, TfChecks.batch): a joint added for one message,
    then for good, names reordered, /tf edges reordered, all inside chunks: the same messages, bit for bit, and the
    same findings as message by message."""
    from urdfcheck.bag import check_recording, source, tfcheck
    from urdfcheck.load import loader

    urdf = tmp_path / "arm.urdf"
    urdf.write_text(ROBOT)
    model = loader.load_model(str(urdf), {})
    events = []
    t = 1.0
    for i in range(4000):
        t += 0.01
        q = {"shoulder": 0.4 * math.sin(i / 50), "elbow": 0.5 * math.cos(i / 50), "wrist": 0.1}
        names = ["shoulder", "elbow"]
        if i == 1200 or 1600 <= i < 2000:
            names = ["shoulder", "elbow", "wrist"]  # a joint added (once, then for a while)
        elif 2000 <= i < 2600:
            names = ["elbow", "shoulder"]  # reordered
        events.append(("js", t, names, [q[n] for n in names]))
        s = ("base_link", "upper_arm", (0.0, 0.0, 0.1), (0.0, 0.0, math.sin(q["shoulder"] / 2),
                                                         math.cos(q["shoulder"] / 2)))
        e = ("upper_arm", "tool", (0.3, 0.0, 0.0), (0.0, math.sin(q["elbow"] / 2), 0.0, math.cos(q["elbow"] / 2)))
        if i == 3300:
            e = ("upper_arm", "tool", (0.302, 0.0, 0.0), e[3])  # another URDF on the robot, once
        if i % 10 == 0:
            events.append(("tf", t, [e, s] if 2400 <= i < 3000 else [s, e], "/tf"))
    bag = write(tmp_path / "run", fmt, events)
    pieces, batched = [], []
    runs, batch = source._runs, tfcheck.TfChecks.batch

    def counted_runs(*a):
        got = runs(*a)
        pieces.extend(fast for _p, fast in got)
        return got

    def counted_batch(self, b):
        done = batch(self, b)
        batched.append(done)
        return done

    monkeypatch.setattr(source, "_runs", counted_runs)
    monkeypatch.setattr(tfcheck.TfChecks, "batch", counted_batch)
    fast = _stream(bag, True)
    assert fast == _stream(bag, False)
    assert len(fast) == len(events)
    assert pieces.count(True) >= 3 and pieces.count(False) >= 2  # whole runs, and the changed messages alone
    found = [(f.code, str(f.severity), f.message) for f in check_recording(model, str(bag))]
    assert True in batched  # (a batch and its /tf at once, where no plan of the layout is new)
    assert found == _findings(model, bag, monkeypatch, False)
    assert {c for c, _s, _m in found} >= {"B001", "B013"}


@pytest.mark.parametrize("fmt", ["mcap", "ros1"])
def test_damaged_chunks_read_whole_find_what_message_by_message_finds(fmt, tmp_path, monkeypatch):
    """A byte changed inside a chunk (a length, a header, a name, a value): the chunk read whole (numpy) and
    record by record give the same findings, the same B014 after the same count of messages included."""
    import random

    from urdfcheck.load import loader

    urdf = tmp_path / "arm.urdf"
    urdf.write_text(ROBOT)
    model = loader.load_model(str(urdf), {})
    clean = write(tmp_path / "run", fmt, _events(3000, {}))
    if clean.is_dir():
        clean = next(clean.glob("*.mcap"))
    data = clean.read_bytes()
    rng = random.Random(39)
    codes = set()
    for k in range(16):
        at = rng.randrange(len(data) // 4, len(data) * 3 // 4)
        bad = bytearray(data)
        bad[at] ^= rng.choice((0x01, 0x10, 0x80, 0xFF))
        path = tmp_path / f"bad{k}{clean.suffix}"
        path.write_bytes(bytes(bad))
        fast = _findings(model, path, monkeypatch, True)
        assert fast == _findings(model, path, monkeypatch, False), at
        codes.update(c for c, _s, _m in fast)
    assert codes  # some changes are found
