"""What joints cost: the same bodies stepped with and without their joints, in one run.

    PYTHONPATH=src .venv/bin/python benchmarks/bench_joints.py [--steps 240]

Scenes (dt = 1/60, ``World()`` defaults):

* chain N: N boxes (0.1 × 0.2 × 0.1 m, 1 kg) hung end to end from a world anchor by ball joints,
  released 5° off the vertical (so it swings and stays awake; sleep off for the timing);
  baseline: the same boxes falling free (no joints, no ground), i.e. the step without any
  solver work.
* ragdoll: the ragdoll demo (12 bones, 11 joints with limits, seed 1); baseline: the same
  bones with the same push but no joints (they fall apart and pile up on the ground).

Printed per scene: ms per step with joints (the default: the point blocks by the exact tree
solve, ``solver/joint_direct.py``), without (the baseline, measured right after in the same
process), their ratio, the velocity passes per step and the largest joint gap over the run;
then the same with every joint left to Gauss–Seidel (``joint_solver.DIRECT = False``, the
solver before the tree solve), its ms, passes and gap.
The first step of each world is a warm-up (numba compiles), not timed.
"""

from __future__ import annotations

import argparse
import math
import os
import time

import numpy as np

import pointmass as pm
from pointmass.demo import load_demo
from pointmass.rigid.joints import BallJoint
from pointmass.rigid.shapes import Box
from pointmass.solver import joint_solver

DT = 1 / 60


def chain(n: int, joined: bool) -> pm.World:
    world = pm.World(gravity=(0.0, -9.81, 0.0), sleep=False)
    tilt = math.radians(5.0)
    down = np.array([math.sin(tilt), -math.cos(tilt), 0.0])
    turn = (math.cos(tilt / 2), 0.0, 0.0, math.sin(tilt / 2))
    above = None
    for k in range(n):
        box = world.add_body(Box((0.05, 0.1, 0.05)), tuple(down * (0.1 + 0.2 * k)), turn,
                             mass=1.0)
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


def timed(world: pm.World, steps: int) -> tuple[float, float, float]:
    """(ms per step, mean velocity passes, largest joint gap [mm]) over ``steps`` steps after
    one warm-up step (the gap is read after each step, outside the timing)."""
    world.step(DT)
    passes = 0
    gap = 0.0
    spent = 0.0
    for _ in range(steps):
        start = time.perf_counter()
        passes += world.step(DT).velocity_passes
        spent += time.perf_counter() - start
        if len(world.joints):
            gap = max(gap, 1e3 * float(np.max(world.joints.separations())))
    return 1e3 * spent / steps, passes / steps, gap


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--steps", type=int, default=240)
    args = parser.parse_args()
    print(f"load: {os.getloadavg()[0]:.2f} (1 min), steps: {args.steps}")
    print(f"{'scene':<12}{'joints ms':>11}{'baseline ms':>13}{'ratio':>8}{'passes':>8}"
          f"{'gap mm':>9}{'GS ms':>9}{'GS passes':>11}{'GS gap mm':>11}")
    scenes = [(f"chain {n}", lambda j, n=n: chain(n, j)) for n in (10, 50, 200)]
    scenes.append(("ragdoll", ragdoll))
    for name, make in scenes:
        ms, passes, gap = timed(make(True), args.steps)
        base, _, _ = timed(make(False), args.steps)
        joint_solver.DIRECT = False
        try:
            gs_ms, gs_passes, gs_gap = timed(make(True), args.steps)
        finally:
            joint_solver.DIRECT = True
        print(f"{name:<12}{ms:>11.3f}{base:>13.3f}{ms / base:>8.2f}{passes:>8.1f}{gap:>9.3f}"
              f"{gs_ms:>9.3f}{gs_passes:>11.1f}{gs_gap:>11.1f}")

if __name__ == "__main__":
    main()
