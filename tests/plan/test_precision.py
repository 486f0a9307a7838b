"""Precision on real robots (issue 15): each false positive found on the corpus, reproduced by a small package,
plus one finding per problem across variants and models, and the known-extension registry.

Every test lints a package written to tmp_path with the real command line (zero-config), so each can fail.
"""
import json
import sys
import xml.etree.ElementTree as ET
from pathlib import Path

import pytest

sys.path.insert(0, str(Path(__file__).resolve().parent.parent))

from conftest import lint_json, run_cli  # noqa: E402

from urdfcheck.core.findings import Finding, Location, Place, Severity  # noqa: E402
from urdfcheck.finish.collapse import chains, collapse, describe  # noqa: E402

PACKAGE_XML = """<?xml version="1.0"?>
<package format="3"><name>{name}</name><version>0.1.0</version><description>d</description>
<maintainer email="a@b.c">a</maintainer><license>MIT</license></package>
"""


def write(root: Path, files: dict) -> Path:
    for name, text in files.items():
        p = root / name
        p.parent.mkdir(parents=True, exist_ok=True)
        p.write_text(text, encoding="utf-8")
    return root


def wheel(side: str, y: float, axis: str = "0 1 0", x: float = 0.0, radius: float = 0.05) -> str:
    return f"""
  <link name="{side}_wheel_link">
    <inertial><mass value="1"/><inertia ixx="0.001" ixy="0" ixz="0" iyy="0.001" iyz="0" izz="0.001"/></inertial>
    <collision><origin rpy="1.5708 0 0"/><geometry><cylinder radius="{radius}" length="0.04"/></geometry></collision>
  </link>
  <joint name="{side}_wheel_joint" type="continuous">
    <parent link="base_link"/><child link="{side}_wheel_link"/>
    <origin xyz="{x} {y} 0"/><axis xyz="{axis}"/>
  </joint>"""


def robot(*parts: str, extra: str = "") -> str:
    return ('<?xml version="1.0"?>\n<robot name="bot">\n  <link name="base_link"/>' + "".join(parts) + extra
            + "\n</robot>\n")


def ros2_control(*joints: str) -> str:
    items = "".join(f'<joint name="{j}"><command_interface name="velocity"/><state_interface name="position"/>'
                    f'<state_interface name="velocity"/></joint>' for j in joints)
    return (f'\n  <ros2_control name="hw" type="system"><hardware><plugin>mock_components/GenericSystem</plugin>'
            f'</hardware>{items}</ros2_control>')


RSP_LAUNCH = """from launch import LaunchDescription
from launch_ros.actions import Node


def generate_launch_description():
    return LaunchDescription([
        Node(package="robot_state_publisher", executable="robot_state_publisher"),
{spawners}
    ])
"""


def spawner(*args: str) -> str:
    return (f'        Node(package="controller_manager", executable="spawner", '
            f'arguments={list(args)!r}),')


def codes(report, *wanted):
    return [(f["code"], f["severity"]) for f in report["findings"] if not wanted or f["code"] in wanted]


def finding(report, code):
    hits = [f for f in report["findings"] if f["code"] == code]
    assert len(hits) == 1, report["findings"]
    return hits[0]


# --- C003: joint state sources ------------------------------------------------------------------------
CASTER = """
  <link name="caster_link"/>
  <joint name="caster_joint" type="continuous">
    <parent link="base_link"/><child link="caster_link"/><origin xyz="-0.2 0 0"/><axis xyz="0 0 1"/>
  </joint>"""


def jsb_package(tmp_path, extra_joints: bool) -> Path:
    jsb_params = "joint_state_broadcaster:\n  ros__parameters:\n    extra_joints: [caster_joint]\n" \
        if extra_joints else ""
    return write(tmp_path / ("with" if extra_joints else "without"), {
        "package.xml": PACKAGE_XML.format(name="bot_description"),
        "urdf/bot.urdf": robot(wheel("left", 0.2), wheel("right", -0.2), CASTER,
                               extra=ros2_control("left_wheel_joint", "right_wheel_joint")),
        "config/controllers.yaml": (
            "controller_manager:\n  ros__parameters:\n    update_rate: 50\n"
            "    joint_state_broadcaster:\n      type: joint_state_broadcaster/JointStateBroadcaster\n"
            + jsb_params),
    })


def test_c003_extra_joints_of_the_joint_state_broadcaster_are_a_state_source(tmp_path):
    _, without = lint_json([jsb_package(tmp_path, extra_joints=False)])
    assert "caster_joint" in finding(without, "C003")["message"]  # the caster has no hardware: nobody covers it
    _, with_extra = lint_json([jsb_package(tmp_path, extra_joints=True)])
    assert codes(with_extra, "C003") == []  # published with a zero state by joint_state_broadcaster


def launch_typed_package(tmp_path, typed: bool) -> Path:
    """Controller types only on the spawner's command line (`-t`), none in the YAML."""
    jsb = spawner("joint_state_broadcaster", "-t", "joint_state_broadcaster/JointStateBroadcaster") if typed \
        else spawner("joint_state_broadcaster")
    dd = spawner("diffbot_base_controller", "--controller-type", "diff_drive_controller/DiffDriveController") \
        if typed else spawner("diffbot_base_controller")
    return write(tmp_path / ("typed" if typed else "untyped"), {
        "package.xml": PACKAGE_XML.format(name="bot_description"),
        "urdf/bot.urdf": robot(wheel("left", 0.2), wheel("right", -0.2),
                               extra=ros2_control("left_wheel_joint", "right_wheel_joint")),
        "config/controllers.yaml": (
            "controller_manager:\n  ros__parameters:\n    update_rate: 50\n"
            "diffbot_base_controller:\n  ros__parameters:\n"
            "    left_wheel_names: [left_wheel_joint]\n    right_wheel_names: [right_wheel_joint]\n"
            "    wheel_separation: 0.30\n    wheel_radius: 0.05\n"),
        "launch/bringup.launch.py": RSP_LAUNCH.format(spawners="\n".join([jsb, dd])),
    })


def test_controller_types_set_in_a_launch_file(tmp_path):
    from urdfcheck.consumers.consumers import discover_consumers
    from urdfcheck.load.loader import load_model

    pkg = launch_typed_package(tmp_path, typed=True)
    model = load_model(str(pkg / "urdf/bot.urdf"))
    c = discover_consumers(str(pkg / "urdf/bot.urdf"), model)
    kinds = {ctrl.name: ctrl.kind for ctrl in c.controllers}
    assert kinds == {"diffbot_base_controller": "diff_drive", "joint_state_broadcaster": "joint_state_broadcaster"}
    assert c.controllers.by_name("diffbot_base_controller").drive is not None
    untyped = launch_typed_package(tmp_path, typed=False)
    c = discover_consumers(str(untyped / "urdf/bot.urdf"), load_model(str(untyped / "urdf/bot.urdf")))
    assert len(c.controllers) == 0  # no type anywhere: not a controller


def test_controller_types_set_in_a_launch_file_end_to_end(tmp_path):
    _, report = lint_json([launch_typed_package(tmp_path, typed=True)])
    got = codes(report, "C003", "C010")
    assert ("C010", "error") in got, report["findings"]  # the diff drive is checked: 0.30 m vs 0.4 m
    assert all(c != "C003" for c, _ in got)  # the broadcaster typed by its spawner covers the wheels


def test_c003_not_reported_when_no_launch_file_starts_robot_state_publisher(tmp_path):
    """ros_controllers' test robots: a controller YAML and a launch file that spawns controllers for a
    hardware simulator, no robot_state_publisher, so nothing needs joint states."""
    files = {
        "package.xml": PACKAGE_XML.format(name="bot_control"),
        "urdf/bot.urdf": robot(wheel("left", 0.2), wheel("right", -0.2)),
        "config/controllers.yaml": ("diffbot_controller:\n  type: diff_drive_controller/DiffDriveController\n"
                                    "  left_wheel: left_wheel_joint\n  right_wheel: right_wheel_joint\n"
                                    "  wheel_separation: 0.4\n  wheel_radius: 0.05\n"),
        "launch/test.launch": ('<launch>\n  <rosparam command="load" file="$(find bot_control)/config/'
                               'controllers.yaml"/>\n  <node name="spawner" pkg="controller_manager" type="spawner"'
                               ' args="diffbot_controller"/>\n</launch>\n'),
    }
    _, report = lint_json([write(tmp_path / "norsp", files)])
    assert codes(report, "C003") == [], report["findings"]
    files["launch/test.launch"] = files["launch/test.launch"].replace(
        "</launch>", '  <node name="rsp" pkg="robot_state_publisher" type="robot_state_publisher"/>\n</launch>')
    _, report = lint_json([write(tmp_path / "rsp", files)])
    assert [c for c, _ in codes(report, "C003")] == ["C003"], report["findings"]


# --- C010 / C011: declared slip factors -------------------------------------------------------------------
def skid_package(tmp_path, name: str, separation: float, multiplier: str, radius_mult: str = "1.0") -> Path:
    return write(tmp_path / name, {
        "package.xml": PACKAGE_XML.format(name="skid_description"),
        "urdf/skid.urdf": robot(wheel("fl", 0.25, x=0.2), wheel("rl", 0.25, x=-0.2),
                                wheel("fr", -0.25, x=0.2), wheel("rr", -0.25, x=-0.2),
                                extra=ros2_control(*(f"{w}_wheel_joint" for w in ("fl", "rl", "fr", "rr")))),
        "config/controllers.yaml": (
            "controller_manager:\n  ros__parameters:\n    update_rate: 50\n"
            "    joint_state_broadcaster:\n      type: joint_state_broadcaster/JointStateBroadcaster\n"
            "    base_controller:\n      type: diff_drive_controller/DiffDriveController\n"
            "base_controller:\n  ros__parameters:\n"
            "    left_wheel_names: [fl_wheel_joint, rl_wheel_joint]\n"
            "    right_wheel_names: [fr_wheel_joint, rr_wheel_joint]\n"
            f"    wheel_separation: {separation}\n    wheel_radius: 0.05\n"
            f"    wheel_separation_multiplier: {multiplier}\n"
            f"    left_wheel_radius_multiplier: {radius_mult}\n    right_wheel_radius_multiplier: {radius_mult}\n"),
    })


@pytest.mark.parametrize("multiplier", ["1.875", "1.5"])
def test_c010_skid_steer_slip_factor_is_information(tmp_path, multiplier):
    code, report = lint_json([skid_package(tmp_path, "skid" + multiplier, 0.5, multiplier)])
    f = finding(report, "C010")
    assert f["severity"] == "info"
    assert "matches" in f["message"] and f"wheel_separation_multiplier {multiplier}" in f["message"]
    assert "slip" in f["message"]
    assert code == 0  # nothing at or above the default --fail-on warning


def test_c010_slip_factor_with_a_base_separation_off_the_model(tmp_path):
    _, report = lint_json([skid_package(tmp_path, "off", 0.45, "1.5")])
    f = finding(report, "C010")
    assert f["severity"] == "info" and "differs" in f["message"] and "by 0.05 m" in f["message"]


def test_c010_without_multiplier_is_still_an_error(tmp_path):
    _, report = lint_json([skid_package(tmp_path, "plain", 0.45, "1.0")])
    assert finding(report, "C010")["severity"] == "error"


def test_c011_radius_multiplier_is_information(tmp_path):
    _, report = lint_json([skid_package(tmp_path, "rmult", 0.5, "1.0", radius_mult="1.05")])
    f = [x for x in report["findings"] if x["code"] == "C011"]
    assert f and all(x["severity"] == "info" for x in f), report["findings"]
    assert len(f) == 2  # one per side, not one per wheel
    assert "1.05 x 0.05 = 0.0525 m" in f[0]["message"]


def test_c011_prints_the_number_of_an_optenv_parameter(tmp_path):
    pkg = write(tmp_path / "ros1", {
        "package.xml": PACKAGE_XML.format(name="bot_control"),
        "urdf/bot.urdf": robot(wheel("left", 0.2, radius=0.06), wheel("right", -0.2, radius=0.06)),
        "config/controllers.yaml": ("diffbot_controller:\n  type: diff_drive_controller/DiffDriveController\n"
                                    "  left_wheel: left_wheel_joint\n  right_wheel: right_wheel_joint\n"
                                    "  wheel_separation: 0.4\n  wheel_radius: $(optenv WHEEL_RADIUS 0.05)\n"),
    })
    _, report = lint_json([pkg])
    msgs = [f["message"] for f in report["findings"] if f["code"] == "C011"]
    assert msgs, report["findings"]
    assert all("0.05 (the default of $(optenv WHEEL_RADIUS))" in m for m in msgs)
    assert not any("$(optenv WHEEL_RADIUS 0.05)" in m for m in msgs)


# --- launch files and YAML given as paths ----------------------------------------------------------------
def test_launch_and_yaml_paths_are_not_models(tmp_path):
    pkg = launch_typed_package(tmp_path, typed=True)
    for p in ("launch/bringup.launch.py", "config/controllers.yaml"):
        code, out, err = run_cli(["lint", "--format", "json", "--no-config", pkg / p])
        assert code in (0, 1, 2), err
        if code == 2:  # refused with a message is fine; a model finding computed against it is not
            assert "Traceback" not in err
            continue
        report = json.loads(out)
        bad = [f for f in report["findings"] if f["code"] in ("U001", "X001", "C001", "C020")]
        assert bad == [], (p, bad)


# --- known extensions -------------------------------------------------------------------------------------
EXTENSIONS = """<?xml version="1.0"?>
<robot name="ext">
  <mujoco><compiler discardvisual="false"/></mujoco>
  <link name="base_link">
    <contact><lateral_friction value="1.0"/></contact>
    <collision concave="true" group="1" mask="1"><geometry><box size="1 1 1"/></geometry></collision>
  </link>
  <link name="l1">
    <inertial><mass value="1"/><inertia ixx="0.1" ixy="0" ixz="0" iyy="0.1" iyz="0" izz="0.1"/></inertial>
  </link>
  <joint name="j1" type="revolute" dont_collapse="true">
    <parent link="base_link"/><child link="l1"/><axis xyz="0 0 1"/>
    <limit lower="-1" upper="1" effort="1" velocity="1"/>
    <dynamics damping="0.1" friction="0.1" D="1" K="2" mu_coulomb="0.3" mu_viscous="0.2"/>
  </joint>
</robot>
"""


def test_known_extensions_are_silent(tmp_path):
    (tmp_path / "ext.urdf").write_text(EXTENSIONS)
    _, report = lint_json([tmp_path / "ext.urdf"])
    assert codes(report, "U002", "U003") == [], report["findings"]


@pytest.mark.parametrize("typo, hint", [
    ('<dynamcis damping="0.1"/>', "dynamics"),
    ('<intertial><mass value="1"/></intertial>', "inertial"),
])
def test_near_misses_of_known_names_are_still_typos(tmp_path, typo, hint):
    text = EXTENSIONS.replace('<link name="l1">', f'<link name="l1">{typo}' if "intertial" in typo else
                              '<link name="l1">').replace('<axis xyz="0 0 1"/>', '<axis xyz="0 0 1"/>' + (
                                  typo if "dynamcis" in typo else ""))
    (tmp_path / "typo.urdf").write_text(text)
    _, report = lint_json([tmp_path / "typo.urdf"])
    f = finding(report, "U002")
    assert f"did you mean '{hint}'" in f["message"]


def test_near_miss_of_an_extension_attribute_names_it(tmp_path):
    (tmp_path / "a.urdf").write_text(EXTENSIONS.replace("mu_coulomb=", "mu_coulmb="))
    _, report = lint_json([tmp_path / "a.urdf"])
    assert "did you mean 'mu_coulomb'" in finding(report, "U003")["message"]


def test_srdf_xacro_is_not_a_model(tmp_path):
    pkg = write(tmp_path / "moveit_config", {
        "package.xml": PACKAGE_XML.format(name="bot_moveit_config"),
        "config/bot.srdf.xacro": ('<?xml version="1.0"?>\n<robot xmlns:xacro="http://www.ros.org/wiki/xacro" '
                                  'name="bot">\n  <group name="arm"><chain base_link="a" tip_link="b"/></group>\n'
                                  '  <disable_collisions link1="a" link2="b" reason="Adjacent"/>\n</robot>\n'),
        "config/bot.urdf": robot(),
    })
    _, report = lint_json([pkg])
    assert [Path(m["path"]).name for m in report["models"]] == ["bot.urdf"]
    assert codes(report, "U002", "S011") == []


def test_passive_joint_with_zero_effort_is_not_j004(tmp_path):
    spring = ('\n  <link name="drop"/>\n  <joint name="drop_joint" type="prismatic"><parent link="base_link"/>'
              '<child link="drop"/><axis xyz="0 0 1"/><limit lower="0" upper="0.01" effort="0" velocity="0"/>'
              '</joint>')
    (tmp_path / "p.urdf").write_text(robot(spring))
    _, report = lint_json([tmp_path / "p.urdf"])
    assert codes(report, "J004") == []
    (tmp_path / "a.urdf").write_text(robot(spring, extra=ros2_control("drop_joint")))
    _, report = lint_json([tmp_path / "a.urdf"])
    assert [c for c, _ in codes(report, "J004")] == ["J004", "J004"]  # actuated: the zeros are placeholders


# --- one finding per problem -------------------------------------------------------------------------------
def f(msg="joint 'a' is bad", model="m.xacro", variant="", line=3, code="S003", via=()):
    return Finding(code, Severity.ERROR, msg, Location("lib.xacro", line, None, via), "x", (), model, variant)


def test_collapse_identical_findings_across_variants():
    names = [f"v{i}=true" for i in range(12)]
    out = collapse([f(variant=v) for v in names] + [f(line=9, variant="v0=true")])
    assert len(out) == 2
    one = [x for x in out if x.location.line == 3][0]
    assert [p.variant for p in one.where] == names
    assert describe(one, {"m.xacro": 16}) == "in 12 of 16 variants: v0=true, v1=true, v2=true, …"
    assert describe(one, {"m.xacro": 12}) == ""  # in every variant: no label needed


def test_collapse_across_models_modulo_the_prefix():
    out = collapse([f("joint 'fer_hand' names parent 'fer_link8'", model="fer.xacro"),
                    f("joint 'fr3_hand' names parent 'fr3_link8'", model="fr3.xacro"),
                    f("joint 'fp3_hand' names parent 'fp3_link8'", model="fp3.xacro")])
    (one,) = out
    assert describe(one) == "in 3 models: fer.xacro, fr3.xacro, fp3.xacro"
    assert one.where[1] == Place("fr3.xacro", "", "joint 'fr3_hand' names parent 'fr3_link8'")
    # urdfdom's own words, quoted in the message, name them in brackets
    (one,) = collapse([f("joint 'a_j' ('parent link [a_l8] of joint [a_j] not found')", model="a.xacro"),
                       f("joint 'b_j' (did you mean 'b_x'?) ('parent link [b_l8] of joint [b_j] not found')",
                         model="b.xacro")])
    assert describe(one) == "in 2 models: a.xacro, b.xacro"


def test_collapse_merges_instances_in_one_model_but_not_different_problems():
    left = f("inertia of 'left_wheel' is bad", via=(Location("robot.xacro", 55),))
    right = f("inertia of 'right_wheel' is bad", via=(Location("robot.xacro", 56),))
    (one,) = collapse([left, right])  # two macro calls, one line to fix
    assert one.message == left.message and describe(one) == "also 'right_wheel'"
    many = collapse([f(f"link 'link{i}' is defined again", variant="no_prefix=true") for i in range(10)])
    assert len(many) == 1 and describe(many[0], {"m.xacro": 4}).startswith(
        "also 'link1', 'link2', 'link3' and 6 more; variant no_prefix=true")
    assert len(collapse([f("effort limit 0"), f("velocity limit 0")])) == 2  # different text: different problems
    assert len(collapse([f(code="S003"), f(code="S004")])) == 2
    assert chains(one) == [(Location("robot.xacro", 55),), (Location("robot.xacro", 56),)]


def test_text_line_of_merged_instances_lists_each_macro_call(tmp_path):
    # the line to fix is the macro's; the calls say which wheels it hits (both must stay visible after merging)
    _, out, _ = run_cli(["lint", "--no-config", Path(__file__).resolve().parents[2] / "examples/broken/xacro_macro"])
    (line,) = [x for x in out.splitlines() if " I004 " in x]
    assert line.endswith("(via agv.urdf.xacro:55; agv.urdf.xacro:56)") and "also 'right_wheel_link'" in line


def multi_variant_package(tmp_path) -> Path:
    """A xacro with 4 boolean args (16 variants) and one problem that does not depend on them."""
    args = "".join(f'<xacro:arg name="a{i}" default="false"/>' for i in range(4))
    return write(tmp_path / "mv", {
        "package.xml": PACKAGE_XML.format(name="mv_description"),
        "urdf/mv.urdf.xacro": (f'<?xml version="1.0"?>\n<robot name="mv" xmlns:xacro="http://www.ros.org/wiki/'
                               f'xacro">{args}\n  <link name="base_link"/>\n  <link name="l"/>\n'
                               f'  <joint name="j" type="fixed"><parent link="base_link"/><child link="l"/>'
                               f'<origin xyz="0 0 0" rpy="0 0 0" xzy="1"/></joint>\n</robot>\n'),
    })


def test_one_line_per_problem_in_every_format(tmp_path):
    pkg = multi_variant_package(tmp_path)
    code, out, _ = run_cli(["lint", "--no-config", pkg])
    lines = [x for x in out.splitlines() if " U003 " in x]
    assert len(lines) == 1 and "[" not in lines[0].split("U003", 1)[1]  # all 16 variants: no label
    _, report = lint_json([pkg])
    (u,) = [x for x in report["findings"] if x["code"] == "U003"]
    assert len(u["where"]) == 16 and len({w["variant"] for w in u["where"]}) == 16
    assert max(len(w["variant"]) for w in u["where"]) <= len("a0=true,a1=true,a2=true,a3=true")
    _, sarif, _ = run_cli(["lint", "--no-config", "--format", "sarif", pkg])
    assert [r["ruleId"] for r in json.loads(sarif)["runs"][0]["results"]].count("U003") == 1
    _, junit, _ = run_cli(["lint", "--no-config", "--format", "junit", pkg])
    failures = [e.text for e in ET.fromstring(junit).iter("failure")] + \
        [e.text for e in ET.fromstring(junit).iter("system-out")]
    assert sum(t.count("U003") for t in failures if t) == 1
    _, md, _ = run_cli(["lint", "--no-config", "--format", "markdown", pkg])
    rows = [x for x in md.splitlines() if x.startswith("| ") and "mv.urdf.xacro" in x and "U003" not in x]
    assert len(rows) == 16 and all(r.rstrip().endswith("| 0 | 1 | 0 |") for r in rows), rows  # no bogus row
    assert sum(1 for x in md.splitlines() if "**U003**" in x) == 1
    _, gh, _ = run_cli(["lint", "--no-config", "--format", "github", pkg])
    assert sum(1 for x in gh.splitlines() if "U003" in x) == 1


def test_collapse_across_models_names_the_variants_when_not_all():
    out = collapse([f("joint 'fer_hand' bad", model="fer.xacro", variant="no_prefix=true"),
                    f("joint 'fr3_hand' bad", model="fr3.xacro", variant="no_prefix=true")])
    (one,) = out
    want = "in 2 models: fer.xacro, fr3.xacro; variant no_prefix=true"
    assert describe(one, {"fer.xacro": 10, "fr3.xacro": 10}) == want
    assert describe(one) == "in 2 models: fer.xacro, fr3.xacro; variant no_prefix=true"  # totals unknown


def test_deployment_labels_are_shown_by_file_name():
    v = ["pkg/launch/a.launch.py", "pkg/launch/a.launch.py [sim=true]", "pkg/launch/b.launch.py"]
    (one,) = collapse([f(variant=x) for x in v])
    assert describe(one, {"m.xacro": 4}) == "in 3 of 4 variants: a.launch.py, a.launch.py [sim=true], b.launch.py"


def test_c003_gazebo_diff_drive_publishing_wheel_tf_is_a_source(tmp_path):
    plugin = ('\n  <gazebo><plugin name="dd" filename="libgazebo_ros_diff_drive.so"><left_joint>left_wheel_joint'
              '</left_joint><right_joint>right_wheel_joint</right_joint><publish_wheel_tf>{}</publish_wheel_tf>'
              '</plugin></gazebo>')
    files = {
        "package.xml": PACKAGE_XML.format(name="bot_description"),
        "launch/sim.launch.py": RSP_LAUNCH.format(spawners=""),
    }
    for flag, want in (("true", []), ("false", ["C003"])):
        files["urdf/bot.urdf"] = robot(wheel("left", 0.2), wheel("right", -0.2), extra=plugin.format(flag))
        _, report = lint_json([write(tmp_path / flag, files)])
        assert [c for c, _ in codes(report, "C003")] == want, report["findings"]


def test_a_xacro_that_can_produce_no_link_is_a_fragment(tmp_path):
    """ros2_control_demos' diffbot.materials.xacro: materials only, included by robots of other packages."""
    pkg = write(tmp_path / "desc", {
        "package.xml": PACKAGE_XML.format(name="demo_description"),
        "urdf/bot.materials.xacro": ('<?xml version="1.0"?>\n<robot xmlns:xacro="http://www.ros.org/wiki/xacro">\n'
                                     '  <material name="blue"><color rgba="0 0 1 1"/></material>\n</robot>\n'),
        "urdf/bot.urdf.xacro": ('<?xml version="1.0"?>\n<robot name="bot" xmlns:xacro="http://www.ros.org/wiki/'
                                'xacro">\n  <link name="base_link"/>\n</robot>\n'),
    })
    _, report = lint_json([pkg])
    assert [Path(m["path"]).name for m in report["models"]] == ["bot.urdf.xacro"]
    assert codes(report, "S011") == []


def test_the_same_problem_at_several_lines_of_a_file_is_one_line(tmp_path):
    # ANYmal names twelve joints like their links; fanuc leaves six effort limits at 0: one line each, every
    # place kept (JSON `also`, SARIF related locations)
    joints = "".join(f'<link name="l{i}"/><joint name="l{i}" type="fixed"><parent link="base_link"/>'
                     f'<child link="l{i}"/></joint>\n' for i in range(1, 6))
    urdf = write(tmp_path, {"robot.urdf": f'<robot name="r">\n<link name="base_link"/>\n{joints}</robot>\n'})
    path = urdf / "robot.urdf"
    _, out, _ = run_cli(["lint", "--no-config", "--select", "S010", path])
    (line,) = [x for x in out.splitlines() if " S010 " in x]
    assert line.split()[0].endswith("robot.urdf:3")
    assert "also 'l2', 'l3', 'l4' and 1 more at lines 4, 5, 6, …" in line
    _, report = lint_json(["--select", "S010", path], flat=False)
    (f,) = report["findings"]
    assert [a["location"]["line"] for a in f["also"]] == [4, 5, 6, 7]
    assert [a["message"].split("'")[1] for a in f["also"]] == ["l2", "l3", "l4", "l5"]
    _, sarif, _ = run_cli(["lint", "--no-config", "--select", "S010", "--format", "sarif", path])
    (res,) = json.loads(sarif)["runs"][0]["results"]
    assert [r["physicalLocation"]["region"]["startLine"] for r in res["relatedLocations"]][-4:] == [4, 5, 6, 7]


def test_different_models_or_variants_at_other_lines_stay_apart():
    a = f("joint 'a' has effort limit 0")._replace(location=Location("m.urdf", 3))
    b = f("joint 'b' has effort limit 0")._replace(location=Location("m.urdf", 4))
    (one,) = collapse([a, b])
    assert [x.location.line for x in one.also] == [4] and describe(one) == "also 'b' at line 4"
    c = b._replace(variant="use_arm=true")  # found in another variant only: its own line, with its label
    assert len(collapse([a, c])) == 2


def test_models_with_the_same_file_name_are_told_apart():
    a = f(model="moveit/panda_description/urdf/panda.urdf.xacro")
    b = f(model="moveit/panda_moveit_config/config/panda.urdf.xacro")
    (one,) = collapse([a, b])
    assert describe(one) == "in 2 models: urdf/panda.urdf.xacro, config/panda.urdf.xacro"


def test_a_missing_file_named_without_quotes_is_the_same_problem_in_each_variant():
    # the UR driver's launch files offer robot types whose visual_parameters.yaml the description lacks:
    # the same line fails in five variants, each naming its own file
    msgs = [f"No such file or directory: ur/config/{t}/visual_parameters.yaml" for t in ("ur12e", "ur15")]
    (one,) = collapse([f(m, code="X010", variant=v) for m, v in zip(msgs, ("ur12e.launch.py", "ur15.launch.py"))])
    assert [p.message or one.message for p in one.places()] == msgs


def test_a_gazebo_block_inside_a_link_says_gazebo_loses_it_too(tmp_path):
    # rosbot's body.urdf.xacro: parser_urdf.cc walks only robot->FirstChildElement("gazebo")
    urdf = write(tmp_path, {"r.urdf": '<robot name="r">\n<link name="base_link">\n  <gazebo><mu1>0.5</mu1></gazebo>\n'
                                      '</link>\n<gazebo reference="base_link"><mu1>0.5</mu1></gazebo>\n</robot>\n'})
    _, report = lint_json(["--select", "U002", urdf / "r.urdf"])
    (u,) = report["findings"]
    assert u["location"]["line"] == 3 and "Gazebo reads <gazebo> only directly under <robot>" in u["message"]


def test_a_material_on_collision_geometry_is_information_not_a_warning(tmp_path):
    # baxter, solo, tiago, centauro (example-robot-data) and robotiq: nothing reads it, and nothing could
    urdf = write(tmp_path, {"r.urdf": '<robot name="r">\n<link name="base_link"><collision><material name="x"/>'
                                      '<geometry><box size="1 1 1"/></geometry></collision>\n'
                                      '<visual><geometry><box size="1 1 1"/></geometry><surface/></visual></link>\n'
                                      '</robot>\n'})
    code, report = lint_json([urdf / "r.urdf"])
    got = {(f["location"]["line"], f["severity"]) for f in report["findings"] if f["code"] == "U002"}
    assert got == {(2, "info"), (3, "warning")} and code == 1  # an unknown element in <visual> still warns
