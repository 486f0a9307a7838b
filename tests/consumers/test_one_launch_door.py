"""One entry point for launch files (consumers.launch.xml.parse_launch, issue 42). The deployment finder read
launch files with its own read, its own Python parse and its own call of the Python reader, beside
`read_launch`: a refusal made in one (a ValueError, a size cap, a package finder) was missed in the other. The scan
fails when a module outside the door reads launch content itself."""
from __future__ import annotations

import ast
from pathlib import Path

import pytest

SRC = Path(__file__).resolve().parents[2] / "src" / "urdfcheck"
DOOR = "consumers/launch/xml.py"
READERS = {"consumers.launch.python": {"read"}, "consumers.launch.xml": {"_parse", "_read_python", "_XmlReader",
                                                                         "_YamlReader", "MAX_BYTES"}}


def _imports(tree):
    """(local name, module, attribute) for each `from urdfcheck.consumers.launch[.x] import y [as z]`."""
    for node in ast.walk(tree):
        if isinstance(node, ast.ImportFrom) and node.module and node.module.startswith("urdfcheck."):
            mod = node.module[len("urdfcheck."):]
            for a in node.names:
                yield a.asname or a.name, mod, a.name


def test_only_the_door_reads_launch_content():
    found = []
    for path in sorted(SRC.rglob("*.py")):
        rel = path.relative_to(SRC).as_posix()
        if rel == DOOR:
            continue
        tree = ast.parse(path.read_text(encoding="utf-8"))
        modules = {}  # local name -> module, for `from urdfcheck.consumers.launch import python as pylaunch`
        for local, mod, name in _imports(tree):
            if f"{mod}.{name}" in READERS:
                modules[local] = f"{mod}.{name}"
            elif name in READERS.get(mod, ()):
                found.append(f"{rel}: imports {name} from {mod}")
        for node in ast.walk(tree):
            if isinstance(node, ast.Call) and isinstance(node.func, ast.Attribute) \
                    and isinstance(node.func.value, ast.Name) and node.func.value.id in modules \
                    and node.func.attr in READERS[modules[node.func.value.id]]:
                found.append(f"{rel}:{node.lineno} {node.func.value.id}.{node.func.attr}() outside the launch door")
    assert not found, found


@pytest.mark.parametrize("text, message", [
    (b"def f(:\n", "Python syntax error"),
    (b"\xff\xfe", "not valid UTF-8"),
])
def test_the_deployment_finder_and_the_consumers_say_the_same(tmp_path, text, message):
    """The finder said "Python launch file not readable" where the consumers said why, and where."""
    from urdfcheck.consumers.common import ConsumerError
    from urdfcheck.consumers.launch.xml import read_launch
    from urdfcheck.core import door
    from urdfcheck.plan.deployments import _Workspace

    f = tmp_path / "bot.launch.py"
    f.write_bytes(text)
    with door.guarded([str(tmp_path)], 1 << 24):
        with pytest.raises(ConsumerError) as e:
            read_launch(str(f))
        got = _Workspace(str(tmp_path), None, None).read(str(f), {})
    assert isinstance(got, ConsumerError) and message in e.value.message
    assert (got.message, got.location) == (e.value.message, e.value.location)
