"""The C and T rules end to end: engine with consumers, the CLI with a config, zero-config discovery, corpus."""
import json
import sys
from pathlib import Path

SRC = Path(__file__).resolve().parents[2] / "src"
if str(SRC) not in sys.path:  # runnable without an editable install
    sys.path.insert(0, str(SRC))

from conftest import flatten, run_cli  # noqa: E402

from urdfcheck.consumers.consumers import Consumers, consumers_for_model, discover_consumers  # noqa: E402
from urdfcheck.consumers.controllers import read_controllers  # noqa: E402
from urdfcheck.consumers.launch.xml import parse_launch  # noqa: E402
from urdfcheck.consumers.params import parse_params  # noqa: E402
from urdfcheck.core.findings import Severity  # noqa: E402
from urdfcheck.model.build import model_from_string  # noqa: E402
from urdfcheck.rules import engine  # noqa: E402

DDC = "ros-controls+ros_controllers/diff_drive_controller"


def wheel(side, y, axis="0 1 0", kind="continuous", radius=0.05):
    return f"""
  <link name="{side}_wheel_link">
    <inertial><mass value="1"/><inertia ixx="0.001" ixy="0" ixz="0" iyy="0.001" iyz="0" izz="0.001"/></inertial>
    <collision><origin rpy="1.5708 0 0"/><geometry><cylinder radius="{radius}" length="0.04"/></geometry></collision>
  </link>
  <joint name="{side}_wheel_joint" type="{kind}">
    <parent link="base_link"/><child link="{side}_wheel_link"/><origin xyz="0 {y} 0"/><axis xyz="{axis}"/>
  </joint>"""


def robot(extra="", left=None, right=None):
    return f"""<?xml version="1.0"?>
<robot name="bot">
  <link name="base_link"/>{left or wheel("left", 0.2)}{right or wheel("right", -0.2)}
  <link name="laser_link"/>
  <joint name="laser_joint" type="fixed"><parent link="base_link"/><child link="laser_link"/>\
<origin xyz="0.2 0 0.1"/></joint>
{extra}</robot>
"""


R2C = """  <ros2_control name="base" type="system">
    <hardware><plugin>mock_components/GenericSystem</plugin></hardware>
    <joint name="left_wheel_joint"><command_interface name="velocity"/><state_interface name="position"/></joint>
    <joint name="right_wheel_joint"><command_interface name="velocity"/><state_interface name="position"/></joint>
  </ros2_control>
"""

CTRL = """controller_manager:
  ros__parameters:
    joint_state_broadcaster:
      type: joint_state_broadcaster/JointStateBroadcaster
diff_drive_controller:
  ros__parameters:
    type: diff_drive_controller/DiffDriveController
    left_wheel_names: [{left}]
    right_wheel_names: [right_wheel_joint]
    wheel_separation: {sep}
    wheel_radius: 0.05
    base_frame_id: {base}
"""


def ctrl_text(left="left_wheel_joint", sep=0.4, base="base_link"):
    return CTRL.format(left=left, sep=sep, base=base)


def run(urdf, *, ctrl=None, launch=None, launch_name="bringup.launch.xml", select=("C", "T"), consumers=None):
    model = model_from_string(urdf, "bot.urdf")
    c = consumers or Consumers()
    if ctrl is not None:
        c.controllers = read_controllers([parse_params(ctrl, "ctrl.yaml")])
    if launch is not None:
        c.launch = [parse_launch(launch, launch_name)]
    sel = engine.Selection(select=tuple(select))
    return engine.run_checks(model, engine.Context(selection=sel, contracts=c))


def codes(findings):
    return sorted({f.code for f in findings})


# --- through the engine -----------------------------------------------------------------------------------------
def test_consistent_deployment_is_clean():
    launch = ('<launch><node pkg="robot_state_publisher" exec="robot_state_publisher"/>'
              '<node pkg="tf2_ros" exec="static_transform_publisher" args="--frame-id map --child-frame-id odom"/>'
              '</launch>')
    fs = run(robot(R2C), ctrl=ctrl_text(), launch=launch)
    assert fs == [], [(f.code, f.message) for f in fs]


def test_unknown_joint_points_into_the_yaml():
    (f,) = [f for f in run(robot(), ctrl=ctrl_text(left="left_wheel_link")) if f.code == "C001"]
    assert (f.location.file, f.location.line) == ("ctrl.yaml", 8) and "is a link, not a joint" in f.message
    (f,) = [f for f in run(robot(), ctrl=ctrl_text(left="left_weel_joint")) if f.code == "C001"]
    assert "did you mean 'left_wheel_joint'" in f.message
    assert not [f for f in run(robot(), ctrl=ctrl_text(left="$(var prefix)left_wheel_joint")) if f.code == "C001"]


def test_fixed_wheel():
    fs = run(robot(left=wheel("left", 0.2, kind="fixed")), ctrl=ctrl_text())
    (f,) = [f for f in fs if f.code == "C002"]
    assert "fixed joint" in f.message and f.location.file == "ctrl.yaml" and f.related[0].file == "bot.urdf"


def test_interfaces_and_ros2_control_blocks():
    position_only = R2C.replace('<command_interface name="velocity"/><state_interface name="position"/></joint>\n'
                                '    <joint name="right',
                                '<command_interface name="position"/></joint>\n    <joint name="right', 1)
    fs = run(robot(position_only), ctrl=ctrl_text())
    c5 = [f for f in fs if f.code == "C005"]
    assert len(c5) == 2 and {"'velocity'" in f.message or "'position' state" in f.message for f in c5} == {True}
    bad = R2C.replace('joint name="left_wheel_joint"', 'joint name="left_wheel_link"')
    fs = run(robot(bad))
    assert [f.code for f in fs] == ["C004"] and "link, not a joint" in fs[0].message
    twice = R2C + R2C.replace('name="base"', 'name="base2"')
    assert "C004" in codes(run(robot(twice)))
    bare = R2C.replace('<joint name="right_wheel_joint"><command_interface name="velocity"/>'
                       '<state_interface name="position"/></joint>', '<joint name="right_wheel_joint"/>')
    (f,) = [f for f in run(robot(bare)) if f.code == "C004"]
    assert "no command or state interface" in f.message
    # the ros2_control mimic idiom (TIAGo Pro's grippers): no interfaces of its own is intended
    for mimic in ('<joint name="right_wheel_joint"><param name="mimic">left_wheel_joint</param></joint>',
                  '<joint name="right_wheel_joint" mimic="true"/>'):
        assert "C004" not in codes(run(robot(bare.replace('<joint name="right_wheel_joint"/>', mimic))))
    in_gz = "  <gazebo>\n" + R2C + "  </gazebo>\n"
    assert codes(run(robot(in_gz))) == ["C006"]


def test_state_sources():
    no_jsb = ctrl_text().replace("joint_state_broadcaster/JointStateBroadcaster", "other_pkg/Other")
    (f,) = [f for f in run(robot(R2C), ctrl=no_jsb) if f.code == "C003"]
    assert f.severity == Severity.WARNING and "left_wheel_joint" in f.message
    jsp = '<launch><node pkg="joint_state_publisher" exec="joint_state_publisher"/></launch>'
    assert "C003" not in codes(run(robot(R2C), ctrl=no_jsb, launch=jsp))
    partial = R2C.replace('    <joint name="right_wheel_joint"><command_interface name="velocity"/>'
                          '<state_interface name="position"/></joint>\n', "")
    (f,) = [f for f in run(robot(partial), ctrl=ctrl_text()) if f.code == "C003"]
    assert "right_wheel_joint" in f.message and f.location.file == "bot.urdf"
    assert "C003" not in codes(run(robot(R2C)))  # no deployment known: nothing to say


def test_wheel_rules_use_rule_options():
    fs = run(robot(), ctrl=ctrl_text(sep=0.4015))
    assert "C010" in codes(fs)
    model = model_from_string(robot(), "bot.urdf")
    c = Consumers(controllers=read_controllers([parse_params(ctrl_text(sep=0.4015), "ctrl.yaml")]))
    sel = engine.Selection(select=("C010",), options={"C010": {"tolerance": 0.002}})
    assert engine.run_checks(model, engine.Context(selection=sel, contracts=c)) == []


def test_unknown_frame():
    (f,) = [f for f in run(robot(), ctrl=ctrl_text(base="base_footprint")) if f.code == "C020"]
    assert "base_footprint" in f.message and f.location.line == 12
    launch = ('<launch><node pkg="tf2_ros" exec="static_transform_publisher" '
              'args="0 0 0 0 0 0 base_footprint base_link"/></launch>')
    assert "C020" not in codes(run(robot(), ctrl=ctrl_text(base="base_footprint"), launch=launch))


def test_tf_rules_from_launch():
    static = '<launch><node pkg="tf2_ros" exec="static_transform_publisher" name="t" args="{}"/></launch>'
    fs = run(robot(), launch=static.format("0.2 0 0.1 0 0 0 base_link laser_link"))
    (f,) = [f for f in fs if f.code == "T001"]
    assert f.location.file == "bringup.launch.xml" and f.related[0].file == "bot.urdf"
    assert "T002" in codes(run(robot(), launch=static.format("0 0.2 0 0 0 0 base_link left_wheel_link")))
    assert "T003" in codes(run(robot(), launch=static.format("0 0 0 0 0 0 base_footprint laser_link")))
    assert "T004" in codes(run(robot(), launch=static.format("0 0 0 0 0 0 laser_link base_link")))
    assert codes(run(robot(), launch=static.format("0 0 0 0 0 0 map odom"))) == ["T005"]
    two = ('<launch><node pkg="robot_state_publisher" exec="robot_state_publisher" name="a" namespace="r1"/>'
           '<node pkg="robot_state_publisher" exec="robot_state_publisher" name="b" namespace="r2"/></launch>')
    assert "T006" in codes(run(robot(), launch=two))


def test_odometry_twice():
    ekf = parse_params("ekf:\n  ros__parameters:\n    world_frame: odom\n    two_d_mode: true\n", "ekf.yaml")
    from urdfcheck.consumers.localization import localization_from_params

    c = Consumers(localization=localization_from_params([ekf]))
    fs = run(robot(), ctrl=ctrl_text(), consumers=c)
    (f,) = [f for f in fs if f.code == "T001"]
    assert "diff_drive_controller" in f.message and "ekf" in f.message
    assert {f.location.file, *(r.file for r in f.related)} == {"ctrl.yaml", "ekf.yaml"}


def test_odometry_to_a_non_root_link():
    footprint = robot().replace('<link name="base_link"/>',
                                '<link name="base_footprint"/><link name="base_link"/>'
                                '<joint name="fp" type="fixed"><parent link="base_footprint"/>'
                                '<child link="base_link"/></joint>')
    (f,) = [f for f in run(footprint, ctrl=ctrl_text()) if f.code == "T003"]
    assert "publish odometry to base_footprint" in f.message
    assert codes([f for f in run(footprint, ctrl=ctrl_text()) if f.code.startswith("T")]) == ["T003"]


# --- through the CLI, with a config --------------------------------------------------------------------------------
def write_pkg(root: Path, urdf: str, files: dict) -> None:
    (root / "urdf").mkdir(parents=True, exist_ok=True)
    (root / "urdf" / "bot.urdf").write_text(urdf)
    (root / "package.xml").write_text("<package format='3'><name>bot</name></package>\n")
    for name, text in files.items():
        p = root / name
        p.parent.mkdir(parents=True, exist_ok=True)
        p.write_text(text)


def lint(cwd, *args):
    code, out, err = run_cli(["lint", "--format", "json", *args], cwd=cwd)
    assert code in (0, 1), err
    return code, flatten(json.loads(out)["findings"])


def test_config_with_custom_driver(tmp_path):
    write_pkg(tmp_path, robot(R2C), {
        "config/ctrl.yaml": ctrl_text(),
        "config/driver.yaml": "base:\n  left: left_wheel_joint\n  right: right_wheel_joint\n  track: 0.45\n"
                              "  radius: 0.05\n  imu: imu_link\n  tf: true\n",
        "urdfcheck.yaml": """\
models:
  - path: urdf/bot.urdf
    controllers: [config/ctrl.yaml]
    drivers:
      - file: config/driver.yaml
        node: base
        left_wheels: [left]
        right_wheels: [right]
        wheel_separation: track
        wheel_radius: radius
        frames: [imu, gps]
        odom_tf: tf
""",
    })
    code, fs = lint(tmp_path)
    got = sorted((f["code"], Path(f["location"]["file"]).name, f["location"]["line"]) for f in fs)
    assert code == 1
    assert ("C010", "driver.yaml", 4) in got  # track 0.45 vs 0.40
    assert ("C020", "driver.yaml", 6) in got  # imu_link is not in the model
    assert ("C007", "urdfcheck.yaml", 5) in got  # the 'gps' key is not in the driver file
    assert any(c == "T001" for c, _, _ in got)  # controller and driver both publish odom -> base_link


def test_zero_config_discovery(tmp_path):
    write_pkg(tmp_path, robot(R2C), {"config/controllers.yaml": ctrl_text(sep=0.5)})
    code, fs = lint(tmp_path, "--no-config", "urdf/bot.urdf")
    assert ([(f["code"], Path(f["location"]["file"]).name) for f in fs if f["code"][0] in "CT"]
            == [("C010", "controllers.yaml")])
    (tmp_path / "config" / "controllers.yaml").write_text("a: [1,\n")
    code, fs = lint(tmp_path, "--no-config", "urdf/bot.urdf")
    assert [(f["code"], f["location"]["line"]) for f in fs if f["code"][0] in "CT"] == [("C007", 2)]


def test_discovery_needs_a_package(tmp_path):
    (tmp_path / "config").mkdir()
    (tmp_path / "config" / "controllers.yaml").write_text(ctrl_text(sep=0.5))
    (tmp_path / "bot.urdf").write_text(robot())
    assert discover_consumers(str(tmp_path / "bot.urdf")) is None


# --- corpus ---------------------------------------------------------------------------------------------------------
def test_corpus_ros1_negative_cases(corpus, tmp_path):
    d = corpus / DDC
    (tmp_path / "urdfcheck.yaml").write_text(f"""\
models:
  - path: {d}/test/diffbot_bad.xacro
    controllers: [{d}/test/diffbot_controllers.yaml]
  - path: {d}/test/skidsteerbot.xacro
    controllers: [{d}/test/skidsteerbot_no_wheels.yaml]
  - path: {d}/test/diffbot_square_wheels.xacro
    controllers: [{d}/test/diffbot_controllers.yaml]
packages: {{diff_drive_controller: {d}}}
""")
    # the config names files outside its folder: the runner vouches for it (issue 19)
    code, fs = lint(tmp_path, "--config", str(tmp_path / "urdfcheck.yaml"), "--trust-config")
    assert code == 1
    by = {}
    for f in fs:
        by.setdefault((f["code"], Path(f["model"]).name), []).append(f)
    c001 = by[("C001", "diffbot_bad.xacro")]
    assert sorted(f["location"]["line"] for f in c001) == [3, 4]
    assert all(Path(f["location"]["file"]).name == "diffbot_controllers.yaml" for f in c001)
    (c013,) = by[("C013", "skidsteerbot.xacro")]
    assert c013["severity"] == "error" and Path(c013["location"]["file"]).name == "skidsteerbot_no_wheels.yaml"
    assert len(by[("C011", "diffbot_square_wheels.xacro")]) == 2  # a box wheel and no wheel_radius


def test_corpus_ros2_demo_is_consistent(corpus):
    d = corpus / "ros-controls+ros2_control_demos"
    from urdfcheck.load.loader import load_model

    pk = {"ros2_control_demo_description": str(d / "ros2_control_demo_description"),
          "ros2_control_demo_example_2": str(d / "example_2/description")}
    entry = d / "example_2/description/urdf/diffbot.urdf.xacro"
    model = load_model(entry, packages=pk)
    c = discover_consumers(str(entry), model, packages=pk)
    assert len(c.controllers) == 2 and len(c.launch) == 1 and not c.errors
    sel = engine.Selection(select=("C", "T"))
    found = engine.run_checks(model, engine.Context(selection=sel, contracts=c))
    # the demo's only contract defect: its left wheel sits at y = -0.05 (see rules/C014.yaml)
    assert [f.code for f in found] == ["C014"]


def test_consumers_for_model_reports_unreadable_files(tmp_path):
    from urdfcheck.request.config import load_config

    write_pkg(tmp_path, robot(), {"config/bad.yaml": "x: [\n", "launch/a.launch.xml": "<launch><node</launch>"})
    (tmp_path / "urdfcheck.yaml").write_text("models:\n  - path: urdf/bot.urdf\n    controllers: [config/bad.yaml]\n"
                                             "    launch: [launch/a.launch.xml]\n")
    cfg = load_config(tmp_path / "urdfcheck.yaml")
    c = consumers_for_model(cfg.models[0], cfg)
    assert sorted(Path(e.location.file).name for e in c.errors) == ["a.launch.xml", "bad.yaml"]
