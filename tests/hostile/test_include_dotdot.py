"""Attack: a relative include climbing out of the package with `../`, directly or after `$(find pkg)`,
and through a symlink planted inside the package."""
import os

from hostile_arena import CANARY_FILE, arena, line_of, stock_xacro  # noqa: F401 (fixture)


def test_dotdot_include_escaping_the_package_is_refused(arena):
    entry = arena.data("include_dotdot.urdf.xacro")
    assert CANARY_FILE in stock_xacro(entry, arena.root), "control: stock xacro includes the secret"
    r = arena.lint(entry)
    f = r.find("X014", entry.name, line_of(entry, "xacro:include"))
    assert "outside the package roots" in f["message"]
    assert r.codes() == ["X014"]


def test_find_then_dotdot_is_refused(arena):
    entry = arena.data("include_find_dotdot.urdf.xacro")
    r = arena.lint(entry)
    r.find("X014", entry.name, line_of(entry, "xacro:include"))


def test_symlink_inside_the_package_pointing_outside_is_refused(arena):
    os.symlink(arena.outside / "secret.xacro", arena.pkg / "urdf" / "innocent.xacro")
    entry = arena.write("urdf/link.urdf.xacro", '<robot name="v" xmlns:xacro="http://www.ros.org/wiki/xacro">\n'
                        '  <link name="a"/>\n  <xacro:include filename="innocent.xacro"/>\n</robot>\n')
    r = arena.lint(entry)
    r.find("X014", entry.name, 3)
