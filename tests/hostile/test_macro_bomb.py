"""Attack: 1.2 KB of nested macros (nine levels, each calling the one below eight times: 134 million links)
that stock xacro grinds on for hours while memory grows."""
from hostile_arena import DATA, arena, line_of  # noqa: F401 (fixture)


def test_the_bomb_is_small():
    assert (DATA / "macro_bomb.urdf.xacro").stat().st_size < 1400


def test_macro_bomb_hits_the_expansion_limit_fast(arena):
    entry = arena.data("macro_bomb.urdf.xacro")
    r = arena.lint(entry)  # the harness bounds the wall time of the whole CLI call
    assert r.codes() == ["X012"], r.findings
    f = r.findings[0]
    assert "evaluated more than" in f["message"] and "elements" in f["message"], f  # the count, not the clock
    # located inside the bomb: the macro body that was expanding, via the chain of call sites
    loc = f["location"]
    assert loc["file"].endswith(entry.name) and loc["line"] is not None
    assert line_of(entry, '<xacro:macro name="a">') <= loc["line"] <= line_of(entry, "<xacro:j/>")


def test_bomb_with_nested_elements_hits_the_limit_too(arena):
    """Each level wraps its calls in an element (no huge sibling lists: the linear-cost variant)."""
    names = "abcdefghij"
    lines = ['<robot name="v" xmlns:xacro="http://www.ros.org/wiki/xacro">', '  <link name="base_link"/>',
             '  <xacro:macro name="a"><link name="x"/></xacro:macro>']
    for i in range(1, 10):
        lines.append(f'  <xacro:macro name="{names[i]}"><g>' + f"<xacro:{names[i - 1]}/>" * 8 + "</g></xacro:macro>")
    lines += ["  <xacro:j/>", "</robot>"]
    entry = arena.write("urdf/nested_bomb.urdf.xacro", "\n".join(lines) + "\n")
    r = arena.lint(entry)
    assert r.codes() == ["X012"], r.findings
