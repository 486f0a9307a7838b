"""Package resolution without ROS: explicit map, ament index, ROS_PACKAGE_PATH, workspace scan."""
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
