"""Recordings, streamed one message at a time (memory does not grow with the recording's length).

Binary recordings are read by bag.containers through core.door (ROS 1 `.bag`, a ROS 2 bag folder or its
metadata.yaml, a single `.db3` or `.mcap` file), only JointState and TF messages decoded (bag.decode);
a text recording is a YAML or JSON list of messages, the form `urdfcheck publish --joint-states` reads, each
with an optional `topic` (default /joint_states): JointState fields (`name`, `position`, `velocity`,
`effort`, `stamp`), or `transforms: [{parent, child, translation, rotation, stamp}]` for /tf and /tf_static.
"""
from __future__ import annotations

import os
from collections.abc import Iterator

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
    start: int = 0  # when the recording's first message read was recorded: locations are offsets from it

    def where(self) -> str:
        return f"{self.topic} message {self.index + 1} (at {(self.time_ns - self.start) / NS:+.3f} s)"


class JointStateBatch:
    """Consecutive JointState messages of one topic, publisher and layout, decoded together (bag.decode.js_batch):
    `stamps` (n,) int64, `position` (n, k), `velocity` (n, kv), `effort` (n, ke) float64, `times` receive times."""

    kind = "joint_state_batch"
    __slots__ = ("topic", "index", "times", "names", "stamps", "position", "velocity", "effort", "callerid", "start",
                 "tfs", "_stamps")

    def __init__(self, topic, index, times, names, stamps, position, velocity, effort, callerid, start, tfs=()):
        self.topic, self.index, self.times, self.names = topic, index, times, names
        self.stamps, self.position, self.velocity, self.effort = stamps, position, velocity, effort
        self.callerid, self.start = callerid, start
        self.tfs = tfs  # [(j, Message)]: TF messages recorded between the batch's message j - 1 and j, in order
        self._stamps = None

    def stamp_list(self) -> list:
        if self._stamps is None:
            self._stamps = self.stamps.tolist()
        return self._stamps

    def __len__(self) -> int:
        return len(self.times)

    def message(self, j: int) -> Message:
        """The j-th message, as the message-by-message reader gives it."""
        return Message(self.topic, self.index + j, int(self.times[j]), "joint_state", JointStateMsg(
            self.names, tuple(self.position[j].tolist()), tuple(self.velocity[j].tolist()),
            tuple(self.effort[j].tolist()), int(self.stamps[j])), self.callerid, self.start)


class FastEdges:
    """The edges of one TFMessage read by layout (bag.decode.TfLayout): `stamps` (E,) and `values` (E, 7: x y z,
    qx qy qz qw) as arrays; iterating gives the Edge records the message-by-message reader gives."""

    __slots__ = ("layout", "stamps", "values")

    def __init__(self, layout, stamps, values):
        self.layout, self.stamps, self.values = layout, stamps, values

    def __len__(self) -> int:
        return len(self.layout.edges)

    def edge(self, i: int) -> Edge:
        p, c = self.layout.edges[i]
        v = self.values[i].tolist()
        return Edge(p, c, tuple(v[:3]), tuple(v[3:]), int(self.stamps[i]))

    def __iter__(self):
        for (p, c), st, v in zip(self.layout.edges, self.stamps.tolist(), self.values.tolist()):
            yield Edge(p, c, tuple(v[:3]), tuple(v[3:]), st)


class TfRun:
    """TF messages of one topic, publisher and layout among a JointStateBatch, decoded together: message i was
    recorded after the batch's message at[i] - 1; `stamps` (n, E), `values` (n, E, 7). Iterating gives
    (j, Message) as a batch's list of TF messages does."""

    __slots__ = ("topic", "callerid", "layout", "index", "at", "times", "stamps", "values", "start", "kind")

    def __init__(self, topic, callerid, layout, index, at, times, stamps, values, start):
        self.topic, self.callerid, self.layout, self.index, self.at = topic, callerid, layout, index, at
        self.times, self.stamps, self.values, self.start = times, stamps, values, start
        self.kind = "tf_static" if topic.endswith("tf_static") else "tf"

    def __len__(self) -> int:
        return len(self.at)

    def message(self, i: int) -> Message:
        return Message(self.topic, self.index + i, int(self.times[i]), self.kind,
                       FastEdges(self.layout, self.stamps[i], self.values[i]), self.callerid, self.start)

    def __iter__(self):
        for i, j in enumerate(self.at.tolist()):
            yield j, self.message(i)


MAX_BATCH = 4096  # messages decoded together: memory stays flat whatever the recording's length
BATCH_BYTES = 8 << 20  # and their bytes
TF_LAYOUT_BYTES = 1 << 16  # a TF message read by layout (its index arrays take 8 bytes a byte); larger: on its own


def is_text(path: str) -> bool:
    return path.lower().endswith(TEXT_SUFFIXES)


def messages(path: str, joint_topic: str | None = None, tf_topics=("/tf", "/tf_static"), others=None,
             text: bool | None = None, facts: dict | None = None, runner: bool = False,
             batches: bool = False) -> Iterator[Message]:
    """Every JointState message of `joint_topic` (default: /joint_states, else the only JointState topic) and
    every TF message of `tf_topics`, in recording order. Raises RecordingError. `others` (a list) receives
    the JointState topics that were not read. `batches`: runs of JointState messages of a binary recording
    come as JointStateBatch (in order with the other messages)."""
    others = [] if others is None else others
    facts = {} if facts is None else facts
    if not os.path.lexists(path):
        raise RecordingError(f"no such file or folder: {path}")
    if os.path.basename(path) != "metadata.yaml" and (is_text(path) if text is None else text):
        yield from _text_messages(path, joint_topic or "/joint_states", tf_topics, others, runner)
    else:
        yield from _bag_messages(path, joint_topic, tf_topics, others, facts, runner, batches)


# --- binary recordings -------------------------------------------------------------------------------------
def _bag_messages(path, joint_topic, tf_topics, others, facts, runner, batches=False) -> Iterator[Message]:
    from urdfcheck.bag import containers, decode
    from urdfcheck.bag.inflate import InflateError, Inflater

    try:
        parts = _parts(path, runner, facts)
        topics: dict[str, str] = {}
        for part in parts:
            got = part.topics()
            if got is None:  # not indexed: every JointState topic is read, the choice made as they come
                topics = None
                break
            topics.update(got)
    except (containers.ContainerError, OSError, ValueError) as e:
        raise RecordingError(_why(e)) from None
    chosen = _choose(topics, joint_topic, others) if topics is not None else None

    def want(topic: str, msgtype: str) -> bool:
        kind = decode.kind_of(msgtype)
        if kind == "tf":
            return topic in tf_topics
        if kind != "joint_state":
            return False
        if joint_topic is not None:
            return topic == joint_topic
        return chosen is None or topic in chosen

    inflater = Inflater()
    counters: dict[str, int] = {}
    late: set = set()
    n = start = 0
    layouts: dict[tuple, object] = {}  # (topic, callerid, cdr) -> the layout of its last JointState
    tf_layouts: dict[tuple, list] = {}  # (topic, callerid, cdr) -> the layouts of its last TF messages
    run: list = []  # the pending batch: [layout, topic, caller, first index, times, payloads, TF messages, bytes]

    hot = [None]  # (topic, callerid, cdr, layout, times, payloads, cap) of the run being gathered

    def flush():
        """The run as one batch (the TF messages recorded among its messages ride along, in order)."""
        lay, topic, caller, index, times, payloads, tfs, _size = run
        run.clear()
        hot[0] = None
        if len(payloads) == 1:
            st, names, pos, vel, eff = decode.joint_state(payloads[0], lay.cdr)
            yield Message(topic, index, times[0], "joint_state", JointStateMsg(names, pos, vel, eff, st), caller,
                          start)
            for _j, m in tfs:
                yield m
            return
        stamps, pos, vel, eff = decode.js_batch(lay, payloads)
        decode.remember_names(lay)
        yield JointStateBatch(topic, index, times, lay.names, stamps, pos, vel, eff, caller, start, tfs)

    def items():
        """The containers' messages, a Block as runs the fast path takes (a marker) or message by message."""
        for part in parts:
            for item in part.messages(want, inflater, blocks=batches):
                if type(item) is containers.Block:
                    for piece, whole in _runs(item, layouts, tf_layouts, chosen, joint_topic):
                        if whole:
                            yield None, "", 0, piece, "", False
                        else:
                            yield from piece.tuples()
                else:
                    yield item

    def fast(piece):
        """JointStateBatch(es) of a run of a Block whose every message fits its topic's layout (_runs)."""
        nonlocal n, start
        import numpy as np

        blk, js, tfi, lay, tl = piece
        a = blk.a
        topic, _typ, caller, _cdr = blk.chans[int(blk.conn[js[0]])]
        if not n:
            start = facts.get("start", int(blk.time[min(js[0], tfi[0]) if len(tfi) else js[0]]))
        n += len(js) + len(tfi)
        cap = min(MAX_BATCH, max(1, BATCH_BYTES // lay.length))
        if len(tfi):
            ttopic, _t, tcaller, _c = blk.chans[int(blk.conn[tfi[0]])]
            tf_at = np.searchsorted(js, tfi)  # how many joint states were recorded before each
        for p in range(0, len(js), cap):
            sel = js[p:p + cap]
            stamps, pos, vel, eff = decode.js_rows(lay, containers.rows(a, blk.lo[sel], lay.length))
            i = counters.get(topic, 0)
            counters[topic] = i + len(sel)
            tfs = ()
            if len(tfi):  # the TF messages after this batch's first joint state (all, for the first) and up to
                # the next batch's first (all, for the last)
                take = np.ones(len(tfi), dtype=bool)
                if p:
                    take &= tf_at > p
                if p + cap < len(js):
                    take &= tf_at <= p + cap
                mine = tfi[take]
                if len(mine):
                    ti = counters.get(ttopic, 0)
                    counters[ttopic] = ti + len(mine)
                    st, vals = tl.rows(containers.rows(a, blk.lo[mine], tl.length))
                    tfs = TfRun(ttopic, tcaller, tl, ti, tf_at[take] - p, blk.time[mine], st, vals, start)
            yield JointStateBatch(topic, i, blk.time[sel], lay.names, stamps, pos, vel, eff, caller, start, tfs)
        decode.remember_names(lay)

    try:
        for topic, msgtype, t, payload, caller, cdr in items():
            if topic is None:
                if run:
                    yield from flush()
                yield from fast(payload)
                continue
            h = hot[0]
            if h is not None and topic == h[0] and caller == h[1] and cdr == h[2] and len(h[4]) < h[6] and \
                    h[3].matches(payload) and payload[0] != 0x28:  # (0x28: perhaps zstd, below)
                # the next message of the run: what the lines below do for it, in short
                h[4].append(t)
                h[5].append(bytes(payload))
                counters[topic] += 1
                n += 1
                continue
            kind = decode.kind_of(msgtype)
            if kind == "joint_state" and chosen is None and joint_topic is None:
                late.add(topic)  # not indexed: the first JointState topic, or /joint_states once seen
                if topic != "/joint_states" and ("/joint_states" in late or len(late) > 1):
                    continue
            if payload[:4] == containers.ZSTD_MAGIC:  # rosbag2 "message" compression
                payload = inflater.inflate("zstd", bytes(payload), None, "a compressed message")
            i = counters.get(topic, 0)
            counters[topic] = i + 1
            if not n:
                start = facts.get("start", t)
            n += 1
            if batches and kind == "joint_state":
                if run and run[1] == topic and run[2] == caller and run[0].cdr == cdr and \
                        len(run[4]) < MAX_BATCH and len(run[4]) * run[0].length < BATCH_BYTES and \
                        run[0].matches(payload):
                    run[4].append(t)
                    run[5].append(bytes(payload))  # (a copy: a view would keep its whole chunk alive)
                    continue
                if run:
                    yield from flush()
                key = (topic, caller, cdr)
                lay = layouts.get(key)
                if lay is None or not lay.matches(payload):
                    lay = decode.js_layout(payload, cdr)
                    if len(layouts) > 64:
                        layouts.clear()
                    layouts[key] = lay
                run[:] = [lay, topic, caller, i, [t], [bytes(payload)], [], 0]
                cap = min(MAX_BATCH, max(1, BATCH_BYTES // lay.length))
                hot[0] = (topic, caller, cdr, lay, run[4], run[5], cap)
                continue
            if run and kind == "joint_state":
                yield from flush()
            if kind == "joint_state":
                st, names, pos, vel, eff = decode.joint_state(payload, cdr)
                yield Message(topic, i, t, "joint_state", JointStateMsg(names, pos, vel, eff, st), caller, start)
            elif batches and len(payload) <= TF_LAYOUT_BYTES:
                key = (topic, caller, cdr)
                known = tf_layouts.setdefault(key, [])
                got = None
                for lay in known:
                    got = lay.read(payload)
                    if got is not None:
                        break
                if got is None:
                    lay = decode.tf_layout(payload, cdr)
                    got = lay.read(payload)
                    known.insert(0, lay)
                    del known[4:]
                    if len(tf_layouts) > 64:
                        tf_layouts.clear()
                m = Message(topic, i, t, "tf_static" if topic.endswith("tf_static") else "tf",
                            FastEdges(lay, *got), caller, start)
            else:
                edges = tuple(Edge(p, c, tr, rot, st) for p, c, tr, rot, st in decode.tf_message(payload, cdr))
                m = Message(topic, i, t, "tf_static" if topic.endswith("tf_static") else "tf", edges, caller,
                            start)
            if kind == "joint_state":
                continue
            if not run:
                yield m
                continue
            # among a run of joint states: rides along with them (the run goes on after it)
            run[6].append((len(run[4]), m))
            run[7] += len(payload)
            if len(run[6]) >= MAX_BATCH or run[7] >= BATCH_BYTES:
                yield from flush()
        if run:
            yield from flush()
    except (containers.ContainerError, decode.DecodeError, InflateError, OSError) as e:
        if run:  # what was read before the damage is checked, as message by message
            yield from flush()
        raise RecordingError(f"the recording is truncated or corrupt after {n} messages: {_why(e)}") from None
    if chosen is None and joint_topic is None and len(late) > 1:
        keep = "/joint_states" if "/joint_states" in late else min(late)
        others.extend(sorted(late - {keep}))


MIN_RUN = 16  # messages: a shorter run of fitting messages is read message by message


def _runs(blk, layouts, tf_layouts, chosen, joint_topic):
    """The Block in order as (piece, fast) pairs: `fast` runs (of one JointState topic and publisher in one layout,
    and at most one TF topic in one layout, each message checked byte for byte against its layout) as (block, the
    JointState indices, the TF indices, layout, TF layout); everything else as a smaller Block read message by
    message (a layout that changes, other publishers, compressed messages)."""
    import numpy as np

    from urdfcheck.bag import containers, decode

    def slow():
        return [(blk, False)]

    if chosen is None and joint_topic is None:
        return slow()
    js_ids, tf_ids = [], []
    for cid, (_topic, typ, _caller, _cdr) in blk.chans.items():
        kind = decode.kind_of(typ)
        (js_ids if kind == "joint_state" else tf_ids).append(cid)
    if len(js_ids) != 1 or len(tf_ids) > 1:
        return slow()
    a, conn = blk.a, blk.conn
    length = blk.hi - blk.lo
    is_js = conn == js_ids[0]
    js = np.flatnonzero(is_js)
    tfi = np.flatnonzero(~is_js)
    if len(js) < MIN_RUN:
        return slow()
    topic, _typ, caller, cdr = blk.chans[js_ids[0]]
    key = (topic, caller, cdr)
    mv = memoryview(blk.buf)
    try:
        lay = layouts.get(key)
        first = mv[int(blk.lo[js[0]]):int(blk.hi[js[0]])]
        if lay is None or not lay.matches(first):
            lay = decode.js_layout(first, cdr)
        tl = None
        if len(tfi):
            ttopic, _t, tcaller, tcdr = blk.chans[tf_ids[0]]
            tfirst = mv[int(blk.lo[tfi[0]]):int(blk.hi[tfi[0]])]
            if len(tfirst) > TF_LAYOUT_BYTES:
                return slow()
            known = tf_layouts.get((ttopic, tcaller, tcdr)) or []
            tl = next((t for t in known if t.read(tfirst) is not None), None) or decode.tf_layout(tfirst, tcdr)
    except decode.DecodeError:
        return slow()
    zstd = np.frombuffer(containers.ZSTD_MAGIC, dtype=np.uint8)
    fits = np.zeros(len(conn), dtype=bool)
    for which, layout in ((js, lay), (tfi, tl)):
        if not len(which):
            continue
        ok = length[which] == layout.length
        got = containers.rows(a, blk.lo[which[ok]], layout.length)
        ok[ok] = decode.fits(layout, got) & ~(got[:, :4] == zstd).all(axis=1)
        fits[which] = ok
    if fits.all():
        edges = [0, len(fits)]
    else:
        edges = np.flatnonzero(np.diff(np.concatenate([[0], fits.astype(np.int8), [0]]))).tolist()
    out = []
    done = 0

    def part(i, j):
        return containers.Block(a, blk.buf, conn[i:j], blk.time[i:j], blk.lo[i:j], blk.hi[i:j], blk.chans)

    for i, j in zip(edges[0::2], edges[1::2]):
        js_run = js[(js >= i) & (js < j)]
        if j - i < MIN_RUN or len(js_run) < MIN_RUN:
            continue
        if i > done:
            out.append((part(done, i), False))
        out.append(((blk, js_run, tfi[(tfi >= i) & (tfi < j)], lay, tl), True))
        done = j
    if not out:
        return slow()
    if done < len(conn):
        out.append((part(done, len(conn)), False))
    layouts[key] = lay
    if tl is not None:
        known = tf_layouts.setdefault((ttopic, tcaller, tcdr), [])
        if tl not in known:
            known.insert(0, tl)
            del known[4:]
    return out


def _why(e: Exception) -> str:
    from urdfcheck.core import door

    if isinstance(e, door.Refused):
        return e.why
    return _reason(e)


def _choose(topics: dict, joint_topic, others) -> set:
    """The JointState topics read: the one asked for; else /joint_states, or the recording's only one."""
    from urdfcheck.bag import decode

    every = {t for t, ty in topics.items() if decode.kind_of(ty) == "joint_state"}
    if joint_topic is not None:
        states = {joint_topic} & every
    elif len(every) > 1:
        states = {"/joint_states"} & every
    else:
        states = every
    others.extend(sorted(every - states))
    return states


class _Part:
    """One storage file of a recording: its container and how its bytes come (plain, or file-compressed)."""

    def __init__(self, path: str, fmt: str, runner: bool, compressed: str = ""):
        self.path, self.fmt, self.runner, self.compressed = path, fmt, runner, compressed

    def topics(self):
        from urdfcheck.bag import containers

        if self.compressed:
            return None if self.fmt == "mcap" else self._sqlite_topics()
        if self.fmt == "ros1":
            return containers.ros1_topics(self.path, self.runner)
        if self.fmt == "mcap":
            return containers.mcap_topics(self.path, self.runner)
        return self._sqlite_topics()

    def _sqlite_topics(self):
        facts: dict = {}
        for _ in self.messages(lambda topic, typ: False, None, facts):
            pass
        return facts.get("topics", {})

    def messages(self, want, inflater, facts=None, blocks=False):
        from urdfcheck.bag import containers
        from urdfcheck.bag.inflate import Inflater
        from urdfcheck.core import door

        facts = self.facts if facts is None else facts
        inflater = inflater or Inflater()
        if self.fmt == "ros1":
            return containers.ros1_messages(self.path, want, facts, self.runner, inflater, blocks)
        if self.fmt == "mcap":
            stream = None
            if self.compressed:
                raw = door.open_stream(self.path, limit=containers.RECORDING_BYTES, runner=self.runner)
                stream = containers.InflatingStream(raw, inflater, "a compressed MCAP file")
            return containers.mcap_messages(self.path, want, facts, self.runner, inflater, stream, blocks)
        image = None
        if self.compressed:
            raw = door.read_bytes(self.path, limit=MAX_SQLITE_IMAGE, runner=self.runner)
            if len(raw) > MAX_SQLITE_IMAGE:
                raise containers.ContainerError("a compressed database larger than "
                                                f"{MAX_SQLITE_IMAGE >> 20} MiB")
            image = inflater.inflate("zstd", raw, _zstd_size(raw), "a compressed database")
        return containers.sqlite_messages(self.path, want, facts, self.runner, inflater, _deadline(), image)


MAX_SQLITE_IMAGE = 512 * 1024**2  # a file-compressed .db3 is opened in memory (never written to /tmp)


def _zstd_size(raw: bytes) -> int | None:
    try:
        try:
            from compression import zstd
        except ImportError:
            from backports import zstd
        size = zstd.get_frame_info(raw).decompressed_size
    except Exception:  # noqa: BLE001 - no size in the frame: the per-message cap applies
        return MAX_SQLITE_IMAGE
    return size if size is not None and size <= MAX_SQLITE_IMAGE else MAX_SQLITE_IMAGE


def _deadline():
    import time

    from urdfcheck.load.budget import current

    b = current()
    return time.monotonic() + (b.remaining() if b is not None else 300.0)


def _parts(path: str, runner: bool, facts: dict) -> list[_Part]:
    """The storage files of a recording: a file alone, or a rosbag2 folder (or its metadata.yaml)."""
    from urdfcheck.bag import containers
    from urdfcheck.core import door

    folder = None
    if os.path.isdir(path):
        folder = path
    elif os.path.basename(path) == "metadata.yaml":
        folder = os.path.dirname(path) or "."
        door.confine(path, runner=runner)
    if folder is not None:
        if runner:  # typed by the runner outside the checkout: its files are the runner's too
            door.runner_folder(folder)
        else:
            door.confine(folder)
    if folder is None:
        fmt = containers.sniff(path, runner)
        if fmt not in ("ros1", "mcap", "sqlite3"):
            raise containers.ContainerError("not a ROS 1 bag, MCAP or rosbag2 sqlite3 file")
        part = _Part(path, fmt, runner)
        part.facts = facts
        return [part]
    meta = os.path.join(folder, "metadata.yaml")
    names, comp = None, ""
    if os.path.lexists(meta):
        info = _metadata(meta, runner and path == meta)
        names = [str(p) for p in info.get("relative_file_paths") or []]
        comp = str(info.get("compression_mode") or "").upper()
        if comp and comp != "NONE" and str(info.get("compression_format") or "zstd").lower() != "zstd":
            raise containers.ContainerError(f"compression {info.get('compression_format')!r} is not read")
        facts["ros"] = 2
    if not names:
        names = sorted(e.name for e in os.scandir(folder)
                       if e.name.endswith((".db3", ".mcap", ".db3.zstd", ".mcap.zstd")))
    if not names:
        raise containers.ContainerError("a folder without metadata.yaml, .db3 or .mcap files")
    parts = []
    for name in names:
        if os.path.isabs(name) or ".." in name.replace("\\", "/").split("/"):
            raise containers.ContainerError(f"metadata.yaml names a file outside its folder: {name[:100]!r}")
        full = os.path.join(folder, name)
        head, _sep, rest = name.replace("\\", "/").partition("/")
        if rest and not os.path.lexists(full) and head == os.path.basename(os.path.abspath(folder)):
            # rosbag2 before metadata version 4 named each file with the bag's folder in front (its reader
            # resolves those from the parent folder): the same file inside this folder
            full = os.path.join(folder, rest)
        if not os.path.lexists(full):
            raise containers.ContainerError(f"{name[:100]!r}, named in metadata.yaml, is missing")
        compressed = "zstd" if name.endswith(".zstd") else ""
        if compressed:
            fmt = "mcap" if name.endswith(".mcap.zstd") else "sqlite3"
        else:
            fmt = containers.sniff(full, False)  # inside the folder: never the runner's own path
            if fmt not in ("ros1", "mcap", "sqlite3"):
                raise containers.ContainerError(f"{name[:100]!r} is not an MCAP or sqlite3 file")
        part = _Part(full, fmt, False, compressed)
        part.facts = facts
        parts.append(part)
    return parts


def _metadata(meta: str, runner: bool) -> dict:
    """rosbag2's metadata.yaml, through the door and the YAML guard (alias bombs, depth, size)."""
    from urdfcheck.bag import containers
    from urdfcheck.core import door
    from urdfcheck.core.yamlimport import yaml
    from urdfcheck.load.xacro import yamlguard

    text = door.read_text(meta, limit=yamlguard.MAX_BYTES, runner=runner)
    try:
        yamlguard.check_yaml_text(text, "metadata.yaml")
        doc = yaml.load(text, Loader=getattr(yaml, "CSafeLoader", yaml.SafeLoader))
    except yamlguard.YamlRefused as e:
        raise containers.ContainerError(e.message) from None
    except (yaml.YAMLError, RecursionError, ValueError):
        raise containers.ContainerError("metadata.yaml is not valid YAML") from None
    info = doc.get("rosbag2_bagfile_information") if isinstance(doc, dict) else None
    if not isinstance(info, dict):
        raise containers.ContainerError("metadata.yaml has no rosbag2_bagfile_information")
    return info


def _list(values) -> tuple:
    """A numpy float64 array as a tuple of Python floats, fast."""
    tolist = getattr(values, "tolist", None)
    return tuple(tolist()) if tolist is not None else tuple(float(x) for x in values)


def _reason(e: Exception) -> str:
    if isinstance(e, OSError) and e.filename is not None and not hasattr(e, "why"):
        # an OSError's text holds the real (absolute) path: a dangling link inside a recording folder would print
        # the runner's temp or workspace path; its own name says which file
        text = f"{e.strerror or type(e).__name__}: {os.path.basename(os.fspath(e.filename))}"
        return text if len(text) < 300 else text[:299] + "\u2026"
    text = str(e).strip() or type(e).__name__
    return text if len(text) < 300 else text[:299] + "\u2026"


# --- text recordings ----------------------------------------------------------------------------------------
def text_items(path: str, runner: bool = False):
    """The items of a YAML/JSON message list, read through the door and bounded (JSON one item at a time,
    YAML through the alias-bomb guard). Raises RecordingError."""
    from urdfcheck.core import door

    try:
        data = door.read_bytes(path, limit=TEXT_LIMIT, runner=runner)
    except door.Refused as e:
        raise RecordingError(f"cannot read the recording: {e.why}") from None
    except (OSError, ValueError) as e:
        raise RecordingError(f"cannot read the recording: {_reason(e)}") from None
    if len(data) > TEXT_LIMIT:
        raise RecordingError(f"a text recording is limited to {TEXT_LIMIT >> 20} MiB; record a bag instead")
    text = data.decode("utf-8", "replace")
    del data
    items = _json_items(text)
    return _yaml_items(text) if items is None else items


def _text_messages(path, joint_topic, tf_topics, others, runner=False) -> Iterator[Message]:
    from urdfcheck.publisher.messages import fields

    items = text_items(path, runner)
    counters: dict[str, int] = {}
    start = None
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
                start = stamp if start is None else start
                yield Message(topic, i, stamp, kind, edges, str(item.get("callerid") or ""), start)
            else:
                names, pos, vel, eff, stamp = fields(item)  # the keys as `urdfcheck publish` reads them
                st = _ns(stamp)
                start = st if start is None else start
                yield Message(topic, i, st, "joint_state", JointStateMsg(
                    tuple(str(x) for x in names or ()), _floats(pos), _floats(vel), _floats(eff), st),
                    str(item.get("callerid") or ""), start)
        except (TypeError, ValueError, KeyError, OverflowError, AttributeError) as e:
            raise RecordingError(f"{topic} message {i + 1} cannot be read: {_reason(e)}") from None


_MESSAGES_KEY = None


def _json_items(text: str):
    """The messages of a JSON recording one at a time (a list, or {"messages": [...]}), never the whole
    document as objects at once (a 60 MB file parsed whole takes 1.75 GB); None: not JSON (read as YAML)."""
    import json
    import re

    global _MESSAGES_KEY
    if _MESSAGES_KEY is None:
        _MESSAGES_KEY = re.compile(r'\s*\{\s*"messages"\s*:\s*\[')
    dec = json.JSONDecoder()
    ws = re.compile(r"\s*")
    m = _MESSAGES_KEY.match(text)
    if m is not None:
        pos = m.end()
    else:
        pos = ws.match(text).end()
        if text.startswith("{", pos):  # one message
            try:
                obj, end = dec.raw_decode(text, pos)
            except (ValueError, RecursionError):
                return None
            return iter([obj]) if not text[end:].strip() else None
        if not text.startswith("[", pos):
            return None
        pos += 1
    try:  # the first item decides JSON or YAML (a YAML flow list starts with '[' too)
        pos = ws.match(text, pos).end()
        if text.startswith("]", pos):
            return iter(())
        first, pos = dec.raw_decode(text, pos)
    except (ValueError, RecursionError):
        return None

    def rest(pos):
        yield first
        while True:
            pos = ws.match(text, pos).end()
            if text.startswith("]", pos):
                return
            if not text.startswith(",", pos):
                raise RecordingError(f"JSON: expected ',' or ']' at character {pos}")
            pos = ws.match(text, pos + 1).end()
            try:
                obj, pos = dec.raw_decode(text, pos)
            except (ValueError, RecursionError) as e:
                raise RecordingError(f"JSON: {_reason(e)}") from None
            yield obj
    return rest(pos)


def _yaml_items(text: str) -> list:
    from urdfcheck.core.yamlimport import yaml
    from urdfcheck.load.xacro import yamlguard

    try:
        yamlguard.check_yaml_text(text, "the recording")  # alias bombs, depth, 8 MiB
        loader = getattr(yaml, "CSafeLoader", yaml.SafeLoader)
        docs = [d for d in yaml.load_all(text, Loader=loader) if d is not None]
    except yamlguard.YamlRefused as e:
        raise RecordingError(f"refused: {e.message}") from None
    except (yaml.YAMLError, RecursionError, ValueError, OverflowError) as e:
        # ValueError: an integer past Python's 4300-digit conversion limit (PyYAML converts it as it composes)
        raise RecordingError(f"neither JSON nor YAML: {_reason(e)}") from None
    items = []
    for d in docs:
        if isinstance(d, dict) and isinstance(d.get("messages"), list):
            d = d["messages"]
        items.extend(d if isinstance(d, list) else [d])
    return items


def _floats(v) -> tuple:
    if v is None:
        return ()
    if not isinstance(v, (list, tuple)):
        raise TypeError("expected a list of numbers")
    return tuple(float("nan") if x is None or (isinstance(x, str) and x.lower() == "nan") else float(x)
                 for x in v)


def _ns(stamp) -> int:
    """Integer nanoseconds of a stamp: publisher.messages.to_ns, the one reading of a stamp (float seconds,
    [sec, nanosec], {sec, nanosec}; past int64 nanoseconds a ValueError)."""
    from urdfcheck.publisher.messages import to_ns

    return to_ns(stamp)


def _edge_from_dict(t, stamp) -> Edge:
    tr = tuple(float(x) for x in t.get("translation") or (0, 0, 0))
    rot = tuple(float(x) for x in t.get("rotation") or (0, 0, 0, 1))
    if len(tr) != 3 or len(rot) != 4:
        raise ValueError("translation needs 3 numbers and rotation 4 (x, y, z, w)")
    return Edge(str(t["parent"]), str(t["child"]), tr, rot, _ns(t.get("stamp", stamp)))
