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
