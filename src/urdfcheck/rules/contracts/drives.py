"""Wheel sets of the catalogue's drives other than diff_drive (steering controllers, tricycle, mecanum) against
the model.

`drive_of(model, wheelset, base)` turns the traction wheels into a `DriveSpec` whose sides are taken from the
model (y > 0 in the base frame is left, REP-103), so that track width, wheel radius, axis alignment and wheel
directions are compared by `wheels.check_drive` (C010, C011, C012, C015). `geometry_problems` compares what
only these drives have (C016): the wheelbase of the steering controllers and tricycle_controller (the distance
along x between the traction wheels and the steering joints, measured at the zero configuration between joint
origins), and mecanum_drive_controller's `sum_of_robot_center_projection_on_X_Y_axis` (lx + ly: the mean
distance of the wheels' tyre centres (their rolling features, as `wheels.check_drive` picks them) from the base
frame's origin along x plus along y).
"""
from __future__ import annotations

from urdfcheck.consumers.controllers import DriveSpec, number, number_text
from urdfcheck.core import geometry as G
from urdfcheck.core.findings import Severity
from urdfcheck.rules.contracts.wheels import WheelProblem, _base_frame, _unit, _wheel_shape


def _positions(model, poses, uses, base: str, feature: bool = True) -> list:
    """(use, joint, position in the base frame) per wheel: the centre of its rolling feature (the tyre, see
    wheels.check_drive), else the joint frame (a steering joint has no rolling feature)."""
    inv = G.inverse(poses[base])
    out = []
    for u in uses:
        j = model.joints.get(u.joint)
        if j is None or j.child not in poses:
            continue
        t = G.compose(inv, poses[j.child])
        link = model.links.get(j.child)
        shape = None
        axis = _unit(j.axis) if j.movable and feature else None
        if link is not None and axis is not None:
            _kind, shape, _others = _wheel_shape(link, axis, 0.001, 0.001)
        out.append((u, j, G.translation(G.compose(t, G.origin_matrix(shape.origin)) if shape is not None else t)))
    return out


def drive_of(model, ws, base: str | None) -> DriveSpec | None:
    """The traction wheels of `ws` as a DriveSpec (sides from the model), None when none is in the model."""
    if not ws.traction:
        return None
    poses = model.world_poses()
    probe = DriveSpec(ws.owner, ws.loc, tuple(ws.traction), (), ws.loc, ws.loc, None, None)
    b = _base_frame(model, poses, probe, base)
    if b is None:
        return None
    placed = _positions(model, poses, ws.traction, b)
    left = tuple(u for u, _, p in placed if p[1] > 0)
    right = tuple(u for u, _, p in placed if p[1] <= 0)
    if not placed:
        return None
    return DriveSpec(owner=ws.owner, loc=ws.loc, left=left, right=right,
                     left_loc=left[0].loc if left else ws.loc, right_loc=right[0].loc if right else ws.loc,
                     wheel_separation=ws.track if ws.kind != "mecanum" else None, wheel_radius=ws.radius,
                     sided=False, separation_key=ws.track_key or "track width", radius_key=ws.radius_key or "radius")


def _mean(xs):
    return sum(xs) / len(xs)


def geometry_problems(model, ws, base: str | None, tolerance: float) -> list[WheelProblem]:
    poses = model.world_poses()
    probe = DriveSpec(ws.owner, ws.loc, tuple(ws.traction) + tuple(ws.steering), (), ws.loc, ws.loc, None, None)
    b = _base_frame(model, poses, probe, base)
    if b is None:
        return []
    out = []
    if ws.kind in ("steering", "tricycle"):
        tr = _positions(model, poses, ws.traction, b)
        st = _positions(model, poses, ws.steering, b, feature=False)
        if not tr or not st:
            return []
        measured = abs(_mean([p[0] for _, _, p in tr]) - _mean([p[0] for _, _, p in st]))
        said = number(ws.wheelbase)
        names = f"{', '.join(u.joint for u, _, _ in tr)} / {', '.join(u.joint for u, _, _ in st)}"
        related = (tr[0][1].loc, st[0][1].loc)
        data = {"measured": measured, "expected": said, "tolerance": tolerance}
        if ws.wheelbase is None and ws.from_urdf:
            pass  # ROS 1 ackermann_steering_controller measures wheel_separation_h in the URDF itself
        elif ws.wheelbase is None:
            out.append(WheelProblem(
                "C016", f"{ws.owner} sets no {ws.wheelbase_key} (it defaults to 0: the controller refuses it or "
                        f"cannot turn); the model's traction and steering joints ({names}) are {measured:.6g} m "
                        f"apart along x", ws.loc, related, None, data))
        elif said is not None and abs(said - measured) > tolerance:
            out.append(WheelProblem(
                "C016", f"{ws.owner}: {ws.wheelbase_key} {number_text(ws.wheelbase)} m, but the model's traction "
                        f"and steering joints ({names}) are {measured:.6g} m apart along x (difference "
                        f"{abs(said - measured):.6g} m, tolerance {tolerance:.6g} m): the robot turns on another "
                        f"radius than commanded and its odometry heading drifts", ws.wheelbase.loc, related, None,
                data))
    elif ws.kind == "mecanum" and ws.projection is not None:
        tr = _positions(model, poses, ws.traction, b)
        said = number(ws.projection)
        if len(tr) < 4 or said is None:
            return []
        measured = _mean([abs(p[0]) for _, _, p in tr]) + _mean([abs(p[1]) for _, _, p in tr])
        if abs(said - measured) > tolerance:
            out.append(WheelProblem(
                "C016", f"{ws.owner}: {ws.projection_key} {number_text(ws.projection)} m, but the model's wheels "
                        f"({', '.join(u.joint for u, _, _ in tr)}) sit {measured:.6g} m from {b} along x plus "
                        f"along y (lx + ly; difference {abs(said - measured):.6g} m, tolerance {tolerance:.6g} m): "
                        f"rotation commands and odometry are scaled wrongly", ws.projection.loc,
                tuple(j.loc for _, j, _ in tr[:2]), Severity.ERROR, {"measured": measured, "expected": said}))
    return out
