"""Attack: `xacro.load_yaml('/etc/passwd')` or with `../` reads files outside the package into the model."""
import pytest
from hostile_arena import CANARY_FILE, PASSWD_MARK, arena, formats, line_of, stock_xacro  # noqa: F401 (fixture)


def test_load_yaml_etc_passwd_is_refused(arena):
    entry = arena.data("load_yaml_passwd.urdf.xacro")
    assert PASSWD_MARK in stock_xacro(entry, arena.root), "control: stock xacro reads /etc/passwd"
    for fmt in formats():
        arena.lint(entry, fmt=fmt)
    r = arena.lint(entry)
    f = r.find("X014", entry.name, line_of(entry, "load_yaml("))
    assert "outside the package roots" in f["message"]
    assert r.codes() == ["X014"]


@pytest.mark.parametrize("name", ["load_yaml_dotdot.urdf.xacro", "load_yaml_deprecated.urdf.xacro"])
def test_load_yaml_outside_the_package_is_refused(arena, name):
    entry = arena.data(name)
    assert CANARY_FILE in stock_xacro(entry, arena.root), "control: stock xacro reads the secret"
    r = arena.lint(entry)
    f = r.find("X014", entry.name, line_of(entry, "load_yaml("))
    assert "outside the package roots" in f["message"]


def test_load_yaml_inside_the_package_still_works(arena):
    arena.write("config/ok.yaml", "name: arm\n")
    entry = arena.write("urdf/ok.urdf.xacro", '<robot name="v" xmlns:xacro="http://www.ros.org/wiki/xacro">\n'
                        '  <link name="${xacro.load_yaml(\'../config/ok.yaml\').name}"/>\n</robot>\n')
    r = arena.lint(entry, extra=["--select", "X"], expect_code=0)
    assert r.findings == []
