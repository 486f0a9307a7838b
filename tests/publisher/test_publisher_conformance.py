"""Conformance: the publisher's ROS 1 profile against Debian's real robot_state_publisher (Noetic 1.15).

Starts a rosmaster on loopback, sets /robot_description, runs /usr/lib/robot_state_publisher/robot_state_publisher,
publishes JointStates and reads /tf and /tf_static with Debian's /usr/bin/python3 rospy (message classes are
generated at run time with genpy.dynamic from the standard definitions: their md5sums match the C++ ones), and
compares every transform, value for value (NaN included), stamp for stamp. Skipped when any piece is missing.
"""
import json
import math
import os
import shutil
import socket
import subprocess
import sys
import time
import xmlrpc.client
from pathlib import Path

import pytest

from urdfcheck.model.build import model_from_string
from urdfcheck.publisher import JointState, StatePublisher

pytestmark = pytest.mark.conformance

RSP = "/usr/lib/robot_state_publisher/robot_state_publisher"
PY = "/usr/bin/python3"
MASTER = shutil.which("rosmaster", path="/usr/bin:" + os.environ.get("PATH", "")) or "/usr/bin/rosmaster"


def _ros_available() -> str | None:
    if not os.access(RSP, os.X_OK):
        return f"{RSP} not installed"
    if not os.path.isfile(MASTER):
        return "rosmaster not installed"
    if not os.access(PY, os.X_OK):
        return f"{PY} not available"
    probe = subprocess.run([PY, "-c", "import rospy, genpy.dynamic, rosmaster"], capture_output=True,
                           env={"PATH": "/usr/bin:/bin"}, timeout=60)
    if probe.returncode:
        return "Debian's rospy/genpy/rosmaster are not importable by /usr/bin/python3"
    return None


_why = _ros_available()
if _why:
    pytest.skip(_why, allow_module_level=True)

CLIENT = r'''
import json, sys, time
import genpy.dynamic
import rospy

HEADER = """================================================================================
MSG: std_msgs/Header
uint32 seq
time stamp
string frame_id
"""
JS = "Header header\n\nstring[] name\nfloat64[] position\nfloat64[] velocity\nfloat64[] effort\n\n" + HEADER
TF = ("geometry_msgs/TransformStamped[] transforms\n\n"
      "================================================================================\n"
      "MSG: geometry_msgs/TransformStamped\nHeader header\nstring child_frame_id\nTransform transform\n\n"
      + HEADER +
      "\n================================================================================\n"
      "MSG: geometry_msgs/Transform\nVector3 translation\nQuaternion rotation\n\n"
      "================================================================================\n"
      "MSG: geometry_msgs/Vector3\nfloat64 x\nfloat64 y\nfloat64 z\n\n"
      "================================================================================\n"
      "MSG: geometry_msgs/Quaternion\nfloat64 x\nfloat64 y\nfloat64 z\nfloat64 w\n")
JointStateMsg = genpy.dynamic.generate_dynamic("sensor_msgs/JointState", JS)["sensor_msgs/JointState"]
TFMessage = genpy.dynamic.generate_dynamic("tf2_msgs/TFMessage", TF)["tf2_msgs/TFMessage"]
assert JointStateMsg._md5sum == "3066dcd76a6cfaef579bd0f34173e9fd", JointStateMsg._md5sum
assert TFMessage._md5sum == "94810edda583a504dfda3829e70d7eec", TFMessage._md5sum

job = json.load(sys.stdin)
rospy.init_node("urdfcheck_conformance", anonymous=True, disable_signals=True, disable_rosout=True)
static, dyn = {}, []

def rec(t):
    return {"parent": t.header.frame_id, "child": t.child_frame_id,
            "stamp": [t.header.stamp.secs, t.header.stamp.nsecs], "received": time.time(),
            "translation": [t.transform.translation.x, t.transform.translation.y, t.transform.translation.z],
            "rotation": [t.transform.rotation.x, t.transform.rotation.y, t.transform.rotation.z,
                         t.transform.rotation.w]}

def on_static(msg):
    for t in msg.transforms:
        static[(t.header.frame_id, t.child_frame_id)] = rec(t)

def on_tf(msg):
    dyn.extend(rec(t) for t in msg.transforms)

rospy.Subscriber("/tf_static", TFMessage, on_static)
rospy.Subscriber("/tf", TFMessage, on_tf)
pub = rospy.Publisher("/joint_states", JointStateMsg, queue_size=1000)
deadline = time.time() + job["timeout"]
while pub.get_num_connections() == 0 and time.time() < deadline:
    time.sleep(0.02)
if pub.get_num_connections() == 0:
    print(json.dumps({"error": "robot_state_publisher never subscribed to /joint_states"}))
    sys.exit(0)
time.sleep(0.3)
for m in job["messages"]:
    msg = JointStateMsg()
    msg.header.stamp = rospy.Time(m["stamp"][0], m["stamp"][1])
    msg.name, msg.position = m["name"], m["position"]
    pub.publish(msg)
    want = m["expect"]
    end = time.time() + (job["timeout"] if want else 0.4)
    while time.time() < end:
        if want and sum(1 for t in dyn if t["stamp"] == m["stamp"]) >= want:
            break
        time.sleep(0.005)
end = time.time() + job["timeout"]
while len(static) < job["expect_static"] and time.time() < end:
    time.sleep(0.02)
time.sleep(job.get("linger", 0.0))
print(json.dumps({"static": list(static.values()), "tf": dyn}))
'''

ROBOT = """<robot name="conformance">
  <link name="base"/><link name="l1"/><link name="l2"/><link name="l3"/><link name="tool"/><link name="p"/>
  <link name="f"/><link name="f2"/><link name="z"/><link name="zp"/><link name="ma"/><link name="mb"/>
  <link name="fx"/>
  <joint name="j1" type="revolute"><parent link="base"/><child link="l1"/><origin xyz="0 0 0.5" rpy="0.1 -0.2 0.3"/>
    <axis xyz="0 0.5 1"/><limit lower="-3" upper="3" effort="1" velocity="1"/></joint>
  <joint name="j2" type="continuous"><parent link="l1"/><child link="l2"/>
    <origin xyz="0.1 0 0" rpy="0 1.5707963267948966 0"/><axis xyz="0 2 0"/></joint>
  <joint name="j3" type="prismatic"><parent link="l2"/><child link="l3"/><axis xyz="1 1 0"/>
    <limit lower="0" upper="1" effort="1" velocity="1"/></joint>
  <joint name="tool_joint" type="fixed"><parent link="l3"/><child link="tool"/>
    <origin xyz="0 0 0.2" rpy="3.14159 0 0"/></joint>
  <joint name="planar_j" type="planar"><parent link="base"/><child link="p"/>
    <origin xyz="1 2 3"/><axis xyz="0 0 1"/></joint>
  <joint name="float_j" type="floating"><parent link="base"/><child link="f"/><origin xyz="0 0 1"/></joint>
  <joint name="under_float" type="fixed"><parent link="f"/><child link="f2"/><origin xyz="0 0 1"/></joint>
  <joint name="zero_rev" type="revolute"><parent link="base"/><child link="z"/><axis xyz="0 0 0"/>
    <limit lower="-1" upper="1" effort="1" velocity="1"/></joint>
  <joint name="zero_pri" type="prismatic"><parent link="base"/><child link="zp"/><origin xyz="1 0 0" rpy="0 0 1"/>
    <axis xyz="0 0 0"/><limit lower="-1" upper="1" effort="1" velocity="1"/></joint>
  <joint name="b_mimic" type="revolute"><parent link="base"/><child link="mb"/><axis xyz="0 0 1"/>
    <limit lower="-3" upper="3" effort="1" velocity="1"/><mimic joint="j1" multiplier="2" offset="0.1"/></joint>
  <joint name="a_mimic" type="revolute"><parent link="mb"/><child link="ma"/><axis xyz="1 0 0"/>
    <limit lower="-3" upper="3" effort="1" velocity="1"/><mimic joint="b_mimic" multiplier="-1" offset="0"/></joint>
  <joint name="fixed_mimic" type="fixed"><parent link="base"/><child link="fx"/><origin xyz="0 1 0"/>
    <mimic joint="j1"/></joint>
</robot>"""


def _free_port() -> int:
    s = socket.socket()
    s.bind(("127.0.0.1", 0))
    port = s.getsockname()[1]
    s.close()
    return port


def _stop(p: subprocess.Popen) -> str:
    if p.poll() is None:
        p.terminate()
        try:
            p.wait(5)
        except subprocess.TimeoutExpired:
            p.kill()
            p.wait(5)
    out = p.stdout.read() if p.stdout else b""
    return out.decode("utf-8", "replace") if isinstance(out, bytes) else out


@pytest.fixture(scope="module")
def master(tmp_path_factory):
    home = tmp_path_factory.mktemp("ros_home")
    port = _free_port()
    uri = f"http://127.0.0.1:{port}/"
    env = {"PATH": "/usr/bin:/bin", "ROS_MASTER_URI": uri, "ROS_HOSTNAME": "127.0.0.1", "ROS_IP": "127.0.0.1",
           "ROS_HOME": str(home), "ROS_LOG_DIR": str(home), "HOME": str(home)}
    proc = subprocess.Popen([PY, MASTER, "--core", "-p", str(port)], env=env, stdout=subprocess.DEVNULL,
                            stderr=subprocess.DEVNULL)
    proxy = xmlrpc.client.ServerProxy(uri)
    for _ in range(150):
        try:
            proxy.getSystemState("/urdfcheck")
            break
        except OSError:
            time.sleep(0.1)
    else:
        _stop(proc)
        pytest.skip("rosmaster did not come up")
    client = home / "client.py"
    client.write_text(CLIENT)
    yield {"env": env, "proxy": proxy, "client": client}
    _stop(proc)


def run_real(master, urdf: str, params: dict, job: dict) -> tuple[dict, str]:
    px = master["proxy"]
    px.setParam("/urdfcheck", "/robot_description", urdf)
    for k in ("publish_frequency", "use_tf_static", "ignore_timestamp", "tf_prefix"):
        try:
            px.deleteParam("/urdfcheck", f"/robot_state_publisher/{k}")
        except Exception:
            pass
    for k, v in params.items():
        px.setParam("/urdfcheck", f"/robot_state_publisher/{k}", v)
    rsp = subprocess.Popen([RSP], env=master["env"], stdout=subprocess.PIPE, stderr=subprocess.STDOUT)
    try:
        out = subprocess.run([PY, str(master["client"])], input=json.dumps(job), capture_output=True, text=True,
                             env=master["env"], timeout=120)
    finally:
        log = _stop(rsp)
    assert out.returncode == 0, out.stderr[-3000:]
    res = json.loads(out.stdout.strip().splitlines()[-1])
    assert "error" not in res, (res, log)
    return res, log


def same(a, b, tol=1e-12) -> bool:
    return all((math.isnan(x) and math.isnan(y)) or abs(x - y) <= tol for x, y in zip(a, b))


def compare(mine, theirs):
    assert [(t.parent, t.child, list(t.stamp)) for t in mine] == [(t["parent"], t["child"], t["stamp"])
                                                                   for t in theirs]
    for a, b in zip(mine, theirs):
        assert same(a.translation, b["translation"]), (a, b)
        assert same(a.rotation, b["rotation"]), (a, b)  # same quaternion sign as KDL, not just the same rotation


MESSAGES = [
    # movable, continuous beyond 2 pi, zero axes (NaN), planar (ignored), unknown name (ignored)
    {"name": ["j1", "j2", "j3", "zero_rev", "zero_pri", "planar_j", "ghost"],
     "position": [0.4, 7.5, 0.3, 0.2, 0.1, 5.0, 1.0], "stamp": [1000, 0]},
    {"name": ["j1"], "position": [0.5], "stamp": [1000, 1_000_000]},  # 1 ms later: throttled at 50 Hz
    {"name": ["j1"], "position": [0.5], "stamp": [1000, 20_000_000]},  # exactly one interval later
    {"name": ["j1", "b_mimic"], "position": [0.6, -0.3], "stamp": [1001, 0]},  # explicit value wins, a_mimic follows
    {"name": ["j2", "j3"], "position": [-9.0, 0.7], "stamp": [1002, 0]},
    {"name": ["j2"], "position": [1.0], "stamp": [999, 0]},  # back in time but clock did not jump: throttled
]


def _expected(model, messages, **kw):
    pub = StatePublisher(model, profile="ros1", **kw)
    per_msg = []
    for m in messages:
        # the real node's clock is wall time, far ahead of these stamps and never going backwards
        per_msg.append(pub.on_joint_state(JointState(m["name"], m["position"], tuple(m["stamp"])), now=2e9))
    return pub, per_msg


def test_real_ros1_robot_state_publisher_default(master):
    model = model_from_string(ROBOT)
    pub, per_msg = _expected(model, MESSAGES)
    assert [len(x) for x in per_msg] == [6, 0, 2, 3, 2, 0]
    job = {"timeout": 15, "expect_static": len(pub.static_transforms()),
           "messages": [dict(m, expect=len(x)) for m, x in zip(MESSAGES, per_msg)]}
    res, log = run_real(master, ROBOT, {}, job)
    compare([t for x in per_msg for t in x], res["tf"])
    theirs = {(t["parent"], t["child"]): t for t in res["static"]}
    mine = {(t.parent, t.child): t for t in pub.static_transforms()}
    assert set(theirs) == set(mine) == {("base", "fx"), ("base", "p"), ("l3", "tool"), ("f", "f2")}
    for k, t in mine.items():
        assert same(t.translation, theirs[k]["translation"]) and same(t.rotation, theirs[k]["rotation"])
    assert "Converting unknown joint type of joint 'planar_j' into a fixed joint" in log


def test_real_ros1_no_tf_static_with_tf_prefix(master):
    model = model_from_string(ROBOT)
    msgs = MESSAGES[:1]
    pub, per_msg = _expected(model, msgs, frame_prefix="/pre", use_tf_static=False)
    fixed = pub.tick(0.0)
    job = {"timeout": 15, "expect_static": 0, "linger": 0.3,
           "messages": [dict(m, expect=len(x)) for m, x in zip(msgs, per_msg)]}
    res, log = run_real(master, ROBOT, {"use_tf_static": False, "tf_prefix": "/pre"}, job)
    assert res["static"] == []
    dynamic = [t for t in res["tf"] if t["stamp"] == [1000, 0]]
    compare(per_msg[0], dynamic)
    assert {t.parent for t in per_msg[0]} <= {"pre/base", "pre/l1", "pre/l2"}
    # fixed transforms come on /tf, again and again, future-dated by 0.5 s
    again = [t for t in res["tf"] if t["stamp"] != [1000, 0]]
    mine = {(t.parent, t.child): t for t in fixed}
    assert {(t["parent"], t["child"]) for t in again} == set(mine)
    assert len(again) >= 2 * len(mine)
    for t in again:
        m = mine[(t["parent"], t["child"])]
        assert same(m.translation, t["translation"]) and same(m.rotation, t["rotation"])
        ahead = t["stamp"][0] + t["stamp"][1] * 1e-9 - t["received"]
        assert 0.3 < ahead <= 0.51


def test_real_ros1_on_pr2(master):
    corpus = Path(os.environ.get("URDFCHECK_CORPUS", Path(__file__).resolve().parents[2] / "shared" / "corpus"))
    path = corpus / "ros+urdf" / "urdf" / "test" / "pr2_desc.urdf"
    if not path.is_file():
        pytest.skip("pr2_desc.urdf not in the corpus")
    np = pytest.importorskip("numpy")
    xml = path.read_text()
    model = model_from_string(xml, str(path))
    from urdfcheck.publisher import configuration_joints

    names = configuration_joints(model)
    rng = np.random.default_rng(7)
    msgs = [{"name": names, "position": rng.uniform(-2, 2, len(names)).tolist(), "stamp": [2000 + i, 0]}
            for i in range(5)]
    pub, per_msg = _expected(model, msgs)
    job = {"timeout": 20, "expect_static": len(pub.static_transforms()),
           "messages": [dict(m, expect=len(x)) for m, x in zip(msgs, per_msg)]}
    res, _ = run_real(master, xml, {}, job)
    compare([t for x in per_msg for t in x], res["tf"])
    assert len(res["static"]) == len(pub.static_transforms())


if __name__ == "__main__":  # pragma: no cover
    sys.exit(pytest.main([__file__, "-v"]))
