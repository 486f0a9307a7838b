"""Attack: a list comprehension is its own code object, so the dunder chain inside it passes stock xacro's
guard; `__subclasses__()` finds os._wrap_close and its `__init__.__globals__['system']`."""
from hostile_arena import arena, assert_stock_executes, line_of  # noqa: F401 (fixture)


def test_comprehension_dunder_escape_is_refused(arena):
    entry = arena.data("comprehension.urdf.xacro")
    assert_stock_executes(arena, entry)
    r = arena.lint(entry)
    f = r.find("X011", entry.name, line_of(entry, "<link name=\"${[c.__init__"))
    assert "__" in f["message"] and "not allowed" in f["message"]
    assert r.codes() == ["X011"]


def test_dunder_names_anywhere_are_refused(arena):
    """The same guard holds at every nesting level and for every spelling the AST can take."""
    exprs = [
        "[x for x in [0] if x.__class__]",                 # in a condition
        "[(k, v.__class__) for k, v in [(1, 2)]]",         # tuple target (no braces: they end ${})
        "[[y.__dict__ for y in [x]] for x in [0]]",        # nested comprehension
        "(x.__class__ for x in [0])",                      # generator expression
        "__builtins__",                                    # bare name
        "python._setitem",                                 # a private method (one '_'), not a key
    ]
    body = "\n".join(f'  <link name="l{i}_${{{e}}}"/>' for i, e in enumerate(exprs))
    entry = arena.write("urdf/many.urdf.xacro", f'<robot name="v" xmlns:xacro="http://www.ros.org/wiki/xacro">\n'
                                               f'{body}\n</robot>\n')
    r = arena.lint(entry)
    # the first refused expression stops the expansion (as any xacro error does), at its own line
    f = r.find("X011", entry.name, 2)
    assert "not allowed" in f["message"]
    for i, e in enumerate(exprs):
        one = arena.write(f"urdf/one{i}.urdf.xacro", '<robot name="v" xmlns:xacro="http://www.ros.org/wiki/xacro">\n'
                                                    f'  <link name="a"/>\n  <link name="l_${{{e}}}"/>\n</robot>\n')
        arena.lint(one).find("X011", one.name, 3)
