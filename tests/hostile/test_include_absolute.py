"""Attack: `<xacro:include filename="/abs/path"/>` reads any XML file on the runner into the model."""
from hostile_arena import CANARY_FILE, arena, formats, line_of, stock_xacro  # noqa: F401 (fixture)


def test_absolute_include_outside_the_package_is_refused(arena):
    entry = arena.data("include_absolute.urdf.xacro")
    assert CANARY_FILE in stock_xacro(entry, arena.root), "control: stock xacro includes the secret"
    for fmt in formats():
        arena.lint(entry, fmt=fmt)
    r = arena.lint(entry)
    f = r.find("X014", entry.name, line_of(entry, "xacro:include"))
    assert "outside the package roots" in f["message"]
    assert r.codes() == ["X014"]


def test_absolute_include_of_system_files_is_refused(arena):
    for i, target in enumerate(["/etc/passwd", "/proc/self/environ", "/dev/zero", "/dev/stdin"]):
        entry = arena.write(f"urdf/abs{i}.urdf.xacro", '<robot name="v" xmlns:xacro="http://www.ros.org/wiki/xacro">\n'
                            f'  <link name="a"/>\n  <xacro:include filename="{target}"/>\n</robot>\n')
        r = arena.lint(entry, forbid_extra=["/dev/zero", "/dev/stdin"])
        f = r.find("X014", entry.name, 3)
        assert "outside the package roots" in f["message"], (target, f)


def test_include_inside_the_package_still_works(arena):
    arena.write("urdf/parts/arm.xacro", '<robot xmlns:xacro="http://www.ros.org/wiki/xacro">\n'
                '  <link name="arm"/>\n</robot>\n')
    entry = arena.write("urdf/ok.urdf.xacro", '<robot name="v" xmlns:xacro="http://www.ros.org/wiki/xacro">\n'
                        '  <xacro:include filename="$(find @PKG@)/urdf/parts/arm.xacro"/>\n'
                        '  <xacro:include filename="parts/arm.xacro"/>\n</robot>\n')
    r = arena.lint(entry, extra=["--select", "X"], expect_code=0)
    assert r.findings == []
