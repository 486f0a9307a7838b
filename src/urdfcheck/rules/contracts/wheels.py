"""Wheel geometry in the model versus what a differential-drive controller or driver is told.

`check_drive(model, drive)` measures, at the zero configuration (`model.world_poses()`, pure Python):

* the rolling feature of each wheel: the largest collision (else visual) cylinder or sphere coaxial with the
  joint axis (a cylinder along the axis, its centre on the axis line; a sphere centred on it). A wheel link
  often holds a hub, a rim and a tyre: the first cylinder is the hub, the largest is what touches the ground.
  With no coaxial shape, the first cylinder or sphere (a cylinder lying the wrong way is then reported);
* separation: the rolling features' centres (else the wheel joint frames), averaged per side, projected on the
  first left wheel's axis, in the base frame: a tyre offset along the axis from its hub joint frame counts where
  the tyre is; compared with `wheel_separation x wheel_separation_multiplier`. A ROS 1 controller given no
  `wheel_separation` computes the plain distance between the wheel joint origins, which is compared with the
  projected separation instead;
* radius: the rolling feature's radius, compared with `wheel_radius x left/right_wheel_radius_multiplier`; a
  cylinder whose axis is not the joint axis is not a wheel rolling on its radius; a ROS 1 controller with no
  `wheel_radius` needs such a shape. When another coaxial shape is close to the largest (a rim inside a thin
  tyre) and the controller's radius lies between the two, the choice rests on shape alone (a `shape` evidence
  step: said as info);
* axes: every wheel's rolling heading in the ground plane (`a x z`) parallel or anti-parallel to the first left
  one's. A camber (the axis tilted out of the ground plane, `rpy="3.14 0 0"` leaves 0.09 degrees) changes no
  heading: below one degree it is the rounding of an rpy and not reported; above, the wheel rolls on its edge;
* counts: as many wheels left as right (none on a side and the controller refuses to start);
* sides (C014): the wheels named left must be on the left of the direction in which positive wheel rotation
  drives the robot. A wheel turning positively about its axis `a` (in the base frame, z up) rolls its centre
  along `a x z`, whose forward (+x) component is `a_y`. diff_drive_controller (ROS 1 and ROS 2) commands
  `w_left = (v - w*s/2)/r`, `w_right = (v + w*s/2)/r` and never looks at the geometry; the robot's actual yaw
  rate is `r*w*(a_y,left + a_y,right) / (y_left - y_right)` per unit commanded `w`. It turns the wrong way
  exactly when `(a_y,left + a_y,right) * (y_left - y_right) < 0`: the left wheels at -y with axes along +y
  (the usual swap), or at +y with both axes along -y (positive rotation drives backward). The left wheels at
  -y with both axes along -y is the correct robot turned 180 degrees about z: it turns the right way (its
  odometry x is reversed, which is not this rule's business). Mixed axis signs (one wheel drives backward)
  leave the turning sense undefined and are not reported here.

Results are structured (`DriveReport`); `DriveReport.problems()` lists them as `WheelProblem`s with the
rule code they belong to. Unknown or non-movable wheel joints are left to the generic joint checks.
"""
from __future__ import annotations

import math

from urdfcheck.consumers.controllers import DriveSpec, JointUse, number, number_text
from urdfcheck.core import geometry as G
from urdfcheck.core.evidence import Step
from urdfcheck.core.findings import Location, Severity
from urdfcheck.core.records import FrozenRecord, Record, TupleRecord

# a camber difference below this is the rounding of an rpy written with 2-4 digits (3.14 leaves 0.09 degrees,
# 1.57 leaves 0.05): no differential-drive consumer reads the axis tilt
CAMBER_TOLERANCE = math.radians(1.0)
AMBIGUOUS_RATIO = 0.75  # another coaxial shape at least this share of the largest radius may be the rolling one
MIN_FORWARD_SIGN = 0.5  # |mean left a_y + mean right a_y| below this: mixed axis signs, turning sense undefined


class Wheel(TupleRecord):
    use: JointUse
    side: str  # "left" / "right"
    link: str
    position: tuple[float, float, float]  # joint frame origin in the base frame
    axis: tuple[float, float, float]  # unit, in the base frame
    joint_loc: Location
    radius: float | None = None
    shape_kind: str = ""  # "cylinder", "sphere", "" (none usable)
    shape_loc: Location | None = None
    shape_from: str = ""  # "collision" / "visual"
    cylinder_misaligned: float | None = None  # angle (rad) between the cylinder axis and the joint axis
    centre: tuple[float, float, float] | None = None  # the rolling feature's centre in the base frame
    others: tuple[float, ...] = ()  # radii of the other coaxial shapes the feature was chosen among


class WheelProblem(FrozenRecord):
    _fields = ('code', 'message', 'at', 'related', 'severity', 'data', 'rests_on')
    code: str
    message: str
    at: Location
    related: tuple[Location, ...]
    severity: Severity | None
    data: dict
    rests_on: tuple

    def __init__(self, code: str,
                 message: str,
                 at: Location,
                 related: tuple[Location, ...] = (),
                 severity: Severity | None = None,
                 data: dict | None = None,
                 rests_on: tuple = ()):
        d = self.__dict__  # FrozenRecord forbids setattr
        d["code"] = code
        d["message"] = message
        d["at"] = at
        d["related"] = related
        d["severity"] = severity
        d["data"] = {} if data is None else data
        d["rests_on"] = tuple(rests_on)


class DriveReport(Record):
    # urdf_distance: |left - right| (what a ROS 1 controller computes)
    # sides_swapped: the left wheels' mean y is below the right wheels' (REP-103 y points left)
    # forward_sign: sum of the mean wheel-axis y per side: > 0 positive rotation drives +x
    # turn_reversed: commanded yaw and physical yaw have opposite signs (C014)
    _fields = ('drive', 'base_frame', 'wheels', 'measured_separation', 'urdf_distance', 'expected_separation',
               'sides_swapped', 'forward_sign', 'turn_reversed', 'problems_', 'notes')

    def __init__(self, drive: DriveSpec,
                 base_frame: str,
                 wheels: list[Wheel] | None = None,
                 measured_separation: float | None = None,
                 urdf_distance: float | None = None,
                 expected_separation: float | None = None,
                 sides_swapped: bool | None = None,
                 forward_sign: float | None = None,
                 turn_reversed: bool | None = None,
                 problems_: list[WheelProblem] | None = None,
                 notes: list | None = None):
        self.drive = drive
        self.base_frame = base_frame
        self.wheels = [] if wheels is None else wheels
        self.measured_separation = measured_separation
        self.urdf_distance = urdf_distance
        self.expected_separation = expected_separation
        self.sides_swapped = sides_swapped
        self.forward_sign = forward_sign
        self.turn_reversed = turn_reversed
        self.problems_ = [] if problems_ is None else problems_
        self.notes = [] if notes is None else notes

    def problems(self) -> list[WheelProblem]:
        return list(self.problems_)


def _unit(v):
    n = G.norm(v)
    return None if n < 1e-12 else tuple(c / n for c in v)


def _dot(a, b) -> float:
    return sum(x * y for x, y in zip(a, b))


def _sub(a, b):
    return tuple(x - y for x, y in zip(a, b))


def _mean(vs):
    n = len(vs)
    return tuple(sum(v[i] for v in vs) / n for i in range(3))


def _angle(a, b) -> float:
    """Angle between two lines (parallel or anti-parallel count as 0)."""
    d = min(1.0, abs(_dot(a, b)))
    return math.acos(d)


def _heading_angle(a, b) -> float:
    """Angle between the rolling headings (`a x z`, in the ground plane) of wheels turning about `a` and `b`
    (parallel or anti-parallel count as 0); the 3-D angle for an axis standing upright (no heading)."""
    ha, hb = _unit((a[1], -a[0], 0.0)), _unit((b[1], -b[0], 0.0))
    if ha is None or hb is None or G.norm((a[0], a[1], 0.0)) < 1e-6 or G.norm((b[0], b[1], 0.0)) < 1e-6:
        return _angle(a, b)
    return _angle(ha, hb)


def _fmt(x: float) -> str:
    return f"{x:.6g}"


def _round_shapes(shapes):
    return [s for s in shapes if s.geometry is not None and s.geometry.kind in ("cylinder", "sphere")
            and s.geometry.radius is not None]


def _coaxial(shape, axis, angle_tolerance: float, tolerance: float) -> bool:
    """The shape (in the wheel link's frame) turns about the joint axis through the link origin: a cylinder along
    the axis, or a sphere, whose centre lies on the axis line."""
    m = G.origin_matrix(shape.origin)
    c = G.translation(m)
    along = _dot(c, axis)
    off = G.norm(tuple(ci - along * ai for ci, ai in zip(c, axis)))
    if off > max(tolerance, 0.05 * shape.geometry.radius):
        return False
    if shape.geometry.kind == "sphere":
        return True
    zc = _unit(G.rotate(m, (0.0, 0.0, 1.0)))
    return zc is not None and _angle(zc, axis) <= angle_tolerance


def _wheel_shape(link, axis=None, angle_tolerance: float = 0.0, tolerance: float = 0.0):
    """(collision/visual, the rolling feature, radii of the other coaxial candidates): the largest coaxial
    cylinder or sphere among the collisions, else the first collision cylinder or sphere (one lying the wrong way
    is reported as such), then the same among the visuals."""
    for kind, shapes in (("collision", link.collisions), ("visual", link.visuals)):
        round_ = _round_shapes(shapes)
        if not round_:
            continue
        if axis is not None:
            coaxial = [s for s in round_ if _coaxial(s, axis, angle_tolerance, tolerance)]
            if coaxial:
                best = max(coaxial, key=lambda s: s.geometry.radius)  # the first of equal radii
                return kind, best, tuple(s.geometry.radius for s in coaxial if s is not best)
        return kind, round_[0], ()
    return "", None, ()


def _base_frame(model, poses, drive: DriveSpec, base: str | None) -> str | None:
    if base and base in poses:
        return base
    for u in drive.left + drive.right:
        j = model.joints.get(u.joint)
        if j is not None and j.child in poses:
            chain = model.chain_to_root(j.child)
            return chain[-1].parent if chain else j.child
    return None


def check_drive(model, drive: DriveSpec, *, base_frame: str | None = None, tolerance: float | None = None,
                angle_tolerance: float | None = None) -> DriveReport:
    """`tolerance` (m) and `angle_tolerance` (rad): the C010-C014 options; None: their catalogue defaults."""
    if tolerance is None or angle_tolerance is None:
        from urdfcheck.rules.catalogue import options_for

        opts = options_for(("C010",))
        tolerance = opts["tolerance"] if tolerance is None else tolerance
        angle_tolerance = opts["angle_tolerance"] if angle_tolerance is None else angle_tolerance
    poses = model.world_poses()
    base = _base_frame(model, poses, drive, base_frame)
    rep = DriveReport(drive, base or "")
    # --- counts (needs no geometry) ---------------------------------------------------------------
    nl, nr = len(drive.left), len(drive.right)
    if nl != nr and drive.sided:
        empty = nl == 0 or nr == 0
        side_empty = "left" if nl == 0 else "right"
        msg = (f"{drive.owner} has {nl} left and {nr} right wheel joint(s)"
               + (f"; with no {side_empty} wheels the controller refuses to start" if empty else
                  "; a differential drive expects the same number on each side"))
        at = (drive.left_loc if nl == 0 else drive.right_loc if nr == 0
              else (drive.left_loc if nl < nr else drive.right_loc))
        other = drive.right_loc if at == drive.left_loc else drive.left_loc
        rep.problems_.append(WheelProblem("C013", msg, at, (other,),
                                          Severity.ERROR if empty else None, {"left": nl, "right": nr}))
    if base is None:
        rep.notes.append(("no wheel joint of the drive is in the model; geometry not compared", drive.loc))
        return rep
    inv_base = G.inverse(poses[base])
    # --- per wheel ----------------------------------------------------------------------------------
    for side, uses in (("left", drive.left), ("right", drive.right)):
        for u in uses:
            j = model.joints.get(u.joint)
            if j is None or not j.movable or j.child not in poses:
                continue
            t = G.compose(inv_base, poses[j.child])
            axis = _unit(G.rotate(t, j.axis))
            if axis is None:
                continue  # zero axis: a joint rule reports it
            link = model.links.get(j.child)
            radius = shape_kind = shape_from = None
            shape_loc = None
            misaligned = None
            centre = None
            others = ()
            ja = _unit(j.axis)
            if link is not None:
                shape_from, shape, others = _wheel_shape(link, ja, angle_tolerance, tolerance)
                if shape is not None:
                    g = shape.geometry
                    radius, shape_kind, shape_loc = g.radius, g.kind, g.loc
                    centre = G.translation(G.compose(t, G.origin_matrix(shape.origin)))
                    if g.kind == "cylinder":
                        zc = _unit(G.rotate(G.origin_matrix(shape.origin), (0.0, 0.0, 1.0)))
                        if zc is not None and ja is not None:
                            ang = _angle(zc, ja)
                            if ang > angle_tolerance:
                                misaligned = ang
            rep.wheels.append(Wheel(u, side, j.child, G.translation(t), axis, j.loc, radius, shape_kind or "",
                                    shape_loc, shape_from or "", misaligned, centre, others))
    lefts = [w for w in rep.wheels if w.side == "left"]
    rights = [w for w in rep.wheels if w.side == "right"]
    ref = lefts[0] if lefts else (rights[0] if rights else None)
    # --- axes ---------------------------------------------------------------------------------------
    if ref is not None:
        for w in rep.wheels:
            if w is ref:
                continue
            ang = _heading_angle(ref.axis, w.axis)
            tilt = _angle(ref.axis, w.axis)
            if ang > angle_tolerance:
                why = (f"they roll in headings {math.degrees(ang):.3g} degrees apart on the ground, so the wheels "
                       f"fight each other")
            elif tilt > max(angle_tolerance, CAMBER_TOLERANCE):
                ang = tilt
                why = (f"they roll the same heading, but one is tilted {math.degrees(tilt):.3g} degrees out of the "
                       f"other's plane (camber): it rolls on its edge, not its tread")
            else:
                continue
            rep.problems_.append(WheelProblem(
                "C012",
                f"wheel joint {w.use.joint} turns about {_vec(w.axis)} but {ref.use.joint} about {_vec(ref.axis)} "
                f"(in {base}); {why}",
                w.joint_loc, (ref.joint_loc, w.use.loc), None,
                {"angle": ang, "joint": w.use.joint, "reference": ref.use.joint}))
    # --- directions (C015) --------------------------------------------------------------------------
    if ref is not None:
        rep.problems_.extend(_direction_problems(drive, base, lefts, rep.wheels))
    # --- separation ---------------------------------------------------------------------------------
    if lefts and rights:
        pl, pr = _mean([w.position for w in lefts]), _mean([w.position for w in rights])
        d = _sub(pl, pr)
        # where the tyres are (a tyre may sit off its hub joint frame along the axis); the joint frames are what a
        # ROS 1 controller measures itself (urdf_distance) and what the sides are judged by
        tl = _mean([w.centre or w.position for w in lefts])
        tr = _mean([w.centre or w.position for w in rights])
        # (type: ignore below) ref: a wheel of the pair
        rep.measured_separation = abs(_dot(_sub(tl, tr), ref.axis))  # type: ignore[union-attr]
        rep.urdf_distance = G.norm(d)
        lateral = d[1]
        if abs(lateral) > tolerance:
            rep.sides_swapped = lateral < 0
        fwd = _mean([w.axis for w in lefts])[1] + _mean([w.axis for w in rights])[1]
        rep.forward_sign = fwd
        if abs(lateral) > tolerance and abs(fwd) >= MIN_FORWARD_SIGN and drive.sided:
            rep.turn_reversed = lateral * fwd < 0
            if rep.turn_reversed:
                rep.problems_.append(_sides_problem(drive, base, lefts, rights, pl, pr, fwd))
        expected = drive.separation
        rep.expected_separation = expected
        names = f"{', '.join(w.use.joint for w in lefts)} / {', '.join(w.use.joint for w in rights)}"
        data = {"measured": rep.measured_separation, "expected": expected, "distance": rep.urdf_distance,
                "tolerance": tolerance}
        sep = drive.wheel_separation
        base_sep = number(sep)
        slip = drive.multiplier("separation")
        if rep.measured_separation <= tolerance:
            rep.problems_.append(WheelProblem(
                "C010",
                f"the wheels of {drive.owner} ({names}) are {_fmt(rep.urdf_distance)} m apart but 0 m apart along "
                f"their axis {_vec(ref.axis)}: "  # type: ignore[union-attr]  # ref: a wheel of the pair
                "they sit one behind the other, not side by side",
                lefts[0].joint_loc, (rights[0].joint_loc,), None, data))
        elif slip is not None and base_sep is not None:
            # a declared slip factor (skid steer): compare the base value with the model, say what it does
            rep.problems_.append(_slip_problem(drive, sep, slip, base_sep, rep.measured_separation, names,
                                               tolerance, (lefts[0].joint_loc, rights[0].joint_loc), data))
        elif expected is None and not drive.sided and sep is None:
            pass  # an optional track width the controller was not given
        elif expected is None:
            if drive.from_urdf and sep is None:
                if abs(rep.urdf_distance - rep.measured_separation) > tolerance:
                    rep.problems_.append(WheelProblem(
                        "C010",
                        f"{drive.owner} sets no wheel_separation, so the ROS 1 controller uses the distance between "
                        f"the wheel joint origins, {_fmt(rep.urdf_distance)} m; the wheels are "
                        f"{_fmt(rep.measured_separation)} m apart along their axis",
                        drive.loc, (lefts[0].joint_loc, rights[0].joint_loc), None, data))
            elif sep is None:
                rep.problems_.append(WheelProblem(
                    "C010",
                    f"{drive.owner} sets no wheel_separation (it defaults to 0); the model's wheels are "
                    f"{_fmt(rep.measured_separation)} m apart ({names})",
                    drive.loc, (lefts[0].joint_loc, rights[0].joint_loc), None, data))
            else:
                bad = sep if base_sep is None else drive.separation_multiplier
                what = "wheel_separation" if base_sep is None else "wheel_separation_multiplier"
                # (type: ignore below) one of the two is set here
                rep.notes.append((f"{what} {bad.value!r} is not a number", bad.loc))  # type: ignore[union-attr]
        elif abs(expected - rep.measured_separation) > tolerance:
            how = (f"{drive.separation_key} {number_text(sep)}" if sep is not None else drive.separation_key)
            rep.problems_.append(WheelProblem(
                "C010",
                f"{drive.owner}: {how} m, but the model's wheels ({names}) are {_fmt(rep.measured_separation)} m "
                f"apart along their axis (difference {_fmt(abs(expected - rep.measured_separation))} m, "
                f"tolerance {_fmt(tolerance)} m)",
                sep.loc if sep is not None else drive.loc, (lefts[0].joint_loc, rights[0].joint_loc), None, data))
    # --- radii --------------------------------------------------------------------------------------
    radius_said: set = set()
    for w in rep.wheels:
        expected = drive.radius(w.side)
        rad_v = drive.wheel_radius
        if w.cylinder_misaligned is not None:
            rep.problems_.append(WheelProblem(
                "C011",
                f"wheel link {w.link}: its {w.shape_from} cylinder's axis is {math.degrees(w.cylinder_misaligned):.3g} "
                f"degrees off the joint axis of {w.use.joint}, so the wheel does not roll on its radius "
                f"(check the <origin rpy> of the cylinder)",
                w.shape_loc or w.joint_loc, (w.joint_loc,), None, {"angle": w.cylinder_misaligned, "link": w.link}))
            continue
        if w.radius is None:
            if drive.from_urdf and rad_v is None:
                rep.problems_.append(WheelProblem(
                    "C011",
                    f"{drive.owner} sets no wheel_radius and wheel link {w.link} has no cylinder or sphere "
                    f"collision/visual geometry: the ROS 1 controller cannot compute the radius and will not start",
                    w.joint_loc, (drive.loc,), Severity.ERROR, {"link": w.link}))
            elif expected is not None:
                rep.notes.append((f"wheel link {w.link} has no cylinder or sphere to compare wheel_radius with",
                                  w.joint_loc))
            continue
        if expected is None:
            if rad_v is None and not drive.from_urdf and drive.sided:
                rep.problems_.append(WheelProblem(
                    "C011",
                    f"{drive.owner} sets no wheel_radius (it defaults to 0); wheel link {w.link} has radius "
                    f"{_fmt(w.radius)} m",
                    drive.loc, (w.shape_loc or w.joint_loc,), None, {"measured": w.radius, "expected": None}))
            continue
        slip = drive.multiplier(w.side)
        base_r = number(rad_v)
        data = {"measured": w.radius, "expected": expected, "link": w.link, "tolerance": tolerance}
        if slip is not None and base_r is not None:
            # a declared correction (tyre compression, slip): compare the base radius, say what it does
            off = abs(base_r - w.radius) > tolerance
            if (w.side, off) in radius_said:
                continue  # one note per side and outcome, not one per wheel
            radius_said.add((w.side, off))
            mult_v = drive.left_radius_multiplier if w.side == "left" else drive.right_radius_multiplier
            agree = f"differs from ({_fmt(abs(base_r - w.radius))} m off)" if off else "matches"
            rep.problems_.append(WheelProblem(
                "C011",
                f"{drive.owner}: wheel_radius {number_text(rad_v)} m {agree} the {w.shape_from} {w.shape_kind} of "
                f"wheel link {w.link} ({_fmt(w.radius)} m); the {w.side} wheel radius multiplier {_fmt(slip)} is a "
                f"declared correction: the controller converts {w.side} wheel rotation to and from ground speed "
                f"with {_fmt(slip)} x {_fmt(base_r)} = {_fmt(base_r * slip)} m",
                # (type: ignore below) set when a multiplier was read
                mult_v.loc, (w.shape_loc or w.joint_loc, rad_v.loc), Severity.INFO, data))  # type: ignore[union-attr]
            continue
        if abs(expected - w.radius) > tolerance:
            # truly ambiguous: another coaxial shape close to the largest (a rim inside a thin tyre, an inner and an
            # outer tyre surface) and the controller's radius between the two: a loaded tyre rolls on a radius
            # there, so which shape is the rolling one is a guess from shape alone. A hub far inside is not.
            ambiguous = any(r >= AMBIGUOUS_RATIO * w.radius and r - tolerance <= expected <= w.radius
                            for r in w.others)
            steps = (Step("wheel", f"{w.shape_from} {w.shape_kind} of radius {_fmt(w.radius)} m of {w.link}",
                          "shape", confirm=f"leave one coaxial collision cylinder or sphere in {w.link}, the one "
                                           f"that touches the ground"),) if ambiguous else ()
            largest = " (the largest of its coaxial shapes)" if w.others else ""
            rep.problems_.append(WheelProblem(
                "C011",
                f"{drive.owner}: {drive.radius_key} {number_text(rad_v)} m, but wheel link {w.link} ({w.use.joint}) "
                f"has a {w.shape_from} {w.shape_kind} of radius {_fmt(w.radius)} m{largest} (difference "
                f"{_fmt(abs(expected - w.radius))} m, tolerance {_fmt(tolerance)} m)",
                # (type: ignore below) set when a radius was read
                rad_v.loc, (w.shape_loc or w.joint_loc,), None, data, steps))  # type: ignore[union-attr]
    return rep


def _direction_problems(drive: DriveSpec, base: str, lefts, wheels) -> list[WheelProblem]:
    """C015: wheels a drive commands alike must roll the same way. A wheel turning positively about its axis `a`
    (in the base frame, z up) rolls along `a x z`, whose forward component is `a_y`; the controllers (diff drive,
    mecanum, steering traction) and Gazebo's drive plugins command every wheel with the same sign to drive
    straight, so a wheel whose `a_y` has the other sign than the reference (the first left wheel) drives the other
    way. A mirrored wheel frame (rpy flipping the child) with a flipped <axis> gives the same effective axis and
    is fine."""
    rolling = [w for w in wheels if abs(w.axis[1]) >= MIN_FORWARD_SIGN]
    if len(rolling) < 2:
        return []
    if drive.sided:
        ref = next((w for w in lefts if w in rolling), rolling[0])
        sign = ref.axis[1] > 0
    else:  # sides read from the model: the majority direction, ties to the first left wheel
        pos = sum(1 for w in rolling if w.axis[1] > 0)
        neg = len(rolling) - pos
        first = next((w for w in lefts if w in rolling), rolling[0])
        sign = pos > neg if pos != neg else first.axis[1] > 0
        ref = next(w for w in ([first] + rolling) if (w.axis[1] > 0) == sign)
    out = []
    for w in rolling:
        if (w.axis[1] > 0) == sign:
            continue
        msg = (f"wheel joint {w.use.joint} turns about {_vec(w.axis)} in {base}, but {ref.use.joint} about "
               f"{_vec(ref.axis)}: {drive.owner} commands both with the same sign to drive straight, so one rolls "
               f"forward and the other backward and the robot spins in place instead of driving (in Gazebo, and on "
               f"hardware that follows the URDF); flip the <axis> of {w.use.joint} (with a mirrored wheel frame, "
               f"the axis must be flipped too: it is the axis in {base} that counts)")
        out.append(WheelProblem("C015", msg, w.joint_loc, (ref.joint_loc, w.use.loc), None,
                                {"joint": w.use.joint, "reference": ref.use.joint, "axis": list(w.axis),
                                 "reference_axis": list(ref.axis)}))
    return out


def _slip_problem(drive: DriveSpec, sep, slip: float, base: float, measured: float, names: str, tolerance: float,
                  related: tuple, data: dict) -> WheelProblem:
    """C010 as information: a wheel_separation_multiplier other than 1 is how the turning of a skid-steer (or
    otherwise slipping) base is tuned. diff_drive_controller (ROS 1 and 2) multiplies wheel_separation by it for
    the wheel commands and the odometry alike; the base value should still be the model's track."""
    eff = slip * base
    if abs(base - measured) <= tolerance:
        agree = f"matches the model's {_fmt(measured)} m ({names})"
    else:
        agree = f"differs from the model's {_fmt(measured)} m ({names}) by {_fmt(abs(base - measured))} m"
    what = ("more wheel speed difference per turn than ideal rolling wheels need: skid-steer slip" if slip > 1 else
            "less wheel speed difference per turn than ideal rolling wheels need")
    msg = (f"{drive.owner}: wheel_separation_multiplier {_fmt(slip)} is a declared slip factor: wheels are commanded "
           f"and odometry integrated with {_fmt(slip)} x {_fmt(base)} = {_fmt(eff)} m ({what}); the base "
           f"wheel_separation {number_text(sep)} m {agree}")
    mult = drive.separation_multiplier
    return WheelProblem("C010", msg, mult.loc if mult is not None else sep.loc, (sep.loc,) + related,
                        Severity.INFO, {**data, "multiplier": slip, "base": base})


def _sides_problem(drive: DriveSpec, base: str, lefts, rights, pl, pr, fwd: float) -> WheelProblem:
    ln = ", ".join(w.use.joint for w in lefts)
    rn = ", ".join(w.use.joint for w in rights)
    where = (f"{drive.owner} names {ln} as left wheel(s) and {rn} as right; in {base} they sit at "
             f"y = {pl[1]:+.6g} m and y = {pr[1]:+.6g} m")
    if fwd > 0:
        why = ("positive rotation of these joints drives the robot forward (+x), so the left wheels are on the "
               "right side (REP-103: y points left)")
    else:
        why = ("their axes point to -y, so positive rotation drives the robot backward (-x) and, seen in the "
               "direction they drive, the left wheels are on the right side")
    msg = (f"{where}: {why}. The controller turns the robot clockwise when asked to turn counter-clockwise "
           f"(and vice versa) and its odometry heading runs the other way; swap the left/right wheel names or "
           f"fix the wheel joint origins/axes")
    return WheelProblem("C014", msg, lefts[0].use.loc, (lefts[0].joint_loc, rights[0].joint_loc, rights[0].use.loc),
                        None, {"left_y": pl[1], "right_y": pr[1], "forward_sign": fwd})


def _vec(v) -> str:
    return "(" + " ".join(f"{0.0 if abs(c) < 5e-7 else c:.3g}" for c in v) + ")"
