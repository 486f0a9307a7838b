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


def test_entry_model_that_is_a_symlink_out_of_the_workspace_is_not_read(arena):
    """A pull request can commit `urdf/robot.urdf -> /some/runner/file`: linting the named file (or the
    package) must not read the target and copy its names into the report."""
    (arena.outside / "secret.urdf").write_text(
        f'<robot name="{CANARY_FILE}">\n  <link name="{CANARY_FILE}"/>\n  <link name="{CANARY_FILE}_2"/>\n</robot>\n')
    for name in ("robot.urdf", "robot.urdf.xacro"):
        link = arena.pkg / "urdf" / name
        os.symlink(arena.outside / "secret.urdf", link)
        r = arena.lint(link)
        f = r.find("X014", name)
        assert "symbolic link" in f["message"]
        assert r.codes() == ["X014"]
        r = arena.lint(arena.pkg)
        assert r.codes() == ["X014"], r.findings
        link.unlink()


def _sibling_link(arena):
    other = arena.ws / "other_description"
    (other / "urdf").mkdir(parents=True)
    (other / "package.xml").write_text("<package format='3'><name>other_description</name></package>\n")
    (other / "urdf" / "arm.urdf").write_text('<robot name="arm">\n  <link name="a"/>\n  <link name="b"/>\n</robot>\n')
    os.symlink(other / "urdf" / "arm.urdf", arena.pkg / "urdf" / "arm.urdf")


def test_symlink_to_a_sibling_package_is_still_linted(arena):
    """In one repository (.git above both), the sibling package is inside the checkout and is linted."""
    (arena.ws / ".git").mkdir()
    _sibling_link(arena)
    r = arena.lint(arena.pkg / "urdf" / "arm.urdf")
    assert "X014" not in r.codes() and "S001" in r.codes(), r.findings


def test_symlink_to_a_sibling_package_outside_the_checkout_is_named(arena):
    """Without a repository around them the checkout is the package: the sibling lies outside, and the link is
    named (X014), never silently dropped (issue 36: the one door)."""
    _sibling_link(arena)
    r = arena.lint(arena.pkg / "urdf" / "arm.urdf")
    assert r.codes() == ["X014"], r.findings
