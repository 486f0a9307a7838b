"""A re-implementation of robot_state_publisher (ROS 2 by default, ROS 1 Noetic as a profile) and batch FK.

Public API::

    from urdfcheck.publisher import (JointState, Transform, Stamp, Profile, StatePublisher, JointStateError,
                                     link_poses, configuration_joints, lookup, kinematic_tree)

    pub = StatePublisher(model)                      # profile="ros2", frame_prefix="", publish_frequency=20
    pub.static_transforms()                          # -> [Transform] for /tf_static
    pub.on_joint_state(JointState(["j1"], [0.5], stamp=1.0))   # -> [Transform] for /tf ([] if throttled)
    pub.last_unknown                                 # names in the last message that are not joints
    link_poses(model, q)                             # {link: (N,4,4) numpy} (numpy imported lazily)
    lookup(model, "base_link", "tool0", {"j1": 0.5}) # pose of tool0 in base_link (tf2_echo base_link tool0)

Nothing here imports numpy, Pinocchio or yourdfpy at import time.
"""
from __future__ import annotations

from urdfcheck.publisher.batch import configuration_joints, link_poses
from urdfcheck.publisher.kinematics import KinematicTree, Note, Segment, kinematic_tree
from urdfcheck.publisher.lookup import TransformLookupError, lookup, lookup_matrix
from urdfcheck.publisher.messages import JointState, Stamp, Transform, stamp_from_ns, to_ns
from urdfcheck.publisher.state import PROFILES, ROS1, ROS2, JointStateError, Profile, StatePublisher, get_profile

__all__ = [
    "JointState", "Transform", "Stamp", "stamp_from_ns", "to_ns",
    "Profile", "ROS1", "ROS2", "PROFILES", "get_profile", "StatePublisher", "JointStateError",
    "KinematicTree", "Segment", "Note", "kinematic_tree",
    "link_poses", "configuration_joints",
    "lookup", "lookup_matrix", "TransformLookupError",
]
