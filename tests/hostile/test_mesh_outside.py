"""Attack: mesh URIs that leave the package (`../../../etc/passwd`, `file:///etc/passwd`,
`package://pkg/../../..`). yourdfpy reads them; urdfcheck must neither read nor stat them (the harness's audit
hook and os.stat wrapper check the parent and the worker) and says they are outside the package roots."""
from hostile_arena import arena, formats, line_of  # noqa: F401 (fixture)


def test_meshes_outside_the_package_are_not_touched(arena):
    entry = arena.data("mesh_outside.urdf")
    r = arena.lint(entry, forbid_extra=["/etc"])
    g = [f for f in r.findings if f["code"] == "G001"]
    for needle in ["../../../../../../../../etc/passwd", "file:///etc/passwd", "/../../outside/secret.txt",
                   "/outside/secret.txt\""]:
        line = line_of(entry, needle)
        hit = [f for f in g if f["location"]["line"] == line]
        assert hit, (needle, line, g)
        assert "outside the package roots" in hit[0]["message"], hit
    assert not [f for f in g if f["location"]["line"] == line_of(entry, "meshes/base.stl")]
    for fmt in formats():
        arena.lint(entry, fmt=fmt, forbid_extra=["/etc"])


def test_mesh_through_a_planted_symlink_is_outside(arena):
    import os

    os.symlink(arena.outside, arena.pkg / "meshes" / "shared")
    entry = arena.write("urdf/sym.urdf", '<robot name="v">\n  <link name="a">\n    <visual><geometry>'
                        '<mesh filename="package://@PKG@/meshes/shared/secret.txt"/></geometry></visual>\n'
                        "  </link>\n</robot>\n")
    r = arena.lint(entry)
    f = r.find("G001", entry.name, 3)
    assert "outside the package roots" in f["message"]


def test_mesh_in_a_xacro_is_checked_the_same_way(arena):
    entry = arena.write("urdf/m.urdf.xacro", '<robot name="v" xmlns:xacro="http://www.ros.org/wiki/xacro">\n'
                        '  <xacro:macro name="part" params="uri"><link name="p"><visual><geometry>'
                        '<mesh filename="${uri}"/></geometry></visual></link></xacro:macro>\n'
                        '  <xacro:part uri="file:///etc/passwd"/>\n</robot>\n')
    r = arena.lint(entry, forbid_extra=["/etc"])
    f = r.find("G001", entry.name, 2)
    assert "outside the package roots" in f["message"]
    assert [v["line"] for v in f["location"].get("via", [])] == [3]
