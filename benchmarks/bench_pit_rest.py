"""Do the frictionless sphere pits of bench_peers.py come to rest and fall asleep? (issue 26,
acceptance point 4: mean speed ≤ 0.002 m/s by 40 s, as the soft-sphere reference
reference_dem_pit.py reaches, asleep by 60 s, the 10 000 pit's overlap ≤ 1 % of the diameter.)

    .venv/bin/python benchmarks/bench_pit_rest.py [--n 100 1000 10000] [--until 60]
        [--sleep on off]

For each pit (default ``World()``, bench_peers' layout and materials) and each sleep setting,
prints every 10 s of simulated time: mean and max speed, particles awake, the largest
sphere–sphere and wall overlap (bench_peers.measure), and the wall-clock cost per step over
the last 10 s (so a pit that falls asleep shows what sleeping saves).
"""

from __future__ import annotations

import argparse
import sys
import time
from pathlib import Path

sys.path.insert(0, str(Path(__file__).parent))
from bench_peers import DT, layout, measure, pointmass_pit


def run(n: int, until: float, sleep: bool) -> None:
    pos, side = layout(n)
    world = pointmass_pit(pos, side)
    world.sleep = sleep
    every = round(10.0 / DT)
    start = time.perf_counter()
    for s in range(1, round(until / DT) + 1):
        world.step(DT)
        if s % every == 0:
            now = time.perf_counter()
            p = world.particles
            m = measure(p.position, p.velocity, side)
            print(f"N={n:6d} sleep={'on ' if sleep else 'off'} t={world.time:5.1f} s  "
                  f"mean |v| {m['mean |v|']:.4f}  max |v| {m['max |v|']:.3f}  "
                  f"awake {int(p.awake.sum()):6d}  overlap {m['sphere overlap [mm]']:.2f} mm "
                  f"(wall {m['wall overlap [mm]']:.2f})  {1e3 * (now - start) / every:.2f} "
                  "ms/step", flush=True)
            start = time.perf_counter()


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--n", type=int, nargs="+", default=[100, 1000, 10000])
    parser.add_argument("--until", type=float, default=60.0)
    parser.add_argument("--sleep", nargs="+", choices=["on", "off"], default=["on", "off"])
    args = parser.parse_args()
    for n in args.n:
        for setting in args.sleep:
            run(n, args.until, setting == "on")


if __name__ == "__main__":
    main()
