# like denso_robot_bringup: `name` is a launch argument without default, passed on to xacro
from launch import LaunchDescription
from launch.actions import DeclareLaunchArgument
from launch.substitutions import Command, LaunchConfiguration, PathJoinSubstitution
from launch_ros.actions import Node
from launch_ros.substitutions import FindPackageShare


def generate_launch_description():
    model = PathJoinSubstitution([FindPackageShare("arm_bringup"), "urdf", "arm.urdf.xacro"])
    return LaunchDescription([
        DeclareLaunchArgument("name", description="Type of the arm."),
        Node(package="robot_state_publisher", executable="robot_state_publisher",
             parameters=[{"robot_description": Command(["xacro ", model, " name:=", LaunchConfiguration("name")])}]),
    ])
