"""Attack: `${10**10**8}` makes Python compute a 330-million-bit integer (minutes of CPU, then str())."""
from hostile_arena import arena, line_of  # noqa: F401 (fixture)


def test_huge_power_is_refused_before_computing(arena):
    entry = arena.data("huge_power.urdf.xacro")
    r = arena.lint(entry)
    f = r.find("X011", entry.name, line_of(entry, "10**10**8"))
    assert "exponent too large" in f["message"]
    assert r.codes() == ["X011"]


def test_other_big_integer_spellings_are_refused(arena):
    for i, e in enumerate(["2**2**30", "1&lt;&lt;(1&lt;&lt;40)", "math.factorial(10**6)", "math.comb(10**7, 10**6)",
                           "9**9**9", "int('9'*4000)**500",
                           "round(1, -10**8)", "python.sum([2**90000]*600000)", "math.prod(python.range(1, 10**6))"]):
        p = arena.write(f"urdf/big{i}.urdf.xacro", '<robot name="v" xmlns:xacro="http://www.ros.org/wiki/xacro">\n'
                                                  f'  <link name="a"/>\n  <link name="l_${{{e}}}"/>\n</robot>\n')
        r = arena.lint(p)
        assert r.codes() == ["X011"], (e, r.findings)
        assert r.findings[0]["location"]["line"] == 3, (e, r.findings)
