"""Nothing dropped (issue 20): the parameter files of a model's package that no deployment reads.

Launch-file deployments read the parameter files their launch files name. Before they existed, zero config
checked every controller, driver and localization file of the model's package against the model; a file that
no launch file names (the seed tutorial's driver YAML beside a launch file that starts robot_state_publisher
alone) must still be checked. `mark_unread` gives each deployment the files of its model's package that no
deployment of the same run reads (`Deployment.package_files`); `consumers.openworld.add_package_files`
checks them against the model once it is built, marked as not known to run in that deployment. It also
notes the workspace (`Deployment.workspace`) and whether another launch file includes the deployment's root.
"""
from __future__ import annotations

import os
from pathlib import Path

from urdfcheck.core.walk import real as realpath  # remembered for the run


def mark_unread(deployments, root: str, included=()) -> None:
    from urdfcheck.load.discover import discover
    from urdfcheck.load.packages import enclosing_package

    read: set[str] = set()
    for d in deployments:
        files = [*d.controller_files, *d.localization_files, *(f for _, fs in d.driver_nodes for f in fs)]
        read.update(realpath(f) for f in files)
    found: dict[str, tuple] = {}
    for d in deployments:
        d.workspace = root
        # a root launch file that another launch file includes, which was not followed to it: that one's
        # world is not known (consumers.openworld)
        d.included_elsewhere = d.launch is not None and realpath(d.launch.file) in included
        if d.model is None:
            continue
        pkg = enclosing_package(Path(os.path.abspath(d.model)).parent)
        if pkg is None:
            continue
        key = str(pkg)
        if key not in found:
            try:
                got = discover(key)
            except OSError:
                continue
            found[key] = (got.params, len(got.models) <= 1)
        params, single = found[key]
        d.package_files = tuple(p for p in params if realpath(p) not in read)
        d.package_single = single
