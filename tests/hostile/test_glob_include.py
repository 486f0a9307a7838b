"""Attack: `<xacro:include filename="/*/*/*.xacro"/>` or `../../../outside/*.xacro`: stock xacro globs the pattern as
written, walking the runner's file system, and the refusal of the first match named a file outside the package.
Here the folder a pattern starts from must lie inside the package roots (nothing outside is listed), every match too,
and refusals name the pattern as written, relative, never an absolute path."""
import pytest
from hostile_arena import arena, line_of  # noqa: F401 (fixture)

NS = 'xmlns:xacro="http://www.ros.org/wiki/xacro"'


@pytest.mark.parametrize("pattern", ["../../../outside/*.xacro", "/*/*/*.xacro", "../*/../../../outside/secret.xacro",
                                     "$(find @PKG@)/../../outside/*", "../../../out*/secret.xacro",
                                     "/tm?/*", "/e[t]c/passw?"])
def test_glob_include_outside_is_refused_without_listing_it(arena, pattern):
    entry = arena.write("urdf/g.urdf.xacro", f'<robot name="v" {NS}>\n  <link name="a"/>\n'
                                             f'  <xacro:include filename="{pattern}"/>\n</robot>\n')
    r = arena.lint(entry)  # the arena's audit fails the test if anything under outside/ was listed or opened
    f = r.find("X014", entry.name, 3)
    assert "outside the package roots" in f["message"]
    assert str(arena.root) not in r.out


def test_glob_include_inside_the_package_works(arena):
    for name in ("a", "b"):
        arena.write(f"urdf/parts/{name}.xacro", f'<robot {NS}>\n  <link name="part_{name}"/>\n</robot>\n')
    entry = arena.write("urdf/ok.urdf.xacro", f'<robot name="v" {NS}>\n  <link name="base_link"/>\n'
                                              '  <xacro:include filename="parts/*.xacro"/>\n'
                                              '  <joint name="ja" type="fixed"><parent link="base_link"/>'
                                              '<child link="part_a"/></joint>\n'
                                              '  <joint name="jb" type="fixed"><parent link="base_link"/>'
                                              '<child link="part_b"/></joint>\n</robot>\n')
    r = arena.lint(entry, extra=["--select", "X,S"], expect_code=0)
    assert r.findings == []


def test_abs_filename_hands_out_no_runner_path(arena):
    arena.write("urdf/cfg.yaml", "name: from_yaml\n")
    entry = arena.write("urdf/p.urdf.xacro",
                        f'<robot name="v" {NS}>\n  <link name="a"/>\n'
                        '  <link name="${xacro.abs_filename(\'cfg.yaml\')}"/>\n'
                        '  <link name="${xacro.load_yaml(xacro.abs_filename(\'cfg.yaml\')).name}"/>\n'
                        '</robot>\n')
    for target in (entry, str(entry)):  # a relative and an absolute entry path
        r = arena.lint(target, extra=["--select", "X,S001"])
        assert str(arena.root) not in r.out
        assert "from_yaml" in r.out and "cfg.yaml" in r.out  # load_yaml(abs_filename(x)) still works
