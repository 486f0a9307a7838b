"""The three recording containers, read through the one door (core.door) and within bounds (issue 36).

Each reader yields `(topic, msgtype, time_ns, payload, callerid, cdr)` for the messages whose topic `want(topic,
msgtype)` accepts, in the order they are stored (the order they were recorded), and fills `facts`: the ROS
version, the topics and their types, whether callerids were recorded. Payloads of other topics are skipped
without being decoded. Chunks inflate within `inflate.Inflater`'s bounds; nothing is written to disk.

- ROS 1 `.bag` (format 2.0): records of a header (fields `name=value`) and data; chunks (none, bz2, lz4) hold
  the connection and message records; a connection's header carries topic, type and callerid.
- MCAP: magic, then records `opcode u8, length u64, content`; chunks (none, zstd, lz4) hold schema, channel and
  message records. rosbag2 compresses single messages (zstd) in "message" mode: told by the zstd magic.
- rosbag2 sqlite3 (`.db3`): opened read-only and immutable, `trusted_schema` off, views, virtual tables and
  generated columns where the messages are read are refused, blobs capped, and a progress handler stops it at
  the run's deadline.

With `blocks=True` the MCAP and ROS 1 readers read an inflated chunk whole (issue 39: per-message Python was the
floor): where every record may start is found with numpy, the records actually met walking the chunk by pointer
doubling (`chain`), and the wanted messages between two other records come as one `Block` of arrays. Whatever
numpy cannot vouch for (a chunk whose walk leaves the candidates, a header of a shape not seen before, a channel
not declared yet) is read record by record, as without `blocks`, errors and all.
"""
from __future__ import annotations

import struct

from urdfcheck.bag.inflate import MAX_CHUNK, InflateError, Inflater
from urdfcheck.core import door

RECORDING_BYTES = 1 << 40  # one recording file: the run's read budget is what bounds it
MAX_HEADER = 16 * 1024**2  # a ROS 1 record header (a connection's carries the full message definition)
ZSTD_MAGIC = b"\x28\xb5\x2f\xfd"
ROS1_MAGIC = b"#ROSBAG V2.0\n"
MCAP_MAGIC = b"\x89MCAP0\r\n"
SQLITE_MAGIC = b"SQLite format 3\x00"


class ContainerError(ValueError):
    """The container is corrupt, truncated or refused; the text says why (no absolute runner path)."""


def sniff(path: str, runner: bool) -> str:
    """'ros1', 'mcap', 'sqlite3' or '' from the first bytes."""
    with door.open_stream(path, limit=RECORDING_BYTES, runner=runner) as f:
        head = f.read(16)
    if head.startswith(ROS1_MAGIC):
        return "ros1"
    if head.startswith(ROS1_MAGIC[:9]):
        raise ContainerError(f"a ROS bag of format {head[9:12].decode('ascii', 'replace')!r}: only 2.0 is read")
    if head.startswith(MCAP_MAGIC):
        return "mcap"
    if head.startswith(SQLITE_MAGIC):
        return "sqlite3"
    if head.startswith(ZSTD_MAGIC):
        return "zstd"
    return ""


def _in_time() -> None:
    """Between records: stop when the run's time budget (load.budget) is spent, even if nothing is yielded."""
    from urdfcheck.load.budget import current

    b = current()
    if b is not None and b.remaining() <= 0:
        raise ContainerError(f"the run's time budget ({b.seconds:g} s) ran out while the recording was read")


def _exact(f, n: int) -> bytes:
    data = f.read(n)
    if len(data) != n:
        raise ContainerError("the file ends in the middle of a record (truncated)")
    return data


# --- ROS 1 -------------------------------------------------------------------------------------------------
def _fields(raw: bytes) -> dict[str, bytes]:
    out, pos, end = {}, 0, len(raw)
    while pos < end:
        if pos + 4 > end:
            raise ContainerError("a record header is cut short")
        (n,) = struct.unpack_from("<I", raw, pos)
        pos += 4
        if pos + n > end:
            raise ContainerError("a record header field runs past its header")
        name, eq, value = raw[pos:pos + n].partition(b"=")
        if not eq:
            raise ContainerError("a record header field without '='")
        out[name.decode("ascii", "replace")] = value
        pos += n
    return out


def _u32(b: bytes) -> int:
    if len(b) != 4:
        raise ContainerError("a header field has the wrong size")
    return struct.unpack("<I", b)[0]


def _time(b: bytes) -> int:
    if len(b) != 8:
        raise ContainerError("a time field has the wrong size")
    sec, nsec = struct.unpack("<II", b)
    return sec * 1_000_000_000 + nsec


def _ros1_inner(buf: bytes):
    """(header fields, data) of each record in an inflated chunk; a message record's header as `_quick` reads
    it."""
    pos, end = 0, len(buf)
    mv = memoryview(buf)
    unpack_from = struct.unpack_from
    shapes: dict[int, list] = {}  # header length -> message headers seen: every byte but the time's is the same
    ticks = 0
    while pos < end:
        ticks += 1
        if not ticks & 4095:  # a chunk of millions of empty records: the run's budget holds inside it too
            _in_time()
        if pos + 4 > end:
            raise ContainerError("a chunk ends in the middle of a record")
        (hl,) = unpack_from("<I", buf, pos)
        if pos + 4 + hl + 4 > end:
            raise ContainerError("a chunk record runs past its chunk")
        header = buf[pos + 4:pos + 4 + hl]
        (dl,) = unpack_from("<I", buf, pos + 4 + hl)
        start = pos + 8 + hl
        if start + dl > end:
            raise ContainerError("a chunk record runs past its chunk")
        quick = None
        for toff, pre, post, conn in shapes.get(hl, ()):
            if header.startswith(pre) and header.endswith(post):
                sec, nsec = unpack_from("<II", header, toff)
                quick = (conn, sec * 1_000_000_000 + nsec, header)
                break
        else:
            quick = _quick(header)
            if quick is not None:
                shape = shapes.setdefault(hl, [])
                if len(shape) < 16 and len(shapes) < 64:
                    toff = quick[3]
                    shape.append((toff, header[:toff], header[toff + 8:], quick[0]))
        yield (quick if quick is not None else _fields(header)), mv[start:start + dl]
        pos = start + dl


def _quick(raw: bytes):
    """(conn, time_ns, raw) of a message record's header (fields op, conn, time, in any order, each once), else
    None: `_fields` reads it (the same answer, slower)."""
    pos, end = 0, len(raw)
    op = conn = tm = None
    unpack_from = struct.unpack_from
    while pos < end:
        if pos + 4 > end:
            return None
        (n,) = unpack_from("<I", raw, pos)
        pos += 4
        f = raw[pos:pos + n]
        pos += n
        if f[:3] == b"op=" and op is None:
            op = f[3:]
        elif f[:5] == b"conn=" and conn is None and n == 9:
            conn = f[5:]
        elif f[:5] == b"time=" and tm is None and n == 13:
            tm = f[5:]
            toff = pos - 8
        else:
            return None
    if op != b"\x02" or conn is None or tm is None or pos != end:
        return None
    sec, nsec = unpack_from("<II", tm)
    return unpack_from("<I", conn)[0], sec * 1_000_000_000 + nsec, raw, toff


def _ros1_candidates(a, shapes):
    """Where a message record of a known header length may start in a chunk, and where it would end."""
    import numpy as np

    end = len(a)
    pos = []
    for hl in shapes:
        b = hl.to_bytes(4, "little")
        p = np.flatnonzero(a[:max(end - 3, 0)] == b[0])
        for k in (1, 2, 3):
            p = p[a[p + k] == b[k]]
        pos.append(p[p + 8 + hl <= end])
    pos = np.sort(np.concatenate(pos)) if pos else np.zeros(0, dtype=np.intp)
    hl = rows(a, pos, 4).view("<u4")[:, 0].astype(np.int64) if len(pos) else np.zeros(0, dtype=np.int64)
    dl = rows(a, pos + 4 + hl, 4).view("<u4")[:, 0].astype(np.int64) if len(pos) else hl
    return pos, pos + 8 + hl + dl, hl


def _ros1_blocks(a, inner, shapes, conns, facts, single):
    """The records of one inflated ROS 1 chunk in order: runs of message records whose headers have a known shape
    (every byte but the time's the same as a message read before) as Blocks, found with numpy (`chain`); any
    other record through `single(pos)` -> (item or None, next pos), which learns new shapes."""
    import numpy as np

    end = len(a)
    pos = 0
    cand = None
    ticks = 0
    while pos < end:
        ticks += 1
        if not ticks & 1023:  # a chunk of millions of odd records: the run's budget holds inside it too
            _in_time()
        if cand is None and shapes:
            cand = _ros1_candidates(a, shapes)
            cand_hls = set(shapes)
        i = int(np.searchsorted(cand[0], pos)) if cand is not None else 0
        if cand is None or i >= len(cand[0]) or cand[0][i] != pos:
            n = len(shapes)
            got, pos = single(pos)
            if got is not None:
                yield got
            if len(shapes) != n:
                cand = None
            continue
        idx, stop = chain(cand[0], cand[1], i)
        bad = None
        if stop > end:  # the last runs past the chunk: single() says so
            bad = int(cand[0][idx[-1]])
            idx = idx[:-1]
        st, ends, hl = cand[0][idx], cand[1][idx], cand[2][idx]
        conn = np.full(len(st), -1, dtype=np.int64)
        toffs = np.zeros(len(st), dtype=np.int64)
        for h, forms in shapes.items():
            mine = np.flatnonzero(hl == h)
            if not len(mine):
                continue
            head = rows(a, st[mine] + 4, h)
            for toff, pre, post, c in forms:
                hit = (conn[mine] < 0) & (head[:, :toff] == np.frombuffer(pre, dtype=np.uint8)).all(axis=1) & \
                    (head[:, toff + 8:] == np.frombuffer(post, dtype=np.uint8)).all(axis=1)
                conn[mine[hit]] = c
                toffs[mine[hit]] = toff
        known = conn >= 0
        if len(st):
            ids = np.unique(conn[known]).tolist()
            if any(c not in conns for c in ids):
                known[:] = False  # single() says which connection is missing, in order
        # runs of known shapes as Blocks, each other record alone
        k = 0
        learnt = False
        while k < len(st):
            if not known[k]:
                ticks += 1
                if not ticks & 1023:
                    _in_time()
                forms = sum(len(f) for f in shapes.values())
                got, _stop = single(int(st[k]))
                if got is not None:
                    yield got
                k += 1
                if sum(len(f) for f in shapes.values()) != forms:  # a new shape: the rest matched again
                    learnt = True
                    break
                continue
            j = k + int(np.argmin(known[k:])) if not known[k:].all() else len(st)
            sl = slice(k, j)
            t = rows(a, st[sl] + 4 + toffs[sl], 8).view("<u4").astype(np.int64)
            times = t[:, 0] * 1_000_000_000 + t[:, 1]
            if "start" not in facts:
                facts["start"] = int(times[0])
            cs = conn[sl]
            ids = np.unique(cs).tolist()
            wanted = [c for c in ids if conns[c][3]]
            if wanted:
                keep = np.isin(cs, wanted) if len(wanted) < len(ids) else slice(None)
                chans = {c: (conns[c][0], conns[c][1], conns[c][2], False) for c in wanted}
                yield Block(a, inner, cs[keep], times[keep], (st[sl] + 8 + hl[sl])[keep], ends[sl][keep], chans)
            k = j
        if learnt:
            pos = int(ends[k - 1])
            if set(shapes) != cand_hls:
                cand = None
            continue
        if bad is not None:
            got, pos = single(bad)
            if got is not None:
                yield got
        else:
            pos = stop


def ros1_messages(path: str, want, facts: dict, runner: bool, inflater: Inflater, blocks: bool = False):
    """`blocks`: the messages of a chunk come as Blocks, found with numpy (`_ros1_blocks`)."""
    facts["ros"] = 1
    shapes: dict[int, list] = {}  # message header length -> (time offset, bytes before, bytes after, connection)
    conns: dict[int, tuple] = {}  # id -> (topic, type, callerid, wanted)
    topics = facts.setdefault("topics", {})

    def connection(fields, data) -> None:
        cid = _u32(fields.get("conn", b""))
        ch = _fields(bytes(data))
        topic = (ch.get("topic") or fields.get("topic") or b"").decode("utf-8", "replace")
        typ = (ch.get("type") or b"").decode("utf-8", "replace")
        caller = (ch.get("callerid") or b"").decode("utf-8", "replace")
        if caller:
            facts["callerids"] = True
        topics.setdefault(topic, typ)
        if cid not in conns:
            conns[cid] = (topic, typ, caller, bool(want(topic, typ)))

    def message(fields, data):
        cid = _u32(fields.get("conn", b""))
        c = conns.get(cid)
        if c is None:
            raise ContainerError(f"a message of connection {cid}, which no connection record declares")
        if "start" not in facts:  # the recording's first message, of any topic: locations count from it
            facts["start"] = _time(fields.get("time", b""))
        if c[3]:
            return (c[0], c[1], _time(fields.get("time", b"")), data, c[2], False)
        return None

    with door.open_stream(path, limit=RECORDING_BYTES, runner=runner) as f:
        _exact(f, len(ROS1_MAGIC))
        ticks = 0
        while True:
            ticks += 1
            if not ticks & 4095:
                _in_time()
            head = f.read(4)
            if not head:
                return
            if len(head) < 4:
                raise ContainerError("the file ends in the middle of a record (truncated)")
            (hl,) = struct.unpack("<I", head)
            if hl > MAX_HEADER:
                raise ContainerError(f"a record header of {hl} bytes")
            fields = _fields(_exact(f, hl))
            (dl,) = struct.unpack("<I", _exact(f, 4))
            op = fields.get("op", b"")
            if op == b"\x05":  # chunk
                if dl > MAX_CHUNK:
                    raise ContainerError(f"a chunk of {dl} bytes")
                comp = (fields.get("compression") or b"none").decode("ascii", "replace")
                try:
                    inner = inflater.inflate(comp, _exact(f, dl), _u32(fields.get("size", b"")), "a ROS 1 chunk")
                except InflateError as e:
                    raise ContainerError(str(e)) from None
                if blocks:
                    import numpy as np

                    def single(pos, inner=inner):
                        # one record, as _ros1_inner and the loop below read it
                        end = len(inner)
                        if pos + 4 > end:
                            raise ContainerError("a chunk ends in the middle of a record")
                        (hl,) = struct.unpack_from("<I", inner, pos)
                        if pos + 4 + hl + 4 > end:
                            raise ContainerError("a chunk record runs past its chunk")
                        header = inner[pos + 4:pos + 4 + hl]
                        (dl,) = struct.unpack_from("<I", inner, pos + 4 + hl)
                        start = pos + 8 + hl
                        if start + dl > end:
                            raise ContainerError("a chunk record runs past its chunk")
                        data = memoryview(inner)[start:start + dl]
                        quick = _quick(header)
                        fi = _fields(header)
                        if quick is not None:
                            forms = shapes.setdefault(hl, [])
                            toff = quick[3]
                            form = (toff, header[:toff], header[toff + 8:], quick[0])
                            if len(forms) < 16 and len(shapes) < 64 and form not in forms:
                                forms.append(form)
                        iop = fi.get("op", b"")
                        got = None
                        if iop == b"\x07":
                            connection(fi, data)
                        elif iop == b"\x02":
                            got = message(fi, data)
                        return got, start + dl

                    yield from _ros1_blocks(np.frombuffer(inner, dtype=np.uint8), inner, shapes, conns, facts,
                                            single)
                    continue
                for fi, data in _ros1_inner(inner):
                    if type(fi) is tuple:  # a message record, its header read in short (_quick)
                        c = conns.get(fi[0])
                        if c is not None and "start" in facts:
                            if c[3]:
                                yield (c[0], c[1], fi[1], data, c[2], False)
                            continue
                        fi = _fields(fi[2])
                    iop = fi.get("op", b"")
                    if iop == b"\x07":
                        connection(fi, data)
                    elif iop == b"\x02":
                        got = message(fi, data)
                        if got is not None:
                            yield got
            elif op == b"\x07":
                if dl > MAX_HEADER:
                    raise ContainerError(f"a connection record of {dl} bytes")
                connection(fields, _exact(f, dl))
            elif op == b"\x02":
                if dl > MAX_CHUNK:
                    raise ContainerError(f"a message of {dl} bytes")
                got = message(fields, _exact(f, dl))
                if got is not None:
                    yield got
            else:  # bag header (its padding), index data, chunk info: skipped, not read
                f.seek(dl, 1)


# --- many messages at once ------------------------------------------------------------------------------
class Block:
    """The wanted messages of part of one inflated chunk, as arrays (what a reader yields with `blocks=True`):
    `a` the chunk (uint8), `conn` their channel or connection ids, `time` receive times (int64), `lo`/`hi` where
    each payload starts and ends in `a`, `chans` id -> (topic, type, callerid, cdr). `tuples()` gives them as
    the message-by-message reader does."""

    __slots__ = ("a", "buf", "conn", "time", "lo", "hi", "chans")

    def __init__(self, a, buf, conn, time, lo, hi, chans):
        self.a, self.buf, self.conn, self.time, self.lo, self.hi, self.chans = a, buf, conn, time, lo, hi, chans

    def __len__(self) -> int:
        return len(self.lo)

    def tuples(self):
        mv = memoryview(self.buf)
        chans = self.chans
        for c, t, lo, hi in zip(self.conn.tolist(), self.time.tolist(), self.lo.tolist(), self.hi.tolist()):
            topic, typ, caller, cdr = chans[c]
            yield topic, typ, t, mv[lo:hi], caller, cdr


def rows(a, at, width: int):
    """The `width` bytes at each offset `at` of the uint8 array `a` as rows (n, width): one copy of each, no index
    matrix. Every row must lie inside `a`."""
    from numpy.lib.stride_tricks import sliding_window_view

    return sliding_window_view(a, width)[at]


def chain(pos, nxt, first: int = 0):
    """The records of a chunk found at once: `pos` (sorted) are where a record may start, `nxt` where the record
    starting there would end. Returns (the indices into `pos` of the records met walking from pos[first], each
    record's end the next one's start, where the walk leaves the candidates: the chunk's end, or a record no
    candidate stands for, which the caller reads itself). The walk is made by pointer doubling: log2(n) numpy
    steps, not one Python step a record."""
    import numpy as np

    n = len(pos)
    out = n
    at = np.searchsorted(pos, nxt)
    hit = at < n
    hit[hit] = pos[at[hit]] == nxt[hit]
    step = np.concatenate([np.where(hit, at, out), [out]]).astype(np.intp)
    levels = [step]
    while (1 << len(levels)) < n + 1:
        step = step[step]
        levels.append(step)
    on = np.zeros(n + 1, dtype=bool)
    on[first] = True
    got = np.array([first], dtype=np.intp)
    for step in reversed(levels):
        on[step[got]] = True
        got = np.flatnonzero(on)
    got = got[:-1] if on[out] else got
    return got, int(nxt[got[-1]])


# --- MCAP --------------------------------------------------------------------------------------------------
class _Buf:
    __slots__ = ("b", "p")

    def __init__(self, b, p=0):
        self.b, self.p = b, p

    def take(self, n: int):
        if n < 0 or self.p + n > len(self.b):
            raise ContainerError("an MCAP record is shorter than its fields")
        v = self.b[self.p:self.p + n]
        self.p += n
        return v

    def u16(self) -> int:
        return struct.unpack("<H", self.take(2))[0]

    def u32(self) -> int:
        return struct.unpack("<I", self.take(4))[0]

    def u64(self) -> int:
        return struct.unpack("<Q", self.take(8))[0]

    def string(self) -> str:
        return bytes(self.take(self.u32())).decode("utf-8", "replace")


def _mcap_inner(buf):
    pos, end = 0, len(buf)
    while pos < end:
        if pos + 9 > end:
            raise ContainerError("an MCAP chunk ends in the middle of a record")
        op = buf[pos]
        (n,) = struct.unpack_from("<Q", buf, pos + 1)
        if pos + 9 + n > end:
            raise ContainerError("an MCAP chunk record runs past its chunk")
        yield op, memoryview(buf)[pos + 9:pos + 9 + n]
        pos += 9 + n


def _mcap_starts(a):
    """Where each record of an inflated MCAP chunk starts and ends (int64 arrays), found with numpy (`chain`);
    None: the chunk is walked record by record. A record starts with its opcode (in a chunk: 3, 4 or 5) and its
    length (u64)."""
    import numpy as np

    end = len(a)
    if end < 9:
        return None
    head = a[:end - 8]
    pos = np.flatnonzero(np.subtract(head, 3, dtype=np.uint8) < 3)  # opcodes 3, 4, 5 (uint8 wraps below 3)
    # (a record inside a chunk of at most MAX_CHUNK bytes: the length's high bytes are zero, which few other
    # bytes of 3 to 5 are followed by)
    for k in (8, 7, 6, 5):
        pos = pos[a[pos + k] == 0]
    if not len(pos) or pos[0] != 0:
        return None
    size = rows(a, pos + 1, 8).view("<u8")[:, 0]
    nxt = pos + 9 + np.minimum(size, end).astype(np.int64)
    got, stop = chain(pos, nxt)
    if stop != end:
        return None
    return pos[got], nxt[got]


def mcap_messages(path: str, want, facts: dict, runner: bool, inflater: Inflater, stream=None,
                  blocks: bool = False):
    """`blocks`: the messages of a chunk come as Block (several per chunk, between its schema and channel
    records), the chunk's records found with numpy."""
    unpack_from = struct.unpack_from
    schemas: dict[int, str] = {}
    channels: dict[int, tuple] = {}  # id -> (topic, type, wanted, cdr)
    topics = facts.setdefault("topics", {})

    def record(op, body):
        if op == 0x03:  # schema
            b = _Buf(body)
            sid = b.u16()
            schemas[sid] = b.string()
            enc = b.string()
            if enc == "ros1msg":
                facts.setdefault("ros", 1)
            elif enc in ("ros2msg", "ros2idl"):
                facts.setdefault("ros", 2)
        elif op == 0x04:  # channel
            b = _Buf(body)
            cid, sid = b.u16(), b.u16()
            topic, enc = b.string(), b.string()
            typ = schemas.get(sid, "")
            topics.setdefault(topic, typ)
            if cid not in channels:
                channels[cid] = (topic, typ, bool(want(topic, typ)), enc != "ros1")
        elif op == 0x05:  # message
            if len(body) < 22:
                raise ContainerError("an MCAP message record is too short")
            (cid,) = struct.unpack_from("<H", body, 0)
            c = channels.get(cid)
            if c is None:
                raise ContainerError(f"a message on channel {cid}, which no channel record declares")
            if "start" not in facts:  # the recording's first message, of any topic: locations count from it
                facts["start"] = struct.unpack_from("<Q", body, 6)[0]
            if c[2]:
                (t,) = struct.unpack_from("<Q", body, 6)
                return (c[0], c[1], t, body[22:], "", c[3])
        return None

    with (stream if stream is not None else door.open_stream(path, limit=RECORDING_BYTES, runner=runner)) as f:
        if _exact(f, 8) != MCAP_MAGIC:
            raise ContainerError("not an MCAP file")
        ticks = 0
        while True:
            head = f.read(9)
            if not head:
                raise ContainerError("the file ends before its footer (truncated)")
            if len(head) < 9:
                raise ContainerError("the file ends in the middle of a record (truncated)")
            op = head[0]
            (n,) = struct.unpack_from("<Q", head, 1)
            ticks += 1
            if not ticks & 4095:
                _in_time()
            if op == 0x00 or op == 0xFF:  # reserved opcodes: not MCAP (a file of zeros)
                raise ContainerError(f"an MCAP record with the invalid opcode {op:#04x}")
            if ticks == 1 and op != 0x01:  # the specification's first record; garbage after the magic is not one
                raise ContainerError("an MCAP file whose first record is not its header")
            if op == 0x02:  # footer: the end, when the closing magic follows it (else the footer is garbage)
                if n != 20:
                    raise ContainerError("an MCAP footer of the wrong length")
                _skip(f, n)
                if f.read(9) != MCAP_MAGIC:
                    raise ContainerError("the MCAP footer is not followed by the closing magic (truncated or corrupt)")
                return
            if op == 0x06:  # chunk
                if n > MAX_CHUNK:
                    raise ContainerError(f"an MCAP chunk of {n} bytes")
                b = _Buf(_exact(f, n))
                b.take(16)  # start and end time
                size = b.u64()
                b.take(4)  # crc
                comp = b.string()
                data = b.take(b.u64())
                try:
                    inner = inflater.inflate(comp, bytes(data), size, "an MCAP chunk")
                except InflateError as e:
                    raise ContainerError(str(e)) from None
                if blocks and len(inner) >= 9:
                    import numpy as np

                    a = np.frombuffer(inner, dtype=np.uint8)
                    found = _mcap_starts(a)
                    if found is not None:
                        _in_time()
                        yield from _mcap_blocks(a, inner, found, channels, facts, record)
                        continue
                # the records of the chunk, as _mcap_inner and record() read them, message records inline (most)
                mv = memoryview(inner)
                pos, end = 0, len(inner)
                ticks = 0
                while pos < end:
                    ticks += 1
                    if not ticks & 4095:  # the budget holds inside a chunk of millions of records
                        _in_time()
                    if pos + 9 > end:
                        raise ContainerError("an MCAP chunk ends in the middle of a record")
                    iop = inner[pos]
                    (m,) = unpack_from("<Q", inner, pos + 1)
                    stop = pos + 9 + m
                    if stop > end:
                        raise ContainerError("an MCAP chunk record runs past its chunk")
                    if iop == 0x05 and m >= 22:
                        c = channels.get(unpack_from("<H", inner, pos + 9)[0])
                        if c is not None and "start" in facts:
                            if c[2]:
                                yield (c[0], c[1], unpack_from("<Q", inner, pos + 15)[0], mv[pos + 31:stop], "",
                                       c[3])
                            pos = stop
                            continue
                    got = record(iop, mv[pos + 9:stop])
                    if got is not None:
                        yield got
                    pos = stop
            elif op in (0x03, 0x04, 0x05):
                if n > MAX_CHUNK:
                    raise ContainerError(f"an MCAP record of {n} bytes")
                got = record(op, memoryview(_exact(f, n)))
                if got is not None:
                    yield got
            else:  # header, indexes, attachments, metadata, statistics, summary: skipped, not read
                _skip(f, n)


def _mcap_blocks(a, inner, found, channels, facts, record):
    """The records of one chunk in order: schema and channel records through `record`, each run of message
    records between them as one Block of its wanted messages."""
    import numpy as np

    starts, ends = found
    ops = a[starts]
    size = ends - starts - 9
    plain = (ops == 5) & (size >= 22)
    cut = np.flatnonzero(~plain).tolist()
    mv = memoryview(inner)
    lo = 0
    for ticks, stop in enumerate(cut + [len(starts)], 1):
        if not ticks & 1023:  # a chunk of millions of schema records: the run's budget holds inside it too
            _in_time()
        if stop > lo:
            st = starts[lo:stop]
            cids = rows(a, st + 9, 2).view("<u2")[:, 0].astype(np.int64)
            times = rows(a, st + 15, 8).view("<u8")[:, 0].astype(np.int64)
            ids = np.unique(cids).tolist()
            if any(i not in channels for i in ids):  # record() says which, after the messages before it
                for p, q in zip(st.tolist(), ends[lo:stop].tolist()):
                    got = record(5, mv[p + 9:q])
                    if got is not None:
                        yield got
            else:
                if "start" not in facts:
                    facts["start"] = int(times[0])
                wanted = [i for i in ids if channels[i][2]]
                if wanted:
                    keep = np.isin(cids, wanted) if len(wanted) < len(ids) else slice(None)
                    chans = {i: (channels[i][0], channels[i][1], "", channels[i][3]) for i in wanted}
                    yield Block(a, inner, cids[keep], times[keep], st[keep] + 31, ends[lo:stop][keep], chans)
        if stop < len(starts):
            p, q = int(starts[stop]), int(ends[stop])
            got = record(int(ops[stop]), mv[p + 9:q])
            if got is not None:
                yield got
        lo = stop + 1


def _skip(f, n: int) -> None:
    if n > (1 << 62):
        raise ContainerError("a record length beyond any file")
    try:
        f.seek(n, 1)
    except (OSError, ValueError, AttributeError):
        while n > 0:  # a decompressing stream: read and drop, in pieces
            got = f.read(min(n, 1 << 20))
            if not got:
                raise ContainerError("the file ends in the middle of a record (truncated)") from None
            n -= len(got)


class InflatingStream:
    """A whole-file zstd stream (rosbag2 "file" compression) read in pieces, within the inflater's bounds."""

    def __init__(self, raw, inflater: Inflater, what: str):
        try:
            from compression import zstd
        except ImportError:
            from backports import zstd
        self.raw, self.inflater, self.what = raw, inflater, what
        self.d = zstd.ZstdDecompressor()
        self.buf = bytearray()
        self.pos = 0

    def read(self, n: int) -> bytes:
        while len(self.buf) - self.pos < n and not self.d.eof:
            chunk = b"" if self.d.needs_input is False else self.raw.read(1 << 20)
            if not chunk and self.d.needs_input:
                break
            try:
                out = self.d.decompress(chunk, max_length=1 << 22)
            except Exception as e:  # noqa: BLE001 - zstd's own error type
                raise ContainerError(f"{self.what} cannot be decompressed: {e}") from None
            self.inflater.used += len(out)
            if self.inflater.used > self.inflater.total:
                raise ContainerError(f"the recording inflates past {self.inflater.total >> 30} GiB in all")
            del self.buf[:self.pos]
            self.pos = 0
            self.buf += out
        data = bytes(self.buf[self.pos:self.pos + n])
        self.pos += len(data)
        return data

    def seek(self, *a):
        raise OSError("not seekable")

    def __enter__(self):
        return self

    def __exit__(self, *exc):
        self.raw.close()


# --- rosbag2 sqlite3 ---------------------------------------------------------------------------------------
MAX_BLOB = 64 * 1024**2


def sqlite_messages(path: str, want, facts: dict, runner: bool, inflater: Inflater, deadline=None,
                    image: bytes | None = None):
    """`image`: the whole database, inflated in memory (rosbag2 "file" compression), instead of `path`."""
    import sqlite3
    import time
    from urllib.parse import quote

    facts["ros"] = 2
    try:
        if image is None:
            real = door.admit(path, limit=RECORDING_BYTES, runner=runner)
            conn = sqlite3.connect(f"file:{quote(real)}?mode=ro&immutable=1", uri=True, check_same_thread=False)
        else:
            if image[18:20] == b"\x02\x02":
                # rosbag2 writes its databases in WAL mode, which sqlite cannot open from memory: the copy in
                # memory says "rollback journal" (the file was closed, so its WAL was folded in before compression)
                image = image[:18] + b"\x01\x01" + image[20:]
            conn = sqlite3.connect(":memory:")
            conn.deserialize(image)
    except sqlite3.Error as e:
        raise ContainerError(f"not a readable rosbag2 database: {e}") from None
    stop = [False]

    def progress():
        if deadline is not None and time.monotonic() > deadline:
            stop[0] = True
            return 1
        return 0

    try:
        conn.setlimit(sqlite3.SQLITE_LIMIT_LENGTH, MAX_BLOB)
        conn.set_progress_handler(progress, 10_000)
        conn.execute("PRAGMA trusted_schema = OFF")
        conn.execute("PRAGMA temp_store = MEMORY")
        conn.execute("PRAGMA hard_heap_limit = 536870912")
        # a damaged sqlite_master may hold its sql as a blob or a number: read as text, never trusted as such
        kinds = {name: (typ, sql if isinstance(sql, str) else bytes(sql).decode("utf-8", "replace")
                        if isinstance(sql, (bytes, bytearray, memoryview)) else str(sql or ""))
                 for typ, name, sql in
                 conn.execute("SELECT type, name, sql FROM sqlite_master WHERE name IN ('topics', 'messages', "
                              "'schema', 'metadata')")}
        for name in ("topics", "messages", "schema"):
            typ, sql = kinds.get(name, ("", ""))
            if typ and (typ != "table" or sql.lstrip().upper().startswith("CREATE VIRTUAL")):
                raise ContainerError(f"its {name!r} is a {typ if typ != 'table' else 'virtual table'}, not a "
                                     "table: refused (a view runs a query of the file's choosing)")
        for name in ("topics", "messages"):
            if name not in kinds:
                raise ContainerError(f"no {name!r} table: not a rosbag2 database")
            hidden = [r[1] for r in conn.execute(f"PRAGMA table_xinfo({name})") if r[6] in (2, 3)]
            if hidden:
                raise ContainerError(f"its {name!r} table has generated columns ({', '.join(hidden[:3])}): refused")
        topics = facts.setdefault("topics", {})
        wanted = {}
        for tid, name, typ, fmt in conn.execute("SELECT id, name, type, serialization_format FROM topics"):
            name, typ = str(name), str(typ)
            topics.setdefault(name, typ)
            if want(name, typ):
                wanted[int(tid)] = (name, typ, str(fmt or "cdr") != "ros1")
        if not wanted:
            return
        first = conn.execute("SELECT min(timestamp) FROM messages").fetchone()
        if first and isinstance(first[0], int) and "start" not in facts:
            facts["start"] = first[0]  # the recording's first message, of any topic: locations count from it
        ids = ",".join(str(i) for i in wanted)
        cur = conn.execute(f"SELECT topic_id, timestamp, data FROM messages WHERE topic_id IN ({ids}) "  # noqa: S608
                           "ORDER BY timestamp")
        while True:
            rows = cur.fetchmany(512)
            if not rows:
                break
            for tid, t, data in rows:
                name, typ, cdr = wanted[tid]
                if not isinstance(data, bytes):
                    raise ContainerError("a message whose data is not a blob")
                yield (name, typ, int(t), data, "", cdr)
    except sqlite3.Error as e:
        if stop[0]:
            raise ContainerError("the run's time budget ran out while the database was read") from None
        raise ContainerError(f"the database cannot be read: {e}") from None
    finally:
        conn.close()


# --- the topics, from the index, before the messages --------------------------------------------------------
def ros1_topics(path: str, runner: bool) -> dict[str, str] | None:
    """topic -> type from the connection records after the bag's index position; None: not indexed."""
    out: dict[str, str] = {}
    with door.open_stream(path, limit=RECORDING_BYTES, runner=runner) as f:
        _exact(f, len(ROS1_MAGIC))
        (hl,) = struct.unpack("<I", _exact(f, 4))
        if hl > MAX_HEADER:
            raise ContainerError(f"a record header of {hl} bytes")
        fields = _fields(_exact(f, hl))
        if fields.get("op") != b"\x03":
            raise ContainerError("the bag does not start with its bag header")
        index = fields.get("index_pos", b"")
        pos = struct.unpack("<Q", index)[0] if len(index) == 8 else 0
        if not pos:
            return None
        f.seek(pos)
        while True:
            head = f.read(4)
            if len(head) < 4:
                return out
            (hl,) = struct.unpack("<I", head)
            if hl > MAX_HEADER:
                raise ContainerError(f"a record header of {hl} bytes")
            fields = _fields(_exact(f, hl))
            (dl,) = struct.unpack("<I", _exact(f, 4))
            if fields.get("op") == b"\x07" and dl <= MAX_HEADER:
                ch = _fields(_exact(f, dl))
                topic = (ch.get("topic") or fields.get("topic") or b"").decode("utf-8", "replace")
                out.setdefault(topic, (ch.get("type") or b"").decode("utf-8", "replace"))
            else:
                f.seek(dl, 1)


def mcap_topics(path: str, runner: bool) -> dict[str, str] | None:
    """topic -> type from the summary section; None: the file has none."""
    import os

    with door.open_stream(path, limit=RECORDING_BYTES, runner=runner) as f:
        size = f.seek(0, os.SEEK_END)
        if size < 8 + 9 + 20 + 8:
            return None
        f.seek(size - 8 - 20 - 9)
        rec = _exact(f, 9 + 20 + 8)
        if rec[0] != 0x02 or rec[-8:] != MCAP_MAGIC:
            return None
        (start,) = struct.unpack_from("<Q", rec, 9)
        if not start or start >= size:
            return None
        f.seek(start)
        schemas: dict[int, str] = {}
        out: dict[str, str] = {}
        while True:
            head = f.read(9)
            if len(head) < 9 or head[0] == 0x02:
                return out
            (n,) = struct.unpack_from("<Q", head, 1)
            if head[0] in (0x03, 0x04) and n <= MAX_HEADER:
                b = _Buf(_exact(f, n))
                if head[0] == 0x03:
                    sid = b.u16()
                    schemas[sid] = b.string()
                else:
                    b.u16()
                    sid = b.u16()
                    out.setdefault(b.string(), schemas.get(sid, ""))
            else:
                _skip(f, n)
