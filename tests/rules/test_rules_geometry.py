"""G rules: meshes on disk, shape sizes, materials and colours, missing geometry."""
from __future__ import annotations

from pathlib import Path

import pytest

from urdfcheck.core.findings import Severity
from urdfcheck.core.paths import shown
from urdfcheck.model.build import model_from_string
from urdfcheck.rules import engine
from urdfcheck.run import Target, lint_target

STL = "solid p\n facet normal 0 0 1\n  outer loop\n   vertex 0 0 0\n   vertex 1 0 0\n   vertex 0 1 0\n" \
      "  endloop\n endfacet\nendsolid p\n"


def run(xml: str, select=("G",), options=None):
    model = model_from_string(xml, "robot.urdf")
    ctx = engine.Context(selection=engine.Selection(select=tuple(select), options=dict(options or {})))
    return engine.run_checks(model, ctx)


def lint_file(path: Path, select=("G001",), options=None, packages=None):
    sel = engine.Selection(select=tuple(select), options=dict(options or {}))
    findings, _ = lint_target(Target(path, packages=dict(packages or {})), sel)
    return findings


def codes(findings):
    return sorted(f.code for f in findings)


def link(body: str, name="base_link") -> str:
    return f'<link name="{name}">{body}</link>'


def visual(geometry: str, material: str = "") -> str:
    return f"<visual><geometry>{geometry}</geometry>{material}</visual>"


def robot(*parts: str) -> str:
    return '<robot name="r">' + "".join(parts) + "</robot>"


# --- G001 --------------------------------------------------------------------------------------------

@pytest.fixture
def pkg(tmp_path):
    """A workspace with package g001_pkg (meshes/part.stl, meshes/Wheel.STL) and its urdf/ folder."""
    root = tmp_path / "ws" / "g001_pkg"
    (root / "meshes").mkdir(parents=True)
    (root / "urdf").mkdir()
    (root / "package.xml").write_text("<package format='3'><name>g001_pkg</name></package>")
    (root / "meshes" / "part.stl").write_text(STL)
    (root / "meshes" / "Wheel.STL").write_text(STL)
    return root


def write_model(pkg: Path, *meshes: str, collision: bool = False) -> Path:
    shapes = "".join(f'<{"collision" if collision else "visual"}><geometry><mesh filename="{m}"/></geometry>'
                     f'</{"collision" if collision else "visual"}>' for m in meshes)
    p = pkg / "urdf" / "robot.urdf"
    p.write_text(robot(link(shapes)))
    return p


def test_g001_existing_meshes_package_relative_and_file_uri(pkg):
    p = write_model(pkg, "package://g001_pkg/meshes/part.stl", "../meshes/part.stl",
                    f"file://{pkg}/meshes/part.stl")
    assert lint_file(p) == []


def test_g001_missing_file_in_found_package(pkg):
    p = write_model(pkg, "package://g001_pkg/meshes/missing.stl")
    found = lint_file(p)
    assert codes(found) == ["G001"]
    assert "file not found" in found[0].message and found[0].location.line == 1


def test_g001_unknown_package(pkg):
    p = write_model(pkg, "package://no_such_pkg_g001/meshes/part.stl")
    found = lint_file(p)
    assert codes(found) == ["G001"]
    assert "package 'no_such_pkg_g001' not found" in found[0].message
    assert "--package no_such_pkg_g001=PATH" in found[0].message


def test_g001_explicit_package_map(pkg, tmp_path):
    other = tmp_path / "elsewhere"
    (other / "meshes").mkdir(parents=True)
    (other / "meshes" / "arm.stl").write_text(STL)
    p = write_model(pkg, "package://vendor_meshes/meshes/arm.stl")
    assert lint_file(p, packages={"vendor_meshes": str(other)}) == []


def test_g001_case_hint(pkg):
    p = write_model(pkg, "package://g001_pkg/meshes/wheel.stl")
    found = lint_file(p)
    assert codes(found) == ["G001"] and "'Wheel.STL'" in found[0].message and "case-sensitive" in found[0].message


def test_g001_outside_package_roots_not_checked(pkg):
    p = write_model(pkg, "file:///etc/hostname", "file:///no/such/dir/x.stl")
    found = lint_file(p)
    assert codes(found) == ["G001", "G001"]
    assert all("outside the package roots, not checked" in f.message for f in found)


def test_g001_package_uri_without_package_name(pkg):
    p = write_model(pkg, "package:///g001_pkg/meshes/part.stl")
    found = lint_file(p)
    assert codes(found) == ["G001"] and "no package name" in found[0].message


def test_g001_remote_and_unsupported_schemes(pkg):
    p = write_model(pkg, "https://example.com/part.stl", "model://part/meshes/part.dae")
    found = lint_file(p)
    assert codes(found) == ["G001"]
    assert "model://" in found[0].message and "unsupported" in found[0].message


def test_g001_once_per_uri_with_related_uses(pkg):
    p = write_model(pkg, "package://g001_pkg/meshes/gone.stl", "package://g001_pkg/meshes/gone.stl",
                    "package://g001_pkg/meshes/gone.stl")
    found = lint_file(p)
    assert len(found) == 1 and len(found[0].related) == 2 and "2 more uses" in found[0].message


def test_g001_ignore_option(pkg):
    p = write_model(pkg, "package://g001_pkg/meshes/lfs/big.dae")
    assert lint_file(p, options={"G001": {"ignore": ["package://g001_pkg/meshes/lfs/*"]}}) == []


def test_g001_relative_to_entry_folder(pkg):
    p = write_model(pkg, "part.stl")  # urdf/part.stl does not exist; meshes/part.stl does
    found = lint_file(p)
    # the path as reports show it (relative when the tmp folder shares a top-level folder with the working one)
    assert codes(found) == ["G001"] and shown(pkg / "urdf" / "part.stl") in found[0].message


# --- G002 --------------------------------------------------------------------------------------------

@pytest.mark.parametrize("geometry, what", [
    ('<box size="0.1 0 0.1"/>', "y=0"),
    ('<box size="-0.1 0.1 0.1"/>', "x=-0.1"),
    ('<cylinder radius="0" length="0.1"/>', "radius=0"),
    ('<cylinder radius="0.1" length="-1"/>', "length=-1"),
    ('<sphere radius="0"/>', "radius=0"),
    ('<capsule radius="0.1" length="0"/>', "length=0"),
])
def test_g002_non_positive_primitive(geometry, what):
    found = run(robot(link(visual(geometry))))
    assert codes(found) == ["G002"] and what in found[0].message and found[0].severity == Severity.ERROR


def test_g002_zero_mesh_scale_is_an_error():
    found = run(robot(link(visual('<mesh filename="package://p/m.stl" scale="1 0 -1"/>'))), select=("G002",))
    assert codes(found) == ["G002"] and found[0].severity == Severity.ERROR and "along y" in found[0].message


def test_g002_negative_mesh_scale_mirrors_and_is_fine():
    assert run(robot(link(visual('<mesh filename="package://p/m.stl" scale="1 -1 1"/>'))), select=("G002",)) == []


def test_g002_positive_sizes_are_fine():
    xml = robot(link(visual('<box size="0.1 0.2 0.001"/>') + visual('<cylinder radius="0.1" length="0.05"/>')
                     + visual('<sphere radius="0.05"/>')
                     + visual('<mesh filename="package://p/m.stl" scale="0.001 0.001 0.001"/>')))
    assert run(xml, select=("G002",)) == []


def test_g002_unreadable_sizes_left_to_the_u_rules():
    found = run(robot(link(visual('<box size="0.1 0.1"/>'))), select=("G", "U"))
    assert codes(found) == ["U004"]


# --- G003 --------------------------------------------------------------------------------------------

RED = '<material name="red"><color rgba="1 0 0 1"/></material>'


def test_g003_top_level_definition_anywhere_in_the_file():
    xml = robot(link(visual('<sphere radius="1"/>', '<material name="red"/>')), RED)
    assert run(xml) == []


def test_g003_never_defined():
    found = run(robot(link(visual('<sphere radius="1"/>', '<material name="blak"/>'))))
    assert codes(found) == ["G003"] and "never defined" in found[0].message


def test_g003_inline_definition_in_an_earlier_link_counts():
    xml = robot(link(visual('<sphere radius="1"/>', RED), "a"),
                link(visual('<sphere radius="1"/>', '<material name="red"/>'), "b"))
    assert run(xml) == []


def test_g003_texture_counts_as_a_definition():
    xml = robot(link(visual('<sphere radius="1"/>', '<material name="t"><texture filename="t.png"/></material>')))
    assert run(xml, select=("G003",)) == []


def test_g003_name_only_reference_before_the_inline_definition():
    xml = robot(link(visual('<sphere radius="1"/>', '<material name="red"/>'), "a"),
                link(visual('<sphere radius="1"/>', RED), "b"))
    found = run(xml)
    assert codes(found) == ["G003", "G003"]
    assert "before it is defined" in found[0].message and "ignores this colour" in found[1].message


def test_g003_top_level_material_without_colour():
    xml = robot('<material name="grey"/>', link(visual('<sphere radius="1"/>', '<material name="grey"/>')))
    found = run(xml)
    assert codes(found) == ["G003"] and "without <color> or <texture>" in found[0].message
    assert found[0].related


def test_g003_empty_name_with_inline_colour_is_fine():
    # SolidWorks exporter style: urdfdom only looks up non-empty names, the inline colour is used
    found = run(robot(link(visual('<sphere radius="1"/>', '<material name=""><color rgba="1 0 0 1"/></material>'))))
    assert found == []


# --- G004 --------------------------------------------------------------------------------------------

def test_g004_top_level_0_255_colour():
    found = run(robot('<material name="o"><color rgba="255 128 0 1"/></material>'))
    assert codes(found) == ["G004"] and "divide by 255" in found[0].message


def test_g004_inline_negative_alpha():
    found = run(robot(link(visual('<sphere radius="1"/>', '<material name="x"><color rgba="0.5 0.5 0.5 -1"/>'
                                                          '</material>'))))
    assert codes(found) == ["G004"] and "a=-1" in found[0].message and "255" not in found[0].message


def test_g004_bounds_are_inclusive():
    assert run(robot('<material name="w"><color rgba="1 1 1 0"/></material>')) == []


# --- G005 --------------------------------------------------------------------------------------------

def test_g005_visual_without_geometry():
    found = run(robot(link('<visual><origin xyz="0 0 1"/></visual>')))
    assert codes(found) == ["G005"] and "no <geometry>" in found[0].message


def test_g005_empty_geometry():
    found = run(robot(link("<collision><geometry/></collision>")))
    assert codes(found) == ["G005"] and "empty" in found[0].message


def test_g005_unknown_shape():
    found = run(robot(link('<visual><geometry><cone radius="1"/></geometry></visual>')), select=("G005",))
    assert codes(found) == ["G005"] and "<cone>" in found[0].message


def test_geometry_rules_quiet_on_a_plain_link():
    assert run(robot(link(visual('<box size="1 1 1"/>') + '<collision><geometry><sphere radius="0.5"/>'
                                                           '</geometry></collision>'))) == []
