"""Attack: no dunder *name* at all. `python.vars(python.type(f))['__globals__']` is a getset descriptor;
`vars(type(d))['__get__'](d, f)` returns the function's module globals, and `['os'].system` runs a command."""
from hostile_arena import arena, assert_stock_executes, line_of  # noqa: F401 (fixture)


def test_vars_type_chain_is_refused(arena):
    entry = arena.data("python_vars_type.urdf.xacro")
    assert_stock_executes(arena, entry)
    r = arena.lint(entry)
    f = r.find("X011", entry.name, line_of(entry, "${python.vars("))
    assert "python.vars" in f["message"] or "python.type" in f["message"]
    assert r.codes() == ["X011"]


def test_type_and_vars_reached_indirectly_are_refused(arena):
    """Not spelled `python.type(...)`: fetched through a subscript, a property or a comprehension."""
    exprs = ["python['type'](1)", "[f for f in [python.vars]][0](math)", "python.get('vars')(math)",
             "python.dict.get(python, 'type')(1).mro()", "python.map(python.type, [1])"]
    for i, e in enumerate(exprs):
        p = arena.write(f"urdf/ind{i}.urdf.xacro", '<robot name="v" xmlns:xacro="http://www.ros.org/wiki/xacro">\n'
                                                  f'  <link name="a"/>\n  <link name="l_${{{e}}}"/>\n</robot>\n')
        f = arena.lint(p).find("X011", p.name, 3)
        assert "not allowed" in f["message"], (e, f)
