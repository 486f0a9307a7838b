"""JointState and TFMessage read straight from their bytes, ROS 1 serialisation or CDR (ROS 2).

The two message types the bag checks read have a fixed layout, so they are decoded here with `struct` instead of
a general deserialiser (rosbags' costs more per message than the checks themselves; issue 39). Every length is
checked against the bytes that are there: a message that lies (a count of 4 billion names) is a DecodeError,
never a huge allocation. The types are told by name (`msgtype`): other types are never decoded.

ROS 1: header = uint32 seq, uint32 sec, uint32 nsec, string frame_id; string = uint32 length + bytes;
arrays = uint32 count + elements. CDR: a 4-byte encapsulation header (byte 1: 0 big-, 1 little-endian), then
fields aligned to their size relative to the end of that header; a string's length counts its NUL; a float64
sequence is aligned to 8 only when it is not empty (what Fast-CDR writes).
"""
from __future__ import annotations

import struct

NS = 1_000_000_000
JOINT_STATE_TYPES = ("sensor_msgs/msg/JointState", "sensor_msgs/JointState")
TF_TYPES = ("tf2_msgs/msg/TFMessage", "tf2_msgs/TFMessage", "tf/tfMessage", "tf/msg/tfMessage")
MAX_ITEMS = 1 << 20  # names or transforms in one message: far beyond any robot


class DecodeError(ValueError):
    pass


def kind_of(msgtype: str) -> str | None:
    """'joint_state', 'tf' or None (a type the checks do not read)."""
    if msgtype in JOINT_STATE_TYPES:
        return "joint_state"
    if msgtype in TF_TYPES:
        return "tf"
    return None


_U32 = {"<": struct.Struct("<I"), ">": struct.Struct(">I")}
_I32 = {"<": struct.Struct("<i"), ">": struct.Struct(">i")}
_TIME1 = struct.Struct("<III")  # ROS 1 header: seq, sec, nsec
_SEVEN = {"<": struct.Struct("<7d"), ">": struct.Struct(">7d")}


class _Cursor:
    """Reads fields from `buf` at `pos`; `base` is where CDR alignment counts from (ROS 1: no alignment)."""

    __slots__ = ("buf", "pos", "end", "base", "e", "cdr")

    def __init__(self, buf, pos: int, e: str, cdr: bool):
        self.buf, self.pos, self.end, self.base, self.e, self.cdr = buf, pos, len(buf), pos, e, cdr

    def align(self, n: int) -> None:
        if self.cdr:
            off = (self.pos - self.base) % n
            if off:
                self.pos += n - off

    def need(self, n: int) -> None:
        if n < 0 or self.pos + n > self.end:
            raise DecodeError("the message is shorter than its fields say")

    def u32(self) -> int:
        self.align(4)
        self.need(4)
        v = _U32[self.e].unpack_from(self.buf, self.pos)[0]
        self.pos += 4
        return v

    def count(self) -> int:
        n = self.u32()
        if n > MAX_ITEMS:
            raise DecodeError(f"a sequence of {n} elements")
        return n

    def string(self) -> str:
        n = self.u32()
        self.need(n)
        raw = bytes(self.buf[self.pos:self.pos + n])
        self.pos += n
        if self.cdr and raw.endswith(b"\0"):
            raw = raw[:-1]
        return raw.decode("utf-8", "replace")

    def stamp(self) -> int:
        if self.cdr:
            self.align(4)
            self.need(8)
            sec = _I32[self.e].unpack_from(self.buf, self.pos)[0]
            nsec = _U32[self.e].unpack_from(self.buf, self.pos + 4)[0]
        else:
            self.need(12)
            _seq, sec, nsec = _TIME1.unpack_from(self.buf, self.pos)  # ROS 1 is little-endian
            self.pos += 4
        self.pos += 8
        return sec * NS + nsec

    def doubles(self) -> tuple:
        n = self.count()
        if not n:
            return ()
        self.align(8)
        self.need(8 * n)
        v = struct.unpack_from(f"{self.e}{n}d", self.buf, self.pos)
        self.pos += 8 * n
        return v

    def seven(self) -> tuple:
        self.align(8)
        self.need(56)
        v = _SEVEN[self.e].unpack_from(self.buf, self.pos)
        self.pos += 56
        return v


def _cursor(buf, cdr: bool) -> _Cursor:
    if not cdr:
        return _Cursor(buf, 0, "<", False)
    if len(buf) < 4:
        raise DecodeError("a CDR message shorter than its encapsulation header")
    kind = buf[1]
    if kind not in (0, 1) or buf[0] != 0:
        raise DecodeError(f"unsupported CDR encapsulation {bytes(buf[:2]).hex()}")
    return _Cursor(buf, 4, "<" if kind == 1 else ">", True)


_last_names = [b"", ()]  # the names' bytes of the last JointState, and their tuple: they rarely change


def joint_state(buf, cdr: bool):
    """(stamp_ns, names, position, velocity, effort)."""
    c = _cursor(buf, cdr)
    stamp = c.stamp()
    c.string()  # frame_id
    n = c.count()
    blob, names = _last_names
    end = c.pos + len(blob)
    if n == len(names) and blob and bytes(buf[c.pos:end]) == blob:
        c.pos = end
    else:
        start = c.pos
        names = _strings(c, n)
        _last_names[:] = [bytes(buf[start:c.pos]), names]
    return stamp, names, c.doubles(), c.doubles(), c.doubles()


def _text(buf, pos: int, end: int, base: int, cdr: bool, u32):
    """The string at `pos` (as `_Cursor.string` reads it) and where it ends."""
    if cdr:
        off = (pos - base) & 3
        if off:
            pos += 4 - off
    if pos + 4 > end:
        raise DecodeError("the message is shorter than its fields say")
    k = u32(buf, pos)[0]
    pos += 4
    if pos + k > end:
        raise DecodeError("the message is shorter than its fields say")
    raw = bytes(buf[pos:pos + k])
    if cdr and raw[-1:] == b"\0":
        raw = raw[:-1]
    return raw.decode("utf-8", "replace"), pos + k


def _strings(c: _Cursor, n: int) -> tuple:
    """n strings, as `_Cursor.string` reads them, in one loop (a JointState of a PR2 names 50 joints)."""
    buf, pos, end, base, cdr = c.buf, c.pos, c.end, c.base, c.cdr
    u32 = _U32[c.e].unpack_from
    out = []
    for _ in range(n):
        text, pos = _text(buf, pos, end, base, cdr, u32)
        out.append(text)
    c.pos = pos
    return tuple(out)


def tf_message(buf, cdr: bool) -> list[tuple]:
    """[(parent, child, (x, y, z), (qx, qy, qz, qw), stamp_ns)], in one loop (a PR2's /tf carries 40 a message)."""
    c = _cursor(buf, cdr)
    n = c.count()
    buf, pos, end, base, e = c.buf, c.pos, c.end, c.base, c.e
    u32 = _U32[e].unpack_from
    i32 = _I32[e].unpack_from
    seven = _SEVEN[e].unpack_from
    time1 = _TIME1.unpack_from
    out = []
    for _ in range(n):
        if cdr:
            off = (pos - base) & 3
            if off:
                pos += 4 - off
            if pos + 8 > end:
                raise DecodeError("the message is shorter than its fields say")
            stamp = i32(buf, pos)[0] * NS + u32(buf, pos + 4)[0]
            pos += 8
        else:
            if pos + 12 > end:
                raise DecodeError("the message is shorter than its fields say")
            _seq, sec, nsec = time1(buf, pos)
            stamp = sec * NS + nsec
            pos += 12
        parent, pos = _text(buf, pos, end, base, cdr, u32)
        child, pos = _text(buf, pos, end, base, cdr, u32)
        if cdr:
            off = (pos - base) & 7
            if off:
                pos += 8 - off
        if pos + 56 > end:
            raise DecodeError("the message is shorter than its fields say")
        v = seven(buf, pos)
        pos += 56
        out.append((parent, child, v[:3], v[3:], stamp))
    return out


# --- JointState in batches ------------------------------------------------------------------------------------
# A driver publishes the same joints, in the same order, message after message: every such message has the same
# length and the same bytes from the end of the stamp to the first position (frame_id, names, counts, padding).
# That layout, read once from one message (`js_layout`), lets a whole run of messages be read with numpy: the
# stamps and the float64 arrays are gathered from fixed offsets. A message that differs anywhere outside the
# stamp and the numbers is not of the layout and is read on its own (`joint_state`).
class JsLayout:
    __slots__ = ("cdr", "e", "length", "head", "lo", "hi", "fixed", "stamp_off", "pos", "vel", "eff", "words",
                 "names", "blob", "_mask")

    def matches(self, buf) -> bool:
        # (bytes() first: comparing a memoryview is item by item, a copy and memcmp is faster)
        if len(buf) != self.length or bytes(buf[self.lo:self.hi]) != self.fixed:
            return False
        if self.cdr and bytes(buf[:4]) != self.head:
            return False
        for at, word in self.words:
            if bytes(buf[at:at + len(word)]) != word:
                return False
        return True


def js_layout(buf, cdr: bool) -> JsLayout:
    """The layout of one JointState message (raises DecodeError as `joint_state` does)."""
    c = _cursor(buf, cdr)
    lay = JsLayout()
    lay.cdr, lay.e, lay.length = cdr, c.e, len(buf)
    lay.head = bytes(buf[:4]) if cdr else b""
    if cdr:
        c.align(4)
        lay.stamp_off = c.pos
    else:
        lay.stamp_off = 4  # after seq
    c.stamp()
    lay.lo = c.pos
    c.string()  # frame_id
    n = c.count()
    blob, names = _last_names
    end = c.pos + len(blob)
    if n == len(names) and blob and bytes(buf[c.pos:end]) == blob:
        c.pos = end  # the same tuple as the last message's: the checks compare names by identity
    else:
        begin = c.pos
        names = _strings(c, n)
        blob = bytes(buf[begin:c.pos])
        _last_names[:] = [blob, names]
    lay.names, lay.blob = names, blob
    arrays = []
    words = []
    for i in range(3):
        c.align(4)
        at = c.pos
        k = c.count()
        if k:
            c.align(8)
        if i == 0:
            lay.hi = c.pos  # frame_id, names, the position count and its padding: all fixed
        c.need(8 * k)
        arrays.append((c.pos, k))
        if i:
            words.append((at, bytes(buf[at:c.pos])))  # the count and the padding after it
        c.pos += 8 * k
    lay.pos, lay.vel, lay.eff = arrays
    lay.fixed = bytes(buf[lay.lo:lay.hi])
    lay.words = tuple(words)
    return lay


def js_batch(lay: JsLayout, payloads):
    """(stamps int64 (n,), position (n, k), velocity (n, kv), effort (n, ke)) of messages of one layout."""
    import numpy as np

    return js_rows(lay, np.frombuffer(b"".join(payloads), dtype=np.uint8).reshape(len(payloads), lay.length))


def js_rows(lay: JsLayout, rows):
    """`js_batch` of messages given as the rows of a uint8 array (n, lay.length)."""
    import numpy as np

    n = len(rows)
    e = lay.e
    s = lay.stamp_off
    if lay.cdr:
        sec = rows[:, s:s + 4].copy().view(e + "i4")[:, 0].astype(np.int64)
    else:
        sec = rows[:, s:s + 4].copy().view("<u4")[:, 0].astype(np.int64)
    nsec = rows[:, s + 4:s + 8].copy().view(e + "u4")[:, 0].astype(np.int64)
    stamps = sec * NS + nsec

    def doubles(off, k):
        if not k:
            return np.empty((n, 0), dtype=np.float64)
        return rows[:, off:off + 8 * k].copy().view(e + "f8").astype(np.float64, copy=False)

    return stamps, doubles(*lay.pos), doubles(*lay.vel), doubles(*lay.eff)


def fits(lay, rows):
    """Which rows (uint8 (n, lay.length)) are messages of this layout (JsLayout or TfLayout): every byte but the
    stamps and the numbers the same (`JsLayout.matches`, `TfLayout.read` for each), compared whole rows at once."""
    import numpy as np

    got = getattr(lay, "_mask", None)
    if got is None:
        if isinstance(lay, JsLayout):
            idx = list(range(4)) if lay.cdr else []
            idx.extend(range(lay.lo, lay.hi))
            for at, word in lay.words:
                idx.extend(range(at, at + len(word)))
            raw = (lay.head if lay.cdr else b"") + lay.fixed + b"".join(w for _at, w in lay.words)
        else:
            idx, raw = lay.keep, lay.keep_bytes
        like = np.zeros(lay.length, dtype=np.uint8)
        like[idx] = np.frombuffer(raw, dtype=np.uint8)
        free = np.ones(lay.length, dtype=bool)
        free[idx] = False
        got = lay._mask = (like, free)
    like, free = got
    return ((rows == like) | free).all(axis=1)


def remember_names(lay: JsLayout) -> None:
    """The next `joint_state` of these names hands back the layout's tuple (the checks compare by identity)."""
    _last_names[:] = [lay.blob, lay.names]


# --- TFMessage by layout ----------------------------------------------------------------------------------------
# robot_state_publisher sends the same edges, in the same order, message after message: only the stamps and the
# seven numbers of each transform change. The layout is read once (`tf_layout`); a message whose every other
# byte is the same is read with numpy (`TfLayout.read`), any other on its own (`tf_message`).
class TfLayout:
    __slots__ = ("cdr", "e", "length", "keep", "keep_bytes", "sec", "nsec", "vals", "edges", "np", "_mask")

    def rows(self, a):
        """`read` of many messages of this layout at once, the rows of a uint8 array (n, length): (stamps (n, E),
        values (n, E, 7))."""
        np = self.np
        e = self.e
        n = len(a)
        c = np.ascontiguousarray
        sec = c(a[:, self.sec]).view((e + "i4") if self.cdr else "<u4").astype(np.int64)
        nsec = c(a[:, self.nsec]).view(e + "u4").astype(np.int64)
        vals = c(a[:, self.vals]).view(e + "f8").astype(np.float64, copy=False).reshape(n, -1, 7)
        return sec * NS + nsec, vals

    def read(self, buf):
        """(stamps int64 (E,), values float64 (E, 7)) when `buf` has this layout, else None."""
        np = self.np
        if len(buf) != self.length:
            return None
        a = np.frombuffer(buf, dtype=np.uint8)
        if a[self.keep].tobytes() != self.keep_bytes:
            return None
        e = self.e
        sec = a[self.sec].view((e + "i4") if self.cdr else "<u4").astype(np.int64)
        nsec = a[self.nsec].view(e + "u4").astype(np.int64)
        vals = a[self.vals].view(e + "f8").astype(np.float64, copy=False).reshape(-1, 7)
        return sec * NS + nsec, vals


def tf_layout(buf, cdr: bool) -> TfLayout:
    """The layout of one TFMessage; raises DecodeError as `tf_message` does."""
    import numpy as np

    edges = tf_message(buf, cdr)
    c = _cursor(buf, cdr)
    lay = TfLayout()
    lay.np, lay.cdr, lay.e, lay.length = np, cdr, c.e, len(buf)
    lay.edges = tuple((p, ch) for p, ch, _t, _r, _s in edges)
    n = c.count()
    variable = np.zeros(len(buf), dtype=bool)
    sec, nsec, vals = [], [], []
    for _ in range(n):  # the walk of tf_message, keeping where the stamps and numbers are
        if cdr:
            c.align(4)
            at = c.pos
        else:
            variable[c.pos:c.pos + 4] = True  # seq
            at = c.pos + 4
        sec.extend(range(at, at + 4))
        nsec.extend(range(at + 4, at + 8))
        c.stamp()
        c.string()
        c.string()
        c.align(8)
        vals.extend(range(c.pos, c.pos + 56))
        c.pos += 56
    for idx in (sec, nsec, vals):
        variable[idx] = True
    lay.keep = np.flatnonzero(~variable)
    lay.keep_bytes = np.frombuffer(buf, dtype=np.uint8)[lay.keep].tobytes()
    lay.sec = np.array(sec, dtype=np.intp)
    lay.nsec = np.array(nsec, dtype=np.intp)
    lay.vals = np.array(vals, dtype=np.intp)
    return lay
