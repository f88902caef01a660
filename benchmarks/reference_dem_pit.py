"""The ball pit's physics solved the slow, accurate way: soft spheres (DEM) with a tiny step.

    .venv/bin/python benchmarks/reference_dem_pit.py [--n 1000] [--seeds 0 1 2] [--until 40]

Why: bench_peers.py asks how quiet each engine's pit is after 600 steps of 1/60 s. Whether a
figure there is the solver's noise or the pile's own motion can only be told against the same
pit solved without a rigid-contact solver's shortcuts. This is the discrete-element method of
granular physics (Cundall & Strack): every touching pair is a linear spring with a dashpot,
stiff enough that the spheres overlap well under a millimetre at rest, damped so that a head-on
collision keeps exactly e = 0.5 of its speed (the damping ratio is found by bisection on one
contact, the tension cut off: spheres push, never pull), integrated with semi-implicit Euler at
a step ~70 times shorter than a contact lasts. Same layout (bench_peers.layout), masses, radii,
walls and gravity; frictionless.

Prints, for each seed, the mean and max speed of the DEM pit and of pointmass's (default
World, dt = 1/60) at each whole multiple of 10 s, and the mean height (the pile compacts while
it still moves). ``--stiffness`` checks that the answer is the hard-sphere limit: raised, the
figures over several seeds should keep their spread (the step shrinks with it). One seed's
figure moves with any change at all — the pile is chaotic — so compare seeds as a set.
Results: RESULTS.md, session 24.
"""

from __future__ import annotations

import argparse
import math
import sys
import time
from pathlib import Path

import numpy as np
from numba import njit

sys.path.insert(0, str(Path(__file__).parent))
from bench_peers import DT, E, R, layout, pointmass_pit

G = 9.81


@njit(cache=True)
def _restitution(zeta: float) -> float:
    """Exit over entry speed of one spring–dashpot contact (ω = 1) with the tension cut off."""
    x, v, h = 0.0, -1.0, 1e-4
    for _ in range(10_000_000):  # an overdamped contact may never let go: e = 0 then
        f = max(-x - 2.0 * zeta * v, 0.0) if x < 0.0 else 0.0
        v += f * h
        x += v * h
        if x >= 0.0 and v > 0.0:
            return v
    return 0.0


def damping_ratio(e: float) -> float:
    """The damping ratio whose contact keeps ``e`` of the closing speed (bisection)."""
    lo, hi = 0.0, 1.0
    for _ in range(50):
        mid = 0.5 * (lo + hi)
        lo, hi = (mid, hi) if _restitution(mid) > e else (lo, mid)
    return 0.5 * (lo + hi)


@njit(cache=True)
def _pairs(pos, half, reach, out_a, out_b):
    """Every pair closer than ``reach`` (a dense cell grid over the box; heights clamped into
    it, which merges cells but never separates neighbours). Returns the count, or -1 if the
    output is too small."""
    n = pos.shape[0]
    nxz = max(1, int(2.0 * half / reach))
    ny = max(1, int(12.0 / reach))
    cell = np.empty(n, np.int64)
    for i in range(n):
        cx = min(max(int((pos[i, 0] + half) / reach), 0), nxz - 1)
        cy = min(max(int(pos[i, 1] / reach), 0), ny - 1)
        cz = min(max(int((pos[i, 2] + half) / reach), 0), nxz - 1)
        cell[i] = (cx * ny + cy) * nxz + cz
    order = np.argsort(cell)
    start = np.zeros(nxz * ny * nxz + 1, np.int64)
    for i in range(n):
        start[cell[i] + 1] += 1
    for c in range(nxz * ny * nxz):
        start[c + 1] += start[c]
    m = 0
    reach2 = reach * reach
    for i in range(n):
        c = cell[i]
        cz = c % nxz
        cy = (c // nxz) % ny
        cx = c // (nxz * ny)
        for dx in range(-1, 2):
            for dy in range(-1, 2):
                for dz in range(-1, 2):
                    x, y, z = cx + dx, cy + dy, cz + dz
                    if x < 0 or x >= nxz or y < 0 or y >= ny or z < 0 or z >= nxz:
                        continue
                    o = (x * ny + y) * nxz + z
                    for k in range(start[o], start[o + 1]):
                        j = order[k]
                        if j <= i:
                            continue
                        d2 = 0.0
                        for q in range(3):
                            d2 += (pos[i, q] - pos[j, q]) ** 2
                        if d2 < reach2:
                            if m == out_a.shape[0]:
                                return -1
                            out_a[m] = i
                            out_b[m] = j
                            m += 1
    return m


@njit(cache=True)
def simulate(pos, vel, half, radius, stiffness, zeta, dt, steps, skin):
    """Advance ``pos``/``vel`` (N, 3) of unit-mass spheres in place by ``steps`` steps. The pair
    list is rebuilt whenever some sphere has moved half the ``skin`` since the last build."""
    n = pos.shape[0]
    c_pair = 2.0 * zeta * math.sqrt(stiffness * 0.5)   # two unit masses: reduced mass 1/2
    c_wall = 2.0 * zeta * math.sqrt(stiffness)
    out_a = np.empty(16 * n, np.int64)
    out_b = np.empty(16 * n, np.int64)
    built = pos.copy()
    m = -1
    force = np.zeros((n, 3))
    for _ in range(steps):
        moved = 0.0
        for i in range(n):
            d2 = 0.0
            for q in range(3):
                d2 += (pos[i, q] - built[i, q]) ** 2
            moved = max(moved, d2)
        if m < 0 or moved > (0.5 * skin) ** 2:
            m = _pairs(pos, half, 2.0 * radius + skin, out_a, out_b)
            while m < 0:
                out_a = np.empty(2 * out_a.shape[0], np.int64)
                out_b = np.empty(2 * out_b.shape[0], np.int64)
                m = _pairs(pos, half, 2.0 * radius + skin, out_a, out_b)
            built[:] = pos
        force[:] = 0.0
        for p in range(m):
            i, j = out_a[p], out_b[p]
            ux = pos[j, 0] - pos[i, 0]
            uy = pos[j, 1] - pos[i, 1]
            uz = pos[j, 2] - pos[i, 2]
            d = math.sqrt(ux * ux + uy * uy + uz * uz)
            depth = 2.0 * radius - d
            if depth <= 0.0:
                continue
            ux /= d
            uy /= d
            uz /= d
            closing = ((vel[i, 0] - vel[j, 0]) * ux + (vel[i, 1] - vel[j, 1]) * uy
                       + (vel[i, 2] - vel[j, 2]) * uz)
            f = max(stiffness * depth + c_pair * closing, 0.0)
            force[i, 0] -= f * ux
            force[i, 1] -= f * uy
            force[i, 2] -= f * uz
            force[j, 0] += f * ux
            force[j, 1] += f * uy
            force[j, 2] += f * uz
        for i in range(n):
            # floor (y = 0) and the four walls (x, z = ±half): outward normal component q
            depth = radius - pos[i, 1]
            if depth > 0.0:
                force[i, 1] += max(stiffness * depth - c_wall * vel[i, 1], 0.0)
            for q in (0, 2):
                depth = pos[i, q] + radius - half
                if depth > 0.0:
                    force[i, q] -= max(stiffness * depth + c_wall * vel[i, q], 0.0)
                depth = -half + radius - pos[i, q]
                if depth > 0.0:
                    force[i, q] += max(stiffness * depth - c_wall * vel[i, q], 0.0)
            vel[i, 0] += force[i, 0] * dt
            vel[i, 1] += (force[i, 1] - G) * dt
            vel[i, 2] += force[i, 2] * dt
            for q in range(3):
                pos[i, q] += vel[i, q] * dt


def contact_time(stiffness: float) -> float:
    """How long a pair contact lasts [s] (half a period of two unit masses on the spring); the
    step is a 70th of it."""
    return math.pi / math.sqrt(stiffness / 0.5)


def reference_run(pos: np.ndarray, side: float, seconds: float, stiffness: float = 1e5):
    """Positions and velocities of the pit started at ``pos`` (at rest) after ``seconds``."""
    zeta = damping_ratio(E)
    dt = contact_time(stiffness) / 70.0
    pos, vel = pos.copy(), np.zeros_like(pos)
    simulate(pos, vel, side / 2, R, stiffness, zeta, dt, round(seconds / dt), 0.1)
    return pos, vel


def summary(pos: np.ndarray, vel: np.ndarray) -> str:
    speed = np.linalg.norm(vel, axis=1)
    return f"mean |v| {speed.mean():.4f}  max |v| {speed.max():.3f}  mean y {pos[:, 1].mean():.4f}"


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--n", type=int, default=1000)
    parser.add_argument("--seeds", type=int, nargs="+", default=[0, 1, 2])
    parser.add_argument("--until", type=float, default=10.0, help="seconds simulated")
    parser.add_argument("--stiffness", type=float, default=1e5, help="N/m (default 1e5)")
    parser.add_argument("--no-pointmass", action="store_true")
    args = parser.parse_args()
    zeta = damping_ratio(E)
    dt = contact_time(args.stiffness) / 70.0
    print(f"DEM: stiffness {args.stiffness:.0e} N/m, damping ratio {zeta:.4f} (e = {E}), "
          f"contact {1e3 * contact_time(args.stiffness):.2f} ms, dt {1e6 * dt:.1f} µs, "
          f"resting overlap under one sphere ≈ {1e3 * G / args.stiffness:.2f} mm")
    for seed in args.seeds:
        start, side = layout(args.n, seed)
        pos, vel = start.copy(), np.zeros_like(start)
        world = None if args.no_pointmass else pointmass_pit(start, side)
        t, clock = 0.0, time.perf_counter()
        while t < args.until - 1e-9:
            span = min(10.0, args.until - t)
            simulate(pos, vel, side / 2, R, args.stiffness, zeta, dt, round(span / dt), 0.1)
            t += span
            print(f"seed {seed}  t {t:5.1f} s  DEM        {summary(pos, vel)}", flush=True)
            if world is not None:
                for _ in range(round(span / DT)):
                    world.step(DT)
                print(f"seed {seed}  t {t:5.1f} s  pointmass  "
                      f"{summary(world.particles.position, world.particles.velocity)}",
                      flush=True)
        print(f"seed {seed}: {time.perf_counter() - clock:.1f} s of wall time")

if __name__ == "__main__":
    main()
