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


def test_deeply_nested_yaml_is_refused_or_loaded_but_never_crashes(arena):
    arena.write("config/deep.yaml", "a: " + "[" * 5000 + "]" * 5000 + "\n")
    entry = arena.write("urdf/deep.urdf.xacro", '<robot name="v" xmlns:xacro="http://www.ros.org/wiki/xacro">\n'
                        '  <link name="a"/>\n'
                        '  <link name="n_${len(str(xacro.load_yaml(\'../config/deep.yaml\')))}"/>\n</robot>\n')
    r = arena.lint(entry)
    assert r.codes()[0] in ("X010", "X012"), r.findings
