"""Attack: `${'a'*10**10}` allocates a 10 GB string (and then xacro writes it into the document)."""
from hostile_arena import arena, line_of  # noqa: F401 (fixture)


def test_huge_repetition_is_refused_before_allocating(arena):
    entry = arena.data("huge_repeat.urdf.xacro")
    r = arena.lint(entry)
    f = r.find("X011", entry.name, line_of(entry, "10**10"))
    assert "longer than" in f["message"]
    assert r.codes() == ["X011"]


def test_large_but_allowed_values_stay_bounded(arena):
    """Just under the evaluator's per-value limits, and multiplied by a macro: still a prompt finding."""
    for i, e in enumerate(["'a'*9999999", "'ab'.center(9999999)", "[0]*9999999", "'x'*5000000 + 'y'*4999999",
                           "' '.join(['a']*3000000)", "'%9999999d' % 1", "python.list(python.range(9999999))",
                           "len([1 for x in python.range(999999)])"]):
        p = arena.write(f"urdf/rep{i}.urdf.xacro",
                        '<robot name="v" xmlns:xacro="http://www.ros.org/wiki/xacro">\n  <link name="a"/>\n'
                        '  <xacro:macro name="m" params="k"><link name="l${k}_${' + e + '}"/></xacro:macro>\n'
                        + "".join(f'  <xacro:m k="{k}"/>\n' for k in range(8)) + "</robot>\n")
        r = arena.lint(p)
        assert r.findings, e
        assert r.codes()[0] in ("X011", "X012"), (e, r.findings)  # refused, or stopped by a budget
