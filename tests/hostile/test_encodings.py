"""Attack (issue 11): a model saved as UTF-16 or UTF-32 was silently not linted: discovery did not see its root tag
(exit 2 "no model found", or the package's other models only), and a named UTF-16 xacro was taken for a library.
urdfdom (TinyXML2) reads UTF-8 only: every such model is an X001 finding that names the encoding; a UTF-8 byte-order
mark is read on, with an X003 warning."""
import pytest
from hostile_arena import arena  # noqa: F401 (fixture)

NS = 'xmlns:xacro="http://www.ros.org/wiki/xacro"'
URDF = '<?xml version="1.0"?>\n<robot name="r">\n  <link name="base_link"/>\n</robot>\n'
XACRO = f'<?xml version="1.0"?>\n<robot name="r" {NS}>\n  <link name="base_link"/>\n</robot>\n'
CODECS = {"utf-16": "UTF-16 (little-endian) with a byte-order mark", "utf-16-le": "UTF-16 (little-endian)",
          "utf-16-be": "UTF-16 (big-endian)", "utf-32": "UTF-32 (little-endian) with a byte-order mark",
          "utf-32-be": "UTF-32 (big-endian)"}


def _write(arena, rel, text, codec):
    p = arena.pkg / rel
    p.parent.mkdir(parents=True, exist_ok=True)
    p.write_bytes(text.encode(codec))
    return p


@pytest.mark.parametrize("codec", sorted(CODECS))
@pytest.mark.parametrize("name,text", [("robot.urdf", URDF), ("robot.urdf.xacro", XACRO)])
def test_foreign_encoding_is_a_finding_when_named(arena, codec, name, text):
    p = _write(arena, f"urdf/{name}", text, codec)
    r = arena.lint(p)
    f = r.find("X001", name, 1)
    assert CODECS[codec] in f["message"] and "UTF-8" in f["message"]


@pytest.mark.parametrize("codec", ["utf-16", "utf-32-be"])
def test_foreign_encoding_is_found_in_a_package(arena, codec):
    _write(arena, "urdf/robot.urdf.xacro", XACRO, codec)
    r = arena.lint(arena.pkg)  # not "no model found" (exit 2), not silently skipped
    r.find("X001", "robot.urdf.xacro", 1)


def test_utf8_bom_is_read_with_a_warning(arena):
    p = arena.pkg / "urdf" / "bom.urdf"
    p.write_bytes(b"\xef\xbb\xbf" + URDF.replace("<link name=\"base_link\"/>", "<link name=\"a\"/><link name=\"b\"/>")
                  .encode())
    r = arena.lint(p)
    assert "byte-order mark" in r.find("X003", "bom.urdf", 1)["message"]
    r.find("S001", "bom.urdf")  # and the model was linted


def test_included_file_in_utf16_is_a_finding_there(arena):
    _write(arena, "urdf/part.xacro", f'<robot {NS}>\n  <link name="arm"/>\n</robot>\n', "utf-16")
    entry = arena.write("urdf/main.urdf.xacro", f'<robot name="v" {NS}>\n  <link name="a"/>\n'
                                                '  <xacro:include filename="part.xacro"/>\n</robot>\n')
    r = arena.lint(entry)
    f = r.find("X001", "part.xacro", 1)
    assert "UTF-16" in f["message"]
