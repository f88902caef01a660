"""What joints cost: the same bodies stepped with and without their joints, in one run.

    PYTHONPATH=src .venv/bin/python benchmarks/bench_joints.py [--steps 240]

Scenes (dt = 1/60, ``World()`` defaults):

* chain N: N boxes (0.1 × 0.2 × 0.1 m, 1 kg) hung end to end from a world anchor by ball joints,
  starting straight and at rest; baseline: the same boxes falling free (no joints, no ground),
  i.e. the step without any solver work. (The 50-box chain does not hold still at the
  defaults: 30 Gauss–Seidel passes do not converge on it, and the joints' bias then feeds it:
  a known limit, see the gap column.)
* ragdoll: the ragdoll demo (12 bones, 11 joints with limits, seed 1); baseline: the same
  bones with the same push but no joints (they fall apart and pile up on the ground).

Printed per scene: ms per step with joints, without (the baseline, measured right after in the
same process), their ratio, the velocity passes per step, and the largest joint gap at the end.
The first step of each world is a warm-up (numba compiles), not timed.
"""

from __future__ import annotations

import argparse
import os
import time

import numpy as np

import pointmass as pm
from pointmass.demo import load_demo
from pointmass.rigid.joints import BallJoint
from pointmass.rigid.shapes import Box

DT = 1 / 60


def chain(n: int, joined: bool) -> pm.World:
    world = pm.World(gravity=(0.0, -9.81, 0.0))
    above = None
    for k in range(n):
        box = world.add_body(Box((0.05, 0.1, 0.05)), (0.0, -0.1 - 0.2 * k, 0.0), mass=1.0)
        if joined:
            world.add(BallJoint(box, (0.0, 0.1, 0.0), above))
        above = box
    return world


def ragdoll(joined: bool) -> pm.World:
    demo = load_demo("ragdoll")
    world = demo.build(demo.default_params()).world
    if not joined:
        for joint in list(world.joints):
            world.remove(joint)
    return world


def timed(world: pm.World, steps: int) -> tuple[float, float]:
    """(ms per step, mean velocity passes) over ``steps`` steps after one warm-up step."""
    world.step(DT)
    passes = 0
    start = time.perf_counter()
    for _ in range(steps):
        passes += world.step(DT).velocity_passes
    return 1e3 * (time.perf_counter() - start) / steps, passes / steps


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--steps", type=int, default=240)
    args = parser.parse_args()
    print(f"load: {os.getloadavg()[0]:.2f} (1 min), steps: {args.steps}")
    print(f"{'scene':<12}{'joints ms':>11}{'baseline ms':>13}{'ratio':>8}{'passes':>8}"
          f"{'gap mm':>8}")
    scenes = [(f"chain {n}", lambda j, n=n: chain(n, j)) for n in (10, 50)]
    scenes.append(("ragdoll", ragdoll))
    for name, make in scenes:
        world = make(True)
        ms, passes = timed(world, args.steps)
        gap = 1e3 * float(np.max(world.joints.separations()))
        base, _ = timed(make(False), args.steps)
        print(f"{name:<12}{ms:>11.3f}{base:>13.3f}{ms / base:>8.2f}{passes:>8.1f}{gap:>8.3f}")


if __name__ == "__main__":
    main()
