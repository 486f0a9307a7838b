"""Issue 15: stock xacro's deprecation warning for the bare helpers (load_yaml, abs_filename) reaches the user
in sandbox mode too, as the same located X016 finding a --trusted (stock) expansion gives."""
import textwrap

import pytest

from urdfcheck.load import loader

XACRO_NS = 'xmlns:xacro="http://www.ros.org/wiki/xacro"'


def package(tmp_path, body: str):
    pkg = tmp_path / "pkg"
    (pkg / "urdf").mkdir(parents=True)
    (pkg / "package.xml").write_text('<package format="3"><name>pkg</name><version>0.0.0</version>'
                                     '<description>d</description><maintainer email="a@b.c">a</maintainer>'
                                     '<license>MIT</license></package>')
    (pkg / "urdf" / "c.yaml").write_text("len: 0.5\n")
    entry = pkg / "urdf" / "r.urdf.xacro"
    entry.write_text(textwrap.dedent(body).lstrip())
    return entry


BARE_LOAD_YAML = f"""
    <robot name="r" {XACRO_NS}>
      <xacro:property name="cfg" value="${{load_yaml('c.yaml')}}"/>
      <link name="base_link"/>
      <link name="l${{cfg['len']}}"/>
      <joint name="j" type="fixed"><parent link="base_link"/><child link="l${{cfg['len']}}"/></joint>
    </robot>
    """


def x016(exp):
    return [(f.code, f.message, f.location.file, f.location.line) for f in exp.findings if f.code == "X016"]


def test_bare_load_yaml_is_a_located_deprecation_warning_in_the_sandbox(tmp_path):
    entry = package(tmp_path, BARE_LOAD_YAML)
    exp = loader.expand(entry)
    assert exp.root is not None and exp.root.find("link[@name='l0.5']") is not None  # the YAML was still read
    (finding,) = x016(exp)
    assert finding[1] == ("xacro warning: Using load_yaml() directly is deprecated. "
                          "Use xacro.load_yaml() instead.")
    assert finding[3] == 4  # where stock evaluates the (lazy) property: the first use


@pytest.mark.parametrize("body", [
    BARE_LOAD_YAML,
    f"""
    <robot name="r" {XACRO_NS}>
      <link name="${{abs_filename('c.yaml')[-6:-5]}}_link"/>
    </robot>
    """,
])
def test_the_sandbox_reports_what_stock_xacro_reports(tmp_path, body):
    # --trusted runs stock's own deprecation wrapper: the sandbox must give the same finding, text and place
    entry = package(tmp_path, body)
    sandboxed, stock = x016(loader.expand(entry)), x016(loader.expand(entry, trusted=True))
    assert stock and "directly is deprecated" in stock[0][1]  # the control: stock really warns here
    assert sandboxed == stock


def test_the_namespaced_helper_is_not_deprecated(tmp_path):
    entry = package(tmp_path, BARE_LOAD_YAML.replace("${load_yaml(", "${xacro.load_yaml("))
    exp = loader.expand(entry)
    assert exp.root is not None and exp.root.find("link[@name='l0.5']") is not None
    assert x016(exp) == []


def test_the_bare_helper_stays_confined(tmp_path):
    # the warning wrapper calls the confined load_yaml, not stock's: a file outside the package is still refused
    entry = package(tmp_path, BARE_LOAD_YAML.replace("'c.yaml'", "'/etc/passwd'"))
    exp = loader.expand(entry)
    assert exp.root is None
    assert [f.code for f in exp.findings] == ["X016", "X014"]  # warned (as stock), then refused
