"""pointmass against the in-run limit: for each scene, one fused numba kernel doing exactly the
scene's work (no World, no generators, no checks), timed in the same run.

    .venv/bin/python benchmarks/bench_limits.py [--quick] [--only-pit | --only-tiny]

Prints body-steps/s (particles × steps / s) for pointmass's World and for the fused loop, and
their ratio (1.0 = the core costs nothing over the bare loop). Median of several repeats; numba
compilation excluded. Scenes: 100 000 free particles under gravity and drag; a 100 × 100 cloth
(19 800 springs with damping, drag, two pinned corners); the ball pit of bench_peers.py
(10 000 spheres, 600 steps from the same start, against fused_pit.py's one-thread sequential
impulses with 10 velocity and 4 position passes; the mean speed and the overlaps after the run
show what each buys). Then the tiny worlds' steps/s, a step's fixed cost (issue 26, point 10:
one sphere resting on the ground ≥ 30 000 steps/s): one particle, a particle on the ground, a
sphere body on the ground, sleep on and off, and bench_rigid's 10-box tower with sleep off
(``--only-tiny``: these rows alone). The tiny rows are CPU time (``time.process_time``) and the
best of the repeats: a step of ~0.1 ms is what a shared machine's other processes stretch most,
and the fastest repeat is the one they disturbed least (on 2 cores shared five ways, wall-clock
medians of the same build moved by ±40 % from run to run; the best CPU repeat by a few %).
"""

from __future__ import annotations

import argparse
import math
import statistics
import sys
import time
from pathlib import Path

import numpy as np
from numba import njit, prange

sys.path.insert(0, str(Path(__file__).parent))
from bench_physics import DT, cloth, free_particles


@njit(cache=True, parallel=True)
def fused_free(pos, vel, inv_mass, g, k1, k2, dt, steps):
    """Gravity (as an acceleration), the cookbook's drag, semi-implicit Euler: one loop, on all
    cores as pointmass runs it at this size, split into the same chunks of 8192 particles."""
    n = pos.shape[0]
    chunk = 8192
    for _ in range(steps):
        for c in prange((n + chunk - 1) // chunk):
            for i in range(c * chunk, min(n, (c + 1) * chunk)):
                vx, vy, vz = vel[i, 0], vel[i, 1], vel[i, 2]
                speed = math.sqrt(vx * vx + vy * vy + vz * vz)
                w = inv_mass[i]
                drag = -(k1 * speed + k2 * speed * speed) / speed * w if speed > 0.0 else 0.0
                vx += (g[0] + drag * vx) * dt
                vy += (g[1] + drag * vy) * dt
                vz += (g[2] + drag * vz) * dt
                vel[i, 0], vel[i, 1], vel[i, 2] = vx, vy, vz
                pos[i, 0] += vx * dt
                pos[i, 1] += vy * dt
                pos[i, 2] += vz * dt


@njit(cache=True)
def fused_cloth(pos, vel, force, inv_mass, a, b, k, rest, damping, g, k1, k2, dt, steps):
    """Springs (Hooke + damping along the spring), drag and integration, fused."""
    for _ in range(steps):
        force[:] = 0.0
        for s in range(a.shape[0]):
            i, j = a[s], b[s]
            dx = pos[i, 0] - pos[j, 0]
            dy = pos[i, 1] - pos[j, 1]
            dz = pos[i, 2] - pos[j, 2]
            length = math.sqrt(dx * dx + dy * dy + dz * dz)
            closing = ((vel[i, 0] - vel[j, 0]) * dx + (vel[i, 1] - vel[j, 1]) * dy
                       + (vel[i, 2] - vel[j, 2]) * dz) / length
            f = (-k[s] * (length - rest[s]) - damping[s] * closing) / length
            force[i, 0] += f * dx
            force[i, 1] += f * dy
            force[i, 2] += f * dz
            force[j, 0] -= f * dx
            force[j, 1] -= f * dy
            force[j, 2] -= f * dz
        for i in range(pos.shape[0]):
            w = inv_mass[i]
            if w > 0.0:
                vx, vy, vz = vel[i, 0], vel[i, 1], vel[i, 2]
                speed = math.sqrt(vx * vx + vy * vy + vz * vz)
                drag = -(k1 * speed + k2 * speed * speed) / speed if speed > 0.0 else 0.0
                for c in range(3):
                    vel[i, c] += (g[c] + (force[i, c] + drag * vel[i, c]) * w) * dt
            for c in range(3):
                pos[i, c] += vel[i, c] * dt


def _median_rate(run, n: int, steps: int, repeats: int) -> float:
    times = []
    for _ in range(repeats):
        start = time.perf_counter()
        run(steps)
        times.append(time.perf_counter() - start)
    return n * steps / statistics.median(times)


def bench_free(n: int, steps: int, repeats: int) -> tuple[float, float]:
    world = free_particles(n)
    drag = world.forces[0]
    world.step(DT)
    p = world.particles
    pos, vel, inv = p.position.copy(), p.velocity.copy(), p.inv_mass.copy()
    fused_free(pos, vel, inv, world.gravity, drag.k1, drag.k2, DT, 1)

    def ours(k):
        for _ in range(k):
            world.step(DT)

    def limit(k):
        fused_free(pos, vel, inv, world.gravity, drag.k1, drag.k2, DT, k)

    return _median_rate(ours, n, steps, repeats), _median_rate(limit, n, steps, repeats)


def bench_cloth(side: int, steps: int, repeats: int) -> tuple[float, float]:
    world = cloth(side)
    world.step(DT)
    springs = world.forces[0]
    p = world.particles
    pos, vel, inv = p.position.copy(), p.velocity.copy(), p.inv_mass.copy()
    force = np.zeros_like(pos)
    args = (springs.a, springs.b, springs.spring_constant, springs.rest_length,
            springs.damping, world.gravity, 0.0, 0.0, DT)
    fused_cloth(pos, vel, force, inv, *args, 1)

    def ours(k):
        for _ in range(k):
            world.step(DT)

    def limit(k):
        fused_cloth(pos, vel, force, inv, *args, k)

    n = side * side
    return _median_rate(ours, n, steps, repeats), _median_rate(limit, n, steps, repeats)


def bench_pit(n: int, repeats: int) -> tuple[tuple[float, dict], tuple[float, dict]]:
    """((pointmass body-steps/s, its pile after the run), (the same for the fused loop)) over
    the pit's 600 steps; a pile is ``bench_peers.measure``'s dict (mean |v|, overlaps)."""
    import bench_peers

    _, side = bench_peers.layout(n)
    results = []
    for run in (bench_peers.run_pointmass, bench_peers.run_fused):
        runs = [run(n) for _ in range(repeats)]
        rate = n * bench_peers.STEPS / statistics.median(seconds for seconds, _, _ in runs)
        results.append((rate, bench_peers.measure(runs[-1][1], runs[-1][2], side)))
    return results[0], results[1]


def tiny_worlds() -> dict:
    """The tiny worlds whose step rate is the engine's fixed cost (issue 26, point 10: a world
    of one sphere resting on the ground at ≥ 30 000 steps/s): builders by name."""
    import pointmass as pm
    from pointmass.rigid.shapes import Sphere

    def particle():
        world = pm.World()
        world.add_particle((0, 1, 0))
        return world

    def resting_particle():
        world = pm.World()
        world.add(pm.Ground())
        world.add_particle((0, 0.1, 0), radius=0.1)
        return world

    def resting_sphere(sleep):
        def build():
            world = pm.World(sleep=sleep)
            world.add(pm.Ground())
            world.add_body(Sphere(0.5), (0, 0.5, 0), mass=1.0)
            return world
        return build

    def tower(sleep):
        def build():  # bench_rigid's tower: 10 unit cubes (1 kg, μ 0.5) on the ground
            world = pm.World(sleep=sleep)
            world.add(pm.Ground(friction=0.5))
            for i in range(10):
                world.add_body(pm.Box((0.5, 0.5, 0.5)), (0, 0.5 + i, 0), mass=1.0,
                               friction=0.5)
            return world
        return build

    return {"1-particle world": particle,
            "1 particle (r 0.1) on the ground": resting_particle,
            "1 sphere body on the ground": resting_sphere(True),
            "1 sphere body on the ground, sleep off": resting_sphere(False),
            "10-box tower, sleep off": tower(False)}


def bench_tiny(steps: int, repeats: int, build=None) -> float:
    """Steps per CPU second of a tiny world (a cookbook user's Python loop), the best of
    ``repeats``; by default one free particle. 60 steps first, so a resting body has settled
    (and, with sleep on, slept)."""
    world = (build or tiny_worlds()["1-particle world"])()
    for _ in range(60):
        world.step(DT)
    best = math.inf
    for _ in range(repeats):
        start = time.process_time()
        for _ in range(steps):
            world.step(DT)
        best = min(best, time.process_time() - start)
    return steps / best


def pit_row(args) -> None:
    """The pit's row, and what each pile looks like after the run."""
    import bench_peers

    bench_peers.run_pointmass(100)  # compile outside the timing
    n = args.pit or (1000 if args.quick else 10_000)
    (ours, pile), (limit, limit_pile) = bench_pit(n, 1 if args.quick else 3)
    name = f"ball pit N = {n}, 600 steps"
    print(f"{name:34s} {ours:12.3g} {limit:12.3g} {ours / limit:7.2f}")
    for who, after in (("pointmass", pile), ("fused loop", limit_pile)):
        print(f"  {who} after the run: mean |v| {after['mean |v|']:.3f} m/s, max |v| "
              f"{after['max |v|']:.2f} m/s, overlap {after['sphere overlap [mm]']:.1f} mm "
              f"(walls {after['wall overlap [mm]']:.1f} mm)")


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--quick", action="store_true", help="fewer steps and repeats")
    parser.add_argument("--pit", type=int, default=None, help="the pit's N (default 10 000; "
                        "--quick: 1000)")
    parser.add_argument("--only-pit", action="store_true", help="the pit row alone")
    parser.add_argument("--only-tiny", action="store_true", help="the tiny worlds' rows alone "
                        "(a step's fixed cost, issue 26 point 10)")
    args = parser.parse_args()
    if args.only_pit:
        print(f"{'scene':34s} {'pointmass':>12s} {'fused loop':>12s} {'ratio':>7s}")
        pit_row(args)
        return
    steps, repeats = (20, 3) if args.quick else (100, 5)
    if args.only_tiny:
        tiny_rows(args, repeats)
        return
    print(f"{'scene':34s} {'pointmass':>12s} {'fused loop':>12s} {'ratio':>7s}")
    for name, (ours, limit) in (
            ("free particles, N = 100 000", bench_free(100_000, steps, repeats)),
            ("cloth 100 × 100 (19 800 springs)", bench_cloth(100, steps, repeats))):
        print(f"{name:34s} {ours:12.3g} {limit:12.3g} {ours / limit:7.2f}")
    pit_row(args)
    tiny_rows(args, repeats)


def tiny_rows(args, repeats: int) -> None:
    """The tiny worlds' steps/s (``tiny_worlds``)."""
    for name, build in tiny_worlds().items():
        steps = 20_000 if not args.quick else 5_000
        tiny = bench_tiny(steps // 10 if "tower" in name else steps, repeats, build)
        print(f"{name + ', steps/s (CPU)':64s} {tiny:12.3g}")


if __name__ == "__main__":
    main()
