"""A workspace is what the user names: every package.xml below it, at any depth, resolves $(find) and
package:// first; unresolved packages are listed together; $(optenv) gives its default in the sandbox;
macro files are libraries."""
import os
from pathlib import Path

from urdfcheck.load import loader
from urdfcheck.load.discover import discover
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
    # its include may bring a robot body: a probe, which the expansion makes a robot (a file of includes only may
    # also be a library of libraries, uuv_simulator's snippets.xacro: issue 37)
    assert names(found.models) == [] and names(found.probes) == ["only_includes.urdf.xacro"]
    assert names(found.libraries) == ["body.xacro", "cond.xacro", "only_includes.urdf.xacro", "props.xacro"]


def test_the_working_directory_is_the_workspace_of_last_resort(tmp_path, monkeypatch):
    deep, entry = two_repositories(tmp_path)
    monkeypatch.chdir(tmp_path / "a_repo")  # the sibling repository is not below the working directory
    assert Resolver(near=entry).find("base_description") is None
    monkeypatch.chdir(tmp_path)  # `urdfcheck lint` run from the workspace root
    assert Resolver(near=entry).find("base_description") == deep
    exp = loader.expand(entry)
    assert exp.root is not None and not exp.findings


# --- planning a named folder (issue 13): deployments once per named root -----------------------------------
NAMED_ROBOT = f"""<?xml version="1.0"?>
<robot name="$(arg name)" {XACRO}>
  <xacro:arg name="name" default="bot"/>
  <xacro:include filename="$(find arm_description)/urdf/parts.xacro"/>
  <xacro:parts/>
</robot>
"""  # like ur.urdf.xacro: `$(arg name)` before its declaration; `xacro robot.urdf.xacro` alone fails

PARTS = f"""<robot {XACRO}>
  <xacro:macro name="parts">
    <link name="base_link"/>
    <link name="tool"/>
    <joint name="j1" type="revolute"><parent link="base_link"/><child link="tool"/><axis xyz="0 0 1"/>
      <limit lower="-1" upper="1" effort="1" velocity="1"/></joint>
  </xacro:macro>
</robot>
"""

ARM_LAUNCH = """
from launch import LaunchDescription
from launch.substitutions import Command, PathJoinSubstitution
from launch_ros.actions import Node
from launch_ros.substitutions import FindPackageShare


def generate_launch_description():
    xacro_file = PathJoinSubstitution([FindPackageShare('arm_description'), 'urdf', 'robot.urdf.xacro'])
    description = {'robot_description': Command(['xacro ', xacro_file, ' name:=arm'])}
    return LaunchDescription([
        Node(package='robot_state_publisher', executable='robot_state_publisher', parameters=[description]),
        Node(package='controller_manager', executable='spawner', arguments=['joint_state_broadcaster']),
    ])
"""


def arm_workspace(tmp_path: Path) -> Path:
    """src/arm_description (the model, a macro library) and src/arm_bringup (the launch file passing name)."""
    d = pkg(tmp_path / "src" / "arm_description", "arm_description")
    write(d / "urdf" / "robot.urdf.xacro", NAMED_ROBOT)
    write(d / "urdf" / "parts.xacro", PARTS)
    b = pkg(tmp_path / "src" / "arm_bringup", "arm_bringup")
    write(b / "launch" / "arm.launch.py", ARM_LAUNCH)
    return tmp_path / "src"


def _plan(paths, here=None):
    from urdfcheck.plan.plan import plan
    from urdfcheck.request.request import make_request

    return plan(make_request([str(p) for p in paths]), here=str(here) if here else None)


def test_a_model_another_package_deploys_is_linted_through_that_deployment_only(tmp_path, monkeypatch):
    from urdfcheck.request.request import make_request
    from urdfcheck.run import run

    src = arm_workspace(tmp_path)
    monkeypatch.chdir(tmp_path)
    targets = _plan([src])
    robot = os.path.realpath(src / "arm_description" / "urdf" / "robot.urdf.xacro")
    mine = [t for t in targets if os.path.realpath(t.path) == robot]
    assert mine and all(t.deployment is not None for t in mine)  # never alone with its defaults
    assert [t.args for t in mine] == [{"name": "arm"}]
    assert mine[0].variant == "src/arm_bringup/launch/arm.launch.py"
    result = run(make_request([str(src)]))
    codes = [f.code for f in result.findings]
    assert "X010" not in codes and "S011" not in codes, result.findings
    assert all(f.variant.endswith("arm.launch.py") for f in result.findings)  # each names its launch file
    # the documented exception to "a run from above = the union of per-package runs": from inside its own
    # package the model has no deployment, so it is linted alone (and fails as `xacro` does)
    alone = run(make_request([str(src / "arm_description")]))
    assert "X010" in [f.code for f in alone.findings]


def test_the_text_report_names_the_launch_file_once(tmp_path, monkeypatch, capsys):
    from urdfcheck.cli import main as cli

    src = arm_workspace(tmp_path)
    write(src / "arm_description" / "urdf" / "parts.xacro", PARTS.replace('<link name="tool"/>', '<link name="tool"/>\n'
                                                                         '    <link name="stray"/>'))
    monkeypatch.chdir(tmp_path)
    assert cli.main(["lint", "src"]) == 1
    out = capsys.readouterr().out
    lines = [ln for ln in out.splitlines() if "stray" in ln]
    assert lines and all(ln.count("arm.launch.py") == 1 for ln in lines), out
    assert "in 1 model (1 from launch-file deployment)." in out  # the summary says where the model came from


def test_a_package_config_still_applies_to_its_package(tmp_path, monkeypatch):
    src = arm_workspace(tmp_path)
    other = pkg(src / "other_description", "other_description")
    write(other / "urdf" / "o.urdf", '<robot name="o"><link name="base_link"/></robot>')
    write(other / "urdfcheck.yaml", "ignore: [F002]\n")
    monkeypatch.chdir(tmp_path)
    targets = _plan([src])
    cfg = {os.path.basename(str(t.path)): getattr(t.settings.config, "path", None) for t in targets}
    assert cfg["o.urdf"] == str(other / "urdfcheck.yaml")
    assert cfg["robot.urdf.xacro"] is None
    assert any(t.deployment is not None for t in targets)


def test_a_package_of_xacro_libraries_only_is_an_info_line_and_exit_0(tmp_path, monkeypatch, capsys):
    from urdfcheck.cli import main as cli

    lib = pkg(tmp_path / "components", "components")
    write(lib / "urdf" / "sensor.urdf.xacro", f'<robot {XACRO}><xacro:macro name="sensor" params="parent">'
                                                f'<link name="s"/></xacro:macro></robot>')
    write(lib / "urdf" / "props.xacro", f'<robot {XACRO}><xacro:property name="r" value="1"/></robot>')
    monkeypatch.chdir(tmp_path)
    assert cli.main(["lint", "components"]) == 0
    captured = capsys.readouterr()
    assert "xacro libraries only" in captured.err and "S011" not in captured.out
    assert cli.main(["lint", "--list", "components"]) == 0
    (tmp_path / "nothing_here").mkdir()
    assert cli.main(["lint", "nothing_here"]) == 2  # an empty folder is still "no model found"


def test_the_per_file_hook_given_a_library_lints_the_robots_that_include_it(tmp_path, monkeypatch):
    src = arm_workspace(tmp_path)
    other = pkg(src / "other_description", "other_description")
    write(other / "urdf" / "o.urdf", '<robot name="o"><link name="base_link"/></robot>')
    (tmp_path / ".git").mkdir()  # a repository: its packages are one checkout (core.checkout)
    monkeypatch.chdir(tmp_path)  # pre-commit runs the hook from the repository root, with file names
    targets = _plan([src / "arm_description" / "urdf" / "parts.xacro"], here=tmp_path)
    assert [os.path.basename(str(t.path)) for t in targets] == ["robot.urdf.xacro"]
    assert targets[0].deployment is not None and targets[0].args == {"name": "arm"}  # through its deployment
    unused = write(src / "arm_description" / "urdf" / "unused.xacro",
                   f'<robot {XACRO}><xacro:macro name="u"><link name="u"/></xacro:macro></robot>')
    got = _plan([unused], here=tmp_path)
    assert list(got) == [] and any("not linted alone" in i for i in got.infos)


def test_each_missing_package_is_one_finding_with_every_place(tmp_path, monkeypatch):
    from urdfcheck.request.request import make_request
    from urdfcheck.run import run

    d = pkg(tmp_path / "desc", "desc")
    write(d / "urdf" / "parts.xacro", f'<robot {XACRO}>\n<xacro:include filename="$(find gone_a)/a.xacro"/>\n'
                                      '<xacro:include filename="$(find gone_b)/b.xacro"/>\n</robot>\n')
    for name in ("one", "two"):
        write(d / "urdf" / f"{name}.urdf.xacro",
              f'<robot name="{name}" {XACRO}>\n<xacro:arg name="fast" default="false"/>\n'
              '<xacro:include filename="$(find gone_a)/x.xacro"/>\n'
              '<xacro:include filename="$(find desc)/urdf/parts.xacro"/>\n<link name="base_link"/>\n</robot>\n')
    monkeypatch.chdir(tmp_path)
    result = run(make_request(["desc"]))
    x013 = [f for f in result.findings if f.code == "X013"]
    assert sorted(f.message.split("'")[1] for f in x013) == ["gone_a", "gone_b"]  # gone_b too, in one run
    a = next(f for f in x013 if "'gone_a'" in f.message)
    places = [(a.location.file, a.location.line)] + [(r.file, r.line) for r in a.related]
    assert {(os.path.basename(f), ln) for f, ln in places} == {("one.urdf.xacro", 3), ("two.urdf.xacro", 3),
                                                               ("parts.xacro", 2)}


def test_srdf_files_are_never_models(tmp_path):
    d = pkg(tmp_path / "moveit_config", "moveit_config")
    write(d / "config" / "arm.srdf", '<robot name="a"><group name="arm"><chain base_link="a" tip_link="b"/></group>'
                                     '</robot>')
    write(d / "config" / "arm.srdf.xacro", f'<robot name="a" {XACRO}><group name="arm"/></robot>')
    write(d / "config" / "semantic.xacro", f'<robot name="a" {XACRO}><group name="arm"><joint name="j"/></group>'
                                           '<disable_collisions link1="a" link2="b" reason="Adjacent"/></robot>')
    write(d / "config" / "groups_only.xacro", f'<robot name="a" {XACRO}><group name="arm"/></robot>')
    write(d / "config" / "groups_and_include.xacro",  # groups, an include (of more groups), no <link>
          f'<robot name="a" {XACRO}><xacro:include filename="$(find moveit_config)/config/more.xacro"/>'
          '<group name="arm"><joint name="j"/></group></robot>')
    write(d / "urdf" / "robot.urdf", '<robot name="r"><link name="base_link"/></robot>')
    assert [os.path.basename(m) for m in discover(d).models] == ["robot.urdf"]
    # named (the per-file hook passes SRDF files): never a model; it stands for its package's robots (those that
    # may be robots are expanded to tell: probes)
    whole = sorted(os.path.basename(str(t.path)) for t in _plan([d]))
    assert "robot.urdf" in whole and "arm.srdf" not in whole and "arm.srdf.xacro" not in whole
    for name in ("arm.srdf.xacro", "arm.srdf"):
        got = _plan([d / "config" / name])
        assert sorted(os.path.basename(str(t.path)) for t in got) == whole, name


def test_several_models_agrees_with_discover_on_every_corpus_package(corpus):
    """Consumer discovery asks only whether a package holds several models; its short cut (two .urdf files
    with links) must answer what the full discovery answers, with the same parameter and launch files."""
    from urdfcheck.load.discover import discover, several_models

    roots = sorted({p.parent for p in corpus.rglob("package.xml")})
    assert roots
    for root in roots:
        found = discover(root)
        assert several_models(root) == (len(found.models) > 1, found.params, found.launch), root
