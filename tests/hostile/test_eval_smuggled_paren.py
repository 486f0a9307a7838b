"""Attack: `$(...)` ends at the first `)`, so the payload is smuggled in through a property; stock `$(eval)`
runs with the *real* builtins (exec, open, __import__ behind a string)."""
from hostile_arena import arena, assert_stock_executes, line_of  # noqa: F401 (fixture)


def test_eval_with_smuggled_payload_is_refused(arena):
    entry = arena.data("eval_smuggled_paren.urdf.xacro")
    assert_stock_executes(arena, entry)
    r = arena.lint(entry)
    # located where $(eval ...) is evaluated (xacro evaluates the property lazily, at its use)
    f = r.find("X011", entry.name, line_of(entry, "$(eval ${payload})"))
    assert "exec" in f["message"]
    assert r.codes() == ["X011"]


def test_eval_builtins_that_read_or_run_are_refused(arena):
    for i, payload in enumerate(["open('@OUTSIDE@/secret.txt').read()", "eval('1+1')", "compile('1', 'x', 'eval')",
                                 "globals()", "getattr(1, 'real')", "breakpoint()", "input()"]):
        p = arena.write(f"urdf/ev{i}.urdf.xacro",
                        '<robot name="v" xmlns:xacro="http://www.ros.org/wiki/xacro">\n'
                        f'  <xacro:property name="p" value="{payload}"/>\n  <link name="a"/>\n'
                        '  <link name="l_$(eval ${p})"/>\n</robot>\n')
        f = arena.lint(p).find("X011", p.name, 4)
        assert "not available" in f["message"] or "not allowed" in f["message"], (payload, f)
