"""F rules: REP-105 localization frames in the URDF, the root link's name."""
from __future__ import annotations

from types import SimpleNamespace

from urdfcheck.core.findings import Severity
from urdfcheck.model.build import model_from_string
from urdfcheck.rules import engine


def run(xml: str, select=("F",), options=None, config=None):
    model = model_from_string(xml, "robot.urdf")
    ctx = engine.Context(selection=engine.Selection(select=tuple(select), options=dict(options or {})),
                         config=config)
    return engine.run_checks(model, ctx)


def codes(findings):
    return sorted(f.code for f in findings)


def chain(*names: str, jtype="fixed") -> str:
    links = "".join(f'<link name="{n}"/>' for n in names)
    joints = "".join(f'<joint name="j{i}" type="{jtype}"><parent link="{a}"/><child link="{b}"/></joint>'
                     for i, (a, b) in enumerate(zip(names, names[1:])))
    return f'<robot name="r">{links}{joints}</robot>'


def test_f001_odom_root():
    found = run(chain("odom", "base_footprint", "base_link"))
    assert codes(found) == ["F001"]  # and no F002: the odom root is F001's finding
    f = found[0]
    assert f.severity == Severity.ERROR and "'odom'" in f.message and "odometry" in f.message
    assert f.location.line == 1 and len(f.related) == 1


def test_f001_map_and_odom():
    found = run(chain("map", "odom", "base_link"))
    assert codes(found) == ["F001", "F001"]
    assert "localization" in found[0].message


def test_f001_odom_below_the_base():
    assert codes(run(chain("base_link", "odom"))) == ["F001"]


def test_f001_namespaced_names():
    assert codes(run(chain("base_link", "robot1/odom"))) == ["F001"]
    assert codes(run(chain("base_link", "${namespace}odom"))) == ["F001"]
    assert run(chain("base_link", "odom_imu_link")) == []


def test_f001_world_root_of_a_fixed_arm_is_normal():
    assert run(chain("world", "base_link", "shoulder_link")) == []


def test_f001_frame_names_from_the_option():
    assert codes(run(chain("base_link", "earth"), options={"F001": {"frames": ["map", "odom", "earth"]}})) == ["F001"]


def test_f001_frame_names_from_the_config():
    cfg = SimpleNamespace(frames={"odom": "wheel_odom", "map": "world_map"})
    assert codes(run(chain("wheel_odom", "base_link"), config=cfg)) == ["F001"]
    assert run(chain("base_link", "odom"), config=cfg) == []  # 'odom' is an ordinary name in this project
    cfg_obj = SimpleNamespace(frames=SimpleNamespace(odom_frame="odom2"))
    assert codes(run(chain("base_link", "odom2"), config=cfg_obj)) == ["F001"]


def test_f002_unexpected_root():
    found = run(chain("chassis", "arm"))
    assert codes(found) == ["F002"] and found[0].severity == Severity.INFO and "'chassis'" in found[0].message


def test_f002_expected_roots():
    for root in ("base_link", "base_footprint", "world", "robot1/base_link", "${namespace}base_footprint",
                 "left_base_link"):
        assert run(chain(root, "arm")) == [], root


def test_f002_option():
    assert run(chain("chassis", "arm"), options={"F002": {"expected": ["chassis"]}}) == []
    assert codes(run(chain("base_link", "arm"), options={"F002": {"expected": ["chassis"]}})) == ["F002"]


def test_f002_base_frame_from_the_config():
    cfg = SimpleNamespace(frames={"map": "map", "odom": "odom", "base": "chassis"})
    assert run(chain("chassis", "arm"), config=cfg) == []


def test_f002_not_with_several_roots():
    assert run('<robot name="r"><link name="a"/><link name="b"/></robot>') == []
