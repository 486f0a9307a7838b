"""Property-based robustness of the whole CLI on mutated inputs (bounded: the file runs in well under a minute).

Seeds are the example package (examples/agv): its plain URDF, its xacro entry and macro file, its controller
and driver YAML and its launch file. Mutations: byte flips, insertions, deletions, truncation; XML element
duplication/deletion, attribute and text replacement with hostile strings, deep nesting; YAML value
replacement, structure swaps, anchors/aliases and tags. For every input:

* the CLI exits 0 or 1 (2 would be a usage error or an internal error: the file exists);
* stderr carries no traceback and no "internal error";
* the call returns within PER_CALL seconds;
* the JSON report parses and validates against src/urdfcheck/schemas/report.schema.json.

URDF and xacro files are linted by path; YAML and launch files by linting the package folder that holds
them (the contracts readers pick them up; if a reader is not wired the property still must hold).
A longer, coverage-guided run lives in fuzz/fuzz_lint.py (atheris).
"""
from __future__ import annotations

import copy
import json
import os
import shutil
import sys
import tempfile
import time
from pathlib import Path

import pytest

hypothesis = pytest.importorskip("hypothesis")
jsonschema = pytest.importorskip("jsonschema")
yaml = pytest.importorskip("yaml")
from conftest import REPO, run_cli  # noqa: E402
from hypothesis import HealthCheck, given, settings  # noqa: E402
from hypothesis import strategies as st  # noqa: E402
from lxml import etree  # noqa: E402

AGV = REPO / "examples" / "agv"
SCHEMA = json.loads((REPO / "src" / "urdfcheck" / "schemas" / "report.schema.json").read_text())
VALIDATOR = jsonschema.Draft202012Validator(SCHEMA)
PER_CALL = float(os.environ.get("URDFCHECK_FUZZ_CALL_BOUND", "15"))  # s; generous: CI boxes are slow
XACRO_TIMEOUT = "5"  # the CLI's --timeout for one expansion during fuzzing
FUZZ = settings(max_examples=int(os.environ.get("URDFCHECK_FUZZ_EXAMPLES", "60")), deadline=None,
                suppress_health_check=[HealthCheck.too_slow, HealthCheck.data_too_large], print_blob=True)

HOSTILE = [
    "", " ", "0", "-0", "nan", "NaN", "inf", "-inf", "1e309", "-1e-320", "1_000", "0x10", "1 2", "1 2 3 4",
    "1,2,3", "true", "None", "${", "$(", "${1/0}", "${undefined}", "$(arg nope)", "$(env HOME)", "$(optenv X y)",
    "$(cwd)", "$(find nope)", "$(eval 1/0)", "${__import__('os')}", "${'a'*10**9}", "${10**10**8}",
    "${[x for x in python.range(10**7)]}", "package://", "package:///x.stl", "package://nope/x.stl",
    "file:///etc/passwd", "../../../../etc/passwd", "/etc/passwd", "http://example.invalid/x.stl",
    "::error file=x::pwned", "##vso[task.setvariable variable=x]1", "\u202e\u2066bidi", "a\u2028b",
    "\x85", "\x9b31m", "<", "]]>", "&amp;", "%s%n", "{0.__class__}", "*a", "&a", "!degrees 90",
    "!!python/object/apply:os.system ['true']", "x" * 5000, "ü" * 300, "\U0001f916",
]
SAFE_HOSTILE = [h for h in HOSTILE if all(c == "\t" or c == "\n" or ord(c) >= 32 for c in h)
                and not any(0x7f <= ord(c) <= 0x9f for c in h)]  # what lxml can store in an attribute
TAGS = ["link", "joint", "robot", "xacro:if", "xacro:macro", "xacro:include", "xacro:property", "group",
        "node", "param", "include", "origin", "inertial", "mesh", "transmission", "ros2_control"]
HOSTILE_BYTES = [b"\x00", b"\xff\xfe", b"\xc3", b"<!DOCTYPE r [<!ENTITY e 'x'>]>", b"<?pi x?>", b"&e;",
                 b"<![CDATA[", b"]]>", b"<!--", b"\r", b"\x1b[31m", b"${", b"$(", b"\t" * 10, b"<" * 50]


# ---- helpers --------------------------------------------------------------------------------------

def check_cli(args, cwd) -> dict:
    """Run the CLI; assert the robustness properties; return the parsed JSON report."""
    t0 = time.monotonic()
    code, out, err = run_cli(["lint", "--no-config", "--format", "json", "--timeout", XACRO_TIMEOUT, *args],
                             cwd=cwd)
    took = time.monotonic() - t0
    where = f"{args}: exit {code}\nstderr: {err[:2000]}\nstdout: {out[:2000]}"
    assert code in (0, 1), where
    assert "Traceback" not in err and "internal error" not in err, where
    assert took <= PER_CALL, f"{took:.1f} s: {where}"
    report = json.loads(out)
    errors = sorted(VALIDATOR.iter_errors(report), key=lambda e: list(e.path))
    assert not errors, f"{where}\nschema: {errors[0].message} at {list(errors[0].path)}"
    return report


def byte_mutations():
    pos = st.floats(min_value=0, max_value=1, allow_nan=False)
    return st.lists(st.one_of(
        st.tuples(st.just("flip"), pos, st.integers(0, 7)),
        st.tuples(st.just("trunc"), pos),
        st.tuples(st.just("delete"), pos, st.integers(1, 64)),
        st.tuples(st.just("insert"), pos, st.one_of(st.sampled_from(HOSTILE_BYTES), st.binary(max_size=16))),
        st.tuples(st.just("dup"), pos, st.integers(1, 400)),
    ), max_size=4)


def apply_bytes(data: bytes, ops) -> bytes:
    for op in ops:
        i = int(op[1] * len(data)) if data else 0
        if op[0] == "flip" and data:
            i = min(i, len(data) - 1)
            data = data[:i] + bytes([data[i] ^ (1 << op[2])]) + data[i + 1:]
        elif op[0] == "trunc":
            data = data[:i]
        elif op[0] == "delete":
            data = data[:i] + data[i + op[2]:]
        elif op[0] == "insert":
            data = data[:i] + op[2] + data[i:]
        elif op[0] == "dup":
            data = data[:i] + data[i:i + op[2]] + data[i:]
    return data


def xml_mutations():
    idx = st.floats(min_value=0, max_value=1, allow_nan=False)
    return st.lists(st.one_of(
        st.tuples(st.just("dup"), idx),
        st.tuples(st.just("del"), idx),
        st.tuples(st.just("attr"), idx, st.integers(0, 5), st.sampled_from(SAFE_HOSTILE)),
        st.tuples(st.just("newattr"), idx, st.sampled_from(["name", "type", "value", "filename", "xyz", "rpy",
                                                             "link", "params", "if", "default", "scope"]),
                  st.sampled_from(SAFE_HOSTILE)),
        st.tuples(st.just("text"), idx, st.sampled_from(SAFE_HOSTILE)),
        st.tuples(st.just("nest"), idx, st.integers(1, 300), st.sampled_from(TAGS)),
        st.tuples(st.just("retag"), idx, st.sampled_from(TAGS)),
    ), min_size=1, max_size=5)


XACRO_NS = "http://www.ros.org/wiki/xacro"


def _tag(root, name: str) -> str:
    if name.startswith("xacro:"):
        return f"{{{XACRO_NS}}}{name[6:]}"
    return name


def apply_xml(data: bytes, ops) -> bytes:
    parser = etree.XMLParser(remove_comments=False, resolve_entities=False)
    root = etree.fromstring(data, parser)
    for op in ops:
        elements = [e for e in root.iter() if isinstance(e.tag, str)]
        el = elements[min(int(op[1] * len(elements)), len(elements) - 1)]
        parent = el.getparent()
        try:
            if op[0] == "dup" and parent is not None:
                el.addnext(copy.deepcopy(el))
            elif op[0] == "del" and parent is not None:
                parent.remove(el)
            elif op[0] == "attr" and el.attrib:
                key = list(el.attrib)[op[2] % len(el.attrib)]
                el.set(key, op[3])
            elif op[0] == "newattr":
                el.set(op[2], op[3])
            elif op[0] == "text":
                el.text = op[2]
            elif op[0] == "nest" and parent is not None:
                outer = inner = etree.Element(_tag(root, op[3]))
                for _ in range(op[2] - 1):
                    inner = etree.SubElement(inner, _tag(root, op[3]))
                el.addprevious(outer)
                inner.append(el)
            elif op[0] == "retag":
                el.tag = _tag(root, op[2])
        except ValueError:  # lxml refuses some values (e.g. control characters): skip that operation
            continue
    return etree.tostring(root, xml_declaration=True, encoding="utf-8")


def yaml_mutations():
    idx = st.floats(min_value=0, max_value=1, allow_nan=False)
    scalar = st.one_of(st.sampled_from(HOSTILE), st.integers(), st.floats(), st.booleans(), st.none())
    return st.lists(st.one_of(
        st.tuples(st.just("set"), idx, scalar),
        st.tuples(st.just("listify"), idx),
        st.tuples(st.just("mapify"), idx),
        st.tuples(st.just("deep"), idx, st.integers(1, 400)),
        st.tuples(st.just("drop"), idx),
        st.tuples(st.just("key"), idx, st.sampled_from(HOSTILE[:30])),
    ), min_size=1, max_size=5)


def _slots(node, path=()):
    yield path
    if isinstance(node, dict):
        for k, v in node.items():
            yield from _slots(v, path + (k,))
    elif isinstance(node, list):
        for i, v in enumerate(node):
            yield from _slots(v, path + (i,))


def _get(node, path):
    for p in path:
        node = node[p]
    return node


def apply_yaml(text: str, ops) -> str:
    docs = [d for d in yaml.safe_load_all(text)]
    doc = docs[0] if docs else {}
    for op in ops:
        slots = list(_slots(doc))[1:]
        if not slots:
            break
        path = slots[min(int(op[1] * len(slots)), len(slots) - 1)]
        parent, last = _get(doc, path[:-1]), path[-1]
        value = parent[last]
        if op[0] == "set":
            parent[last] = op[2]
        elif op[0] == "listify":
            parent[last] = [value, value]
        elif op[0] == "mapify":
            parent[last] = {"x": value, str(last): value}
        elif op[0] == "deep":
            for _ in range(op[2]):
                value = [value]
            parent[last] = value
        elif op[0] == "drop":
            del parent[last]
        elif op[0] == "key" and isinstance(parent, dict):
            parent[op[2]] = parent.pop(last)
    try:
        return yaml.safe_dump(doc, sort_keys=False, allow_unicode=True, width=10**6)
    except RecursionError:  # PyYAML's dumper needs 3 frames a level; JSON is YAML and needs one
        return json.dumps(doc)


def text_tricks():
    """YAML-only text additions: anchors/aliases (incl. a small bomb), tags, merge keys, documents."""
    return st.lists(st.sampled_from([
        "\nx_anchor: &a [1, 2, 3]\ny_alias: *a\n",
        "\nbomb0: &b0 [lol, lol, lol, lol, lol, lol, lol, lol]\nbomb1: &b1 [*b0, *b0, *b0, *b0, *b0, *b0, *b0, *b0]\n"
        "bomb2: &b2 [*b1, *b1, *b1, *b1, *b1, *b1, *b1, *b1]\nbomb3: [*b2, *b2, *b2, *b2, *b2, *b2, *b2, *b2]\n",
        "\nangle: !degrees 90\n", "\nevil: !!python/object/apply:os.system ['true']\n",
        "\nmerge:\n  <<: *undefined\n", "\n---\nsecond: document\n", "\n%YAML 1.1\n---\n", "\n? [complex, key]\n: v\n",
        "\nself: &s\n  me: *s\n", "\n\t tab: indent\n", "\n" + "[" * 2000 + "]" * 2000 + "\n",
    ]), max_size=2)


# ---- fixtures: one copy of the example package per test call ---------------------------------------

class Pkg:
    """A throw-away copy of examples/agv (no urdfcheck.yaml) under a fresh temp dir."""

    def __init__(self, keep=("package.xml", "urdf", "config", "launch")):
        self._tmp = tempfile.TemporaryDirectory(prefix="urdfcheck-fuzz-")
        self.root = Path(self._tmp.name)
        self.pkg = self.root / "agv_description"
        self.pkg.mkdir()
        for name in keep:
            src = AGV / name
            (shutil.copytree if src.is_dir() else shutil.copy)(src, self.pkg / name)

    def __enter__(self):
        return self

    def __exit__(self, *exc):
        self._tmp.cleanup()


def _seed(rel: str) -> bytes:
    return (AGV / rel).read_bytes()


# ---- the properties ---------------------------------------------------------------------------------

@FUZZ
@given(xml_ops=xml_mutations(), byte_ops=byte_mutations())
def test_mutated_urdf(xml_ops, byte_ops):
    data = apply_bytes(apply_xml(_seed("urdf/agv.urdf"), xml_ops), byte_ops)
    with Pkg(keep=("package.xml",)) as p:
        f = p.pkg / "urdf" / "robot.urdf"
        f.parent.mkdir()
        f.write_bytes(data)
        check_cli([f], p.root)


@FUZZ
@given(which=st.sampled_from(["urdf/agv.urdf.xacro", "urdf/macros/components.xacro"]),
       xml_ops=xml_mutations(), byte_ops=byte_mutations())
def test_mutated_xacro(which, xml_ops, byte_ops):
    data = apply_bytes(apply_xml(_seed(which), xml_ops), byte_ops)
    with Pkg(keep=("package.xml", "urdf")) as p:
        (p.pkg / "urdf" / "agv.urdf").unlink()
        (p.pkg / which).write_bytes(data)
        check_cli([p.pkg / "urdf" / "agv.urdf.xacro"], p.root)


@FUZZ
@given(which=st.sampled_from(["config/agv_controllers.yaml", "config/agv_driver_ros1.yaml"]),
       yaml_ops=yaml_mutations(), tricks=text_tricks(), byte_ops=byte_mutations())
def test_mutated_controller_yaml(which, yaml_ops, tricks, byte_ops):
    text = apply_yaml(_seed(which).decode("utf-8"), yaml_ops) + "".join(tricks)
    data = apply_bytes(text.encode("utf-8"), byte_ops)
    with Pkg() as p:
        for x in (p.pkg / "urdf").glob("*.xacro"):  # the plain URDF keeps each call fast
            x.unlink()
        shutil.rmtree(p.pkg / "urdf" / "macros")
        (p.pkg / which).write_bytes(data)
        check_cli([p.pkg], p.root)


@FUZZ
@given(xml_ops=xml_mutations(), byte_ops=byte_mutations(), as_ros1=st.booleans())
def test_mutated_launch_xml(xml_ops, byte_ops, as_ros1):
    data = apply_bytes(apply_xml(_seed("launch/agv.launch.xml"), xml_ops), byte_ops)
    with Pkg() as p:
        for x in (p.pkg / "urdf").glob("*.xacro"):
            x.unlink()
        shutil.rmtree(p.pkg / "urdf" / "macros")
        target = p.pkg / "launch" / ("agv.launch" if as_ros1 else "agv.launch.xml")
        (p.pkg / "launch" / "agv.launch.xml").unlink()
        target.write_bytes(data)
        check_cli([p.pkg], p.root)


PY_LAUNCH = '''from launch import LaunchDescription
from launch_ros.actions import Node


def generate_launch_description():
    return LaunchDescription([
        Node(package="robot_state_publisher", executable="robot_state_publisher",
             parameters=[{"robot_description": open("/etc/passwd").read()}]),
        Node(package="controller_manager", executable="ros2_control_node",
             parameters=["config/agv_controllers.yaml"]),
        Node(package="tf2_ros", executable="static_transform_publisher",
             arguments=["--frame-id", "map", "--child-frame-id", "odom"]),
    ])
'''


@settings(FUZZ, max_examples=max(10, FUZZ.max_examples // 2))
@given(byte_ops=byte_mutations(), nest=st.integers(0, 3000), junk=st.sampled_from(SAFE_HOSTILE))
def test_mutated_python_launch_is_never_executed(byte_ops, nest, junk):
    """.launch.py files are parsed (ast), never run: a payload in one must not execute, deep nesting
    must not crash the parser."""
    src = PY_LAUNCH.replace('"map"', repr(junk)) + f"\nX = {'[' * nest}{']' * nest}\n"
    src += "\nimport os\nos.system('touch PWNED_BY_LAUNCH')\n"
    data = apply_bytes(src.encode("utf-8"), byte_ops)
    with Pkg() as p:
        for x in (p.pkg / "urdf").glob("*.xacro"):
            x.unlink()
        shutil.rmtree(p.pkg / "urdf" / "macros")
        (p.pkg / "launch" / "agv.launch.py").write_bytes(data)
        check_cli([p.pkg], p.root)
        assert not (p.root / "PWNED_BY_LAUNCH").exists() and not (p.pkg / "PWNED_BY_LAUNCH").exists()


@settings(FUZZ, max_examples=max(10, FUZZ.max_examples // 2))
@given(depth=st.integers(1, 20000), tag=st.sampled_from(["link", "xacro:if", "visual", "a"]),
       xacro=st.booleans(), close=st.booleans())
def test_deep_nesting(depth, tag, xacro, close):
    """Nesting beyond libxml2's depth cap, beyond Python's recursion limit, unclosed."""
    ns = f' xmlns:xacro="{XACRO_NS}"' if xacro or tag.startswith("xacro:") else ""
    open_tag = f'<{tag} value="1">' if tag == "xacro:if" else f"<{tag}>"
    body = open_tag * depth + (f"</{tag}>" * depth if close else "")
    data = f'<robot name="r"{ns}>\n<link name="base_link"/>\n{body}\n</robot>\n'.encode()
    with Pkg(keep=("package.xml",)) as p:
        f = p.pkg / ("deep.urdf.xacro" if xacro else "deep.urdf")
        f.write_bytes(data)
        report = check_cli([f], p.root)
        # closed <xacro:if value="1"> blocks are expanded away (the namespace makes the file xacro), as stock
        # xacro does: only libxml2's depth cap (256 levels, <robot> included) makes them a finding
        limit = 254 if tag == "xacro:if" and close else 250
        if not close or depth > limit:
            assert report["findings"], "deep or broken nesting must be a finding"


# ---- issue 11: callables handed out as values; extreme finite numbers ------------------------------

def _callables_grammar():
    import importlib.util

    spec = importlib.util.spec_from_file_location("fuzz_callables", REPO / "fuzz" / "callables.py")
    mod = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(mod)
    return mod


CALLABLES = _callables_grammar()


@settings(FUZZ, max_examples=max(20, FUZZ.max_examples))
@given(rnd=st.randoms(use_true_random=False))
def test_callables_as_values_leak_nothing(rnd):
    """fuzz/callables.py's grammar (a guarded method or function passed to map/filter/sorted(key=)/min/max, nested
    maps, properties, $(eval), unit tags) through the whole CLI: with a secret in the environment and a marker in
    argv, no output holds either (nor a module's file path nor the workspace's absolute path)."""
    case = CALLABLES.generate(rnd)
    old_argv = list(sys.argv)
    os.environ[CALLABLES.SECRET_VAR] = CALLABLES.SECRET
    sys.argv.append(CALLABLES.ARGV_MARK)
    try:
        with Pkg(keep=("package.xml",)) as p:
            (p.pkg / "config").mkdir(exist_ok=True)
            f = p.pkg / "urdf" / "p.urdf.xacro"
            f.parent.mkdir(exist_ok=True)
            f.write_text(case["xacro"], encoding="utf-8")
            if case["yaml"] is not None:
                (p.pkg / "config" / "u.yaml").write_text(case["yaml"], encoding="utf-8")
            (p.root / "outside").mkdir()
            (p.root / "outside" / "secret.yaml").write_text(f"x: {CALLABLES.FILE_SECRET}\n")
            report = check_cli([f], p.root)
            text = json.dumps(report)
            for marker in CALLABLES.LEAK_MARKERS + (str(p.root),):
                assert marker not in text, (marker, case["xacro"][-300:])
    finally:
        sys.argv[:] = old_argv
        os.environ.pop(CALLABLES.SECRET_VAR, None)


EXTREME = [1.7976931348623157e308, -1.7976931348623157e308, 1e308, 1e200, -1e200, 1e154, 1e-300, -1e-300,
           5e-324, -5e-324, 0.0, -0.0, 2.0 ** 53 + 1, 1e16, 3.4e38]


@settings(FUZZ, max_examples=max(30, FUZZ.max_examples))
@given(data=st.data())
def test_extreme_finite_numbers_are_findings_not_crashes(data):
    """Every number of every numeric attribute of the example URDF replaced by an extreme finite float (hypothesis
    picks which): rules report the values, none crashes (R001: 'rule ... crashed', e.g. OverflowError)."""
    root = etree.fromstring(_seed("urdf/agv.urdf"))
    slots = [(el, name) for el in root.iter() if isinstance(el.tag, str) for name, value in el.attrib.items()
             if all(_is_number(v) for v in value.split()) and value.split()]
    floats = st.one_of(st.sampled_from(EXTREME), st.floats(allow_nan=False, allow_infinity=False))
    picked = data.draw(st.lists(st.sampled_from(range(len(slots))), min_size=1, max_size=12, unique=True))
    for i in picked:
        el, name = slots[i]
        n = len(el.get(name).split())
        el.set(name, " ".join(repr(data.draw(floats)) for _ in range(n)))
    with Pkg(keep=("package.xml",)) as p:
        f = p.pkg / "urdf" / "robot.urdf"
        f.parent.mkdir()
        f.write_bytes(etree.tostring(root))
        report = check_cli([f], p.root)
        crashed = [x["message"] for x in report["findings"] if x["code"] == "R001"]
        assert not crashed, crashed


def _is_number(text: str) -> bool:
    try:
        float(text)
    except ValueError:
        return False
    return True
