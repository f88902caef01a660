"""Soak: ten simulated minutes of the 1000-sphere ball pit and of the bridge under its heaviest
load, printing energy, overlap, floor penetration, link error and escapes over time.

    .venv/bin/python benchmarks/soak.py [--minutes 10] [--every 60]

A pass is: nothing escapes, the floor penetration does not grow, the overlap stays below 1 % of
the diameter, the bridge's rods hold. Figures go in the issue notes; nothing here is timed.
"""

from __future__ import annotations

import argparse
import math
import sys
import time
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "tests" / "physics"))

from test_solver import ball_pit

import pointmass as pm
from pointmass.demo import Simulation, load_demo

DT = 1.0 / 60.0


def soak_pit(minutes: float, every: float) -> None:
    world = ball_pit(1000)
    side = 1.1 * math.ceil(math.sqrt(1000 / 4)) / 2
    print("ball pit, N = 1000: t [s], kinetic [J], total [J], mean |v| [m/s], max overlap "
          "[mm], floor penetration [mm], escapes")
    steps = round(minutes * 60 / DT)
    report = round(every / DT)
    start = time.perf_counter()
    for n in range(1, steps + 1):
        stats = world.step(DT)
        if n % report == 0:
            p = world.particles
            floor = max(0.0, float(-(p.position[:, 1] - p.radius).min()))
            out = (np.abs(p.position[:, [0, 2]]) > side + 1e-6).any(axis=1).sum()
            speed = float(np.linalg.norm(p.velocity, axis=1).mean())
            print(f"{world.time:7.0f} {world.kinetic_energy():10.4f} "
                  f"{world.kinetic_energy() + world.potential_energy():10.2f} {speed:8.4f} "
                  f"{1e3 * stats.max_penetration:8.3f} {1e3 * floor:8.3f} {out:4d}", flush=True)
    print(f"  ({time.perf_counter() - start:.0f} s of wall time)")


def soak_bridge(minutes: float, every: float) -> None:
    sim = Simulation(load_demo("bridge"), overrides=["load_mass=50"])
    world = sim.world
    rods = [g for g in world.contact_generators if isinstance(g, pm.Rod)]
    cables = [g for g in world.contact_generators if isinstance(g, pm.Cable)]
    print("bridge, 50 kg load walked back and forth: t [s], kinetic [J], worst rod error [%], "
          "worst cable stretch [%]")
    steps = round(minutes * 60 / sim.scene.dt)
    report = round(every / sim.scene.dt)
    load = sim.scene.handles["load"]
    for n in range(1, steps + 1):
        load.x = 3.0 * math.sin(0.2 * world.time)  # walk the load along the deck
        sim.step()
        if n % report == 0:
            rod = max((float(np.abs(r.current_lengths(world.particles) / r.lengths_target - 1)
                             .max()) for r in rods), default=0.0)
            cable = max((float((c.current_lengths(world.particles) / c.lengths_target - 1)
                               .max()) for c in cables), default=0.0)
            print(f"{world.time:7.0f} {world.kinetic_energy():10.4f} {100 * rod:8.3f} "
                  f"{100 * cable:8.3f}", flush=True)


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--minutes", type=float, default=10.0)
    parser.add_argument("--every", type=float, default=60.0, help="report every N seconds")
    args = parser.parse_args()
    soak_pit(args.minutes, args.every)
    soak_bridge(args.minutes, args.every)


if __name__ == "__main__":
    main()
