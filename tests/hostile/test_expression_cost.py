"""Attack: per-expression limits multiplied. Each `${...}` is bounded on its own (iterations, sizes, bits), but
a loop over a big operand (`s.find` on a 1 MB string, `divmod` of 100 000-bit integers, `==` of two 1 MB
strings) costs far more than its iteration count says, and macros repeat expressions. One budget per expansion
charges iterations *and* the size of the operands touched."""
import pytest
from hostile_arena import arena  # noqa: F401 (fixture)

LOOPS = [
    "[s.find('x') for i in python.range(400000)]",
    "[s.upper() for i in python.range(400000)]",
    "[python.divmod(b, 3**10000) for i in python.range(400000)]",
    "[s == t for i in python.range(400000)]",
    "[math.factorial(5000) for i in python.range(400000)]",
    "[3**60000 for i in python.range(400000)]",
    "[s[1:] for i in python.range(400000)]",
    "[python.str(L) for i in python.range(400000)]",
    "python.sum([2**99000]*499999)",
    "[python.sorted(L) for i in python.range(40000)]",
    "[python.hash(s+'x') for i in python.range(400000)]",
]


@pytest.mark.parametrize("loop", LOOPS)
def test_loops_over_big_operands_hit_the_expansion_budget(arena, loop):
    entry = arena.write("urdf/cost.urdf.xacro",
                        '<robot name="v" xmlns:xacro="http://www.ros.org/wiki/xacro">\n'
                        '  <xacro:property name="s" value="${\'a\'*999999}"/>\n'
                        '  <xacro:property name="t" value="${\'a\'*999999}"/>\n'
                        '  <xacro:property name="L" value="${[0]*300000}"/>\n'
                        '  <xacro:property name="b" value="${2**99000}"/>\n'
                        '  <link name="a"/>\n'
                        f'  <link name="l_${{len({loop})}}"/>\n</robot>\n')
    r = arena.lint(entry)
    f = r.find("X011", entry.name, 7)
    assert "in total" in f["message"] or "too large" in f["message"], f


def test_many_cheap_expressions_share_one_budget(arena):
    """A cheap loop in a macro called a hundred times: each call is fine, together they are refused."""
    entry = arena.write("urdf/many.urdf.xacro",
                        '<robot name="v" xmlns:xacro="http://www.ros.org/wiki/xacro">\n  <link name="a"/>\n'
                        '  <xacro:macro name="m" params="k">'
                        '<link name="l${k}_${len([1 for x in python.range(99999)])}"/></xacro:macro>\n'
                        + "".join(f'  <xacro:m k="{k}"/>\n' for k in range(100)) + "</robot>\n")
    r = arena.lint(entry)
    f = r.find("X011", entry.name, 3)
    assert "in total" in f["message"]
    call = f["location"]["via"][0]["line"] - 3  # the k-th call, counted from 1
    assert 3 <= call <= 6, f  # a handful of calls fit in the budget, the rest are never evaluated
