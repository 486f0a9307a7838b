"""C024: a navigation or perception parameter file names a frame that nobody publishes (issue 41).

The frames come from `consumers.navigation`; what is published is the TF graph C020 and the T rules use (the
model's links under robot_state_publisher's prefix, launch files' static transforms, odometry and localization
owners, Gazebo plugins, declared owners), plus the REP-105 frames localization provides (`map`, `odom`, `earth`,
and the names the config gives them). A claim that nobody publishes a frame is a warning only where a launch file
of the deployment starts a Nav2 node with the file; a file that only lies in the package gives an info.
"""
from __future__ import annotations

import os
from collections.abc import Iterator

from urdfcheck.core.findings import Problem, Severity
from urdfcheck.core.records import TYPE_CHECKING
from urdfcheck.rules.catalogue import check

if TYPE_CHECKING:  # the checks' argument types (no import at run time)
    from urdfcheck.model.robot import Model
    from urdfcheck.rules.engine import Context

_REP105 = ("map", "odom", "earth")
_OWN_EDGE_OF = {"amcl": "odom_frame_id", "slam_toolbox": "odom_frame"}
_OWN_EDGE = frozenset(_OWN_EDGE_OF.values())
_SCAN_PACKAGES = ("depthimage_to_laserscan", "pointcloud_to_laserscan")


def _files(c) -> tuple[list[str], set[str]]:
    """Parameter files to read, and the real paths of those a launch file of the deployment gives a Nav2 node."""
    launched = {os.path.realpath(f) for f in c.files.get("localization", ())}
    seen: dict[str, str] = {}
    for key in ("localization", "package", "params"):
        for f in c.files.get(key, ()):
            if f.endswith((".yaml", ".yml")):
                seen.setdefault(os.path.realpath(f), f)
    # a launch file read with the model (zero config) that gives a navigation node the file, by its last two
    # path components (the launch file names it in the install layout: $(find-pkg-share pkg)/config/x.yaml)
    tails = {_tail(pf) for li in c.launch for n in li.nodes
             if not n.condition and (n.package.startswith("nav2_") or n.package in _SCAN_PACKAGES)
             for pf in n.param_files if isinstance(pf, str) and "\x00" not in pf}
    launched |= {real for real, f in seen.items() if _tail(f) in tails}
    # nav2_bringup's launch files take the whole Nav2 parameter file as `params_file`; a launch file of the
    # deployment that passes one (under no undecided condition) runs Nav2 with it
    for li in c.launch:
        for inc in li.includes:
            v = inc.args.get("params_file") if not inc.condition else None
            if isinstance(v, str) and v.endswith((".yaml", ".yml")) and "\x00" not in v and os.path.isfile(v):
                real = os.path.realpath(v)
                seen.setdefault(real, v)
                launched.add(real)
    return list(seen.values()), launched


def _tail(path: str) -> str:
    return "/".join(path.replace(os.sep, "/").split("/")[-2:])


@check("C024", needs="consumers")
def navigation_frame_unknown(model: Model, ctx: Context) -> Iterator[Problem]:
    from urdfcheck.consumers.consumers import _Reader
    from urdfcheck.consumers.consumers import consumers_of as consumers
    from urdfcheck.consumers.navigation import nav_frames
    from urdfcheck.rules.checks.contracts import _suggest_frame, _unresolved
    from urdfcheck.rules.checks.tf.graph import deployment_graph as _graph
    from urdfcheck.rules.checks.tf.graph import vouched_claims

    c = consumers(model, ctx)
    paths, launched = _files(c)
    r = _Reader()
    pfs = [pf for pf in (r.params(p, []) for p in paths) if pf is not None] if paths else []
    frames = [(nf.value, nf.node, nf.key, nf.file, os.path.realpath(nf.file) in launched) for nf in nav_frames(pfs)]
    frames += _odom_frames(c)
    if not frames:
        return
    prefix = c.rsp_prefix
    links = {prefix + n for n in model.links}
    g = vouched_claims(_graph(model, c))  # an untrusted config's declared owners publish nothing (issue 36)
    published = {f for cl in g.claims for f in (cl.parent, cl.child)}
    owners: dict[str, set] = {}  # frame -> owners of the claims naming it
    for cl in g.claims:
        for f in (cl.parent, cl.child):
            owners.setdefault(f, set()).add(cl.owner)
    known = links | published | set(_REP105) | {v for v in c.frames.values() if v}
    seen = set()
    for value, node, key, _file, strong in frames:
        name = str(value.value).strip().lstrip("/")
        if not name or _unresolved(name) or "<" in name or name in links or name in _REP105:
            continue
        if key in _OWN_EDGE:  # a localization node's odom frame: its own map -> odom claim does not publish it
            mine = f" {node}"
            if any(not o.endswith(mine) for o in owners.get(name, ())):
                continue
        elif name in known:
            continue
        if (name, str(value.loc)) in seen:
            continue
        seen.add((name, str(value.loc)))
        hint = _suggest_frame(name, sorted((links | published) - {name}))
        yield Problem(f"{node.lstrip('/')} parameter {key}: frame {name!r} is neither a link of the model nor "
                      f"published by anything in the deployment{hint}; the node waits for a transform that never "
                      f"comes", at=value.loc, data={"frame": name, "node": node, "key": key},
                      severity=None if strong else Severity.INFO, absent=None if hint else "publish it")


def _odom_frames(c) -> list[tuple]:
    """AMCL's and slam_toolbox's odom frame: they publish map -> odom and look odom -> base up from odometry."""
    out = []
    deployed = {id(n) for n in c.localization} if c.origin == "deployment" else set()
    for n in [*c.localization, *c.elsewhere_localization]:
        key = _OWN_EDGE_OF.get(n.kind)
        v = n.values.get(key) if key else None
        if v is None or getattr(v, "default", False) or not isinstance(v.value, str):
            continue
        out.append((v, n.node, key, n.file, id(n) in deployed))
    return out
