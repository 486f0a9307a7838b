#!/usr/bin/python3
"""Record small ROS 1 bags with Debian's ROS 1 packages, for tests/fixtures/ros1 (issue 39).

Real software writes them: `roscore`, Debian's `robot_state_publisher` (C++), joint state drivers and TF
broadcasters written with `rospy` and `tf2_ros`, and `rosbag record`; `rosbag compress` and the rosbag Python API
make the compressed and callerid-less variants. Needs (Debian bookworm):

    apt-get install ros-core ros-robot-state-publisher python3-rosbag python3-rospy python3-tf2-ros \\
        python3-sensor-msgs python3-tf2-msgs

Run with the system Python (rospy lives there): `/usr/bin/python3 tools/record_ros1_bags.py tests/fixtures/ros1`.
Each scenario runs its own master on a free port, for about three seconds of robot time.
"""
from __future__ import annotations

import os
import signal
import socket
import subprocess
import sys
import tempfile
import time

ROBOT = """<?xml version="1.0"?>
<robot name="cart">
  <link name="base_link"/>
  <link name="left_wheel"/>
  <link name="right_wheel"/>
  <link name="arm_link"/>
  <link name="laser"/>
  <joint name="left_wheel_joint" type="continuous">
    <parent link="base_link"/><child link="left_wheel"/><origin xyz="0 0.2 0.05" rpy="-1.5708 0 0"/>
    <axis xyz="0 0 1"/>
  </joint>
  <joint name="right_wheel_joint" type="continuous">
    <parent link="base_link"/><child link="right_wheel"/><origin xyz="0 -0.2 0.05" rpy="-1.5708 0 0"/>
    <axis xyz="0 0 1"/>
  </joint>
  <joint name="arm_joint" type="revolute">
    <parent link="base_link"/><child link="arm_link"/><origin xyz="0.1 0 0.3"/><axis xyz="0 0 1"/>
    <limit lower="-2" upper="2" effort="5" velocity="1"/>
  </joint>
  <joint name="laser_joint" type="fixed">
    <parent link="base_link"/><child link="laser"/><origin xyz="{laser_x} 0 0.25"/>
  </joint>
</robot>
"""
WHEELS = ["left_wheel_joint", "right_wheel_joint"]
ARM = ["arm_joint"]

DRIVER = r'''
import math, sys, rospy
from sensor_msgs.msg import JointState
names = sys.argv[1].split(",")
rate, offset, topic = float(sys.argv[2]), float(sys.argv[3]), sys.argv[4]
rospy.init_node(sys.argv[5])
pub = rospy.Publisher(topic, JointState, queue_size=10)
r = rospy.Rate(rate)
t0 = rospy.Time.now()
while not rospy.is_shutdown():
    now = rospy.Time.now()
    s = (now - t0).to_sec()
    msg = JointState()
    msg.header.stamp = now + rospy.Duration(offset)
    msg.name = names
    msg.position = [0.5 * math.sin(s + i) for i in range(len(names))]
    msg.velocity = [0.5 * math.cos(s + i) for i in range(len(names))]
    pub.publish(msg)
    try:
        r.sleep()
    except rospy.ROSInterruptException:
        break
'''

ODOM = r'''
import sys, rospy, tf2_ros
from geometry_msgs.msg import TransformStamped
rospy.init_node(sys.argv[1])
b = tf2_ros.TransformBroadcaster()
r = rospy.Rate(float(sys.argv[2]))
x = 0.0
while not rospy.is_shutdown():
    t = TransformStamped()
    t.header.stamp = rospy.Time.now()
    t.header.frame_id, t.child_frame_id = "odom", "base_link"
    x += float(sys.argv[3])
    t.transform.translation.x = x
    t.transform.rotation.w = 1.0
    b.sendTransform(t)
    try:
        r.sleep()
    except rospy.ROSInterruptException:
        break
'''

STATIC = r'''
import sys, rospy, tf2_ros
from geometry_msgs.msg import TransformStamped
rospy.init_node(sys.argv[1])
b = tf2_ros.StaticTransformBroadcaster()
t = TransformStamped()
t.header.stamp = rospy.Time.now()
t.header.frame_id, t.child_frame_id = sys.argv[2], sys.argv[3]
t.transform.translation.x, t.transform.translation.z = float(sys.argv[4]), 0.25
t.transform.rotation.w = 1.0
b.sendTransform(t)
rospy.spin()
'''

SCENARIOS = {
    # name: (rsp params, the URDF's laser x on the robot, drivers, extra nodes)
    "clean": ({}, 0.2, [(WHEELS + ARM, 50, 0.0, "/joint_states", "jsp")], []),
    "no_tf_static": ({"use_tf_static": "false"}, 0.2, [(WHEELS + ARM, 50, 0.0, "/joint_states", "jsp")], []),
    "drivers": ({}, 0.2, [(WHEELS, 50, 0.0, "/joint_states", "base_driver"),
                          (ARM, 30, -3.0, "/joint_states", "arm_driver")], []),
    "remapped": ({"joint_states": "/robot/joint_states"}, 0.2,
                 [(WHEELS + ARM, 50, 0.0, "/joint_states", "jsp")], [("odom", "diff_drive", 50, 0.01)]),
    "prefix_laser": ({"tf_prefix": "robot1"}, 0.22, [(WHEELS + ARM, 50, 0.0, "/joint_states", "jsp")], []),
    "two_odom": ({}, 0.2, [(WHEELS + ARM, 50, 0.0, "/joint_states", "jsp")],
                 [("odom", "diff_drive", 50, 0.01), ("odom", "ekf", 30, 0.012)]),
    "second_static": ({}, 0.2, [(WHEELS + ARM, 50, 0.0, "/joint_states", "jsp")],
                      [("static", "laser_calib", "base_link", "laser", 0.23)]),
}


def free_port() -> int:
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return s.getsockname()[1]


def record(name: str, out_dir: str, seconds: float = 3.0) -> str:
    params, laser_x, drivers, extra = SCENARIOS[name]
    port = free_port()
    home = tempfile.mkdtemp(prefix="ros1home-")
    env = dict(os.environ, ROS_MASTER_URI=f"http://127.0.0.1:{port}", ROS_HOME=home, ROS_LOG_DIR=home,
               ROS_HOSTNAME="127.0.0.1")
    procs = []

    def start(args, **kw):
        p = subprocess.Popen(args, env=env, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL,
                             start_new_session=True, **kw)
        procs.append(p)
        return p

    start(["roscore", "-p", str(port)])
    for _ in range(100):
        if subprocess.run(["rostopic", "list"], env=env, capture_output=True).returncode == 0:
            break
        time.sleep(0.2)
    subprocess.run(["rosparam", "set", "robot_description", ROBOT.format(laser_x=laser_x)], env=env, check=True)
    rsp = ["/usr/lib/robot_state_publisher/robot_state_publisher", "__name:=robot_state_publisher"]
    for k, v in params.items():
        rsp.append(f"joint_states:={v}" if k == "joint_states" else f"_{k}:={v}")
    start(rsp)
    path = os.path.join(out_dir, f"{name}.bag")
    rec = start(["rosbag", "record", "-O", path, "/joint_states", "/tf", "/tf_static", "__name:=recorder"])
    time.sleep(1.5)  # the recorder subscribes before anything is published
    for e in extra:
        if e[0] == "odom":
            start([sys.executable, "-c", ODOM, e[1], str(e[2]), str(e[3])])
        else:
            start([sys.executable, "-c", STATIC, e[1], e[2], e[3], str(e[4])])
    for names, rate, offset, topic, node in drivers:
        start([sys.executable, "-c", DRIVER, ",".join(names), str(rate), str(offset), topic, node])
    time.sleep(seconds)
    rec.send_signal(signal.SIGINT)  # rosbag closes the bag (writes its index) on SIGINT
    try:
        rec.wait(timeout=20)
    except subprocess.TimeoutExpired:
        pass
    for p in reversed(procs):
        if p.poll() is None:
            os.killpg(p.pid, signal.SIGINT)
    for p in procs:
        try:
            p.wait(timeout=10)
        except subprocess.TimeoutExpired:
            os.killpg(p.pid, signal.SIGKILL)
    import shutil

    shutil.rmtree(home, ignore_errors=True)  # the master's logs
    return path


def variants(out_dir: str) -> None:
    """The clean bag compressed (lz4, bz2), and the second_static bag rewritten through the rosbag Python API,
    which keeps one connection per topic (the callerids are gone)."""
    import shutil

    import rosbag

    clean = os.path.join(out_dir, "clean.bag")
    for fmt in ("lz4", "bz2"):
        out = os.path.join(out_dir, f"clean_{fmt}.bag")
        shutil.copyfile(clean, out)
        subprocess.run(["rosbag", "compress", f"--{fmt}", "-f", "-q", out], check=True, capture_output=True)
        os.unlink(os.path.join(out_dir, f"clean_{fmt}.orig.bag"))
    src = os.path.join(out_dir, "second_static.bag")
    with rosbag.Bag(src) as bag, rosbag.Bag(os.path.join(out_dir, "second_static_nocaller.bag"), "w") as out:
        for topic, msg, t in bag.read_messages():
            out.write(topic, msg, t)


def main() -> int:
    out_dir = sys.argv[1] if len(sys.argv) > 1 else "tests/fixtures/ros1"
    os.makedirs(out_dir, exist_ok=True)
    for name in (sys.argv[2:] or SCENARIOS):
        print("recording", record(name, out_dir), flush=True)
    with open(os.path.join(out_dir, "robot.urdf"), "w") as f:
        f.write(ROBOT.format(laser_x=0.2))
    variants(out_dir)
    return 0


if __name__ == "__main__":
    sys.exit(main())
