# like panther: `wheel_type:=custom` is documented to need the user's own wheel_config_file
from launch import LaunchDescription
from launch.actions import DeclareLaunchArgument
from launch.substitutions import Command, LaunchConfiguration, PathJoinSubstitution
from launch_ros.actions import Node
from launch_ros.substitutions import FindPackageShare


def generate_launch_description():
    wheel_type = LaunchConfiguration("wheel_type")
    model = PathJoinSubstitution([FindPackageShare("wh_description"), "urdf", "rover.urdf.xacro"])
    wheels = PathJoinSubstitution([FindPackageShare("wh_description"), "config", wheel_type])
    return LaunchDescription([
        DeclareLaunchArgument("wheel_type", default_value="WH01.yaml", choices=["WH01.yaml", "custom.yaml"]),
        Node(package="robot_state_publisher", executable="robot_state_publisher",
             parameters=[{"robot_description": Command(["xacro ", model, " wheel_config_file:=", wheels])}]),
    ])
