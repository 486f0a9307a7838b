from launch import LaunchDescription
from launch_ros.actions import Node
from my_robot_utils.description import load_description


class Robot:
    def urdf(self):
        return open("x.urdf").read()


def generate_launch_description():
    return LaunchDescription([
        Node(package="robot_state_publisher", executable="robot_state_publisher",
             parameters=[{"robot_description": load_description("bot")}]),
    ])
