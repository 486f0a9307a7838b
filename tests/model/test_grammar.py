"""The one model builder reads every element of the URDF grammar, and reports every way the grammar says an
element can be wrong, where it is written. Generated from model/grammar.py, not hand-listed: an element,
attribute or kind added to the grammar is covered here at once.

Two views are compared. The compiled readers (build.py, the only way the builder reads attributes) against a
plain interpretation of the grammar written here (`expected`); and the whole build against the issue each
mutation must produce, at the mutated element's line: an element the builder forgot to read, or read
without its reader, fails here even when the document is otherwise ordinary.
"""
from __future__ import annotations

import math
import random

import pytest
from lxml import etree

from urdfcheck.core.findings import Location
from urdfcheck.model import build as B
from urdfcheck.model import grammar as G
from urdfcheck.model import readergen

ROBOT_CHILDREN = ("material", "link", "joint")  # the rest are extension blocks, kept raw


def sample(a: G.Attr) -> str:
    if a.kind == G.NUMBER:
        return "0.25"
    if a.kind == G.VECTOR:
        return " ".join(["0.5"] * a.size)
    return f"{a.name}_v"


def element(tag: str, version, shape: str = "box") -> etree._Element:
    """`<tag>` with every attribute `version` reads and, recursively, every child element the grammar allows
    (one shape per geometry)."""
    el = etree.Element(tag)
    later = {n for group in G.GRAMMAR[tag].exclusive for n in group[1:]}  # one of each exclusive group
    for a in G.GRAMMAR[tag].attrs:
        if a.since <= version and a.name not in later:
            el.set(a.name, sample(a))
    kids = G.children(tag)
    if tag == "geometry":
        kids = (shape,)
    elif tag == "robot":
        kids = ROBOT_CHILDREN
    for c in kids:
        el.append(element(c, version, shape))
    if tag == "robot" and version > G.V1_0:
        el.set("version", G.version_text(version))
    elif tag == "robot":
        del el.attrib["version"]
    return el


def document(version, shape: str = "box") -> bytes:
    return etree.tostring(element("robot", version, shape), pretty_print=True)


def build(data: bytes):
    root = etree.fromstring(data)
    return B.build(root, lambda el: Location("g.urdf", el.sourceline), "g.urdf"), root


def expected(el, version):
    """What the grammar says `el`'s attributes read as: (values, issue codes), straightforwardly."""
    values, codes = [], []
    for a in G.GRAMMAR[el.tag].attrs:
        if a.since > version:
            if el.get(a.name) is not None:
                codes.append("U008")
            continue
        raw = el.get(a.name)
        req = G.required(a, version)
        if raw is None or (a.kind == G.NAME and raw == ""):
            if req:
                codes.append("U006")
            values.append(None if a.kind == G.NAME else a.default)
            continue
        if a.kind in (G.TEXT, G.NAME):
            values.append(raw)
            continue
        parts = raw.split()
        if a.kind == G.VECTOR and len(parts) != a.size:
            codes.append("U004")
            values.append(a.default)
            continue
        try:
            nums = [float(p) for p in parts] if a.kind == G.VECTOR else [float(raw)]
            ok = "_" not in raw and all(math.isfinite(v) for v in nums)
        except ValueError:
            ok = False
        if not ok:
            codes.append("U005")
            values.append(a.default)
        else:
            values.append(tuple(nums) if a.kind == G.VECTOR else nums[0])
    readable = G.attributes(el.tag, version)
    for group in G.GRAMMAR[el.tag].exclusive:
        if all(n in readable and el.get(n) is not None for n in group):
            codes.append("U009")
    known = G.attributes(el.tag, G.NEWEST) | {G.SRC_ATTR}
    codes += ["U003" for k in el.keys() if k not in known and not k.startswith("{")]
    if not G.children(el.tag):
        codes += ["U002" for c in el if isinstance(c.tag, str)]
    return values, sorted(codes)


# --- mutations, from the grammar ---------------------------------------------------------------------------
def mutations(tag: str, version):
    """(name, edit(el), issue code) for every way the grammar says `<tag>` can be wrong in `version`."""
    el = G.GRAMMAR[tag]
    mates = {n: [m for m in g if m != n] for g in el.exclusive for n in g}

    def put(e, n, value):  # set one attribute, dropping the ones it must not be given with
        for m in mates.get(n, ()):
            e.attrib.pop(m, None)
        e.set(n, value)

    out = [("unknown-attribute", lambda e: e.set("bogus_attr", "1"), "U003")]
    if G.children(tag):
        out.append(("unknown-child", lambda e: e.append(etree.Element("bogus_child")), "U002"))
    else:
        out.append(("child-of-leaf", lambda e: e.append(etree.Element("bogus_child")), "U002"))
    readable = G.attributes(tag, version)
    for group in el.exclusive:
        if all(n in readable for n in group):
            out.append(("+".join(group), lambda e, g=group: [e.set(n, sample(_attr(tag, n))) for n in g], "U009"))
    for a in el.attrs:
        n = a.name
        if a.since > version:
            out.append((f"{n}-needs-{G.version_text(a.since)}", lambda e, n=n, a=a: put(e, n, sample(a)), "U008"))
            continue
        if G.required(a, version):
            out.append((f"{n}-missing", lambda e, n=n: e.attrib.pop(n, None), "U006"))
        if a.kind == G.NAME and G.required(a, version):
            out.append((f"{n}-empty", lambda e, n=n: put(e, n, ""), "U006"))
        if a.kind == G.NUMBER:
            out += [(f"{n}-word", lambda e, n=n: put(e, n, "x"), "U005"),
                    (f"{n}-nan", lambda e, n=n: put(e, n, "nan"), "U005"),
                    (f"{n}-inf", lambda e, n=n: put(e, n, "-inf"), "U005"),
                    (f"{n}-underscore", lambda e, n=n: put(e, n, "1_0"), "U005")]
        if a.kind == G.VECTOR:
            out += [(f"{n}-short", lambda e, n=n, k=a.size: put(e, n, " ".join(["1"] * (k - 1))), "U004"),
                    (f"{n}-long", lambda e, n=n, k=a.size: put(e, n, " ".join(["1"] * (k + 1))), "U004"),
                    (f"{n}-nan", lambda e, n=n, k=a.size: put(e, n, " ".join(["nan"] + ["1"] * (k - 1))), "U005"),
                    (f"{n}-word", lambda e, n=n, k=a.size: put(e, n, " ".join(["1"] * (k - 1) + ["x"])), "U005")]
    return out


def _attr(tag, name) -> G.Attr:
    return next(a for a in G.GRAMMAR[tag].attrs if a.name == name)


def cases():
    for version in G.VERSIONS:
        for shape in G.SHAPES:
            if shape == "capsule" and version < G.V1_1:
                continue  # U008 on the shape itself, see test_capsule_needs_1_1
            root = etree.fromstring(document(version, shape))
            seen = set()
            for k, el in enumerate(root.iter()):
                if el.tag in seen or (shape != "box" and el.tag != shape):
                    continue  # each element once per version; the other shapes only for themselves
                seen.add(el.tag)
                for name, edit, code in mutations(el.tag, version):
                    if el.tag == "robot" and name.startswith("version"):
                        continue
                    yield pytest.param(version, shape, k, edit, code,
                                       id=f"{G.version_text(version)}-{el.tag}-{name}")


CASES = list(cases())


def test_every_grammar_element_is_in_the_generated_documents():
    tags = {el.tag for v in G.VERSIONS for s in G.SHAPES for el in etree.fromstring(document(v, s)).iter()}
    assert tags == set(G.GRAMMAR)


@pytest.mark.parametrize("version", G.VERSIONS, ids=G.version_text)
def test_generated_documents_read_without_issues(version):
    for shape in G.SHAPES:
        if shape == "capsule" and version < G.V1_1:
            continue
        model, _ = build(document(version, shape))
        assert model.issues == (), (shape, model.issues)
        assert model.version == version


@pytest.mark.parametrize("version,shape,index,edit,code", CASES)
def test_each_mutation_is_reported_at_its_element(version, shape, index, edit, code):
    root = etree.fromstring(document(version, shape))
    el = list(root.iter())[index]
    edit(el)
    data = etree.tostring(root, pretty_print=True)
    model, root2 = build(data)
    el2 = list(root2.iter())[index]
    codes = [i.code for i in model.issues]
    assert code in codes, (code, model.issues)
    hit = next(i for i in model.issues if i.code == code)
    line = el2.sourceline if code != "U002" else next(c for c in el2 if c.tag == "bogus_child").sourceline
    assert hit.loc.line == line
    # nothing else is reported: the mutation is the only thing wrong
    assert set(codes) == {code}, model.issues


@pytest.mark.parametrize("version", G.VERSIONS, ids=G.version_text)
def test_compiled_readers_agree_with_the_grammar(version):
    """Every element of every generated and randomly mutated document: the compiled reader's values and issues
    equal a plain reading of the grammar."""
    rng = random.Random(hash(version))
    for _ in range(40):
        root = etree.fromstring(document(version, rng.choice([s for s in G.SHAPES
                                                              if s != "capsule" or version >= G.V1_1])))
        els = [el for el in root.iter() if el.tag in G.GRAMMAR]
        for el in rng.sample(els, 4):
            muts = [m for m in mutations(el.tag, version) if not (el.tag == "robot" and m[0].startswith("version"))]
            rng.choice(muts)[1](el)
        b = B._Builder(lambda e: Location("g.urdf", e.sourceline), "g.urdf", version, None)
        for el in root.iter():
            if el.tag not in G.GRAMMAR:
                continue
            before = len(b.issues)
            got = list(B.readers(version)[el.tag](b, el))
            want, codes = expected(el, version)
            assert got == want, (el.tag, etree.tostring(el))
            assert sorted(i.code for i in b.issues[before:]) == codes, (el.tag, etree.tostring(el))


def test_capsule_needs_1_1():
    model, _ = build(document(G.V1_0, "capsule"))
    assert [i.code for i in model.issues] == ["U008", "U008"]  # in the visual and in the collision


def test_reader_source_is_plain_python_from_the_grammar():
    src = readergen.reader_source("limit", G.V1_2)
    for a in G.GRAMMAR["limit"].attrs:
        assert repr(a.name) in src
    assert "acceleration" not in readergen.reader_source("limit", G.V1_0)


def test_generated_readers_are_up_to_date():
    assert readergen.PATH.read_text(encoding="utf-8") == readergen.module_source(), \
        "model/readers.py is stale: regenerate it with `PYTHONPATH=src python -m urdfcheck.model.readergen`"


@pytest.mark.parametrize("version", G.VERSIONS, ids=G.version_text)
def test_in_memory_readers_equal_the_generated_ones(version):
    """What build.readers falls back to when readers.py is stale reads exactly like readers.py."""
    from urdfcheck.model.readers import READERS

    mem = readergen.compiled(version)
    assert mem.keys() == READERS[version].keys()
    for tag in G.GRAMMAR:
        assert mem[tag].__code__.co_code == READERS[version][tag].__code__.co_code, tag


def test_attributes_by_version_for_other_checks():
    assert "quat_xyzw" not in G.attributes("origin", G.V1_0)
    assert "quat_xyzw" in G.attributes("origin", G.V1_1)
    assert {"acceleration", "deceleration", "jerk"} <= G.attributes("limit", G.V1_2)
    assert not {"acceleration", "deceleration", "jerk"} & G.attributes("limit", G.V1_1)
    assert G.introduced("limit", "jerk") == G.V1_2 and G.introduced("limit", "bogus") is None
    assert G.attributes("bogus") == frozenset()


@pytest.mark.parametrize("version", G.VERSIONS, ids=G.version_text)
def test_xacro_source_markers_are_not_attributes(version):
    root = etree.fromstring(document(version))
    for el in root.iter():
        el.set(G.SRC_ATTR, "0:1")
    model, _ = build(etree.tostring(root))
    assert model.issues == ()
    for el in root.iter():
        if el.tag == "mass":
            el.set("bogus_attr", "1")
        if el.tag == "inertia":
            del el.attrib["ixx"]
    model, _ = build(etree.tostring(root))
    assert sorted(i.code for i in model.issues) == ["U003", "U006"]


@pytest.mark.parametrize("xyz, finite", [("1e308 1e308 0", True), ("-1.7e308 -1.7e308 1", True),
                                         ("1 inf 0", False), ("nan 0 0", False), ("inf -inf 0", False)])
def test_a_vector_whose_sum_overflows_is_still_finite(xyz, finite):
    """The vector reader's fast test is a finite sum; a sum that overflows must not make finite values unreadable."""
    m = B.model_from_string(f'<robot name="r"><link name="a"><visual><origin xyz="{xyz}"/><geometry><box size="1 1 1"/>'
                            '</geometry></visual></link></robot>')
    bad = [i for i in m.issues if i.code == "U005"]
    assert (not bad) == finite
    if finite:
        assert m.links["a"].visuals[0].origin.xyz == tuple(float(v) for v in xyz.split())
