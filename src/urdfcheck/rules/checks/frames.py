"""F rules: frame names against REP-105 (base_link, odom, map)."""
from __future__ import annotations

from collections.abc import Mapping

from urdfcheck.core.findings import Problem
from urdfcheck.core.records import TYPE_CHECKING
from urdfcheck.rules.catalogue import check, options_for

if TYPE_CHECKING:  # the checks' argument types (no import at run time)
    from collections.abc import Iterator

    from urdfcheck.model.robot import Model
    from urdfcheck.rules.engine import Context


def _frame_setting(frames, key: str):
    """`frames.map` / `frames['map']` (also `map_frame`), whatever shape the config gives."""
    for k in (key, f"{key}_frame"):
        if isinstance(frames, Mapping):
            v = frames.get(k)
        else:
            v = getattr(frames, k, None)
        if isinstance(v, str) and v.strip():
            return v.strip()
    return None


def localization_frames(ctx) -> dict[str, str]:
    """frame name -> its REP-105 role ('map' or 'odom'); config frames override F001's option (F002 asks
    too: F001's option, as configured, whichever rule runs)."""
    names = options_for(("F001",), ctx.selection.options)["frames"]
    out = {str(n).lstrip("/"): str(n).lstrip("/") for n in names}
    frames = getattr(ctx.config, "frames", None) if ctx is not None else None
    if frames is not None:
        for role in ("map", "odom"):
            v = _frame_setting(frames, role)
            if v:
                for k in [k for k, r in out.items() if r == role]:
                    del out[k]
                out[v.lstrip("/")] = role
    return out


_OWNER = {
    "map": "map->odom belongs to the localization node (AMCL, slam_toolbox, robot_localization)",
    "odom": "odom->base_link belongs to the odometry publisher (diff_drive_controller, robot_localization, the "
            "base driver)",
}


def _role(name: str, frames: dict[str, str]) -> str | None:
    """The REP-105 role of a link name: exact, or behind a namespace ('robot1/odom', '${ns}odom')."""
    bare = name.lstrip("/")
    if bare in frames:
        return frames[bare]
    for sep in ("/", "}"):
        if sep in bare:
            tail = bare.rsplit(sep, 1)[1]
            if tail in frames:
                return frames[tail]
    return None


@check("F001")
def localization_frame_in_urdf(model: Model, ctx: Context) -> Iterator[Problem]:
    frames = localization_frames(ctx)
    for link in model.link_list:
        role = _role(link.name, frames)
        if role is None:
            continue
        joints = list(model.child_joints.get(link.name, ()))
        parent = model.parent_joint.get(link.name)
        if parent is not None:
            joints.insert(0, parent)
        owner = _OWNER.get(role, f"the {role} frame belongs to localization")
        yield Problem(
            f"link {link.name!r} is the REP-105 {role!r} frame: {owner}. In the URDF, robot_state_publisher "
            "publishes it as well, so two nodes fight over the same TF edge (jumping poses, TF_REPEATED_DATA, "
            "or a frame with two parents). Remove it from the robot description",
            at=link, related=tuple(joints))


def _matches(name: str, expected) -> bool:
    """An expected name, also behind a multi-robot prefix: 'robot1/base_link', 'left_base_link', and
    '${namespace}base_footprint' in files that a launch script fills in before use."""
    for e in expected:
        if not e:
            continue
        if name == e:
            return True
        if name.endswith(e) and name[-len(e) - 1] in "/_}":
            return True
    return False


@check("F002")
def unexpected_root_name(model: Model, ctx: Context) -> Iterator[Problem]:
    root = model.root
    if root is None:
        return
    expected = [str(n) for n in ctx.options["expected"]]
    frames = getattr(ctx.config, "frames", None)
    base = _frame_setting(frames, "base") if frames is not None else None
    if base and base not in expected:
        expected.append(base)  # the project's own base frame (config `frames: {base: ...}`)
    if _matches(root, expected) or _role(root, localization_frames(ctx)) is not None:
        return  # F001 reports a map/odom root
    link = model.links.get(root)
    yield Problem(
        f"root link {root!r} is not one of {', '.join(expected) or '(none configured)'}: REP-105 tools "
        "(navigation, odometry, robot_localization) attach odom->base_link to the robot's base frame, and fixed "
        "arms usually hang from world or base_link. Rename the root or add a base_link root with a fixed joint",
        at=link if link is not None else model)
