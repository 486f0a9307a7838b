"""The open world (issue 20): what a deployment's consumers did not understand, and the parameter files of a
model's package that no launch file reads.

A check that claims something is absent (nothing publishes joint states, nothing publishes a frame, the
TF graph is not one tree) marks its `Problem` with `absent`; the engine makes it an error or warning only
when the consumers it was checked against understood everything that could supply it
(`Consumers.unknown` empty), and otherwise an info naming what was not understood. What was not understood
is a property of the deployment, written once here:

* its root launch file starts robot_state_publisher and nothing that moves or supplies the robot (a
  description launch file that a bringup launch file includes, or is meant to include);
* a node of no known kind that was not read (`my_joint_publisher.py`, a camera driver);
* an include or a launch file that was not followed or not read;
* zero config without a launch file: parameter files beside the model, with nothing saying what runs.

Parameter files of the model's package that no deployment reads (`package_files`) are still checked against
the model, as before launch deployments existed: their controllers and base drivers (read by key shape,
`infer_driver`) join the consumers marked `elsewhere` (they are not known to run in this deployment), so their
joint, wheel and frame contracts are checked, they count as joint state suppliers elsewhere (C003 then says
so and does not fail), and they claim no transform in this deployment's TF graph.
"""
from __future__ import annotations

import os

from urdfcheck.core import lazyre
from urdfcheck.core.findings import Location
from urdfcheck.core.walk import real as realpath  # remembered for the run

LOCALIZATION_PACKAGES = ("robot_localization", "nav2_amcl", "amcl", "slam_toolbox", "nav2_bringup",
                         "nav2_controller", "nav2_planner", "nav2_bt_navigator", "nav2_map_server")
# nodes whose parameters are not a custom driver's (their kinds are read elsewhere, or say nothing of the model)
KNOWN_PACKAGES = {"robot_state_publisher", "joint_state_publisher", "joint_state_publisher_gui", "controller_manager",
                  "tf", "tf2_ros", "rviz", "rviz2", "xacro", "rqt_robot_steering", "teleop_twist_keyboard",
                  "teleop_twist_joy", "joy", "joy_linux", "twist_mux", "rosbridge_server", "foxglove_bridge",
                  "topic_tools", "image_transport", *LOCALIZATION_PACKAGES}
KNOWN_PREFIXES = ("rviz", "gazebo", "ros_gz", "ros_ign", "moveit", "nav2_", "rqt")
# tools that neither move nor supply the robot: a root launch file that starts robot_state_publisher and only
# these beside it is a description fragment
_TOOLS = {"rviz", "rviz2", "xacro", "rqt_robot_steering", "foxglove_bridge", "rosbridge_server", "tf", "tf2_ros"}


def known_kind(pkg: str) -> bool:
    """A node package whose role the readers know (or that says nothing about the model's states and frames)."""
    return pkg in KNOWN_PACKAGES or pkg.startswith(KNOWN_PREFIXES)


def _node_label(n) -> str:
    exe = n.executable or n.name or "?"
    return f"`{exe}`" + (f" (package {n.package})" if n.package and n.package != exe else "")


def deployment_unknowns(dep, drivers=()) -> list[tuple[str, Location]]:
    """What the deployment `dep` (plan.deployments.Deployment) did not understand, as (what, where).
    `drivers`: the base drivers read from its nodes' parameters (a node whose parameters name joints was read;
    one whose parameters say nothing of joints, a camera's, was not: it may publish its own frames)."""
    from urdfcheck.core.paths import shown as display

    out: list[tuple[str, Location]] = []
    read = {d.loc for d in drivers if d.joints}
    nodes = [n for info in dep.infos for n in info.nodes]
    for n in nodes:
        if n.loc in read or known_kind(n.package or "") or _read_and_silent(n, dep.workspace):
            continue
        out.append((f"{_node_label(n)} in {display(n.loc.file)}", n.loc))
    for msg, loc in dep.notes:
        if msg.startswith(("include not followed", "launch file not read")):
            out.append((f"{msg} ({display(loc.file)})", loc))
    root = [i for i in dep.infos if dep.launch is not None and realpath(i.path) == realpath(
        dep.launch.file)]
    if getattr(dep, "included_elsewhere", False):
        out.append((f"the launch files that include {display(dep.launch.file)} (not followed to it)", dep.launch))
    elif root and not dep.chain and _description_only(root[0], nodes):
        out.append((f"the launch files that include {display(dep.launch.file)} (it starts robot_state_publisher "
                    "and nothing that moves or supplies the robot: a description launch file)", dep.launch))
    return out


# what a node's own script would contain if it published joint states, transforms or a model
_SUPPLIES = lazyre.compile(rb"JointState|TransformBroadcaster|sendTransform|TFMessage|tf2_ros|\btf\b|robot_description"
                       rb"|urdf|xacro")
_SCRIPTS: dict[tuple, bool] = {}
MAX_SCRIPT_FILES = 5000


def _read_and_silent(node, workspace: str | None) -> bool:
    """The node is a Python script of a package in the workspace that was read and publishes no joint states,
    no transforms and no model (a battery monitor, a command timeout): it supplies nothing an absence is
    about. C++ executables (named by a build target, not a file) stay unknown."""
    exe = node.executable or ""
    if not workspace or not node.package or not exe or "/" in exe or "\x00" in exe:
        return False
    key = (workspace, node.package, exe)
    if key not in _SCRIPTS:
        _SCRIPTS[key] = _silent_script(workspace, node.package, exe)
    return _SCRIPTS[key]


def _silent_script(workspace: str, package: str, exe: str) -> bool:
    from urdfcheck.core import door
    from urdfcheck.load.discover import _walk
    from urdfcheck.load.packages import leaves_cwd, workspace_packages

    dirs = workspace_packages(workspace).get(package) or []
    names = {exe} if exe.endswith(".py") else {exe, exe + ".py"}
    hits = [os.path.join(d, f) for folder in dirs[:1] for d, f in _walk(str(folder), MAX_SCRIPT_FILES) if f in names]
    if len(hits) != 1 or leaves_cwd(hits[0]):
        return False
    try:
        text = door.read_bytes(hits[0], limit=1024 * 1024)
    except OSError:
        return False
    if not (hits[0].endswith(".py") or text.startswith(b"#!") and b"python" in text.split(b"\n", 1)[0]):
        return False
    return _SUPPLIES.search(text) is None


def _description_only(root, nodes) -> bool:
    """The root launch file's tree starts robot_state_publisher and only tools beside it (no controller
    manager, joint state publisher, simulator, driver or localization)."""
    if root.includes:
        return False
    for n in nodes:
        pkg = n.package or ""
        if pkg == "robot_state_publisher" or pkg in _TOOLS or pkg.startswith(("rviz", "rqt")):
            continue
        return False
    return True


def _gives_a_model(li) -> bool:
    """A robot_state_publisher of the launch file is given a model (understood or not): a description launch file,
    not a bare node that waits for one."""
    if any(s.description is not None or getattr(s, "unread", "") for s in li.state_publishers) \
            or getattr(li, "descriptions", None):
        return True
    from urdfcheck.core import door

    try:
        return b"robot_description" in door.read_bytes(li.path, limit=2 * 1024 * 1024)
    except OSError:
        return False


def package_unknowns(c) -> list[tuple[str, Location]]:
    """Zero config: parameter files beside the model, and either no launch file of the package that starts
    robot_state_publisher (what runs beside the model is not known) or nodes of no known kind in them."""
    first = next((ctrl.loc for ctrl in c.controllers), None) or next((d.loc for d in c.drivers), None)
    if first is None and not c.launch:
        return []
    if not any(li.state_publishers for li in c.launch):
        return [("no launch file found that runs this model with its parameter files (what runs beside it is "
                 "not known)", first or Location(c.launch[0].path))]
    return launch_unknowns(c) + description_files(c.launch)


def description_files(launches) -> list[tuple[str, Location]]:
    """Zero config: when every launch file beside the model that starts robot_state_publisher starts it alone
    (with tools), they are description launch files, meant to be included by a bringup or simulation launch
    file that starts the rest (a vendor driver, joint_state_publisher): that world is not known."""
    from urdfcheck.core.paths import shown as display

    starters = [li for li in launches if li.state_publishers]
    if not starters or not all(_description_only(li, li.nodes) and _gives_a_model(li) for li in starters):
        return []
    return [(f"the launch files that include {display(li.path)} (it starts robot_state_publisher and nothing "
             "that moves or supplies the robot: a description launch file)", Location(li.path)) for li in starters]


def launch_unknowns(c, read=()) -> list[tuple[str, Location]]:
    """Nodes of no known kind in the launch files `c` read (but those given a parameter file in `read`: a
    declared driver), and includes not followed: what a config's launch files run that was not understood."""
    from urdfcheck.core.paths import shown as display

    read = {realpath(f) for f in read}
    out = [(f"{_node_label(n)} in {display(n.loc.file)}", n.loc) for li in c.launch for n in li.nodes
           if not known_kind(n.package or "") and not ({realpath(f) for f in n.param_files} & read)]
    out.extend((f"{msg} ({display(loc.file)})", loc) for msg, loc in c.notes
               if msg.startswith("include") and "not followed" in msg)
    return out


# --- parameter files no deployment reads -------------------------------------------------------------------
_JOINT_KEY = lazyre.compile(r"(^|[._])(\w*_)?joints?$|_wheel_names$|_joint_names$")
_FRAME_KEY = lazyre.compile(r"_frame(_id)?$|^frame_id$")
_GEOMETRY = ("wheel_separation", "track_width", "wheel_radius")


def infer_driver(name: str, file: str, loc: Location, params: dict, *, needs_joints: bool = False):
    """A `controllers.Driver` from parameters whose keys are shaped like joint names (*_joint, *_joints,
    *_wheel_names), frame ids (*_frame, *_frame_id) or wheel geometry (wheel_separation / track_width,
    wheel_radius with left and right wheel names); None when no key has such a shape (`needs_joints`: when
    no key names a joint). The meaning is inferred from the key: the checks report these as warnings."""
    from urdfcheck.consumers.common import Value
    from urdfcheck.consumers.controllers import Driver, DriveSpec, JointUse

    joints, left, right, frames = [], [], [], []
    for key, v in sorted(params.items()):
        leaf = key.split(".")[-1]
        vals = v.value if isinstance(v.value, list) else [v.value]
        if not all(isinstance(x, str) and x and "$(" not in x and "\x00" not in x for x in vals):
            continue
        if _JOINT_KEY.search(leaf):
            role = "left_wheel" if leaf.startswith("left") and "wheel" in leaf else \
                "right_wheel" if leaf.startswith("right") and "wheel" in leaf else "joint"
            uses = [JointUse(x, v.item_loc(i) if isinstance(v.value, list) else v.loc, name, role=role)
                    for i, x in enumerate(vals)]
            (left if role == "left_wheel" else right if role == "right_wheel" else joints).extend(uses)
        elif _FRAME_KEY.search(leaf) and not isinstance(v.value, list):
            frames.append(Value(v.value.strip().lstrip("/"), v.loc))
    if not (joints or left or right or frames) or (needs_joints and not (joints or left or right)):
        return None
    drv = Driver(name, file, loc, tuple(left + right + joints), frames=tuple(frames))
    geo = {k.split(".")[-1]: v for k, v in params.items() if k.split(".")[-1] in _GEOMETRY}
    if left and right and (geo.get("wheel_separation") or geo.get("track_width") or geo.get("wheel_radius")):
        drv.drive = DriveSpec(owner=name, loc=loc, left=tuple(left), right=tuple(right),
                              left_loc=left[0].loc, right_loc=right[0].loc,
                              wheel_separation=geo.get("wheel_separation") or geo.get("track_width"),
                              wheel_radius=geo.get("wheel_radius"))
    drv.inferred = True
    return drv


def names_a_joint(pf, joints: set[str]) -> bool:
    """The parameter file names one of `joints` (as a value, or in a list)."""
    if not joints:
        return False
    for node in pf.nodes.values():
        for v in node.params.values():
            val = v.value
            if isinstance(val, str) and val in joints:
                return True
            if isinstance(val, list) and any(isinstance(x, str) and x in joints for x in val):
                return True
    return False


def add_package_files(c, files, model, reader, *, single: bool, why: str) -> None:
    """Check `files` (parameter files of the model's package that no deployment reads) against `model` too:
    their controllers, base drivers and localization nodes join `c` marked `elsewhere` = `why`. In a package
    of several models, only the files that name one of the model's joints."""
    from urdfcheck.consumers.controllers import read_controllers
    from urdfcheck.consumers.localization import localization_from_params

    joints = set(model.joints) if model is not None else set()
    entry = getattr(model, "source", None) or ""
    mine, others = _references(entry, files) if not single and entry else (set(), set())
    pfs, skipped = [], []
    for f in files:
        real = realpath(f)
        if real in others:  # another model of the package names it (consumers.pairing)
            skipped.append(f)
            continue
        errs: list = []
        pf = reader.params(f, errs)
        if pf is None:
            if single or real in mine:
                from urdfcheck.consumers.params import foreign

                c.errors.extend(e for e in errs if e not in c.errors and (real in mine or not foreign(f, e)))
            continue
        if single or real in mine or names_a_joint(pf, joints):
            pfs.append(pf)
            if hasattr(c, "pair"):
                c.pair([f], "referenced" if real in mine else "only" if single else "overlap", entry)
    if skipped:
        from urdfcheck.consumers.pairing import others_files

        c.unknown = list(c.unknown or ()) + others_files(skipped)
    if not pfs:
        return
    ctrls = read_controllers(pfs)
    taken = {ctl.node for ctl in c.controllers}
    for ctl in ctrls:
        if ctl.node in taken:
            continue
        ctl.elsewhere = why
        c.controllers.controllers[ctl.node] = ctl
        c.notes.extend(ctl.notes)
    loc_nodes = localization_from_params(pfs)
    c.elsewhere_localization = list(c.elsewhere_localization) + list(loc_nodes)
    for drv in package_drivers(pfs, ctrls, loc_nodes):
        drv.elsewhere = why
        c.drivers.append(drv)
    files_read = c.files.setdefault("package", [])
    files_read.extend(pf.path for pf in pfs if pf.path not in files_read)


def _references(entry: str, files) -> tuple[set, set]:
    """The package's files named for this model and for its other models only (consumers.pairing)."""
    from pathlib import Path

    from urdfcheck.consumers.pairing import finder, references
    from urdfcheck.load.discover import discover
    from urdfcheck.load.packages import enclosing_package

    root = enclosing_package(Path(os.path.abspath(entry)).parent)
    if root is None:
        return set(), set()
    try:
        found = discover(str(root))
        return references(entry, str(root), found.models, files, found.launch, finder(str(root)))
    except OSError:
        return set(), set()


def package_drivers(pfs, controllers, localization) -> list:
    """Base drivers read by key shape from the nodes of parameter files that are neither controllers (nor the
    controller manager) nor localization nodes: a node whose keys name joints (`infer_driver`)."""
    taken = {(ctl.file, ctl.node) for ctl in controllers} | {(n.file, n.node) for n in localization}
    out = []
    for pf in pfs:
        for key, node in pf.nodes.items():
            if (pf.path, key) in taken or (pf.path, node.name) in taken or node.basename == "controller_manager" \
                    or any(k == "type" or k.endswith(".type") for k in node.params):
                continue
            label = os.path.splitext(os.path.basename(pf.path))[0] if node.name in ("/", "") else node.basename
            drv = infer_driver(f"{label} (inferred from {os.path.basename(pf.path)})", pf.path, node.loc,
                               node.params, needs_joints=True)
            if drv is not None:
                out.append(drv)
    return out


def elsewhere(item) -> str | None:
    """Why a controller or driver is not known to run in this deployment (None: it runs here)."""
    return getattr(item, "elsewhere", None)


_BROADCASTER = lazyre.compile(
    rb"joint_state_broadcaster|joint_state_controller|JointStateBroadcaster|JointStateController")
_WORKSPACE: dict[str, list] = {}  # workspace root -> its broadcaster files' controllers (read once per run)


def workspace_broadcasters(c, joints: set) -> list:
    """Joint state broadcasters configured anywhere in the consumers' workspace (`c.workspace`), in files that
    `c` does not read and that name some of `joints` (a `*_control` package's YAML beside the controllers of
    this model): suppliers that another launch file may start beside this one. (broadcaster, the joints its
    file names), each marked `elsewhere`."""
    root = getattr(c, "workspace", None)
    if not root or not joints:
        return []
    if root not in _WORKSPACE:
        _WORKSPACE[root] = _broadcasters(root)
    mine = {realpath(f) for fs in (c.files or {}).values() for f in fs}
    out = []
    for ctl, named in _WORKSPACE[root]:
        hit = named & joints
        if hit and realpath(ctl.file) not in mine:
            out.append((ctl, hit))
    return out


def _broadcasters(root: str) -> list:
    from urdfcheck.consumers.common import ConsumerError
    from urdfcheck.consumers.controllers import JSB, JSC, read_controllers
    from urdfcheck.consumers.params import read_params
    from urdfcheck.core import door
    from urdfcheck.load.discover import discover

    out = []
    for f in discover(root).params:
        try:
            if not _BROADCASTER.search(door.read_bytes(f, limit=2 * 1024 * 1024)):
                continue
        except OSError:
            continue
        try:
            pf = read_params(f)
        except ConsumerError:
            continue
        named = {x for node in pf.nodes.values() for v in node.params.values()
                 for x in (v.value if isinstance(v.value, list) else [v.value]) if isinstance(x, str)}
        for ctl in read_controllers([pf]):
            if ctl.kind in (JSB, JSC):
                ctl.elsewhere = f"it is configured in {_show(f)}, which no launch file of this deployment reads"
                out.append((ctl, named))
    return out


def _show(path: str) -> str:
    from urdfcheck.core.paths import shown as display

    return display(path)


# --- custom drivers, read by the shape of their keys ---------------------------------------------------------
def infer_drivers(driver_nodes, reader) -> list:
    """A `controllers.Driver` per node of no known kind whose parameters (inline, and from the parameter files
    it is given) have keys shaped like joint names, frame ids or wheel geometry (`openworld.infer_driver`).
    The meaning is inferred from the key, so the checks report these as warnings (`inferred`)."""
    out = []
    for node, files in driver_nodes:
        name = f"{node.name or node.executable or node.package} (inferred from {node.package})"
        params: dict = {}
        for f in files:
            pf = reader.params(f, [])
            if pf is None:
                continue
            mine = [n for key, n in pf.nodes.items()
                    if key.rstrip("/").split("/")[-1] in (node.name, node.executable, "**") or len(pf.nodes) == 1]
            for n in mine:
                params.update(n.params)
        params.update({k: v for k, v in node.params.items() if v.value is not None and not k.startswith("\x00")})
        drv = infer_driver(name, files[0] if files else node.loc.file, node.loc, params)
        if drv is not None:
            out.append(drv)
    return out
