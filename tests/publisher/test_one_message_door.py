"""One door for JointState message lists (issue 42). The text of a joint-state file is read by one function,
`bag.source.text_items` (through core.door, bounded, YAML guarded), for `urdfcheck bag` and `urdfcheck publish`
alike; the keys of a message and its stamp are read by one module, `publisher.messages` (`fields`, `to_ns`).
`bag.source` had its own stamp reader and key lookup: a file written with `names:`/`positions:` was replayed by
`publish` but its joints were never named for `bag`. The scans fail on a second reader of either."""
from __future__ import annotations

import ast
from pathlib import Path

SRC = Path(__file__).resolve().parents[2] / "src" / "urdfcheck"
MESSAGE_KEYS = {"name", "names", "position", "positions", "velocity", "effort", "sec", "secs", "nanosec", "nsec",
                "nsecs"}
READS = {("json", "load"), ("json", "loads"), ("json", "JSONDecoder"), ("door", "read_bytes"), ("door", "read_text"),
         ("door", "open_stream")}


def _tree(rel):
    return ast.parse((SRC / rel).read_text(encoding="utf-8"))


def _message_modules():
    for folder in ("bag", "publisher", "cli"):
        for path in sorted((SRC / folder).glob("*.py")):
            yield path.relative_to(SRC).as_posix()


def test_only_publisher_messages_reads_message_keys():
    found = []
    for rel in _message_modules():
        if rel == "publisher/messages.py":
            continue
        for node in ast.walk(_tree(rel)):
            key = None
            if isinstance(node, ast.Call) and isinstance(node.func, ast.Attribute) and node.func.attr == "get" \
                    and node.args and isinstance(node.args[0], ast.Constant):
                key = node.args[0].value
            elif isinstance(node, ast.Subscript) and isinstance(node.ctx, ast.Load) \
                    and isinstance(node.slice, ast.Constant):
                key = node.slice.value
            if key in MESSAGE_KEYS and rel.startswith(("bag/source", "publisher/", "cli/publish")):
                found.append(f"{rel}:{node.lineno} reads the message key {key!r}")
    assert not found, found


def test_the_publish_command_reads_joint_states_through_the_recording_reader():
    tree = _tree("cli/publish.py")
    found = []
    for node in ast.walk(tree):
        if isinstance(node, ast.Call):
            f = node.func
            if isinstance(f, ast.Name) and f.id == "open":
                found.append(f"cli/publish.py:{node.lineno} open()")
            if isinstance(f, ast.Attribute) and isinstance(f.value, ast.Name) and (f.value.id, f.attr) in READS:
                found.append(f"cli/publish.py:{node.lineno} {f.value.id}.{f.attr}")
            if isinstance(f, ast.Attribute) and isinstance(f.value, ast.Name) and f.value.id == "yaml":
                found.append(f"cli/publish.py:{node.lineno} yaml.{f.attr}")
    calls = {getattr(n.func, "id", getattr(n.func, "attr", None)) for n in ast.walk(tree) if isinstance(n, ast.Call)}
    assert "text_items" in calls
    assert not found, found


def test_a_recording_and_publish_read_the_same_keys(tmp_path):
    """`names:`/`positions:` and a stamp in `nsec`: `publish` read them, the recording reader did not."""
    from urdfcheck.bag.source import _text_messages
    from urdfcheck.core import door
    from urdfcheck.publisher import JointState

    item = {"names": ["a", "b"], "positions": [0.5, 1.0], "stamp": {"sec": 2, "nsec": 5}}
    f = tmp_path / "states.json"
    import json

    f.write_text(json.dumps([item]))
    with door.guarded([str(tmp_path)], 1 << 24):
        (m,) = list(_text_messages(str(f), "/joint_states", (), []))
    js = JointState.from_dict(item)
    assert m.data.names == tuple(js.names) and m.data.position == tuple(js.positions)
    assert m.time_ns == js.stamp_ns == 2_000_000_005
