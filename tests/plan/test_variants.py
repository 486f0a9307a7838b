"""Automatic variants (pairwise over the boolean xacro args, args of included files) and what the per-file
pre-commit hook lints for a robot file, a macro file or a YAML file (issue 22)."""
from __future__ import annotations

import itertools
import shutil

import pytest
from conftest import REPO, run_cli

from urdfcheck.load.variants import _pairs, auto_variants, boolean_args, pairwise

PKG_XML = """<?xml version="1.0"?>
<package format="3"><name>{name}</name><version>0.0.1</version><description>d</description>
<maintainer email="a@b.c">a</maintainer><license>MIT</license></package>
"""

INERTIAL = ('<inertial><mass value="1"/><inertia ixx="0.1" ixy="0" ixz="0" iyy="0.1" iyz="0" izz="0.1"/>'
            '</inertial>')


def link(name: str) -> str:
    return f'<link name="{name}">{INERTIAL}</link>'


def fixed(name: str, parent: str, child: str) -> str:
    return (f'<joint name="{name}" type="fixed"><parent link="{parent}"/><child link="{child}"/>'
            '<origin xyz="0.1 0 0"/></joint>')


def robot(body: str, args: str = "") -> str:
    return (f'<?xml version="1.0"?>\n<robot name="r" xmlns:xacro="http://www.ros.org/wiki/xacro">\n{args}\n'
            f'<link name="base_link"/>{link("body")}{fixed("body_joint", "base_link", "body")}\n{body}\n</robot>\n')


# a defect only when both flags are true: the gripper is attached to a link that exists only without the arm
BOTH = """<xacro:if value="$(arg use_arm)">{arm}</xacro:if>
<xacro:if value="$(arg use_gripper)">
  <xacro:if value="$(arg use_arm)">{gripper}{bad}</xacro:if>
</xacro:if>""".format(arm=link("arm") + fixed("arm_joint", "body", "arm"),
                      gripper=link("gripper") + fixed("gripper_joint", "arm", "gripper"),
                      bad=fixed("broken_joint", "no_such_link", "gripper"))


def test_pairwise_covers_every_pair():
    for n in range(2, 25):
        rows = pairwise(n)
        assert rows[0] == (False,) * n
        want = {(i, a, j, b) for i, j in itertools.combinations(range(n), 2) for a in (0, 1) for b in (0, 1)}
        got = set().union(*(_pairs(r) for r in rows))
        assert {(i, int(a), j, int(b)) for i, a, j, b in got} >= want
        assert len(rows) <= 2 * n + 2  # small: far below 2**n
    assert len(pairwise(5)) <= 8


def test_five_boolean_args_defect_needing_two_true(tmp_path):
    pkg = tmp_path / "five_description"
    (pkg / "urdf").mkdir(parents=True)
    (pkg / "package.xml").write_text(PKG_XML.format(name="five_description"))
    args = "".join(f'<xacro:arg name="{n}" default="false"/>' for n in ("use_lidar", "use_arm", "use_camera",
                                                                        "use_gripper", "use_imu"))
    model = pkg / "urdf" / "five.urdf.xacro"
    model.write_text(robot(BOTH, args))
    names = [n for n, _ in auto_variants(str(model), {})]
    assert len(names) < 2 ** 5 and "defaults" in names
    assert any("use_arm=true" in n and "use_gripper=true" in n for n in names)
    code, out, err = run_cli(["lint", "--no-config", "--format", "text", str(model)])
    assert code == 1, out + err
    assert "S003" in out and "no_such_link" in out


def args_in_include(tmp_path):
    pkg = tmp_path / "arm_description"
    (pkg / "urdf").mkdir(parents=True)
    (pkg / "config").mkdir()
    (pkg / "package.xml").write_text(PKG_XML.format(name="arm_description"))
    macro = pkg / "urdf" / "gripper.xacro"
    macro.write_text('<?xml version="1.0"?>\n<robot xmlns:xacro="http://www.ros.org/wiki/xacro">\n'
                     '  <xacro:arg name="use_gripper" default="false"/>\n'
                     f'  <xacro:macro name="parts">{BOTH}</xacro:macro>\n</robot>\n')
    model = pkg / "urdf" / "arm.urdf.xacro"
    model.write_text(robot('<xacro:include filename="$(find arm_description)/urdf/gripper.xacro"/>\n<xacro:parts/>',
                           '<xacro:arg name="use_arm" default="true"/>'))
    return pkg, model, macro


def test_args_declared_in_included_files_are_varied(tmp_path):
    pkg, model, macro = args_in_include(tmp_path)
    assert boolean_args(str(model)) == {"use_arm": "true", "use_gripper": "false"}
    assert [a for _, a in auto_variants(str(model), {})][-1] == {"use_arm": "false", "use_gripper": "true"}


def test_a_big_package_map_is_resolved_once_per_root(tmp_path, monkeypatch):
    """A workspace run gives every model the map of all packages: each root's real path is taken once per model,
    not once per included file (the corpus spent most of its planning there)."""
    import os

    pkg, model, macro = args_in_include(tmp_path)
    parts = [pkg / "urdf" / f"part{i}.xacro" for i in range(12)]
    for i, part in enumerate(parts):
        part.write_text(robot("", f'<xacro:arg name="flag{i}" default="false"/>'))
    model.write_text(robot("".join(f'<xacro:include filename="$(find arm_description)/urdf/{p.name}"/>\n'
                                   for p in parts), '<xacro:arg name="use_arm" default="true"/>'))
    packages = {"arm_description": str(pkg), **{f"p{i}": str(tmp_path / f"p{i}") for i in range(60)}}
    calls = []
    real = os.path.realpath
    monkeypatch.setattr(os.path, "realpath", lambda p, **kw: calls.append(p) or real(p, **kw))
    assert list(boolean_args(str(model), packages)) == ["use_arm"] + [f"flag{i}" for i in range(12)]
    # the map's roots once for the resolver and once for the confinement, and the files: not roots x files
    assert len(calls) < 3 * len(packages), len(calls)


@pytest.mark.parametrize("named", ["model", "macro"])
def test_per_file_hook_lints_the_broken_variant(tmp_path, named):
    """The per-file hook (`urdfcheck lint FILE...`) given the robot file or its macro file fails on the variant
    `use_arm and use_gripper` (before: the robot file's defaults only, and the included arg never varied)."""
    pkg, model, macro = args_in_include(tmp_path)
    code, out, err = run_cli(["lint", "--format", "text", str(model if named == "model" else macro)], cwd=pkg)
    assert code == 1, out + err
    assert "S003" in out and "use_gripper=true" in out
    code, out, err = run_cli(["lint", "--format", "text", "--arg", "use_gripper:=false",
                              str(model if named == "model" else macro)], cwd=pkg)
    assert code == 0, out + err  # the flag fixes the argument: no variant has the defect


def test_yaml_file_lints_the_models_that_read_it(tmp_path):
    pkg = tmp_path / "contract_wheel_radius"
    shutil.copytree(REPO / "examples/broken/contract_wheel_radius", pkg)
    code, out, err = run_cli(["lint", "--format", "text", "config/agv_controllers.yaml"], cwd=pkg)
    assert code == 1, out + err
    assert "C011" in out
    other = tmp_path / "ci.yml"
    other.write_text("on: push\n")
    code, out, err = run_cli(["lint", "--format", "text", str(other)], cwd=tmp_path)
    assert code == 0 and "no robot or deployment" in err, out + err


def test_config_file_named_lints_its_scope(tmp_path):
    pkg = tmp_path / "agv"
    shutil.copytree(REPO / "examples/agv", pkg)
    code, out, err = run_cli(["lint", "--list", "urdfcheck.yaml"], cwd=pkg)
    assert code == 0, err
    assert "no_camera" in out
