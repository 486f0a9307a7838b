"""The tree tells the truth: every module a comment, docstring, doc (docs/*.md, README, CONTRIBUTING) or test text
names exists. A module moved or deleted leaves its old name in prose, where no import fails; this test does.

Three spellings are checked: `urdfcheck.a.b[.name]` anywhere; `a.b` in backticks whose first word is a source
package (consumers.discover_consumers, written in backticks); and file paths `a/b.py` whose first folder is a
source package, tests/, tools/ or bench/ (`src/urdfcheck/` may precede). A trailing name after a module must be
written in that module."""
from __future__ import annotations

import io
import re
import tokenize
from pathlib import Path

from conftest import REPO

SRC = REPO / "src" / "urdfcheck"
PACKAGES = sorted(p.name for p in SRC.iterdir() if (p / "__init__.py").is_file())
# source packages whose names are also the usual variable names in prose (`model.joints`, `request.paths`)
VARIABLES = {"model", "report", "request", "bag"}
FILE_ENDINGS = {"py", "yaml", "yml", "json", "md", "xml", "urdf", "xacro", "launch", "sarif", "toml", "txt"}

PREFIXED = re.compile(r"(?<![\w.])urdfcheck((?:\.[A-Za-z_]\w*)+)")
TICKED = re.compile(r"`((?:" + "|".join(p for p in PACKAGES if p not in VARIABLES) + r")(?:\.[A-Za-z_]\w*)+)[`(]")
PATH = re.compile(r"(?<![\w/.-])((?:src/urdfcheck/)?([a-z_]+)/(?:[a-z_]\w*/)*[a-z_]\w*\.py)\b")


def _prose(path: Path):
    """(line, text) of what is prose in a file: all of a Markdown file; the comments and docstrings (and, outside
    tests, every string) of a Python file."""
    text = path.read_text(encoding="utf-8", errors="replace")
    if path.suffix != ".py":
        yield from enumerate(text.splitlines(), 1)
        return
    in_tests = "tests" in path.relative_to(REPO).parts[:1]
    for tok in tokenize.generate_tokens(io.StringIO(text).readline):
        if tok.type == tokenize.COMMENT or (tok.type == tokenize.STRING and (
                not in_tests or tok.string.lstrip("rbfuRBFU").startswith(('"""', "'''")))):
            for i, line in enumerate(tok.string.splitlines()):
                yield tok.start[0] + i, line


def _module_names(parts: list[str]) -> bool:
    """Does `urdfcheck.<parts>` name a module, a module's name, or a name a package's __init__ defines?"""
    here = SRC
    for i, part in enumerate(parts):
        if (here / part / "__init__.py").is_file():
            here = here / part
            continue
        if (here / part).is_dir():  # a data folder (urdfcheck.schemas)
            return True
        if (here / f"{part}.py").is_file():
            rest = parts[i + 1:]
            return not rest or re.search(rf"\b{re.escape(rest[0])}\b", (here / f"{part}.py").read_text()) is not None
        init = here / "__init__.py"
        return init.is_file() and re.search(rf"\b{re.escape(part)}\b", init.read_text()) is not None
    return True


def _path_exists(path: str, first: str) -> bool:
    if path.startswith("src/urdfcheck/"):
        return (REPO / path).is_file()
    if first in PACKAGES:
        return (SRC / path).is_file()
    if first in ("tests", "tools", "bench"):
        return (REPO / path).is_file()
    if first in _FOLDERS:  # relative to a package (`checks/joints.py` in rules/)
        return any(str(f).endswith("/" + path) for f in SRC.rglob("*.py"))
    return True  # another project's file (colcon's verb/build.py), or a package's file in an example


_FOLDERS = {p.name for p in SRC.rglob("*") if p.is_dir() and p.name != "__pycache__"}


def stale_names(files) -> list[str]:
    out = []
    for f in files:
        for n, line in _prose(f):
            names = [m.group(1)[1:].split(".") for m in PREFIXED.finditer(line)]
            names += [m.group(1).split(".") for m in TICKED.finditer(line)]
            for parts in names:
                if parts[-1] in FILE_ENDINGS or parts[0].startswith("__") or len(parts[0]) == 1:
                    continue  # urdfcheck.yml, urdfcheck.__file__, a placeholder (urdfcheck.a in a graph test)
                if line[:line.find("urdfcheck")].endswith("tool."):  # [tool.urdfcheck.models]: a TOML table
                    continue
                if not _module_names(parts):
                    out.append(f"{f.relative_to(REPO)}:{n}: {'.'.join(parts)}")
            for m in PATH.finditer(line):
                if not _path_exists(m.group(1), m.group(2)):
                    out.append(f"{f.relative_to(REPO)}:{n}: {m.group(1)}")
    return out


def _files():
    return [*SRC.rglob("*.py"), *(REPO / "tests").glob("*.py"), *(REPO / "docs").glob("*.md"), REPO / "README.md",
            REPO / "CONTRIBUTING.md", *(REPO / "bench").glob("*.py")]


def test_every_module_prose_names_exists():
    assert stale_names([f for f in _files() if f.is_file()]) == []


def test_the_check_finds_a_stale_name(tmp_path):
    """Not vacuous: each spelling of a module that is gone is found, and one that exists is not."""
    probe = REPO / "tests" / "_probe_prose_names.md"
    try:
        probe.write_text("`urdfcheck.pipeline.run` and `consumers.discover_consumers` and checks/gone.py, "
                         "src/urdfcheck/cli/gone.py; fine: `urdfcheck.cli.cache.plan`, cli/cache.py\n")
        found = [x.split(": ", 1)[1] for x in stale_names([probe])]
    finally:
        probe.unlink()
    assert found == ["pipeline.run", "consumers.discover_consumers", "checks/gone.py", "src/urdfcheck/cli/gone.py"]
