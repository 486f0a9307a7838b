"""A Python launch file whose include path doubles a string variable after variable: reading it must stay
cheap (the evaluator remembers variables and has a step budget) and the include is simply not followed."""
import ast

from urdfcheck.consumers.launch import python as pylaunch
from urdfcheck.consumers.launch.xml import parse_launch


def _blowup(n=40, includes=50):
    lines = ['x0 = "ab"'] + [f"x{i} = x{i - 1} + x{i - 1}" for i in range(1, n)]
    lines += [f"i{k} = IncludeLaunchDescription(PythonLaunchDescriptionSource(x{n - 1}))" for k in range(includes)]
    return "\n".join(lines) + "\n"


def test_doubling_variables_are_evaluated_once_and_capped():
    text = _blowup()
    info = parse_launch(text.encode(), "/tmp/bringup.launch.py")
    assert len(info.includes) == 50 and all(i.file is None for i in info.includes)  # longer than any path
    r = pylaunch.PyLaunch("/tmp/bringup.launch.py", ast.parse(text), {}, lambda p: None)
    got = pylaunch.text_of(r.ev(ast.parse("x39", mode="eval").body))
    assert pylaunch.UNKNOWN in got and len(got) <= pylaunch._MAX_LEN
    assert r.steps < 200  # one evaluation per variable, not 2**39


def test_the_step_budget_ends_any_evaluation():
    # many distinct variables, each used once: the budget, not the depth, ends it
    text = ("\n".join(f'v{i} = "a"' for i in range(30_000))
            + "\nx = [" + ", ".join(f"v{i}" for i in range(30_000)) + "]\n")
    r = pylaunch.PyLaunch("/tmp/l.launch.py", ast.parse(text), {}, lambda p: None)
    got = r.ev(ast.parse("x", mode="eval").body)
    assert got is None or None in got
    assert r.steps <= pylaunch._MAX_STEPS + 30_002  # past the budget each piece costs one step, no more
