"""Attack: a pull request commits a named pipe (FIFO) where the linter reads a file. `open()` of a FIFO blocks until a
writer appears, forever in CI: as an entry model found by discovery (.urdf / .xacro), an explicitly named model, a
xacro include, a `xacro.load_yaml` file, a controller YAML (config/*.yaml) or a launch file.

Every read of a checkout file checks that it is a regular file and opens it non-blocking (core/safeio.py): the
FIFO is a finding (or is skipped where it is no model), and the run ends quickly."""
import os
import signal

import pytest
from hostile_arena import arena, line_of  # noqa: F401 (fixture)

pytestmark = pytest.mark.skipif(not hasattr(os, "mkfifo"), reason="needs named pipes")

NS = 'xmlns:xacro="http://www.ros.org/wiki/xacro"'
GOOD = '<robot name="v">\n  <link name="base_link"/>\n</robot>\n'


@pytest.fixture(autouse=True)
def no_hang():
    """A regression hangs in open(): fail the test after 20 s instead of hanging the suite."""
    def alarm(signum, frame):
        raise TimeoutError("blocked reading a FIFO")

    old = signal.signal(signal.SIGALRM, alarm)
    signal.alarm(20)
    yield
    signal.alarm(0)
    signal.signal(signal.SIGALRM, old)


def fifo(arena, rel):
    p = arena.pkg / rel
    p.parent.mkdir(parents=True, exist_ok=True)
    os.mkfifo(p)
    return p


@pytest.mark.parametrize("rel", ["urdf/pipe.urdf", "urdf/pipe.urdf.xacro"])
def test_fifo_model_in_a_package_does_not_block_discovery(arena, rel):
    arena.write("urdf/robot.urdf", GOOD.replace("<robot", "<robot").replace("</robot>", '  <link name="x"/>\n</robot>'))
    fifo(arena, rel)
    r = arena.lint(arena.pkg)  # the good model has two roots: exit 1 with that finding; the FIFO is no model
    assert "S001" in r.codes()


@pytest.mark.parametrize("name", ["pipe.urdf", "pipe.urdf.xacro"])
def test_fifo_named_as_the_model_is_a_finding(arena, name):
    p = fifo(arena, f"urdf/{name}")
    r = arena.lint(p)
    f = r.find("X001", name)
    assert "not a regular file" in f["message"] and "named pipe" in f["message"]


def test_fifo_include_is_a_finding_at_the_include(arena):
    fifo(arena, "urdf/part.xacro")
    entry = arena.write("urdf/inc.urdf.xacro", f'<robot name="v" {NS}>\n  <link name="a"/>\n'
                                               '  <xacro:include filename="part.xacro"/>\n</robot>\n')
    r = arena.lint(entry)
    f = r.find("X010", entry.name, 3)
    assert "not a regular file" in f["message"]


def test_fifo_load_yaml_is_a_finding(arena):
    fifo(arena, "config/pipe.yaml")
    entry = arena.write("urdf/y.urdf.xacro", f'<robot name="v" {NS}>\n  <link name="a"/>\n'
                                             '  <link name="${xacro.load_yaml(\'../config/pipe.yaml\').x}"/>\n'
                                             '</robot>\n')
    r = arena.lint(entry)
    f = r.find("X010", entry.name, 3)
    assert "not a regular file" in f["message"]


@pytest.mark.parametrize("rel", ["config/controllers.yaml", "launch/bringup.launch.xml", "launch/bringup.launch.py",
                                 "launch/robot.launch"])
def test_fifo_consumer_files_do_not_block(arena, rel):
    arena.write("urdf/robot.urdf", '<robot name="v">\n  <link name="base_link"/>\n  <link name="x"/>\n</robot>\n')
    fifo(arena, rel)
    r = arena.lint(arena.pkg)
    assert "S001" in r.codes()


def test_read_file_refuses_every_special_file(tmp_path):
    from urdfcheck.core.safeio import NotRegularFile, read_file

    p = tmp_path / "pipe"
    os.mkfifo(p)
    for path, kind in [(p, "named pipe"), ("/dev/null", "character device"), (tmp_path, "folder")]:
        with pytest.raises(NotRegularFile) as info:
            read_file(path, 10)
        assert kind in info.value.strerror
    f = tmp_path / "f"
    f.write_bytes(b"x" * 100)
    assert read_file(f, 10) == b"x" * 11  # the cap plus one: callers tell "too large" from "exactly the cap"
    assert read_file(f, 1000) == b"x" * 100
