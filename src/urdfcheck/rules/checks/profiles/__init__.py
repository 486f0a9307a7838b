"""P rules: consumer profiles (issue 25). What MuJoCo, Gazebo, Isaac Sim, KDL, Pinocchio, PyBullet and MoveIt will
reject (error) or silently change (warning, info) when they read the model, each rule written from the consumer's
own source. `--profile NAME` (config `profiles:`) turns a profile's rules on at their catalogue severity; without
it, a rejection no general rule reports stays visible as an info naming the consumer. What each consumer does is
data (common.GENERAL, behaviour.py), measured against the real consumers by tests/differential.py (issue 40)."""
from urdfcheck.rules.checks.profiles import (  # noqa: F401  (registers the checks)
    gazebo,
    kdl,
    moveit,
    mujoco,
    pinocchio,
    pybullet,
)
