"""Whether a model can have consumers: the one test, asked by the planner's target (which looks for them only then),
the engine (which loads the contract and TF rules only then) and the run's warm-up (which imports them ahead).

A model can have consumers when the planner gave it some (`plan.plan.Target.consumers`), when a config is in
force, or when it sits in a ROS package (zero config looks for them beside it: `consumers.consumers.consumers_near`).
A lone URDF outside any package, linted without a config, has none, and its run never imports the readers.
"""
from __future__ import annotations

from pathlib import Path


def in_package(path) -> bool:
    """A package.xml in the folder of `path` (symlinks resolved, as the model is read) or above it. A path whose
    real place the run's door refuses is in none: nothing beside it is looked at."""
    from urdfcheck.core import door
    from urdfcheck.load.packages import enclosing_package

    try:
        real = door.confine(path)
    except OSError:
        return False
    return enclosing_package(Path(real)) is not None


def may_have_consumers(model, ctx) -> bool:
    if getattr(ctx, "contracts", None) is not None or getattr(ctx, "config", None) is not None:
        return True
    return in_package(getattr(getattr(ctx, "expanded", None), "entry", None) or model.source)
