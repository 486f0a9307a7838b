"""robot_state_publisher's own test models (values its C++ tests expect), and agreement with yourdfpy on real models."""
import math
from pathlib import Path

import pytest

from urdfcheck.model.build import model_from_string
from urdfcheck.publisher import (
    JointState,
    StatePublisher,
    TransformLookupError,
    configuration_joints,
    link_poses,
    lookup,
)

EPS = 0.01  # the C++ tests' tolerance


def _model(corpus, *parts):
    p = corpus.joinpath(*parts)
    if not p.is_file():
        pytest.skip(f"{p} not in the corpus")
    return model_from_string(p.read_text(), str(p))


def test_two_links_fixed_joint(corpus):
    m = _model(corpus, "ros+robot_state_publisher", "test", "two_links_fixed_joint.urdf")
    pub = StatePublisher(m)
    (t,) = pub.startup(0.0)["/tf_static"]
    assert (t.parent, t.child) == ("link1", "link2")
    assert t.translation == pytest.approx((5.0, 0.0, 0.0), abs=EPS)
    assert t.rotation == pytest.approx((0.0, 0.0, math.sin(0.785), math.cos(0.785)), abs=1e-12)
    # test_two_joints: lookupTransform("link1", "link2") ~ (5, 0, 0); base_link/wim_link do not exist
    assert lookup(m, "link1", "link2").translation == pytest.approx((5.0, 0.0, 0.0), abs=EPS)
    with pytest.raises(TransformLookupError):
        lookup(m, "base_link", "wim_link")


def test_two_links_fixed_joint_prefix(corpus):
    m = _model(corpus, "ros+robot_state_publisher", "test", "two_links_fixed_joint.urdf")
    pub = StatePublisher(m, frame_prefix="my_prefix/")  # the launch file's parameter
    (t,) = pub.static_transforms()
    assert (t.parent, t.child) == ("my_prefix/link1", "my_prefix/link2")
    assert t.translation == pytest.approx((5.0, 0.0, 0.0), abs=EPS)


def test_two_links_moving_joint(corpus):
    m = _model(corpus, "ros+robot_state_publisher", "test", "two_links_moving_joint.urdf")
    pub = StatePublisher(m)
    assert pub.static_transforms() == []
    (t,) = pub.on_joint_state(JointState(["joint1"], [math.pi], 1.0))
    assert (t.parent, t.child) == ("link1", "link2")
    assert t.translation == pytest.approx((5.0, 0.0, 0.0), abs=EPS)
    # continuous about x (default axis) by pi after a yaw of 1.57
    expected = (math.cos(0.785), math.sin(0.785), 0.0, 0.0)
    assert t.rotation == pytest.approx(expected, abs=1e-6)
    assert lookup(m, "link1", "link2", {"joint1": math.pi}).translation == pytest.approx((5.0, 0.0, 0.0), abs=EPS)


def test_mimic_joint_model_and_description_change(corpus):
    m = _model(corpus, "ros+robot_state_publisher", "test", "mimic_joint.urdf")
    pub = StatePublisher(m)
    st = {t.child: t for t in pub.static_transforms()}
    assert set(st) == {"second_link", "third_link"}
    for t in st.values():
        assert t.parent == "base_link"
        assert t.translation == pytest.approx((0.0, 1.0, 0.0))
        assert t.rotation == pytest.approx((math.sin(0.5), 0.0, 0.0, math.cos(0.5)))
    assert pub.on_joint_state(JointState(["base_to_second_joint"], [0.3], 1.0)) == []
    assert any(n.code == "mimic-not-movable" for n in pub.notes)
    # test_change_mimic_joint: the description is replaced by a single link: nothing to publish, no error
    one = StatePublisher(model_from_string("<robot name='test'><link name='base_link'/></robot>"))
    assert one.static_transforms() == [] and one.on_joint_state(JointState([], [], 1.0)) == []


@pytest.mark.parametrize("parts", [
    ("ros+kdl_parser", "kdl_parser", "test", "test_robot.urdf"),
    ("ros+kdl_parser", "kdl_parser_py", "test", "test.urdf"),
    ("ros+urdf", "urdf", "test", "pr2_desc.urdf"),
    ("ros+robot_state_publisher", "urdf", "test-desc.urdf"),
    ("ros+urdf", "urdf", "test", "singularity.urdf"),
])
def test_corpus_models_publish_consistently(corpus, parts):
    """Message path, batch FK and lookup agree on the corpus models."""
    np = pytest.importorskip("numpy")
    m = _model(corpus, *parts)
    names = configuration_joints(m)
    rng = np.random.default_rng(0)
    q = rng.uniform(-2, 2, (5, len(names)))
    poses = link_poses(m, q)
    pub = StatePublisher(m, ignore_timestamp=True)
    root = m.root
    static = {t.child: t for t in pub.static_transforms()}
    for i in range(5):
        edges = dict(static)
        edges.update({t.child: t for t in pub.on_joint_state(JointState(names, q[i].tolist(), float(i)))})
        for link in list(m.links)[:40]:
            lk = lookup(m, root, link, dict(zip(names, q[i])))
            chain, cur = [], link
            while cur in edges:
                chain.append(edges[cur])
                cur = edges[cur].parent
            mat = np.eye(4)
            for t in reversed(chain):
                mat = mat @ np.array(t.matrix())
            assert np.allclose(mat, np.array(lk.matrix()), atol=1e-12)
            assert np.allclose(mat, poses[link][i], atol=1e-12)


def _example_robot(*parts):
    try:
        from importlib.metadata import distribution

        base = Path(distribution("example-robot-data").locate_file("cmeel.prefix/share/example-robot-data/robots"))
    except Exception:
        pytest.skip("example-robot-data not installed")
    p = base.joinpath(*parts)
    if not p.is_file():
        pytest.skip(f"{p} missing")
    return p


def _yourdfpy_poses_agree(path):
    np = pytest.importorskip("numpy")
    yourdfpy = pytest.importorskip("yourdfpy")
    xml = Path(path).read_text()
    m = model_from_string(xml, str(path))
    u = yourdfpy.URDF.load(str(path), build_scene_graph=True, load_meshes=False, build_collision_scene_graph=False,
                           load_collision_meshes=False)
    names = configuration_joints(m)
    rng = np.random.default_rng(1)
    pub = StatePublisher(m, ignore_timestamp=True)
    static = {t.child: t for t in pub.static_transforms()}
    for i in range(5):
        q = rng.uniform(-1.5, 1.5, len(names))
        # far from the previous configuration: trimesh keeps transforms that changed by less than 1e-8
        u.update_cfg(dict(zip(names, q.tolist())))
        edges = dict(static)
        edges.update({t.child: t for t in pub.on_joint_state(JointState(names, q.tolist(), float(i)))})
        for link in m.links:
            chain, cur = [], link
            while cur in edges:
                chain.append(edges[cur])
                cur = edges[cur].parent
            mat = np.eye(4)
            for t in reversed(chain):
                mat = mat @ np.array(t.matrix())
            assert np.allclose(mat, u.get_transform(link, cur), atol=1e-9), link
    return m


def test_yourdfpy_agrees_on_pr2(corpus):
    p = corpus / "ros+urdf" / "urdf" / "test" / "pr2_desc.urdf"
    if not p.is_file():
        pytest.skip("pr2_desc.urdf not in the corpus")
    _yourdfpy_poses_agree(p)  # mimic gripper joints included: sources are actuated, no multi-DOF joints


def test_yourdfpy_agrees_on_ur5():
    m = _yourdfpy_poses_agree(_example_robot("ur_description", "urdf", "ur5_robot.urdf"))
    assert len(configuration_joints(m)) == 6


def test_yourdfpy_agrees_on_kdl_test_robot(corpus):
    p = corpus / "ros+kdl_parser" / "kdl_parser" / "test" / "test_robot.urdf"
    if not p.is_file():
        pytest.skip("kdl_parser test_robot.urdf not in the corpus")
    _yourdfpy_poses_agree(p)
