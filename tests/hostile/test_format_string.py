"""Attack: `'{0.__globals__[os].environ[VAR]}'.format(fn)` walks attributes named inside a *string*, so no
dunder name reaches stock xacro's guard; the secret environment variable ends up in the model."""
from hostile_arena import CANARY_ENV, arena, formats, line_of, stock_xacro  # noqa: F401 (fixture)


def test_format_attribute_access_is_refused_and_leaks_nothing(arena):
    entry = arena.data("format_string.urdf.xacro")
    assert CANARY_ENV in stock_xacro(entry, arena.root), "control: stock xacro leaks the variable"
    for fmt in formats():  # the secret is in no output format
        r = arena.lint(entry, fmt=fmt)
    r = arena.lint(entry)
    f = r.find("X011", entry.name, line_of(entry, "${template.format("))
    assert "attribute or index access" in f["message"]
    assert r.codes() == ["X011"]


def test_other_format_spellings_are_refused(arena):
    cases = {
        "format_map": '<xacro:property name="t" value="{x.__class__}"/>\n  <link name="l_${t.format_map(dict(x=1))}"/>',
        "index": '<xacro:property name="t" value="{0[__globals__]}"/>\n  <link name="l_${t.format(xacro.dotify)}"/>',
        "percent_width": '<link name="l_${\'%99999999999d\' % 1}"/>',
    }
    for name, body in cases.items():
        p = arena.write(f"urdf/{name}.urdf.xacro", '<robot name="v" xmlns:xacro="http://www.ros.org/wiki/xacro">\n'
                                                   f'  <link name="a"/>\n  {body}\n</robot>\n')
        r = arena.lint(p)
        assert r.codes() == ["X011"], (name, r.findings)
        assert r.findings[0]["location"]["line"] == 3 + body.count("\n"), (name, r.findings)
