"""U rules: what the model builder could not read (reported where it was written), the declared URDF version
against the target distribution's urdfdom, and quaternion origins (URDF 1.1)."""
from __future__ import annotations

import math
import os
from pathlib import Path

from urdfcheck.core.findings import Problem, Severity
from urdfcheck.core.records import TYPE_CHECKING
from urdfcheck.model import grammar as G
from urdfcheck.rules.catalogue import check

if TYPE_CHECKING:  # the checks' argument types (no import at run time)
    from collections.abc import Iterator

    from urdfcheck.model.robot import Model
    from urdfcheck.rules.engine import Context


@check("U001", "U002", "U003", "U004", "U005", "U006", "U008", "U009")
def unreadable_values(model: Model, ctx: Context) -> Iterator[Problem]:
    for issue in model.issues:
        yield Problem(issue.message, at=issue.loc, code=issue.code, severity=issue.severity)


# --- U007: the declared URDF version ----------------------------------------------------------------------------
def target_of(model, ctx) -> tuple[G.Target, str]:
    """The target distribution and why: the config/command line (`target`), else what the enclosing package
    tells (a catkin package is ROS 1, i.e. Noetic), else what the workspace names, else Humble."""
    # the request's merged target (flag over config) when the engine hands it over, else the config's key
    name = getattr(ctx, "target", None) or getattr(getattr(ctx, "config", None), "target", None)
    if name in G.TARGETS:
        return G.TARGETS[name], "the configured target (--target or the config key)"
    if _catkin_package(model.source):
        return G.TARGETS["noetic"], "the enclosing package.xml builds with catkin (ROS 1)"
    return assumed_target(model.source)


def describe_target(source: str, configured: str | None = None) -> tuple[str, str]:
    """(distribution, why) for a model file, as U007 and the profiles decide it (`lint --list` prints it)."""
    if configured in G.TARGETS:
        return configured, "the configured target (--target or the config key)"
    if _catkin_package(source):
        return "noetic", "the enclosing package.xml builds with catkin (ROS 1)"
    t, why = assumed_target(source)
    return t.name, why


def assumed_target(source: str) -> tuple[G.Target, str]:
    """Without a configured target: what the workspace names (CI files, Dockerfiles, .repos, the branch in
    .git/HEAD), else Humble, the oldest supported ROS 2 LTS (issue 25: the newest was the least likely one)."""
    if source and not source.startswith("<"):
        from urdfcheck.load.distro import workspace_distro

        found = workspace_distro(os.path.dirname(os.path.abspath(source)))
        if found is not None and found[0] in G.TARGETS:
            return G.TARGETS[found[0]], f"assumed: {found[1]}; set target: to change it"
    return G.TARGETS[G.DEFAULT_TARGET], ("assumed: the oldest supported ROS 2 LTS, as nothing in the workspace names "
                                         "a distribution; set target: or --target to change it")


_CATKIN: dict[str, bool] = {}


def _catkin_package(source: str) -> bool:
    if not source or source.startswith("<"):
        return False
    from urdfcheck.load.packages import enclosing_package

    d = enclosing_package(Path(os.path.abspath(source)).parent)
    if d is None:
        return False
    key = str(d)
    if key not in _CATKIN:
        try:
            from urdfcheck.core import door  # a regular file only: a FIFO must not block

            head = door.read_bytes(d / "package.xml", limit=65536)
        except OSError:
            head = b""
        _CATKIN[key] = b"<buildtool_depend>catkin</buildtool_depend>" in head.replace(b" ", b"")
    return _CATKIN[key]


@check("U007")
def urdf_version(model: Model, ctx: Context) -> Iterator[Problem]:
    raw = model.declared_version
    if raw is None:
        return  # URDF 1.0, read by every urdfdom
    version, error = G.parse_version(raw)
    where = f'<robot version="{raw}">'
    if error:
        yield Problem(f"{where}: urdfdom refuses the model (\"{error}\"), so robot_state_publisher does not start; "
                      f"write version=\"1.0\" (or leave it out)", at=model)
        return
    if version not in G.VERSIONS:
        text = G.version_text(version)  # type: ignore[arg-type]  # no error: parse_version gave a version
        yield Problem(f"{where}: no URDF version {text} exists; urdfdom refuses the model "
                      f"(6.0: \"{G.supported_message(G.NEWEST)}\"; before 5.1: \"{G.supported_message(G.V1_0)}\"), "
                      f"so robot_state_publisher does not start", at=model)
        return
    target, why = target_of(model, ctx)
    if version > target.newest:
        need = "5.1" if version == G.V1_1 else "6.0"
        yield Problem(f"{where} needs urdfdom >= {need} (ROS 2 Rolling), but {target.name} ships urdfdom "
                      f"{target.urdfdom}, which refuses the model (\"{G.supported_message(target.newest)}\"): "
                      f"robot_state_publisher does not start (target {target.name}: {why}); write the model as "
                      f"URDF {G.version_text(target.newest)} (rpy instead of quat_xyzw, no acceleration/jerk "
                      f"limits) or set the target to rolling", at=model)


# --- U010: quaternions ----------------------------------------------------------------------------------------------
def _origins(model):
    for j in model.joint_list:
        yield j.origin
    for link in model.link_list:
        if link.inertial is not None:
            yield link.inertial.origin
        for s in link.visuals:
            yield s.origin
        for s in link.collisions:
            yield s.origin


@check("U010")
def quaternion_not_unit(model: Model, ctx: Context) -> Iterator[Problem]:
    if model.version < G.V1_1:
        return  # no quaternion is read (U008 says so)
    tol = float(ctx.options["tolerance"])  # typed and defaulted by the catalogue (rules/U010.yaml)
    for o in _origins(model):
        q = o.quat
        if q is None or o.loc is None:
            continue
        norm = math.sqrt(sum(v * v for v in q))
        text = " ".join(f"{v:g}" for v in q)
        if norm == 0.0:
            yield Problem(f"quat_xyzw=\"{text}\" is the zero quaternion, which is no rotation: urdfdom silently "
                          f"reads it as the identity", at=o.loc, severity=Severity.ERROR)
        elif abs(norm - 1.0) > tol:
            unit = " ".join(f"{v / norm:.9g}" for v in q)
            yield Problem(f"quat_xyzw=\"{text}\" has length {norm:.6g}, not 1: urdfdom divides it by its length "
                          f"and uses {unit}; write that (a typo in one component changes the rotation without a "
                          f"word)", at=o.loc)
