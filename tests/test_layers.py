"""Data flows one way: a lower stage never imports a higher one (the layers contract in pyproject.toml,
[tool.importlinter]: core < model < load < rules, contracts < publisher, verify < pipeline < report < cli,
pytest_plugin). Run by import-linter when installed, else by an equivalent check on the modules' imports."""
from __future__ import annotations

import ast
import shutil
import subprocess
import sys
from pathlib import Path

REPO = Path(__file__).resolve().parent.parent
SRC = REPO / "src" / "urdfcheck"

# low to high; names on one row may import each other
LAYERS = [("core",), ("model",), ("load",), ("rules", "contracts"), ("publisher", "verify"), ("pipeline",),
          ("report",), ("cli", "pytest_plugin")]
RANK = {name: i for i, row in enumerate(LAYERS) for name in row}


def _lint_imports() -> str | None:
    exe = Path(sys.executable).parent / "lint-imports"
    return str(exe) if exe.is_file() else shutil.which("lint-imports")


def test_import_linter_contract_is_kept():
    exe = _lint_imports()
    if exe is None:  # the AST check below covers the same rule
        import pytest

        pytest.skip("import-linter not installed")
    proc = subprocess.run([exe, "--config", str(REPO / "pyproject.toml")], cwd=REPO, capture_output=True,
                          text=True, timeout=300, env={"PYTHONPATH": str(REPO / "src"), "PATH": "/usr/bin:/bin"})
    assert proc.returncode == 0, proc.stdout[-3000:] + proc.stderr[-2000:]


def _imports(path: Path):
    """(line, imported urdfcheck module) for every import in the file, function-local ones included."""
    tree = ast.parse(path.read_text(encoding="utf-8"), str(path))
    for node in ast.walk(tree):
        if isinstance(node, ast.Import):
            for a in node.names:
                yield node.lineno, a.name
        elif isinstance(node, ast.ImportFrom) and node.module and node.level == 0:
            yield node.lineno, node.module
            for a in node.names:  # `from urdfcheck import report` names a sub-package
                yield node.lineno, f"{node.module}.{a.name}"


def _layer(module: str) -> str | None:
    parts = module.split(".")
    if parts[0] != "urdfcheck" or len(parts) < 2:
        return None
    return parts[1] if parts[1] in RANK else None


def test_no_module_imports_a_higher_layer():
    bad = []
    for path in sorted(SRC.rglob("*.py")):
        rel = path.relative_to(SRC)
        own = rel.parts[0].removesuffix(".py")
        if own not in RANK:
            continue  # __init__ (the public API) and __main__ sit on top
        for line, module in _imports(path):
            other = _layer(module)
            if other is not None and RANK[other] > RANK[own]:
                bad.append(f"src/urdfcheck/{rel}:{line}: {own} imports {module} ({other} is a higher layer)")
    assert not bad, "\n".join(bad)
