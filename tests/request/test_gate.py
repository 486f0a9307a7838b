"""The gate belongs to the runner (issue 36): a config found in the checkout (or named without --trust-config)
adds, never hides; discovery skips by ROS's marker files, never by folder names; whatever robot_state_publisher
is given is a robot, whatever its name. Each case: a broken robot that passed on the old code ("All checks
passed", exit 0) and fails now, with the refused key said at its line (X018)."""
import json
import os

import pytest
from conftest import run_cli
from samples import BAD, GOOD

BROKEN = ("bot/urdf/broken.urdf", 5)  # U002 (<orign>), a warning


def _ws(tmp_path, config: str | None = None, where: str = "urdfcheck.yaml"):
    """A repository (.git) with the package bot: a broken robot beside a clean one."""
    ws = tmp_path / "ws"
    (ws / ".git").mkdir(parents=True)
    (ws / "bot" / "urdf").mkdir(parents=True)
    (ws / "bot" / "package.xml").write_text("<package format='3'><name>bot</name></package>")
    (ws / "bot" / "urdf" / "broken.urdf").write_text(BAD)
    (ws / "bot" / "urdf" / "clean.urdf").write_text(GOOD)
    if config is not None:
        (ws / where).parent.mkdir(parents=True, exist_ok=True)
        (ws / where).write_text(config)
    return ws


def _lint(ws, *args):
    code, out, err = run_cli(["lint", "--format", "json", *args], cwd=ws)
    assert code in (0, 1), err
    return code, [(f["code"], f["location"]["file"], f["location"]["line"], f["severity"])
                  for f in json.loads(out)["findings"]]


def _x018(found):
    return [(f, line) for c, f, line, sev in found if c == "X018" and sev == "error"]


def _has_broken(found, severity="warning"):
    return ("U002", *BROKEN, severity) in found


# --- models: adds to discovery ---------------------------------------------------------------------------------
DECOY = {
    "urdfcheck.yaml": ("urdfcheck.yaml", "models:\n  - path: bot/urdf/clean.urdf\n"),
    ".urdfcheck.yaml": (".urdfcheck.yaml", "models:\n  - path: bot/urdf/clean.urdf\n"),
    "pyproject": ("pyproject.toml",
                  '[project]\nname = "x"\n\n[[tool.urdfcheck.models]]\npath = "bot/urdf/clean.urdf"\n'),
    "nested": ("bot/urdfcheck.yaml", "models:\n  - path: urdf/clean.urdf\n"),
}


@pytest.mark.parametrize("case", sorted(DECOY))
def test_a_declared_decoy_does_not_hide_the_robot_beside_it(tmp_path, case):
    where, text = DECOY[case]
    ws = _ws(tmp_path, text, where)
    code, found = _lint(ws)
    assert code == 1 and _has_broken(found), found
    code, found = _lint(ws, ".")
    assert code == 1 and _has_broken(found), found
    if case != "nested":  # the runner vouching for it: its models are all that is linted
        code, found = _lint(ws, "--config", where, "--trust-config")
        assert code == 0 and found == [], found


# --- what lowers the gate: refused at its key, an error -----------------------------------------------------------
def _all_families_but_x():
    from urdfcheck.rules.catalogue import catalogue

    return sorted({c[0] for c in catalogue()} - {"X"})


LOWERING = {
    "ignore all but X": (lambda: f"ignore: [{', '.join(_all_families_but_x())}]\n", 1, "warning"),
    "ignore the code": (lambda: "ignore: [U002]\n", 1, "warning"),
    "severity down to info": (lambda: "severity: {U: info}\n", 1, "warning"),
    "severity of the code": (lambda: "severity:\n  U002: info\n", 2, "warning"),
    "select B": (lambda: "select: [B]\n", 1, "warning"),
    "fail_on error with lowered severities": (lambda: "fail_on: error\nseverity: {U002: info, X: info}\n", None,
                                              "warning"),
}


@pytest.mark.parametrize("case", sorted(LOWERING))
def test_what_lowers_the_gate_is_refused_at_its_key(tmp_path, case):
    text, line, severity = LOWERING[case]
    ws = _ws(tmp_path, text())
    code, found = _lint(ws)
    assert code == 1 and _has_broken(found, severity), found
    refused = _x018(found)
    assert refused and all(f == "urdfcheck.yaml" for f, _ in refused), found
    if line is not None:
        assert refused == [("urdfcheck.yaml", line)]
    # named with --config alone it is as untrusted as found; with --trust-config the runner lowers the gate
    code, found = _lint(ws, "--config", "urdfcheck.yaml")
    assert code == 1 and _has_broken(found, severity) and _x018(found), found
    code, found = _lint(ws, "--config", "urdfcheck.yaml", "--trust-config")
    assert not _x018(found) and code == 0, found


def test_fail_on_error_with_lowered_severities_says_each_refused_key(tmp_path):
    ws = _ws(tmp_path, "fail_on: error\nseverity: {U002: info, X: info}\n")
    code, found = _lint(ws)
    assert code == 1 and sorted(_x018(found)) == [("urdfcheck.yaml", 1), ("urdfcheck.yaml", 2),
                                                   ("urdfcheck.yaml", 2)], found


def test_a_rule_option_that_loosens_the_check_is_refused(tmp_path):
    ws = _ws(tmp_path, "rules:\n  J007:\n    tolerance: 1.0e+9\n")
    (ws / "bot" / "urdf" / "broken.urdf").write_text(
        '<robot name="r">\n  <link name="base_link"/>\n  <link name="arm"/>\n'
        '  <joint name="j" type="revolute">\n    <axis xyz="0 0 2"/>\n    <parent link="base_link"/>\n'
        '    <child link="arm"/>\n    <limit lower="0" upper="1" effort="1" velocity="1"/>\n  </joint>\n</robot>\n')
    code, found = _lint(ws)
    assert code == 1 and "J007" in [c for c, *_ in found] and _x018(found) == [("urdfcheck.yaml", 3)], found
    code, found = _lint(ws, "--config", "urdfcheck.yaml", "--trust-config")
    assert "J007" not in [c for c, *_ in found], found
    # tightening is anyone's right: kept, no X018
    (ws / "urdfcheck.yaml").write_text("select: [ALL]\nseverity: {J007: error}\nfail_on: info\n"
                                       "rules: {J007: {tolerance: 1.0e-9}}\n")
    code, found = _lint(ws)
    assert code == 1 and ("J007", "bot/urdf/broken.urdf", 5, "error") in found, found
    assert not [c for c in found if c[0] == "X018"], found


@pytest.mark.parametrize("code, option, value, ok", [
    ("J007", "tolerance", 1e-9, True), ("J007", "tolerance", 1e9, False), ("J007", "tolerance", True, False),
    ("I003", "min_mass", 0.0, True), ("I003", "min_mass", 10.0, False),
    ("I003", "allow_singular", False, True), ("I003", "allow_singular", True, True),
    ("F001", "frames", ["map", "odom", "earth"], True), ("F001", "frames", [], False),
    ("F002", "expected", ["base_link"], True), ("F002", "expected", ["chassis"], False),
    ("G001", "ignore", [], True), ("G001", "ignore", ["*"], False),
])
def test_rule_options_tighten_per_type(code, option, value, ok):
    from urdfcheck.request.trust import tightens

    assert tightens(code, option, value) is ok


def test_packages_may_not_point_the_checkouts_own_package_at_a_clean_copy(tmp_path):
    ws = _ws(tmp_path, "packages: {bot: vendor/bot_clean}\n")
    (ws / "bot" / "urdf" / "robot.urdf.xacro").write_text(
        '<robot name="r" xmlns:xacro="http://www.ros.org/wiki/xacro">\n'
        '  <xacro:include filename="$(find bot)/urdf/parts.xacro"/>\n  <xacro:parts/>\n</robot>\n')
    (ws / "bot" / "urdf" / "parts.xacro").write_text(
        '<robot xmlns:xacro="http://www.ros.org/wiki/xacro">\n  <xacro:macro name="parts">\n'
        '    <link name="base_link"/>\n    <link name="arm"/>\n    <joint name="j" type="fixed">\n'
        '      <orign xyz="0 0 1"/>\n      <parent link="base_link"/>\n      <child link="arm"/>\n    </joint>\n'
        '  </xacro:macro>\n</robot>\n')
    (ws / "bot" / "urdf" / "broken.urdf").unlink()
    clean = ws / "vendor" / "bot_clean" / "urdf"
    clean.mkdir(parents=True)
    (clean / "parts.xacro").write_text(
        '<robot xmlns:xacro="http://www.ros.org/wiki/xacro">\n  <xacro:macro name="parts">\n'
        '    <link name="base_link"/>\n  </xacro:macro>\n</robot>\n')
    code, found = _lint(ws, "bot")
    assert code == 1 and ("U002", "bot/urdf/parts.xacro", 6, "warning") in found, found
    assert _x018(found) == [("urdfcheck.yaml", 1)]
    code, found = _lint(ws, "--config", "urdfcheck.yaml", "--trust-config", "bot")
    assert code == 0 and found == [], found
    (ws / "urdfcheck.yaml").write_text("packages: {bot: bot, other: vendor/bot_clean}\n")  # its own folder: fine
    code, found = _lint(ws, "bot")
    assert not _x018(found) and ("U002", "bot/urdf/parts.xacro", 6, "warning") in found, found
    # a clean copy committed under the same name: choosing it is the runner's too
    (ws / "vendor" / "bot_clean" / "package.xml").write_text("<package format='3'><name>bot</name></package>")
    (ws / "urdfcheck.yaml").write_text("packages: {bot: vendor/bot_clean}\n")
    code, found = _lint(ws, "bot")
    assert code == 1 and ("U002", "bot/urdf/parts.xacro", 6, "warning") in found, found
    assert _x018(found) == [("urdfcheck.yaml", 1)]



def test_a_config_naming_the_package_that_holds_it_needs_no_scan(tmp_path, monkeypatch):
    """`packages: {bot: .}` in bot's own config, its models inside bot: zero config resolves that same copy for
    them (the nearest), so the entry is kept without scanning the repository for other copies of bot, even with a
    second copy committed. A model of the config outside bot takes the scan again, and the choice is refused."""
    from urdfcheck.load import packages as pkgs

    scanned = []
    real_scan = pkgs.workspace_packages
    monkeypatch.setattr(pkgs, "workspace_packages", lambda root: scanned.append(str(root)) or real_scan(root))
    ws = _ws(tmp_path, "models:\n  - path: urdf/broken.urdf\npackages: {bot: .}\n", "bot/urdfcheck.yaml")
    (ws / "vendor" / "bot_clean").mkdir(parents=True)
    (ws / "vendor" / "bot_clean" / "package.xml").write_text("<package format='3'><name>bot</name></package>")
    code, found = _lint(ws, "bot")
    assert code == 1 and _has_broken(found) and not _x018(found), found
    assert str(ws) not in scanned
    (ws / "vendor" / "bot_clean" / "urdf").mkdir()
    (ws / "vendor" / "bot_clean" / "urdf" / "clean.urdf").write_text(GOOD)
    (ws / "bot" / "urdfcheck.yaml").write_text("models:\n  - path: urdf/broken.urdf\n"
                                                "  - path: ../vendor/bot_clean/urdf/clean.urdf\npackages: {bot: .}\n")
    code, found = _lint(ws, "bot")
    assert _has_broken(found) and _x018(found) == [("bot/urdfcheck.yaml", 4)], found
    assert str(ws) in scanned


TYPO = """<robot name="r" xmlns:xacro="http://www.ros.org/wiki/xacro">
  <xacro:arg name="typo" default="true"/>
  <link name="base_link"/>
  <link name="arm"/>
  <joint name="j" type="fixed">
    <xacro:if value="$(arg typo)"><orign xyz="0 0 1"/></xacro:if>
    <parent link="base_link"/>
    <child link="arm"/>
  </joint>
</robot>
"""


@pytest.mark.parametrize("spec", ["    args: {typo: 'false'}\n", "    variants: {clean: {typo: 'false'}}\n"])
def test_args_that_replace_a_default_add_a_variant_never_the_defaults_away(tmp_path, spec):
    ws = _ws(tmp_path, "models:\n  - path: bot/urdf/robot.urdf.xacro\n" + spec)
    (ws / "bot" / "urdf" / "broken.urdf").unlink()
    (ws / "bot" / "urdf" / "robot.urdf.xacro").write_text(TYPO)
    code, out, err = run_cli(["lint", "--format", "json"], cwd=ws)
    report = json.loads(out)
    assert code == 1, err
    assert any(f["code"] == "U002" and f["location"]["line"] == 6 for f in report["findings"]), report["findings"]
    assert {m["variant"] for m in report["models"]} >= {"xacro defaults"}
    x018 = [f for f in report["findings"] if f["code"] == "X018"]
    assert [(f["severity"], f["location"]["line"]) for f in x018] == [("info", 3)]
    code, out, _ = run_cli(["lint", "--format", "json", "--config", "urdfcheck.yaml", "--trust-config"], cwd=ws)
    assert code == 0 and json.loads(out)["findings"] == []


# --- a trusted config outside the checkout (the base revision's, in a private temp file) ---------------------------
def test_a_trusted_config_kept_outside_the_checkout(tmp_path):
    ws = _ws(tmp_path)
    private = tmp_path / "private"
    private.mkdir()
    (private / "base.yaml").write_text("models:\n  - path: bot/urdf/broken.urdf\nignore: [U002]\n")
    from urdfcheck.request.request import make_request
    from urdfcheck.run import run

    old = os.getcwd()
    os.chdir(ws)
    try:
        result = run(make_request([], config=str(private / "base.yaml"), trust_config=True, config_root=str(ws)))
        assert result.findings == [] and [t.path.name for t in result.targets] == ["broken.urdf"]
        untrusted = run(make_request([], config=str(private / "base.yaml"), config_root=str(ws)))
        assert {f.code for f in untrusted.findings} == {"U002", "X018"}
    finally:
        os.chdir(old)


# --- the pytest plugin reads the same plan ------------------------------------------------------------------------
def test_the_plugin_gives_the_undeclared_robot_an_item(tmp_path):
    from urdfcheck.plan.plan import plan
    from urdfcheck.request.request import make_request

    ws = _ws(tmp_path, "models:\n  - path: urdf/clean.urdf\n", "bot/urdfcheck.yaml")
    targets = plan(make_request([], root=str(ws / "bot")), here=str(ws / "bot"))  # what the plugin plans
    assert sorted(t.path.name for t in targets) == ["broken.urdf", "clean.urdf"]


# --- discovery: marker files, not folder names --------------------------------------------------------------------
@pytest.mark.parametrize("folder", ["log", "build", "install", "venv", "devel", "node_modules"])
def test_a_package_under_a_plain_output_folder_name_is_linted(tmp_path, folder):
    ws = tmp_path / "ws"
    (ws / "clean" / "urdf").mkdir(parents=True)
    (ws / "clean" / "package.xml").write_text("<package format='3'><name>clean</name></package>")
    (ws / "clean" / "urdf" / "clean.urdf").write_text(GOOD)
    pkg = ws / folder / "bot"
    (pkg / "urdf").mkdir(parents=True)
    (pkg / "package.xml").write_text("<package format='3'><name>bot</name></package>")
    (pkg / "urdf" / "broken.urdf").write_text(BAD)
    code, found = _lint(ws, "--no-config", ".")
    assert code == 1 and ("U002", f"{folder}/bot/urdf/broken.urdf", 5, "warning") in found, found
    marker = {"venv": "pyvenv.cfg", "devel": ".catkin", "node_modules": ".package-lock.json"}.get(folder,
                                                                                                  "COLCON_IGNORE")
    (ws / folder / marker).write_text("")  # what colcon (or venv, catkin, npm) writes there
    code, found = _lint(ws, "--no-config", ".")
    assert code == 0 and found == [], found


# --- whatever robot_state_publisher is given is a robot -----------------------------------------------------------
def test_a_robot_in_an_srdf_named_file_loaded_by_a_launch_file_is_linted(tmp_path):
    ws = _ws(tmp_path)
    (ws / "bot" / "urdf" / "broken.urdf").unlink()
    (ws / "bot" / "urdf" / "robot.srdf.xacro").write_text(TYPO)
    (ws / "bot" / "launch").mkdir()
    (ws / "bot" / "launch" / "bot.launch.xml").write_text(
        "<launch>\n  <node pkg=\"robot_state_publisher\" exec=\"robot_state_publisher\">\n"
        "    <param name=\"robot_description\" "
        "value=\"$(command 'xacro $(find-pkg-share bot)/urdf/robot.srdf.xacro')\"/>\n  </node>\n</launch>\n")
    code, found = _lint(ws, "--no-config", ".")
    assert code == 1 and ("U002", "bot/urdf/robot.srdf.xacro", 6, "warning") in found, found


def test_declared_consumers_add_to_those_found_beside_the_model(tmp_path):
    """A config that declares a model with a clean controllers file does not hide the driver file beside it whose
    wheel separation is wrong: the model is linted again with the consumers zero config finds."""
    import shutil

    from conftest import REPO

    ws = tmp_path / "ws"
    shutil.copytree(REPO / "examples" / "broken" / "contract_wheel_separation", ws)
    (ws / ".git").mkdir()
    (ws / "urdfcheck.yaml").write_text(
        "models:\n  - path: urdf/agv.urdf\n    controllers: [config/agv_controllers.yaml]\n")
    code, found = _lint(ws)
    assert code == 1 and ("C010", "config/agv_driver_ros1.yaml", 7, "warning") in found, found
    code, found = _lint(ws, "--config", "urdfcheck.yaml", "--trust-config")
    assert code == 0 and found == [], found


# --- the other keys an unvouched config sets: each either only adds, or is refused at its key ---------------------
def _example(tmp_path, name: str, config: str):
    """A checkout holding examples/broken/<name>, its urdfcheck.yaml replaced by `config`."""
    import shutil

    from conftest import REPO

    ws = tmp_path / "ws"
    shutil.copytree(REPO / "examples" / "broken" / name, ws)
    (ws / ".git").mkdir()
    (ws / "urdfcheck.yaml").write_text(config)
    return ws


SENSOR = """models:
  - path: urdf/agv.urdf
    controllers: [config/agv_controllers.yaml]
    drivers:
      - file: config/agv_driver_ros1.yaml
        name: agv_base_driver
        joints: [left_wheel_joint, right_wheel_joint]
        left_wheels: [left_wheel_joint]
        right_wheels: [right_wheel_joint]
        wheel_separation: wheel_separation
        wheel_radius: wheel_radius
        frames: [imu_frame_id, laser_frame_id]
        odom_tf: publish_odom_tf
    launch: [launch/agv.launch.xml]
"""
SENSOR_C020 = ("C020", "config/agv_driver_ros1.yaml", 9, "error")  # frame 'imu', the link is imu_link


def test_tf_owners_cannot_publish_a_frame_nobody_publishes(tmp_path):
    """`tf_owners` declares a publisher urdfcheck cannot read: from a config the runner did not vouch for it may add
    a second publisher (a conflict), never make a frame "published" that nothing publishes."""
    ws = _example(tmp_path, "contract_sensor_frame_id", SENSOR + 'tf_owners: {"base_link->imu": imu_driver}\n')
    code, found = _lint(ws)
    assert code == 1 and SENSOR_C020 in found, found
    _, out, _ = run_cli(["lint", "--format", "json"], cwd=ws)
    said = [f["message"] for f in json.loads(out)["findings"] if f["code"] == "C020"]
    assert any("tf_owners" in m and "--trust-config" in m for m in said), said
    code, found = _lint(ws, "--config", "urdfcheck.yaml", "--trust-config")
    assert code == 0 and found == [], found


def test_tf_owners_cannot_join_two_trees(tmp_path):
    """T005: the seed with its controller's odometry TF turned off; its config still declares the controller as the
    owner of odom -> base_link, which joined the two trees. Untrusted, the declaration publishes nothing."""
    import shutil

    from conftest import REPO

    ws = tmp_path / "agv"
    shutil.copytree(REPO / "examples" / "agv", ws)
    (ws / ".git").mkdir()
    ctl = ws / "config" / "agv_controllers.yaml"
    ctl.write_text(ctl.read_text().replace("enable_odom_tf: true", "enable_odom_tf: false"))
    code, found = _lint(ws, "--no-config")
    t005 = sorted({c for c in found if c[0] == "T005"})
    assert t005 and code == 1, found  # what zero config says
    code, found = _lint(ws)
    assert code == 1 and t005 == sorted({c for c in found if c[0] == "T005"}), found
    code, found = _lint(ws, "--config", "urdfcheck.yaml", "--trust-config")
    assert not [c for c in found if c[0] == "T005"], found


def test_tf_owners_that_name_the_publishers_read_add_nothing(tmp_path):
    """The seed's declarations (examples/agv) document the publishers the files start: no finding, no refusal."""
    import shutil

    from conftest import REPO

    ws = tmp_path / "agv"
    shutil.copytree(REPO / "examples" / "agv", ws)
    (ws / ".git").mkdir()
    code, found = _lint(ws)
    assert code == 0 and found == [], found


def test_frames_that_rename_the_rep105_frames_are_refused(tmp_path):
    """`frames:` renames map/odom/base for the F and T rules: renaming `map` took a link named map out of F001."""
    ws = _ws(tmp_path, "frames: {map: world, odom: odom}\n")
    (ws / "bot" / "urdf" / "broken.urdf").write_text(
        '<robot name="r">\n  <link name="base_link"/>\n  <link name="map"/>\n'
        '  <joint name="j" type="fixed">\n    <parent link="map"/>\n    <child link="base_link"/>\n  </joint>\n'
        '</robot>\n')
    code, found = _lint(ws, "--no-config")
    f001 = [c for c in found if c[0] == "F001"]
    assert f001 and code == 1, found
    code, found = _lint(ws)
    assert code == 1 and [c for c in found if c[0] == "F001"] == f001, found
    assert _x018(found) == [("urdfcheck.yaml", 1)], found
    code, found = _lint(ws, "--config", "urdfcheck.yaml", "--trust-config")
    assert not [c for c in found if c[0] == "F001"] and not _x018(found), found
    (ws / "urdfcheck.yaml").write_text("frames: {map: map, odom: odom, base: base_link}\n")  # the defaults: fine
    code, found = _lint(ws)
    assert not _x018(found) and [c for c in found if c[0] == "F001"] == f001, found


def test_a_target_is_the_runners(tmp_path):
    """`target: rolling` made urdfdom 6 judge the model: a URDF 1.1 quaternion origin that Humble's urdfdom refuses
    passed (U007)."""
    ws = _ws(tmp_path, "target: rolling\n")
    (ws / "bot" / "urdf" / "broken.urdf").write_text(
        '<robot name="r" version="1.1">\n  <link name="base_link"/>\n  <link name="arm"/>\n'
        '  <joint name="j" type="fixed">\n    <origin xyz="0 0 0.1" quat_xyzw="0 0 0.7071068 0.7071068"/>\n'
        '    <parent link="base_link"/>\n    <child link="arm"/>\n  </joint>\n</robot>\n')
    code, found = _lint(ws, "--no-config")
    u007 = [c for c in found if c[0] == "U007"]
    assert u007 and code == 1, found
    code, found = _lint(ws)
    assert code == 1 and [c for c in found if c[0] == "U007"] == u007, found
    assert _x018(found) == [("urdfcheck.yaml", 1)], found
    code, found = _lint(ws, "--config", "urdfcheck.yaml", "--trust-config")
    assert code == 0 and found == [], found
    code, found = _lint(ws, "--no-config", "--target", "rolling")  # the runner's flag
    assert code == 0 and found == [], found


def test_profiles_only_add_checks(tmp_path):
    """`profiles:` turns consumer profiles on: a profile's finding goes from info to its severity, and nothing it
    does removes a finding (rules/checks/profiles/common.speak), so an untrusted config may set it."""
    ws = _ws(tmp_path, "profiles: [mujoco, pybullet]\n")
    code, plain = _lint(ws, "--no-config")
    code, found = _lint(ws)
    assert code == 1 and not _x018(found), found
    assert {c[:3] for c in plain} <= {c[:3] for c in found}, (plain, found)


def test_launch_args_add_the_launch_defaults_never_replace_them(tmp_path):
    """The EKF beside the drive controller (both publish odom -> base_link, T001) runs unless `use_ekf` is false:
    the config's `launch_args: {use_ekf: false}` read the launch file without it, and every file of the package
    was declared, so nothing else read it with its default."""
    import re

    ws = _example(tmp_path, "contract_odom_tf_twice",
                  "models:\n  - path: urdf/agv.urdf\n    controllers: [config/agv_controllers.yaml]\n"
                  "    launch: [launch/agv.launch.xml]\n    launch_args: {use_ekf: 'false'}\n")
    (ws / "config" / "ekf.yaml").unlink()
    launch = ws / "launch" / "agv.launch.xml"
    text = launch.read_text().replace("<launch>\n", '<launch>\n  <arg name="use_ekf" default="true"/>\n', 1)
    text = text.replace('name="ekf_filter_node" output="screen">', 'name="ekf_filter_node" output="screen" '
                        'if="$(var use_ekf)">')
    launch.write_text(re.sub(r'<param from="[^"]*ekf.yaml"/>', '<param name="world_frame" value="odom"/>\n'
                             '    <param name="base_link_frame" value="base_link"/>', text))
    code, found = _lint(ws)
    assert code == 1 and ("T001", "config/agv_controllers.yaml", 27, "error") in found, found
    assert ("X018", "urdfcheck.yaml", 5, "info") in found, found
    code, found = _lint(ws, "--config", "urdfcheck.yaml", "--trust-config")
    assert code == 0 and found == [], found


def test_a_frame_prefix_adds_the_launch_defaults_never_replaces_them(tmp_path):
    """A static_transform_publisher in the launch file publishes base_link -> laser_link, which the model publishes
    too (T001); `frame_prefix: r/` renamed the model's frames away from it."""
    ws = _example(tmp_path, "contract_static_tf_duplicate",
                  "models:\n  - path: urdf/agv.urdf\n    controllers: [config/agv_controllers.yaml]\n"
                  "    launch: [launch/agv.launch.xml]\n    frame_prefix: r/\n")
    code, found = _lint(ws)
    assert code == 1 and ("T001", "launch/agv.launch.xml", 32, "error") in found, found
    assert ("X018", "urdfcheck.yaml", 5, "info") in found, found
    code, found = _lint(ws, "--config", "urdfcheck.yaml", "--trust-config")
    assert ("T001", "launch/agv.launch.xml", 32, "error") not in found, found


def test_a_declared_localization_file_does_not_hide_the_driver_beside_it(tmp_path):
    """`localization:` makes a file's node run with the model: a fake EKF file whose base frame is the driver's typo
    'imu' published that frame (the driver's C020 gone; only the fake file's own was said). Declared from an untrusted
    config, the model is also linted with the consumers zero config finds beside it."""
    ws = _example(tmp_path, "contract_sensor_frame_id", SENSOR + "    localization: [fake/ekf.yaml]\n")
    (ws / "fake").mkdir()
    (ws / "fake" / "ekf.yaml").write_text("ekf_filter_node:\n  ros__parameters:\n    world_frame: odom\n"
                                          "    odom_frame: odom\n    base_link_frame: imu\n")
    code, found = _lint(ws)
    assert code == 1 and ("C020", "config/agv_driver_ros1.yaml", 9, "warning") in found, found
    code, found = _lint(ws, "--config", "urdfcheck.yaml", "--trust-config")
    assert [c[:3] for c in found if c[0] == "C020"] == [("C020", "fake/ekf.yaml", 5)], found


# --- declared consumer files that nothing runs with the model: a claim, never a publication -----------------------
FAKE_DRIVE = """controller_manager:
  ros__parameters:
    fake_drive:
      type: diff_drive_controller/DiffDriveController
fake_drive:
  ros__parameters:
    left_wheel_names: [left_wheel_joint]
    right_wheel_names: [right_wheel_joint]
    wheel_separation: 0.50
    wheel_radius: 0.10
    odom_frame_id: odom
    base_frame_id: base_link
    enable_odom_tf: true
"""


def test_a_declared_controller_file_nothing_starts_does_not_join_two_trees(tmp_path):
    """T005: the seed with its controller's odometry TF turned off, and a second controllers file (a drive controller
    with enable_odom_tf) that no launch file loads, declared beside the real one: its odom -> base_link joined the
    trees. Zero config counts only what the launch file starting robot_state_publisher loads."""
    import shutil

    from conftest import REPO

    ws = tmp_path / "agv"
    shutil.copytree(REPO / "examples" / "agv", ws)
    (ws / ".git").mkdir()
    ctl = ws / "config" / "agv_controllers.yaml"
    ctl.write_text(ctl.read_text().replace("enable_odom_tf: true", "enable_odom_tf: false"))
    (ws / "test").mkdir()
    (ws / "test" / "fake.yaml").write_text(FAKE_DRIVE)
    cfg = ws / "urdfcheck.yaml"
    text = cfg.read_text().replace("controllers: [config/agv_controllers.yaml]",
                                   "controllers: [config/agv_controllers.yaml, test/fake.yaml]")
    cfg.write_text(text.split("tf_owners:")[0] + "packages: {agv_description: .}\n")
    code, found = _lint(ws, "--no-config")
    t005 = sorted({c for c in found if c[0] == "T005"})
    assert t005 and code == 1, found  # what zero config says
    code, out, _ = run_cli(["lint", "--format", "json"], cwd=ws)
    said = [f for f in json.loads(out)["findings"] if f["code"] == "T005"]
    assert code == 1 and t005 == sorted({("T005", f["location"]["file"], f["location"]["line"], f["severity"])
                                         for f in said}), said
    assert all("test/fake.yaml" in f["message"] and "--trust-config" in f["message"] for f in said), said
    code, found = _lint(ws, "--config", "urdfcheck.yaml", "--trust-config")  # the runner says it runs
    assert code == 0 and found == [], found
    # the seed's own controllers file, declared without launch files: the model's package, as zero config reads it
    ctl.write_text(ctl.read_text().replace("enable_odom_tf: false", "enable_odom_tf: true"))
    cfg.write_text(cfg.read_text().replace(", test/fake.yaml", "").replace("    launch: [launch/agv.launch.xml]\n", ""))
    code, found = _lint(ws)
    assert code == 0 and found == [], found


def test_a_declared_driver_file_nothing_starts_does_not_publish_a_frame(tmp_path):
    """C020: a second driver declared on a file of three keys, publishing base_link -> imu (the real driver's typo)."""
    ws = _example(tmp_path, "contract_sensor_frame_id", SENSOR.replace(
        "    launch:", "      - file: fake/imu.yaml\n        name: imu_driver\n        odom_tf: publish_tf\n"
                      "        odom_frame: parent_frame\n        base_frame: child_frame\n    launch:"))
    (ws / "fake").mkdir()
    (ws / "fake" / "imu.yaml").write_text("publish_tf: true\nparent_frame: base_link\nchild_frame: imu\n")
    code, found = _lint(ws)
    assert code == 1 and SENSOR_C020 in found, found
    _, out, _ = run_cli(["lint", "--format", "json"], cwd=ws)
    said = [f["message"] for f in json.loads(out)["findings"]
            if (f["code"], f["location"]["file"]) == SENSOR_C020[:2]]
    assert said and "fake/imu.yaml" in said[0] and "--trust-config" in said[0], said
    code, found = _lint(ws, "--config", "urdfcheck.yaml", "--trust-config")
    assert SENSOR_C020 not in found, found


RSP_NODE = """  <node pkg="robot_state_publisher" exec="robot_state_publisher" name="rsp2">
    <param name="robot_description"
           value="$(command 'xacro $(find-pkg-share broken_contract_sensor_frame_id_description)/urdf/agv.urdf')"/>
  </node>
"""


@pytest.mark.parametrize("robot", [False, True], ids=["beside", "a second deployment"])
def test_a_declared_launch_file_does_not_publish_a_frame_for_the_deployment(tmp_path, robot):
    """C020: a launch file with a static_transform_publisher base_link -> imu, declared beside the real one. Zero config
    reads each launch file that starts robot_state_publisher as a deployment of its own, and no other; the config read
    them together. What the declared launch files that start the robot do not all run only claims."""
    both = "launch: [launch/agv.launch.xml, fake/tf.launch.xml]"
    ws = _example(tmp_path, "contract_sensor_frame_id", SENSOR.replace("launch: [launch/agv.launch.xml]", both))
    (ws / "fake").mkdir()
    (ws / "fake" / "tf.launch.xml").write_text(
        "<launch>\n" + (RSP_NODE if robot else "") + '  <node pkg="tf2_ros" exec="static_transform_publisher" '
        'name="imu_tf"\n        args="--frame-id base_link --child-frame-id imu"/>\n</launch>\n')
    code, found = _lint(ws)
    assert code == 1 and SENSOR_C020 in found, found
    code, found = _lint(ws, "--config", "urdfcheck.yaml", "--trust-config")
    assert SENSOR_C020 not in found, found


def test_a_declared_driver_file_nothing_starts_supplies_no_joint_state(tmp_path):
    """C003: a driver declared on a one-key file naming the caster joint nothing publishes a state for."""
    ws = _example(tmp_path, "contract_joint_no_state",
                  "models:\n  - path: urdf/agv.urdf\n    controllers: [config/agv_controllers.yaml]\n"
                  "    drivers:\n      - file: fake/d.yaml\n        name: caster_driver\n        joints: [caster]\n"
                  "    launch: [launch/agv.launch.xml]\n")
    (ws / "fake").mkdir()
    (ws / "fake" / "d.yaml").write_text("caster: rear_caster_swivel_joint\n")
    code, found = _lint(ws, "--no-config")
    c003 = [c for c in found if c[0] == "C003"]
    assert c003 == [("C003", "urdf/agv.urdf", 160, "warning")] and code == 1, found  # what zero config says
    code, found = _lint(ws)
    assert code == 1 and [c for c in found if c[0] == "C003"] == c003, found
    code, found = _lint(ws, "--config", "urdfcheck.yaml", "--trust-config")
    assert code == 0 and found == [], found
