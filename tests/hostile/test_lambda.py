"""Attack: a lambda hides its dunder chain from stock xacro's `__` name guard and reaches os.system."""
from hostile_arena import arena, assert_stock_executes, line_of  # noqa: F401 (fixture)


def test_lambda_is_refused_and_never_runs(arena):
    entry = arena.data("lambda.urdf.xacro")
    assert_stock_executes(arena, entry)
    r = arena.lint(entry)
    f = r.find("X011", entry.name, line_of(entry, "${(lambda:"))
    assert "lambda" in f["message"]
    assert r.codes() == ["X011"]
