"""Attack: module globals leak between files linted in one process. File A redefines `pi` and mutates
xacro's shared `math` namespace; stock xacro hands the mutation to every later file (B computes with pi == 3).
urdfcheck expands each file in a forked worker: B always sees the real values, even when A ran --trusted."""
import math

from conftest import run_cli
from hostile_arena import arena, line_of  # noqa: F401 (fixture)

from urdfcheck.core import worker
from urdfcheck.load import loader

REAL = f"pi_{math.pi}_{math.pi}_{math.cos(math.pi)}"


def _stock_a_then_b(a, b):
    def run():
        import xacro

        try:
            xacro.process_file(str(a))
        except Exception:  # noqa: BLE001 - A's own result does not matter
            pass
        return xacro.process_file(str(b)).toprettyxml()

    return worker.run(run, timeout=30)


def test_stock_xacro_leaks_between_files(arena):
    a, b = arena.data("globals_a.urdf.xacro"), arena.data("globals_b.urdf.xacro")
    out = _stock_a_then_b(a, b)
    assert REAL not in out and "pi_3.14" in out and "_3_" in out, "control: stock xacro leaks A's math.pi into B"


def test_file_b_sees_the_real_globals(arena):
    a, b = arena.data("globals_a.urdf.xacro"), arena.data("globals_b.urdf.xacro")
    r = arena.lint(a, b)
    r.find("X011", a.name, line_of(a, "python.dict.update"))
    assert not [f for f in r.findings if f["location"]["file"].endswith(b.name) and f["code"].startswith("X")]
    # B, expanded after A in the same process, through the API and through the CLI
    assert loader.expand(a).root is None
    exp = loader.expand(b)
    assert exp.root is not None and REAL in exp.clean_text()
    code, out, err = run_cli(["expand", arena.rel(b)], cwd=arena.root)
    assert code == 0 and REAL in out, err


def test_isolation_holds_even_when_a_runs_unsandboxed(arena):
    a, b = arena.data("globals_a.urdf.xacro"), arena.data("globals_b.urdf.xacro")
    exp_a = loader.expand(a, trusted=True)  # stock eval: the mutation really runs, in the worker
    assert exp_a.root is not None and "m_None" in exp_a.clean_text()
    exp = loader.expand(b)
    assert REAL in exp.clean_text()
    exp = loader.expand(b, trusted=True)
    assert REAL in exp.clean_text()


def test_the_parent_process_never_imports_state_from_a_worker(arena):
    import xacro

    before = (dict(xacro._global_symbols["math"]), xacro.safe_eval, xacro.eval_all, xacro.parse)
    a = arena.data("globals_a.urdf.xacro")
    loader.expand(a, trusted=True)
    arena.lint(a)
    assert (dict(xacro._global_symbols["math"]), xacro.safe_eval, xacro.eval_all, xacro.parse) == before
