"""Attack: a YAML alias bomb ("billion laughs" for YAML) pulled in with xacro.load_yaml."""
from hostile_arena import arena, line_of  # noqa: F401 (fixture)


def test_yaml_alias_bomb_is_refused(arena):
    yaml_file = arena.data("alias_bomb.yaml", "config/alias_bomb.yaml")
    entry = arena.data("yaml_alias_bomb.urdf.xacro")
    r = arena.lint(entry)
    assert r.codes() == ["X012"], r.findings
    f = r.findings[0]
    assert "alias" in f["message"]
    loc = f["location"]
    assert (loc["file"].endswith(entry.name) and loc["line"] == line_of(entry, "load_yaml(")) or \
        loc["file"].endswith(yaml_file.name), f


def test_deeply_nested_yaml_is_refused_fast(arena):
    """PyYAML's scanner is quadratic in flow depth: 5 000 levels took over a second before the RecursionError."""
    arena.write("config/deep.yaml", "a: " + "[" * 5000 + "]" * 5000 + "\n")
    entry = arena.write("urdf/deep.urdf.xacro", '<robot name="v" xmlns:xacro="http://www.ros.org/wiki/xacro">\n'
                        '  <link name="a"/>\n'
                        '  <link name="n_${len(str(xacro.load_yaml(\'../config/deep.yaml\')))}"/>\n</robot>\n')
    r = arena.lint(entry)
    f = r.find("X012", entry.name, 3)
    assert "deeper" in f["message"]


URDF = """<robot name="v">
  <link name="base_link"/>
  <link name="left_wheel"/>
  <joint name="left_wheel_joint" type="continuous"><parent link="base_link"/><child link="left_wheel"/>
    <axis xyz="0 1 0"/></joint>
</robot>
"""


def test_compact_yaml_nesting_in_a_controller_file_cannot_crash_the_linter(arena):
    """`? ? ? ... x` nests 60 000 levels in 120 KB: libyaml's recursive C composer overflowed the stack and the
    whole CLI died with SIGSEGV (no report at all). The contracts reader now counts the depth on the event stream."""
    arena.write("urdf/robot.urdf", URDF)
    bomb = arena.write("config/controllers.yaml", "? " * 60000 + "x\n")
    arena.write("config/other.yaml", "- ? " * 40000 + "x\n")
    r = arena.lint(arena.pkg)
    f = r.find("C007", bomb.name, 1)
    assert "nested deeper" in f["message"]


def test_yaml_alias_bomb_in_a_controller_file_is_refused(arena):
    arena.write("urdf/robot.urdf", URDF)
    bomb = arena.data("alias_bomb.yaml", "config/controllers.yaml")
    r = arena.lint(arena.pkg)
    assert any(f["code"] == "C007" and f["location"]["file"].endswith(bomb.name) for f in r.findings), r.findings


def test_compact_nesting_through_load_yaml_is_refused(arena):
    arena.write("config/deep.yaml", "? " * 60000 + "x\n")
    entry = arena.write("urdf/deep2.urdf.xacro", '<robot name="v" xmlns:xacro="http://www.ros.org/wiki/xacro">\n'
                        '  <link name="a"/>\n'
                        '  <link name="n_${len(str(xacro.load_yaml(\'../config/deep.yaml\')))}"/>\n</robot>\n')
    r = arena.lint(entry)
    f = r.find("X012", entry.name, 3)
    assert "deeper" in f["message"]
