"""Property test: random kinematic trees and joint states, publisher vs Pinocchio (world poses) and vs yourdfpy
(per-joint transforms).

Where the tools genuinely disagree the test asserts the known difference instead of skipping:

* planar: robot_state_publisher publishes it static at its origin; Pinocchio models 3 DOF (compared at neutral);
* floating: robot_state_publisher publishes nothing (the child roots a separate TF tree); Pinocchio: free-flyer;
* zero axis: robot_state_publisher publishes NaN; Pinocchio's revolute "rotation" is cos(q)*I and its prismatic
  joint does not move; yourdfpy gives a NaN rotation (revolute) or no motion (prismatic);
* non-unit prismatic axis: yourdfpy translates by q * axis (KDL and Pinocchio normalise);
* yourdfpy's trimesh scene graph keeps the old transform when the new one is within 1e-8 (per element);
* mimic: robot_state_publisher fills mimic joints in name order from direct sources only (some are never
  published); yourdfpy evaluates a mimic of a mimic as offset only and reads sources from the joint-index slot.
"""
import io
import logging
import math
import os
import warnings

import pytest

np = pytest.importorskip("numpy")
pin = pytest.importorskip("pinocchio")
hypothesis = pytest.importorskip("hypothesis")
from hypothesis import HealthCheck, given, settings  # noqa: E402
from hypothesis import strategies as st  # noqa: E402

from urdfcheck.core.geometry import from_rt, rpy_matrix  # noqa: E402
from urdfcheck.model.build import model_from_string  # noqa: E402
from urdfcheck.publisher import JointState, StatePublisher  # noqa: E402

MOVABLE = ("revolute", "continuous", "prismatic")
TYPES = ("revolute", "continuous", "prismatic", "fixed", "planar", "floating")
TOL = 1e-9
EXAMPLES = int(os.environ.get("URDFCHECK_HYPOTHESIS_EXAMPLES", "60"))  # raise it for a long soak


def finite(lo, hi):
    return st.floats(lo, hi, allow_nan=False, allow_infinity=False)


@st.composite
def axes(draw):
    if draw(st.integers(0, 14)) == 0:
        return (0.0, 0.0, 0.0)
    d = draw(st.tuples(finite(-1, 1), finite(-1, 1), finite(-1, 1)))
    n = math.sqrt(sum(c * c for c in d))
    if n < 1e-3:
        d, n = (1.0, 0.0, 0.0), 1.0
    scale = draw(st.sampled_from([1.0, 1.0, draw(finite(0.05, 20.0))]))
    return tuple(c / n * scale for c in d)


@st.composite
def robots(draw):
    n = draw(st.integers(1, 7))
    names = draw(st.permutations([f"j{i}" for i in range(n)]))  # random names: random mimic name order
    joints, movable = [], []
    for i in range(n):
        jtype = draw(st.sampled_from(TYPES))
        j = {
            "name": names[i], "type": jtype, "parent": f"l{draw(st.integers(0, i))}", "child": f"l{i + 1}",
            "xyz": draw(st.tuples(finite(-2, 2), finite(-2, 2), finite(-2, 2))),
            "rpy": draw(st.tuples(finite(-4, 4), finite(-4, 4), finite(-4, 4))),
            "axis": draw(axes()), "mimic": None,
            "limit": (draw(finite(-3, 0)), draw(finite(0, 3))),
            "quat": None,
        }
        if draw(st.integers(0, 3)) == 0:  # URDF 1.1: the origin as quat_xyzw, any length and sign
            q = draw(st.tuples(finite(-1, 1), finite(-1, 1), finite(-1, 1), finite(-1, 1)))
            n = math.sqrt(sum(c * c for c in q))
            if n > 1e-3:
                j["quat"] = tuple(c / n * draw(st.sampled_from([1.0, 1.0, -1.0, 0.5])) for c in q)
                j["rpy"] = rpy_of(quat_matrix(j["quat"]))  # what the peers are given (they read rpy only)
        if jtype in MOVABLE and movable and draw(st.booleans()):  # mimic any earlier movable joint, any branch
            j["mimic"] = (names[draw(st.sampled_from(movable))], draw(finite(-3, 3)), draw(finite(-2, 2)))
        if jtype in MOVABLE:
            movable.append(i)
        joints.append(j)
    active = [j["name"] for j in joints if j["type"] in MOVABLE and j["mimic"] is None]
    values = {name: draw(finite(-10, 10)) for name in active}  # continuous angles well beyond +-pi
    return joints, values


def quat_matrix(q):
    """The rotation of a quaternion (x, y, z, w) of any length: numpy, independent of the code under test."""
    x, y, z, w = np.array(q, dtype=float) / np.linalg.norm(q)
    return np.array([[1 - 2 * (y * y + z * z), 2 * (x * y - z * w), 2 * (x * z + y * w)],
                     [2 * (x * y + z * w), 1 - 2 * (x * x + z * z), 2 * (y * z - x * w)],
                     [2 * (x * z - y * w), 2 * (y * z + x * w), 1 - 2 * (x * x + y * y)]])


def rpy_of(r):
    """URDF roll, pitch, yaw (R = Rz(yaw) Ry(pitch) Rx(roll)) of a rotation matrix."""
    pitch = math.atan2(-r[2, 0], math.hypot(r[0, 0], r[1, 0]))
    return (math.atan2(r[2, 1], r[2, 2]), pitch, math.atan2(r[1, 0], r[0, 0]))


def to_xml(joints, *, peers: bool = False) -> str:
    """The model; `peers`: every origin as rpy (Pinocchio's and yourdfpy's readers ignore quat_xyzw)."""
    r = repr
    version = ' version="1.1"' if not peers and any(j["quat"] for j in joints) else ""  # quat_xyzw: URDF 1.1
    out = [f'<robot name="random"{version}>'] + [f'<link name="l{i}"/>' for i in range(len(joints) + 1)]
    for j in joints:
        turn = f'quat_xyzw="{" ".join(map(r, j["quat"]))}"' if j["quat"] and not peers else \
            f'rpy="{" ".join(map(r, j["rpy"]))}"'
        out.append(f'<joint name="{j["name"]}" type="{j["type"]}">'
                   f'<origin xyz="{" ".join(map(r, j["xyz"]))}" {turn}/>'
                   f'<parent link="{j["parent"]}"/><child link="{j["child"]}"/>'
                   f'<axis xyz="{" ".join(map(r, j["axis"]))}"/>'
                   f'<limit lower="{r(j["limit"][0])}" upper="{r(j["limit"][1])}" effort="1" velocity="1"/>')
        if j["mimic"]:
            out.append(f'<mimic joint="{j["mimic"][0]}" multiplier="{r(j["mimic"][1])}" offset="{r(j["mimic"][2])}"/>')
        out.append("</joint>")
    out.append("</robot>")
    return "".join(out)


# --- independent references -------------------------------------------------------------------------------------
def rsp_values(joints, values):
    """robot_state_publisher's rule, written out independently: name order, direct sources, explicit wins."""
    pos = dict(values)
    for j in sorted((j for j in joints if j["mimic"]), key=lambda j: j["name"]):
        src, m, o = j["mimic"]
        if src in pos and j["name"] not in pos:
            pos[j["name"]] = pos[src] * m + o
    return pos


def transitive_values(joints, values):
    by = {j["name"]: j for j in joints}
    out = dict(values)

    def get(name):
        if name not in out:
            src, m, o = by[name]["mimic"]
            out[name] = get(src) * m + o
        return out[name]

    for j in joints:
        if j["type"] in MOVABLE:
            get(j["name"])
    return out


def origin_matrix(j):
    if j["quat"]:
        m = np.eye(4)
        m[:3, :3], m[:3, 3] = quat_matrix(j["quat"]), j["xyz"]
        return m
    return np.array(from_rt(rpy_matrix(*j["rpy"]), j["xyz"]))


def local_matrix(j, q, *, normalise=True):
    """origin * motion(q) about/along the (normalised) axis, numpy; the URDF meaning of one joint."""
    o = origin_matrix(j)
    if j["type"] not in MOVABLE:
        return o
    a = np.array(j["axis"], dtype=float)
    n = np.linalg.norm(a)
    if normalise:
        a = a / n if n else a * np.nan
    m = np.eye(4)
    if j["type"] == "prismatic":
        m[:3, 3] = a * q
    else:
        k = np.array([[0, -a[2], a[1]], [a[2], 0, -a[0]], [-a[1], a[0], 0]])
        m[:3, :3] = np.eye(3) + math.sin(q) * k + (1 - math.cos(q)) * (k @ k)
    return o @ m


def tf_matrix(t):
    x, y, z, w = t.rotation
    m = np.eye(4)
    m[:3, :3] = [[1 - 2 * (y * y + z * z), 2 * (x * y - z * w), 2 * (x * z + y * w)],
                 [2 * (x * y + z * w), 1 - 2 * (x * x + z * z), 2 * (y * z - x * w)],
                 [2 * (x * z - y * w), 2 * (y * z + x * w), 1 - 2 * (x * x + y * y)]]
    m[:3, 3] = t.translation
    return m


def pinocchio_poses(xml, joints, values):
    model = pin.buildModelFromXML(xml)
    data = model.createData()
    q = pin.neutral(model)
    full = transitive_values(joints, values)
    for jid in range(1, model.njoints):
        jm, name = model.joints[jid], model.names[jid]
        if name in full:
            if jm.nq == 2:  # continuous: (cos, sin)
                q[jm.idx_q:jm.idx_q + 2] = (math.cos(full[name]), math.sin(full[name]))
            else:
                q[jm.idx_q] = full[name]
    pin.forwardKinematics(model, data, q)
    pin.updateFramePlacements(model, data)
    return model, data, full


@given(robots())
@settings(max_examples=EXAMPLES, deadline=None, suppress_health_check=[HealthCheck.too_slow])
def test_publisher_matches_pinocchio_and_yourdfpy(robot):
    joints, values = robot
    xml = to_xml(joints)
    model = model_from_string(xml)
    by = {j["name"]: j for j in joints}
    parent_joint = {j["child"]: j for j in joints}

    pub = StatePublisher(model, ignore_timestamp=True)
    static = pub.static_transforms()
    dynamic = pub.on_joint_state(JointState(list(values), list(values.values()), 1.0))
    edges = {t.child: t for t in static + dynamic}
    assert len(edges) == len(static) + len(dynamic)
    rsp = rsp_values(joints, values)

    # per joint: what the publisher sends, or the stated reason it sends nothing
    for j in joints:
        t = edges.get(j["child"])
        if j["type"] == "floating":
            assert t is None  # delta: never published
        elif j["type"] in ("fixed", "planar"):
            assert t in static  # planar: static at its origin (kdl_parser makes it fixed)
            assert np.allclose(tf_matrix(t), local_matrix(j, 0.0), atol=TOL, rtol=0)
        elif j["name"] not in rsp:
            assert t is None  # delta: a mimic joint robot_state_publisher's name-order rule never fills
        elif not any(j["axis"]):
            # delta: KDL divides the zero axis by its norm -> NaN
            assert all(math.isnan(v) for v in t.translation)
            if j["type"] == "revolute" or j["type"] == "continuous":
                assert all(math.isnan(v) for v in t.rotation)
        else:
            assert np.allclose(tf_matrix(t), local_matrix(j, rsp[j["name"]]), atol=TOL, rtol=0)

    # world poses: compose the published transforms per TF tree, compare with Pinocchio
    peer_xml = to_xml(joints, peers=True)
    pmodel, pdata, full = pinocchio_poses(peer_xml, joints, values)

    def chain(link):
        out = []
        while link in parent_joint:
            j = parent_joint[link]
            out.append(j)
            link = j["parent"]
        return out[::-1]

    def frame(link):
        return pdata.oMf[pmodel.getFrameId(link, pin.FrameType.BODY)].homogeneous

    def zero_axis_above(link):
        return any(jj["type"] in MOVABLE and not any(jj["axis"]) for jj in chain(link))

    for j in joints:  # the stated Pinocchio deltas
        jid = pmodel.getJointId(j["name"])
        if j["type"] == "planar":
            assert pmodel.joints[jid].nv == 3
        elif j["type"] == "floating":
            assert pmodel.joints[jid].nv == 6
        elif j["type"] in MOVABLE and not any(j["axis"]) and not zero_axis_above(j["parent"]):
            q = full[j["name"]]
            rel = np.linalg.inv(frame(j["parent"])) @ frame(j["child"])
            o = origin_matrix(j)
            if j["type"] == "prismatic":
                assert np.allclose(rel, o, atol=TOL)  # does not move
            else:
                assert np.allclose(rel[:3, :3], math.cos(q) * o[:3, :3], atol=TOL)  # cos(q) * I: not a rotation
                assert np.allclose(rel[:3, 3], o[:3, 3], atol=TOL)

    compared = []
    for i in range(1, len(joints) + 1):
        link = f"l{i}"
        ch = chain(link)
        # the TF root: the model root, or the child of the last floating joint on the way
        k0 = max((k for k, j in enumerate(ch) if j["type"] == "floating"), default=-1)
        root = ch[k0]["child"] if k0 >= 0 else "l0"
        path = ch[k0 + 1:]
        if any(j["type"] in MOVABLE and not any(j["axis"]) for j in path):
            continue  # zero axis on the way: NaN (asserted per joint above)
        if any(j["type"] in MOVABLE and j["name"] not in rsp for j in path):
            continue  # an unpublished mimic joint on the way: no TF path (asserted above)
        m = np.eye(4)
        for j in path:
            m = m @ tf_matrix(edges[j["child"]])
        expected = np.linalg.inv(frame(root)) @ frame(link)
        assert np.allclose(m, expected, atol=TOL, rtol=0), (link, m, expected)
        compared.append(link)
    first = joints[0]  # l0 -> l1: nothing above it, so l1 is compared unless the joint itself is excluded
    if first["type"] != "floating" and not (first["type"] in MOVABLE and not any(first["axis"])):
        assert "l1" in compared, compared

    # yourdfpy, per joint transform (its composition is trimesh's scene graph)
    yourdfpy = pytest.importorskip("yourdfpy")
    logging.disable(logging.WARNING)
    try:
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            u = yourdfpy.URDF.load(io.BytesIO(peer_xml.encode()), build_scene_graph=True, load_meshes=False,
                                   build_collision_scene_graph=False, load_collision_meshes=False)
            before = {k: v["matrix"].copy() for k, v in u.scene.graph.transforms.edge_data.items()}
            u.update_cfg(dict(values))
    finally:
        logging.disable(logging.NOTSET)
    ed = u.scene.graph.transforms.edge_data
    act = u.actuated_joint_names
    multi_dof_slots = [jj.name for jj in u.actuated_joints if jj.type in ("floating", "planar")]

    def ydf_equal(my, expected, key, atol=TOL):
        if np.allclose(my, expected, atol=atol, rtol=0):
            return True
        # delta: trimesh's scene graph ignores an update within 1e-8 (per element) of the stored matrix
        return np.array_equal(my, before[key]) and np.all(np.abs(expected - before[key]) < 1e-8)

    for j in joints:
        key = (j["parent"], j["child"])
        my = ed[key]["matrix"]
        if j["type"] not in MOVABLE:
            assert np.allclose(my, local_matrix(j, 0.0), atol=TOL, rtol=0)  # planar/floating: origin only
            continue
        if j["mimic"] is None:
            q = values[j["name"]]
        else:
            src, mm, oo = j["mimic"]
            # yourdfpy: sources must be actuated (a mimic source counts as 0); slot = joint index, not DOF index
            q = (u.cfg[act.index(src)] if src in act else 0.0) * mm + oo
            if src in act and not any(act.index(x) < act.index(src) for x in multi_dof_slots) \
                    and by[src]["mimic"] is None:
                assert q == pytest.approx(full[j["name"]], abs=1e-12)  # no delta in this case
        norm = math.sqrt(sum(c * c for c in j["axis"]))
        if norm == 0.0:
            if j["type"] == "prismatic":
                assert np.allclose(my, origin_matrix(j), atol=TOL, rtol=0)  # delta: no motion (RSP: NaN)
            else:
                assert np.isnan(my[:3, :3]).all()  # delta: NaN rotation (RSP: NaN translation too)
            continue
        if j["type"] == "prismatic":
            # delta: yourdfpy translates by q * axis without normalising
            assert ydf_equal(my, local_matrix(j, q * norm), key, atol=TOL * max(1.0, norm * abs(q)))
        else:
            assert ydf_equal(my, local_matrix(j, q), key)
    hypothesis.event(f"quat_xyzw origins: {sum(1 for j in joints if j['quat'])}")
