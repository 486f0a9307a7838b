"""What the language server knows, without the protocol: the open documents, the last lint of each unit, and the
answers (findings per file, hover, definition, code actions) computed from them.

A document is linted as `urdfcheck lint` lints the package holding it (the nearest folder with a package.xml, inside
the workspace), with the editor's unsaved text of every open document standing in for the disk's
(`core.safeio.overlaid`): the same plan, config, variants, deployments and sandbox as the command line. A finding
in an included macro file goes to that file; editing a macro file re-lints the package, so the models that include
it are linted again. Nothing is written: the lint cache is not used, and code actions are edits the editor applies.
"""
from __future__ import annotations

import os
import re
import threading

from urdfcheck.core import lazyre
from urdfcheck.core.findings import Finding

MODEL_SUFFIXES = (".urdf", ".xacro", ".urdf.xacro")
TEXT_SUFFIXES = MODEL_SUFFIXES + (".yaml", ".yml", ".launch", ".xml", ".py", ".lua", ".srdf")
_WORD = lazyre.compile(r"[A-Za-z0-9_./:\-]+")
_NAME = lazyre.compile(r"[A-Za-z_][A-Za-z0-9_]*")
MAX_STAMP_DIRS = 2_000  # folders of a unit looked at to tell "nothing changed"
MAX_DEFINITION_FILES = 500  # xacro files of a package searched for a macro or property definition
_FIND = lazyre.compile(r"\$\(find(?:-pkg-share)?\s+([A-Za-z0-9_]+)\s*\)([^\"'\s<>]*)")
_MEAN = lazyre.compile(r"did you mean '([^']+)'")
_QUOTED = lazyre.compile(r"'([^']+)'")


class Unit:
    """One lint unit: a package folder (or a single model file outside any package) and its last result."""

    def __init__(self, path: str):
        self.path = path
        self.files: set[str] = set()  # files with findings at the last run (to clear them next time)
        self.read: set[str] = set()  # files the last run's expansions read (includes, macro files)
        self.models: dict = {}
        self.findings: list[Finding] = []
        self.stamp: tuple | None = None  # what the last run saw (open texts, files on disk): unchanged -> reuse
        self.last: dict[str, list[Finding]] = {}


class Session:
    def __init__(self, root: str | None = None, options: dict | None = None):
        self.root = os.path.realpath(root or os.getcwd())
        self.options = dict(options or {})
        self.documents: dict[str, str] = {}  # absolute real path -> unsaved text
        self.units: dict[str, Unit] = {}
        self._lock = threading.Lock()  # one lint at a time: the sandbox forks per expansion

    # --- documents -------------------------------------------------------------------------------------------
    def open(self, path: str, text: str) -> None:
        self.documents[os.path.realpath(path)] = text

    def close(self, path: str) -> None:
        self.documents.pop(os.path.realpath(path), None)

    def text(self, path: str) -> str | None:
        real = os.path.realpath(path)
        if real in self.documents:
            return self.documents[real]
        from urdfcheck.core import door

        try:
            return door.read_text(real, limit=8 * 2**20)
        except OSError:
            return None

    # --- linting ---------------------------------------------------------------------------------------------
    def unit_of(self, path: str) -> str | None:
        """The folder (or model file) `urdfcheck lint` would be given for a change of `path`."""
        real = os.path.realpath(path)
        d = os.path.dirname(real)
        while True:
            if os.path.isfile(os.path.join(d, "package.xml")):
                return d
            if d == self.root or os.path.dirname(d) == d or not _below(d, self.root):
                break
            d = os.path.dirname(d)
        for unit in self.units.values():  # a macro file outside any package, read by a unit's models
            if real in unit.read:
                return unit.path
        return real if real.endswith(MODEL_SUFFIXES) else None

    def lint(self, path: str) -> dict[str, list[Finding]]:
        """Lint the unit holding `path` with the open documents' text; findings by absolute file. Files that had
        findings at the unit's previous run and have none now map to [] (their diagnostics are cleared)."""
        unit_path = self.unit_of(path)
        if unit_path is None:
            return {}
        unit = self.units.setdefault(unit_path, Unit(unit_path))
        stamp = self._stamp(unit)
        if stamp == unit.stamp:  # nothing it reads changed: the same answer, without a run
            return dict(unit.last)
        with self._lock:
            result = self._run(unit_path)
        by_file: dict[str, list[Finding]] = {f: [] for f in unit.files}
        if result is not None:
            for f in result.findings:
                by_file.setdefault(os.path.realpath(self.absolute(f.location.file)), []).append(f)
            unit.read = {os.path.realpath(p) for p in getattr(result, "read", ()) or ()}
            unit.models = dict(result.models)
            unit.findings = list(result.findings)
        unit.files = {f for f, fs in by_file.items() if fs}
        by_file.setdefault(os.path.realpath(path), [])  # the edited document always hears back (cleared if clean)
        unit.stamp, unit.last = stamp, dict(by_file)
        return by_file

    def _stamp(self, unit: Unit) -> tuple:
        """The open documents' texts and the size and mtime of every file below the unit and read by it."""
        import hashlib

        texts = hashlib.sha256()
        for p in sorted(self.documents):
            texts.update(p.encode("utf-8", "surrogateescape") + b"\0" + self.documents[p].encode("utf-8") + b"\0")
        files = set(unit.read)
        if os.path.isdir(unit.path):
            from urdfcheck.core import walk

            for folder, entries in walk.folders(unit.path, max_dirs=MAX_STAMP_DIRS):
                files.update(os.path.join(folder, name) for name in walk.files(entries))
        else:
            files.add(unit.path)
        disk = []
        for f in sorted(files):
            try:
                st = os.stat(f)
            except OSError:
                continue
            disk.append((f, st.st_mtime_ns, st.st_size))
        return texts.hexdigest(), tuple(disk)

    def _run(self, unit_path: str):
        from urdfcheck.core.safeio import overlaid
        from urdfcheck.request.request import UsageError, make_request
        from urdfcheck.run import run

        texts = {p: t.encode("utf-8") for p, t in self.documents.items()}
        try:
            with overlaid(texts):
                return run(make_request([unit_path], root=self.root, **self.options))
        except UsageError:
            return None

    def absolute(self, file: str) -> str:
        return file if os.path.isabs(file) else os.path.normpath(os.path.join(self.root, file))

    def findings_at(self, path: str, line: int) -> list[Finding]:
        """The last findings located at `path`, 1-based `line`."""
        real = os.path.realpath(path)
        out = []
        for unit in self.units.values():
            for f in unit.findings:
                if f.location.line == line and os.path.realpath(self.absolute(f.location.file)) == real:
                    out.append(f)
        return out

    # --- hover and definition --------------------------------------------------------------------------------
    def hover(self, path: str, line: int, col: int) -> str | None:
        """Markdown for the position (1-based line, 0-based column): the rule page of a finding there, a xacro
        property's value or macro's signature, a joint or link of the model."""
        parts = []
        from urdfcheck.rules.docs import page

        for f in self.findings_at(path, line):
            text = page(f.code, "markdown")
            if text:
                parts.append(text)
        word = self._word(path, line, col)
        if word:
            d = self.definition_of(path, word)
            if d is not None:
                parts.append(d[2])
        return "\n\n---\n\n".join(parts) if parts else None

    def definition(self, path: str, line: int, col: int) -> tuple[str, int] | None:
        """(file, 1-based line) of what the word at the position names."""
        found = self._find_path(path, line, col)
        if found is not None:
            return found, 1
        word = self._word(path, line, col)
        if not word:
            return None
        d = self.definition_of(path, word)
        return (d[0], d[1]) if d is not None else None

    def _find_path(self, path: str, line: int, col: int) -> str | None:
        """The file a `$(find pkg)/rest` under the position names (xacro includes, launch files), when it exists."""
        text = self.text(path)
        lines = text.splitlines() if text else []
        if not 1 <= line <= len(lines):
            return None
        for m in _FIND.finditer(lines[line - 1]):
            if m.start() <= col <= m.end():
                from pathlib import Path

                from urdfcheck.load.packages import Resolver

                root = Resolver(near=Path(os.path.dirname(os.path.realpath(path)))).find(m.group(1))
                target = os.path.join(str(root), m.group(2).lstrip("/")) if root is not None else None
                return target if target and os.path.isfile(target) else None
        return None

    def _word(self, path: str, line: int, col: int) -> str | None:
        text = self.text(path)
        if text is None:
            return None
        lines = text.splitlines()
        if not 1 <= line <= len(lines):
            return None
        s = lines[line - 1]
        for m in _WORD.finditer(s):
            if m.start() <= col <= m.end():
                return m.group(0)
        return None

    def definition_of(self, path: str, word: str) -> tuple[str, int, str] | None:
        """(file, line, markdown) for a path (`package://`, `$(find)`), a xacro macro or property, or a model's
        joint or link named `word`."""
        hit = self._path_target(path, word)
        if hit is not None:
            return hit
        name = word.split(":", 1)[1] if word.startswith("xacro:") else word
        name = name.strip("${}()")
        if _NAME.fullmatch(name):
            hit = self._xacro_definition(path, name)
            if hit is not None:
                return hit
            return self._model_part(name)
        return None

    def _path_target(self, path: str, word: str) -> tuple[str, int, str] | None:
        if not word.startswith("package://"):
            return None
        from pathlib import Path

        from urdfcheck.load.packages import Resolver

        target, _ = Resolver(near=Path(os.path.dirname(os.path.realpath(path)))).resolve_uri(
            word, Path(os.path.dirname(path)))
        if target is None or not target.exists():
            return None
        return str(target), 1, f"`{word}` → `{self._shown(str(target))}`"

    def _xacro_files(self, path: str) -> list[str]:
        """The document, what its unit's last run read, and the xacro files of its package (a bounded walk)."""
        real = os.path.realpath(path)
        files = [real]
        for unit in self.units.values():
            if real in unit.read or unit.path == real or _below(real, unit.path):
                files.extend(sorted(unit.read))
        unit = self.unit_of(real)
        if unit is not None and os.path.isdir(unit):
            from urdfcheck.core import walk

            found = []
            for folder, entries in walk.folders(unit, max_dirs=200):
                found.extend(os.path.join(folder, n) for n in walk.files(entries) if n.endswith(".xacro"))
                if len(found) >= MAX_DEFINITION_FILES:
                    break
            files.extend(found[:MAX_DEFINITION_FILES])
        return list(dict.fromkeys(files))

    def _xacro_definition(self, path: str, name: str) -> tuple[str, int, str] | None:
        for f in self._xacro_files(path):
            text = self.text(f)
            if not text or "xacro" not in text:
                continue
            for kind, line, detail in _xacro_defs(text, name):
                label = (f"xacro macro `{name}({detail})`" if kind == "macro"
                         else f"xacro property `{name}` = `{detail}`")
                return f, line, f"{label}, defined at `{self._shown(f)}:{line}`"
        return None

    def _model_part(self, name: str) -> tuple[str, int, str] | None:
        for unit in self.units.values():
            for model in unit.models.values():
                if model is None:
                    continue
                for kind, table in (("joint", model.joints), ("link", model.links)):
                    part = table.get(name)
                    if part is not None and part.loc.line:
                        extra = f" ({part.type})" if kind == "joint" else ""
                        file = self.absolute(part.loc.file)
                        return file, part.loc.line, f"{kind} `{name}`{extra} at `{self._shown(file)}:{part.loc.line}`"
        return None

    def _shown(self, file: str) -> str:
        return os.path.relpath(file, self.root) if _below(file, self.root) else os.path.basename(file)

    # --- code actions ----------------------------------------------------------------------------------------
    def actions(self, path: str, line: int) -> list[tuple[str, int, int, int, str]]:
        """Edits for the findings at `path`:`line` (1-based): (title, line, start col, end col, new text), with
        end col -1 meaning "insert a line before `line`"."""
        text = self.text(path)
        if text is None:
            return []
        lines = text.splitlines()
        if not 1 <= line <= len(lines):
            return []
        src = lines[line - 1]
        out = []
        for f in self.findings_at(path, line):
            m = _MEAN.search(f.message)
            if m:
                for q in _QUOTED.findall(f.message[: m.start()]):
                    col = _find_word(src, q)
                    if col >= 0:
                        out.append((f"Replace '{q}' with '{m.group(1)}' ({f.code})", line, col, col + len(q),
                                    m.group(1)))
                        break
            indent = src[: len(src) - len(src.lstrip())]
            comment = (f"{indent}# urdfcheck: ignore[{f.code}]" if path.endswith((".yaml", ".yml"))
                       else f"{indent}<!-- urdfcheck: ignore[{f.code}] -->")
            out.append((f"Suppress {f.code} here (inline comment)", line, 0, -1, comment))
        return out


def _find_word(line: str, word: str) -> int:
    for m in re.finditer(re.escape(word), line):
        before = line[m.start() - 1] if m.start() else " "
        after = line[m.end()] if m.end() < len(line) else " "
        if not (before.isalnum() or before == "_") and not (after.isalnum() or after == "_"):
            return m.start()
    return -1


def _xacro_defs(text: str, name: str):
    """(kind, line, detail) of `<xacro:macro name=NAME params=...>` and `<xacro:property name=NAME value=...>`."""
    from urdfcheck.core import xmlfront
    from urdfcheck.core.lxmlimport import etree

    try:
        root = etree.fromstring(text.encode("utf-8"), xmlfront.parser(recover=True))
    except etree.XMLSyntaxError:
        return
    if root is None:
        return
    for el in root.iter():
        tag = el.tag if isinstance(el.tag, str) else ""
        local = tag.rsplit("}", 1)[-1]
        if local in ("macro", "property") and el.get("name") == name and ("xacro" in tag or tag.startswith("{")):
            detail = el.get("params", "") if local == "macro" else el.get("value", (el.text or "").strip()[:80])
            yield local, el.sourceline or 1, detail


def _below(path: str, base: str) -> bool:
    return path == base or path.startswith(base.rstrip(os.sep) + os.sep)
