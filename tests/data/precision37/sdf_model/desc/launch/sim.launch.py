# robot_state_publisher is given an SDFormat model (it reads it through sdformat_urdf)
import os

from ament_index_python.packages import get_package_share_directory
from launch import LaunchDescription
from launch_ros.actions import Node


def generate_launch_description():
    pkg = get_package_share_directory("desc")
    sdf_file = os.path.join(pkg, "models", "bot", "model.sdf")
    with open(sdf_file) as infp:
        robot_desc = infp.read()
    return LaunchDescription([
        Node(package="robot_state_publisher", executable="robot_state_publisher",
             parameters=[{"use_sim_time": True}, {"robot_description": robot_desc}]),
    ])
