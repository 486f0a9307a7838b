"""The deployment TF graph and its analyses (T001..T006), on hand-made claims and on a model."""
import sys
from pathlib import Path

SRC = Path(__file__).resolve().parents[2] / "src"
if str(SRC) not in sys.path:  # runnable without an editable install
    sys.path.insert(0, str(SRC))

from urdfcheck.consumers.tfclaims import (  # noqa: E402
    DYNAMIC,
    STATIC,
    TFClaim,
    claims_from_model,
    claims_from_owners,
    parse_edge,
)
from urdfcheck.core.findings import Location  # noqa: E402
from urdfcheck.model.build import model_from_string  # noqa: E402
from urdfcheck.rules.checks.tf.graph import (  # noqa: E402
    PublisherInfo,
    TFGraph,
    analyze,
    cycles,
    duplicate_owners,
    multiple_parents,
    not_one_tree,
    prefix_collisions,
    static_and_dynamic,
)

MODEL = """<robot name="r">
  <link name="base_link"/><link name="wheel"/><link name="laser"/><link name="float"/><link name="slider"/>
  <joint name="wheel_joint" type="continuous"><parent link="base_link"/><child link="wheel"/></joint>
  <joint name="laser_joint" type="fixed"><parent link="base_link"/><child link="laser"/></joint>
  <joint name="float_joint" type="floating"><parent link="base_link"/><child link="float"/></joint>
  <joint name="slide" type="planar"><parent link="base_link"/><child link="slider"/></joint>
</robot>"""


def L(line, f="launch.xml"):
    return Location(f, line)


def claim(p, c, owner, kind=STATIC, line=1, f="launch.xml", source="launch"):
    return TFClaim(p, c, owner, kind, L(line, f), source)


def test_model_claims():
    m = model_from_string(MODEL, "r.urdf")
    cs = {c.child: c for c in claims_from_model(m)}
    assert set(cs) == {"wheel", "laser", "slider"}  # floating joints are not published
    assert cs["wheel"].kind == DYNAMIC and cs["laser"].kind == STATIC and cs["slider"].kind == STATIC
    assert cs["wheel"].owner == "robot_state_publisher" and cs["wheel"].loc.file == "r.urdf"
    pre = claims_from_model(m, prefix="r1/")
    assert {(c.parent, c.child) for c in pre} >= {("r1/base_link", "r1/wheel")}


def test_duplicate_owner_even_with_equal_values():
    m = model_from_string(MODEL, "r.urdf")
    g = TFGraph().extend(claims_from_model(m))
    g.add(claim("base_link", "/laser", "static_transform_publisher laser_tf", line=7))
    (p,) = duplicate_owners(g)
    assert p.code == "T001"
    assert "robot_state_publisher" in p.message and "static_transform_publisher laser_tf" in p.message
    locs = {c.loc for c in p.claims}
    assert Location("launch.xml", 7) in locs and any(loc.file == "r.urdf" for loc in locs)
    assert not static_and_dynamic(g) and not multiple_parents(g)


def test_two_odometry_publishers():
    g = TFGraph().extend([
        claim("odom", "base_link", "diff_drive_controller", DYNAMIC, 3, "ctrl.yaml", "controller"),
        claim("odom", "base_link", "robot_localization (ekf) /ekf", DYNAMIC, 9, "ekf.yaml", "localization"),
    ])
    (p,) = duplicate_owners(g)
    assert p.at == Location("ctrl.yaml", 3) and p.related == (Location("ekf.yaml", 9),)


def test_static_and_dynamic():
    m = model_from_string(MODEL, "r.urdf")
    g = TFGraph().extend(claims_from_model(m))
    g.add(claim("base_link", "wheel", "static_transform_publisher w"))
    (p,) = static_and_dynamic(g)
    assert p.code == "T002" and p.frames == ("base_link", "wheel")
    assert not duplicate_owners(g)  # mixed kinds are T002, not T001


def test_multiple_parents_and_not_one_tree():
    m = model_from_string(MODEL, "r.urdf")
    g = TFGraph().extend(claims_from_model(m))
    g.add(claim("odom", "base_footprint", "diff_drive_controller", DYNAMIC, source="controller"))
    g.add(claim("base_footprint", "laser", "static_transform_publisher x"))
    (p,) = multiple_parents(g)
    assert p.code == "T003" and p.frames == ("laser",) and "base_link" in p.message and "base_footprint" in p.message
    assert not static_and_dynamic(g) and not duplicate_owners(g)  # T001/T002/T003 do not overlap
    assert not_one_tree(g) == []  # the two-parent frame joins the trees: reported as T003 only
    g2 = TFGraph().extend(claims_from_model(m) + [claim("odom", "base_footprint", "ddc", DYNAMIC, source="controller")])
    (t,) = not_one_tree(g2, {"map": "map", "odom": "odom", "base": "base_link"})
    assert t.code == "T005" and set(t.frames) == {"base_link", "odom"}
    assert "nothing publishes odom -> base_link" in t.message


def test_map_without_odom_link():
    g = TFGraph().extend([claim("map", "odom", "amcl", DYNAMIC), claim("base_link", "laser", "rsp")])
    (t,) = not_one_tree(g)
    assert "odom -> base_link" in t.message
    g2 = TFGraph().extend([claim("odom", "base_link", "ddc", DYNAMIC), claim("map", "odom2", "x")])
    assert not_one_tree(g2)


def test_cycles_reported_once():
    g = TFGraph().extend([claim("a", "b", "x", line=1), claim("b", "c", "x", line=2), claim("c", "a", "y", line=3),
                          claim("c", "d", "x", line=4)])
    (p,) = cycles(g)
    assert p.code == "T004" and set(p.frames) == {"a", "b", "c"} and "->" in p.message
    self_loop = TFGraph().extend([claim("a", "a", "x")])
    assert len(cycles(self_loop)) == 1


def test_one_tree_is_clean():
    m = model_from_string(MODEL, "r.urdf")
    g = TFGraph().extend(claims_from_model(m))
    g.extend([claim("odom", "base_link", "ddc", DYNAMIC), claim("map", "odom", "static_transform_publisher")])
    assert analyze(g, {"map": "map", "odom": "odom", "base": "base_link"}) == []


def test_declared_owners():
    assert parse_edge("map -> odom") == ("map", "odom")
    assert parse_edge("/map->/odom") == ("map", "odom")
    assert parse_edge("map") is None
    owners = claims_from_owners({"map->odom": "amcl"}, {"map->odom": Location("urdfcheck.yaml", 4)})
    g = TFGraph().extend(owners + [claim("map", "odom", "robot_localization (ekf) /ekf", DYNAMIC,
                                         source="localization")])
    (p,) = duplicate_owners(g)
    assert "amcl" in p.message and Location("urdfcheck.yaml", 4) in {c.loc for c in p.claims}


def test_frame_prefix_collisions():
    pubs = [PublisherInfo("rsp1", "", L(3), "/r1"), PublisherInfo("rsp2", "", L(8), "/r2"),
            PublisherInfo("rsp3", "r3/", L(12), "/r3"), PublisherInfo("rsp4", None, L(15))]
    (p,) = prefix_collisions(pubs)
    assert p.code == "T006" and p.at == L(3) and L(8) in p.related
    assert not prefix_collisions(pubs[2:])
