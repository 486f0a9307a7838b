"""Attack: a DOCTYPE with entities. Billion laughs expands 1 KB into gigabytes; an external entity
(`SYSTEM "file:///etc/passwd"`) copies a file into the model. Stock tools disagree (lxml/yourdfpy recover an
empty robot, Pinocchio/TinyXML do not expand entities), so the linter and the robot could see different
documents: urdfcheck refuses any DOCTYPE, in a .urdf, in a .xacro and in a file a xacro includes."""
import pytest
from hostile_arena import arena, formats, line_of  # noqa: F401 (fixture)


@pytest.mark.parametrize("name", ["billion_laughs.urdf", "xxe.urdf", "billion_laughs.urdf.xacro", "xxe.urdf.xacro"])
def test_doctype_is_refused_at_its_line(arena, name):
    entry = arena.data(name)
    r = arena.lint(entry)
    f = r.find("X002", entry.name, line_of(entry, "<!DOCTYPE"))
    assert "DOCTYPE" in f["message"]
    assert r.codes() == ["X002"]


def test_doctype_in_an_included_xacro_is_refused_there(arena):
    part = arena.data("xxe_part.xacro", "urdf/parts/xxe_part.xacro")
    entry = arena.data("includes_xxe.urdf.xacro")
    for fmt in formats():
        arena.lint(entry, fmt=fmt)
    r = arena.lint(entry)
    assert r.codes() == ["X002"], r.findings
    # reported in the included file, at its DOCTYPE (the include line is where it came from)
    r.find("X002", part.name, line_of(part, "<!DOCTYPE"))


def test_doctype_smuggled_through_the_expansion_is_refused(arena):
    """A DOCTYPE cannot come out of xacro either: text that *looks* like one stays escaped text."""
    entry = arena.write("urdf/smuggle.urdf.xacro",
                        '<robot name="v" xmlns:xacro="http://www.ros.org/wiki/xacro">\n'
                        '  <link name="a"/>\n'
                        '  <link name="${\'&lt;!DOCTYPE x [&lt;!ENTITY e SYSTEM &quot;file:///etc/passwd&quot;&gt;]&gt;\'}"/>\n'
                        '</robot>\n')
    r = arena.lint(entry)  # a weird link name (disconnected), never an entity expansion
    assert "X002" not in r.codes()


def test_undeclared_entity_and_parameter_entities_are_refused(arena):
    for i, text in enumerate([
        '<robot name="v">\n  <link name="&undeclared;"/>\n</robot>\n',
        '<?xml version="1.0"?>\n<!DOCTYPE robot [<!ENTITY % p SYSTEM "file:///etc/passwd"> %p;]>\n<robot name="v"/>\n',
        '<?xml version="1.0"?>\n<!DOCTYPE robot SYSTEM "http://example.invalid/evil.dtd">\n<robot name="v"/>\n',
    ]):
        p = arena.write(f"urdf/ent{i}.urdf", text)
        r = arena.lint(p)
        assert r.codes() and r.codes()[0] in ("X001", "X002"), (text, r.findings)
        assert r.findings[0]["location"]["line"] == (2 if i == 0 else 2), (text, r.findings)
