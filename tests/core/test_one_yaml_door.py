"""One door for YAML (core/yamldoor, issue 42): the size, nesting and alias-bomb guards, and their limits, are
written once. xacro's `load_yaml` and the recordings (`load.xacro.yamlguard`) and the consumer files
(`consumers.yamlsrc`) had a guard each, with different limits and different holes. The scan fails when a second
module walks YAML events to bound nesting, or when a function parses YAML without passing the door first."""
from __future__ import annotations

import ast
from pathlib import Path

import pytest

from urdfcheck.core import yamldoor

SRC = Path(__file__).resolve().parents[2] / "src" / "urdfcheck"
DOOR = "core/yamldoor.py"
PARSES = {"load", "load_all", "safe_load", "safe_load_all", "full_load", "unsafe_load", "compose", "compose_all",
          "parse", "scan"}
GUARDS = {"check", "compose_first", "check_yaml_text", "parse_yaml", "load_yaml"}
# the package's own data files (shipped with urdfcheck, never a checked tree's)
OWN_DATA = {"model/extensions.py", "rules/catalogue.py"}


def _functions(tree):
    for node in ast.walk(tree):
        if isinstance(node, (ast.FunctionDef, ast.AsyncFunctionDef)):
            yield node


def _called(fn) -> set[str]:
    out = set()
    for node in ast.walk(fn):
        if isinstance(node, ast.Call):
            f = node.func
            out.add(f.attr if isinstance(f, ast.Attribute) else getattr(f, "id", ""))
    return out


def _sources():
    for path in sorted(SRC.rglob("*.py")):
        yield path.relative_to(SRC).as_posix(), ast.parse(path.read_text(encoding="utf-8"))


def test_only_the_door_bounds_yaml_nesting():
    found = []
    for rel, tree in _sources():
        if rel == DOOR:
            continue
        for node in ast.walk(tree):
            if isinstance(node, ast.Attribute) and node.attr in ("SequenceStartEvent", "MappingStartEvent"):
                found.append(f"{rel}:{node.lineno} walks YAML events ({node.attr})")
            if isinstance(node, ast.Assign) and isinstance(node.value, (ast.Constant, ast.BinOp)):
                for t in node.targets:
                    if isinstance(t, ast.Name) and t.id in ("MAX_NODES", "MAX_BYTES") and "yaml" in rel:
                        found.append(f"{rel}:{node.lineno} states a YAML limit ({t.id})")
    assert not found, found


def test_every_yaml_parse_passes_the_door():
    found = []
    for rel, tree in _sources():
        if rel == DOOR or rel in OWN_DATA:
            continue
        for fn in _functions(tree):
            calls = [n for n in ast.walk(fn) if isinstance(n, ast.Call) and isinstance(n.func, ast.Attribute)
                     and isinstance(n.func.value, ast.Name) and n.func.value.id == "yaml" and n.func.attr in PARSES]
            if calls and not (_called(fn) & GUARDS):
                found += [f"{rel}:{c.lineno} yaml.{c.func.attr} in {fn.name}() without the YAML door" for c in calls]
    assert not found, found


def test_the_limits_are_named_per_use():
    assert yamldoor.CONSUMER.max_bytes < yamldoor.XACRO.max_bytes
    assert yamldoor.CONSUMER.max_nodes < yamldoor.XACRO.max_nodes


BOMB = "a: &a [x, x, x, x, x, x, x, x, x, x]\n" + "".join(
    f"{c}: &{c} [*{p}, *{p}, *{p}, *{p}, *{p}, *{p}, *{p}, *{p}, *{p}, *{p}]\n" for p, c in zip("abcdefg", "bcdefgh"))


@pytest.mark.parametrize("text, what", [
    ("[" * 300 + "]" * 300, "depth"),
    ("? " * 300 + "x\n", "depth"),
    (BOMB, "bomb"),
    ("---\nok: 1\n---\n" + BOMB, "bomb"),  # the second document of a stream (a recording) counts too
])
def test_the_door_refuses(text, what):
    with pytest.raises(yamldoor.Refused) as e:
        yamldoor.check(text, yamldoor.XACRO)
    assert e.value.what == what


def test_the_xacro_guard_and_the_consumer_reader_refuse_the_same_nesting():
    """Block-dash nesting: the consumer reader refused it by a linear pre-scan the xacro guard did not have."""
    from urdfcheck.consumers.common import ConsumerError
    from urdfcheck.consumers.yamlsrc import parse_yaml
    from urdfcheck.load.xacro import yamlguard

    text = "- " * 300 + "x\n"
    with pytest.raises(ConsumerError, match="nested deeper than 256"):
        parse_yaml(text, "p.yaml")
    with pytest.raises(yamlguard.YamlRefused, match="nests deeper than 256"):
        yamlguard.check_yaml_text(text, "p.yaml")


def test_a_multi_document_recording_with_anchors_is_read():
    """The old xacro guard composed one document only: a YAML stream with an anchor was refused as not YAML."""
    from urdfcheck.load.xacro import yamlguard

    yamlguard.check_yaml_text("---\na: &x [1]\nb: *x\n---\nc: 2\n", "rec.yaml")
