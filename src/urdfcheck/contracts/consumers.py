"""The consumers of one model, read once: what the contract (C) and TF (T) checks look at.

`consumers_for_model(model_config, config)` reads what the config declares for a model;
`discover_consumers(entry_path, model)` is the zero-config fallback: parameter files and launch files of the
package enclosing the model (see `discover`), associated with the model when the package has only one
entry model, or when they name one of its joints (parameter files) / its file name (launch files).

Reading never raises: unreadable files become `errors` (`ConsumerError`, reported as C007).
"""
from __future__ import annotations

import os
from collections.abc import Mapping
from pathlib import Path

from urdfcheck.contracts.common import ConsumerError
from urdfcheck.contracts.controllers import ControllerSet, Driver, read_controllers, read_driver
from urdfcheck.contracts.graph import TFClaim, claims_from_owners
from urdfcheck.contracts.launch import LaunchInfo, read_launch
from urdfcheck.contracts.localization import LocalizationNode, localization_from_params
from urdfcheck.contracts.params import ParamFile, read_params
from urdfcheck.core.findings import Location
from urdfcheck.core.records import Record

DEFAULT_FRAMES = {"map": "map", "odom": "odom", "base": "base_link"}


class Consumers(Record):
    # tf_owners: declared in the config
    # frames: REP-105 names: map, odom, base
    # frame_prefix: the config's robot_state_publisher frame_prefix for this model
    # notes: (message, Location)
    # origin: "config" or "discovered"
    # files: kind -> [paths read]
    _fields = ('controllers', 'drivers', 'launch', 'localization', 'tf_owners', 'frames', 'frame_prefix', 'errors',
               'notes', 'origin', 'files')

    def __init__(self, controllers: ControllerSet | None = None,
                 drivers: list[Driver] | None = None,
                 launch: list[LaunchInfo] | None = None,
                 localization: list[LocalizationNode] | None = None,
                 tf_owners: list[TFClaim] | None = None,
                 frames: dict | None = None,
                 frame_prefix: str = "",
                 errors: list[ConsumerError] | None = None,
                 notes: list | None = None,
                 origin: str = "config",
                 files: dict | None = None):
        self.controllers = ControllerSet({}, ()) if controllers is None else controllers
        self.drivers = [] if drivers is None else drivers
        self.launch = [] if launch is None else launch
        self.localization = [] if localization is None else localization
        self.tf_owners = [] if tf_owners is None else tf_owners
        self.frames = dict(DEFAULT_FRAMES) if frames is None else frames
        self.frame_prefix = frame_prefix
        self.errors = [] if errors is None else errors
        self.notes = [] if notes is None else notes
        self.origin = origin
        self.files = {} if files is None else files

    @property
    def empty(self) -> bool:
        return not (len(self.controllers) or self.drivers or self.launch or self.localization or self.tf_owners
                    or self.errors)

    def joint_uses(self):
        """Every (JointUse, owner kind) a controller or driver names."""
        for c in self.controllers:
            for u in c.joints + c.state_joints:
                yield u, "controller", c
        for d in self.drivers:
            for u in d.joints:
                yield u, "driver", d

    def launch_frame_prefix(self) -> str | None:
        """The frame_prefix of the one robot_state_publisher in the launch files, if exactly one (literal)."""
        rsps = [s for li in self.launch for s in li.state_publishers if not s.condition]
        if len(rsps) == 1 and rsps[0].frame_prefix is not None:
            return rsps[0].frame_prefix
        return None

    @property
    def rsp_prefix(self) -> str:
        if self.frame_prefix:
            return self.frame_prefix
        return self.launch_frame_prefix() or ""


class _Reader:
    def __init__(self):
        self.cache: dict[str, ParamFile | ConsumerError] = {}

    def params(self, path: str, errors: list) -> ParamFile | None:
        got = self.cache.get(path)
        if got is None:
            try:
                got = read_params(path)
            except ConsumerError as e:
                got = e
            self.cache[path] = got
        if isinstance(got, ConsumerError):
            if got not in errors:
                errors.append(got)
            return None
        return got


MAX_INCLUDE_DEPTH = 8
MAX_LAUNCH_FILES = 100


def _read_launch(paths, out: Consumers, args=None, packages=None, reader: _Reader | None = None,
                 follow: bool = False) -> None:
    """Read the launch files `paths`; with `follow`, also the files they include (the files a config names
    run together, so what they include runs too). Each file is read once, with the arguments of its first
    appearance; an include is not followed when its file or condition is not literal, or when it lies
    outside the including file's package and the known packages."""
    from urdfcheck.contracts.launchparams import _allowed_roots, _inside

    queue = [(str(p), args, 0) for p in paths]
    seen: set[str] = set()
    while queue:
        p, a, depth = queue.pop(0)
        real = os.path.realpath(p)
        if real in seen:
            continue
        seen.add(real)
        try:
            li = read_launch(p, args=a, packages=packages)
        except ConsumerError as e:
            out.errors.append(e)
            continue
        out.launch.append(li)
        if not follow:
            continue
        for inc in li.includes:
            why = None
            if inc.file is None:
                why = "its file name is not literal"
            elif inc.condition is not None:
                why = f"it runs only under a condition that cannot be decided ({inc.condition})"
            elif depth + 1 > MAX_INCLUDE_DEPTH or len(seen) + len(queue) >= MAX_LAUNCH_FILES:
                why = "too many nested launch files"
            elif not _inside(inc.file, _allowed_roots(li, packages or {})):
                why = "it is outside the including file's package and the known packages"
            elif not os.path.isfile(inc.file):
                why = "no such file"
            if why is not None:
                out.notes.append((f"include {inc.file or '?'} not followed: {why}", inc.loc))
                continue
            queue.append((inc.file, dict(inc.args), depth + 1))
    for li in out.launch:
        out.notes.extend(li.notes)
    if len(out.controllers) and any(li.param_sets for li in out.launch):
        from urdfcheck.contracts.launchparams import apply_launch_params

        r = reader or _Reader()
        out.notes.extend(apply_launch_params(out.controllers, out.launch, lambda f: r.params(f, []), packages or {}))


def consumers_for_model(mc, config=None, *, packages: Mapping[str, str] | None = None,
                        reader: _Reader | None = None) -> Consumers:
    """Consumers declared in the config for one model (`config.ModelConfig`)."""
    r = reader or _Reader()
    out = Consumers(origin="config")
    if config is not None:
        out.frames = {**DEFAULT_FRAMES, **dict(config.frames)}
        out.tf_owners = claims_from_owners(dict(config.tf_owners), dict(config.tf_owner_locs), Location(config.path))
    out.frame_prefix = mc.frame_prefix
    pfs = [pf for pf in (r.params(p, out.errors) for p in mc.controllers) if pf is not None]
    out.controllers = read_controllers(pfs)
    out.notes.extend(out.controllers.notes)
    for c in out.controllers:
        out.notes.extend(c.notes)
    for d in mc.drivers:
        pf = r.params(d.file, out.errors)
        if pf is None:
            continue
        drv = read_driver(d, [pf])
        out.drivers.append(drv)
    loc_pfs = [pf for pf in (r.params(p, out.errors) for p in mc.localization) if pf is not None]
    out.localization = localization_from_params(loc_pfs)
    pk = dict(packages or (config.packages if config is not None else {}))
    _read_launch(mc.launch, out, dict(mc.launch_args), pk, r, follow=True)
    _launch_typed(out, pfs)
    out.files = {"controllers": list(mc.controllers), "drivers": [d.file for d in mc.drivers],
                 "launch": list(mc.launch), "localization": list(mc.localization)}
    return out


# --- zero-config -----------------------------------------------------------------------------------------
def _package_root(entry: str) -> Path | None:
    p = Path(os.path.abspath(entry)).parent
    for d in (p, *p.parents):
        if (d / "package.xml").is_file():
            return d
    return None


def discover_consumers(entry: str, model=None, *, packages: Mapping[str, str] | None = None) -> Consumers | None:
    """Consumers found next to a model without a config; None when the model is in no ROS package."""
    from urdfcheck.contracts.discover import discover

    root = _package_root(entry)
    if root is None:
        return None
    found = discover(root)
    single = len(found.models) <= 1
    joints = set(model.joints) if model is not None else set()
    out = Consumers(origin="discovered")
    r = _Reader()
    pfs = []
    from urdfcheck.contracts.prefilter import worth_parsing

    for p in found.params:
        if not single and not worth_parsing(p, joints):  # names none of the joints: dropped below anyway
            continue
        errs: list = []
        pf = r.params(p, errs)
        if pf is None:
            if single:
                out.errors.extend(errs)
            continue
        if single or _names_a_joint(pf, joints):
            pfs.append(pf)
    out.controllers = read_controllers(pfs)
    for c in out.controllers:
        out.notes.extend(c.notes)
    out.localization = localization_from_params(pfs)
    base = os.path.basename(entry)
    launches = []
    for p in found.launch:
        if single or _mentions(p, base):
            launches.append(p)
    pk = dict(packages or {})
    _read_launch(launches, out, None, pk, r)
    _launch_typed(out, pfs)
    # every launch file of the package, associated with this model or not: when none starts a
    # robot_state_publisher, nothing in the package needs joint states (C003)
    out.files = {"params": [pf.path for pf in pfs], "launch": launches, "package_launch": list(found.launch)}
    return out


def consumers_near(entry: str, model=None, *, packages: Mapping[str, str] | None = None, config=None) -> Consumers:
    """Zero config (or a config with no entry for this model): the consumers beside the model
    (`discover_consumers`; none outside a ROS package), with the config's frames and TF owners, which a
    config names for every model. Discovery is best effort: a failure gives no consumers, never an error."""
    try:
        found = discover_consumers(entry, model, packages=packages)
    except Exception:  # noqa: BLE001 - discovery is best effort; never break the checks
        found = None
    c = found or Consumers(origin="none")
    if config is not None:
        c.frames = {**c.frames, **dict(getattr(config, "frames", {}) or {})}
        owners = dict(getattr(config, "tf_owners", {}) or {})
        if owners and not c.tf_owners:
            c.tf_owners = claims_from_owners(owners, dict(getattr(config, "tf_owner_locs", {}) or {}),
                                             Location(getattr(config, "path", "<config>")))
    return c


def _launch_typed(out: Consumers, pfs: list) -> None:
    """Controllers whose type a launch file gives (`spawner NAME -t TYPE`) and whose parameter file does not:
    read the parameter files again with those types (issue 15: such a diff drive was never checked)."""
    from urdfcheck.contracts.controllers import spawner_types

    types = spawner_types(out.launch)
    if not pfs or not types or all(out.controllers.by_name(n) is not None for n in types) \
            or any(li.param_sets for li in out.launch):  # (ROS 1 launch parameters were applied already)
        return
    out.controllers = read_controllers(pfs, launch_types=types)
    for c in out.controllers:
        if out.controllers.by_name(c.name) is c and c.name in types:
            out.notes.extend(c.notes)


def _names_a_joint(pf: ParamFile, joints: set[str]) -> bool:
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


def _mentions(path: str, name: str) -> bool:
    from urdfcheck.load.packages import leaves_cwd

    if leaves_cwd(path):
        return False
    try:
        from urdfcheck.core.safeio import read_file

        return name.encode() in read_file(path, 2 * 1024 * 1024)
    except OSError:
        return False
