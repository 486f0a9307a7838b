# the robot's file is a required launch argument (no default): the path is nothing but a launch-time piece
from launch import LaunchDescription
from launch.actions import DeclareLaunchArgument
from launch.substitutions import Command, LaunchConfiguration
from launch_ros.actions import Node


def generate_launch_description():
    return LaunchDescription([
        DeclareLaunchArgument("robot_xacro_file", description="Xacro describing the robot."),
        Node(package="robot_state_publisher", executable="robot_state_publisher",
             parameters=[{"robot_description": Command(["xacro ", LaunchConfiguration("robot_xacro_file")])}]),
    ])
