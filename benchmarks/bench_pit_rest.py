"""Do the frictionless sphere pits of bench_peers.py come to rest and fall asleep? (issue 26,
acceptance point 4: mean speed ≤ 0.002 m/s by 40 s, as the soft-sphere reference
reference_dem_pit.py reaches, asleep by 60 s, the 10 000 pit's overlap ≤ 1 % of the diameter.)

    .venv/bin/python benchmarks/bench_pit_rest.py [--n 100 1000 10000] [--until 60]
        [--sleep on off] [--every 10] [--set NAME=VALUE ...]
        [--save-at T --state PATH | --state PATH]

For each pit (default ``World()``, bench_peers' layout and materials) and each sleep setting,
prints every ``--every`` s of simulated time: mean, median and max speed, particles awake, the
largest sphere–sphere and wall overlap (bench_peers.measure), the median speed over the last
interval in the thirds of the pit along x (the particles' index order: the rows' order in the
sweeps), and the wall-clock cost per step over the interval (so a pit that falls asleep shows
what sleeping saves).

Measuring the 10 000 pit to 60 s is costly; ``--save-at 30 --state s.pkl`` pickles the world
at 30 s (``World`` pickles whole: particles, sleep state, the impulse history; a copy steps on
with the same bits), and ``--state s.pkl --until 40`` goes on from it, with ``--set
max_large_velocity_passes=40`` (any ``SolverSettings`` field) to see what a setting changes
from the same state.
"""

from __future__ import annotations

import argparse
import dataclasses
import pickle
import sys
import time
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).parent))
from bench_peers import DT, layout, measure, pointmass_pit


def settings_from(assignments: list[str], settings):
    """``settings`` with each ``NAME=VALUE`` applied (the field's own type)."""
    changes = {}
    names = {f.name: f for f in dataclasses.fields(settings)}
    for text in assignments:
        name, sep, value = text.partition("=")
        if not sep or name not in names:
            raise SystemExit(f"--set expects NAME=VALUE with NAME a SolverSettings field "
                             f"({', '.join(names)}), got {text!r}")
        changes[name] = type(getattr(settings, name))(float(value))
    return dataclasses.replace(settings, **changes)


def run(n: int, until: float, sleep: bool, every_s: float, assignments: list[str],
        state: str | None, save_at: float | None) -> None:
    pos, side = layout(n)
    if state is not None and save_at is None:
        with open(state, "rb") as f:
            world = pickle.load(f)
    else:
        world = pointmass_pit(pos, side)
    world.sleep = sleep
    world.settings = settings_from(assignments, world.settings)
    every = round(every_s / DT)
    speeds = []
    start = time.perf_counter()
    while world.time < until - 1e-9:
        world.step(DT)
        p = world.particles
        speeds.append(np.linalg.norm(p.velocity, axis=1))
        s = round(world.time / DT)
        if save_at is not None and s == round(save_at / DT):
            with open(state, "wb") as f:
                pickle.dump(world, f)
        if s % every == 0:
            now = time.perf_counter()
            m = measure(p.position, p.velocity, side)
            x = p.position[:, 0]
            third = side / 6
            creep = np.mean(speeds, axis=0)
            thirds = [np.median(creep[x < -third]), np.median(creep[np.abs(x) <= third]),
                      np.median(creep[x > third])]
            print(f"N={n:6d} sleep={'on ' if sleep else 'off'} t={world.time:5.1f} s  "
                  f"mean |v| {m['mean |v|']:.4f}  median {np.median(speeds[-1]):.4f}  "
                  f"max |v| {m['max |v|']:.3f}  awake {int(p.awake.sum()):6d}  "
                  f"overlap {m['sphere overlap [mm]']:.2f} mm (wall {m['wall overlap [mm]']:.2f})"
                  f"  median by x third {thirds[0]:.4f} {thirds[1]:.4f} {thirds[2]:.4f}  "
                  f"{1e3 * (now - start) / every:.2f} ms/step", flush=True)
            speeds = []
            start = time.perf_counter()


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--n", type=int, nargs="+", default=[100, 1000, 10000])
    parser.add_argument("--until", type=float, default=60.0)
    parser.add_argument("--sleep", nargs="+", choices=["on", "off"], default=["on", "off"])
    parser.add_argument("--every", type=float, default=10.0, help="report interval [s]")
    parser.add_argument("--set", nargs="+", default=[], metavar="NAME=VALUE",
                        help="SolverSettings fields to change")
    parser.add_argument("--state", help="a pickled world to go on from (or to save to)")
    parser.add_argument("--save-at", type=float, help="save the world to --state at this time")
    args = parser.parse_args()
    if (args.save_at is not None or args.state is not None) and \
            (len(args.n) != 1 or len(args.sleep) != 1):
        raise SystemExit("--state and --save-at take one --n and one --sleep")
    if args.save_at is not None and args.state is None:
        raise SystemExit("--save-at needs --state PATH to save to")
    for n in args.n:
        for setting in args.sleep:
            run(n, args.until, setting == "on", args.every, args.set, args.state, args.save_at)


if __name__ == "__main__":
    main()
