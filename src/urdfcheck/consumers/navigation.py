"""Frames named by navigation and perception parameter files (issue 41): Nav2 costmaps, bt_navigator and the
other Nav2 servers, the collision monitor, depth-image and point-cloud to laser-scan converters.

None of these nodes publishes the frames it names: each looks them up in TF and stops (a costmap waiting for
`robot_base_frame`, a scan converter stamping scans no one can transform) when nobody publishes them. The
parameters and their defaults are those of the nodes' own declarations:

* nav2_costmap_2d (`costmap_2d_ros.cpp`): `global_frame`, `robot_base_frame`; obstacle and voxel layers
  (`obstacle_layer.cpp`): `observation_sources`, each `<source>.sensor_frame` ("" = the message's frame);
* nav2_bt_navigator (`bt_navigator.cpp`), nav2_behaviors (`behavior_server.cpp`), nav2_smoother:
  `global_frame`, `robot_base_frame`, `local_frame`;
* nav2_collision_monitor (`collision_monitor_node.cpp`): `base_frame_id`, `odom_frame_id`;
* depthimage_to_laserscan (`DepthImageToLaserScanROS.cpp`): `output_frame`;
  pointcloud_to_laserscan (`pointcloud_to_laserscan_node.cpp`): `target_frame` ("" = the cloud's frame).

Nodes are recognised by their names or, for renamed nodes, by keys only those nodes have. AMCL's base frame is
read with the TF owners (`localization`) and checked by C020.
"""
from __future__ import annotations

from collections.abc import Iterable

from urdfcheck.consumers.common import Value
from urdfcheck.consumers.params import ParamFile
from urdfcheck.core.records import TupleRecord

_NAV_NODES = {
    "local_costmap": ("global_frame", "robot_base_frame"),
    "global_costmap": ("global_frame", "robot_base_frame"),
    "bt_navigator": ("global_frame", "robot_base_frame"),
    "behavior_server": ("global_frame", "robot_base_frame", "local_frame"),
    "recoveries_server": ("global_frame", "robot_base_frame"),
    "smoother_server": ("robot_base_frame",),
    "collision_monitor": ("base_frame_id", "odom_frame_id"),
    "collision_detector": ("base_frame_id", "odom_frame_id"),
    "depthimage_to_laserscan": ("output_frame",),
    "depthimage_to_laserscan_node": ("output_frame",),
    "pointcloud_to_laserscan": ("target_frame",),
    "pointcloud_to_laserscan_node": ("target_frame",),
}
_COSTMAPS = ("local_costmap", "global_costmap")


class NavFrame(TupleRecord):
    """A frame a navigation or perception node names: `value` (a Value with its location), the node, the key."""

    value: Value
    node: str
    key: str
    file: str


def _kind(basename: str, params: dict) -> str | None:
    if basename in _NAV_NODES:
        return basename
    if "robot_base_frame" in params and ("plugins" in params or "footprint" in params
                                         or "robot_radius" in params):
        return "local_costmap"  # a costmap under another name
    if "output_frame" in params and "scan_height" in params:
        return "depthimage_to_laserscan"
    if "target_frame" in params and "min_height" in params and "angle_min" in params:
        return "pointcloud_to_laserscan"
    return None


def nav_frames(files: Iterable[ParamFile]) -> list[NavFrame]:
    out: list[NavFrame] = []
    for pf in files:
        if pf.dialect != "ros2":
            continue
        for key, node in pf.nodes.items():
            kind = _kind(node.basename, node.params)
            if kind is None:
                continue
            for name in _NAV_NODES[kind]:
                v = node.params.get(name)
                if v is not None and isinstance(v.value, str) and v.value.strip():
                    out.append(NavFrame(v, key, name, pf.path))
            if kind in _COSTMAPS:
                out.extend(_sensor_frames(node, key, pf.path))
    return out


def _sensor_frames(node, key: str, path: str) -> list[NavFrame]:
    """`<layer>.<source>.sensor_frame` of each observation source an obstacle or voxel layer lists."""
    out = []
    for pname, v in node.params.items():
        if not pname.endswith(".observation_sources"):
            continue
        sources = v.value.split() if isinstance(v.value, str) else v.value if isinstance(v.value, list) else []
        layer = pname[: -len(".observation_sources")]
        for source in (s for s in sources if isinstance(s, str)):
            sv = node.params.get(f"{layer}.{source}.sensor_frame")
            if sv is not None and isinstance(sv.value, str) and sv.value.strip():
                out.append(NavFrame(sv, key, f"{layer}.{source}.sensor_frame", path))
    return out
