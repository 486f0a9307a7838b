"""Recordings are untrusted input (issue 36): every file of one goes through core.door, and nothing in one can
hang the run, inflate without bound, run a query of the file's choosing or write to /tmp.

The cases that hung or blew up before run the real CLI in a subprocess with `--budget`: the subprocess time-out
is only a guard against a hang (the old code's failure), never a measurement."""
import json
import os
import sqlite3
import struct
import subprocess
import sys

import pytest
from bagwriter import write
from conftest import run_cli

pytest.importorskip("rosbags")

SRC = os.path.join(os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__)))), "src")
ARM = """<?xml version="1.0"?>
<robot name="arm">
  <link name="base_link"/><link name="upper_arm"/>
  <joint name="shoulder" type="revolute">
    <parent link="base_link"/><child link="upper_arm"/><origin xyz="0 0 0.1"/><axis xyz="0 0 1"/>
    <limit lower="-1.5" upper="1.5" effort="10" velocity="1"/>
  </joint>
</robot>
"""


def cli(tmp_path, recording, *extra, timeout=120, env=None):
    """The CLI in a subprocess (a hang is a failure, not a frozen test run): (exit code, JSON report)."""
    (tmp_path / "robot.urdf").write_text(ARM)
    e = dict(os.environ, PYTHONPATH=SRC + os.pathsep + os.environ.get("PYTHONPATH", ""))
    e.update(env or {})
    p = subprocess.run([sys.executable, "-m", "urdfcheck", "bag", "robot.urdf", str(recording), "--format", "json",
                        "--no-config", *extra], cwd=tmp_path, capture_output=True, text=True, timeout=timeout, env=e)
    assert p.returncode in (0, 1), p.stderr
    return p.returncode, json.loads(p.stdout)


def b014(report) -> str:
    msgs = [f["message"] for f in report["findings"] if f["code"] == "B014"]
    assert msgs, report["findings"]
    return " ".join(msgs)


# --- crafted containers --------------------------------------------------------------------------------------
def _s(text: str) -> bytes:
    b = text.encode()
    return struct.pack("<I", len(b)) + b


def _rec(op: int, body: bytes) -> bytes:
    return bytes([op]) + struct.pack("<Q", len(body)) + body


def _joint_state_cdr() -> bytes:
    import numpy as np
    from rosbags.typesys import Stores, get_typestore

    ts = get_typestore(Stores.ROS2_HUMBLE)
    T = ts.types
    msg = T["sensor_msgs/msg/JointState"](
        header=T["std_msgs/msg/Header"](stamp=T["builtin_interfaces/msg/Time"](sec=1, nanosec=0), frame_id=""),
        name=["shoulder"], position=np.array([0.1]), velocity=np.array([], dtype=float),
        effort=np.array([], dtype=float))
    return bytes(ts.serialize_cdr(msg, "sensor_msgs/msg/JointState"))


def mcap(chunks: list[bytes]) -> bytes:
    out = b"\x89MCAP0\r\n" + _rec(0x01, _s("ros2") + _s("test"))
    out += b"".join(chunks)
    out += _rec(0x0F, struct.pack("<I", 0)) + _rec(0x02, struct.pack("<QQI", 0, 0, 0)) + b"\x89MCAP0\r\n"
    return out


def mcap_chunk(records: bytes, compression: str, declared: int | None = None) -> bytes:
    if compression == "zstd":
        from backports import zstd

        data = zstd.compress(records)
    else:
        data = records
    size = len(records) if declared is None else declared
    return _rec(0x06, struct.pack("<QQQI", 0, 0, size, 0) + _s(compression) + struct.pack("<Q", len(data)) + data)


def mcap_channel() -> bytes:
    return (_rec(0x03, struct.pack("<H", 1) + _s("sensor_msgs/msg/JointState") + _s("ros2msg") + _s(""))
            + _rec(0x04, struct.pack("<HH", 1, 1) + _s("/joint_states") + _s("cdr") + struct.pack("<I", 0)))


def mcap_message(payload: bytes, t: int = 1) -> bytes:
    return _rec(0x05, struct.pack("<HIQQ", 1, 0, t, t) + payload)


def test_mcap_zstd_chunk_declaring_1kb_is_refused_not_inflated(tmp_path):
    bomb = mcap_chunk(b"\0" * (300 * 1024**2), "zstd", declared=1024)  # 300 MB of zeros, ~10 KB on disk
    (tmp_path / "bomb.mcap").write_bytes(mcap([bomb]))
    code, report = cli(tmp_path, "bomb.mcap")
    assert code == 1 and "declared size" in b014(report)


def test_mcap_of_a_million_messages_stops_at_the_budget(tmp_path):
    one = mcap_message(_joint_state_cdr())
    chunk = mcap_chunk(mcap_channel() + one * 1_000_000, "zstd")  # ~30 KB on disk
    (tmp_path / "many.mcap").write_bytes(mcap([chunk]))
    assert (tmp_path / "many.mcap").stat().st_size < 200_000
    code, report = cli(tmp_path, "many.mcap", "--budget", "2")
    assert code == 1 and "time budget" in b014(report)


def test_ros1_lz4_chunk_bomb_is_refused(tmp_path):
    import lz4.frame

    def record(fields: dict, data: bytes) -> bytes:
        head = b"".join(struct.pack("<I", len(k) + 1 + len(v)) + k.encode() + b"=" + v for k, v in fields.items())
        return struct.pack("<I", len(head)) + head + struct.pack("<I", len(data)) + data

    header = record({"op": b"\x03", "index_pos": struct.pack("<Q", 0), "conn_count": struct.pack("<I", 0),
                     "chunk_count": struct.pack("<I", 1)}, b" " * 64)
    chunk = record({"op": b"\x05", "compression": b"lz4", "size": struct.pack("<I", 1024)},
                   lz4.frame.compress(b"\0" * (64 * 1024**2)))
    (tmp_path / "bomb.bag").write_bytes(b"#ROSBAG V2.0\n" + header + chunk)
    code, report = cli(tmp_path, "bomb.bag")
    assert code == 1 and "declared size" in b014(report)


def test_ros2_message_compression_bomb_is_refused_and_nothing_goes_to_tmp(tmp_path):
    from backports import zstd

    payload = zstd.compress(b"\0" * (200 * 1024**2))  # one "message", 200 MB inflated
    chunk = mcap_chunk(mcap_channel() + mcap_message(payload), "")
    (tmp_path / "msg.mcap").write_bytes(mcap([chunk]))
    tmp = tmp_path / "tmpdir"
    tmp.mkdir()
    code, report = cli(tmp_path, "msg.mcap", env={"TMPDIR": str(tmp)})
    assert code == 1 and "decompression bomb" in b014(report)
    assert not list(tmp.iterdir())


def test_ros2_file_compression_is_read_in_memory_and_bounded(tmp_path):
    from backports import zstd

    folder = write(tmp_path / "rec", "mcap", [("js", 1.0 + i / 50, ["shoulder"], [0.1]) for i in range(20)])
    (mc,) = [p for p in folder.iterdir() if p.suffix == ".mcap"]
    (folder / (mc.name + ".zstd")).write_bytes(zstd.compress(mc.read_bytes()))
    mc.unlink()
    meta = (folder / "metadata.yaml").read_text()
    meta = meta.replace(f"- {mc.name}\n", f"- {mc.name}.zstd\n").replace(
        "compression_mode: ''", "compression_mode: FILE").replace("compression_format: ''", "compression_format: zstd")
    assert "compression_format: zstd" in meta and "compression_mode: FILE" in meta
    (folder / "metadata.yaml").write_text(meta)
    tmp = tmp_path / "tmpdir"
    tmp.mkdir()
    code, report = cli(tmp_path, "rec", env={"TMPDIR": str(tmp)})
    assert code == 0, report["findings"]  # 20 clean JointStates read from the compressed file
    assert not list(tmp.iterdir())
    (folder / (mc.name + ".zstd")).write_bytes(zstd.compress(b"\x89MCAP0\r\n" + b"\0" * (400 * 1024**2)))
    code, report = cli(tmp_path, "rec", env={"TMPDIR": str(tmp)})
    assert code == 1 and b014(report)
    assert not list(tmp.iterdir())


# --- sqlite3 -------------------------------------------------------------------------------------------------
def _db3_folder(tmp_path, make):
    """A rosbag2 folder (metadata.yaml from rosbags' writer) whose .db3 is replaced by `make(connection)`."""
    folder = write(tmp_path / "rec", "sqlite3", [("js", 1.0, ["shoulder"], [0.1])])
    (db,) = [p for p in folder.iterdir() if p.suffix == ".db3"]
    db.unlink()
    con = sqlite3.connect(db)
    make(con)
    con.commit()
    con.close()
    return folder


TOPICS = ("CREATE TABLE topics(id INTEGER PRIMARY KEY, name TEXT, type TEXT, serialization_format TEXT, "
          "offered_qos_profiles TEXT, type_description_hash TEXT)")
ENDLESS = "WITH RECURSIVE c(x) AS (SELECT 1 UNION ALL SELECT x + 1 FROM c) SELECT count(*) FROM c"


def test_db3_schema_view_over_an_endless_query_is_refused(tmp_path):
    def make(con):
        con.execute(TOPICS)
        con.execute("CREATE TABLE messages(id INTEGER PRIMARY KEY, topic_id INTEGER, timestamp INTEGER, data BLOB)")
        con.execute(f"CREATE VIEW schema AS SELECT ({ENDLESS}) AS schema_version, 'humble' AS ros_distro")

    folder = _db3_folder(tmp_path, make)
    code, report = cli(tmp_path, folder.name, "--budget", "3")
    assert code == 1 and "view" in b014(report)


def test_db3_messages_view_and_generated_blob_are_refused(tmp_path):
    def view(con):
        con.execute(TOPICS)
        con.execute("INSERT INTO topics VALUES (1, '/joint_states', 'sensor_msgs/msg/JointState', 'cdr', '', '')")
        con.execute(f"CREATE VIEW messages AS SELECT 1 AS id, 1 AS topic_id, ({ENDLESS}) AS timestamp, "
                    "x'00' AS data")

    code, report = cli(tmp_path, _db3_folder(tmp_path, view).name, "--budget", "3")
    assert code == 1 and "view" in b014(report)

    def generated(con):
        con.execute(TOPICS)
        con.execute("INSERT INTO topics VALUES (1, '/joint_states', 'sensor_msgs/msg/JointState', 'cdr', '', '')")
        con.execute("CREATE TABLE messages(id INTEGER PRIMARY KEY, topic_id INTEGER, timestamp INTEGER, "
                    "data BLOB GENERATED ALWAYS AS (zeroblob(700000000)) VIRTUAL)")
        con.execute("INSERT INTO messages(id, topic_id, timestamp) VALUES (1, 1, 1)")

    import shutil

    shutil.rmtree(tmp_path / "rec")
    code, report = cli(tmp_path, _db3_folder(tmp_path, generated).name, "--budget", "3")
    assert code == 1 and "generated" in b014(report)


def test_fifo_inside_a_bag_folder_is_refused_not_waited_on(tmp_path):
    folder = write(tmp_path / "rec", "sqlite3", [("js", 1.0, ["shoulder"], [0.1])])
    (db,) = [p for p in folder.iterdir() if p.suffix == ".db3"]
    db.unlink()
    os.mkfifo(db)
    code, report = cli(tmp_path, folder.name, "--budget", "3")
    assert code == 1 and "regular file" in b014(report)


# --- text recordings -----------------------------------------------------------------------------------------
BOMB = "a: &a [x, x, x, x, x, x, x, x, x]\n" + "".join(
    f"{c}: &{c} [*{p}, *{p}, *{p}, *{p}, *{p}, *{p}, *{p}, *{p}, *{p}]\n"
    for p, c in zip("abcdefgh", "bcdefghi"))


def test_yaml_alias_bomb_recording_is_refused(tmp_path):
    (tmp_path / "bomb.yaml").write_text(BOMB)
    assert len(BOMB) < 700
    code, report = cli(tmp_path, "bomb.yaml", "--budget", "5")
    assert code == 1 and "bomb" in b014(report)


def test_large_json_recording_is_streamed_not_parsed_whole(tmp_path):
    """60 MB of JSON messages, read within a memory budget (300 MiB) below what parsing it whole takes (~700 MB)."""
    one = json.dumps({"name": ["shoulder"] * 100, "position": [0.5] * 100, "stamp": 1.0}, separators=(",", ":"))
    n = 60_000_000 // (len(one) + 2)
    with open(tmp_path / "big.json", "w") as f:
        f.write("[")
        for i in range(n):
            f.write(("," if i else "") + one.replace('"stamp":1.0', f'"stamp":{1 + i / 100}'))
        f.write("]")
    code, report = cli(tmp_path, "big.json", timeout=600, env={"URDFCHECK_RUN_BUDGET": "600:300"})
    codes = {f["code"] for f in report["findings"]}
    assert "X017" not in codes and "B014" not in codes, report["findings"]


# --- the door ------------------------------------------------------------------------------------------------
def _model():
    from urdfcheck.model.build import model_from_string

    return model_from_string(ARM)


def _messages(found):
    return [(f.code, f.message) for f in found]


def test_links_out_of_the_checkout_inside_a_recording_folder_are_refused(tmp_path):
    from urdfcheck.bag import check_recording
    from urdfcheck.core import door

    outside = tmp_path / "outside"
    checkout = tmp_path / "checkout"
    checkout.mkdir()
    secret = write(outside, "sqlite3", [("js", 1.0, ["secret_joint_name"], [0.1])])
    (secret_db,) = [p for p in secret.iterdir() if p.suffix == ".db3"]
    folder = write(checkout / "rec", "sqlite3", [("js", 1.0, ["shoulder"], [0.1])])
    (db,) = [p for p in folder.iterdir() if p.suffix == ".db3"]
    db.unlink()
    db.symlink_to(secret_db)
    with door.guarded([checkout]):
        for runner in (False, True):  # named by the config, or typed by the runner: the inside is the checkout's
            found = check_recording(_model(), str(folder), runner=runner)
            assert [f.code for f in found] == ["B014"], _messages(found)
            assert "outside the checkout" in found[0].message and "secret_joint_name" not in found[0].message
            assert str(tmp_path) not in found[0].message
    (folder / "metadata.yaml").unlink()
    (folder / "metadata.yaml").symlink_to(secret / "metadata.yaml")
    with door.guarded([checkout]):
        found = check_recording(_model(), str(folder / "metadata.yaml"), runner=True)
        assert [f.code for f in found] == ["B014"] and "outside the checkout" in found[0].message


def test_a_runner_typed_folder_outside_the_checkout_is_read(tmp_path):
    from urdfcheck.bag import check_recording
    from urdfcheck.core import door

    checkout = tmp_path / "checkout"
    checkout.mkdir()
    folder = write(tmp_path / "data" / "rec", "sqlite3", [("js", 1.0, ["wrist"], [0.1])])
    with door.guarded([checkout]):
        found = check_recording(_model(), str(folder), runner=True)
        assert "B001" in {f.code for f in found}, _messages(found)  # read: the runner named it
    with door.guarded([checkout]):
        found = check_recording(_model(), str(folder), runner=False)  # a config cannot name it
        assert [f.code for f in found] == ["B014"], _messages(found)


def test_a_runner_typed_recording_linked_out_of_the_checkout_is_refused(tmp_path):
    from urdfcheck.bag import check_recording
    from urdfcheck.core import door

    checkout = tmp_path / "checkout"
    checkout.mkdir()
    (tmp_path / "creds.yaml").write_text("- {name: [aws_secret_key_is_here], position: [1], stamp: 1}\n")
    (checkout / "ref.yaml").symlink_to(tmp_path / "creds.yaml")
    with door.guarded([checkout]):
        found = check_recording(_model(), str(checkout / "ref.yaml"), runner=True)
    assert [f.code for f in found] == ["B014"] and "aws_secret" not in found[0].message
    # typed outside the checkout, the same file is the runner's own choice
    with door.guarded([checkout]):
        found = check_recording(_model(), str(tmp_path / "creds.yaml"), runner=True)
    assert "B001" in {f.code for f in found}


def test_publish_joint_states_fifo_and_bomb_are_usage_errors(tmp_path):
    (tmp_path / "robot.urdf").write_text(ARM)
    os.mkfifo(tmp_path / "pipe.yaml")
    code, _, err = run_cli(["publish", "robot.urdf", "--joint-states", "pipe.yaml"], cwd=tmp_path)
    assert code == 2 and "regular file" in err
    (tmp_path / "bomb.yaml").write_text(BOMB)
    code, _, err = run_cli(["publish", "robot.urdf", "--joint-states", "bomb.yaml"], cwd=tmp_path)
    assert code == 2 and "bomb" in err


@pytest.mark.parametrize("fmt", ["ros1", "sqlite3", "mcap", "yaml"])
def test_recordings_are_read_only_through_the_door(fmt, tmp_path, monkeypatch):
    """No reader of a recording opens a file by itself: `open` is gone while it reads; sqlite3 is handed the
    door's admitted path, read-only and immutable."""
    import builtins
    from pathlib import Path

    from urdfcheck.bag import check_recording

    if fmt == "yaml":
        rec = tmp_path / "rec.yaml"
        rec.write_text("- {name: [shoulder], position: [0.1], stamp: 1.0}\n")
    else:
        rec = write(tmp_path / "rec", fmt, [("js", 1.0 + i / 50, ["shoulder"], [0.1]) for i in range(5)])
    model = _model()
    check_recording(model, str(rec))  # once before: the modules it imports lazily are imported (that is open())
    connects = []
    real_connect = sqlite3.connect

    def connect(database, *a, **kw):
        connects.append((str(database), kw.get("uri")))
        return real_connect(database, *a, **kw)

    def no_open(*a, **kw):
        raise AssertionError(f"a direct open() of {a[:1]}")

    monkeypatch.setattr(sqlite3, "connect", connect)
    monkeypatch.setattr(builtins, "open", no_open)  # (the door's own os.fdopen goes through io.open)
    for name in ("open", "read_bytes", "read_text"):
        monkeypatch.setattr(Path, name, no_open)
    found = check_recording(model, str(rec))
    monkeypatch.undo()
    assert not found, _messages(found)
    for database, uri in connects:
        assert uri and database.startswith("file:") and database.endswith("?mode=ro&immutable=1"), database
    assert bool(connects) == (fmt == "sqlite3")
