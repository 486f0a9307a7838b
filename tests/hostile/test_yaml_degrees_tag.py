"""Attack: the `!degrees`/`!radians` constructors that xacro.load_yaml registers feed the scalar to xacro's
eval, so a plain-looking .yaml file runs code when a model loads it."""
from hostile_arena import arena, assert_stock_executes, line_of  # noqa: F401 (fixture)


def test_degrees_tag_payload_is_refused(arena):
    yaml_file = arena.data("evil_angles.yaml", "config/evil_angles.yaml")
    entry = arena.data("yaml_degrees.urdf.xacro")
    assert_stock_executes(arena, entry)
    r = arena.lint(entry)
    assert r.codes() == ["X011"], r.findings
    # at the payload's own line in the YAML file, via the model line that loads it
    f = r.find("X011", yaml_file.name, line_of(yaml_file, "joint_limit: !degrees"))
    assert [v["line"] for v in f["location"]["via"]] == [line_of(entry, "limits.joint_limit")]
    assert f["location"]["via"][0]["file"].endswith(entry.name)
    assert "not allowed" in f["message"]


def test_units_tags_still_work_for_honest_yaml(arena):
    arena.write("config/limits.yaml", "upper: !degrees 90\nlower: !radians -pi/2\nlength: !millimeters 250\n")
    entry = arena.write("urdf/ok.urdf.xacro", '<robot name="v" xmlns:xacro="http://www.ros.org/wiki/xacro">\n'
                        '  <xacro:property name="c" value="${xacro.load_yaml(\'../config/limits.yaml\')}"/>\n'
                        '  <link name="a"/>\n  <link name="b"/>\n'
                        '  <joint name="j" type="revolute"><parent link="a"/><child link="b"/>'
                        '<axis xyz="0 0 1"/><limit lower="${c.lower}" upper="${c.upper}" effort="1" velocity="1"/>'
                        '</joint>\n</robot>\n')
    r = arena.lint(entry, extra=["--select", "X,U,J"], expect_code=0)
    assert r.findings == []
