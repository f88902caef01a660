"""Particle links benchmark: steps per second of chains, a bridge and a small pile, the scenes
that reach the particle solver's exact solve (``solver/direct.py``) and its re-measured
projection (``solver/remeasure.py``).

    .venv/bin/python benchmarks/bench_links.py [--steps N] [--repeat R]

Prints, per scene, steps per second (the best of ``--repeat`` runs, after one warm-up step so
numba's compilation is excluded) and the largest link stretch seen. Compare two builds by
running this file with each on ``PYTHONPATH`` in the same session, one after the other.
"""

from __future__ import annotations

import argparse
import time

import numpy as np

import pointmass as pm


def level_chain(links: int, length: float, load: float) -> tuple[pm.World, list]:
    """``links`` 1 kg particles on rods of ``length`` from an anchor, released level; with a
    load on a 0.6 m cable (e = 0) from the last when ``load`` > 0."""
    world = pm.World()
    ids = world.add_particles([((i + 1) * length, 0.0, 0.0) for i in range(links)],
                              masses=np.ones(links))
    rods = [world.add(pm.AnchoredRod(ids[0], (0.0, 0.0, 0.0), length))]
    if links > 1:
        rods.append(world.add(pm.Rod(ids[:-1], ids[1:], length)))
    if load > 0:
        heavy = world.add_particle((links * length + 0.6, 0.0, 0.0), mass=load)
        rods.append(world.add(pm.Cable(ids[-1], heavy, 0.6, restitution=0.0)))
    return world, rods


def swinging_load(load: float) -> tuple[pm.World, list]:
    """The issue-26 scene: a 1 kg particle up on a 0.5 m anchored rod, ``load`` kg level
    beside it on a 0.6 m cable (e = 0)."""
    world = pm.World()
    light = world.add_particle((0.0, 0.5, 0.0), mass=1.0)
    heavy = world.add_particle((0.0, 0.5, 0.6), mass=load)
    rods = [world.add(pm.AnchoredRod(light, (0.0, 0.0, 0.0), 0.5)),
            world.add(pm.Cable(light, heavy, 0.6, restitution=0.0))]
    return world, rods


def small_pile() -> tuple[pm.World, list]:
    """40 spheres dropped into a small box (contacts only: no link)."""
    rng = np.random.default_rng(2)
    world = pm.World()
    world.add_particles(rng.uniform((-0.5, 0.2, -0.5), (0.5, 2.0, 0.5), (40, 3)), radii=0.1)
    world.add(pm.BoxContainer((-0.6, 0.0, -0.6), (0.6, 5.0, 0.6), restitution=0.3))
    world.add(pm.SphereCollisions(restitution=0.3))
    return world, []


SCENES = {
    "issue scene 100 kg, dt 1/32": (lambda: swinging_load(100.0), 1 / 32),
    "issue scene 1000 kg, dt 1/32": (lambda: swinging_load(1000.0), 1 / 32),
    "10 rods + 1000 kg, level, dt 1/32": (lambda: level_chain(10, 0.5, 1000.0), 1 / 32),
    "50 rods + 1000 kg, level, dt 1/32": (lambda: level_chain(50, 0.5, 1000.0), 1 / 32),
    "30 rods of 0.3 m, level, dt 1/60": (lambda: level_chain(30, 0.3, 0.0), 1 / 60),
    "100 rods of 1 m, level, dt 1/60": (lambda: level_chain(100, 1.0, 0.0), 1 / 60),
    "40-sphere pile, dt 1/60": (small_pile, 1 / 60),
}


def stretch(world: pm.World, links: list) -> float:
    worst = 0.0
    for link in links:
        rest = link.lengths_target
        err = link.current_lengths(world.particles) / rest - 1.0
        worst = max(worst, float(np.max(err if isinstance(link, pm.Cable) else np.abs(err))))
    return worst


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--steps", type=int, default=100)
    parser.add_argument("--repeat", type=int, default=3)
    args = parser.parse_args()
    print(f"pointmass from {pm.__file__}")
    for name, (make, dt) in SCENES.items():
        best = float("inf")
        worst = 0.0
        try:
            for _ in range(args.repeat):
                world, links = make()
                world.step(dt)  # compile (cached after the first run)
                start = time.perf_counter()
                for _ in range(args.steps):
                    world.step(dt)
                    if links:
                        worst = max(worst, stretch(world, links))
                best = min(best, time.perf_counter() - start)
        except FloatingPointError as error:  # a build that blows up on the scene
            print(f"{name:38s} blew up: {error}")
            continue
        print(f"{name:38s} {args.steps / best:9.0f} steps/s   max stretch {worst:.2e}")


if __name__ == "__main__":
    main()
