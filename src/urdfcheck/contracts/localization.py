"""Localization nodes read from parameter files, and the TF edge each one broadcasts.

robot_localization (`ekf_node`, `ukf_node`; ROS 1 and ROS 2): `map_frame` (map), `odom_frame` (odom),
`base_link_frame` (base_link), `world_frame` (defaults to odom_frame), `publish_tf` (true).
world_frame == odom_frame -> publishes odom -> base_link; world_frame == map_frame -> map -> odom.

AMCL (nav2 and ROS 1): `global_frame_id` (map), `odom_frame_id` (odom), `base_frame_id`
(nav2: base_footprint, ROS 1: base_link), `tf_broadcast` (true) -> map -> odom.

A node is recognised by its parameters (robot_localization: `world_frame`/`base_link_frame` or a sensor
input such as `odom0`/`imu0`; AMCL: `global_frame_id` with `odom_frame_id`, or a node called `amcl`).
"""
from __future__ import annotations

import re
from collections.abc import Iterable
from typing import NamedTuple

from urdfcheck.contracts.common import Value, as_bool
from urdfcheck.contracts.params import NodeParams, ParamFile
from urdfcheck.core.findings import Location

_RL_INPUT = re.compile(r"^(odom|imu|pose|twist)\d+$")


class LocalizationNode(NamedTuple):
    node: str
    kind: str  # "ekf", "ukf", "amcl"
    file: str
    loc: Location
    publish_tf: Value
    world_frame: Value
    map_frame: Value
    odom_frame: Value
    base_frame: Value

    @property
    def publishes(self) -> bool:
        return bool(as_bool(self.publish_tf.value))

    def edge(self) -> tuple[str, str] | None:
        """(parent, child) of the transform it broadcasts; None when it broadcasts none (or world_frame is odd)."""
        if not self.publishes:
            return None
        world = _frame(self.world_frame)
        if world == _frame(self.odom_frame):
            return (_frame(self.odom_frame), _frame(self.base_frame))
        if world == _frame(self.map_frame):
            return (_frame(self.map_frame), _frame(self.odom_frame))
        return None

    @property
    def edge_loc(self) -> Location:
        """Where the decision was written: publish_tf if set, else world_frame, else the node."""
        for v in (self.world_frame, self.publish_tf):
            if not v.default:
                return v.loc
        return self.loc


def _frame(v: Value) -> str:
    return str(v.value).strip().lstrip("/")


def _is_robot_localization(node: NodeParams) -> bool:
    p = node.params
    if "world_frame" in p or "base_link_frame" in p:
        return True
    return any(_RL_INPUT.match(k) for k in p) and ("frequency" in p or "two_d_mode" in p)


def _is_amcl(node: NodeParams) -> bool:
    p = node.params
    return ("global_frame_id" in p and "odom_frame_id" in p) or (node.basename == "amcl" and bool(p))


def _val(node: NodeParams, key: str, default) -> Value:
    v = node.params.get(key)
    if v is None:
        return Value(default, node.loc, default=True)
    return v


def localization_from_params(files: Iterable[ParamFile]) -> list[LocalizationNode]:
    out: list[LocalizationNode] = []
    for pf in files:
        for key, node in pf.nodes.items():
            if _is_robot_localization(node):
                odom = _val(node, "odom_frame", "odom")
                world = node.params.get("world_frame") or Value(odom.value, node.loc, default=True)
                kind = "ukf" if "ukf" in node.name.lower() or "alpha" in node.params else "ekf"
                out.append(LocalizationNode(
                    node=key, kind=kind, file=pf.path, loc=node.loc,
                    publish_tf=_val(node, "publish_tf", True), world_frame=world,
                    map_frame=_val(node, "map_frame", "map"), odom_frame=odom,
                    base_frame=_val(node, "base_link_frame", "base_link"),
                ))
            elif _is_amcl(node):
                glob = _val(node, "global_frame_id", "map")
                out.append(LocalizationNode(
                    node=key, kind="amcl", file=pf.path, loc=node.loc,
                    publish_tf=_val(node, "tf_broadcast", True), world_frame=glob, map_frame=glob,
                    odom_frame=_val(node, "odom_frame_id", "odom"),
                    base_frame=_val(node, "base_frame_id", "base_footprint" if pf.dialect == "ros2" else "base_link"),
                ))
    return out
