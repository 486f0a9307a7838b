"""`urdfcheck diff`: what a change does to the robot (issue 22)."""
from __future__ import annotations

import json
import os
import re
import shutil
import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]
AGV = ROOT / "examples" / "agv"
SRC = str(ROOT / "src")


def cli(*args, cwd=None):
    env = {**os.environ, "PYTHONPATH": SRC + os.pathsep + os.environ.get("PYTHONPATH", "")}
    return subprocess.run([sys.executable, "-m", "urdfcheck", "diff", *map(str, args)], capture_output=True,
                          text=True, cwd=cwd, env=env, timeout=120)


def edit(path: Path, old: str, new: str) -> None:
    text = path.read_text()
    assert old in text, old
    path.write_text(text.replace(old, new))


@pytest.fixture
def two(tmp_path):
    old, new = tmp_path / "old", tmp_path / "new"
    shutil.copytree(AGV, old)
    shutil.copytree(AGV, new)
    return old, new


def as_json(res):
    assert res.returncode in (0, 1), res.stderr
    return json.loads(res.stdout)


def test_laser_moved_one_centimetre(two):
    old, new = two
    edit(new / "urdf/agv.urdf.xacro", 'name="laser_link" parent="base_link" xyz="0.25 0 0.15"',
         'name="laser_link" parent="base_link" xyz="0.26 0 0.15"')
    data = as_json(cli(old, new, "--format", "json"))
    xacro = [m for m in data["models"] if m["model"] == "urdf/agv.urdf.xacro"]
    assert {m["variant"] for m in xacro} == {"camera", "no_camera"}
    for m in xacro:
        assert m["status"] == "changed"
        assert [f["frame"] for f in m["moved"]] == ["laser_link"]  # and nothing else moved
        assert m["moved"][0]["zero_mm"] == pytest.approx(10.0, abs=1e-6)
        assert m["moved"][0]["deg"] == 0
        assert m["moved"][0]["because"] == "laser_link_joint"
        assert [(c["name"], c["field"]) for c in m["changes"]] == [("laser_link_joint", "origin.xyz")]
    plain = [m for m in data["models"] if m["model"] == "urdf/agv.urdf"]
    assert [m["status"] for m in plain] == ["unchanged"]
    res = cli(old, new)
    assert "laser_link moved 10 mm" in res.stdout and res.returncode == 0
    assert cli(old, new, "--fail-on-change").returncode == 1


def test_joint_limit_in_the_macro(two):
    old, new = two
    edit(new / "urdf/macros/components.xacro", 'velocity="10.0"', 'velocity="8.0"')
    data = as_json(cli(old, new, "--format", "json"))
    m = next(m for m in data["models"] if m["variant"] == "camera")
    got = {(c["name"], c["field"], c["old"], c["new"]) for c in m["changes"]}
    assert got == {("left_wheel_joint", "limit.velocity", 10.0, 8.0),
                   ("right_wheel_joint", "limit.velocity", 10.0, 8.0)}
    assert m["moved"] == []


def test_comments_and_formatting_are_no_change(two):
    old, new = two
    f = new / "urdf/agv.urdf.xacro"
    text = f.read_text().replace('xyz="0.25 0 0.15"', 'xyz="0.250  0.0 0.15"  ')
    text = text.replace("<!-- Sensors -->", "<!-- Sensors (comment edited) -->\n\n   <!-- another -->")
    f.write_text(text.replace('value="0.10"/>', 'value="0.1" />'))
    res = cli(old, new, "--fail-on-change")
    assert res.returncode == 0, res.stdout + res.stderr
    assert "no change in 3 model variants" in res.stdout


def test_rename_inertia_material_and_contract(two):
    old, new = two
    f = new / "urdf/agv.urdf.xacro"
    edit(f, 'name="imu_link" parent="base_link"', 'name="imu_frame" parent="base_link"')
    edit(f, 'mass="0.15"/>', 'mass="0.25"/>')
    edit(f, '<color rgba="0.05 0.05 0.05 1.0"/>', '<color rgba="0.1 0.1 0.1 1.0"/>')
    edit(new / "config/agv_controllers.yaml", "left_wheel_names: [left_wheel_joint]", "left_wheel_names: [left_wheel]")
    data = as_json(cli(old, new, "--format", "json"))
    m = next(m for m in data["models"] if m["variant"] == "camera")
    assert m["links"]["renamed"] == [["imu_link", "imu_frame"]]
    assert m["joints"]["renamed"] == [["imu_link_joint", "imu_frame_joint"]]
    assert m["links"]["added"] == m["links"]["removed"] == []
    fields = {(c["kind"], c["name"], c["field"]) for c in m["changes"]}
    assert ("link", "laser_link", "mass") in fields and ("link", "laser_link", "inertia") in fields
    assert ("material", "black", "rgba") in fields
    assert ("link", "left_wheel_link", "visual[left_wheel].material") in fields
    contract = [c for c in m["changes"] if c["kind"] == "contract"]
    assert any("diff_drive_controller" in c["name"] and "left_wheel" in c["new"] for c in contract), contract
    assert m["moved"] == []
    md = cli(old, new, "--format", "markdown").stdout
    assert "```mermaid" in md and "linkStyle" in md and "| what | field | before | after |" in md


def test_added_link_and_moved_children(tmp_path):
    a = tmp_path / "a.urdf"
    b = tmp_path / "b.urdf"
    base = """<robot name="r">
  <link name="base"/><link name="arm"/><link name="tool"/>
  <joint name="j1" type="revolute"><parent link="base"/><child link="arm"/><origin xyz="0 0 {z}"/>
    <axis xyz="0 0 1"/><limit lower="-1" upper="1" effort="1" velocity="1"/></joint>
  <joint name="j2" type="fixed"><parent link="arm"/><child link="tool"/><origin xyz="0.5 0 0"/></joint>
  {extra}
</robot>"""
    a.write_text(base.format(z="0.1", extra=""))
    b.write_text(base.format(z="0.1", extra='<link name="cam"/><joint name="jc" type="fixed"><parent link="tool"/>'
                                           '<child link="cam"/></joint>').replace('<axis xyz="0 0 1"/>',
                                                                                    '<axis xyz="0 1 0"/>'))
    data = as_json(cli(a, b, "--format", "json"))
    (m,) = data["models"]
    assert m["links"]["added"] == ["cam"] and m["joints"]["added"] == ["jc"]
    moved = {x["frame"]: x for x in m["moved"]}
    # the axis changed: nothing moves at zero, the random configurations move the arm and what hangs from it
    assert set(moved) == {"arm", "tool"}
    assert moved["tool"]["zero_mm"] == 0 and moved["tool"]["mm"] > 0 and moved["tool"]["because"] == "j1"
    assert ("j1", "axis") in {(c["name"], c["field"]) for c in m["changes"]}


def _git(*args, cwd):
    env = {**os.environ, "GIT_AUTHOR_NAME": "t", "GIT_AUTHOR_EMAIL": "t@t", "GIT_COMMITTER_NAME": "t",
           "GIT_COMMITTER_EMAIL": "t@t"}
    subprocess.run(["git", *args], cwd=cwd, check=True, capture_output=True, env=env)


@pytest.mark.skipif(shutil.which("git") is None, reason="git not installed")
def test_git_revision_reads_old_files_without_checkout(tmp_path):
    repo = tmp_path / "repo"
    shutil.copytree(AGV, repo / "agv_description")
    _git("init", "-q", cwd=repo)
    _git("add", "-A", cwd=repo)
    _git("commit", "-qm", "init", cwd=repo)
    f = repo / "agv_description/urdf/agv.urdf.xacro"
    edit(f, 'xyz="0.25 0 0.15"', 'xyz="0.26 0 0.15"')
    before = f.read_text()
    res = cli("--git", "HEAD", "--format", "json", cwd=repo)
    data = as_json(res)
    changed = [m for m in data["models"] if m["status"] == "changed"]
    assert changed and all([x["frame"] for x in m["moved"]] == ["laser_link"] for m in changed)
    assert f.read_text() == before  # the working tree is untouched
    status = subprocess.run(["git", "status", "--porcelain"], cwd=repo, capture_output=True, text=True).stdout
    assert status.split() == ["M", "agv_description/urdf/agv.urdf.xacro"]
    assert not data["old"].startswith(str(repo))  # the old side lived outside the user's tree
    assert cli("--git", "no-such-rev", cwd=repo).returncode == 2


def test_usage_errors(tmp_path):
    assert cli(tmp_path / "missing", tmp_path).returncode == 2
    assert cli(tmp_path).returncode == 2


def test_broken_side_is_not_a_clean_diff(tmp_path):
    a, b = tmp_path / "a.urdf", tmp_path / "b.urdf"
    a.write_text('<robot name="r"><link name="base"/></robot>')
    b.write_text('<robot name="r"><link name="base"/>')
    res = cli(a, b)
    assert res.returncode == 1 and "does not load" in res.stdout


@pytest.mark.skipif(shutil.which("git") is None, reason="git not installed")
def test_git_new_package_is_added(tmp_path):
    repo = tmp_path / "repo"
    (repo / "docs").mkdir(parents=True)
    (repo / "docs/readme.md").write_text("x\n")
    _git("init", "-q", cwd=repo)
    _git("add", "-A", cwd=repo)
    _git("commit", "-qm", "init", cwd=repo)
    shutil.copytree(AGV, repo / "agv_description")
    data = as_json(cli("--git", "HEAD", "agv_description", "--format", "json", cwd=repo))
    assert {m["status"] for m in data["models"]} == {"added"}
    assert cli("--git", "HEAD", "agv_description", "--fail-on-change", cwd=repo).returncode == 1


def test_plain_urdf_against_the_variants_of_a_xacro(two):
    old, new = two
    data = as_json(cli(old / "urdf/agv.urdf", new / "urdf/agv.urdf.xacro", "--format", "json"))
    by = {m["variant"]: m for m in data["models"]}
    assert set(by) == {"camera", "no_camera"}  # the one URDF against each variant of the xacro
    assert by["camera"]["status"] == "unchanged"  # agv.urdf is the xacro's output with use_camera:=true
    assert by["no_camera"]["links"]["removed"] == ["camera_link"]
    shapes = {c["field"] for c in by["no_camera"]["changes"] if c["name"] == "base_link"}
    assert shapes == {"visual[camera_mast]", "collision[camera_mast]"}


def _repo(tmp_path, drop_config=True) -> Path:
    repo = tmp_path / "repo"
    shutil.copytree(AGV, repo / "agv_description")
    if drop_config:  # zero config: the launch file's deployment is what is planned
        (repo / "agv_description/urdfcheck.yaml").unlink()
    _git("init", "-q", cwd=repo)
    _git("add", "-A", cwd=repo)
    _git("commit", "-qm", "init", cwd=repo)
    return repo


@pytest.mark.skipif(shutil.which("git") is None, reason="git not installed")
def test_two_launch_files_match_their_own_deployment(tmp_path):
    """`cp bringup.launch sim.launch`, commit, `diff --git HEAD`: nothing changed, nothing removed and added,
    and the compared tree's temporary folder is named nowhere."""
    repo = _repo(tmp_path)
    launch = repo / "agv_description/launch"
    shutil.copy(launch / "agv.launch.xml", launch / "sim.launch.xml")
    _git("add", "-A", cwd=repo)
    _git("commit", "-qm", "sim", cwd=repo)
    res = cli("--git", "HEAD", "--format", "json", "--fail-on-change", cwd=repo)
    data = as_json(res)
    assert res.returncode == 0, res.stdout
    assert {m["status"] for m in data["models"]} == {"unchanged"}
    variants = {m["variant"] for m in data["models"]}
    assert {"agv_description/launch/agv.launch.xml", "agv_description/launch/sim.launch.xml"} <= variants
    assert "urdfcheck-" not in res.stdout and str(tmp_path) not in res.stdout and "/tmp" not in res.stdout
    assert data["old"] == "HEAD" and not os.path.isabs(data["new"])
    # the launch file added since HEAD~1 is the one thing added (with each of its launch-argument variants)
    data = as_json(cli("--git", "HEAD~1", "--format", "json", cwd=repo))
    added = {(m["variant"], m["status"]) for m in data["models"] if m["status"] != "unchanged"}
    assert ("agv_description/launch/sim.launch.xml", "added") in added
    assert {v.split(" [")[0] for v, _ in added} == {"agv_description/launch/sim.launch.xml"}
    assert {s for _, s in added} == {"added"}


def test_two_folders_json_names_no_absolute_path(two):
    old, new = two
    res = cli(old, new, "--format", "json", cwd=old.parent)
    data = as_json(res)
    assert data["old"] == "old" and data["new"] == "new"
    assert str(old.parent) not in res.stdout


@pytest.mark.skipif(shutil.which("git") is None, reason="git not installed")
def test_absolute_mesh_paths_are_compared_package_relative(tmp_path):
    """A model whose meshes are `file://$(find pkg)/...` (absolute once expanded): the revision's copy lies
    elsewhere, yet a comment-only edit is no change."""
    repo = tmp_path / "repo"
    shutil.copytree(AGV, repo / "agv_description")
    f = repo / "agv_description/urdf/agv.urdf.xacro"
    edit(f, '<robot name="agv" xmlns:xacro="http://www.ros.org/wiki/xacro">',
         '<robot name="agv" xmlns:xacro="http://www.ros.org/wiki/xacro">\n  <link name="shell"><visual><geometry>'
         '<mesh filename="file://$(find agv_description)/meshes/shell.stl"/></geometry></visual></link>\n'
         '  <joint name="shell_joint" type="fixed"><parent link="base_link"/><child link="shell"/></joint>')
    (repo / "agv_description/meshes").mkdir()
    (repo / "agv_description/meshes/shell.stl").write_bytes(b"solid s\nendsolid s\n")
    _git("init", "-q", cwd=repo)
    _git("add", "-A", cwd=repo)
    _git("commit", "-qm", "init", cwd=repo)
    edit(f, "agv: a small differential-drive AGV.", "agv: a small differential-drive AGV (comment edit).")
    res = cli("--git", "HEAD", "--format", "json", cwd=repo)
    data = as_json(res)
    assert {m["status"] for m in data["models"]} == {"unchanged"}, res.stdout
    # and a real move of the mesh file is a change, named package-relative
    edit(f, "/meshes/shell.stl", "/meshes/shell2.stl")
    data = as_json(cli("--git", "HEAD", "--format", "json", cwd=repo))
    meshes = {(c["old"][0], c["new"][0]) for m in data["models"] for c in m["changes"] if c["field"].endswith("mesh")}
    assert meshes == {("package://agv_description/meshes/shell.stl", "package://agv_description/meshes/shell2.stl")}


@pytest.mark.skipif(shutil.which("git") is None, reason="git not installed")
def test_controller_parameters_a_contract_reads_are_shown(tmp_path):
    repo = _repo(tmp_path)
    f = repo / "agv_description/config/agv_controllers.yaml"
    edit(f, "wheel_separation: 0.50", "wheel_separation: 0.45")
    edit(f, "enable_odom_tf: true", "enable_odom_tf: false")
    res = cli("--git", "HEAD", "--format", "json", cwd=repo)
    data = as_json(res)
    # the deployments whose launch file loads the controller file; the package's other model (agv.urdf) is not
    # paired with it (pairing by reference first, issue 37)
    deployed = [m for m in data["models"] if m["variant"].startswith("agv_description/launch/")]
    assert deployed
    for m in deployed:
        got = {c["name"]: (c["old"], c["new"]) for c in m["changes"]}
        assert got["controller diff_drive_controller wheel_separation"] == (0.5, 0.45)
        assert got["controller diff_drive_controller odom tf odom -> base_link"] == ("on", "off")
    text = cli("--git", "HEAD", cwd=repo).stdout
    assert "wheel_separation: 0.5 -> 0.45" in text


@pytest.mark.skipif(shutil.which("git") is None, reason="git not installed")
def test_controller_joint_lists_and_frames_are_shown(tmp_path):
    """The other contract facts issue 38 names: a wheel joint list (the right wheels now two joints, one of them
    no joint of the model) and the frame the odometry is about."""
    repo = _repo(tmp_path)
    f = repo / "agv_description/config/agv_controllers.yaml"
    edit(f, "right_wheel_names: [right_wheel_joint]", "right_wheel_names: [right_wheel_joint, rear_right_joint]")
    edit(f, "base_frame_id: base_link", "base_frame_id: base_footprint")
    data = as_json(cli("--git", "HEAD", "--format", "json", cwd=repo))
    deployed = [m for m in data["models"] if m["variant"].startswith("agv_description/launch/")]
    assert deployed
    for m in deployed:
        got = {c["name"]: (c["old"], c["new"]) for c in m["changes"]}
        assert got["controller diff_drive_controller right wheels"] == (["right_wheel_joint"],
                                                                       ["right_wheel_joint", "rear_right_joint"])
        assert got["controller diff_drive_controller joints"] == (
            ["left_wheel_joint", "right_wheel_joint"], ["left_wheel_joint", "rear_right_joint", "right_wheel_joint"])
        assert "controller diff_drive_controller odom tf odom -> base_footprint" in got
        assert any(k.endswith(" frames") and "base_footprint" in (v[1] or []) for k, v in got.items()), got


def test_per_variant_repeats_are_collapsed(two):
    old, new = two
    edit(new / "urdf/agv.urdf.xacro", 'name="laser_link" parent="base_link" xyz="0.25 0 0.15"',
         'name="laser_link" parent="base_link" xyz="0.26 0 0.15"')
    text = cli(old, new).stdout
    assert text.count("laser_link moved 10 mm") == 1, text  # once for both variants of the xacro
    assert "urdf/agv.urdf.xacro: changed in 2 of 2 variants" in text
    md = cli(old, new, "--format", "markdown").stdout
    assert md.count("origin.xyz") == 1, md


@pytest.mark.skipif(shutil.which("git") is None, reason="git not installed")
def test_a_renamed_model_is_compared_with_its_old_self(tmp_path):
    repo = _repo(tmp_path)
    _git("mv", "agv_description/urdf/agv.urdf", "agv_description/urdf/agv_v2.urdf", cwd=repo)
    edit(repo / "agv_description/urdf/agv_v2.urdf", 'rpy="0 0 0" xyz="0.25 0 0.15"', 'rpy="0 0 0" xyz="0.26 0 0.15"')
    data = as_json(cli("--git", "HEAD", "--format", "json", cwd=repo))
    mine = [m for m in data["models"] if "agv_v2" in m["model"] or m["model"].endswith("agv.urdf")]
    assert [m["status"] for m in mine] == ["changed"], mine
    fields = [(c["kind"], c["field"]) for c in mine[0]["changes"]]
    assert ("model", "file") in fields and [x["frame"] for x in mine[0]["moved"]] == ["laser_link"]


def test_markdown_and_text_are_inert_for_hostile_names(tmp_path):
    """Link and joint names are the pull request's: no HTML, links, @mentions or bidi controls."""
    evil = "x&lt;img src=y onerror=alert(1)&gt;@octocat[z](https://e.example)\u202eevil"
    a, b = tmp_path / "a.urdf", tmp_path / "b.urdf"
    a.write_text('<robot name="r"><link name="base"/></robot>')
    b.write_text(f'<robot name="r"><link name="base"/><link name="{evil}"/>'
                 f'<joint name="j{evil}" type="fixed"><parent link="base"/><child link="{evil}"/></joint></robot>')
    md = cli(a, b, "--format", "markdown").stdout
    text = cli(a, b).stdout
    assert "added" in text and "added" in md
    for out in (md, text):
        assert "\u202e" not in out
    assert "<img" not in md and "@octocat" not in md
    assert not re.search(r"(?<!\\)\]\(https", md)  # a link only where the bracket is not escaped
