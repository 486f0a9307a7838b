"""What depends on a parameter file: the targets a YAML file named by itself (the per-file pre-commit hook)
stands for.

A YAML file is no robot; a change to it matters to the robots and deployments that read it: the targets of its
workspace (the working directory when the file is below it, else its package) whose planned consumers read it
(controllers, drivers, launch parameters), and the models of the package that holds it (a model reads its own
package's parameter files: `xacro.load_yaml`, the consumers found beside it). A config file stands for its
scope. A YAML file nothing reads is an info line.
"""
from __future__ import annotations

import os
from pathlib import Path

from urdfcheck.core.paths import shown

CONFIG_NAMES = ("urdfcheck.yaml", ".urdfcheck.yaml")


def targets_reading(planner, raw: str, settings) -> list:
    from urdfcheck.load.packages import enclosing_package

    path = os.path.abspath(raw)
    if os.path.basename(path) in CONFIG_NAMES:
        return planner.path_targets(os.path.dirname(path))
    here = os.path.abspath(planner.here)
    pkg = enclosing_package(Path(path).parent)
    ws = here if _below(path, here) else str(pkg or os.path.dirname(path))
    real = os.path.realpath(path)
    out = []
    for t in planner.workspace_targets(ws):
        own = enclosing_package(Path(os.path.abspath(t.path)).parent)
        if (own is not None and _below(real, os.path.realpath(own))) or real in _read_by(t):
            out.append(t)
    if not out:
        planner.infos.append(f"{shown(raw)}: a YAML file that no robot or deployment of its "
                             "workspace reads: not linted")
    return out


def _read_by(t) -> set[str]:
    if t._contracts is None:  # consumers found beside the model once it is built: its package (above)
        return set()
    consumers = t.contracts
    files = getattr(consumers, "files", None) or {}
    return {os.path.realpath(p) for paths in files.values() for p in paths}


def _below(path: str, base: str) -> bool:
    return path == base or path.startswith(base.rstrip(os.sep) + os.sep)
