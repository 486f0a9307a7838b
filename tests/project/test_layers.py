"""Data flows one way: a lower stage never imports a higher one (the layers contract in pyproject.toml,
[tool.importlinter]: core < model < load < consumers < rules < request < plan < finish < publisher, verify < bag <
run < diff < report < cli, pytest_plugin). Run by import-linter when installed, else by an equivalent check on the
modules' imports."""
from __future__ import annotations

import ast
import shutil
import subprocess
import sys
from pathlib import Path

REPO = Path(__file__).resolve().parents[2]
SRC = REPO / "src" / "urdfcheck"

# low to high; names on one row may import each other
LAYERS = [("core",), ("model",), ("load",), ("consumers",), ("rules",), ("request",), ("plan",), ("finish",),
          ("publisher", "verify"), ("bag",), ("run",), ("diff",), ("report",), ("cli", "pytest_plugin")]
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


def _module_name(path: Path) -> str:
    parts = ["urdfcheck", *path.relative_to(SRC).with_suffix("").parts]
    return ".".join(parts[:-1] if parts[-1] == "__init__" else parts)


def _import_graph() -> dict[str, dict[str, int]]:
    """module -> {imported urdfcheck module: line}, module-level and function-local imports alike (a
    function-local import that closes a cycle still ties the two modules together)."""
    paths = {_module_name(p): p for p in sorted(SRC.rglob("*.py"))}
    graph: dict[str, dict[str, int]] = {}
    for name, path in paths.items():
        out: dict[str, int] = {}
        tree = ast.parse(path.read_text(encoding="utf-8"), str(path))
        for node in ast.walk(tree):
            targets = []
            if isinstance(node, ast.Import):
                targets = [a.name for a in node.names if a.name in paths]
            elif isinstance(node, ast.ImportFrom) and node.module and node.level == 0:
                for a in node.names:  # `from urdfcheck.consumers.launch import python` imports the sub-module
                    sub = f"{node.module}.{a.name}"
                    targets.append(sub if sub in paths else node.module)
            for t in targets:
                if t in paths and t != name:
                    out.setdefault(t, node.lineno)
        graph[name] = out
    return graph


def _cycles(graph: dict[str, dict[str, int]]) -> list[list[str]]:
    """The strongly connected components of more than one module (Tarjan, iterative)."""
    index: dict[str, int] = {}
    low: dict[str, int] = {}
    stack: list[str] = []
    on: set[str] = set()
    out: list[list[str]] = []
    for start in graph:
        if start in index:
            continue
        work = [(start, iter(graph[start]))]
        index[start] = low[start] = len(index)
        stack.append(start)
        on.add(start)
        while work:
            v, it = work[-1]
            w = next(it, None)
            if w is not None:
                if w not in index:
                    index[w] = low[w] = len(index)
                    stack.append(w)
                    on.add(w)
                    work.append((w, iter(graph[w])))
                elif w in on:
                    low[v] = min(low[v], index[w])
                continue
            work.pop()
            if work:
                low[work[-1][0]] = min(low[work[-1][0]], low[v])
            if low[v] == index[v]:
                comp = []
                while True:
                    w = stack.pop()
                    on.discard(w)
                    comp.append(w)
                    if w == v:
                        break
                if len(comp) > 1:
                    out.append(sorted(comp))
    return out


def test_no_import_cycles():
    """No module imports (even inside a function) a module that imports it back, directly or through others:
    a shared piece belongs in a lower module both import."""
    graph = _import_graph()
    bad = []
    for comp in _cycles(graph):
        members = set(comp)
        edges = [f"  {a} -> {b} (line {line})" for a in comp for b, line in sorted(graph[a].items()) if b in members]
        bad.append("cycle: " + " <-> ".join(comp) + "\n" + "\n".join(edges))
    assert not bad, "\n".join(bad)


def test_cycle_check_sees_function_local_imports():
    """The check above is not vacuous: a two-module cycle closed by an import inside a function is found."""
    graph = {"urdfcheck.a": {"urdfcheck.b": 1}, "urdfcheck.b": {"urdfcheck.a": 9}, "urdfcheck.c": {"urdfcheck.a": 2}}
    assert _cycles(graph) == [["urdfcheck.a", "urdfcheck.b"]]
    assert _cycles({"urdfcheck.a": {"urdfcheck.b": 1}, "urdfcheck.b": {}}) == []
    tree_graph = _import_graph()
    # the real graph holds function-level edges too (plan.py imports deployments only inside a method)
    local = [(a, b) for a, deps in tree_graph.items() for b in deps
             if a == "urdfcheck.plan.plan" and b == "urdfcheck.plan.deployments"]
    assert local, "plan.plan imports plan.deployments inside a function; the graph must see it"
