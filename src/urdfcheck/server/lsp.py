"""The protocol side of `urdfcheck server` (pygls over stdio): documents in, diagnostics, hover, definitions and
code actions out. Every answer comes from `server.session`; this module only converts.

Diagnostics are published on open and save at once, and on change after a short pause (`DEBOUNCE` seconds with no
further edit): a lint runs the sandboxed xacro worker, so linting on every keystroke would queue stale runs. A run
whose unit was edited again meanwhile is dropped, not published.
"""
from __future__ import annotations

import asyncio
import os
import sys

from lsprotocol import types
from pygls.lsp.server import LanguageServer
from pygls.uris import from_fs_path, to_fs_path

from urdfcheck import __version__
from urdfcheck.core.findings import Severity
from urdfcheck.server.session import TEXT_SUFFIXES, Session

DEBOUNCE = 0.3
_SEVERITY = {Severity.ERROR: types.DiagnosticSeverity.Error, Severity.WARNING: types.DiagnosticSeverity.Warning,
             Severity.INFO: types.DiagnosticSeverity.Information}


class UrdfcheckServer(LanguageServer):
    def __init__(self, options: dict | None = None):
        super().__init__("urdfcheck", __version__)
        self.options = dict(options or {})
        self.session: Session | None = None
        self.generation: dict[str, int] = {}
        self.pending: dict[str, asyncio.Task] = {}

    def get_session(self) -> Session:
        if self.session is None:
            root = self.workspace.root_path if self.workspace is not None else None
            self.session = Session(root or os.getcwd(), self.options)
        return self.session


server = UrdfcheckServer()


def _path(uri: str) -> str | None:
    p = to_fs_path(uri)
    return os.path.realpath(p) if p else None


def _ours(path: str | None) -> bool:
    return bool(path) and path.endswith(TEXT_SUFFIXES)


def _sync(ls: UrdfcheckServer, uri: str) -> str | None:
    path = _path(uri)
    if not _ours(path):
        return None
    doc = ls.workspace.get_text_document(uri)
    ls.get_session().open(path, doc.source)
    return path


def _range(session: Session, file: str, line: int | None) -> types.Range:
    row = max((line or 1) - 1, 0)
    text = session.text(file) or ""
    lines = text.splitlines()
    width = len(lines[row]) if row < len(lines) else 0
    start = len(lines[row]) - len(lines[row].lstrip()) if row < len(lines) else 0
    return types.Range(types.Position(row, start), types.Position(row, max(width, start)))


def _diagnostic(session: Session, file: str, f) -> types.Diagnostic:
    related = []
    for loc in tuple(f.related) + tuple(f.location.via):
        if loc.file:
            target = session.absolute(loc.file)
            related.append(types.DiagnosticRelatedInformation(
                types.Location(from_fs_path(target), _range(session, target, loc.line)),
                "called here" if loc in f.location.via else "related"))
    places = f.places()
    message = f.message
    if len(places) > 1 or (places and places[0].variant):
        variants = sorted({p.variant or "defaults" for p in places})
        message += f" [in {', '.join(variants[:4])}{' …' if len(variants) > 4 else ''}]"
    return types.Diagnostic(range=_range(session, file, f.location.line), message=message,
                            severity=_SEVERITY.get(f.severity, types.DiagnosticSeverity.Information),
                            code=f.code, source="urdfcheck", related_information=related or None)


def _publish(ls: UrdfcheckServer, by_file: dict) -> None:
    session = ls.get_session()
    for file, found in by_file.items():
        diags = [_diagnostic(session, file, f) for f in found]
        ls.text_document_publish_diagnostics(types.PublishDiagnosticsParams(uri=from_fs_path(file),
                                                                            diagnostics=diags))


async def _lint_later(ls: UrdfcheckServer, path: str, delay: float) -> None:
    session = ls.get_session()
    unit = session.unit_of(path) or path
    gen = ls.generation.get(unit, 0) + 1
    ls.generation[unit] = gen
    old = ls.pending.pop(unit, None)
    if old is not None and not old.done():
        old.cancel()

    async def job():
        if delay:
            await asyncio.sleep(delay)
        token = f"urdfcheck-{unit}-{gen}"
        progress = _progress_begin(ls, token, unit)
        try:
            by_file = await asyncio.get_running_loop().run_in_executor(None, session.lint, path)
        finally:
            if progress:
                ls.work_done_progress.end(token, types.WorkDoneProgressEnd(message="done"))
        if ls.generation.get(unit) == gen:  # edited again meanwhile: a newer run publishes
            _publish(ls, by_file)

    ls.pending[unit] = asyncio.ensure_future(job())


def _progress_begin(ls: UrdfcheckServer, token: str, unit: str) -> bool:
    caps = ls.client_capabilities
    if not (caps and caps.window and caps.window.work_done_progress):
        return False
    try:
        ls.work_done_progress.create(token)
        ls.work_done_progress.begin(token, types.WorkDoneProgressBegin(
            title="urdfcheck", message=f"linting {os.path.basename(unit)}", cancellable=False))
    except Exception:  # a client that refuses the token still gets its diagnostics
        return False
    return True


async def _touched(ls: UrdfcheckServer, uri: str, delay: float) -> None:
    path = _sync(ls, uri)
    if path:
        await _lint_later(ls, path, delay)


@server.feature(types.TEXT_DOCUMENT_DID_OPEN)
async def did_open(ls: UrdfcheckServer, params: types.DidOpenTextDocumentParams):
    await _touched(ls, params.text_document.uri, 0)


@server.feature(types.TEXT_DOCUMENT_DID_CHANGE)
async def did_change(ls: UrdfcheckServer, params: types.DidChangeTextDocumentParams):
    await _touched(ls, params.text_document.uri, DEBOUNCE)  # typing: wait for a pause


@server.feature(types.TEXT_DOCUMENT_DID_SAVE)
async def did_save(ls: UrdfcheckServer, params: types.DidSaveTextDocumentParams):
    await _touched(ls, params.text_document.uri, 0)


@server.feature(types.TEXT_DOCUMENT_DID_CLOSE)
def did_close(ls: UrdfcheckServer, params: types.DidCloseTextDocumentParams):
    path = _path(params.text_document.uri)
    if path:
        ls.get_session().close(path)


@server.feature(types.TEXT_DOCUMENT_HOVER)
def hover(ls: UrdfcheckServer, params: types.HoverParams):
    path = _path(params.text_document.uri)
    if not _ours(path):
        return None
    text = ls.get_session().hover(path, params.position.line + 1, params.position.character)
    if not text:
        return None
    return types.Hover(contents=types.MarkupContent(kind=types.MarkupKind.Markdown, value=text))


@server.feature(types.TEXT_DOCUMENT_DEFINITION)
def definition(ls: UrdfcheckServer, params: types.DefinitionParams):
    path = _path(params.text_document.uri)
    if not _ours(path):
        return None
    hit = ls.get_session().definition(path, params.position.line + 1, params.position.character)
    if hit is None:
        return None
    file, line = hit
    pos = types.Position(max(line - 1, 0), 0)
    return types.Location(uri=from_fs_path(file), range=types.Range(pos, pos))


@server.feature(types.TEXT_DOCUMENT_CODE_ACTION,
                types.CodeActionOptions(code_action_kinds=[types.CodeActionKind.QuickFix]))
def code_action(ls: UrdfcheckServer, params: types.CodeActionParams):
    path = _path(params.text_document.uri)
    if not _ours(path):
        return None
    uri = params.text_document.uri
    out = []
    for line in range(params.range.start.line + 1, params.range.end.line + 2):
        for title, row, start, end, new in ls.get_session().actions(path, line):
            if end < 0:  # a new line before `row`
                pos = types.Position(row - 1, 0)
                edit = types.TextEdit(types.Range(pos, pos), new + "\n")
            else:
                edit = types.TextEdit(types.Range(types.Position(row - 1, start), types.Position(row - 1, end)), new)
            out.append(types.CodeAction(title=title, kind=types.CodeActionKind.QuickFix,
                                        edit=types.WorkspaceEdit(changes={uri: [edit]})))
    return out or None


def main(options: dict | None = None) -> int:
    server.options = dict(options or {})
    server.start_io(sys.stdin.buffer, sys.stdout.buffer)
    return 0
