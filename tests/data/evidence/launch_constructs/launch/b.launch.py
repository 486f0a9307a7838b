from launch import LaunchDescription
from launch_ros.actions import Node


class Robot:
    def __init__(self, path):
        self.path = path

    def urdf(self):
        with open(self.path) as f:
            return f.read()


def generate_launch_description():
    robot = Robot("urdf/bot.urdf")
    return LaunchDescription([
        Node(package="robot_state_publisher", executable="robot_state_publisher",
             parameters=[{"robot_description": robot.urdf()}]),
    ])
