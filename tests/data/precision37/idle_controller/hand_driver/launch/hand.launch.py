# like schunk_svh_driver: the hand's side is a launch argument; only the controller it names is spawned
from launch import LaunchDescription
from launch.actions import DeclareLaunchArgument
from launch.substitutions import Command, LaunchConfiguration, PathJoinSubstitution
from launch_ros.actions import Node
from launch_ros.substitutions import FindPackageShare


def generate_launch_description():
    control = LaunchConfiguration("control")
    model = PathJoinSubstitution([FindPackageShare("hand_driver"), "urdf", "hand.urdf"])
    controllers = PathJoinSubstitution([FindPackageShare("hand_driver"), "config", "hand.yaml"])
    return LaunchDescription([
        DeclareLaunchArgument("control", default_value="right_hand"),
        Node(package="controller_manager", executable="ros2_control_node", parameters=[controllers]),
        Node(package="robot_state_publisher", executable="robot_state_publisher",
             parameters=[{"robot_description": Command(["cat ", model])}]),
        Node(package="controller_manager", executable="spawner", arguments=["joint_state_broadcaster"]),
        Node(package="controller_manager", executable="spawner", arguments=[control]),
    ])
