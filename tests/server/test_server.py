"""`urdfcheck server` driven as a real LSP client over stdio (pytest-lsp): diagnostics equal lint's, an edit adds
and clears them, hover, definition and code actions answer, and nothing is written into the workspace."""
from __future__ import annotations

import asyncio
import hashlib
import os
import shutil
import sys
from pathlib import Path

import pytest

pytest.importorskip("pygls")
pytest_lsp = pytest.importorskip("pytest_lsp")
from lsprotocol import types  # noqa: E402
from pytest_lsp import ClientServerConfig, LanguageClient  # noqa: E402

REPO = Path(__file__).resolve().parents[2]
EXAMPLE = REPO / "examples" / "broken" / "xacro_macro"
WORK = Path(os.environ.get("URDFCHECK_TEST_LSP_DIR", "")) if os.environ.get("URDFCHECK_TEST_LSP_DIR") else None
DEFECT = 'iyy="${mass * radius * radius}"'
FIXED = 'iyy="${mass * radius * radius / 2}"'


ANYMAL = REPO.parent / "shared" / "corpus" / "ANYbotics+anymal_c_simple_description"


def _workspace() -> Path:
    import tempfile

    base = Path(tempfile.mkdtemp(prefix="urdfcheck-lsp-"))
    shutil.copytree(EXAMPLE, base / "xacro_macro")
    shutil.copytree(REPO / "examples" / "agv", base / "agv")
    shutil.copytree(REPO / "examples" / "broken" / "contract_driver_joint_typo", base / "typo")
    if ANYMAL.is_dir():  # a corpus package (public, unseen by the rules' authors), when the corpus is present
        shutil.copytree(ANYMAL, base / "anymal")
    return base


BASE = _workspace()
PKG = BASE / "xacro_macro"
AGV_YAML = BASE / "agv" / "config" / "agv_controllers.yaml"
WHEEL = PKG / "urdf" / "macros" / "wheel.xacro"
TOP = PKG / "urdf" / "agv.urdf.xacro"


def _uri(p: Path) -> str:
    return p.resolve().as_uri()


def _digest(folder: Path) -> dict[str, str]:
    return {str(p.relative_to(folder)): hashlib.sha256(p.read_bytes()).hexdigest()
            for p in sorted(folder.rglob("*")) if p.is_file()}


BEFORE = _digest(BASE)


@pytest_lsp.fixture(scope="module", config=ClientServerConfig(
    server_command=[sys.executable, "-m", "urdfcheck", "server"]))
async def client(lsp_client: LanguageClient):
    await lsp_client.initialize_session(types.InitializeParams(
        capabilities=types.ClientCapabilities(),
        root_uri=_uri(BASE),
        workspace_folders=[types.WorkspaceFolder(uri=_uri(BASE), name="ws")]))
    yield
    await lsp_client.shutdown_session()


async def _until(client: LanguageClient, uri: str, pred, timeout: float = 120.0):
    """Wait for diagnostics of `uri` that satisfy `pred` (a guard against a hang, not a speed test)."""
    async def wait():
        while not (uri in client.diagnostics and pred(client.diagnostics[uri])):
            await client.wait_for_notification(types.TEXT_DOCUMENT_PUBLISH_DIAGNOSTICS)
        return client.diagnostics[uri]
    return await asyncio.wait_for(wait(), timeout)


def _codes(diags) -> set[tuple[str, int]]:
    return {(str(d.code), d.range.start.line + 1) for d in diags}


@pytest.mark.asyncio(loop_scope="module")
async def test_open_gives_lints_findings(client: LanguageClient):
    import urdfcheck

    text = WHEEL.read_text(encoding="utf-8")
    client.text_document_did_open(types.DidOpenTextDocumentParams(types.TextDocumentItem(
        uri=_uri(WHEEL), language_id="xml", version=1, text=text)))
    diags = await _until(client, _uri(WHEEL), lambda d: len(d) > 0)
    cwd = os.getcwd()
    try:
        os.chdir(PKG)
        expected = {(f.code, f.location.line) for f in urdfcheck.lint([str(PKG)], no_config=False).findings
                    if Path(f.location.file).name == WHEEL.name}
    finally:
        os.chdir(cwd)
    assert expected and _codes(diags) == expected
    assert ("I004", 31) in _codes(diags)


@pytest.mark.asyncio(loop_scope="module")
async def test_edit_clears_and_adds_the_diagnostic(client: LanguageClient):
    text = WHEEL.read_text(encoding="utf-8")
    assert DEFECT in text
    fixed = text.replace(DEFECT, FIXED)
    client.text_document_did_change(types.DidChangeTextDocumentParams(
        text_document=types.VersionedTextDocumentIdentifier(uri=_uri(WHEEL), version=2),
        content_changes=[types.TextDocumentContentChangeWholeDocument(text=fixed)]))
    await _until(client, _uri(WHEEL), lambda d: not any(x.code == "I004" for x in d))
    client.text_document_did_change(types.DidChangeTextDocumentParams(
        text_document=types.VersionedTextDocumentIdentifier(uri=_uri(WHEEL), version=3),
        content_changes=[types.TextDocumentContentChangeWholeDocument(text=text)]))
    diags = await _until(client, _uri(WHEEL), lambda d: any(x.code == "I004" for x in d))
    assert ("I004", 31) in _codes(diags)
    assert WHEEL.read_text(encoding="utf-8") == text  # the unsaved edits never reached the disk


@pytest.mark.asyncio(loop_scope="module")
async def test_hover_shows_the_rule_page_and_the_macro(client: LanguageClient):
    await _until(client, _uri(WHEEL), lambda d: any(x.code == "I004" for x in d))
    hover = await client.text_document_hover_async(types.HoverParams(
        text_document=types.TextDocumentIdentifier(uri=_uri(WHEEL)), position=types.Position(30, 12)))
    assert hover is not None and "I004" in hover.contents.value
    top = TOP.read_text(encoding="utf-8")
    row = next(i for i, line in enumerate(top.splitlines()) if "<xacro:wheel" in line)
    col = top.splitlines()[row].index("xacro:wheel") + 3
    client.text_document_did_open(types.DidOpenTextDocumentParams(types.TextDocumentItem(
        uri=_uri(TOP), language_id="xml", version=1, text=top)))
    hover = await client.text_document_hover_async(types.HoverParams(
        text_document=types.TextDocumentIdentifier(uri=_uri(TOP)), position=types.Position(row, col)))
    assert hover is not None and "xacro macro `wheel(" in hover.contents.value


@pytest.mark.asyncio(loop_scope="module")
async def test_definition_of_a_macro_call(client: LanguageClient):
    top = TOP.read_text(encoding="utf-8")
    row = next(i for i, line in enumerate(top.splitlines()) if "<xacro:wheel" in line)
    col = top.splitlines()[row].index("xacro:wheel") + 8
    loc = await client.text_document_definition_async(types.DefinitionParams(
        text_document=types.TextDocumentIdentifier(uri=_uri(TOP)), position=types.Position(row, col)))
    assert loc is not None
    macro_line = next(i for i, line in enumerate(WHEEL.read_text().splitlines()) if 'xacro:macro name="wheel"' in line)
    assert Path(loc.uri.replace("file://", "")).resolve() == WHEEL.resolve()
    assert loc.range.start.line == macro_line


@pytest.mark.asyncio(loop_scope="module")
async def test_definition_of_a_find_path(client: LanguageClient):
    top = TOP.read_text(encoding="utf-8")
    row = next(i for i, line in enumerate(top.splitlines()) if "$(find" in line and "wheel.xacro" in line)
    col = top.splitlines()[row].index("$(find") + 10
    loc = await client.text_document_definition_async(types.DefinitionParams(
        text_document=types.TextDocumentIdentifier(uri=_uri(TOP)), position=types.Position(row, col)))
    assert loc is not None and Path(loc.uri.replace("file://", "")).resolve() == WHEEL.resolve()


@pytest.mark.asyncio(loop_scope="module")
async def test_code_action_suppresses_the_finding(client: LanguageClient):
    await _until(client, _uri(WHEEL), lambda d: any(x.code == "I004" for x in d))
    actions = await client.text_document_code_action_async(types.CodeActionParams(
        text_document=types.TextDocumentIdentifier(uri=_uri(WHEEL)),
        range=types.Range(types.Position(30, 0), types.Position(30, 0)),
        context=types.CodeActionContext(diagnostics=[])))
    titles = [a.title for a in actions or []]
    assert "Suppress I004 here (inline comment)" in titles
    edit = next(a for a in actions if a.title.startswith("Suppress")).edit.changes[_uri(WHEEL)][0]
    assert edit.range.start.line == 30 and "urdfcheck: ignore[I004]" in edit.new_text


@pytest.mark.asyncio(loop_scope="module")
async def test_joint_name_in_controller_yaml_leads_to_the_model(client: LanguageClient):
    text = AGV_YAML.read_text(encoding="utf-8")
    client.text_document_did_open(types.DidOpenTextDocumentParams(types.TextDocumentItem(
        uri=_uri(AGV_YAML), language_id="yaml", version=1, text=text)))
    await _until(client, _uri(AGV_YAML), lambda d: True)  # its package was linted (the file may be clean)
    row = next(i for i, line in enumerate(text.splitlines()) if "left_wheel_names" in line)
    col = text.splitlines()[row].index("left_wheel_joint") + 2

    async def ask():
        while True:  # the package's lint (which knows the model) may still be running
            hover = await client.text_document_hover_async(types.HoverParams(
                text_document=types.TextDocumentIdentifier(uri=_uri(AGV_YAML)), position=types.Position(row, col)))
            if hover is not None:
                return hover
            await asyncio.sleep(0.2)
    hover = await asyncio.wait_for(ask(), 120)
    assert "joint `left_wheel_joint` (continuous)" in hover.contents.value
    loc = await client.text_document_definition_async(types.DefinitionParams(
        text_document=types.TextDocumentIdentifier(uri=_uri(AGV_YAML)), position=types.Position(row, col)))
    assert loc is not None and loc.uri.endswith(".xacro")
    target = Path(loc.uri.replace("file://", "")).read_text().splitlines()[loc.range.start.line]
    assert "left_wheel_joint" in target or "_wheel_joint" in target


@pytest.mark.asyncio(loop_scope="module")
async def test_corpus_package_diagnostics_equal_lints(client: LanguageClient):
    import urdfcheck

    model = BASE / "anymal" / "urdf" / "anymal.urdf"
    if not model.is_file():
        pytest.skip("shared corpus not present")
    text = model.read_text(encoding="utf-8")
    client.text_document_did_open(types.DidOpenTextDocumentParams(types.TextDocumentItem(
        uri=_uri(model), language_id="xml", version=1, text=text)))
    diags = await _until(client, _uri(model), lambda d: len(d) > 0, timeout=240)
    cwd = os.getcwd()
    try:
        os.chdir(BASE)
        expected = {(f.code, f.location.line) for f in urdfcheck.lint([str(BASE / "anymal")]).findings
                    if Path(f.location.file).name == model.name}
    finally:
        os.chdir(cwd)
    assert expected and _codes(diags) == expected


@pytest.mark.asyncio(loop_scope="module")
async def test_did_you_mean_is_a_quick_fix(client: LanguageClient):
    yaml_file = BASE / "typo" / "config" / "agv_driver_ros1.yaml"
    text = yaml_file.read_text(encoding="utf-8")
    client.text_document_did_open(types.DidOpenTextDocumentParams(types.TextDocumentItem(
        uri=_uri(yaml_file), language_id="yaml", version=1, text=text)))
    diags = await _until(client, _uri(yaml_file), lambda d: any(x.code == "C001" for x in d))
    row = next(d.range.start.line for d in diags if d.code == "C001")
    actions = await client.text_document_code_action_async(types.CodeActionParams(
        text_document=types.TextDocumentIdentifier(uri=_uri(yaml_file)),
        range=types.Range(types.Position(row, 0), types.Position(row, 0)),
        context=types.CodeActionContext(diagnostics=[])))
    fix = next(a for a in actions if a.title.startswith("Replace 'left_wheel_jiont'"))
    edit = fix.edit.changes[_uri(yaml_file)][0]
    line = text.splitlines()[row]
    assert edit.new_text == "left_wheel_joint"
    assert line[edit.range.start.character:edit.range.end.character] == "left_wheel_jiont"
    suppress = next(a for a in actions if a.title.startswith("Suppress C001"))
    assert "# urdfcheck: ignore[C001]" in suppress.edit.changes[_uri(yaml_file)][0].new_text


def test_nothing_written_into_the_workspace():
    assert _digest(BASE) == BEFORE


def test_neovim_builtin_client_receives_the_diagnostics():
    """Debian's Neovim, headless, with its own LSP client (tools/nvim_check.sh): the same diagnostic."""
    import subprocess

    if not shutil.which("nvim"):
        pytest.skip("neovim not installed")
    env = dict(os.environ, PYTHON=sys.executable)
    proc = subprocess.run(["bash", str(REPO / "tools" / "nvim_check.sh"), str(WHEEL)], capture_output=True,
                          text=True, env=env, timeout=240)
    assert proc.stdout.split("\n")[0] == "I004 31", proc.stdout + proc.stderr
