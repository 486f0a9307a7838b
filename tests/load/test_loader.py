"""Loading: plain URDF lines, xacro source map (macro lines and call sites), tolerant parsing."""
import textwrap

import pytest
from conftest import lint_json, run_cli

from urdfcheck.load import loader
from urdfcheck.model.build import model_from_string

XACRO_NS = 'xmlns:xacro="http://www.ros.org/wiki/xacro"'


def write(folder, name, text):
    p = folder / name
    p.parent.mkdir(parents=True, exist_ok=True)
    p.write_text(textwrap.dedent(text).lstrip(), encoding="utf-8")
    return p


def test_plain_urdf_elements_carry_their_lines(tmp_path):
    p = write(tmp_path, "r.urdf", """
        <robot name="r">
          <link name="a"/>
          <link name="b"/>
          <joint name="j" type="revolute">
            <parent link="a"/>
            <child link="b"/>
            <axis xyz="0 0 1"/>
            <limit lower="-1" upper="1" effort="1" velocity="1"/>
          </joint>
        </robot>
        """)
    m = loader.load_model(p)
    assert m.links["b"].loc.line == 3
    j = m.joints["j"]
    assert (j.loc.line, j.axis_loc.line, j.limit.loc.line, j.child_loc.line) == (4, 7, 8, 6)
    assert m.roots == ("a",)


def test_xacro_macro_in_included_file_points_at_macro_line_with_call_sites(tmp_path):
    write(tmp_path, "package.xml", "<package format='3'><name>demo</name></package>")
    write(tmp_path, "urdf/macros/wheel.xacro", f"""
        <robot {XACRO_NS}>
          <xacro:macro name="wheel" params="side y">
            <link name="${{side}}_wheel"/>
            <joint name="${{side}}_joint" type="continuous">
              <parent link="base_link"/>
              <child link="${{side}}_wheel"/>
              <origin xyz="0 ${{y}} 0"/>
              <axis xyz="0 2 0"/>
            </joint>
          </xacro:macro>
        </robot>
        """)
    entry = write(tmp_path, "urdf/robot.urdf.xacro", f"""
        <robot name="r" {XACRO_NS}>
          <xacro:include filename="$(find demo)/urdf/macros/wheel.xacro"/>
          <link name="base_link"/>
          <xacro:wheel side="left" y="0.25"/>
          <xacro:wheel side="right" y="-0.25"/>
        </robot>
        """)
    exp = loader.expand(entry)
    assert not exp.findings, exp.findings
    m = loader.build_model(exp)
    left, right = m.joints["left_joint"], m.joints["right_joint"]
    assert left.loc.file.endswith("urdf/macros/wheel.xacro") and left.loc.line == 4
    assert left.axis_loc.line == 8
    assert [v.line for v in left.loc.via] == [4]
    assert [v.line for v in right.loc.via] == [5]
    assert left.loc.via[0].file.endswith("robot.urdf.xacro")
    assert m.links["base_link"].loc.file.endswith("robot.urdf.xacro") and m.links["base_link"].loc.line == 3
    # and a finding on the macro's axis is reported at the macro file through the CLI
    code, report = lint_json([entry, "--select", "U,J"], cwd=tmp_path)
    assert report["findings"] == [] or all(f["location"]["file"].endswith(("wheel.xacro", "robot.urdf.xacro"))
                                           for f in report["findings"])


def test_nested_macros_record_the_whole_call_chain(tmp_path):
    entry = write(tmp_path, "r.urdf.xacro", f"""
        <robot name="r" {XACRO_NS}>
          <xacro:macro name="inner" params="n">
            <link name="${{n}}"/>
          </xacro:macro>
          <xacro:macro name="outer" params="n">
            <xacro:inner n="${{n}}_x"/>
          </xacro:macro>
          <xacro:outer n="a"/>
        </robot>
        """)
    m = loader.load_model(entry)
    loc = m.links["a_x"].loc
    assert loc.line == 3
    assert [v.line for v in loc.via] == [6, 8]


def test_block_parameters_keep_the_call_site_line(tmp_path):
    entry = write(tmp_path, "r.urdf.xacro", f"""
        <robot name="r" {XACRO_NS}>
          <xacro:macro name="fixed_to_base" params="child *origin">
            <link name="${{child}}"/>
            <joint name="${{child}}_joint" type="fixed">
              <xacro:insert_block name="origin"/>
              <parent link="base_link"/>
              <child link="${{child}}"/>
            </joint>
          </xacro:macro>
          <link name="base_link"/>
          <xacro:fixed_to_base child="laser">
            <origin xyz="1 2 3"/>
          </xacro:fixed_to_base>
        </robot>
        """)
    m = loader.load_model(entry)
    j = m.joints["laser_joint"]
    assert j.origin.xyz == (1.0, 2.0, 3.0)
    assert j.origin.loc.line == 12


def test_xacro_error_is_a_located_finding_not_a_crash(tmp_path):
    entry = write(tmp_path, "r.urdf.xacro", f"""
        <robot name="r" {XACRO_NS}>
          <link name="base_link"/>
          <link name="${{undefined_thing}}"/>
        </robot>
        """)
    exp = loader.expand(entry)
    assert exp.root is None
    (f,) = [f for f in exp.findings if f.code == "X010"]
    assert f.location.line == 3 and "undefined_thing" in f.message


def test_a_required_argument_nobody_sets_names_the_argument_and_the_fix(tmp_path):
    # xacro says "Undefined substitution argument name" for an argument called `name`: unreadable as it stands
    entry = write(tmp_path, "r.urdf.xacro", f"""
        <robot name="$(arg name)" {XACRO_NS}>
          <link name="base_link"/>
        </robot>
        """)
    (f,) = [f for f in loader.expand(entry).findings if f.code == "X010"]
    assert "argument 'name' has no default" in f.message and "--arg name:=" in f.message
    assert loader.load_model(entry, {"name": "ur5"}).name == "ur5"


def test_unresolved_package_is_x013(tmp_path):
    entry = write(tmp_path, "r.urdf.xacro", f"""
        <robot name="r" {XACRO_NS}>
          <xacro:include filename="$(find nowhere_pkg)/x.xacro"/>
        </robot>
        """)
    exp = loader.expand(entry)
    assert [f.code for f in exp.findings] == ["X013"]
    assert "nowhere_pkg" in exp.findings[0].message and exp.findings[0].location.line == 2


def test_package_flag_resolves_find(tmp_path):
    other = tmp_path / "elsewhere"
    write(other, "parts.xacro", f'<robot {XACRO_NS}><link name="base_link"/></robot>')
    entry = write(tmp_path / "pkg", "r.urdf.xacro", f"""
        <robot name="r" {XACRO_NS}>
          <xacro:include filename="$(find parts_pkg)/parts.xacro"/>
        </robot>
        """)
    exp = loader.expand(entry, packages={"parts_pkg": str(other)})
    assert exp.findings == [] and exp.root is not None


def test_xacro_args_are_applied(tmp_path):
    entry = write(tmp_path, "r.urdf.xacro", f"""
        <robot name="r" {XACRO_NS}>
          <xacro:arg name="cam" default="true"/>
          <link name="base_link"/>
          <xacro:if value="$(arg cam)"><link name="camera"/></xacro:if>
        </robot>
        """)
    assert "camera" in loader.load_model(entry).links
    assert "camera" not in loader.load_model(entry, {"cam": "false"}).links
    assert loader.expand(entry).declared_args == {"cam": "true"}


def test_expand_command_prints_what_xacro_prints(tmp_path):
    entry = write(tmp_path, "r.urdf.xacro", f"""
        <robot name="r" {XACRO_NS}>
          <xacro:property name="w" value="0.5"/>
          <link name="base_link"><visual><geometry><box size="${{w}} 1 1"/></geometry></visual></link>
        </robot>
        """)
    code, out, err = run_cli(["expand", entry])
    assert code == 0, err
    assert '<box size="0.5 1 1"/>' in out and "__ucsrc" not in out
    assert out.startswith('<?xml version="1.0" ?>')


@pytest.mark.parametrize("text,code", [
    ('<robot name="r"><link name="a"><visual><origin xyz="0 0"/></visual></link></robot>', "U004"),
    ('<robot name="r"><link name="a"><visual><origin xyz="0 0 nan"/></visual></link></robot>', "U005"),
    ('<robot name="r"><link name="a"><visual><origin xyz="0 0 1e999"/></visual></link></robot>', "U005"),
    ('<robot name="r"><link name="a"><visual><origin xyz="0 0 1_0"/></visual></link></robot>', "U005"),
    ('<robot name="r"><link name="a"><visual><orign xyz="0 0 1"/></visual></link></robot>', "U002"),
    ('<robot name="r"><link name="a"><visual><origin xzy="0 0 1"/></visual></link></robot>', "U003"),
    ('<robot name="r"><link/></robot>', "U006"),
    ('<model name="r"><link name="a"/></model>', "U001"),
])
def test_bad_values_become_issues(text, code):
    m = model_from_string(text)
    assert code in [i.code for i in m.issues]


def test_simulator_extensions_that_a_consumer_reads_are_not_reported():
    m = model_from_string('<robot name="r"><link name="a"><contact><lateral_friction value="1"/></contact>'
                          '<self_collision_checking/></link></robot>')
    assert not m.issues
    m = model_from_string('<robot name="r"><link name="a"><contactt/></link></robot>')
    assert [i.code for i in m.issues] == ["U002"]  # a typo of it still is


def test_unexpanded_xacro_in_a_plain_urdf_is_named():
    m = model_from_string('<robot name="r"><link name="a"><visual><origin xyz="$(optenv X 0 0 1)"/>'
                          '<geometry><sphere radius="${r}"/></geometry></visual></link></robot>')
    assert [i.code for i in m.issues] == ["U004", "U005"]
    assert all("unexpanded xacro substitution" in i.message for i in m.issues)
    m = model_from_string('<robot name="r"><link name="a"><visual><origin xyz="0 0"/></visual></link></robot>')
    assert "xacro" not in m.issues[0].message


def test_typo_suggestion():
    m = model_from_string('<robot name="r"><link name="a"><visual><orign/></visual></link></robot>')
    assert "did you mean 'origin'" in m.issues[0].message


@pytest.mark.parametrize("data,code", [
    (b'<robot name="r"><link name="a"></robot>', "X001"),
    (b'<robot name="r"/><robot name="s"/>', "X002"),
    (b'<robot name="r"/>trailing', "X002"),
    (b'<?xml version="1.0"?><!DOCTYPE r [<!ENTITY a "b">]><robot name="&a;"/>', "X002"),
    (b'<?pi x?><robot name="r"/>', "X002"),
    (b'<robot name="\xff\xfe"/>', "X001"),
])
def test_hostile_or_broken_xml_is_a_finding(tmp_path, data, code):
    p = tmp_path / "r.urdf"
    p.write_bytes(data)
    exp = loader.expand(p)
    assert exp.root is None
    assert [f.code for f in exp.findings] == [code]
    assert exp.findings[0].location.line is not None


def test_tolerated_declaration_typo_is_a_warning_and_the_model_loads(tmp_path):
    p = tmp_path / "r.urdf"
    p.write_bytes(b'<?xml verison="1.0"?>\n<robot name="r">\n  <link name="a"/>\n</robot>\n')
    exp = loader.expand(p)
    assert [f.code for f in exp.findings] == ["X003"]
    m = loader.build_model(exp)
    assert m.links["a"].loc.line == 3


def test_missing_path_is_usage_error():
    code, out, err = run_cli(["lint", "/nonexistent/robot.urdf"])
    assert code == 2 and "no such file" in err


def test_bad_flag_is_usage_error():
    with pytest.raises(SystemExit) as e:
        run_cli(["lint", "--no-such-flag"])
    assert e.value.code == 2


def test_output_is_deterministic(tmp_path, corpus):
    target = corpus / "ros+urdf" / "urdf" / "test"
    a = run_cli(["lint", "--format", "json", "--no-config", target])
    b = run_cli(["lint", "--format", "json", "--no-config", target])
    assert a == b


def test_a_xacro_file_named_urdf_is_expanded(tmp_path):
    p = write(tmp_path, "r.urdf", f"""
        <robot name="r" {XACRO_NS}>
          <xacro:property name="n" value="b"/>
          <link name="a"/>
          <link name="${{n}}"/>
        </robot>
        """)
    exp = loader.expand(p)
    assert exp.xacro and not exp.findings
    assert [el.get("name") for el in exp.root.iter("link")] == ["a", "b"]


@pytest.mark.parametrize("ns", ["http://www.ros.org/wiki/&#120;acro", "&#104;ttp://www.ros.org/wiki/xac&#x72;o"])
def test_the_xacro_namespace_is_recognised_when_spelled_with_character_references(tmp_path, ns):
    # no "xacro" anywhere in the bytes: the loader must still look at the parsed namespace
    p = write(tmp_path, "r.urdf", f"""
        <robot name="r" xmlns:x="{ns}">
          <x:unknown_directive/>
          <link name="a"/>
        </robot>
        """)
    assert b"xacro" not in p.read_bytes()
    assert loader.expand(p).xacro


def test_a_declaration_after_blank_lines_is_a_warning_and_the_model_loads(tmp_path):
    # urdfdom (check_urdf, robot_state_publisher) reads such a file; libxml2 and xacro do not
    p = tmp_path / "r.urdf"
    p.write_bytes(b'\n\n<?xml version="1.0"?>\n<robot name="r">\n  <link name="a"/>\n</robot>\n')
    exp = loader.expand(p)
    (f,) = exp.findings
    assert f.code == "X003" and f.location.line == 3 and "not at the start" in f.message
    assert loader.build_model(exp).links["a"].loc.line == 5


def test_a_package_url_in_an_include_says_xacro_does_not_resolve_it(tmp_path):
    # example-robot-data's hector quadrotor_base.xacro: stock xacro fails the same way, with a path it made up
    entry = write(tmp_path, "r.urdf.xacro", f"""
        <robot name="r" {XACRO_NS}>
          <xacro:include filename="package://some_pkg/urdf/base.urdf.xacro"/>
        </robot>
        """)
    (f,) = [f for f in loader.expand(entry).findings if f.code == "X010"]
    assert "xacro does not resolve package:// URLs" in f.message and f.location.line == 2


def test_a_urdf_declaring_xacro_with_substitutions_is_expanded(tmp_path):
    """Issue 37: a .urdf whose launch file runs it through xacro (it declares the namespace and writes ${...}) is
    expanded, not read raw (every such number was U005); without the declaration it stays a plain URDF."""
    body = ('  <link name="base_link"/>\n  <link name="b"/>\n  <joint name="j" type="fixed"><parent link="base_link"/>'
            '<child link="b"/><origin xyz="${0.1*2} 0 0"/></joint>\n</robot>\n')
    (tmp_path / "x.urdf").write_text('<robot name="r" xmlns:xacro="http://www.ros.org/wiki/xacro">\n' + body)
    (tmp_path / "plain.urdf").write_text('<robot name="r">\n' + body)
    _, report = lint_json([str(tmp_path / "x.urdf")], cwd=tmp_path)
    assert [f["code"] for f in report["findings"] if f["severity"] != "info"] == [], report["findings"]
    _, report = lint_json([str(tmp_path / "plain.urdf")], cwd=tmp_path)
    assert "U005" in [f["code"] for f in report["findings"]]
