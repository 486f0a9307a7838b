"""Parity with stock xacro (issue 37): the sandbox accepts every property name and expression stock xacro accepts,
except its stated safety refusals (load/xacro/safeeval.py's module doc), on the same document.

Stock xacro runs in this process, as a library, on generated harmless expressions only (arithmetic, strings,
names, a few allowed calls); never on a file from outside the test."""
import os
import tempfile

from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from urdfcheck.load import loader

XACRO_NS = 'xmlns:xacro="http://www.ros.org/wiki/xacro"'


def stock(text: str, path: str):
    """('ok', pretty XML) or ('error', exception class name) from stock xacro on the document."""
    import xacro

    try:
        return "ok", xacro.process_file(path).toprettyxml(indent="  ")  # the file just written from `text`
    except Exception as e:  # noqa: BLE001 - any stock failure is "stock refuses this document"
        return "error", type(e).__name__


def ours(path: str):
    exp = loader.expand(path, {}, timeout=60)
    if exp.root is None:
        return "error", [(f.code, f.message) for f in exp.findings]
    return "ok", exp.clean_text()


def compare(text: str):
    with tempfile.TemporaryDirectory() as tmp:
        path = os.path.join(tmp, "gen.urdf.xacro")
        with open(path, "w", encoding="utf-8") as f:
            f.write(text)
        theirs = stock(text, path)
        mine = ours(path)
    if theirs[0] == "ok":
        assert mine == theirs, (text, theirs[1], mine[1])
    else:
        assert mine[0] == "error", (text, theirs[1], mine[1])


# property names: identifiers with 0..2 leading underscores, sometimes a keyword or a builtin's name
names = st.one_of(
    st.from_regex(r"_{0,2}[A-Za-z][A-Za-z0-9_]{0,5}", fullmatch=True),
    st.sampled_from(["_", "_x", "_origin_xyz", "__x", "x__", "len", "pi", "math", "True", "None", "class", "lambda"]),
)
numbers = st.one_of(st.integers(-1000, 1000).map(str), st.floats(-100, 100, allow_nan=False).map(lambda x: f"{x:.3f}"))
strings = st.from_regex(r"[a-z_ ]{0,6}", fullmatch=True).map(repr)


def expressions(refs):
    leaf = st.one_of(numbers, strings, st.sampled_from(refs))
    return st.recursive(leaf, lambda sub: st.one_of(
        st.tuples(sub, st.sampled_from(["+", "-", "*", "==", "<", " and ", " or ", " if True else "]), sub)
        .map(lambda t: f"({t[0]}{t[1]}{t[2]})"),
        sub.map(lambda e: f"str({e})"),
        sub.map(lambda e: f"[_v for _v in [{e}]][0]"),
        sub.map(lambda e: f"python.abs(len(str({e})))"),
        sub.map(lambda e: f"str({e}).upper()"),
        sub.map(lambda e: f"xacro.dotify(dict(_k={e}))._k"),
        sub.map(lambda e: f"[{e}, 1].pop(0)"),
        sub.map(lambda e: f"'{{}}-{{}}'.format({e}, {e})"),
        sub.map(lambda e: f"{{'a': {e}}}.get('a')"),
    ), max_leaves=4)


@st.composite
def documents(draw):
    props = draw(st.lists(names, min_size=1, max_size=3, unique=True))
    lines = []
    defined = []
    for name in props:
        value = draw(expressions(defined + [name]) if defined else st.one_of(numbers, strings))
        lines.append(f'  <xacro:property name="{name}" value="${{{value}}}"/>')
        defined.append(name)
    expr = draw(expressions(defined))
    lines.append(f'  <link name="l"><visual><material name="${{{expr}}}"/></visual></link>')
    return f'<robot name="r" {XACRO_NS}>\n' + "\n".join(lines) + "\n</robot>\n"


@settings(max_examples=120, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(documents())
def test_sandbox_accepts_what_stock_xacro_accepts(text):
    compare(text)


def test_a_property_with_one_leading_underscore_is_an_ordinary_name():
    """The report's case: stock accepts `_origin_xyz`; the sandbox refused it as X011 "reserved" and the whole robot
    went unlinted."""
    compare(f'<robot name="r" {XACRO_NS}>\n  <xacro:property name="_origin_xyz" value="0 0 0.1"/>\n'
            '  <link name="a"/><link name="b"/>\n  <joint name="j" type="fixed"><parent link="a"/><child link="b"/>'
            '<origin xyz="${_origin_xyz}"/></joint>\n</robot>\n')


def test_a_yaml_style_key_with_one_underscore_reads_as_stock_reads_it():
    compare(f'<robot name="r" {XACRO_NS}>\n  <xacro:property name="cfg" value="${{xacro.dotify(dict(_a=2))}}"/>\n'
            '  <link name="l${cfg._a}"/>\n</robot>\n')


def test_double_underscore_stays_refused_as_stock_refuses_it():
    compare(f'<robot name="r" {XACRO_NS}>\n  <link name="${{__x}}"/>\n</robot>\n')



def test_a_list_popped_in_a_recursive_macro_expands_as_in_stock():
    """ar4_description pops its mesh and material lists in a recursive macro: the sandbox refused list.pop and the
    whole robot went unlinted."""
    compare(f'<robot name="r" {XACRO_NS}>\n'
            '  <xacro:macro name="chain" params="names">\n'
            '    <xacro:if value="${names}">\n'
            '      <link name="${names.pop(0)}"/>\n'
            '      <xacro:chain names="${names}"/>\n'
            '    </xacro:if>\n'
            '  </xacro:macro>\n'
            '  <xacro:property name="all" value="${[\'a\', \'b\', \'c\']}"/>\n'
            '  <xacro:chain names="${all}"/>\n'
            '  <xacro:property name="d" value="${dict(x=1, y=2)}"/>\n'
            '  <link name="l${d.pop(\'x\')}${len(d)}"/>\n'
            '</robot>\n')


def test_growing_a_value_in_place_stays_refused():
    import xacro

    from urdfcheck.load.xacro.safeeval import Refused, default_evaluator

    ev = default_evaluator(xacro._global_symbols)
    table = xacro.Table(xacro._global_symbols)
    table["l"] = [1]
    for expr in ("l.append(1)", "l.extend([1])", "l.insert(0, 1)"):
        try:
            ev.evaluate(expr, table)
        except Refused:
            continue
        raise AssertionError(f"{expr} was not refused")
