"""Move src/urdfcheck into folders in data order (issue 24), rewriting every reference to the moved modules.

    python tools/relayout.py [--dry-run] [--repo PATH]

Run it from a clean checkout after merging; it `git mv`s the files, then rewrites:
  * imports, absolute and relative (`from urdfcheck.pipeline import run as pipeline`,
    `from urdfcheck.contracts.launch import X`, `from . import x`), splitting a `from PKG import a, b` whose
    names now live in different packages;
  * dotted module paths in strings and prose (`"urdfcheck.pipeline.run._dedupe"`, `pipeline.plan.Target`)
    and file paths (`contracts/yamlsrc.py`) in src/, tests/, bench/, fuzz/, docs/, .ci/, *.md and pyproject.toml;
  * the import-linter layers in pyproject.toml and tests/test_layers.py, and docs/design.md's folder picture
    (generated from the moved tree: one line per module).
A module under contracts/ or pipeline/ that this script does not know (added after it was written) is mapped
by its name, else by its folder, and the guess is printed. Hatch needs nothing: the wheel packages
`src/urdfcheck` whole and the catalogue is `rules/` at the repository root.

Data order is the folder order; the import layers are not quite the same order, because the first stages use
services of later ones: the request checks rule codes against the catalogue (rules), the planner reads launch
files (consumers) and resolves packages (load). Those are imports of pure readers, never of a later stage's
results, and the layers contract keeps them one way.
"""
from __future__ import annotations

import argparse
import ast
import re
import subprocess
import sys
from pathlib import Path

# old module (below urdfcheck) -> new module
KNOWN = {
    "pipeline.request": "request.request",
    "pipeline.config": "request.config",
    "pipeline.schemagate": "request.schemagate",
    "pipeline.plan": "plan.plan",
    "pipeline.deployments": "plan.deployments",
    "contracts.consumers": "consumers.consumers",
    "contracts.common": "consumers.common",
    "contracts.yamlsrc": "consumers.yamlsrc",
    "contracts.params": "consumers.params",
    "contracts.controllers": "consumers.controllers",
    "contracts.localization": "consumers.localization",
    "contracts.graph": "consumers.graph",
    "contracts.launch": "consumers.launch.xml",
    "contracts.pylaunch": "consumers.launch.python",
    "contracts.pyinclude": "consumers.launch.include",
    "contracts.launchinfo": "consumers.launch.info",
    "contracts.launchparams": "consumers.launch.params",
    # discovery of entry models and consumer files: the consumers' readers and the planner both use it
    "contracts.discover": "load.discover",
    "contracts.registry": "rules.checks.contracts",
    "contracts.rules_impl": "rules.contracts.impl",
    "contracts.wheels": "rules.contracts.wheels",
    "pipeline.baseline": "finish.baseline",
    "pipeline.collapse": "finish.collapse",
    "pipeline.run": "run",
    # added in wave 3 by other branches, placed by what they import
    "pipeline.trust": "request.trust",
    "pipeline.variants": "load.variants",  # the config (variants: auto) and the planner both read it
    "pipeline.dependents": "plan.dependents",
    "pipeline.robots": "plan.robots",
    "pipeline.understood": "plan.understood",
    "pipeline.unread": "plan.unread",
    "pipeline.diff": "diff.compare",  # two loaded models compared: a stage above run, beside the reports
    "pipeline.gitside": "diff.gitside",
    "contracts.catalog": "consumers.catalog",
    "contracts.uses": "consumers.uses",
    "contracts.gazebo": "consumers.gazebo",
    "contracts.openworld": "consumers.openworld",
    "contracts.prefilter": "consumers.prefilter",
    "contracts.drives": "rules.contracts.drives",  # wheel sets measured on the model, beside wheels
}
GONE = ("contracts", "pipeline")  # packages emptied by the move (their __init__.py is deleted)
NEW_PACKAGES = ("request", "plan", "consumers", "consumers.launch", "finish", "rules.contracts", "diff")
PACKAGE_DOCS = {
    "request": "The request: flags, API arguments and config files merged once (`make_request`, `Settings`).",
    "plan": "Planning: a request becomes targets (models, variants, deployments from launch files).",
    "consumers": "Readers of what consumes a model (parameter, controller, driver, localization files, launch\n"
                 "files), read statically: nothing here imports or runs user code.",
    "consumers.launch": "Launch files, one reader per format: XML/YAML (`xml`), Python via `ast` (`python`,\n"
                        "`include`), the records they share (`info`), the parameters they set (`params`).",
    "finish": "The finish stage: one finding per problem (`collapse`), the baseline.",
    "diff": "`urdfcheck diff`: two revisions of a description planned and loaded like `lint`, then compared.",
    "rules.contracts": "The bodies of the contract (C) and TF-ownership (T) checks, imported on first use by\n"
                       "`rules.checks.contracts`.",
}
# unknown modules: by name first, then by the folder they are in
GUESS_BY_NAME = [
    (re.compile(r"launch"), "consumers.launch"),
    (re.compile(r"^(request|config|schema|trust|gate)"), "request"),
    (re.compile(r"(plan|variant|deploy|discover)"), "plan"),
    (re.compile(r"(baseline|collapse|finish|dedupe)"), "finish"),
    (re.compile(r"(rules|checks)"), "rules.contracts"),
]
GUESS_BY_FOLDER = {"contracts": "consumers", "pipeline": "plan"}

# low to high; one row may import each other (import-linter `layers`, and tests/test_layers.py)
LAYERS = [("core",), ("model",), ("load",), ("consumers",), ("rules",), ("request",), ("plan",), ("finish",),
          ("publisher", "verify"), ("bag",), ("run",), ("diff",), ("report",), ("cli", "pytest_plugin")]
# the folder picture, in data order
PICTURE_ORDER = ["core", "request", "plan", "consumers", "load", "model", "rules", "finish", "run.py",
                 "publisher", "verify", "bag", "diff", "report", "cli", "pytest_plugin.py"]
TEXT_GLOBS = ["src/**/*.py", "tests/**/*.py", "bench/**/*.py", "fuzz/**/*.py", "tools/**/*.py", "docs/**/*.md",
              "*.md", "fuzz/*.md", "bench/*.md", "tests/**/*.md", ".ci/*", "pyproject.toml", ".pre-commit-hooks.yaml"]
SKIP_TEXT = {"CHANGELOG.md", "tools/relayout.py"}  # history stays as written; this script names the old paths


def guess(old: str) -> tuple[str, str]:
    """(new module, why) for a module the table does not know."""
    folder, _, name = old.partition(".")
    leaf = name.split(".")[-1]
    for pattern, where in GUESS_BY_NAME:
        if pattern.search(leaf):
            return f"{where}.{name}", f"name matches {pattern.pattern!r}"
    return f"{GUESS_BY_FOLDER[folder]}.{name}", f"folder {folder}/"


def plan_moves(src: Path) -> tuple[dict, list[str]]:
    """Every module under the emptied packages -> its new module; and the lines saying what was guessed."""
    moves, notes = {}, []
    for folder in GONE:
        base = src / folder
        if not base.is_dir():
            continue
        for path in sorted(base.rglob("*.py")):
            rel = path.relative_to(src).with_suffix("")
            parts = rel.parts
            if parts[-1] == "__init__":
                if len(parts) > 2:  # a sub-package: its folder moves with it
                    old = ".".join(parts[:-1])
                    if old not in KNOWN and not any(old.startswith(k + ".") for k in moves):
                        new, why = guess(old)
                        moves[old] = new
                        notes.append(f"guessed {old} -> {new} ({why})")
                continue
            old = ".".join(parts)
            if any(old.startswith(k + ".") for k in moves):
                continue  # inside a moved sub-package
            if old in KNOWN:
                moves[old] = KNOWN[old]
            else:
                new, why = guess(old)
                moves[old] = new
                notes.append(f"guessed {old} -> {new} ({why})")
    return moves, notes


def module_file(src: Path, module: str) -> Path:
    p = src.joinpath(*module.split("."))
    return p if p.is_dir() else p.with_suffix(".py")


def git(repo: Path, *args: str) -> None:
    subprocess.run(["git", *args], cwd=repo, check=True)


def move_files(repo: Path, src: Path, moves: dict, dry: bool) -> None:
    for pkg in NEW_PACKAGES:
        init = src.joinpath(*pkg.split("."), "__init__.py")
        if not init.exists():
            print(f"create {init.relative_to(repo)}")
            if not dry:
                init.parent.mkdir(parents=True, exist_ok=True)
                doc = PACKAGE_DOCS.get(pkg)
                init.write_text(f'"""{doc}\n"""\n' if doc else "", encoding="utf-8")
                git(repo, "add", str(init))
    for old, new in moves.items():
        a = module_file(src, old)
        b = src.joinpath(*new.split("."))
        b = b if a.is_dir() else b.with_suffix(".py")
        print(f"git mv {a.relative_to(repo)} {b.relative_to(repo)}")
        if not dry:
            b.parent.mkdir(parents=True, exist_ok=True)
            git(repo, "mv", str(a), str(b))
    for folder in GONE:
        base = src / folder
        init = base / "__init__.py"
        if init.exists():
            print(f"git rm {init.relative_to(repo)}")
            if not dry:
                git(repo, "rm", "-q", str(init))
        if not dry and base.is_dir():
            for p in sorted(base.rglob("__pycache__"), reverse=True):
                for f in p.iterdir():
                    f.unlink()
                p.rmdir()
            left = [p for p in base.rglob("*") if p.is_file()]
            if left:
                print(f"warning: left in {base.relative_to(repo)}: {[str(p.relative_to(base)) for p in left]}")
            else:
                for d in sorted((p for p in base.rglob("*") if p.is_dir()), reverse=True):
                    d.rmdir()
                base.rmdir()


# --- rewriting -------------------------------------------------------------------------------------------------
class Rewriter:
    def __init__(self, moves: dict, modules: set[str]):
        self.moves = moves
        self.longest = sorted(moves, key=len, reverse=True)
        self.modules = modules  # every module (old names) that existed before the move, dotted below urdfcheck

    def module(self, dotted: str) -> str:
        """An old dotted name below urdfcheck (module, or module.attribute) -> the new one."""
        for old in self.longest:
            if dotted == old or dotted.startswith(old + "."):
                return self.moves[old] + dotted[len(old):]
        return dotted

    # from urdfcheck.X import a, b as c (X absolute or relative, resolved by the caller)
    def from_import(self, pkg: str, names: list[tuple[str, str | None]], indent: str, comment: str = ""
                    ) -> str | None:
        groups: dict[str, list[str]] = {}
        changed = False
        for name, alias in names:
            full = f"{pkg}.{name}" if pkg else name
            if name != "*" and full in self.modules:  # a module named from its package
                new = self.module(full)
                parent, _, leaf = new.rpartition(".")
                if new != full:
                    changed = True
                spec = leaf if (alias or name) == leaf else f"{leaf} as {alias or name}"
                groups.setdefault(parent, []).append(spec)
            else:
                new_pkg = self.module(pkg)
                changed |= new_pkg != pkg
                groups.setdefault(new_pkg, []).append(name if alias is None else f"{name} as {alias}")
        if not changed:
            return None
        lines = []
        for parent, specs in groups.items():
            mod = "urdfcheck" + (f".{parent}" if parent else "")
            note = f"  {comment}" if comment and not lines else ""  # the statement's comment, once
            one = f"{indent}from {mod} import {', '.join(specs)}{note}"
            if len(one) > 120:
                one = (f"{indent}from {mod} import ({note}\n" + "".join(f"{indent}    {s},\n" for s in specs)
                       + f"{indent})")
            lines.append(one)
        return "\n".join(lines)

    def python(self, text: str, path: Path, src: Path, old_module: str | None) -> str:
        """Rewrite the import statements of a Python file (found with ast), then dotted names in the rest."""
        try:
            tree = ast.parse(text)
        except SyntaxError:
            return self.prose(text)
        lines = text.splitlines(keepends=True)
        edits = []  # (first line, last line, replacement)
        for node in ast.walk(tree):
            if not isinstance(node, ast.ImportFrom):
                continue
            if node.level:  # relative: resolve against the module's old package
                if old_module is None:
                    continue
                base = old_module.split(".")[:-node.level] if old_module else []
                pkg = ".".join(base + ([node.module] if node.module else []))
            elif node.module and (node.module == "urdfcheck" or node.module.startswith("urdfcheck.")):
                pkg = node.module[len("urdfcheck."):] if node.module != "urdfcheck" else ""
            else:
                continue
            first = lines[node.lineno - 1]
            indent = first[:len(first) - len(first.lstrip())]
            last = lines[node.end_lineno - 1]
            tail = last[node.end_col_offset:].strip()  # a comment after the statement stays
            if node.end_lineno > node.lineno and "#" in first:  # a comment after the opening parenthesis
                tail = first[first.index("#"):].strip()
            names = [(a.name, a.asname) for a in node.names]
            new = self.from_import(pkg, names, indent, tail)
            if new is None and node.level:  # a moved file's relative import: absolute
                spec = ", ".join(n if a is None else f"{n} as {a}" for n, a in names)
                new = f"{indent}from urdfcheck{'.' + pkg if pkg else ''} import {spec}" + (f"  {tail}" if tail else "")
            if new is None:
                continue
            edits.append((node.lineno, node.end_lineno, new + "\n"))
        for first, last, new in sorted(edits, reverse=True):
            lines[first - 1:last] = [new]
        return self.code("".join(lines))

    def code(self, text: str) -> str:
        """Dotted `urdfcheck.` names everywhere (attribute chains of imported modules are real references);
        short names (`pipeline.run`) and file paths only in strings and comments: in code, `pipeline.run(...)`
        may be a module imported under the name `pipeline`."""
        import io
        import tokenize

        try:
            tokens = list(tokenize.generate_tokens(io.StringIO(text).readline))
        except (tokenize.TokenError, SyntaxError):
            return self.prose(text)
        starts = [0]
        for line in text.splitlines(keepends=True):
            starts.append(starts[-1] + len(line))
        pieces, at = [], 0
        for tok in tokens:
            if tok.type not in (tokenize.STRING, tokenize.COMMENT):
                continue
            a = starts[tok.start[0] - 1] + tok.start[1]
            b = starts[tok.end[0] - 1] + tok.end[1]
            pieces.append(self._DOTTED.sub(self._dotted, text[at:a]))
            pieces.append(self.prose(text[a:b]))
            at = b
        pieces.append(self._DOTTED.sub(self._dotted, text[at:]))
        return "".join(pieces)

    def _dotted(self, m) -> str:
        return "urdfcheck." + self.module(m.group(1)[1:]) if self._known(m.group(1)[1:]) else m.group(0)

    _DOTTED = re.compile(r"\burdfcheck((?:\.[A-Za-z_]\w*)+)")
    _SHORT = re.compile(r"(?<![\w.])((?:contracts|pipeline)(?:\.[A-Za-z_]\w*)+)")
    _PATH = re.compile(r"(?<![\w.])((?:src/urdfcheck/)?)((?:contracts|pipeline)(?:/\w+)+)\.py\b")

    def prose(self, text: str) -> str:
        """Dotted module names (with or without `urdfcheck.`) and file paths of moved modules."""
        def short(m):
            return self.module(m.group(1)) if self._known(m.group(1)) else m.group(0)

        def path(m):
            old = m.group(2).replace("/", ".")
            if old not in self.moves:
                return m.group(0)
            return m.group(1) + self.moves[old].replace(".", "/") + ".py"

        text = self._DOTTED.sub(self._dotted, text)
        text = self._PATH.sub(path, text)
        return self._SHORT.sub(short, text)

    def _known(self, dotted: str) -> bool:
        return any(dotted == old or dotted.startswith(old + ".") for old in self.longest)


def old_module_of(path: Path, src: Path, reverse: dict) -> str | None:
    """The dotted name (below urdfcheck) a moved or unmoved source file had before the move."""
    try:
        rel = path.relative_to(src).with_suffix("")
    except ValueError:
        return None
    parts = list(rel.parts)
    is_init = parts[-1] == "__init__"
    if is_init:
        parts = parts[:-1]
    name = ".".join(parts)
    name = reverse.get(name, name)
    return name + (".__init__" if is_init else "")


def text_files(repo: Path) -> list[Path]:
    out = []
    for pattern in TEXT_GLOBS:
        for p in repo.glob(pattern):
            rel = str(p.relative_to(repo))
            if p.is_file() and rel not in SKIP_TEXT and "/data/" not in rel and ".venv" not in rel and p not in out:
                out.append(p)
    return out


def rewrite(repo: Path, src: Path, moves: dict, modules: set[str], dry: bool) -> list[Path]:
    rw = Rewriter(moves, modules)
    reverse = {new: old for old, new in moves.items()}
    changed = []
    for p in text_files(repo):
        text = p.read_text(encoding="utf-8")
        if p.suffix == ".py":
            new = rw.python(text, p, src, old_module_of(p, src, reverse))
        else:
            new = rw.prose(text)
        if new != text:
            changed.append(p)
            if not dry:
                p.write_text(new, encoding="utf-8")
    return changed


def layers_contract(repo: Path, dry: bool) -> None:
    top = list(reversed(LAYERS))
    block = ('[[tool.importlinter.contracts]]\n'
             f'name = "layers: {" < ".join(", ".join(r) for r in LAYERS)}"\n'
             'type = "layers"\nlayers = [\n'
             + "".join(f'  "{" : ".join("urdfcheck." + n for n in row)}",\n' for row in top) + ']\n')
    py = repo / "pyproject.toml"
    text = py.read_text(encoding="utf-8")
    new = re.sub(r"\[\[tool\.importlinter\.contracts\]\]\nname = \"layers:.*?\n\]\n", lambda m: block, text,
                 flags=re.S)
    test = repo / "tests" / "test_layers.py"
    ttext = test.read_text(encoding="utf-8")
    rows = ", ".join("(" + ", ".join(f'"{n}"' for n in row) + ",)" if len(row) == 1 else
                     "(" + ", ".join(f'"{n}"' for n in row) + ")" for row in LAYERS)
    tnew = re.sub(r"LAYERS = \[.*?\]\n", lambda m: _wrap(f"LAYERS = [{rows}]") + "\n", ttext, flags=re.S)
    order = " < ".join(", ".join(r) for r in LAYERS)
    doc = _wrap_doc(f'"""Data flows one way: a lower stage never imports a higher one (the layers contract in '
                    f'pyproject.toml, [tool.importlinter]: {order}). Run by import-linter when installed, else by '
                    'an equivalent check on the modules\' imports."""')
    tnew = re.sub(r'\A""".*?"""', lambda m: doc, tnew, flags=re.S)
    design = repo / "docs" / "design.md"
    dtext = design.read_text(encoding="utf-8") if design.is_file() else ""
    dnew = re.sub(r"- Layers \(low to high\): .*?tests/test_layers\.py\.", lambda m: _wrap_doc(
        f"- Layers (low to high): {order}; `[tool.importlinter]` in pyproject.toml, run by tests/test_layers.py."
        ).replace("\n", "\n  "), dtext, flags=re.S)
    for p, old, fresh in ((py, text, new), (test, ttext, tnew), (design, dtext, dnew)):
        if fresh != old:
            print(f"layers: {p.relative_to(repo)}")
            if not dry:
                p.write_text(fresh, encoding="utf-8")


def _wrap(line: str, width: int = 116) -> str:
    if len(line) <= width:
        return line
    head, _, rest = line.partition("[")
    items = rest[:-1].split(", (")
    out, cur = [], head + "["
    for i, it in enumerate(items):
        piece = ("(" if i else "") + it + ("," if i < len(items) - 1 else "]")
        if len(cur) + len(piece) + 1 > width:
            out.append(cur.rstrip())
            cur = " " * (len(head) + 1)
        cur += piece + " "
    out.append(cur.rstrip())
    return "\n".join(out)


def _wrap_doc(text: str, width: int = 116) -> str:
    words, lines, cur = text.split(" "), [], ""
    for w in words:
        if cur and len(cur) + 1 + len(w) > width:
            lines.append(cur)
            cur = w
        else:
            cur = f"{cur} {w}" if cur else w
    return "\n".join(lines + [cur])


def tidy(repo: Path, files: list[Path]) -> None:
    """Sort the rewritten imports (ruff's isort rules, as tests/test_style.py checks them)."""
    import importlib.util
    import shutil

    if importlib.util.find_spec("ruff") is not None:
        cmd = [sys.executable, "-m", "ruff"]
    elif shutil.which("ruff"):
        cmd = [shutil.which("ruff")]
    else:
        print("ruff not found: sort the imports of the rewritten files (ruff check --fix --select I)")
        return
    subprocess.run([*cmd, "check", "--fix", "--select", "I", "--quiet", *map(str, files)], cwd=repo, check=False)


def first_line(path: Path) -> str:
    try:
        doc = ast.get_docstring(ast.parse(path.read_text(encoding="utf-8"))) or ""
    except SyntaxError:
        doc = ""
    line = doc.strip().split("\n\n")[0].replace("\n", " ")
    line = re.sub(r"\s+", " ", line)
    return line if len(line) <= 110 else line[:107].rstrip() + "..."


def picture(src: Path) -> str:
    """The folder tree in data order, one line per module with its docstring's first sentence."""
    out = ["```"]
    for name in PICTURE_ORDER:
        p = src / name
        if p.is_file():
            out.append(f"{name:<28} {first_line(p)}")
            continue
        if not p.is_dir():
            continue
        out.append(f"{name + '/':<28} {first_line(p / '__init__.py')}".rstrip())
        for f in sorted(p.rglob("*.py")):
            rel = f.relative_to(p)
            if f.name == "__init__.py" and (rel.parent == Path(".") or not first_line(f)):
                continue
            if "_generated" in rel.parts:
                continue
            shown = str(rel) if f.name != "__init__.py" else f"{rel.parent}/"
            out.append(f"  {shown:<26} {first_line(f)}")
    out.append("```")
    return "\n".join(out)


def design_picture(repo: Path, src: Path, dry: bool) -> None:
    doc = repo / "docs" / "design.md"
    text = doc.read_text(encoding="utf-8")
    section = ("## Folders (src/urdfcheck), in data order\n\n"
               "Generated by `tools/relayout.py` (the import layers are in pyproject.toml).\n\n"
               + picture(src) + "\n\n")
    new = re.sub(r"## Folders \(src/urdfcheck\).*?(?=\n## )", lambda m: section.rstrip("\n") + "\n", text,
                 flags=re.S)
    if new != text:
        print("picture: docs/design.md")
        if not dry:
            doc.write_text(new, encoding="utf-8")


def all_modules(src: Path) -> set[str]:
    out = set()
    for p in src.rglob("*.py"):
        rel = p.relative_to(src).with_suffix("")
        parts = rel.parts[:-1] if rel.parts[-1] == "__init__" else rel.parts
        if parts:
            out.add(".".join(parts))
    return out


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--repo", default=str(Path(__file__).resolve().parent.parent))
    ap.add_argument("--dry-run", action="store_true", help="print the moves and the files to rewrite only")
    ns = ap.parse_args(argv)
    repo = Path(ns.repo).resolve()
    src = repo / "src" / "urdfcheck"
    moves, notes = plan_moves(src)
    if not moves:
        print("nothing to move (already in data order?)")
        return 0
    for line in notes:
        print(line)
    modules = all_modules(src)
    move_files(repo, src, moves, ns.dry_run)
    changed = rewrite(repo, src, moves, modules, ns.dry_run)
    for p in changed:
        print(f"rewrote {p.relative_to(repo)}")
    layers_contract(repo, ns.dry_run)
    if not ns.dry_run:
        design_picture(repo, src, ns.dry_run)
        tidy(repo, [p for p in changed if p.suffix == ".py"])
    print(f"{len(moves)} modules moved, {len(changed)} files rewritten, {len(notes)} guessed")
    return 0


if __name__ == "__main__":
    sys.exit(main())
