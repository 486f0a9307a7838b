"""One set-up of lxml's parser (core/xmlfront.options, issue 42): every XML urdfcheck reads is parsed with entities
unresolved, no DTD, no network and libxml2's limits, because each copy of those options was where a hardening fix
was made once and missed once. The scan fails on any other parser construction, and on a parse without a parser."""
from __future__ import annotations

import ast
from pathlib import Path

from urdfcheck.core import xmlfront

SRC = Path(__file__).resolve().parents[2] / "src" / "urdfcheck"
MAKERS = {"XMLParser", "XMLPullParser", "HTMLParser", "iterparse", "XMLSchema"}
PARSES = {"fromstring", "XML", "parse"}


def _calls(tree):
    for node in ast.walk(tree):
        if isinstance(node, ast.Call) and isinstance(node.func, ast.Attribute):
            yield node, node.func.attr


def test_only_xmlfront_sets_up_a_parser():
    found = []
    for path in sorted(SRC.rglob("*.py")):
        rel = path.relative_to(SRC).as_posix()
        tree = ast.parse(path.read_text(encoding="utf-8"))
        for node, name in _calls(tree):
            base = node.func.value
            on_etree = isinstance(base, ast.Name) and base.id == "etree"
            if not on_etree:
                continue
            if name in MAKERS and rel != "core/xmlfront.py":
                found.append(f"{rel}:{node.lineno} etree.{name}")
            if name in PARSES and len(node.args) < 2 and not any(k.arg == "parser" for k in node.keywords):
                found.append(f"{rel}:{node.lineno} etree.{name} with lxml's default parser")
    assert not found, found


def test_the_one_parser_resolves_no_entity_and_reads_no_dtd(tmp_path):
    secret = tmp_path / "secret.txt"
    secret.write_text("TOKEN")
    doc = (f'<!DOCTYPE r [<!ENTITY x SYSTEM "file://{secret}">]><r>&x;</r>').encode()
    from urdfcheck.core.lxmlimport import etree

    for p in (xmlfront.parser(), xmlfront.parser(recover=True), xmlfront.parser(comments=False, huge=True)):
        try:
            root = etree.fromstring(doc, p)
        except etree.XMLSyntaxError:
            continue
        assert "TOKEN" not in etree.tostring(root).decode()
    assert xmlfront.options(comments=False)["remove_comments"] and not xmlfront.options()["huge_tree"]


def test_pathlib_is_imported_without_urllib():
    """urdfcheck imports pathlib without urllib.parse and ipaddress (core/pathimport.py); `Path.as_uri()` still
    works, and a later `import urllib.parse` is the real module. In an interpreter without site (this venv's
    site imports urllib itself)."""
    import os
    import subprocess
    import sys
    from pathlib import Path

    import urdfcheck

    code = ("import sys, urdfcheck; before = ('urllib.parse' in sys.modules, 'ipaddress' in sys.modules, "
            "'pathlib' in sys.modules); from pathlib import Path; uri = Path('/a b').as_uri(); "
            "import urllib.parse; print(before, uri, urllib.parse.quote('a b'), hasattr(urllib.parse, '_stand_in'))")
    env = dict(os.environ, PYTHONPATH=str(Path(urdfcheck.__file__).resolve().parents[1]))
    out = subprocess.run([sys.executable, "-S", "-c", code], env=env, capture_output=True, text=True, timeout=60)
    assert out.stdout.strip() == "(False, False, True) file:///a%20b a%20b False", out.stdout + out.stderr
