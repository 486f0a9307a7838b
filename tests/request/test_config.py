"""urdfcheck.yaml / .urdfcheck.yaml / [tool.urdfcheck]: finding, validating, resolving, targets."""
import sys
from pathlib import Path

SRC = Path(__file__).resolve().parents[2] / "src"
if str(SRC) not in sys.path:  # runnable without an editable install
    sys.path.insert(0, str(SRC))

import pytest  # noqa: E402

from urdfcheck.core.findings import Severity  # noqa: E402
from urdfcheck.request.config import ConfigError, auto_variants, boolean_args, find_config, load_config  # noqa: E402

URDF = '<robot name="r"><link name="base_link"/></robot>\n'
XACRO = """<robot name="r" xmlns:xacro="http://www.ros.org/wiki/xacro">
  <xacro:arg name="use_camera" default="true"/>
  <xacro:arg name="use_lidar" default="false"/>
  <xacro:arg name="name" default="agv"/>
  <!-- <xacro:arg name="commented" default="true"/> -->
  <link name="base_link"/>
</robot>
"""


def make_pkg(root: Path) -> Path:
    (root / "urdf").mkdir(parents=True, exist_ok=True)
    (root / "config").mkdir(exist_ok=True)
    (root / "launch").mkdir(exist_ok=True)
    (root / "urdf" / "agv.urdf.xacro").write_text(XACRO)
    (root / "urdf" / "plain.urdf").write_text(URDF)
    (root / "config" / "ctrl.yaml").write_text("a: 1\n")
    (root / "config" / "drv.yaml").write_text("wheel_radius: 0.1\n")
    (root / "launch" / "bringup.launch.xml").write_text("<launch/>\n")
    return root


FULL = """\
models:
  - path: urdf/agv.urdf.xacro
    args: {name: agv}
    variants: {camera: {use_camera: "true"}, no_camera: {use_camera: false}}
    controllers: [config/ctrl.yaml]
    drivers:
      - file: config/drv.yaml
        node: ""
        joints: [left_wheel_joint, right_wheel_joint]
        wheel_separation: wheel_separation
        wheel_radius: wheel_radius
        left_wheels: left_wheel_joint
        right_wheels: [right_wheel_joint]
        frames: [imu_frame_id]
        odom_tf: publish_odom_tf
    launch: [launch/bringup.launch.xml]
    localization: []
    frame_prefix: ""
frames: {map: map, odom: odom, base: base_footprint}
tf_owners: {"map->odom": amcl}
packages: {agv_description: .}
select: [ALL]
ignore: [I005, G0]
fail_on: error
severity: {F002: warning, J: info}
rules: {C010: {tolerance: 0.002}, F002: {expected: [base_link, base_footprint]}}
trusted: false
allow_env: [HOME]
max_elements: 5000
"""


def test_full_config(tmp_path):
    root = make_pkg(tmp_path / "agv")
    (root / "urdfcheck.yaml").write_text(FULL)
    cfg = load_config(root / "urdfcheck.yaml", trusted=True)  # the runner vouches for it: every key counts
    (m,) = cfg.models
    assert m.path == str(root / "urdf" / "agv.urdf.xacro")
    assert m.controllers == (str(root / "config" / "ctrl.yaml"),)
    assert m.launch == (str(root / "launch" / "bringup.launch.xml"),)
    assert dict(m.args) == {"name": "agv"}
    assert {k: dict(v) for k, v in m.variants.items()} == {"camera": {"use_camera": "true"},
                                                           "no_camera": {"use_camera": "false"}}
    assert m.variant_args() == [("camera", {"name": "agv", "use_camera": "true"}),
                                ("no_camera", {"name": "agv", "use_camera": "false"})]
    (d,) = m.drivers
    assert d.file == str(root / "config" / "drv.yaml") and d.left_wheels == ("left_wheel_joint",)
    assert d.loc.file == str(root / "urdfcheck.yaml") and d.loc.line == 7
    assert d.wheel_radius == "wheel_radius" and d.frames == ("imu_frame_id",)
    assert dict(cfg.frames) == {"map": "map", "odom": "odom", "base": "base_footprint"}
    assert dict(cfg.tf_owners) == {"map->odom": "amcl"} and cfg.tf_owner_locs["map->odom"].line == 20
    assert dict(cfg.packages) == {"agv_description": str(root)}
    assert cfg.select == ("ALL",) and cfg.ignore == ("I005", "G0") and cfg.fail_on == Severity.ERROR
    assert dict(cfg.severity) == {"F002": Severity.WARNING, "J": Severity.INFO}
    assert dict(cfg.rules["C010"]) == {"tolerance": 0.002}
    assert cfg.allow_env == ("HOME",) and cfg.notes == () and cfg.vouched
    assert cfg.loc("models", 0, "path").line == 2
    with pytest.raises(AttributeError):
        cfg.trusted = True
    with pytest.raises(TypeError):
        cfg.rules["C010"]["tolerance"] = 1


def test_full_config_found_in_the_checkout_adds_never_hides(tmp_path):
    """Issue 19 and 36: allow_env is the runner's to give, a lower limit stays; what lowers the gate is an X018
    error at its key and ignored (ignore; fail_on: error; J down to info; a C010 tolerance above the default; a
    renamed REP-105 frame),
    what tightens stays (F002 up to warning, fewer accepted F002 names); args replacing defaults add the
    defaults variant (tests/request/test_gate.py)."""
    root = make_pkg(tmp_path / "agv")
    (root / "urdfcheck.yaml").write_text(FULL)
    cfg = load_config(root / "urdfcheck.yaml")
    assert cfg.allow_env == () and cfg.trusted is False and cfg.max_elements == 5000 and not cfg.vouched
    assert cfg.select == ("ALL",) and cfg.ignore == () and cfg.fail_on is None
    assert dict(cfg.severity) == {"F002": Severity.WARNING}
    assert "C010" not in cfg.rules and dict(cfg.rules["F002"]) == {"expected": ["base_link", "base_footprint"]}
    notes = [(f.code, f.severity, f.location.line) for f in cfg.notes]
    assert notes == [("X018", Severity.WARNING, 28), ("X018", Severity.ERROR, 23), ("X018", Severity.ERROR, 25),
                     ("X018", Severity.ERROR, 24), ("X018", Severity.ERROR, 26), ("X018", Severity.ERROR, 19)]
    assert dict(cfg.frames) == {"map": "map", "odom": "odom", "base": "base_link"}  # base_footprint: refused
    # name: agv and the camera variant are the xacro defaults: no variant is added
    assert [n for n, _ in cfg.models[0].variant_args()] == ["camera", "no_camera"]


def test_defaults(tmp_path):
    (tmp_path / "urdfcheck.yaml").write_text("")
    cfg = load_config(tmp_path / "urdfcheck.yaml")
    assert cfg.models == () and cfg.select is None and cfg.fail_on is None
    assert dict(cfg.frames) == {"map": "map", "odom": "odom", "base": "base_link"}


# --- finding ---------------------------------------------------------------------------------------------------
def test_find_upward_and_precedence(tmp_path):
    deep = tmp_path / "a" / "b" / "c"
    deep.mkdir(parents=True)
    assert find_config(deep) is None or not str(find_config(deep)).startswith(str(tmp_path))
    (tmp_path / "pyproject.toml").write_text("[project]\nname = 'x'\n")  # no [tool.urdfcheck]: skipped
    assert find_config(deep) is None or not str(find_config(deep)).startswith(str(tmp_path))
    (tmp_path / "a" / "pyproject.toml").write_text("[tool.urdfcheck]\nfail_on = 'error'\n")
    assert find_config(deep) == str(tmp_path / "a" / "pyproject.toml")
    (tmp_path / "a" / ".urdfcheck.yaml").write_text("")
    assert find_config(deep) == str(tmp_path / "a" / ".urdfcheck.yaml")
    (tmp_path / "a" / "urdfcheck.yaml").write_text("")
    assert find_config(deep) == str(tmp_path / "a" / "urdfcheck.yaml")
    (tmp_path / "a" / "b" / ".urdfcheck.yaml").write_text("")
    assert find_config(deep) == str(tmp_path / "a" / "b" / ".urdfcheck.yaml")  # nearest wins
    f = deep / "robot.urdf"
    f.write_text(URDF)
    assert find_config(f) == str(tmp_path / "a" / "b" / ".urdfcheck.yaml")  # a file starts at its folder


def test_pyproject(tmp_path):
    make_pkg(tmp_path)
    (tmp_path / "pyproject.toml").write_text("""\
[project]
name = "x"

[tool.urdfcheck]
select = ["S", "J002"]
fail_on = "info"

[tool.urdfcheck.frames]
base = "base_footprint"

[[tool.urdfcheck.models]]
path = "urdf/plain.urdf"
controllers = ["config/ctrl.yaml"]
""")
    cfg = load_config(tmp_path / "pyproject.toml")
    # a select narrower than ALL is the runner's to give (issue 36): refused at its line; fail_on info tightens
    assert cfg.select is None and cfg.fail_on == Severity.INFO
    # so is renaming a REP-105 frame, said at its table
    assert [(f.code, f.severity, f.location.line) for f in cfg.notes] == [("X018", Severity.ERROR, 5),
                                                                           ("X018", Severity.ERROR, 8)]
    trusted = load_config(tmp_path / "pyproject.toml", trusted=True)
    assert trusted.select == ("S", "J002") and trusted.frames["base"] == "base_footprint"
    assert cfg.frames["base"] == "base_link"
    assert cfg.models[0].path == str(tmp_path / "urdf" / "plain.urdf")


def test_pyproject_errors_name_the_line(tmp_path):
    (tmp_path / "pyproject.toml").write_text('[project]\nname = "x"\n\n'
                                             '[tool.urdfcheck]\nselect = ["S"]\nfail_on = "sometimes"\n')
    with pytest.raises(ConfigError) as e:
        load_config(tmp_path / "pyproject.toml")
    assert "fail_on" in str(e.value) and e.value.location.line == 6
    (tmp_path / "pyproject.toml").write_text('[tool.urdfcheck]\nselect = [\n')
    with pytest.raises(ConfigError, match="TOML"):
        load_config(tmp_path / "pyproject.toml")


# --- validation: errors name the key and its line ----------------------------------------------------------------
@pytest.mark.parametrize("text,key,line", [
    ("select: [ALL]\nfial_on: error\n", "fial_on", 2),
    ("fail_on: sometimes\n", "fail_on", 1),
    ("select: [S001, bad]\n", "select.1", 1),
    ("severity:\n  S001: loud\n", "severity.S001", 2),
    ("severity:\n  nope: error\n", "severity.nope", 2),
    ("rules:\n  C010: 0.002\n", "rules.C010", 2),
    ("models:\n  - path: urdf/plain.urdf\n    controlers: [config/ctrl.yaml]\n", "models.0.controlers", 3),
    ("models:\n  - path: urdf/missing.urdf\n", "models.0.path", 2),
    ("models:\n  - path: urdf/plain.urdf\n    controllers: [config/nope.yaml]\n", "models.0.controllers.0", 3),
    ("models:\n  - path: urdf/plain.urdf\n    drivers:\n      - {node: x}\n", "models.0.drivers.0", 4),
    ("models:\n  - path: urdf/plain.urdf\n    variants: sometimes\n", "models.0.variants", 3),
    ("tf_owners: {map_odom: amcl}\n", "tf_owners.map_odom", 1),
    ("packages: {p: ./nowhere}\n", "packages.p", 1),
    ("trusted: yes please\n", "trusted", 1),
    ("frames: {base: base_link, world: map}\n", "frames.world", 1),
])
def test_errors_name_key_and_line(tmp_path, text, key, line):
    make_pkg(tmp_path)
    (tmp_path / "urdfcheck.yaml").write_text(text)
    with pytest.raises(ConfigError) as e:
        load_config(tmp_path / "urdfcheck.yaml")
    assert key in str(e.value), str(e.value)
    assert e.value.location.file == str(tmp_path / "urdfcheck.yaml")
    assert e.value.location.line == line, (str(e.value), e.value.location)


def test_unknown_key_suggests(tmp_path):
    (tmp_path / "urdfcheck.yaml").write_text("ignroe: [I005]\n")
    with pytest.raises(ConfigError, match="did you mean 'ignore'"):
        load_config(tmp_path / "urdfcheck.yaml")


def test_bad_yaml_and_bombs(tmp_path):
    (tmp_path / "urdfcheck.yaml").write_text("select: [S\nignore: []\n")
    with pytest.raises(ConfigError) as e:
        load_config(tmp_path / "urdfcheck.yaml")
    assert e.value.location.line is not None
    bomb = ['a: &a [x,x,x,x,x,x,x,x,x,x]'] + [
        f"{chr(98 + i)}: &{chr(98 + i)} [" + ",".join([f"*{chr(97 + i)}"] * 10) + "]" for i in range(7)]
    (tmp_path / "urdfcheck.yaml").write_text("\n".join(bomb) + "\n")
    with pytest.raises(ConfigError, match="bomb|alias"):
        load_config(tmp_path / "urdfcheck.yaml")
    (tmp_path / "urdfcheck.yaml").write_text("- a\n- b\n")
    with pytest.raises(ConfigError, match="mapping"):
        load_config(tmp_path / "urdfcheck.yaml")


# --- variants and targets --------------------------------------------------------------------------------------
def test_boolean_args_and_auto_variants(tmp_path):
    f = tmp_path / "r.urdf.xacro"
    f.write_text(XACRO)
    assert boolean_args(str(f)) == {"use_camera": "true", "use_lidar": "false"}
    names = [n for n, _ in auto_variants(str(f), {})]
    # named by what differs from the defaults (issue 15: short, readable labels)
    assert names == ["defaults", "use_lidar=true", "use_camera=false", "use_camera=false,use_lidar=true"]
    assert ([a for _, a in auto_variants(str(f), {"use_lidar": "true"})]
            == [{"use_camera": "true"}, {"use_camera": "false"}])
    many = "".join(f'<xacro:arg name="a{i}" default="false"/>' for i in range(6))
    g = tmp_path / "many.xacro"
    g.write_text(f'<robot xmlns:xacro="http://www.ros.org/wiki/xacro">{many}</robot>')
    got = [a for _, a in auto_variants(str(g), {})]  # beyond 4 arguments: the defaults, then pairwise
    assert got[0] == {} and len(got) < 2 ** 6
    assert all(any(a.get(f"a{i}") == "true" and a.get(f"a{j}") == "true" for a in got)
               for i in range(6) for j in range(i + 1, 6))


def test_targets(tmp_path):
    root = make_pkg(tmp_path / "agv")
    (root / "urdfcheck.yaml").write_text(
        "models:\n  - path: urdf/agv.urdf.xacro\n    variants: auto\n    args: {use_lidar: 'true'}\n"
        "    controllers: [config/ctrl.yaml]\npackages: {agv_description: .}\n")
    from urdfcheck.plan.plan import plan
    from urdfcheck.request.request import make_request

    cfg = str(root / "urdfcheck.yaml")
    # named by itself (no --trust-config) it adds (issue 36): the defaults of the arg it replaces, and the model
    # it does not declare
    ts = plan(make_request([], config=cfg), here=str(root))  # run in the package
    assert [(t.path.name, t.variant, t.args) for t in ts] == [
        ("agv.urdf.xacro", "defaults", {"use_lidar": "true", "use_camera": "true"}),
        ("agv.urdf.xacro", "use_camera=false", {"use_lidar": "true", "use_camera": "false"}),
        ("agv.urdf.xacro", "xacro defaults", {}), ("plain.urdf", "", {})]
    assert len(plan(make_request([str(root)], config=cfg))) == 4
    ts = plan(make_request([], config=cfg, trust_config=True))  # the runner vouches: its models are all
    assert [(t.variant, t.args) for t in ts] == [("defaults", {"use_lidar": "true", "use_camera": "true"}),
                                                 ("use_camera=false", {"use_lidar": "true", "use_camera": "false"})]
    assert ts[0].contracts is ts[1].contracts  # consumers are read once per model
    assert ts[0].contracts.files["controllers"] == [str(root / "config" / "ctrl.yaml")]
    assert ts[0].packages == {"agv_description": str(root)}
    over = plan(make_request([], config=cfg, args={"use_camera": "false"}, packages={"other": "/x"},
                             trust_config=True))
    assert all(t.args["use_camera"] == "false" for t in over) and over[0].packages["other"] == "/x"
    only = plan(make_request([str(root / "urdf" / "plain.urdf")], config=cfg))
    assert [t.path.name for t in only] == ["plain.urdf"] and only[0].contracts is None  # not configured: zero-config
    assert len(plan(make_request([str(root)], config=cfg, trust_config=True))) == 2


def test_cli_reports_the_bad_key(tmp_path):
    from conftest import run_cli

    make_pkg(tmp_path)
    (tmp_path / "urdfcheck.yaml").write_text("select: [ALL]\nfail_on: never\n")
    code, out, err = run_cli(["lint", "urdf/plain.urdf"], cwd=tmp_path)
    assert code == 2
    assert "fail_on" in err and "urdfcheck.yaml:2" in err


BOMB = """<robot name="r" xmlns:xacro="http://www.ros.org/wiki/xacro">
  <xacro:macro name="m" params="n">
    <link name="l${n}"/>
    <xacro:if value="${n > 0}"><xacro:m n="${n - 1}"/></xacro:if>
  </xacro:macro>
  <xacro:m n="40"/>
</robot>
"""


def test_max_elements_from_the_config_limits_expansion(tmp_path):
    from conftest import run_cli

    (tmp_path / "package.xml").write_text("<package><name>p</name></package>")
    (tmp_path / "r.urdf.xacro").write_text(BOMB)
    args = ["lint", "--select", "X", "--format", "json", "r.urdf.xacro"]
    code, out, err = run_cli(args, cwd=tmp_path)
    assert code == 0, out + err  # 41 links: well inside the default budget
    (tmp_path / "urdfcheck.yaml").write_text("max_elements: 50\n")
    code, out, err = run_cli(args, cwd=tmp_path)
    assert code == 1 and "X012" in out and "more than 50 elements" in out
    code, out, err = run_cli(args + ["--max-elements", "100000"], cwd=tmp_path)
    assert code == 0, out + err  # the command line wins
    (tmp_path / "urdfcheck.yaml").write_text("max_elements: 0\n")
    code, out, err = run_cli(args, cwd=tmp_path)
    assert code == 2 and "max_elements" in err

