"""Attack: `$(env VAR)`, `$(optenv VAR)`, `$(cwd)` (and env() inside `$(eval)`) copy the CI runner's secrets
and paths into the model, and from there into reports and artefacts."""
import pytest
from hostile_arena import CANARY_ENV, CANARY_VAR, arena, formats, line_of, stock_xacro  # noqa: F401 (fixture)


@pytest.mark.parametrize("name,needle", [("env.urdf.xacro", "$(env "),
                                         ("eval_env.urdf.xacro", "$(eval ${read_secret})")])
def test_environment_access_is_refused(arena, name, needle):
    entry = arena.data(name)
    assert CANARY_ENV in stock_xacro(entry, arena.root), "control: stock xacro copies the secret"
    for fmt in formats():
        arena.lint(entry, fmt=fmt)
    r = arena.lint(entry)
    f = r.find("X015", entry.name, line_of(entry, needle))
    assert CANARY_VAR in f["message"] and "allow-listed" in f["message"]
    assert r.codes() == ["X015"]


def test_optenv_gives_its_default_never_the_environment(arena):
    entry = arena.data("optenv.urdf.xacro")
    assert CANARY_ENV in stock_xacro(entry, arena.root), "control: stock xacro copies the secret"
    for fmt in formats():
        assert CANARY_ENV not in arena.lint(entry, fmt=fmt).out
    r = arena.lint(entry)
    assert "X015" not in r.codes()  # $(optenv VAR fallback) is "fallback" in the sandbox


def test_cwd_is_refused(arena):
    entry = arena.data("cwd.urdf.xacro")
    assert str(arena.root) in stock_xacro(entry, arena.root), "control: stock xacro copies the runner's path"
    r = arena.lint(entry)
    assert str(arena.root) not in r.out
    f = r.find("X015", entry.name, line_of(entry, "$(cwd)"))
    assert "$(cwd)" in f["message"]
    assert r.codes() == ["X015"]


def test_allow_listed_variable_is_read_but_others_are_not(arena, monkeypatch):
    monkeypatch.setenv("ROBOT_PREFIX", "left_")
    entry = arena.write("urdf/allowed.urdf.xacro",
                        '<robot name="v" xmlns:xacro="http://www.ros.org/wiki/xacro">\n'
                        '  <link name="$(env ROBOT_PREFIX)base"/>\n'
                        f'  <link name="$(optenv {CANARY_VAR} x)"/>\n</robot>\n')
    r = arena.lint(entry, extra=["--allow-env", "ROBOT_PREFIX"])
    assert "X015" not in r.codes() and CANARY_ENV not in r.out  # optenv: its default, the variable is not read
    entry = arena.write("urdf/allowed_env.urdf.xacro",
                        '<robot name="v" xmlns:xacro="http://www.ros.org/wiki/xacro">\n'
                        '  <link name="$(env ROBOT_PREFIX)base"/>\n'
                        f'  <link name="$(env {CANARY_VAR})"/>\n</robot>\n')
    r = arena.lint(entry, extra=["--allow-env", "ROBOT_PREFIX"])
    f = r.find("X015", entry.name, 3)
    assert CANARY_VAR in f["message"]
