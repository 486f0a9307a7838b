"""Issue 41: ros2_control resources (C022, C023), navigation frames (C024), self-collision at zero (G006).

Each seeded defect is an example package (examples/broken/, checked by test_examples.py); here each one's clean twin
(the one-line fix its model comment names) has no finding of the code, and the cases around each rule's edges
(inactive spawners, conditions, unlaunched files, SRDF entries, adjacency, coal missing) behave as documented."""
import shutil
from pathlib import Path

import pytest
from conftest import REPO, lint_json

BROKEN = REPO / "examples" / "broken"


def _copy(tmp_path, name):
    dst = tmp_path / name
    shutil.copytree(BROKEN / name, dst)
    (dst / "EXPECTED").unlink()
    return dst


def _edit(path: Path, old: str, new: str):
    text = path.read_text(encoding="utf-8")
    assert old in text, old
    path.write_text(text.replace(old, new), encoding="utf-8")


def _codes(folder, code):
    _, report = lint_json([str(folder)])
    return [(Path(f["location"]["file"]).name, f["location"]["line"], f["severity"]) for f in report["findings"]
            if f["code"] == code]


def test_claimed_twice_twin_spawns_inactive(tmp_path):
    pkg = _copy(tmp_path, "ros2control_claimed_twice")
    assert _codes(pkg, "C022") == [("arm.launch.xml", 10, "error")]
    _edit(pkg / "launch" / "arm.launch.xml", 'args="admittance_controller"', 'args="admittance_controller --inactive"')
    assert _codes(pkg, "C022") == []


@pytest.mark.parametrize("flag", ["--stopped", "--load-only"])
def test_claimed_twice_other_inactive_flags(tmp_path, flag):
    pkg = _copy(tmp_path, "ros2control_claimed_twice")
    _edit(pkg / "launch" / "arm.launch.xml", 'args="admittance_controller"', f'args="admittance_controller {flag}"')
    assert _codes(pkg, "C022") == []


def test_claimed_twice_alternatives_behind_a_condition(tmp_path):
    """Spawners behind a launch argument are alternatives: not compared."""
    pkg = _copy(tmp_path, "ros2control_claimed_twice")
    _edit(pkg / "launch" / "arm.launch.xml", '<launch>',
          '<launch>\n  <arg name="admittance" default="false"/>')
    _edit(pkg / "launch" / "arm.launch.xml", 'exec="spawner" args="admittance_controller"',
          'exec="spawner" args="admittance_controller" if="$(var admittance)"')
    assert _codes(pkg, "C022") == []


def test_claimed_twice_one_spawner_names_both(tmp_path):
    pkg = _copy(tmp_path, "ros2control_claimed_twice")
    _edit(pkg / "launch" / "arm.launch.xml", 'args="arm_controller"', 'args="arm_controller admittance_controller"')
    _edit(pkg / "launch" / "arm.launch.xml",
          '  <node pkg="controller_manager" exec="spawner" args="admittance_controller"/>\n', '')
    assert _codes(pkg, "C022") == [("arm.launch.xml", 9, "error")]


def test_claimed_twice_different_interfaces_do_not_conflict(tmp_path):
    pkg = _copy(tmp_path, "ros2control_claimed_twice")
    urdf = pkg / "urdf" / "arm.urdf"
    _edit(urdf, '<joint name="joint2"><command_interface name="position"/>',
          '<joint name="joint2"><command_interface name="position"/><command_interface name="velocity"/>')
    yaml = pkg / "config" / "controllers.yaml"
    text = yaml.read_text(encoding="utf-8")
    head, _, tail = text.partition("admittance_controller:\n  ros__parameters:")
    yaml.write_text(head + "admittance_controller:\n  ros__parameters:" +
                    tail.replace("joints: [joint1, joint2]", "joints: [joint2]").replace(
                        "command_interfaces: [position]", "command_interfaces: [velocity]"), encoding="utf-8")
    assert _codes(pkg, "C022") == []


def test_chained_reference_twin(tmp_path):
    pkg = _copy(tmp_path, "ros2control_chained_reference")
    assert _codes(pkg, "C023") == [("controllers.yaml", 16, "error")]
    _edit(pkg / "config" / "controllers.yaml", "    joints: [joint1]\n", "    joints: [joint1, joint2]\n")
    assert _codes(pkg, "C023") == []


def test_nav2_frame_twin(tmp_path):
    pkg = _copy(tmp_path, "nav2_frame_typo")
    assert _codes(pkg, "C024") == [("nav2_params.yaml", 10, "warning")]
    _edit(pkg / "config" / "nav2_params.yaml", "base_footprnt", "base_footprint")
    assert _codes(pkg, "C024") == []


def test_nav2_frame_unlaunched_is_info(tmp_path):
    """Without a launch file giving a Nav2 node the file, the claim rests on the file lying in the package."""
    pkg = _copy(tmp_path, "nav2_frame_typo")
    (pkg / "launch" / "nav.launch.xml").unlink()
    assert _codes(pkg, "C024") == [("nav2_params.yaml", 10, "info")]


def test_nav2_sensor_frame_and_rep105(tmp_path):
    """An observation source's sensor_frame is checked; map and odom are localization's and never reported."""
    pkg = _copy(tmp_path, "nav2_frame_typo")
    _edit(pkg / "config" / "nav2_params.yaml", "base_footprnt", "base_footprint")
    _edit(pkg / "config" / "nav2_params.yaml", "sensor_frame: laser_link", "sensor_frame: laser_lnk")
    assert _codes(pkg, "C024") == [("nav2_params.yaml", 18, "warning")]


def test_self_collision_twin(tmp_path):
    pytest.importorskip("coal")
    pkg = _copy(tmp_path, "self_collision_home")
    assert _codes(pkg, "G006") == [("arm.urdf", 34, "info")]
    urdf = pkg / "urdf" / "arm.urdf"
    _edit(urdf, '<origin xyz="0 0 -0.25"/>\n      <geometry><box size="0.05 0.05 0.3"/>',
          '<origin xyz="0 0 -0.1"/>\n      <geometry><box size="0.05 0.05 0.1"/>')
    assert _codes(pkg, "G006") == []


def _srdf(pkg, entries):
    (pkg / "config").mkdir(exist_ok=True)
    (pkg / "config" / "arm.srdf").write_text(
        '<?xml version="1.0"?>\n<robot name="home_arm">\n  <group name="arm"><chain base_link="base_link" '
        f'tip_link="link2"/></group>\n{entries}</robot>\n', encoding="utf-8")


def test_self_collision_srdf_of_the_robot(tmp_path):
    """An SRDF of the robot that does not disable the pair makes it a warning; one that does silences it."""
    pytest.importorskip("coal")
    pkg = _copy(tmp_path, "self_collision_home")
    _srdf(pkg, '  <disable_collisions link1="base_link" link2="link1" reason="Adjacent"/>\n')
    assert _codes(pkg, "G006") == [("arm.urdf", 34, "warning")]
    _srdf(pkg, '  <disable_collisions link1="link2" link2="${prefix}base_link" reason="Default"/>\n')
    assert _codes(pkg, "G006") == []


def test_self_collision_limits_exclude_zero(tmp_path):
    """A joint between the links that cannot be at zero: the zero pose of the pair is never reached."""
    pytest.importorskip("coal")
    pkg = _copy(tmp_path, "self_collision_home")
    _edit(pkg / "urdf" / "arm.urdf", '<limit lower="-3" upper="3" effort="10" velocity="1"/>\n  </joint>\n</robot>',
          '<limit lower="0.5" upper="3" effort="10" velocity="1"/>\n  </joint>\n</robot>')
    assert _codes(pkg, "G006") == []


def test_self_collision_adjacent_and_welded_links(tmp_path):
    """Parent and child of a joint, and links welded by fixed joints, are never compared."""
    pytest.importorskip("coal")
    pkg = _copy(tmp_path, "self_collision_home")
    urdf = pkg / "urdf" / "arm.urdf"
    # base_link welded to link1 (joint1 fixed): link2 is then adjacent to the group base_link + link1
    _edit(urdf, '<joint name="joint1" type="revolute">', '<joint name="joint1" type="fixed">')
    assert _codes(pkg, "G006") == []
    # link2 hangs from base_link itself: adjacent; what remains is link2 against its sibling link1
    _edit(urdf, '<joint name="joint1" type="fixed">', '<joint name="joint1" type="revolute">')
    _edit(urdf, '<parent link="link1"/>\n    <child link="link2"/>',
          '<parent link="base_link"/>\n    <child link="link2"/>')
    _, report = lint_json([str(pkg)])
    pairs = [f["message"] for f in report["findings"] if f["code"] == "G006"]
    assert pairs and all("base_link" not in str(p) for p in pairs), pairs


def test_self_collision_without_coal_says_nothing(monkeypatch):
    """Without coal the rule is silent (no crash, no finding)."""
    from urdfcheck.rules import selfcollision

    monkeypatch.setattr(selfcollision, "_coal", lambda: (None, None))
    model = _model(BROKEN / "self_collision_home" / "urdf" / "arm.urdf")
    assert list(selfcollision.self_collisions(model, "", 0.005)) == []
    monkeypatch.undo()
    pytest.importorskip("coal")
    assert len(list(selfcollision.self_collisions(model, "", 0.005))) == 1


def _model(path):
    from urdfcheck.load.loader import load_model

    return load_model(str(path))


def test_nav2_params_file_given_to_nav2_bringup(tmp_path):
    """A launch file of the deployment that includes nav2_bringup with `params_file` runs Nav2 with that file."""
    pkg = _copy(tmp_path, "nav2_frame_typo")
    launch = pkg / "launch" / "nav.launch.xml"
    text = launch.read_text(encoding="utf-8")
    head = text[:text.index('  <node pkg="nav2_controller"')]
    launch.write_text(head + '  <include file="$(find-pkg-share nav2_bringup)/launch/navigation_launch.py">\n'
                      '    <arg name="params_file"'
                      ' value="$(find-pkg-share bot_description)/config/nav2_params.yaml"/>\n'
                      '  </include>\n</launch>\n', encoding="utf-8")
    assert _codes(pkg, "C024") == [("nav2_params.yaml", 10, "warning")]


def test_self_collision_loads_coal_only_for_candidates(tmp_path):
    """The bounding-box test runs first: a model whose shapes cannot interpenetrate by `depth` never imports coal
    (it takes over a second to import); one with a candidate pair does."""
    import subprocess
    import sys

    pytest.importorskip("coal")
    pkg = _copy(tmp_path, "self_collision_home")
    code = ("import sys; from urdfcheck.load.loader import load_model; from urdfcheck.rules import selfcollision as s;"
            "m = load_model(sys.argv[1]); n = len(list(s.self_collisions(m, '', 0.005)));"
            "print(n, 'coal' in sys.modules)")
    env = {"PYTHONPATH": str(REPO / "src"), "PATH": "/usr/bin:/bin"}

    def run():
        out = subprocess.run([sys.executable, "-c", code, str(pkg / "urdf" / "arm.urdf")], capture_output=True,
                             text=True, env=env, check=True)
        return out.stdout.split()

    assert run() == ["1", "True"]
    _edit(pkg / "urdf" / "arm.urdf", '<origin xyz="0 0 -0.25"/>\n      <geometry><box size="0.05 0.05 0.3"/>',
          '<origin xyz="0 0 -0.1"/>\n      <geometry><box size="0.05 0.05 0.1"/>')
    assert run() == ["0", "False"]


def test_amcl_odom_frame_nobody_publishes(tmp_path):
    """AMCL publishes map -> odom_frame_id itself; the odom frame must come from odometry: a frame only AMCL's own
    edge names is reported, REP-105 `odom` never."""
    pkg = _copy(tmp_path, "nav2_frame_typo")
    params = pkg / "config" / "nav2_params.yaml"
    _edit(params, "base_footprnt", "base_footprint")
    params.write_text(params.read_text(encoding="utf-8") + "\namcl:\n  ros__parameters:\n    base_frame_id: "
                      "base_footprint\n    global_frame_id: map\n    odom_frame_id: odom_frame\n", encoding="utf-8")
    _edit(pkg / "launch" / "nav.launch.xml", "</launch>",
          '  <node pkg="nav2_amcl" exec="amcl" name="amcl">\n'
          '    <param from="$(find-pkg-share bot_description)/config/nav2_params.yaml"/>\n  </node>\n</launch>')
    assert _codes(pkg, "C024") == [("nav2_params.yaml", 25, "warning")]
    _edit(params, "odom_frame_id: odom_frame", "odom_frame_id: odom")
    assert _codes(pkg, "C024") == []


@pytest.mark.parametrize("size", ["1e300 1e300 1e300", "inf 1 1", "nan 1 1", "0 0 0"])
def test_self_collision_absurd_sizes_are_skipped(tmp_path, size):
    """A box of no size or of an absurd one is left out: no crash, no finding about it."""
    pkg = _copy(tmp_path, "self_collision_home")
    _edit(pkg / "urdf" / "arm.urdf", '<box size="0.2 0.2 0.1"/>', f'<box size="{size}"/>')
    _, report = lint_json([str(pkg)])
    assert [f for f in report["findings"] if f["code"] in ("G006", "R001")] == []
