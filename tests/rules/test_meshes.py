"""Issue 41: mesh files read by urdfcheck itself (core/meshfile.py, through the door), millimetre meshes (U012)
and self-collision at zero on collision meshes (G006).

The seeded defects are example packages (examples/broken/units_mm_mesh, self_collision_mesh; test_examples.py
checks their EXPECTED); here their clean twins, the reader's formats and bounds, and the edges of each rule."""
from __future__ import annotations

import os
import shutil
import struct

import pytest
from conftest import REPO, lint_json

from urdfcheck.core import door, meshfile

BROKEN = REPO / "examples" / "broken"


def _box(sx, sy, sz, c=(0.0, 0.0, 0.0)):
    """The 12 triangles of a box of the given size centred at c."""
    v = [(c[0] + a * sx / 2, c[1] + b * sy / 2, c[2] + d * sz / 2) for a in (-1, 1) for b in (-1, 1) for d in (-1, 1)]
    faces = [(0, 1, 3), (0, 3, 2), (4, 6, 7), (4, 7, 5), (0, 4, 5), (0, 5, 1), (2, 3, 7), (2, 7, 6), (0, 2, 6),
             (0, 6, 4), (1, 5, 7), (1, 7, 3)]
    return [(v[i], v[j], v[k]) for i, j, k in faces]


def _binary_stl(tris) -> bytes:
    out = bytearray(b"solid but binary".ljust(80)) + struct.pack("<I", len(tris))
    for t in tris:
        out += struct.pack("<12fH", 0, 0, 0, *t[0], *t[1], *t[2], 0)
    return bytes(out)


def _ascii_stl(tris) -> str:
    lines = ["solid s"]
    for t in tris:
        lines += ["facet normal 0 0 0", "outer loop", *(f"vertex {x} {y} {z}" for x, y, z in t), "endloop", "endfacet"]
    return "\n".join([*lines, "endsolid s"]) + "\n"


def _copy(tmp_path, name):
    dst = tmp_path / name
    shutil.copytree(BROKEN / name, dst)
    (dst / "EXPECTED").unlink()
    return dst


def _edit(path, old: str, new: str):
    text = path.read_text(encoding="utf-8")
    assert old in text, old
    path.write_text(text.replace(old, new), encoding="utf-8")


def _codes(folder, code):
    _, report = lint_json([str(folder)])
    return [(os.path.basename(f["location"]["file"]), f["location"]["line"], f["severity"])
            for f in report["findings"] if f["code"] == code]


# --- the reader ---------------------------------------------------------------------------------------------------
def _bounds(path):
    m = meshfile.read(path)
    assert m is not None, path
    lo, hi = m.bounds()
    return [round(x, 6) for x in lo + hi], len(m.triangles)


def test_stl_binary_and_ascii(tmp_path):
    (tmp_path / "b.stl").write_bytes(_binary_stl(_box(2, 4, 6, (1, 0, 0))))
    (tmp_path / "a.STL").write_text(_ascii_stl(_box(2, 4, 6)), encoding="utf-8")
    assert _bounds(tmp_path / "b.stl") == ([0, -2, -3, 2, 2, 3], 12)
    assert _bounds(tmp_path / "a.STL") == ([-1, -2, -3, 1, 2, 3], 12)


def test_obj_vertices_and_faces(tmp_path):
    (tmp_path / "m.obj").write_text("# cube corner\nv 0 0 0\nv 10 0 0\nv 0 20 0\nv 0 0 30\nvn 0 0 1\n"
                                    "f 1//1 2//1 3//1\nf 1 2 3 4\n", encoding="utf-8")
    assert _bounds(tmp_path / "m.obj") == ([0, 0, 0, 10, 20, 30], 3)


_DAE = """<?xml version="1.0"?>
<COLLADA xmlns="http://www.collada.org/2005/11/COLLADASchema" version="1.4.1">
  <asset><unit name="{unit_name}" meter="{meter}"/><up_axis>Z_UP</up_axis></asset>
  <library_geometries>
    <geometry id="g"><mesh>
      <source id="g-pos"><float_array id="g-arr" count="9">0 0 0 100 0 0 0 200 0</float_array></source>
      <source id="g-nrm"><float_array id="g-narr" count="3">0 0 1</float_array></source>
      <vertices id="g-v"><input semantic="POSITION" source="#g-pos"/></vertices>
      <triangles count="1"><input semantic="VERTEX" source="#g-v" offset="0"/>
        <input semantic="NORMAL" source="#g-nrm" offset="1"/><p>0 0 1 0 2 0</p></triangles>
    </mesh></geometry>
  </library_geometries>
  <library_visual_scenes><visual_scene id="s">
    <node id="n">{transform}<instance_geometry url="#g"/></node>
  </visual_scene></library_visual_scenes>
</COLLADA>
"""


def test_collada_unit_and_node_transforms(tmp_path):
    (tmp_path / "mm.dae").write_text(_DAE.format(unit_name="millimeter", meter="0.001", transform=""), "utf-8")
    assert _bounds(tmp_path / "mm.dae") == ([0, 0, 0, 0.1, 0.2, 0], 1)
    (tmp_path / "n.dae").write_text(_DAE.format(unit_name="meter", meter="1", transform=(
        '<translate>1 0 0</translate><rotate>0 0 1 90</rotate><scale>0.01 0.01 0.01</scale>')), "utf-8")
    assert _bounds(tmp_path / "n.dae") == ([-1, 0, 0, 1, 1, 0], 1)


@pytest.mark.parametrize("name,data", [
    ("m.ply", b"ply\nformat ascii 1.0\n"),  # a format not read
    ("m.stl", b"not an stl at all"),
    ("m.dae", b"<COLLADA><unclosed"),
    ("m.obj", b"v 1 2\n"),
    ("m.stl", b"solid s\nvertex 1 nan 3\nendsolid\n"),
])
def test_what_is_not_read_gives_none(tmp_path, name, data):
    (tmp_path / name).write_bytes(data)
    assert meshfile.read(tmp_path / name) is None


def test_bounded_in_bytes_and_vertices(tmp_path, monkeypatch):
    (tmp_path / "b.stl").write_bytes(_binary_stl(_box(1, 1, 1) * 4))
    monkeypatch.setattr(meshfile, "_cache", {})
    monkeypatch.setattr(meshfile, "MAX_VERTICES", 100)
    assert meshfile.read(tmp_path / "b.stl") is None  # 144 vertices
    monkeypatch.setattr(meshfile, "MAX_VERTICES", 1000)
    monkeypatch.setattr(meshfile, "MAX_BYTES", 1000)
    meshfile._cache.clear()  # a file is read once per run: the verdict is kept
    assert meshfile.read(tmp_path / "b.stl") is None  # 2484 bytes
    monkeypatch.setattr(meshfile, "MAX_BYTES", 10_000)
    meshfile._cache.clear()
    assert meshfile.read(tmp_path / "b.stl") is not None


def test_faces_are_bounded_too(tmp_path, monkeypatch):
    (tmp_path / "m.obj").write_text("v 0 0 0\nv 1 0 0\nv 0 1 0\n" + "f 1 2 3\n" * 50, encoding="utf-8")
    monkeypatch.setattr(meshfile, "_cache", {})
    monkeypatch.setattr(meshfile, "MAX_INDICES", 100)
    assert meshfile.read(tmp_path / "m.obj") is None
    (tmp_path / "m.dae").write_text(_DAE.format(unit_name="meter", meter="1", transform="").replace(
        "<p>0 0 1 0 2 0</p>", "<p>" + "0 0 1 0 2 0 " * 50 + "</p>"), "utf-8")
    assert meshfile.read(tmp_path / "m.dae") is None


def test_a_mesh_linked_out_of_the_run_is_not_read(tmp_path):
    outside, inside = tmp_path / "outside", tmp_path / "checkout"
    outside.mkdir()
    inside.mkdir()
    (outside / "secret.stl").write_bytes(_binary_stl(_box(1, 1, 1)))
    os.symlink(outside / "secret.stl", inside / "m.stl")
    with door.guarded([inside]):
        assert meshfile.read(inside / "m.stl") is None


# --- U012: millimetre meshes --------------------------------------------------------------------------------------
def test_mm_mesh_twin_with_scale_is_clean(tmp_path):
    pkg = _copy(tmp_path, "units_mm_mesh")
    assert _codes(pkg, "U012") == [("arm.urdf", 25, "warning")]
    _edit(pkg / "urdf" / "arm.urdf", 'meshes/link1.stl"/>', 'meshes/link1.stl" scale="0.001 0.001 0.001"/>')
    code, report = lint_json([str(pkg)])
    assert (code, report["findings"]) == (0, [])


def test_mm_mesh_found_by_the_inertia_alone(tmp_path):
    pkg = _copy(tmp_path, "units_mm_mesh")
    _edit(pkg / "urdf" / "arm.urdf", '<geometry><cylinder radius="0.04" length="0.3"/></geometry>',
          '<geometry><mesh filename="package://mm_arm_description/meshes/link1.stl"/></geometry>')
    assert _codes(pkg, "U012") == [("arm.urdf", 25, "warning"), ("arm.urdf", 29, "warning")]


@pytest.mark.parametrize("old,new", [
    # a reference that says metres: the collision box as large as the mesh as written
    ('<cylinder radius="0.04" length="0.3"/>', '<box size="80 80 300"/>'),
    # no reference at all (no other shape, no inertia)
    ('<geometry><cylinder radius="0.04" length="0.3"/></geometry>', '<geometry><sphere radius="0"/></geometry>'),
    # the mesh file is missing (as in the corpora): nothing to measure
    ('meshes/link1.stl"/>', 'meshes/gone.stl"/>'),
])
def test_mm_mesh_only_when_unambiguous(tmp_path, old, new):
    pkg = _copy(tmp_path, "units_mm_mesh")
    assert _codes(pkg, "U012") == [("arm.urdf", 25, "warning")]
    _edit(pkg / "urdf" / "arm.urdf", old, new)
    if "sphere" in new:
        _edit(pkg / "urdf" / "arm.urdf", '<mass value="1.0"/>', '<mass value="0"/>')
    assert _codes(pkg, "U012") == []


def test_mm_mesh_small_parts_and_far_ratios_are_not_reported(tmp_path):
    """A mesh under 5 units across as written, or 100x its reference, is not called millimetres."""
    pkg = _copy(tmp_path, "units_mm_mesh")
    assert _codes(pkg, "U012") == [("arm.urdf", 25, "warning")]
    (pkg / "meshes" / "link1.stl").write_bytes(_binary_stl(_box(0.8, 0.8, 3, (0, 0, 1.5))))
    assert _codes(pkg, "U012") == []
    (pkg / "meshes" / "link1.stl").write_bytes(_binary_stl(_box(8, 8, 30, (0, 0, 15))))
    assert _codes(pkg, "U012") == []


def test_mm_collada_with_its_unit_is_not_reported(tmp_path):
    pkg = _copy(tmp_path, "units_mm_mesh")
    # 300 as written in millimetres, and the file says so: 0.3 m, the link's size
    (pkg / "meshes" / "link1.dae").write_text(
        _DAE.format(unit_name="millimeter", meter="0.001", transform="").replace(
            "0 0 0 100 0 0 0 200 0", "0 0 0 80 0 0 0 80 300"), "utf-8")
    _edit(pkg / "urdf" / "arm.urdf", "meshes/link1.stl", "meshes/link1.dae")
    assert _codes(pkg, "U012") == []
    _edit(pkg / "meshes" / "link1.dae", 'meter="0.001"', 'meter="1"')
    assert _codes(pkg, "U012") == [("arm.urdf", 25, "warning")]


# --- G006 on collision meshes -------------------------------------------------------------------------------------
def test_self_collision_mesh_twin_is_clean(tmp_path):
    pytest.importorskip("coal")
    pkg = _copy(tmp_path, "self_collision_mesh")
    assert _codes(pkg, "G006") == [("arm.urdf", 32, "info")]
    _edit(pkg / "urdf" / "arm.urdf", "meshes/link2.stl", "meshes/link2_short.stl")
    code, report = lint_json([str(pkg)])
    assert (code, report["findings"]) == (0, [])


def test_self_collision_mesh_against_a_primitive_and_the_srdf(tmp_path):
    """A mesh against a box; an SRDF of the robot that does not disable the pair makes it a warning."""
    pytest.importorskip("coal")
    pkg = _copy(tmp_path, "self_collision_mesh")
    _edit(pkg / "urdf" / "arm.urdf", '<geometry><mesh filename="package://mesh_arm_description/meshes/base.stl"/>',
          '<origin xyz="0 0 0.05"/><geometry><box size="0.2 0.2 0.1"/>')
    assert _codes(pkg, "G006") == [("arm.urdf", 32, "info")]
    (pkg / "config").mkdir()
    (pkg / "config" / "arm.srdf").write_text(
        '<?xml version="1.0"?>\n<robot name="mesh_arm">\n  <group name="arm"><chain base_link="base_link" '
        'tip_link="link2"/></group>\n</robot>\n', encoding="utf-8")
    assert _codes(pkg, "G006") == [("arm.urdf", 32, "warning")]


def test_self_collision_mesh_scale_is_applied(tmp_path):
    """The same link2 mesh at half scale hangs clear of the base."""
    pytest.importorskip("coal")
    pkg = _copy(tmp_path, "self_collision_mesh")
    assert _codes(pkg, "G006") == [("arm.urdf", 32, "info")]
    _edit(pkg / "urdf" / "arm.urdf", 'meshes/link2.stl"/>', 'meshes/link2.stl" scale="1 1 0.5"/>')
    assert _codes(pkg, "G006") == []


def test_self_collision_concave_mesh_whose_hull_only_reaches_the_neighbour(tmp_path):
    """A U-shaped base around link2's foot: the hulls overlap by centimetres, the triangles never meet."""
    pytest.importorskip("coal")
    pkg = _copy(tmp_path, "self_collision_mesh")
    assert _codes(pkg, "G006") == [("arm.urdf", 32, "info")]
    # link2's foot spans x 0.035..0.085, z 0..0.3 (world); the base: two walls at x < 0.02 and x > 0.1, and a floor
    # below z = -0.02, so its hull holds the foot and its surface stays 15 mm away
    walls = _box(0.12, 0.2, 0.1, (-0.04, 0, 0.05)) + _box(0.1, 0.2, 0.1, (0.15, 0, 0.05)) \
        + _box(0.3, 0.2, 0.02, (0.05, 0, -0.03))
    (pkg / "meshes" / "base.stl").write_bytes(_binary_stl(walls))
    assert _codes(pkg, "G006") == []
    # the same walls closer, into the foot: reported
    walls = _box(0.16, 0.2, 0.1, (-0.02, 0, 0.05)) + _box(0.1, 0.2, 0.1, (0.15, 0, 0.05))
    (pkg / "meshes" / "base.stl").write_bytes(_binary_stl(walls))
    assert _codes(pkg, "G006") == [("arm.urdf", 32, "info")]


def test_self_collision_flat_mesh_is_left_out(tmp_path):
    """A flat collision mesh (a plane) has no convex hull: left out (coal's qhull crashed the process on it)."""
    pytest.importorskip("coal")
    pkg = _copy(tmp_path, "self_collision_mesh")
    assert _codes(pkg, "G006") == [("arm.urdf", 32, "info")]
    plane = [((-0.1, -0.1, 0.05), (0.1, -0.1, 0.05), (0.1, 0.1, 0.05)), ((-0.1, -0.1, 0.05), (0.1, 0.1, 0.05),
                                                                        (-0.1, 0.1, 0.05))]
    (pkg / "meshes" / "base.stl").write_bytes(_binary_stl(plane))
    assert _codes(pkg, "G006") == []


def test_self_collision_collada_with_another_up_axis_is_left_out(tmp_path):
    """The base as COLLADA: Z_UP is placed as written and found; Y_UP is left out (loaders disagree on turning it)."""
    pytest.importorskip("coal")
    pkg = _copy(tmp_path, "self_collision_mesh")
    tris = _box(0.2, 0.2, 0.1, (0, 0, 0.05))
    corners = sorted({p for t in tris for p in t})
    index = {p: i for i, p in enumerate(corners)}
    flat = " ".join(f"{x:g} {y:g} {z:g}" for x, y, z in corners)
    p = " ".join(f"{index[a]} 0 {index[b]} 0 {index[c]} 0" for a, b, c in tris)
    dae = _DAE.format(unit_name="meter", meter="1", transform="").replace(
        '<float_array id="g-arr" count="9">0 0 0 100 0 0 0 200 0</float_array>',
        f'<float_array id="g-arr" count="{3 * len(corners)}">{flat}</float_array>').replace(
        '<triangles count="1">', f'<triangles count="{len(tris)}">').replace("<p>0 0 1 0 2 0</p>", f"<p>{p}</p>")
    (pkg / "meshes" / "base.dae").write_text(dae, encoding="utf-8")
    _edit(pkg / "urdf" / "arm.urdf", "meshes/base.stl", "meshes/base.dae")
    assert _codes(pkg, "G006") == [("arm.urdf", 32, "info")]
    _edit(pkg / "meshes" / "base.dae", "<up_axis>Z_UP</up_axis>", "<up_axis>Y_UP</up_axis>")
    assert _codes(pkg, "G006") == []


def test_mm_mesh_placeholder_inertia_is_no_reference(tmp_path):
    """Three equal moments (a placeholder, usually) give no size: with only that, no finding."""
    pkg = _copy(tmp_path, "units_mm_mesh")
    assert _codes(pkg, "U012") == [("arm.urdf", 25, "warning")]
    _edit(pkg / "urdf" / "arm.urdf", '<geometry><cylinder radius="0.04" length="0.3"/></geometry>',
          '<geometry><mesh filename="package://mm_arm_description/meshes/link1.stl"/></geometry>')
    _edit(pkg / "urdf" / "arm.urdf", 'ixx="0.0079" ixy="0" ixz="0" iyy="0.0079" iyz="0" izz="0.0008"',
          'ixx="0.0057" ixy="0" ixz="0" iyy="0.0057" iyz="0" izz="0.0057"')
    assert _codes(pkg, "U012") == []
