"""ROS 1 launch files writing controller parameters: `<param>`, inline `<rosparam>` and `<rosparam file ns>`.

roslaunch builds the parameter server from every launch file in document order: a later write of the same name
wins. A controller read from a parameter file (`consumers.controllers`) is therefore overridden by

* `<param name="diffbot_controller/wheel_separation" value="0.52"/>` (relative names resolve against the
  enclosing `<group ns>`; `type=` or roslaunch's int/float/bool guess gives the value);
* `<rosparam ns="diffbot_controller">wheel_radius: 0.12</rosparam>` and `<rosparam param=...>` (inline YAML);
* `<rosparam command="load" file="$(find pkg)/config/wheels.yaml" ns="diffbot_controller"/>` (another file's
  values, located in that file);

unless the launch file loads the controller's own parameter file again afterwards (that resets what the file
sets). A controller whose file the launch loads under `<group ns="r1">` (or `ns="r1"`) lives at `/r1/<name>`;
a file it does not load is taken to live at the root.

Only ROS 1 controllers (`ros: 1`) and only literal values are applied; the new value keeps the location where
it was written (the launch file line, or the loaded file's line), so C010/C011 point there. Not handled (left
as they are): `<include>`d launch files (not followed), `$(eval)`/`$(env)` values, `<param command=...>`,
parameters set inside `<node>` (private `~` names), writes under an `if`/`unless` that cannot be decided, and
custom drivers (their key paths are read from their file only).
"""
from __future__ import annotations

import os
from collections.abc import Callable, Iterable, Mapping
from pathlib import Path

from urdfcheck.consumers.common import Value
from urdfcheck.consumers.controllers import Controller, ControllerSet, finish_controller
from urdfcheck.consumers.launch.xml import LaunchInfo, ParamSet, RosparamLoad
from urdfcheck.consumers.params import ParamFile
from urdfcheck.core.paths import shown


def _ns_join(ns: str, rest: str) -> str:
    return "/" + "/".join(s for s in (ns.strip("/"), rest.strip("/")) if s)


def _file_sets(pf: ParamFile, ns: str, order: int, subst: tuple | None = None,
               only_substituted: bool = False) -> list[ParamSet]:
    """The parameters a ROS 1 file writes when loaded at `ns`, as global names (`subst`: loaded with
    `subst_value="true"`, its `$(arg ...)` take these values; `only_substituted`: just the values that changed)."""
    from urdfcheck.consumers.launch.xml import substitute_args

    out = []
    for node_name, node in pf.nodes.items():
        for pname, v in node.params.items():
            if subst is not None and isinstance(v.value, str) and "$(" in v.value:
                v = Value(substitute_args(v.value, dict(subst)), v.loc, v.default, v.items)
            elif only_substituted:
                continue
            rest = (node_name.strip("/") + "/" if node_name != "/" else "") + pname.replace(".", "/")
            out.append(ParamSet(_ns_join(ns, rest), v, order))
    return out


def _same_file(a: str, b: str) -> bool:
    try:
        return os.path.realpath(a) == os.path.realpath(b)
    except (OSError, ValueError):
        return False


def _inside(path: str, roots: Iterable[str]) -> bool:
    real = os.path.realpath(path)
    return any(real == r or real.startswith(r.rstrip(os.sep) + os.sep) for r in roots)


def _allowed_roots(li: LaunchInfo, packages: Mapping[str, str]) -> list[str]:
    """Where a launch file may load parameter files from: its own package and the known packages."""
    from urdfcheck.load.packages import enclosing_package

    roots = [os.path.realpath(p) for p in packages.values()]
    own = enclosing_package(Path(os.path.abspath(li.path)))
    roots.append(os.path.realpath(own) if own is not None else os.path.dirname(os.path.realpath(li.path)))
    return roots


def apply_launch_params(cset: ControllerSet, launches: Iterable[LaunchInfo],
                        read: Callable[[str], ParamFile | None], packages: Mapping[str, str] | None = None) -> list:
    """Apply ROS 1 launch parameter writes to the controllers of `cset` (in place). `read(path)` reads a
    parameter file loaded by a `<rosparam file>` (None when it cannot be read); only regular files inside the
    launch file's package or a known package (`packages`) are read. Returns notes (message, Location)."""
    notes: list = []
    ros1 = [c for c in cset if c.ros == 1]
    if not ros1:
        return notes
    for li in launches:
        if not li.param_sets:
            continue
        # where each controller lives: the namespaces its own file is loaded at by this launch file
        homes: dict[str, list[str]] = {}
        for c in ros1:
            loads = [ld.ns for ld in li.param_sets if isinstance(ld, RosparamLoad) and _same_file(ld.file, c.file)]
            homes[c.node] = [_ns_join(ns, c.node) for ns in loads] or [c.node]
        changed: dict[str, dict[str, Value]] = {}
        for item in li.param_sets:
            if isinstance(item, RosparamLoad):
                own = [c for c in ros1 if _same_file(item.file, c.file)]
                if own:  # the controller's own file again: its values win over earlier writes
                    for c in own:
                        mine = changed.get(c.node)
                        if mine:
                            for k in list(mine):
                                if k in _file_params(c, read):
                                    del mine[k]
                    pf = read(own[0].file) if item.subst is not None else None
                    if pf is None:
                        continue
                    sets = _file_sets(pf, item.ns, item.order, item.subst, only_substituted=True)
                else:
                    if not (os.path.isabs(item.file) and os.path.isfile(item.file)):
                        notes.append((f"rosparam file {shown(item.file)} not found; its parameters are not applied",
                                      item.loc))
                        continue
                    if not _inside(item.file, _allowed_roots(li, packages or {})):
                        notes.append((f"rosparam file {shown(item.file)} is outside the known packages; not read",
                                      item.loc))
                        continue
                    pf = read(item.file)
                    if pf is None or pf.dialect != "ros1":
                        continue
                    sets = _file_sets(pf, item.ns, item.order, item.subst)
            else:
                sets = [item]
            for ps in sets:
                for c in ros1:
                    for home in homes[c.node]:
                        prefix = home.rstrip("/") + "/"
                        if ps.name.startswith(prefix):
                            pname = ps.name[len(prefix):].replace("/", ".")
                            if pname and pname != "type":
                                changed.setdefault(c.node, {})[pname] = ps.value
        for c in ros1:
            new = changed.get(c.node)
            if new:
                _rebuild(cset, c, new)
    return notes


def _file_params(c: Controller, read) -> set[str]:
    pf = read(c.file)
    if pf is None:
        return set()
    out = set()
    for node_name, node in pf.nodes.items():
        for pname in node.params:
            full = "/" + "/".join(s for s in (node_name.strip("/"), pname.replace(".", "/")) if s)
            prefix = c.node.rstrip("/") + "/"
            if full.startswith(prefix):
                out.add(full[len(prefix):].replace("/", "."))
    return out


def _rebuild(cset: ControllerSet, c: Controller, new: dict[str, Value]) -> None:
    params = {**c.params, **new}
    fresh = Controller(name=c.name, node=c.node, type=c.type, type_loc=c.type_loc, loc=c.loc, kind=c.kind, ros=c.ros,
                       file=c.file, params=params)
    finish_controller(fresh, {x.name for x in cset})
    cset.controllers[c.node] = fresh
