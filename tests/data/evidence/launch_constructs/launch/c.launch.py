from launch import LaunchDescription
from launch.actions import OpaqueFunction
from launch.substitutions import LaunchConfiguration
from launch_ros.actions import Node


def launch_setup(context, *args, **kwargs):
    desc = context.perform_substitution(LaunchConfiguration("description"))
    return [Node(package="robot_state_publisher", executable="robot_state_publisher",
                 parameters=[{"robot_description": desc}])]


def generate_launch_description():
    return LaunchDescription([OpaqueFunction(function=launch_setup)])
