"""Does a physics step let other Python threads run? (The window overlaps physics in a worker
thread with drawing on the main thread: that only pays when the step's kernels release the GIL.)

    PYTHONPATH=src .venv/bin/python benchmarks/bench_gil.py [--count 10000] [--steps 60]

Runs the ball pit (``--count`` spheres, poured ``--settle`` simulated seconds first), then:
``--steps`` steps alone; a pure-Python spin loop alone for as long; the steps in a thread
while the main thread spins in Python (needs the GIL); and the steps beside a main thread busy
hashing (sha256 of 1 MiB lets the GIL go: a core taken, the GIL free). Prints the step times,
and how much of its own speed the Python spin kept while the steps ran (≈100% on two free
cores when the kernels release the GIL; far less when they hold it). The step beside the
hashing against the step beside the spin separates sharing the cores from waiting for the GIL
(on a busy machine both vary: compare figures of one run).
"""

from __future__ import annotations

import argparse
import hashlib
import sys
import threading
import time

import pointmass as pm


def spin(until: float) -> int:
    """Count loop turns of plain Python until ``perf_counter() >= until``."""
    n = 0
    clock = time.perf_counter
    while clock() < until:
        n += 1
    return n


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--count", type=int, default=10000)
    parser.add_argument("--steps", type=int, default=60)
    parser.add_argument("--settle", type=float, default=3.0)
    parser.add_argument("--switch-interval", type=float, default=None,
                        help="sys.setswitchinterval for the run [s] (Python's default: 0.005)")
    args = parser.parse_args()
    if args.switch_interval is not None:
        sys.setswitchinterval(args.switch_interval)

    sim = pm.Simulation("ball_pit", overrides=[f"count={args.count}"])
    sim.advance(args.settle)                      # compile, and pour a pile

    t0 = time.perf_counter()
    for _ in range(args.steps):
        sim.step()
    alone = time.perf_counter() - t0

    t0 = time.perf_counter()
    rate = spin(t0 + alone) / alone               # spins per second, nothing else running

    done = []

    def work() -> None:
        start = time.perf_counter()
        for _ in range(args.steps):
            sim.step()
        done.append(time.perf_counter() - start)

    thread = threading.Thread(target=work)
    t0 = time.perf_counter()
    thread.start()
    turns = 0
    while thread.is_alive():
        turns += spin(time.perf_counter() + 0.005)
    thread.join()
    shared = time.perf_counter() - t0
    kept = turns / (rate * shared)

    block = bytes(1 << 20)
    thread = threading.Thread(target=work)
    thread.start()
    while thread.is_alive():
        hashlib.sha256(block).digest()            # C, without the GIL
    thread.join()
    ms = [1e3 * x / args.steps for x in (alone, done[0], done[1])]
    print(f"{args.count} spheres, {sim.world.contacts.count} contacts: step {ms[0]:.2f} ms "
          f"alone, {ms[2]:.2f} ms beside a thread hashing (a core busy, GIL free), "
          f"{ms[1]:.2f} ms beside a thread spinning in Python (a core busy and the GIL), "
          f"which kept {100 * kept:.0f}% of its speed")


if __name__ == "__main__":
    main()
