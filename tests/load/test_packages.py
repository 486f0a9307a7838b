"""Package resolution without ROS: explicit map, ament index, ROS_PACKAGE_PATH, workspace scan."""

import os
from pathlib import Path

from urdfcheck.load.packages import Resolver


def pkg(folder: Path, name: str) -> Path:
    folder.mkdir(parents=True, exist_ok=True)
    (folder / "package.xml").write_text(f"<package format='3'><name>{name}</name></package>")
    return folder


def test_workspace_scan_prefers_the_package_nearest_the_input(tmp_path):
    far = pkg(tmp_path / "a_other" / "demo", "demo")
    near = pkg(tmp_path / "z_mine" / "demo", "demo")
    entry = near / "urdf" / "robot.urdf.xacro"
    entry.parent.mkdir()
    entry.write_text("<robot/>")
    assert Resolver(near=entry).find("demo") == near
    assert Resolver(near=far / "x.urdf").find("demo") == far


def test_explicit_mapping_wins_over_the_scan(tmp_path):
    pkg(tmp_path / "ws" / "demo", "demo")
    other = tmp_path / "elsewhere"
    other.mkdir()
    r = Resolver({"demo": str(other)}, near=tmp_path / "ws" / "demo" / "r.urdf")
    assert r.find("demo") == other.resolve()


def test_ament_index_and_ros_package_path(tmp_path):
    prefix = tmp_path / "install"
    (prefix / "share" / "ament_index" / "resource_index" / "packages").mkdir(parents=True)
    (prefix / "share" / "ament_index" / "resource_index" / "packages" / "arm").write_text("")
    ros = pkg(tmp_path / "ros1" / "legacy", "legacy")
    r = Resolver(environ={"AMENT_PREFIX_PATH": str(prefix), "ROS_PACKAGE_PATH": str(tmp_path / "ros1")})
    assert r.find("arm") == prefix / "share" / "arm"
    assert r.find("legacy") == ros
    assert r.find("missing") is None


def test_reads_are_confined_to_the_roots(tmp_path):
    root = pkg(tmp_path / "ws" / "demo", "demo")
    r = Resolver(near=root / "r.urdf")
    assert r.allowed(root / "urdf" / "x.xacro")
    assert not r.allowed("/etc/passwd")
    assert not r.allowed(root / ".." / ".." / ".." / "secret")


def test_install_layout_path_falls_back_to_the_source_layout(tmp_path):
    root = pkg(tmp_path / "ws" / "demo", "demo")
    (root / "description" / "urdf").mkdir(parents=True)
    (root / "description" / "urdf" / "parts.xacro").write_text("<robot/>")
    r = Resolver(near=root)
    base = r.find("demo")
    assert r.source_layout(base / "urdf" / "parts.xacro") == root / "description" / "urdf" / "parts.xacro"
    path, problem = r.resolve_uri("package://demo/urdf/parts.xacro", root)
    assert problem is None and path.exists()


def test_source_layout_two_down_unique_and_literal(tmp_path):
    from urdfcheck.core import walk

    root = pkg(tmp_path / "ws" / "demo", "demo")
    deep = root / "src" / "description" / "meshes"
    deep.mkdir(parents=True)
    (deep / "[ab].dae").write_text("x")  # a name, not a pattern: "a.dae" would match the pattern
    (root / "src" / "description" / "meshes" / "a.dae").write_text("x")
    r = Resolver(near=root)
    base = r.find("demo")
    assert r.source_layout(base / "meshes" / "[ab].dae") == deep / "[ab].dae"
    assert r.source_layout(base / "meshes" / "b.dae") is None
    with walk.remembered():  # a run: its folders are listed once
        assert r.source_layout(base / "meshes" / "a.dae") == deep / "a.dae"
        (root / "other" / "meshes").mkdir(parents=True)
        (root / "other" / "meshes" / "a.dae").write_text("x")
        assert r.source_layout(base / "meshes" / "a.dae") == deep / "a.dae"  # the run does not list again
    assert r.source_layout(base / "meshes" / "a.dae") == root / "other" / "meshes" / "a.dae"  # one down first
    (root / "more" / "meshes").mkdir(parents=True)
    (root / "more" / "meshes" / "a.dae").write_text("x")
    assert r.source_layout(base / "meshes" / "a.dae") is None  # two one down: ambiguous


def test_source_layout_lists_each_folder_once_a_run(tmp_path, monkeypatch):
    from urdfcheck.core import walk

    root = pkg(tmp_path / "ws" / "demo", "demo")
    for d in ("a", "b", "c"):
        (root / d / "x").mkdir(parents=True)
    r = Resolver(near=root)
    base = r.find("demo")
    listed = []
    real = os.scandir
    monkeypatch.setattr(os, "scandir", lambda p=".": listed.append(os.fspath(p)) or real(p))
    with walk.remembered():
        for i in range(20):
            assert r.source_layout(base / "meshes" / f"m{i}.stl") is None
        assert len(listed) == len(set(listed)) == 4  # the root and its 3 folders, once each
        walk.forget()  # a forked worker whose reads are recorded lists again
        assert r.source_layout(base / "meshes" / "m.stl") is None and len(listed) == 8


def test_confinement_and_layout_with_a_workspace_map(tmp_path):
    """With many roots (a workspace map) a path is looked up by its ancestors: the same answers as one by one."""
    from urdfcheck.core import walk

    roots = {f"p{i}": pkg(tmp_path / "ws" / f"p{i}", f"p{i}") for i in range(12)}
    (tmp_path / "ws" / "p1x").mkdir()  # a sibling whose name starts like a root's
    (roots["p7"] / "description" / "meshes").mkdir(parents=True)
    (roots["p7"] / "description" / "meshes" / "m.stl").write_text("solid")
    r = Resolver({k: str(v) for k, v in roots.items()})  # no near: the roots are the map alone
    for run in (False, True):
        with walk.remembered() if run else open(os.devnull):
            assert r.allowed(roots["p3"] / "urdf" / "x.xacro") and r.allowed(roots["p3"])
            assert not r.allowed(tmp_path / "ws" / "p1x" / "x.xacro")
            assert not r.allowed(tmp_path / "elsewhere.urdf") and not r.allowed("/")
            assert r.source_layout(roots["p7"] / "meshes" / "m.stl") == roots["p7"] / "description" / "meshes" / "m.stl"
            assert r.source_layout(roots["p6"] / "meshes" / "m.stl") is None


def test_the_source_layout_never_looks_outside_the_package(tmp_path, monkeypatch):
    """`$(find P)/../x` is the model's own text: the fallback joins it to folders inside P, and a name that climbs
    out is not looked up at all (before, `P/*/../../x` was probed beside P)."""
    from urdfcheck.load.packages import layout_hits

    root = pkg(tmp_path / "ws" / "demo", "demo")
    (root / "a").mkdir()
    (tmp_path / "ws" / "secret.xacro").write_text("<robot/>")
    looked = []
    real = os.path.isfile
    monkeypatch.setattr(os.path, "isfile", lambda p: looked.append(os.fspath(p)) or real(p))
    for rel in ("../secret.xacro", "../../ws/secret.xacro", "x/../../secret.xacro", str(tmp_path / "ws" / "s.xacro")):
        assert layout_hits(str(root), rel) == []
    assert not [p for p in looked if not os.path.normpath(p).startswith(str(root) + os.sep)], looked
    (root / "a" / "urdf").mkdir()
    (root / "a" / "urdf" / "x.xacro").write_text("<robot/>")
    assert layout_hits(str(root), "urdf/../urdf/x.xacro") == [str(root / "a" / "urdf" / "x.xacro")]


def test_the_enclosing_package_is_found_without_a_workspace_scan(tmp_path, monkeypatch):
    import urdfcheck.load.packages as packages

    mine = pkg(tmp_path / "ws" / "mine", "mine")
    sibling = pkg(tmp_path / "ws" / "sibling", "sibling")
    scans = []
    real_scan = packages.scan
    monkeypatch.setattr(packages, "scan", lambda *a, **kw: scans.append(a) or real_scan(*a, **kw))
    r = Resolver(near=mine / "urdf" / "robot.urdf.xacro")
    assert r.find("mine") == mine.resolve() and scans == []
    assert r.find("sibling") == sibling.resolve() and len(scans) == 1  # anything else still scans, once
    assert r.find("mine") == mine.resolve() and len(scans) == 1


def test_the_environment_still_wins_over_the_enclosing_package(tmp_path):
    mine = pkg(tmp_path / "ws" / "mine", "mine")
    ros = pkg(tmp_path / "ros1" / "mine", "mine")
    r = Resolver(near=mine / "r.urdf", environ={"ROS_PACKAGE_PATH": str(tmp_path / "ros1")})
    assert r.find("mine") == ros


def test_a_package_xml_linked_out_of_the_scanned_folder_is_not_listed(tmp_path):
    """The scans read only package.xml files that really lie below the folder scanned: a linked package.xml
    leading out of it is not listed (one leading to a file inside is), and a linked folder is never entered.
    Regular files are not resolved one by one (the walk never enters a linked folder), links are."""
    from urdfcheck.load.packages import scan, workspace_packages

    def package(folder, name):
        folder.mkdir(parents=True)
        (folder / "package.xml").write_text(f"<package><name>{name}</name></package>")
        return folder

    ws, outside = tmp_path / "ws", tmp_path / "outside"
    package(ws / "real_pkg", "real_pkg")
    package(outside / "far", "far_pkg")
    (ws / "linked_file").mkdir()
    os.symlink(outside / "far" / "package.xml", ws / "linked_file" / "package.xml")
    (ws / "linked_inside").mkdir()
    os.symlink(ws / "real_pkg" / "package.xml", ws / "linked_inside" / "package.xml")
    os.symlink(outside / "far", ws / "linked_folder")
    assert sorted(scan(ws)) == ["real_pkg"]
    assert scan(ws)["real_pkg"] in (ws / "real_pkg", ws / "linked_inside")
    assert workspace_packages(ws) == {"real_pkg": [ws / "real_pkg"]}  # a linked package.xml is not a package
