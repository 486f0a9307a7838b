"""Registration of the contract (C) and TF-ownership (T) checks.

The implementations (rules_impl.py) and the YAML/launch readers behind them are imported on first use,
and not at all for a model that has no consumers: a lone URDF outside any ROS package, linted without
a config, never loads them (this keeps `urdfcheck lint robot.urdf` fast).
"""
from __future__ import annotations

from urdfcheck.rules.catalogue import check

_RULES = (
    ("C001", "unknown_joint"),
    ("C002", "joint_not_movable"),
    ("C003", "joint_without_state_source"),
    ("C004", "ros2_control_joint_invalid"),
    ("C005", "missing_interface"),
    ("C006", "ros2_control_in_gazebo"),
    ("C007", "unreadable_consumer"),
    ("C010", "wheel_separation_mismatch"),
    ("C011", "wheel_radius_mismatch"),
    ("C012", "wheel_axes_not_parallel"),
    ("C013", "unequal_wheel_count"),
    ("C014", "wheel_sides_swapped"),
    ("C015", "wheel_direction_reversed"),
    ("C016", "drive_geometry_mismatch"),
    ("C017", "unknown_hardware_component"),
    ("C020", "unknown_frame"),
    ("C022", "claims:interface_claimed_twice"),
    ("C023", "claims:chained_reference_missing"),
    ("C024", "navframes:navigation_frame_unknown"),
    ("T001", "duplicate_tf_owner"),
    ("T002", "static_and_dynamic_tf"),
    ("T003", "tf_multiple_parents"),
    ("T004", "tf_cycle"),
    ("T005", "tf_not_one_tree"),
    ("T006", "frame_prefix_collision"),
)


def _may_have_consumers(model, ctx) -> bool:
    """Consumers given (the planner's, `plan.plan.Target.consumers`), a config, or a model inside a ROS
    package (a context made by hand: the consumers beside it are looked for)."""
    if getattr(ctx, "contracts", None) is not None or getattr(ctx, "config", None) is not None:
        return True
    entry = getattr(getattr(ctx, "expanded", None), "entry", None) or model.source
    from pathlib import Path

    from urdfcheck.load.packages import enclosing_package

    return enclosing_package(Path(entry).resolve()) is not None  # a few stat calls; not kept on the context


MODEL_ONLY = {"C004", "C006"}  # read only the URDF's own <ros2_control> blocks


def _lazy(code: str, spec: str):
    # "name": a function of rules.contracts.impl; "module:name": of rules.contracts.<module>
    module, _, name = spec.rpartition(":")

    def run(model, ctx):
        if code not in MODEL_ONLY and not _may_have_consumers(model, ctx):
            return ()
        if code in MODEL_ONLY and not model.ros2_control:
            return ()
        import importlib

        impl = importlib.import_module(f"urdfcheck.rules.contracts.{module or 'impl'}")
        return getattr(impl, name)(model, ctx)

    run.__name__ = run.__qualname__ = name
    return check(code)(run)


for _code, _spec in _RULES:
    globals()[_spec.rpartition(":")[2]] = _lazy(_code, _spec)
