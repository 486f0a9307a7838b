"""The harness itself: its audit really sees what happens in the forked xacro worker. With --trusted (stock
eval, no confinement: for one's own files only) the payloads run, and the checks that guard every attack test
must fail loudly."""
import pytest
from hostile_arena import arena  # noqa: F401 (fixture)


def test_audit_records_a_command_run_inside_the_worker(arena, tmp_path):
    elsewhere = tmp_path / "elsewhere" / "PWNED"  # outside the arena: only the audit hook can notice
    elsewhere.parent.mkdir()
    entry = arena.data("lambda.urdf.xacro")
    entry.write_text(entry.read_text().replace(str(arena.marker), str(elsewhere)))
    with pytest.raises(AssertionError) as e:
        arena.lint(entry, extra=["--trusted"])
    assert elsewhere.exists(), "control: --trusted runs stock eval"
    assert "audit" in str(e.value) and "os.system" in str(e.value) and "touch" in str(e.value)


def test_audit_records_a_read_outside_the_package(arena):
    entry = arena.write("urdf/x.urdf.xacro", '<robot name="v" xmlns:xacro="http://www.ros.org/wiki/xacro">\n'
                        '  <link name="a"/>\n'
                        '  <link name="${len(xacro.load_yaml(\'@OUTSIDE@/secret.yaml\').keys())}"/>\n</robot>\n')
    with pytest.raises(AssertionError) as e:
        arena.lint(entry, extra=["--trusted"])
    assert "audit" in str(e.value) and "secret.yaml" in str(e.value)


def test_marker_and_leak_checks_fire(arena):
    entry = arena.data("lambda.urdf.xacro")
    with pytest.raises(AssertionError, match="code execution"):
        arena.lint(entry, extra=["--trusted"])
    arena.marker.unlink()
    entry = arena.data("env.urdf.xacro")
    with pytest.raises(AssertionError, match="leaked"):
        arena.lint(entry, extra=["--trusted"])


def test_only_the_bytecode_cache_is_exempt(tmp_path):
    """The import system's .pyc writes (a module first imported during a lint, bytecode writing on) are not
    counted; any other folder made or file renamed is."""
    from hostile_arena import _bytecode_cache

    cache = tmp_path / "pkg" / "__pycache__"
    assert _bytecode_cache("os.mkdir", (str(cache), 0o777, -1))
    pyc = str(cache / "m.cpython-311.pyc")
    assert _bytecode_cache("os.rename", (pyc + ".123", pyc, -1, -1))
    assert not _bytecode_cache("os.mkdir", (str(tmp_path / "pkg" / "evil"), 0o777, -1))
    assert not _bytecode_cache("os.rename", (str(cache / "m.pyc.1"), str(tmp_path / "pkg" / "m.pyc"), -1, -1))
    assert not _bytecode_cache("os.rename", (str(tmp_path / "a.txt"), str(tmp_path / "b.txt"), -1, -1))
    assert not _bytecode_cache("os.remove", (str(cache / "m.cpython-311.pyc"), -1))
