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
