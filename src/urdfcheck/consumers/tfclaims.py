"""TF claims: who publishes which parent -> child transform (the model, launch files, consumers, the config).

Claims (`TFClaim(parent, child, owner, kind, loc)`) come from

* the model, published by robot_state_publisher (`claims_from_model`): fixed and planar joints are static
  (/tf_static; RSP publishes a planar joint at its zero position), revolute/continuous/prismatic joints are
  dynamic (/tf), floating joints are skipped (RSP does not publish them). Only the first joint per child
  link is used (a second parent is the model's own structure error);
* static_transform_publisher nodes in launch files (static);
* controllers and drivers that broadcast odometry (dynamic odom -> base);
* localization, SLAM and drivers that broadcast frames (robot_localization, AMCL, slam_toolbox, cartographer,
  realsense2_camera: `localization.py`, data in `tfowners.yaml`);
* Gazebo plugins and gz-sim systems in the model's <gazebo> blocks (`consumers.gazebo.plugin_claims`, source
  "gazebo"): their odometry transforms (dynamic), counted against the controllers' only when the controllers run
  in the simulator (`rules.checks.tf._apart`);
* owners declared in the config (`tf_owners: {"map->odom": amcl}`) (dynamic). A declaration that names the
  publisher already read for that edge (`add_declared`: the same owner, its node name, or its kind, e.g.
  `map_to_odom`, `static_transform_publisher`, `diff_drive_controller`) documents that publisher and adds no
  second claim; one naming somebody else is a second publisher (T001/T002).

Frame names are compared without a leading "/". The analysis of the graph they make (`rules.checks.tf.graph`)
sits beside the T rules.
"""
from __future__ import annotations

from collections.abc import Iterable, Mapping

from urdfcheck.core.findings import Location
from urdfcheck.core.records import TupleRecord

STATIC = "static"
DYNAMIC = "dynamic"
RSP = "robot_state_publisher"


class TFClaim(TupleRecord):
    parent: str
    child: str
    owner: str  # "robot_state_publisher", "static_transform_publisher <name>", a controller name, "amcl", ...
    kind: str  # "static" or "dynamic"
    loc: Location
    source: str = ""  # "model", "launch", "controller", "driver", "localization", "config"

    @property
    def edge(self) -> tuple[str, str]:
        return (self.parent, self.child)


def norm(frame: str) -> str:
    return str(frame).strip().lstrip("/")


# --- claim sources -----------------------------------------------------------------------------------
def claims_from_model(model, prefix: str = "", owner: str = RSP) -> list[TFClaim]:
    """robot_state_publisher's transforms for a Model (frame_prefix applied)."""
    out = []
    seen: set[str] = set()
    for j in model.joint_list:
        if j.parent is None or j.child is None or j.child in seen:
            continue
        seen.add(j.child)
        if j.type == "floating":
            continue
        kind = STATIC if j.type in ("fixed", "planar") else DYNAMIC
        out.append(TFClaim(prefix + j.parent, prefix + j.child, owner, kind, j.loc, "model"))
    return out


def claims_from_static_tfs(static_tfs: Iterable, notes: list | None = None) -> list[TFClaim]:
    out = []
    for s in static_tfs:
        if getattr(s, "condition", None):
            if notes is not None:
                notes.append((f"static transform {s.parent} -> {s.child} is conditional ({s.condition}); "
                               f"left out of the TF graph", s.loc))
            continue
        owner = "static_transform_publisher" + (f" {s.node_name}" if getattr(s, "node_name", "") else "")
        out.append(TFClaim(s.parent, s.child, owner, STATIC, s.loc, "launch"))
    return out


def claims_from_odom(odom_tfs: Iterable, base_frame: str = "base_link", source: str = "controller") -> list[TFClaim]:
    """From `controllers.OdomTF`s (enabled ones); an empty child means the configured base frame."""
    out = []
    for o in odom_tfs:
        if o is None or not o.enabled:
            continue
        out.append(TFClaim(o.parent, o.child or base_frame, o.owner, DYNAMIC, o.loc, source))
    return out


def claims_from_localization(nodes: Iterable) -> list[TFClaim]:
    out = []
    for n in nodes:
        owner = {"ekf": "robot_localization (ekf)", "ukf": "robot_localization (ukf)"}.get(n.kind, n.kind)
        for e in n.edges():  # localization, SLAM and drivers: every edge the node's parameters turn on
            kind = STATIC if e.kind == STATIC else DYNAMIC
            out.append(TFClaim(e.parent, e.child, f"{owner} {n.node}", kind, e.loc, "localization"))
    return out


def parse_edge(text: str) -> tuple[str, str] | None:
    """"map->odom", "map -> odom", "map/odom"? only the arrow forms."""
    for sep in ("->", "→", " to "):
        if sep in text:
            a, b = text.split(sep, 1)
            a, b = norm(a), norm(b)
            if a and b:
                return a, b
    return None


# the source of a `tf_owners` declaration in a config the runner did not vouch for (found in the checkout, or named
# without --trust-config; issue 36). It may add a publisher, and so a conflict (T001..T004), never make a frame
# published that nothing read publishes: T005, C020 and C024 judge the graph without it (`vouched_claims`).
UNTRUSTED = "config (untrusted)"
DECLARED = ("config", UNTRUSTED)


def claims_from_owners(owners: Mapping[str, str], locs: Mapping[str, Location] | None = None,
                       default_loc: Location | None = None, source: str = "config") -> list[TFClaim]:
    out = []
    for edge_text, owner in owners.items():
        e = parse_edge(edge_text)
        if e is None:
            continue
        loc = (locs or {}).get(edge_text) or default_loc or Location("<config>")
        out.append(TFClaim(e[0], e[1], str(owner), DYNAMIC, loc, source))
    return out
