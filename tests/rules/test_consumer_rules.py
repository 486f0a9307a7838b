"""Contract (C) and TF (T) rules are ordinary `@check` rules that need a model's consumers: the engine imports
them only for a model that can have consumers, and the scaffold writes them like any other rule."""
import subprocess
import sys
from pathlib import Path

from urdfcheck.rules import catalogue as rulebook
from urdfcheck.rules.scaffold import scaffold

REPO = Path(__file__).resolve().parents[2]
SRC = REPO / "src"


def test_every_contract_and_tf_rule_is_an_ordinary_check_that_needs_consumers():
    checks = rulebook.load_checks()
    for code, fn in checks.items():
        if code[0] in "CT":
            assert fn.__module__.startswith("urdfcheck.rules.checks."), (code, fn.__module__)
            want = "ros2_control" if code in ("C004", "C006") else "consumers"
            assert fn.needs == want, (code, fn.needs)
        else:
            assert fn.needs == "model", (code, fn.needs)


_PROBE = """
import sys
from urdfcheck.model.build import model_from_string
from urdfcheck.rules.engine import Context, run_checks
model = model_from_string('<robot name="r"><link name="base_link"/></robot>', path=sys.argv[1])
found = run_checks(model, Context())
print(sorted(m for m in sys.modules if m.startswith(("urdfcheck.rules.checks.", "urdfcheck.consumers."))))
"""


def _imported(tmp_path, model_path) -> str:
    proc = subprocess.run([sys.executable, "-c", _PROBE, str(model_path)], capture_output=True, text=True,
                          cwd=tmp_path, env={"PYTHONPATH": str(SRC), "PATH": "/usr/bin:/bin"})
    assert proc.returncode == 0, proc.stderr
    return proc.stdout


def test_a_lone_urdf_never_imports_the_consumer_rules(tmp_path):
    out = _imported(tmp_path, tmp_path / "robot.urdf")
    assert "urdfcheck.rules.checks.joints" in out
    for name in ("contracts", "tf", "claims", "navframes"):
        assert f"'urdfcheck.rules.checks.{name}'" not in out


def test_a_model_in_a_ros_package_runs_the_consumer_rules(tmp_path):
    (tmp_path / "package.xml").write_text("<package><name>bot</name></package>")
    (tmp_path / "urdf").mkdir()
    out = _imported(tmp_path, tmp_path / "urdf" / "robot.urdf")
    for name in ("contracts", "tf", "claims", "navframes"):
        assert f"'urdfcheck.rules.checks.{name}'" in out


def test_the_scaffold_makes_a_contract_rule_like_any_other(tmp_path):
    """One entry and one check module edited, for a C rule as for a J rule (plus the generated index)."""
    (tmp_path / "rules").mkdir()
    checks = tmp_path / "src" / "urdfcheck" / "rules" / "checks"
    (checks / "tf").mkdir(parents=True)
    for name in ("joints.py", "contracts.py", "tf/__init__.py"):
        (checks / name).write_text((SRC / "urdfcheck" / "rules" / "checks" / name).read_text())
    made = {code: scaffold(tmp_path, code, name, module) for code, name, module in (
        ("J099", "joint-thing", "joints"), ("C099", "controller-thing", "contracts"), ("T099", "tf-thing", "tf"))}
    assert {len(v) for v in made.values()} == {len(made["J099"])}
    contracts = (checks / "contracts.py").read_text()
    assert '@check("C099", needs="consumers")\ndef controller_thing(model: Model, ctx: Context)' in contracts
    assert '@check("T099", needs="consumers")' in (checks / "tf" / "__init__.py").read_text()
    assert '@check("J099")\ndef joint_thing' in (checks / "joints.py").read_text()
    for name in ("joints.py", "contracts.py", "tf/__init__.py"):
        compile((checks / name).read_text(), name, "exec")


def test_every_check_is_typed():
    """Each registered check says `(model: Model, ctx: Context) -> Iterator[Problem]` (or Iterable): mypy checks
    its body (tests/project/test_types.py)."""
    import inspect

    for code, fn in rulebook.load_checks().items():
        sig = inspect.signature(fn)
        params = [str(p.annotation) for p in sig.parameters.values()]
        assert params == ["Model", "Context"], (code, fn.__name__, params)
        assert str(sig.return_annotation) in ("Iterator[Problem]", "Iterable[Problem]"), (code, fn.__name__)
