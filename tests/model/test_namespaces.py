"""XML namespaces read like urdfdom reads them (issue 15, precision).

urdfdom, Pinocchio, MuJoCo and Drake parse URDF with TinyXML2, which ignores namespaces: a `<robot
xmlns="http://...">` is a plain robot and `<drake:joint_lower_limit>` without xmlns:drake is an element whose name
has a colon. urdfcheck reads such files the same way (the rest of the checks run) and says at most a warning
(X005) where another consumer misbehaves; every other hardening of the XML front end stays.
"""
import sys
import textwrap
from pathlib import Path

import pytest

sys.path.insert(0, str(Path(__file__).resolve().parent.parent))

from conftest import lint_json  # noqa: E402

from urdfcheck.core import xmlfront  # noqa: E402
from urdfcheck.load import loader  # noqa: E402
from urdfcheck.model.build import model_from_string  # noqa: E402

ARM = """
  <link name="base_link"/>
  <link name="arm"/>
  <joint name="j1" type="revolute">
    <parent link="base_link"/><child link="{child}"/><axis xyz="0 0 1"/>
    <limit lower="-1" upper="1" effort="1" velocity="1"/>{extra}
  </joint>
"""


def robot(head: str, child: str = "arm", extra: str = "", tail: str = "") -> str:
    return f"<robot {head}>{ARM.format(child=child, extra=extra)}{tail}</robot>\n"


def codes(tmp_path: Path, text: str, name: str = "r.urdf") -> list[tuple[str, int | None]]:
    p = tmp_path / name
    p.write_text(textwrap.dedent(text), encoding="utf-8")
    _, out = lint_json([str(p)])
    return [(f["code"], f["location"]["line"]) for f in out["findings"]]


def _codes_of(out_codes):
    return [c for c, _ in out_codes]


# --- a default namespace on the root -------------------------------------------------------------------------

def test_default_namespace_root_is_a_robot_and_its_real_errors_are_reported(tmp_path):
    found = codes(tmp_path, robot('name="r" xmlns="http://www.ros.org"', child="missing"))
    assert "U001" not in _codes_of(found)
    assert ("X005", 1) in found  # yourdfpy reads it as an empty robot: a warning, not an error
    assert "S003" in _codes_of(found)  # the file's real error (unknown child link) is no longer hidden


def test_default_namespace_model_has_the_local_names():
    m = model_from_string(robot('name="r" xmlns="http://www.ros.org"'))
    assert set(m.links) == {"base_link", "arm"} and set(m.joints) == {"j1"}
    assert not [i for i in m.issues if i.code in ("U001", "U002", "U003")]


def test_default_namespace_warning_is_x005_warning_severity(tmp_path):
    p = tmp_path / "r.urdf"
    p.write_text(robot('name="r" xmlns="http://www.ros.org"'), encoding="utf-8")
    _, out = lint_json([str(p)])
    (f,) = [f for f in out["findings"] if f["code"] == "X005"]
    assert f["severity"] == "warning" and "http://www.ros.org" in f["message"]


def test_default_namespace_inside_a_gazebo_block_is_silent(tmp_path):
    tail = '<gazebo><plugin xmlns="http://example.org/p" name="p" filename="libp.so"><x>1</x></plugin></gazebo>'
    found = codes(tmp_path, robot('name="r"', tail=tail))
    assert "X005" not in _codes_of(found)


def test_default_namespace_on_a_link_is_a_warning_but_the_link_is_read():
    root, warnings = xmlfront.parse(b'<robot name="r"><link xmlns="http://x" name="a"/></robot>')
    assert root[0].tag == "link" and [w.code for w in warnings] == ["X005"]
    assert "skip this <link>" in warnings[0].message


def test_yourdfpy_reads_a_default_namespace_robot_as_empty(tmp_path):
    # the reason X005 exists for this case: check it stays true of the installed yourdfpy
    yourdfpy = pytest.importorskip("yourdfpy")
    p = tmp_path / "r.urdf"
    p.write_text(robot('name="r" xmlns="http://www.ros.org"'), encoding="utf-8")
    u = yourdfpy.URDF.load(str(p), load_meshes=False, build_scene_graph=False, load_collision_meshes=False)
    assert u.robot.links == [] and u.robot.joints == []
    p.write_text(robot('name="r"'), encoding="utf-8")
    u = yourdfpy.URDF.load(str(p), load_meshes=False, build_scene_graph=False, load_collision_meshes=False)
    assert len(u.robot.links) == 2


def test_declared_prefixes_are_untouched():
    root, warnings = xmlfront.parse(b'<robot name="r" xmlns:drake="http://drake.mit.edu">'
                                    b'<drake:x a="1"/></robot>')
    assert warnings == [] and root[0].tag == "{http://drake.mit.edu}x"


# --- an undeclared prefix (Drake's own models) ---------------------------------------------------------------

DRAKE = robot('name="r"', extra='\n    <drake:rotor_inertia value="0.1"/><drake:gear_ratio value="10"/>',
              tail='\n  <drake:collision_filter_group name="g" drake:ignore="true"><drake:member link="arm"/>'
                   '</drake:collision_filter_group>\n  <link name="x" drake:foo="1"/>\n'
                   '  <joint name="j2" type="fixed"><parent link="arm"/><child link="x"/></joint>\n')


def test_undeclared_drake_prefix_is_read_not_refused(tmp_path):
    found = codes(tmp_path, DRAKE)
    assert "X001" not in _codes_of(found)
    x005 = [line for c, line in found if c == "X005"]
    assert x005 == [7]  # one warning per prefix, at its first use
    # drake:* elements and attributes are Drake's known extensions (model/extensions.yaml)
    assert not {"U002", "U003"} & set(_codes_of(found)), found


def test_undeclared_prefix_warning_names_the_prefix():
    _, warnings = xmlfront.parse(DRAKE.encode())
    (w,) = warnings
    assert w.code == "X005" and "'drake'" in w.message and w.line == 7


def test_undeclared_other_prefix_is_still_an_unknown_element(tmp_path):
    found = codes(tmp_path, robot('name="r"', tail='<foo:bar/>'))
    assert "X005" in _codes_of(found) and "U002" in _codes_of(found)


def test_typo_beside_drake_extensions_is_still_reported(tmp_path):
    found = codes(tmp_path, robot('name="r"', extra='<drake:rotor_inertia value="1"/><dynamcis damping="1"/>'))
    assert "U002" in _codes_of(found)


def test_undeclared_prefix_in_xacro_is_what_xacro_says(tmp_path):
    # real xacro (expat) stops at an unbound prefix: the file is not read past that, and says so
    text = robot('name="r" xmlns:xacro="http://www.ros.org/wiki/xacro"', extra='<drake:rotor_inertia value="1"/>')
    found = codes(tmp_path, text, name="r.urdf.xacro")
    assert "X010" in _codes_of(found) and "X005" in _codes_of(found)


# --- the hardening stays -------------------------------------------------------------------------------------

@pytest.mark.parametrize("data, code", [
    # a real syntax error next to a namespace error is still refused
    (b'<robot name="r"><drake:x/><link name="a"></robot>', "X001"),
    (b'<robot name="r"><drake:x/><link name="&undefined;"/></robot>', "X001"),
    (b'<robot name="r"><drake:x/></robot><robot/>', "X002"),
    (b'<!DOCTYPE r [<!ENTITY a "b">]><robot name="r"><drake:x v="&a;"/></robot>', "X002"),
    (b'<robot name="r"><drake:x/>' + b"<a>" * 300 + b"</a>" * 300 + b"</robot>", "X004"),
    (b'<robot name="r"><drake:x/><?pi x?></robot>', "X002"),
])
def test_namespace_leniency_keeps_every_refusal(data, code):
    with pytest.raises(xmlfront.XmlRefused) as e:
        xmlfront.parse(data)
    assert e.value.issue.code == code


def test_only_an_undeclared_prefix_is_accepted():
    # other namespace errors (an empty prefixed declaration, a malformed qualified name) stay refused
    for data in (b'<robot name="r" xmlns:q=""><link name="a"/></robot>', b'<robot name="r"><a:b:c/></robot>'):
        with pytest.raises(xmlfront.XmlRefused) as e:
            xmlfront.parse(data)
        assert e.value.issue.code == "X001"


def test_validation_pass_keeps_lines_and_accepts_comments_before_the_root():
    data = (b'<?xml version="1.0"?>\n<!-- c -->\n<?pi x?>\n<robot name="r">\n<link name="a" drake:x="1"/>\n'
            b'<link name="b"/>\n</robot>\n')
    with pytest.raises(xmlfront.XmlRefused):  # a PI before the root is still refused
        xmlfront.parse(data)
    root, warnings = xmlfront.parse(data.replace(b"<?pi x?>", b""))
    assert [(w.code, w.line) for w in warnings] == [("X005", 5)]
    assert [(el.get("name"), el.sourceline) for el in root] == [("a", 5), ("b", 6)]
    assert root[0].get("drake:x") == "1"


def test_plain_file_loader_reports_x005_at_its_line(tmp_path):
    p = tmp_path / "r.urdf"
    p.write_text(DRAKE, encoding="utf-8")
    exp = loader.expand(p)
    assert exp.root is not None
    assert [(f.code, f.location.line) for f in exp.findings] == [("X005", 7)]


def test_many_undeclared_uses_and_a_late_prefix():
    # libxml2 logs at most 100 errors: a prefix first used after that is still found, a late fault still refused
    data = (b'<robot name="r">\n' + b'<drake:x a="1"/>\n' * 300 + b'<foo:y/>\n' + b'<link name="a"/>\n'
            b'</robot>\n')
    root, warnings = xmlfront.parse(data)
    assert [(w.code, w.line) for w in warnings] == [("X005", 2), ("X005", 302)]
    assert root[-1].get("name") == "a" and root[300].tag == "foo:y"
    with pytest.raises(xmlfront.XmlRefused) as e:
        xmlfront.parse(data + b"<robot/>")
    assert (e.value.issue.code, e.value.issue.line) == ("X002", 305)


def test_default_namespace_in_a_xacro_file(tmp_path):
    # xacro keeps xmlns="..." in its output; the expanded model is read by local names, the warning is once
    text = robot('name="r" xmlns="http://www.ros.org" xmlns:xacro="http://www.ros.org/wiki/xacro"',
                 child="${c}").replace("<link", '<xacro:property name="c" value="missing"/><link', 1)
    found = codes(tmp_path, text, name="r.urdf.xacro")
    assert "U001" not in _codes_of(found) and _codes_of(found).count("X005") == 1
    assert "S003" in _codes_of(found)
