#!/usr/bin/env python3
"""Recordings fuzzer (issue 36): mutated and hostile ROS 1 bags, rosbag2 sqlite3 folders, MCAP and YAML/JSON
joint-state lists, through `urdfcheck bag MODEL REC` and `urdfcheck lint MODEL --bag REC`.

    python3 fuzz/recordings.py --count 40000 --seed 36 [--hang 15] [--report FILE]

Seeds (written once per run with tests/bagwriter.py, rosbags' writers): a recording of the fixture robot
(tests/fixtures/ros1/robot.urdf) whose every JointState names a joint the robot lacks (B001), in ROS 1 (plain,
bz2 and lz4 chunks), rosbag2 sqlite3 and MCAP folders (metadata.yaml + storage file), MCAP re-chunked with zstd and
lz4, and as YAML and JSON message lists. Inputs:

  mutate   a seed's bytes flipped, inserted, deleted, lengths set to 0 or 2^32-1 / 2^64-1, truncated; one file of a
           folder (metadata.yaml or the storage file) or a file alone;
  hostile  decompression bombs (ROS 1 bz2/lz4 chunks, MCAP zstd/lz4 chunks declaring 1 KB or 2^63, rosbag2 file
           compression), a 2-million-message MCAP, bogus chunk and record sizes, sqlite with views (recursive),
           triggers, generated huge blobs, odd schemas; symlinks out of the checkout (the recording itself,
           metadata.yaml, the .db3, the folder; to the canary file, /proc/self/environ, /dev/zero), FIFOs,
           metadata naming `../` or absolute files, YAML alias bombs, deep nesting, huge numbers.

Each input runs the real CLI in-process in a forked child (harness.py) with `--budget 3`, in a report format in
turn. A seeded recording always holds something wrong (the unknown joint, or it is unreadable): "All checks passed"
or a report without findings is a silent pass; a hostile shape must exit 1 (or 2 with a reason). Exit 1 when any
count is non-zero.
"""
from __future__ import annotations

import bz2
import json
import os
import random
import shutil
import sqlite3
import struct
import sys
from pathlib import Path

HERE = Path(__file__).resolve().parent
sys.path.insert(0, str(HERE))
sys.path.insert(0, str(HERE.parent / "tests"))
import bagwriter  # noqa: E402
import harness  # noqa: E402

FIXTURES = HERE.parent / "tests" / "fixtures" / "ros1"
FORMATS = ("text", "json", "text", "sarif", "text", "markdown", "github", "junit")
JOINTS = ["left_wheel_joint", "right_wheel_joint", "arm_joint", "ghost_joint"]


# --- seeds ---------------------------------------------------------------------------------------------------
def _events(n: int = 40):  # (more than source.MIN_RUN: chunks read whole take the fast path too)
    ev = [("tf", 0.0, [("base_link", "laser", (0.1, 0.0, 0.2), (0, 0, 0, 1))], "/tf_static")]
    for i in range(n):
        t = 0.1 * (i + 1)
        ev.append(("js", t, JOINTS, [0.1 * i, 0.2, 0.3, 0.4]))
    return ev


def _ros1_compressed(dst: Path, fmt: str) -> Path:
    from rosbags.rosbag1 import Writer

    class W(Writer):
        def __init__(self, path, *a, **k):
            super().__init__(path, *a, **k)
            self.set_compression(getattr(Writer.CompressionFormat, fmt))

    import rosbags.rosbag1 as r1

    old = r1.Writer
    r1.Writer = W
    try:
        return bagwriter.write(dst, "ros1", _events())
    finally:
        r1.Writer = old


def _mcap_records(data: bytes):
    p = 8
    while p + 9 <= len(data):
        op = data[p]
        (n,) = struct.unpack_from("<Q", data, p + 1)
        yield op, data[p + 9:p + 9 + n]
        p += 9 + n


def mcap_rechunk(data: bytes, comp: str, declared=None, inner: bytes | None = None) -> bytes:
    """The MCAP's chunks' records compressed with `comp`; `declared` overrides the uncompressed size field;
    `inner` replaces the records of the first chunk."""
    out = [data[:8]]
    first = True
    for op, body in _mcap_records(data):
        if op == 0x06:
            b = 0
            start, end, size, crc = struct.unpack_from("<QQQI", body, 0)
            b = 28
            (cl,) = struct.unpack_from("<I", body, b)
            b += 4 + cl
            (rl,) = struct.unpack_from("<Q", body, b)
            recs = body[b + 8:b + 8 + rl]
            if inner is not None and first:
                recs = inner
            first = False
            packed = compress(comp, recs)
            size = len(recs) if declared is None else declared
            c = comp.encode()
            body = struct.pack("<QQQI", start, end, size, 0) + struct.pack("<I", len(c)) + c + \
                struct.pack("<Q", len(packed)) + packed
        elif op == 0x02:  # footer: the summary's offsets moved; say there is none (readers stream the file)
            body = bytes(20)
        out.append(bytes([op]) + struct.pack("<Q", len(body)) + body)
    out.append(data[-8:])
    return b"".join(out)


def compress(comp: str, data: bytes) -> bytes:
    if comp == "zstd":
        from backports import zstd

        return zstd.ZstdCompressor().compress(data, mode=zstd.ZstdCompressor.FLUSH_FRAME) \
            if hasattr(zstd.ZstdCompressor, "FLUSH_FRAME") else zstd.compress(data)
    if comp == "lz4":
        import lz4.frame

        return lz4.frame.compress(data)
    if comp == "bz2":
        return bz2.compress(data, 1)
    return data


def _ros1_records(data: bytes):
    """(header bytes, data bytes) of a ROS 1 bag's top-level records."""
    p = 13
    while p + 4 <= len(data):
        (hl,) = struct.unpack_from("<I", data, p)
        h = data[p + 4:p + 4 + hl]
        (dl,) = struct.unpack_from("<I", data, p + 4 + hl)
        d = data[p + 8 + hl:p + 8 + hl + dl]
        yield h, d
        p += 8 + hl + dl


def _fields(h: bytes) -> list:
    out, p = [], 0
    while p + 4 <= len(h):
        (n,) = struct.unpack_from("<I", h, p)
        k, _, v = h[p + 4:p + 4 + n].partition(b"=")
        out.append((k, v))
        p += 4 + n
    return out


def _header(fields) -> bytes:
    return b"".join(struct.pack("<I", len(k) + 1 + len(v)) + k + b"=" + v for k, v in fields)


def ros1_rechunk(data: bytes, comp: str, declared=None, inner: bytes | None = None) -> bytes:
    """A plain ROS 1 bag with its chunks compressed with `comp` (bz2, lz4, or any name), `size` set to
    `declared`, and the first chunk's records replaced by `inner`."""
    out = [data[:13]]
    first = True
    for h, d in _ros1_records(data):
        f = _fields(h)
        if dict(f).get(b"op") == b"\x05":
            recs = inner if (inner is not None and first) else d
            first = False
            size = len(recs) if declared is None else declared
            d = compress(comp, recs)
            f = [(k, v) for k, v in f if k not in (b"compression", b"size")] + [
                (b"compression", comp.encode()), (b"size", struct.pack("<I", size & 0xFFFFFFFF))]
            h = _header(f)
        out.append(struct.pack("<I", len(h)) + h + struct.pack("<I", len(d)) + d)
    return _index_pos(out)


def _index_pos(out: list) -> bytes:
    """The bag header's index_pos pointed at the new offset of the index (the first top-level connection
    record), so readers that start from the index see the rewritten chunks' bag as valid."""
    pos, at = 0, None
    for rec in out[1:]:
        (hl,) = struct.unpack_from("<I", rec, 0)
        if dict(_fields(rec[4:4 + hl])).get(b"op") == b"\x07" and at is None:
            at = len(out[0]) + pos
        pos += len(rec)
    first = out[1]
    (hl,) = struct.unpack_from("<I", first, 0)
    f = _fields(first[4:4 + hl])
    if at is not None and dict(f).get(b"op") == b"\x03":
        h = _header([(k, struct.pack("<Q", at) if k == b"index_pos" else v) for k, v in f])
        out[1] = struct.pack("<I", len(h)) + h + first[4 + hl:]
    return b"".join(out)


def _folder_bytes(folder: Path) -> dict:
    return {p.name: p.read_bytes() for p in folder.iterdir() if p.is_file()}


def make_seeds(tmp: Path) -> dict:
    """name -> {relative path: bytes}: each seed is the set of files of one recording (first: what to name)."""
    tmp.mkdir(parents=True, exist_ok=True)
    seeds: dict = {}
    plain = bagwriter.write(tmp / "plain", "ros1", _events()).read_bytes()
    seeds["ros1"] = {"rec.bag": plain}
    for fmt in ("BZ2", "LZ4"):
        seeds[f"ros1-{fmt.lower()}"] = {"rec.bag": _ros1_compressed(tmp / fmt, fmt).read_bytes()}
    for fmt in ("sqlite3", "mcap"):
        folder = bagwriter.write(tmp / fmt, fmt, _events())
        files = _folder_bytes(folder)
        seeds[fmt] = {f"rec/{k}": v for k, v in sorted(files.items(), key=lambda kv: kv[0] != "metadata.yaml")}
        (name,) = [k for k in files if k != "metadata.yaml"]
        seeds[fmt + "-alone"] = {"rec" + Path(name).suffix: files[name]}
    mcap = seeds["mcap-alone"]["rec.mcap"]
    for comp in ("zstd", "lz4"):
        seeds[f"mcap-{comp}"] = {"rec.mcap": mcap_rechunk(mcap, comp)}
    items = [{"topic": "/joint_states", "stamp": 0.1 * i, "name": JOINTS, "position": [0.1, 0.2, 0.3, 0.4]}
             for i in range(5)]
    items.append({"topic": "/tf_static", "transforms": [{"parent": "base_link", "child": "laser",
                                                         "translation": [0.1, 0, 0.2], "rotation": [0, 0, 0, 1]}]})
    seeds["json"] = {"rec.json": json.dumps(items).encode()}
    seeds["yaml"] = {"rec.yaml": "".join(
        f"- topic: /joint_states\n  stamp: {0.1 * i:.1f}\n  name: [{', '.join(JOINTS)}]\n"
        "  position: [0.1, 0.2, 0.3, 0.4]\n"
        for i in range(5)).encode()}
    return seeds


# --- hostile pieces made once ---------------------------------------------------------------------------------
def make_bombs(small: bool = False) -> dict:
    """Chunks of zeros; `small` (the test suite's slice): 8 MiB each, still far past any size they declare."""
    zeros = bytes((8 if small else 64) * 1024**2)
    if small:
        return {"zstd": compress("zstd", zeros), "lz4": compress("lz4", zeros), "bz2": bz2.compress(zeros, 9)}
    return {"zstd": compress("zstd", zeros * 16),  # 1 GiB
            "lz4": compress("lz4", zeros * 4),  # 256 MiB
            "bz2": bz2.compress(zeros[: 16 * 1024**2], 9)}  # 16 MiB (bz2 is slow to make)


def _mcap_many(mcap: bytes, n: int) -> bytes:
    """The first chunk's records followed by n copies of its last message record."""
    for op, body in _mcap_records(mcap):
        if op == 0x06:
            (cl,) = struct.unpack_from("<I", body, 28)
            b = 32 + cl
            (rl,) = struct.unpack_from("<Q", body, b)
            recs = body[b + 8:b + 8 + rl]
            last = None
            p = 0
            while p + 9 <= len(recs):
                (m,) = struct.unpack_from("<Q", recs, p + 1)
                if recs[p] == 0x05:
                    last = recs[p:p + 9 + m]
                p += 9 + m
            return recs + last * n
    raise ValueError("no chunk")


def sqlite_variants(db: bytes, tmp: Path) -> dict:
    """Hostile .db3 files derived from the seed: name -> bytes."""
    sqls = {
        "view-recursive": ["ALTER TABLE messages RENAME TO m0",
                           "CREATE VIEW messages AS WITH RECURSIVE c(x) AS (SELECT 1 UNION ALL SELECT x+1 FROM c) "
                           "SELECT x AS id, 1 AS topic_id, x AS timestamp, zeroblob(10) AS data FROM c"],
        "view-topics": ["ALTER TABLE topics RENAME TO t0",
                        "CREATE VIEW topics AS WITH RECURSIVE c(x) AS (SELECT 1 UNION ALL SELECT x+1 FROM c) "
                        "SELECT x AS id, 'n' || x AS name, 'sensor_msgs/msg/JointState' AS type, 'cdr' AS "
                        "serialization_format, '' AS offered_qos_profiles FROM c"],
        "trigger": ["CREATE TABLE log(x)", "CREATE TRIGGER t AFTER INSERT ON messages BEGIN INSERT INTO log VALUES "
                    "(1); END", "CREATE TEMP TRIGGER IF NOT EXISTS q AFTER DELETE ON topics BEGIN SELECT 1; END"],
        "generated-blob": ["ALTER TABLE messages ADD COLUMN big BLOB AS (zeroblob(700000000))",
                           "ALTER TABLE messages RENAME TO m0",
                           "CREATE TABLE messages(id INTEGER PRIMARY KEY, topic_id INTEGER, timestamp INTEGER, "
                           "data BLOB AS (zeroblob(700000000)))"],
        "no-messages": ["DROP TABLE messages"],
        "no-topics": ["DROP TABLE topics"],
        "text-types": ["UPDATE messages SET topic_id = 'x', timestamp = 'late', data = 'not a blob'"],
        "null-data": ["UPDATE messages SET data = NULL, timestamp = NULL"],
        "huge-ids": ["UPDATE messages SET topic_id = 9223372036854775807, timestamp = -9223372036854775808"],
        "topic-names": ["UPDATE topics SET name = char(27) || ']52;c;' || name || char(8238), type = "
                        "'sensor_msgs/msg/JointState' || char(10) || '::error::x'"],
        "many-rows": ["WITH RECURSIVE c(x) AS (SELECT 1 UNION ALL SELECT x+1 FROM c WHERE x < 200000) "
                      "INSERT INTO messages(topic_id, timestamp, data) SELECT topic_id, timestamp, data FROM "
                      "messages, c WHERE messages.id = 2"],
        "big-blob": ["UPDATE messages SET data = zeroblob(40000000) WHERE id = 2"],
        "schema-extra": ["CREATE TABLE schema(schema_version INTEGER, ros_distro TEXT)",
                         "INSERT INTO schema VALUES (99, 'x' || char(10) || '::warning::y')"],
        "virtual": ["ALTER TABLE messages RENAME TO m0",
                    "CREATE VIRTUAL TABLE messages USING fts5(id, topic_id, timestamp, data)"],
    }
    out = {}
    for name, stmts in sqls.items():
        p = tmp / f"v-{name}.db3"
        p.write_bytes(db)
        try:
            con = sqlite3.connect(p)
            for s in stmts:
                con.execute(s)
            con.commit()
            con.close()
        except sqlite3.Error:
            continue
        out[name] = p.read_bytes()
    return out


# --- the grammar ----------------------------------------------------------------------------------------------
OPS = ("flip", "insert", "delete", "u32max", "u64max", "zero", "truncate", "dup")


def mutate(r: random.Random, data: bytes) -> bytes:
    b = bytearray(data)
    for _ in range(r.randrange(1, 6)):
        op = r.choice(OPS)
        p = r.randrange(max(len(b), 1))
        if op == "flip" and b:
            b[p] ^= 1 << r.randrange(8)
        elif op == "insert":
            b[p:p] = r.choice([b"\x00", b"\xff" * 4, b"op=\x05", b"compression=bz2", b"\n", b"*a ", b"&a ",
                               bytes(r.randrange(256) for _ in range(r.randrange(1, 16)))])
        elif op == "delete":
            del b[p:p + r.randrange(1, 64)]
        elif op == "u32max":
            b[p:p + 4] = b"\xff\xff\xff\xff"
        elif op == "u64max":
            b[p:p + 8] = b"\xff" * 8
        elif op == "zero":
            b[p:p + 8] = bytes(8)
        elif op == "truncate":
            del b[max(p, 8):]
        elif op == "dup":
            q = r.randrange(max(len(b), 1))
            b[q:q] = b[p:p + r.randrange(1, 256)]
    return bytes(b)


def _text_hostile(r: random.Random) -> bytes:
    k = r.choice(["alias", "deep", "deep-json", "huge-num", "not-list", "long-json", "bad-utf8", "tags", "anchors"])
    if k == "alias":
        lines = ['a: &a ["lol","lol","lol","lol","lol","lol","lol","lol","lol"]']
        for i in range(1, 10):
            prev = chr(96 + i)
            lines.append(f"{chr(97 + i)}: &{chr(97 + i)} [" + ",".join([f"*{prev}"] * 9) + "]")
        return ("\n".join(lines) + "\n").encode()
    if k == "deep":
        n = r.choice([100, 5000, 100000])
        return ("- " + "[" * n + "]" * n + "\n").encode()
    if k == "deep-json":
        n = r.choice([100, 5000, 200000])
        return ("[" + "{\"name\": " * 1 + "[" * n + "]" * n + "}]").encode()
    if k == "huge-num":
        return json.dumps([{"name": ["arm_joint"], "position": [1], "stamp": 1}]).replace(
            "[1]", "[1e99999]").replace('"stamp": 1', '"stamp": ' + "9" * 5000).encode()
    if k == "not-list":
        return r.choice([b"42\n", b"null\n", b"{}", b"'x'", b"!!python/object:os.system {}", b"[1, 2, 3]"])
    if k == "long-json":
        item = json.dumps({"name": ["ghost_joint"], "position": [0.1], "stamp": 0.1})
        return ("[" + ",".join([item] * r.choice([1000, 60000])) + "]").encode()
    if k == "bad-utf8":
        return b"- name: [\xff\xfe\xc3]\n  position: [0]\n"
    if k == "tags":
        return b"- !!python/name:os.system\n- !custom {name: [a]}\n- !!binary AAAA\n"
    return b"- &x {name: [ghost_joint], position: [0.1], stamp: 0.1}\n" + b"- *x\n" * 2000


def generate(r: random.Random, seeds: dict, bombs: dict, dbs: dict, i: int, small: bool = False) -> dict:
    """One input: {"files": {rel: bytes | ("symlink", target) | ("fifo",)}, "rec": rel, "strict": bool, ...}."""
    name = r.choice(sorted(seeds))
    files = dict(seeds[name])
    rec = "rec" if name in ("sqlite3", "mcap") else next(iter(files))
    strict = False  # True: the input is broken beyond reading; any exit 0 is silent
    how = r.random()
    kind = "mutate"
    if how < 0.7:
        target = r.choice(list(files))
        files[target] = mutate(r, files[target])
    else:
        kind = r.choice(["bomb-ros1", "bomb-mcap", "mcap-many", "sqlite", "symlink", "fifo", "meta", "text",
                         "sizes", "zstd-file", "empty"])
        strict = kind not in ("sqlite", "meta", "sizes")
        if kind == "bomb-ros1":
            comp = r.choice(["bz2", "lz4"])
            inner = None
            seed = seeds["ros1"]["rec.bag"]
            declared = r.choice([1000, 0, 2**32 - 1, 100 * 1024**2])
            data = ros1_rechunk(seed, comp, declared)
            if r.random() < 0.8:  # the first chunk replaced by the bomb itself
                out = [data[:13]]
                for h, d in _ros1_records(data):
                    if dict(_fields(h)).get(b"op") == b"\x05" and inner is None:
                        inner = d = bombs[comp]
                    out.append(struct.pack("<I", len(h)) + h + struct.pack("<I", len(d)) + d)
                data = b"".join(out)
            files, rec = {"rec.bag": data}, "rec.bag"
        elif kind == "bomb-mcap":
            comp = r.choice(["zstd", "lz4", "gzip", "", "ZSTD"])
            declared = r.choice([1024, 0, 2**63, 2**64 - 1, 255 * 1024**2, None])
            data = mcap_rechunk(seeds["mcap-alone"]["rec.mcap"], comp if comp in ("zstd", "lz4") else "", declared)
            if comp in bombs and r.random() < 0.8:
                data = _swap_mcap_chunk(data, bombs[comp], comp)
            elif comp not in ("zstd", "lz4"):
                data = data.replace(b"\x00\x00\x00\x00" + b"\x00" * 0, b"\x00\x00\x00\x00", 1)
            files, rec = {"rec.mcap": data}, "rec.mcap"
        elif kind == "mcap-many":
            recs = _mcap_many(seeds["mcap-alone"]["rec.mcap"], r.choice([2000, 200000, 2000000][:2 if small else 3]))
            files = {"rec.mcap": mcap_rechunk(seeds["mcap-alone"]["rec.mcap"], r.choice(["zstd", "lz4"]),
                                              inner=recs)}
            rec = "rec.mcap"
        elif kind == "sqlite":
            v = r.choice(sorted(dbs))
            strict = v not in ("trigger", "schema-extra", "topic-names", "many-rows", "big-blob", "huge-ids")
            if r.random() < 0.5:
                files, rec = {"rec.db3": dbs[v]}, "rec.db3"
            else:
                files = dict(seeds["sqlite3"])
                db = next(k for k in files if k.endswith(".db3"))
                files[db] = dbs[v]
                rec = "rec"
            kind = "sqlite-" + v
        elif kind == "symlink":
            to = r.choice(["OUT/secret.txt", "OUT/secret.yaml", "/proc/self/environ", "/dev/zero", "/dev/urandom",
                           "OUT", "/etc/passwd", "../OUT/secret.yaml", "/proc/self/cmdline", "rec.bag"])
            where = r.choice(["rec", "meta", "storage", "folder"])
            if where == "rec":
                rec = r.choice(["rec.bag", "rec.yaml", "rec.json", "rec.mcap", "rec.db3", "rec"])
                files = {rec: ("symlink", to)}
            elif where == "folder":
                files, rec = {"rec": ("symlink", "OUT")}, "rec"
            else:
                files = dict(seeds[r.choice(["sqlite3", "mcap"])])
                rec = "rec"
                key = "rec/metadata.yaml" if where == "meta" else next(k for k in files if not k.endswith("yaml"))
                files[key] = ("symlink", to)
            kind += "-" + where
        elif kind == "fifo":
            where = r.choice(["rec", "meta", "storage"])
            if where == "rec":
                rec = r.choice(["rec.bag", "rec.yaml", "rec.json", "rec.mcap", "rec.db3"])
                files = {rec: ("fifo",)}
            else:
                files = dict(seeds[r.choice(["sqlite3", "mcap"])])
                rec = "rec"
                key = "rec/metadata.yaml" if where == "meta" else next(k for k in files if not k.endswith("yaml"))
                files[key] = ("fifo",)
            kind += "-" + where
        elif kind == "meta":
            files = dict(seeds[r.choice(["sqlite3", "mcap"])])
            rec = r.choice(["rec", "rec/metadata.yaml"])
            meta = files["rec/metadata.yaml"].decode()
            variant = r.choice(["dotdot", "abs", "alias", "deep", "bad", "many", "comp", "missing", "self"])
            strict = variant not in ("many", "self")
            store = next(k for k in files if not k.endswith("yaml")).split("/")[-1]
            if variant == "dotdot":
                meta = meta.replace(f"- {store}", "- ../../OUT/secret.txt")
            elif variant == "abs":
                meta = meta.replace(f"- {store}", "- /proc/self/environ")
            elif variant == "alias":
                meta = _text_hostile(random.Random(0)).decode("utf-8", "replace") + meta
            elif variant == "deep":
                meta = meta + "x: " + "[" * 20000 + "]" * 20000 + "\n"
            elif variant == "bad":
                meta = meta[: r.randrange(len(meta))] + "\t: {\n"
            elif variant == "many":
                meta = meta.replace(f"- {store}", f"- {store}\n" + f"  - {store}\n" * 50)
            elif variant == "comp":
                meta = meta.replace("compression_mode: ''", "compression_mode: FILE").replace(
                    "compression_format: ''", "compression_format: " + r.choice(["zstd", "gzip", "lz4", "'x'"]))
                meta = meta.replace("compression_mode: \"\"", "compression_mode: FILE")
                strict = False
            elif variant == "missing":
                meta = meta.replace(f"- {store}", "- nothere.db3")
            else:
                meta = meta.replace(f"- {store}", "- metadata.yaml")
            files["rec/metadata.yaml"] = meta.encode()
            kind += "-" + variant
        elif kind == "text":
            ext = r.choice(["yaml", "json", "yml"])
            files, rec = {f"rec.{ext}": _text_hostile(r)}, f"rec.{ext}"
            strict = False  # some shapes are readable lists without joint states: B015, stated
        elif kind == "sizes":
            src = r.choice(["ros1", "mcap-alone", "ros1-lz4", "mcap-zstd"])
            data = bytearray(next(iter(seeds[src].values())))
            # the length fields: ROS 1 header/data lengths after the magic, MCAP record lengths
            for _ in range(r.randrange(1, 4)):
                p = r.randrange(8, len(data) - 8)
                data[p:p + 8] = r.choice([b"\xff" * 8, struct.pack("<Q", 2**62), struct.pack("<Q", len(data) * 3),
                                          struct.pack("<I", 2**31) + b"\x00" * 4])
            files = {next(iter(seeds[src])): bytes(data)}
            rec = next(iter(files))
            strict = False
        elif kind == "zstd-file":  # rosbag2 file compression: a .db3.zstd / .mcap.zstd bomb
            files = dict(seeds[r.choice(["sqlite3", "mcap"])])
            store = next(k for k in files if not k.endswith("yaml"))
            name = store.split("/")[-1]
            meta = files["rec/metadata.yaml"].decode().replace(f"- {name}", f"- {name}.zstd")
            meta = meta.replace("compression_mode: ''", "compression_mode: FILE").replace(
                "compression_format: ''", "compression_format: zstd")
            del files[store]
            files[store + ".zstd"] = bombs["zstd"] if r.random() < 0.7 else compress("zstd", seeds["sqlite3"][
                next(k for k in seeds["sqlite3"] if k.endswith(".db3"))])
            files["rec/metadata.yaml"] = meta.encode()
            rec = "rec"
            strict = files[store + ".zstd"] is bombs["zstd"]
        else:  # empty files and folders
            rec = r.choice(["rec.bag", "rec.mcap", "rec.db3", "rec.yaml", "rec.json", "rec"])
            files = {rec: b""} if rec != "rec" else {"rec/metadata.yaml": b""}
    argv = _argv(r, rec, i)
    return {"i": i, "name": name, "kind": kind, "files": files, "rec": rec, "strict": strict, "argv": argv}


def _swap_mcap_chunk(data: bytes, bomb: bytes, comp: str) -> bytes:
    out = [data[:8]]
    done = False
    for op, body in _mcap_records(data):
        if op == 0x06 and not done:
            done = True
            (cl,) = struct.unpack_from("<I", body, 28)
            head = body[:32 + cl]
            body = head + struct.pack("<Q", len(bomb)) + bomb
        elif op == 0x02:
            body = bytes(20)
        out.append(bytes([op]) + struct.pack("<Q", len(body)) + body)
    out.append(data[-8:])
    return b"".join(out)


def _argv(r: random.Random, rec: str, i: int) -> list[str]:
    fmt = FORMATS[i % len(FORMATS)]
    if r.random() < 0.5:
        argv = ["bag", "robot.urdf", rec]
    else:
        argv = ["lint", "robot.urdf", "--bag", rec]
    argv += ["--budget", "3", "--format", fmt, "--no-cache"]
    return argv


# --- running ---------------------------------------------------------------------------------------------------
def place(ws: Path, case: dict, out: Path) -> None:
    if ws.exists():
        shutil.rmtree(ws, ignore_errors=True)
        if ws.exists():  # a FIFO or odd mode left behind
            os.system(f"rm -rf '{ws}'")
    ws.mkdir(parents=True)
    shutil.copyfile(FIXTURES / "robot.urdf", ws / "robot.urdf")
    for rel, v in case["files"].items():
        p = ws / rel
        p.parent.mkdir(parents=True, exist_ok=True)
        if isinstance(v, tuple) and v[0] == "symlink":
            to = v[1].replace("OUT", str(out)) if v[1].startswith("OUT") else v[1].replace("../OUT", os.path.relpath(
                out, p.parent))
            os.symlink(to, p)
        elif isinstance(v, tuple):
            os.mkfifo(p)
        else:
            p.write_bytes(v)


def direct(rec: str, model) -> tuple[int | str, str]:
    """The fast path: `check_recording` in-process, inside the run's door (the checkout as its root) and a
    3-second budget, as `urdfcheck bag` calls it; (1 with findings, 0 without, or 'EXC'; their text)."""
    from urdfcheck.bag import check_recording
    from urdfcheck.core import door
    from urdfcheck.load.budget import run_budget

    try:
        with run_budget(3.0), door.guarded([os.getcwd()]):
            found = check_recording(model, rec, runner=True)
    except BaseException as e:  # noqa: BLE001 - counted
        if isinstance(e, KeyboardInterrupt):
            raise
        import traceback

        return "EXC", "".join(traceback.format_exception(type(e), e, e.__traceback__))[-3000:]
    text = "\n".join(f"{f.code} {f.severity} {f.location} {f.message}" for f in found)
    return (1 if found else 0), (text or "All checks passed (no findings)")


def do_one_factory(base: Path, out: Path, marks, cli_every: int):
    ws = base / "ws"
    from urdfcheck.model.build import model_from_string

    model = model_from_string((FIXTURES / "robot.urdf").read_text())

    def do_one(case: dict) -> dict:
        place(ws, case, out)
        os.chdir(ws)
        before = harness.snapshot(ws)
        if case["i"] % cli_every:
            code, text = direct(case["rec"], model)
            case = {**case, "argv": ["(direct)", "--format", "text"]}
        else:
            code, text = harness.cli(case["argv"])
        os.chdir(base)
        after = harness.snapshot(ws)
        bad = harness.judge(code, text, marks, must_fail=case["strict"])
        fmt = case["argv"][case["argv"].index("--format") + 1]
        if code in (0, 1) and "silent" not in bad and _no_findings(fmt, text):
            bad.append("silent")  # the seed's unknown joint (or the damage) is always worth a finding
        if before != after:
            bad.append("writes")
        outcome = f"{case['kind']} exit {code}" + (" cli" if case["argv"][0] != "(direct)" else "")
        return {"bad": bad, "outcome": outcome if not case["kind"].startswith("mutate") else f"mutate exit {code}" + (
            " cli" if case["argv"][0] != "(direct)" else ""),
                "detail": text[:4000] if code == "EXC" else text[-1500:]}

    return do_one


def _no_findings(fmt: str, text: str) -> bool:
    if "All checks passed" in text:
        return True
    if fmt == "json":
        try:
            doc = json.loads(text[text.index("{"):])
            return not doc.get("findings") and not any(m.get("findings") for m in doc.get("models", []) or [])
        except (ValueError, AttributeError):
            return False
    if fmt == "sarif":
        try:
            doc = json.loads(text[text.index("{"):])
            return not any(run.get("results") for run in doc.get("runs", []))
        except (ValueError, AttributeError):
            return False
    return False


def show(case: dict) -> dict:
    return {"i": case["i"], "kind": case["kind"], "name": case["name"], "rec": case["rec"], "argv": case["argv"],
            "files": {k: (list(v) if isinstance(v, tuple) else f"{len(v)} bytes") for k, v in case["files"].items()}}


def pieces(folder: Path, small: bool = False) -> tuple[dict, dict, dict]:
    """(seeds, bombs, hostile .db3 files) the grammar draws from, made once per run in `folder`."""
    seeds = make_seeds(folder)
    dbs = sqlite_variants(next(v for k, v in seeds["sqlite3"].items() if k.endswith(".db3")), folder)
    return seeds, make_bombs(small), dbs


def run(count: int, seed: int, hang: float, batch: int = 100, report: str | None = None, only: str | None = None,
        cli_every: int = 5, seconds: float | None = None, small: bool = False):
    r = random.Random(seed)
    with harness.Session("urdfcheck-fuzzrec-") as run_:
        seeds, bombs, dbs = pieces(run_.base / "seeds", small)
        do_one = do_one_factory(run_.base, run_.out, run_.marks, cli_every)

        def make(done: int, n: int) -> list:
            cases = []
            while len(cases) < n:
                c = generate(r, seeds, bombs, dbs, done + len(cases), small)
                if only is None or c["kind"].startswith(only):
                    cases.append(c)
            return cases

        run_.steps(count, 2000, seconds, report, make, do_one, hang, batch, show=show)
    return run_.result()


def main(argv=None) -> int:
    ap = harness.parser(__doc__, count=2000, seed=36, hang=15.0, batch=100)
    ap.add_argument("--only", help="only inputs whose kind starts with this (mutate, bomb, sqlite, symlink, ...)")
    ap.add_argument("--cli-every", type=int, default=5, help="every N-th input through the whole CLI (the others "
                    "call check_recording in-process, as `urdfcheck bag` does)")
    ns = ap.parse_args(argv)
    stats, examples, t0 = run(ns.count, ns.seed, ns.hang, ns.batch, ns.report, ns.only, max(ns.cli_every, 1),
                              seconds=ns.seconds)
    return harness.finish(stats, examples, t0, ns.report)


if __name__ == "__main__":
    sys.exit(main())
