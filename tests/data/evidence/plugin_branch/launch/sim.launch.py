from launch import LaunchDescription
from launch.substitutions import Command, PathJoinSubstitution
from launch_ros.actions import Node
from launch_ros.substitutions import FindPackageShare


def generate_launch_description():
    model = PathJoinSubstitution([FindPackageShare("branchbot"), "urdf", "robot.urdf.xacro"])
    return LaunchDescription([
        Node(package="robot_state_publisher", executable="robot_state_publisher",
             parameters=[{"robot_description": Command(["xacro ", model])}]),
        Node(package="gazebo_ros", executable="spawn_entity.py", arguments=["-topic", "robot_description"]),
        Node(package="controller_manager", executable="spawner", arguments=["joint_state_broadcaster"]),
    ])
