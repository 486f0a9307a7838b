#!/usr/bin/env python3
"""Generate a large, valid, deterministic URDF for benchmarks.

    python bench/gen_urdf.py N OUT [--seed S]      (OUT "-" writes to stdout)

The model is a tree of N links: mostly serial chains (at most MAX_CHAIN links, like an arm), which
branch off a random earlier link. Joints are revolute, continuous, prismatic and fixed, with limits
where URDF requires them (revolute/prismatic: lower/upper/effort/velocity; continuous: effort/velocity
only). Each link has one box or cylinder visual and collision, a material from a small set defined once
at the top, and an inertial computed from the solid-body formula of its shape (so every inertia is
positive definite and satisfies the triangle inequality). Axes are unit vectors. The same (N, seed)
always gives the same bytes.
"""
from __future__ import annotations

import argparse
import math
import random
import sys

MAX_CHAIN = 12
BRANCH_P = 0.15  # chance that a chain ends early and the next link branches off an earlier one

MATERIALS = (
    ("grey", "0.5 0.5 0.5 1"),
    ("blue", "0.1 0.3 0.8 1"),
    ("orange", "1 0.45 0.05 1"),
    ("black", "0.05 0.05 0.05 1"),
    ("white", "0.95 0.95 0.95 1"),
)
JOINT_TYPES = ("revolute",) * 5 + ("continuous",) * 2 + ("prismatic",) * 2 + ("fixed",) * 1
AXES = ("1 0 0", "0 1 0", "0 0 1", "-1 0 0", "0 -1 0", "0 0 -1",
        "0.6 0.8 0", "0 0.6 0.8", "0.8 0 -0.6")


def _f(x: float) -> str:
    return f"{x:.6g}"


def _shape(rng: random.Random) -> tuple[str, float, tuple[float, float, float]]:
    """(geometry XML, mass, principal moments Ixx Iyy Izz) for a random solid primitive."""
    mass = round(rng.uniform(0.2, 5.0), 3)
    if rng.random() < 0.5:
        x, y, z = (round(rng.uniform(0.02, 0.4), 3) for _ in range(3))
        geo = f'<box size="{_f(x)} {_f(y)} {_f(z)}"/>'
        inertia = (mass * (y * y + z * z) / 12, mass * (x * x + z * z) / 12, mass * (x * x + y * y) / 12)
    else:
        r = round(rng.uniform(0.01, 0.12), 3)
        h = round(rng.uniform(0.02, 0.5), 3)
        geo = f'<cylinder radius="{_f(r)}" length="{_f(h)}"/>'
        side = mass * (3 * r * r + h * h) / 12
        inertia = (side, side, mass * r * r / 2)
    return geo, mass, inertia


def _link(name: str, rng: random.Random) -> str:
    geo, mass, (ixx, iyy, izz) = _shape(rng)
    ox, oy, oz = (round(rng.uniform(-0.05, 0.05), 3) for _ in range(3))
    origin = f'<origin xyz="{_f(ox)} {_f(oy)} {_f(oz)}" rpy="0 0 0"/>'
    mat = MATERIALS[rng.randrange(len(MATERIALS))][0]
    return (
        f'  <link name="{name}">\n'
        f'    <visual>\n      {origin}\n      <geometry>{geo}</geometry>\n'
        f'      <material name="{mat}"/>\n    </visual>\n'
        f'    <collision>\n      {origin}\n      <geometry>{geo}</geometry>\n    </collision>\n'
        f'    <inertial>\n      {origin}\n      <mass value="{_f(mass)}"/>\n'
        f'      <inertia ixx="{ixx:.9g}" ixy="0" ixz="0" iyy="{iyy:.9g}" iyz="0" izz="{izz:.9g}"/>\n'
        f'    </inertial>\n'
        f'  </link>\n'
    )


def _joint(name: str, parent: str, child: str, rng: random.Random) -> str:
    jtype = JOINT_TYPES[rng.randrange(len(JOINT_TYPES))]
    xyz = " ".join(_f(round(rng.uniform(-0.3, 0.3), 3)) for _ in range(3))
    rpy = " ".join(_f(round(rng.uniform(-math.pi, math.pi), 4)) for _ in range(3))
    out = [f'  <joint name="{name}" type="{jtype}">\n',
           f'    <parent link="{parent}"/>\n    <child link="{child}"/>\n',
           f'    <origin xyz="{xyz}" rpy="{rpy}"/>\n']
    if jtype != "fixed":
        out.append(f'    <axis xyz="{AXES[rng.randrange(len(AXES))]}"/>\n')
    effort = _f(round(rng.uniform(5, 300), 1))
    velocity = _f(round(rng.uniform(0.5, 6), 2))
    if jtype == "revolute":
        lo = round(rng.uniform(-math.pi, -0.1), 4)
        hi = round(rng.uniform(0.1, math.pi), 4)
        out.append(f'    <limit lower="{_f(lo)}" upper="{_f(hi)}" effort="{effort}" velocity="{velocity}"/>\n')
    elif jtype == "prismatic":
        lo = round(rng.uniform(-0.5, 0.0), 3)
        hi = round(rng.uniform(0.05, 0.5), 3)
        out.append(f'    <limit lower="{_f(lo)}" upper="{_f(hi)}" effort="{effort}" velocity="{velocity}"/>\n')
    elif jtype == "continuous":
        out.append(f'    <limit effort="{effort}" velocity="{velocity}"/>\n')
    if jtype != "fixed":
        out.append(f'    <dynamics damping="{_f(round(rng.uniform(0, 1), 3))}" friction="0"/>\n')
    out.append("  </joint>\n")
    return "".join(out)


def parents(n_links: int, seed: int = 0) -> list[int]:
    """parents[i] is the index of link i's parent (-1 for the root, link 0)."""
    rng = random.Random(f"parents:{seed}")
    out = [-1] * n_links
    chain = 1
    for i in range(1, n_links):
        if chain < MAX_CHAIN and rng.random() >= BRANCH_P:
            out[i] = i - 1
            chain += 1
        else:
            out[i] = rng.randrange(i)
            chain = 1
    return out


def generate(n_links: int, seed: int = 0, name: str | None = None) -> str:
    """A URDF document (str) with exactly `n_links` links and `n_links - 1` joints."""
    if n_links < 1:
        raise ValueError("n_links must be >= 1")
    rng = random.Random(seed)
    width = max(4, len(str(n_links - 1)))
    lname = [f"link_{i:0{width}d}" for i in range(n_links)]
    parts = ['<?xml version="1.0"?>\n',
             f'<!-- generated by bench/gen_urdf.py: {n_links} links, seed {seed} -->\n',
             f'<robot name="{name or f"gen_{n_links}"}">\n']
    for mname, rgba in MATERIALS:
        parts.append(f'  <material name="{mname}">\n    <color rgba="{rgba}"/>\n  </material>\n')
    for i, p in enumerate(parents(n_links, seed)):
        parts.append(_link(lname[i], rng))
        if p >= 0:
            parts.append(_joint(f"joint_{i:0{width}d}", lname[p], lname[i], rng))
    parts.append("</robot>\n")
    return "".join(parts)


def write(n_links: int, out: str, seed: int = 0) -> None:
    text = generate(n_links, seed)
    if out == "-":
        sys.stdout.write(text)
    else:
        with open(out, "w", encoding="utf-8") as f:
            f.write(text)


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(description="Write a valid URDF with N links (deterministic).")
    ap.add_argument("n", type=int, metavar="N", help="number of links (>= 1)")
    ap.add_argument("out", metavar="OUT", help='output file, or "-" for stdout')
    ap.add_argument("--seed", type=int, default=0, help="random seed (default 0)")
    a = ap.parse_args(argv)
    if a.n < 1:
        ap.error("N must be >= 1")
    write(a.n, a.out, a.seed)
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
