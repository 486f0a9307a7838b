"""The example packages against their consumers, through the real CLI.

* examples/agv lints clean with its urdfcheck.yaml (declared controllers, ROS 1 driver, launch, variants, TF owners)
  and without it (zero-config discovery), and the config really reaches the consumers (mutations are caught);
* every examples/broken/contract_* and variant_* package reports exactly its EXPECTED (tests/project/test_examples.py
  does the generic comparison; the details each defect must carry are checked here);
* C014 wheel-sides-swapped by forward kinematics, ROS 1 launch parameter overrides, and the corpus cases.
"""
import json
import shutil
import sys
from pathlib import Path

SRC = Path(__file__).resolve().parents[2] / "src"
if str(SRC) not in sys.path:  # runnable without an editable install
    sys.path.insert(0, str(SRC))

import pytest  # noqa: E402
from conftest import REPO, flatten, lint_json, run_cli  # noqa: E402
from test_examples import BROKEN, actual, lint_package, read_expected_full  # noqa: E402

from urdfcheck.consumers.common import Value  # noqa: E402
from urdfcheck.consumers.controllers import DriveSpec, JointUse  # noqa: E402
from urdfcheck.consumers.launch.xml import ParamSet, RosparamLoad, parse_launch  # noqa: E402
from urdfcheck.core.findings import Location  # noqa: E402
from urdfcheck.model.build import model_from_string  # noqa: E402
from urdfcheck.rules.contracts.wheels import check_drive  # noqa: E402

AGV = REPO / "examples" / "agv"
CONTRACT_PACKAGES = sorted(p.parent.name for pat in ("contract_*/EXPECTED", "variant_*/EXPECTED")
                           for p in BROKEN.glob(pat))
DDC = "ros-controls+ros_controllers/diff_drive_controller"


def lint_cfg(args, cwd=REPO):
    """The CLI with config discovery (no --no-config); (exit code, json report)."""
    code, out, err = run_cli(["lint", "--format", "json", *[str(a) for a in args]], cwd=cwd)
    assert code in (0, 1), (code, err)
    report = json.loads(out)
    report["findings"] = flatten(report["findings"])  # one per line, as the rules found them
    return code, report


def summary(report):
    return [(f["code"], Path(f["location"]["file"]).name, f["location"]["line"], f["variant"])
            for f in report["findings"]]


# --- the AGV ---------------------------------------------------------------------------------------------------
@pytest.mark.parametrize("args,cwd", [(["examples/agv"], REPO), ([], AGV), (["urdf/agv.urdf.xacro"], AGV)],
                         ids=["from-root", "inside", "one-model"])
def test_agv_with_its_config_is_clean(args, cwd):
    code, report = lint_cfg(args, cwd)
    assert report["findings"] == [], summary(report)
    assert code == 0
    models = {(Path(m["path"]).name, m["variant"]) for m in report["models"]}
    if args == ["urdf/agv.urdf.xacro"]:
        assert models == {("agv.urdf.xacro", "camera"), ("agv.urdf.xacro", "no_camera")}
    else:  # the declared variants, and the plain URDF (declared too: a config lints only what it declares)
        assert models == {("agv.urdf.xacro", "camera"), ("agv.urdf.xacro", "no_camera"), ("agv.urdf", "")}


def test_agv_zero_config_is_clean():
    code, report = lint_json(["examples/agv"], cwd=REPO)
    assert report["findings"] == [], summary(report)
    assert code == 0
    models = {(Path(m["path"]).name, m["variant"]) for m in report["models"]}
    # the xacro is the model launch/agv.launch.xml starts robot_state_publisher with: linted as that deployment
    # (the launch file's arguments and consumers), not alone with its boolean variants (plan/plan.py)
    # (plan/plan.py); the launch argument use_camera reaches the xacro argument: its other value is a deployment too
    assert models == {("agv.urdf", ""), ("agv.urdf.xacro", "examples/agv/launch/agv.launch.xml"),
                      ("agv.urdf.xacro", "examples/agv/launch/agv.launch.xml [use_camera=false]")}


def test_agv_config_reaches_every_consumer():
    from urdfcheck.consumers.consumers import consumers_for_model
    from urdfcheck.load.loader import load_model
    from urdfcheck.request.config import load_config
    from urdfcheck.rules.checks.tf.graph import deployment_graph as _graph

    cfg = load_config(AGV / "urdfcheck.yaml")
    assert [Path(m.path).name for m in cfg.models] == ["agv.urdf.xacro", "agv.urdf"]
    assert dict(cfg.frames) == {"map": "map", "odom": "odom", "base": "base_link"}
    for mc in cfg.models:
        c = consumers_for_model(mc, cfg)
        assert not c.errors
        assert sorted(x.name for x in c.controllers) == ["diff_drive_controller", "joint_state_broadcaster"]
        (drv,) = c.drivers
        assert not drv.missing and [str(v) for v in drv.frames] == ["imu_link", "laser_link"]
        assert drv.odom_tf is not None and drv.odom_tf.enabled is False  # publish_odom_tf: false
        assert drv.drive.separation == 0.5 and float(drv.drive.wheel_radius.value) == 0.1
        (li,) = c.launch
        assert [(s.parent, s.child) for s in li.static_tfs] == [("map", "odom")]
        model = load_model(mc.path, packages=dict(cfg.packages))
        g = _graph(model, c)
        assert g.roots() == ["map"]  # one tree: map -> odom -> base_link -> ...
        owners = {(cl.parent, cl.child): (cl.owner, cl.source) for cl in g.claims if cl.source != "model"}
        # the declared owners name the publishers read from the files: no second claim
        assert owners == {("map", "odom"): ("static_transform_publisher map_to_odom", "launch"),
                          ("odom", "base_link"): ("diff_drive_controller", "controller")}


@pytest.fixture
def agv_copy(tmp_path):
    dst = tmp_path / "agv"
    shutil.copytree(AGV, dst)
    return dst


def test_agv_config_catches_a_driver_mismatch(agv_copy):
    f = agv_copy / "config" / "agv_driver_ros1.yaml"
    f.write_text(f.read_text().replace("wheel_separation: 0.50", "wheel_separation: 0.52"))
    code, report = lint_cfg([], cwd=agv_copy)
    assert code == 1
    got = {(c, name, line) for c, name, line, _ in summary(report)}
    assert got == {("C010", "agv_driver_ros1.yaml", 7)}
    # zero-config reads the custom driver by the shape of its keys (issue 20): the same line; no launch file loads
    # it and the package holds two models, so it is paired by the joint names it shares with the model, a guess:
    # an info that says how to confirm the pairing (issue 37)
    _, plain = lint_json([agv_copy], cwd=agv_copy)
    assert {(f["code"], f["severity"], f["location"]["line"]) for f in plain["findings"]} == {("C010", "info", 7)}
    for c010 in plain["findings"]:
        assert "to confirm: name it under models:" in c010["message"]
        (guess,) = [s for s in c010["evidence"] if not s["evidence"]]
        assert guess["what"] == "parameters" and guess["how"] == "overlap"
        assert "agv_driver_ros1.yaml for " in guess["subject"]


def test_agv_camera_frame_in_the_driver_breaks_the_no_camera_variant(agv_copy):
    f = agv_copy / "config" / "agv_driver_ros1.yaml"
    f.write_text(f.read_text() + "camera_frame_id: camera_link\n")
    c = agv_copy / "urdfcheck.yaml"
    c.write_text(c.read_text().replace("frames: [imu_frame_id, laser_frame_id]   #",
                                       "frames: [imu_frame_id, laser_frame_id, camera_frame_id]   #"))
    _, report = lint_cfg([], cwd=agv_copy)
    assert [(x[0], x[3]) for x in summary(report)] == [("C020", "no_camera")]


def test_agv_declared_owner_that_disagrees_is_reported(agv_copy):
    c = agv_copy / "urdfcheck.yaml"
    c.write_text(c.read_text().replace('"map->odom": map_to_odom', '"map->odom": amcl'))
    code, report = lint_cfg([], cwd=agv_copy)
    assert code == 1 and {f["code"] for f in report["findings"]} == {"T002"}
    assert all("amcl" in f["message"] and "map_to_odom" in f["message"] for f in report["findings"])


# --- the broken contract packages ---------------------------------------------------------------------------------
def test_there_are_contract_packages():
    assert {"contract_static_tf_duplicate", "contract_driver_joint_typo", "contract_wheel_separation",
            "contract_wheel_radius", "contract_odom_tf_twice", "contract_sensor_frame_id", "contract_joint_no_state",
            "variant_camera_off", "contract_wheels_swapped", "contract_launch_override"} <= set(CONTRACT_PACKAGES)


@pytest.mark.parametrize("name", CONTRACT_PACKAGES)
def test_contract_package_reports_exactly_its_expected(name):
    full = read_expected_full(name)
    with_variants = any(v for *_, v in full)  # then every line of that EXPECTED names its variant(s)
    want = sorted((c, w, v or "") for c, w, _, v in full)
    code, report = lint_package(name)
    got = sorted((c, w, f["variant"] if with_variants else "")
                 for (c, w, _), f in zip(actual(report["findings"], name), report["findings"]))
    assert got == want, [(f["code"], f["message"]) for f in report["findings"]]
    assert code == 1


def _finding(name, code):
    _, report = lint_package(name)
    (f,) = [f for f in report["findings"] if f["code"] == code][:1]
    return f


def _related(f):
    return {(Path(r["file"]).name, r["line"]) for r in f.get("related", [])}


def test_static_duplicate_names_both_publishers():
    f = _finding("contract_static_tf_duplicate", "T001")
    assert "base_link -> laser_link" in f["message"] and "robot_state_publisher" in f["message"]
    assert "static_transform_publisher base_to_laser" in f["message"]
    assert ("agv.urdf", 152) in _related(f)  # laser_link_joint


def test_odom_tf_twice_names_controller_and_ekf_with_locations():
    f = _finding("contract_odom_tf_twice", "T001")
    assert "diff_drive_controller" in f["message"] and "ekf_filter_node" in f["message"]
    assert "agv_controllers.yaml:27" in f["message"] and "ekf.yaml:9" in f["message"]
    assert ("ekf.yaml", 9) in _related(f)


def test_typo_and_frame_hints():
    assert "did you mean 'left_wheel_joint'" in _finding("contract_driver_joint_typo", "C001")["message"]
    assert "did you mean 'imu_link'" in _finding("contract_sensor_frame_id", "C020")["message"]
    # no misleading hint: camera_link is not laser_link just because both end in _link
    assert "did you mean" not in _finding("variant_camera_off", "C020")["message"]


def test_variant_package_is_clean_with_the_camera():
    code, report = lint_cfg(["--arg", "use_camera:=true", "examples/broken/variant_camera_off"])
    assert report["findings"] == [] and code == 0


# --- C014: forward kinematics, not the joint's xyz ---------------------------------------------------------------
def _wheel(side, xyz, rpy="0 0 0", axis="0 1 0", parent="base_link"):
    return f"""
  <link name="{side}_link"><collision><origin rpy="1.5708 0 0"/>
    <geometry><cylinder radius="0.1" length="0.05"/></geometry></collision></link>
  <joint name="{side}_joint" type="continuous"><parent link="{parent}"/><child link="{side}_link"/>
    <origin xyz="{xyz}" rpy="{rpy}"/><axis xyz="{axis}"/></joint>"""


def _robot(*parts):
    return model_from_string(f'<robot name="r"><link name="base_link"/>{"".join(parts)}</robot>', "r.urdf")


def _drive():
    yml = "c.yaml"
    return DriveSpec("ddc", Location(yml, 1), (JointUse("left_joint", Location(yml, 2), "ddc", role="left_wheel"),),
                     (JointUse("right_joint", Location(yml, 3), "ddc", role="right_wheel"),), Location(yml, 2),
                     Location(yml, 3), Value(0.5, Location(yml, 4)), None)


def c014(model):
    rep = check_drive(model, _drive())
    return [p for p in rep.problems() if p.code == "C014"], rep


def test_c014_plain_swap():
    (p,), rep = c014(_robot(_wheel("left", "0 -0.25 0"), _wheel("right", "0 0.25 0")))
    assert rep.turn_reversed is True and p.at == Location("c.yaml", 2)
    assert "y = -0.25 m" in p.message and "drives the robot forward" in p.message


def test_c014_correct_robot_and_rotated_wheel_frames():
    assert c014(_robot(_wheel("left", "0 0.25 0"), _wheel("right", "0 -0.25 0")))[0] == []
    # turtlebot3 style: wheel frames rotated -90 degrees about x, turning about their z (= +y in base_link)
    tb3 = _robot(_wheel("left", "0 0.25 0", "-1.5708 0 0", "0 0 1"),
                 _wheel("right", "0 -0.25 0", "-1.5708 0 0", "0 0 1"))
    probs, rep = c014(tb3)
    assert probs == [] and rep.forward_sign == pytest.approx(2, abs=1e-3)


def test_c014_a_wheel_written_at_negative_y_can_be_on_the_left():
    # the left wheel hangs from a mount rotated by pi about x: its origin says y = -0.25, FK puts it at +0.25,
    # and its axis 0 -1 0 is +y in base_link
    mount = ('<link name="mount"/><joint name="mount_joint" type="fixed"><parent link="base_link"/>'
             '<child link="mount"/><origin xyz="0 0 0" rpy="3.14159265 0 0"/></joint>')
    m = _robot(mount, _wheel("left", "0 -0.25 0", axis="0 -1 0", parent="mount"), _wheel("right", "0 -0.25 0"))
    probs, rep = c014(m)
    assert probs == [] and rep.sides_swapped is False and rep.turn_reversed is False


def test_c014_the_sign_of_rotation_matters():
    # left at -y but both axes along -y: the correct robot turned 180 degrees about z; it turns the right way
    turned = _robot(_wheel("left", "0 -0.25 0", axis="0 -1 0"), _wheel("right", "0 0.25 0", axis="0 -1 0"))
    probs, rep = c014(turned)
    assert probs == [] and rep.sides_swapped is True and rep.turn_reversed is False
    # left at +y with both axes along -y: positive rotation drives backward, and the robot turns the wrong way
    backward = _robot(_wheel("left", "0 0.25 0", axis="0 -1 0"), _wheel("right", "0 -0.25 0", axis="0 -1 0"))
    (p,), _ = c014(backward)
    assert "backward" in p.message
    # mixed signs: turning sense undefined (it spins when told to drive straight); not C014's finding
    mixed = _robot(_wheel("left", "0 0.25 0", axis="0 1 0"), _wheel("right", "0 -0.25 0", axis="0 -1 0"))
    probs, rep = c014(mixed)
    assert probs == [] and rep.turn_reversed is None


# --- ROS 1 launch overrides ---------------------------------------------------------------------------------------
ROS1_CTRL = """joint_state_controller:
  type: joint_state_controller/JointStateController
diff_drive_controller:
  type: diff_drive_controller/DiffDriveController
  left_wheel: left_wheel_joint
  right_wheel: right_wheel_joint
  wheel_separation: 0.50
  wheel_radius: 0.10
"""


def ros1_pkg(tmp_path, launch_body, extra=None):
    (tmp_path / "urdf").mkdir()
    (tmp_path / "config").mkdir()
    (tmp_path / "launch").mkdir()
    (tmp_path / "package.xml").write_text("<package format='3'><name>bot</name><version>0.0.0</version>"
                                          "<description>d</description><maintainer email='a@b.c'>a</maintainer>"
                                          "<license>MIT</license></package>")
    urdf = (BROKEN / "contract_launch_override" / "urdf" / "agv.urdf").read_text()
    (tmp_path / "urdf" / "agv.urdf").write_text(urdf)
    (tmp_path / "config" / "ctrl.yaml").write_text(ROS1_CTRL)
    for k, v in (extra or {}).items():
        (tmp_path / k).write_text(v)
    (tmp_path / "launch" / "bot.launch").write_text(f"<launch>\n{launch_body}</launch>\n")
    (tmp_path / "urdfcheck.yaml").write_text("models:\n  - path: urdf/agv.urdf\n    controllers: [config/ctrl.yaml]\n"
                                             "    launch: [launch/bot.launch]\npackages: {bot: .}\nselect: [C, T]\n")
    code, report = lint_cfg(["--config", "urdfcheck.yaml", "--trust-config"], cwd=tmp_path)  # select: the runner's
    return [(f["code"], Path(f["location"]["file"]).name, f["location"]["line"]) for f in report["findings"]]


LOAD = '  <rosparam command="load" file="$(find bot)/config/ctrl.yaml"/>\n'


def test_launch_param_after_the_load_wins(tmp_path):
    got = ros1_pkg(tmp_path, LOAD + '  <param name="diff_drive_controller/wheel_separation" value="0.52"/>\n')
    assert got == [("C010", "bot.launch", 3)]


def test_launch_param_before_the_load_is_overwritten(tmp_path):
    assert ros1_pkg(tmp_path, '  <param name="diff_drive_controller/wheel_separation" value="0.52"/>\n' + LOAD) == []


def test_launch_rosparam_file_with_ns_and_inline_yaml(tmp_path):
    body = (LOAD + '  <rosparam command="load" file="$(find bot)/config/wheels.yaml" ns="diff_drive_controller"/>\n'
            '  <rosparam ns="diff_drive_controller">\n    wheel_separation: 0.55\n  </rosparam>\n')
    got = ros1_pkg(tmp_path, body, {"config/wheels.yaml": "wheel_radius: 0.12\n"})
    assert sorted(got) == [("C010", "bot.launch", 5), ("C011", "wheels.yaml", 1), ("C011", "wheels.yaml", 1)]


def test_launch_group_namespace(tmp_path):
    body = ('  <group ns="r1">\n' + LOAD +
            '    <param name="diff_drive_controller/wheel_radius" value="0.12"/>\n  </group>\n'
            '  <param name="diff_drive_controller/wheel_separation" value="0.52"/>\n')  # another robot's
    got = ros1_pkg(tmp_path, body)
    assert got == [("C011", "bot.launch", 4), ("C011", "bot.launch", 4)]


def test_launch_non_literal_values_are_not_applied(tmp_path):
    body = LOAD + ('  <param name="diff_drive_controller/wheel_separation" value="$(env SEP)"/>\n'
                   '  <param name="diff_drive_controller/wheel_radius" command="cat radius.txt"/>\n'
                   '  <param name="diff_drive_controller/wheel_radius" value="0.12" if="$(env USE_BIG)"/>\n')
    assert ros1_pkg(tmp_path, body) == []


def test_launch_reader_records_parameter_writes():
    li = parse_launch('<launch>\n<group ns="a">\n<param name="c/x" value="1"/>\n<param name="/g" value="true"/>\n'
                      '<param name="s" type="str" value="0.5"/>\n'
                      '<rosparam file="/tmp/f.yaml" ns="n"/>\n</group>\n'
                      '<node pkg="p" type="t" name="n"><param name="private" value="1"/></node>\n</launch>',
                      "x.launch")
    sets = li.param_sets
    assert [(s.name, s.value.value) for s in sets if isinstance(s, ParamSet)] == [("/a/c/x", 1), ("/g", True),
                                                                                 ("/a/s", "0.5")]
    (load,) = [s for s in sets if isinstance(s, RosparamLoad)]
    assert (load.file, load.ns) == ("/tmp/f.yaml", "/a/n")
    assert parse_launch('<launch><param name="x" value="1"/><node pkg="a" exec="b"/></launch>',
                        "y.launch.xml").param_sets == []  # ROS 2 XML: not a parameter server


# --- corpus ----------------------------------------------------------------------------------------------------
def test_corpus_ros_controllers_negative_cases_are_flagged(corpus, tmp_path):
    d = corpus / DDC
    (tmp_path / "urdfcheck.yaml").write_text(f"""\
models:
  - path: {d}/test/diffbot_bad.xacro
    controllers: [{d}/test/diffbot_controllers.yaml]
  - path: {d}/test/skidsteerbot.xacro
    controllers: [{d}/test/skidsteerbot_no_wheels.yaml]
packages: {{diff_drive_controller: {d}}}
""")
    # the config names files outside its folder: the runner vouches for it (issue 19)
    code, report = lint_cfg(["--config", str(tmp_path / "urdfcheck.yaml"), "--trust-config"], cwd=tmp_path)
    assert code == 1
    by = {}
    for f in report["findings"]:
        by.setdefault((f["code"], Path(f["model"]).name), []).append(f)
    c001 = by[("C001", "diffbot_bad.xacro")]  # wheel_0_joint / wheel_1_joint are not in diffbot_bad
    assert sorted((Path(f["location"]["file"]).name, f["location"]["line"]) for f in c001) == \
        [("diffbot_controllers.yaml", 3), ("diffbot_controllers.yaml", 4)]
    (c013,) = by[("C013", "skidsteerbot.xacro")]  # left_wheel: []
    assert c013["severity"] == "error" and Path(c013["location"]["file"]).name == "skidsteerbot_no_wheels.yaml"


def test_corpus_ros2_control_demos_diffbot_wheels_are_swapped(corpus):
    """example_2's diffbot: left_wheel_joint at y = -0.05 (rpy 0, axis 0 1 0), right_wheel_joint at +0.05.
    Positive rotation drives both forward, so the joint named left is the right wheel: C014 (see rules/C014.yaml)."""
    d = corpus / "ros-controls+ros2_control_demos"
    code, report = lint_json(["--package", f"ros2_control_demo_description={d / 'ros2_control_demo_description'}",
                              "--package", f"ros2_control_demo_example_2={d / 'example_2/description'}",
                              d / "example_2/description/urdf/diffbot.urdf.xacro"], cwd=REPO)
    c014 = [f for f in report["findings"] if f["code"] == "C014"]
    assert [(Path(f["location"]["file"]).name, f["location"]["line"]) for f in c014] == \
        [("diffbot_controllers.yaml", 9)]
    assert "y = -0.05 m and y = +0.05 m" in c014[0]["message"]
    assert {(Path(r["file"]).name, r["line"]) for r in c014[0]["related"]} >= \
        {("diffbot_description.urdf.xacro", 46), ("diffbot_description.urdf.xacro", 82)}
    assert {f["code"] for f in report["findings"]} <= {"C014", "I005"}


def test_launch_rosparam_file_outside_the_packages_is_not_read(tmp_path):
    outside = tmp_path / "elsewhere"
    outside.mkdir()
    (outside / "wheels.yaml").write_text("wheel_radius: 0.12\n")
    pkg = tmp_path / "pkg"
    pkg.mkdir()
    body = LOAD + f'  <rosparam command="load" file="{outside / "wheels.yaml"}" ns="diff_drive_controller"/>\n'
    assert ros1_pkg(pkg, body) == []
