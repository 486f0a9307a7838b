"""Every command reads the settings `lint` reads (issue 24): a config's `packages:` and limits reach `expand`,
`tree`, `tf`, `publish`, `verify` and the API's `load()`/`expand()`; the pytest plugin reports what `run()`
reports; `urdfcheck.load` stays the function."""
from __future__ import annotations

import json
import os
import shutil
import sys
import textwrap

import pytest
from conftest import run_cli

import urdfcheck

ROBOT = """<robot name="r" xmlns:xacro="http://www.ros.org/wiki/xacro">
  <xacro:include filename="$(find my_parts)/urdf/part.xacro"/>
  <link name="base_link"><inertial><mass value="1"/>
    <inertia ixx="1" iyy="1" izz="1" ixy="0" ixz="0" iyz="0"/></inertial></link>
  <xacro:part parent="base_link"/>
</robot>
"""
PART = """<robot xmlns:xacro="http://www.ros.org/wiki/xacro">
  <xacro:macro name="part" params="parent">
    <link name="part_link"><inertial><mass value="1"/>
      <inertia ixx="1" iyy="1" izz="1" ixy="0" ixz="0" iyz="0"/></inertial></link>
    <joint name="part_joint" type="revolute">
      <parent link="${parent}"/><child link="part_link"/><origin xyz="0 0 1"/><axis xyz="0 0 1"/>
      <limit lower="-1" upper="1" effort="1" velocity="1"/>
    </joint>
  </xacro:macro>
</robot>
"""


@pytest.fixture
def ws(tmp_path, monkeypatch):
    """pkg/ needs the package my_parts, which only its urdfcheck.yaml places (../parts)."""
    (tmp_path / ".git").mkdir()  # one repository: a config may name its sibling folder (issue 19's confinement)
    (tmp_path / "parts" / "urdf").mkdir(parents=True)
    (tmp_path / "parts" / "urdf" / "part.xacro").write_text(PART)
    pkg = tmp_path / "pkg"
    (pkg / "urdf").mkdir(parents=True)
    (pkg / "urdf" / "robot.urdf.xacro").write_text(ROBOT)
    (pkg / "urdfcheck.yaml").write_text("packages:\n  my_parts: ../parts\n")
    monkeypatch.chdir(pkg)
    return pkg


MODEL = os.path.join("urdf", "robot.urdf.xacro")


def test_lint_resolves_the_package_the_config_places(ws):
    code, out, err = run_cli(["lint", "--format", "json", "."])
    assert "X013" not in out, out


def test_expand_reads_the_config(ws):
    code, out, err = run_cli(["expand", MODEL])
    assert code == 0, err
    assert "part_link" in out and "X013" not in err


@pytest.mark.parametrize("argv", [["tree", MODEL], ["tf", MODEL, "base_link", "part_link", "--joint", "part_joint=0"]])
def test_tree_and_tf_read_the_config(ws, argv):
    code, out, err = run_cli(argv)
    assert code == 0, err
    assert "part_link" in out or "1.000" in out


def test_publish_reads_the_config(ws):
    (ws / "js.json").write_text(json.dumps([{"name": ["part_joint"], "position": [0.5], "stamp": 1.0}]))
    code, out, err = run_cli(["publish", MODEL, "--joint-states", "js.json"])
    assert code == 0, err
    assert "part_link" in out


def test_verify_reads_the_config(ws):
    pytest.importorskip("pinocchio")
    code, out, err = run_cli(["verify", MODEL, "-n", "3", "--no-yourdfpy"])
    assert "X013" not in err and "not found" not in err, err
    assert code == 0, out + err


def test_api_load_and_expand_read_the_config(ws):
    model = urdfcheck.load(MODEL)
    assert "part_link" in model.links
    assert "part_link" in urdfcheck.expand(MODEL).clean_text()


def test_limits_of_the_config_reach_expand_and_load(ws):
    (ws / "urdfcheck.yaml").write_text("packages:\n  my_parts: ../parts\nmax_elements: 3\n")
    code, out, _ = run_cli(["lint", "--format", "json", "."])
    codes = {f["code"] for f in json.loads(out)["findings"]}
    assert "X017" in codes or "X012" in codes, codes
    code, out, err = run_cli(["expand", MODEL])
    assert code == 1 and ("X017" in err or "X012" in err), err
    with pytest.raises(urdfcheck.LoadError):
        urdfcheck.load(MODEL)


def test_flags_still_win_over_the_config(ws):
    (ws / "urdfcheck.yaml").write_text("packages:\n  my_parts: ../parts\nmax_elements: 3\n")
    code, out, err = run_cli(["expand", MODEL, "--max-elements", "1000"])
    assert code == 0, err


def test_load_stays_a_function_after_lint_and_expand(ws):
    urdfcheck.lint(".")
    urdfcheck.expand(MODEL)
    import urdfcheck.load.packages as packages  # the sub-package's modules stay importable

    assert callable(urdfcheck.load) and packages.Resolver
    assert "part_link" in urdfcheck.load(MODEL).links


def test_unknown_command_says_did_you_mean(tmp_path):
    code, out, err = run_cli(["lnt"], cwd=tmp_path)
    assert code == 2
    assert "unknown command 'lnt'" in err and "did you mean 'lint'" in err


def test_a_file_named_like_a_command_is_still_linted(tmp_path):
    (tmp_path / "lnt").write_text("<robot name='r'><link name='a'/></robot>")
    code, out, err = run_cli(["lnt"], cwd=tmp_path)
    assert code in (0, 1), err


def test_tree_of_a_folder_shows_its_robot_or_says_what_it_expects(ws, tmp_path):
    code, out, err = run_cli(["tree", "."])
    assert code == 0, err
    assert "part_link" in out
    (ws / "urdf" / "other.urdf").write_text("<robot name='o'><link name='a'/></robot>")
    code, out, err = run_cli(["tree", "."])
    assert code == 2
    assert "robot.urdf.xacro" in err and "other.urdf" in err


# --- the pytest plugin reads run()'s per-target results --------------------------------------------------
MISSING = """<robot name="{name}" xmlns:xacro="http://www.ros.org/wiki/xacro">
  <xacro:include filename="$(find nowhere_pkg)/urdf/x.xacro"/>
  <link name="base_link"/>
</robot>
"""


def test_plugin_equals_the_cli_with_a_missing_package_and_a_baseline(tmp_path, monkeypatch):
    pkg = tmp_path / "pkg"
    (pkg / "urdf").mkdir(parents=True)
    (pkg / "package.xml").write_text("<package format='3'><name>pkg</name></package>")
    (pkg / "urdf" / "a.urdf.xacro").write_text(MISSING.format(name="a"))
    (pkg / "urdf" / "b.urdf.xacro").write_text(MISSING.format(name="b"))
    (pkg / "urdf" / "c.urdf").write_text(textwrap.dedent("""\
        <robot name="c"><link name="base_link"/><link name="x"/>
        <joint name="j" type="fixed"><parent link="base_link"/><child link="x"/><orign xyz="0 0 1"/></joint>
        </robot>"""))
    (pkg / "urdfcheck.yaml").write_text("frames: {base: base_link}\n")  # no select: a found config may not narrow
    monkeypatch.chdir(pkg)
    code, _, err = run_cli(["lint", "--write-baseline", "base.json"])
    assert code == 0, err
    (pkg / "urdf" / "d.urdf").write_text("<robot name='d'><link name='a'/><link name='a'/></robot>")
    code, out, err = run_cli(["lint", "--format", "json", "--baseline", "base.json"])
    cli = sorted((f["code"], f["location"]["file"], f["message"]) for f in json.loads(out)["findings"])
    assert cli and all(c != "X013" for c, _, _ in cli), cli  # the baseline holds the X013

    from urdfcheck.request.request import make_request
    from urdfcheck.run import run

    req = make_request([], baseline="base.json")
    result = run(req)
    shares = sorted((f.code, f.location.file, f.message) for fs in result.shares for f in fs)
    assert sorted(set(shares)) == cli
    # without the baseline: one X013 for the package, in the share of each model that needs it
    result = run(make_request([]))
    x013 = [f for fs in result.shares for f in fs if f.code == "X013"]
    assert len(x013) == 2 and x013[0] == x013[1] and "referenced in 2 places" in x013[0].message


def test_plugin_items_show_the_cli_findings(tmp_path, monkeypatch):
    pytester_src = str(__import__("pathlib").Path(urdfcheck.__file__).resolve().parent.parent)
    pkg = tmp_path / "pkg"
    (pkg / "urdf").mkdir(parents=True)
    (pkg / "package.xml").write_text("<package format='3'><name>pkg</name></package>")
    (pkg / "urdf" / "a.urdf.xacro").write_text(MISSING.format(name="a"))
    (pkg / "urdf" / "b.urdf.xacro").write_text(MISSING.format(name="b"))
    (pkg / "urdf" / "d.urdf").write_text("<robot name='d'><link name='a'/><link name='a'/></robot>")
    (pkg / "urdfcheck.yaml").write_text("frames: {base: base_link}\n")  # no select: a found config may not narrow
    monkeypatch.chdir(pkg)
    code, _, err = run_cli(["lint", "--write-baseline", "base.json"])
    (pkg / "urdf" / "e.urdf").write_text("<robot name='e'><link name='a'/><link name='a'/></robot>")
    code, out, err = run_cli(["lint", "--format", "json", "--baseline", "base.json"])
    cli = json.loads(out)["findings"]
    import subprocess

    env = {**os.environ, "PYTEST_DISABLE_PLUGIN_AUTOLOAD": "1",
           "PYTHONPATH": os.pathsep.join(filter(None, [pytester_src, os.environ.get("PYTHONPATH")]))}
    proc = subprocess.run([sys.executable, "-m", "pytest", "-p", "urdfcheck.pytest_plugin", "-p", "no:cacheprovider",
                           "--urdfcheck-baseline", "base.json", "-q", "-rf"], cwd=pkg, env=env,
                          capture_output=True, text=True, timeout=300)
    text = proc.stdout
    assert "1 failed" in text and "3 passed" in text, text
    for f in cli:
        assert f["message"] in text
    assert "X013" not in text


# --- paths: one helper, messages built with display paths -------------------------------------------------
WHEELS = os.path.join(os.path.dirname(__file__), "..", "..", "examples", "broken", "contract_odom_tf_twice")


def test_root_slash_keeps_messages_intact(tmp_path):
    work = tmp_path / "w"
    shutil.copytree(WHEELS, work)
    code, out, err = run_cli(["lint", "--format", "json", "--root", "/", str(work)])
    found = json.loads(out)["findings"]
    t001 = [f for f in found if f["code"] == "T001"]
    assert t001, found
    msg = t001[0]["message"]
    # every "/" kept: the paths in the message are shown relative to the root like the location
    assert "ekf_filter_node" in msg and os.path.relpath(str(work / "config" / "ekf.yaml"), "/") + ":" in msg, msg
    assert t001[0]["location"]["file"] == os.path.relpath(str(work / "config" / "agv_controllers.yaml"), "/")


def test_run_from_slash_keeps_messages_intact(tmp_path):
    work = tmp_path / "w"
    shutil.copytree(WHEELS, work)
    code, out, err = run_cli(["lint", "--format", "json", str(work)], cwd="/")
    t001 = [f for f in json.loads(out)["findings"] if f["code"] == "T001"]
    assert t001 and "ekf_filter_node" in t001[0]["message"]
    assert os.path.relpath(str(work / "config" / "agv_controllers.yaml"), "/") + ":" in t001[0]["message"]


BRINGUP_LAUNCH = """<launch>
  <node pkg="robot_state_publisher" exec="robot_state_publisher">
    <param name="robot_description" value="$(command 'xacro $(find-pkg-share my_description)/urdf/robot.urdf.xacro')"/>
  </node>
</launch>
"""


def test_a_sibling_folder_model_prints_no_absolute_path(tmp_path, monkeypatch):
    desc = tmp_path / "ws" / "src" / "my_description"
    (desc / "urdf").mkdir(parents=True)
    (tmp_path / "ws" / ".git").mkdir()  # one repository holds both packages (a config may name its sibling)
    (desc / "package.xml").write_text("<package format='3'><name>my_description</name></package>")
    (desc / "urdf" / "robot.urdf.xacro").write_text(
        "<robot name='r' xmlns:xacro='http://www.ros.org/wiki/xacro'><link name='base_link'/>"
        "<joint name='j' type='fixed'><parent link='base_link'/><child link='nowhere'/></joint></robot>")
    bringup = tmp_path / "ws" / "src" / "my_bringup"
    (bringup / "launch").mkdir(parents=True)
    (bringup / "package.xml").write_text("<package format='3'><name>my_bringup</name></package>")
    (bringup / "launch" / "robot.launch.xml").write_text(BRINGUP_LAUNCH)
    (bringup / "urdfcheck.yaml").write_text("packages:\n  my_description: ../my_description\n")
    monkeypatch.chdir(bringup)
    absolute = str(tmp_path)
    code, out, err = run_cli(["lint", "--format", "json", "."])
    found = json.loads(out)["findings"]
    assert found, (out, err)
    assert absolute not in out and absolute not in err, out
    code, out, err = run_cli(["lint", "--list", "."])
    assert code == 0 and "robot.urdf.xacro" in out, out + err
    assert absolute not in out and absolute not in err, out
    assert os.path.join("..", "my_description", "urdf", "robot.urdf.xacro") in out
    for fmt in ("text", "sarif", "junit", "github", "markdown"):
        code, out, err = run_cli(["lint", "--format", fmt, "."])
        assert code == 1 and absolute not in out, (fmt, out)
