#!/usr/bin/env python3
"""Forward-kinematics benchmarks for urdfcheck's publisher.

Prints:
  * batch FK (``link_poses``, numpy) configurations/s vs Pinocchio forwardKinematics + updateFramePlacements in a
    Python loop, on a UR5 and a PR2-size model, same run, with the ratio;
  * single JointState -> transforms messages/s (``StatePublisher.on_joint_state``) on the UR5, and the ratio to
    the ~1,000 msg/s robot_state_publisher manages;
  * wall time of ``urdfcheck verify`` (a fresh process, imports included) on the PR2-size model, 1,000
    configurations.

Usage: python bench/bench_fk.py [--n 2000] [--messages 100000] [--ur5 PATH] [--pr2 PATH]
"""
from __future__ import annotations

import argparse
import os
import subprocess
import sys
import time
from pathlib import Path

REPO = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(REPO / "src"))


def _example_robot(*parts) -> Path | None:
    try:
        from importlib.metadata import distribution

        base = Path(distribution("example-robot-data").locate_file("cmeel.prefix/share/example-robot-data/robots"))
    except Exception:
        return None
    p = base.joinpath(*parts)
    return p if p.is_file() else None


def _corpus(*parts) -> Path | None:
    base = Path(os.environ.get("URDFCHECK_CORPUS", REPO.parent / "shared" / "corpus"))
    p = base.joinpath(*parts)
    return p if p.is_file() else None


def best_of(fn, repeat=3):
    best = float("inf")
    for _ in range(repeat):
        t = time.perf_counter()
        fn()
        best = min(best, time.perf_counter() - t)
    return best


def bench_batch(path: Path, n: int) -> dict:
    import numpy as np
    import pinocchio as pin

    from urdfcheck.model.build import model_from_string
    from urdfcheck.publisher import link_poses
    from urdfcheck.verify.compare import sample_configurations

    xml = path.read_text()
    model = model_from_string(xml, str(path))
    names, q = sample_configurations(model, n, seed=0)
    link_poses(model, q[:10])  # warm the tree cache
    t_ours = best_of(lambda: link_poses(model, q))

    pm = pin.buildModelFromXML(xml)
    data = pm.createData()
    qs = np.tile(pin.neutral(pm), (n, 1))
    for k, name in enumerate(names):
        if not pm.existJointName(name):
            continue
        jm = pm.joints[pm.getJointId(name)]
        if jm.nq == 2:
            qs[:, jm.idx_q] = np.cos(q[:, k])
            qs[:, jm.idx_q + 1] = np.sin(q[:, k])
        else:
            qs[:, jm.idx_q] = q[:, k]

    def pin_loop():
        fk, upd = pin.forwardKinematics, pin.updateFramePlacements
        for i in range(n):
            fk(pm, data, qs[i])
            upd(pm, data)

    t_pin = best_of(pin_loop)

    fids = [pm.getFrameId(link, pin.FrameType.BODY) for link in model.links
            if pm.existFrame(link, pin.FrameType.BODY)]

    def pin_loop_copy():  # the same, plus every link's pose copied out (what link_poses returns)
        fk, upd = pin.forwardKinematics, pin.updateFramePlacements
        out = np.empty((n, len(fids), 4, 4))
        for i in range(n):
            fk(pm, data, qs[i])
            upd(pm, data)
            omf = data.oMf
            out[i] = [omf[f].homogeneous for f in fids]

    t_copy = best_of(pin_loop_copy)
    return {"model": path.name, "links": len(model.links), "dof": len(names), "n": n,
            "ours": n / t_ours, "pinocchio": n / t_pin, "pinocchio_copy": n / t_copy}


def bench_messages(path: Path, count: int) -> dict:
    from urdfcheck.model.build import model_from_string
    from urdfcheck.publisher import JointState, StatePublisher, configuration_joints

    model = model_from_string(path.read_text(), str(path))
    names = configuration_joints(model)
    pub = StatePublisher(model)  # default ROS 2 profile, 20 Hz: stamps 0.1 s apart always publish
    msgs = [JointState(names, [0.001 * i + 0.1 * k for k in range(len(names))], 0.1 * (i + 1))
            for i in range(count)]
    for m in msgs[:100]:
        pub.on_joint_state(m)
    pub = StatePublisher(model)

    def run():
        p = StatePublisher(model)
        on = p.on_joint_state
        for m in msgs:
            on(m)

    t = best_of(run)
    out = pub.on_joint_state(msgs[0])
    return {"model": path.name, "joints": len(names), "transforms_per_message": len(out), "rate": count / t}


def bench_verify(path: Path, n: int = 1000) -> dict:
    env = dict(os.environ, PYTHONPATH=str(REPO / "src") + os.pathsep + os.environ.get("PYTHONPATH", ""))
    cmd = [sys.executable, "-m", "urdfcheck", "verify", str(path), "-n", str(n)]
    times, last = [], None
    for _ in range(3):
        t = time.perf_counter()
        last = subprocess.run(cmd, capture_output=True, text=True, env=env)
        times.append(time.perf_counter() - t)
    return {"model": path.name, "n": n, "seconds": min(times), "all": times, "exit": last.returncode,
            "summary": last.stdout.strip().splitlines()[-1] if last.stdout.strip() else last.stderr[-300:]}


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--n", type=int, default=2000, help="configurations for the batch FK comparison")
    ap.add_argument("--messages", type=int, default=100_000, help="JointState messages for the single-message path")
    ap.add_argument("--ur5", type=Path, default=_example_robot("ur_description", "urdf", "ur5_robot.urdf"))
    ap.add_argument("--pr2", type=Path, default=_corpus("ros+urdf", "urdf", "test", "pr2_desc.urdf")
                    or _example_robot("pr2_description", "urdf", "pr2.urdf"))
    a = ap.parse_args()
    if a.ur5 is None or a.pr2 is None:
        print("need a UR5 and a PR2 URDF (pip install example-robot-data, or --ur5/--pr2)", file=sys.stderr)
        return 2

    print(f"batch FK, {a.n} configurations (configurations/s; best of 3)")
    print("  pinocchio: forwardKinematics + updateFramePlacements per configuration in a Python loop;")
    print("  +copy: the same plus every link's pose copied into a numpy array (what link_poses returns)")
    print(f"  {'model':<22}{'links':>6}{'dof':>5}{'urdfcheck':>12}{'pinocchio':>12}{'ratio':>8}"
          f"{'pin+copy':>12}{'ratio':>8}")
    for p in (a.ur5, a.pr2):
        r = bench_batch(p, a.n)
        print(f"  {r['model']:<22}{r['links']:>6}{r['dof']:>5}{r['ours']:>12,.0f}{r['pinocchio']:>12,.0f}"
              f"{r['ours'] / r['pinocchio']:>7.2f}x{r['pinocchio_copy']:>12,.0f}"
              f"{r['ours'] / r['pinocchio_copy']:>7.2f}x")

    r = bench_messages(a.ur5, a.messages)
    print(f"\nsingle JointState -> transforms, {r['model']} ({r['joints']} joints, {r['transforms_per_message']} "
          f"transforms/message)")
    print(f"  {r['rate']:,.0f} messages/s = {r['rate'] / 1000:.0f}x robot_state_publisher's ~1,000 msg/s")

    r = bench_verify(a.pr2)
    print(f"\nurdfcheck verify {r['model']} -n {r['n']} (fresh process, imports included)")
    print(f"  {r['seconds']:.2f} s (best of 3: {', '.join(f'{x:.2f}' for x in r['all'])}); exit {r['exit']}; "
          f"{r['summary']}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
