"""A workspace is what the user names: every package.xml below it, at any depth, resolves $(find) and
package:// first; unresolved packages are listed together; $(optenv) gives its default in the sandbox;
macro files are libraries."""
import os
from pathlib import Path

from urdfcheck.contracts.discover import discover
from urdfcheck.load import loader
from urdfcheck.load.packages import Resolver, missing_packages, workspace_map, workspace_packages

XACRO = 'xmlns:xacro="http://www.ros.org/wiki/xacro"'


def pkg(folder: Path, name: str) -> Path:
    folder.mkdir(parents=True, exist_ok=True)
    (folder / "package.xml").write_text(f"<package format='3'><name>{name}</name></package>")
    return folder


def write(path: Path, text: str) -> Path:
    path.parent.mkdir(parents=True, exist_ok=True)
    path.write_text(text)
    return path


def two_repositories(tmp_path: Path) -> tuple[Path, Path]:
    """robot_description (repo a) includes a macro from base_description, which lives in another
    repository beside it, several folders deep."""
    deep = pkg(tmp_path / "b_repo" / "common" / "group" / "more" / "deeper" / "still" / "base_description",
               "base_description")
    write(deep / "urdf" / "base.xacro",
          f'<robot {XACRO}><xacro:macro name="base"><link name="base_link"/></xacro:macro></robot>')
    desc = pkg(tmp_path / "a_repo" / "robot_description", "robot_description")
    entry = write(desc / "urdf" / "robot.urdf.xacro",
                  f'<robot name="r" {XACRO}>\n'
                  '  <xacro:include filename="$(find base_description)/urdf/base.xacro"/>\n'
                  '  <xacro:base/>\n</robot>\n')
    return deep, entry


def test_packages_at_any_depth_are_found(tmp_path):
    deep, _ = two_repositories(tmp_path)
    assert len(deep.relative_to(tmp_path).parts) > 6  # deeper than the enclosing-workspace scan goes
    found = workspace_packages(tmp_path)
    assert found["base_description"] == [deep]
    assert set(found) == {"base_description", "robot_description"}


def test_a_duplicate_name_resolves_to_the_copy_nearest_the_model(tmp_path):
    a = pkg(tmp_path / "a" / "common", "common")
    b = pkg(tmp_path / "b" / "common", "common")
    assert workspace_map(tmp_path, near=tmp_path / "a" / "robot" / "x.xacro")["common"] == str(a)
    assert workspace_map(tmp_path, near=tmp_path / "b" / "robot" / "x.xacro")["common"] == str(b)


def test_a_sibling_repository_resolves_through_the_named_workspace(tmp_path):
    deep, entry = two_repositories(tmp_path)
    assert Resolver(near=entry).find("base_description") is None  # the repository alone does not see it
    assert Resolver(near=entry, workspace=tmp_path).find("base_description") == deep
    exp = loader.expand(entry, packages=workspace_map(tmp_path, near=entry))
    assert exp.root is not None, exp.findings
    assert [el.get("name") for el in exp.root.iter("link")] == ["base_link"]


def test_every_unresolved_package_is_listed_once_with_its_places(tmp_path):
    desc = pkg(tmp_path / "robot_description", "robot_description")
    write(desc / "urdf" / "parts.xacro",
          f'<robot {XACRO}>\n<xacro:include filename="$(find gone_a)/a.xacro"/>\n'
          '<mesh filename="package://gone_b/m.stl"/>\n</robot>\n')
    entry = write(desc / "urdf" / "robot.urdf.xacro",
                  f'<robot name="r" {XACRO}>\n'
                  '  <xacro:include filename="$(find robot_description)/urdf/parts.xacro"/>\n'
                  '  <xacro:include filename="$(find gone_a)/b.xacro"/>\n</robot>\n')
    r = Resolver(near=entry)
    missing = missing_packages([entry], r.find)
    assert list(missing) == ["gone_a", "gone_b"]
    assert missing["gone_a"] == [(str(entry), 3), (str(desc / "urdf" / "parts.xacro"), 2)]
    assert missing["gone_b"] == [(str(desc / "urdf" / "parts.xacro"), 3)]


def test_optenv_is_its_default_and_env_stays_refused(tmp_path, monkeypatch):
    monkeypatch.setenv("UC_TEST_SECRET", "leaked")
    f = write(tmp_path / "r.urdf.xacro",
              f'<robot name="r" {XACRO}>\n<link name="$(optenv UC_TEST_SECRET fallback)"/>\n'
              '<link name="b$(optenv UC_TEST_SECRET)"/>\n</robot>\n')
    exp = loader.expand(f)
    assert [el.get("name") for el in exp.root.iter("link")] == ["fallback", "b"]
    exp = loader.expand(f, allow_env=("UC_TEST_SECRET",))
    assert [el.get("name") for el in exp.root.iter("link")] == ["leaked", "bleaked"]
    g = write(tmp_path / "e.urdf.xacro", f'<robot name="r" {XACRO}>\n<link name="$(env UC_TEST_SECRET)"/>\n</robot>\n')
    exp = loader.expand(g)
    assert [x.code for x in exp.findings] == ["X015"] and "leaked" not in exp.findings[0].message


def test_macro_and_property_files_are_libraries(tmp_path):
    p = pkg(tmp_path / "d", "d")
    write(p / "urdf" / "props.xacro", f'<robot {XACRO}><xacro:property name="r" value="1"/></robot>')
    write(p / "urdf" / "cond.xacro", f'<robot {XACRO}><xacro:arg name="a" default="1"/><xacro:if value="1">'
                                     '<xacro:macro name="m"><link name="l"/></xacro:macro></xacro:if></robot>')
    write(p / "urdf" / "body.xacro", f'<robot name="b" {XACRO}><link name="base_link"/></robot>')
    write(p / "urdf" / "only_includes.urdf.xacro",
          f'<robot name="x" {XACRO}><xacro:include filename="$(find other)/urdf/body.xacro"/></robot>')
    found = discover(p)
    names = lambda xs: sorted(os.path.basename(x) for x in xs)  # noqa: E731
    assert names(found.models) == ["only_includes.urdf.xacro"]  # its include brings a robot body
    assert names(found.libraries) == ["body.xacro", "cond.xacro", "props.xacro"]  # body.xacro: included


def test_the_working_directory_is_the_workspace_of_last_resort(tmp_path, monkeypatch):
    deep, entry = two_repositories(tmp_path)
    monkeypatch.chdir(tmp_path / "a_repo")  # the sibling repository is not below the working directory
    assert Resolver(near=entry).find("base_description") is None
    monkeypatch.chdir(tmp_path)  # `urdfcheck lint` run from the workspace root
    assert Resolver(near=entry).find("base_description") == deep
    exp = loader.expand(entry)
    assert exp.root is not None and not exp.findings
