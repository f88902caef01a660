"""How pointmass's parallel paths scale with cores: free particles and the ball pit's solver.

    .venv/bin/python benchmarks/bench_threads.py [--threads 1 2 4 8 16] [--pit 10000] [--quick]

For each thread count (``numba.set_num_threads``): 100 000 free particles under gravity and
drag (pointmass's World against bench_limits' fused loop, both on the same threads), and the
ball pit of bench_peers.py on the solver's block-parallel path
(``SolverSettings.parallel_min_contacts`` = 0) against its default serial path in the same
run. The pit's final positions are hashed: the parallel path must give the same bits for
every thread count (it orders rows by the contacts alone). Written to decide where the
parallel solver pays; on the 2-core development machine it never did (see RESULTS.md), so run
this where there are more cores.
"""

from __future__ import annotations

import argparse
import hashlib
import sys
import time
from pathlib import Path

import numba

sys.path.insert(0, str(Path(__file__).parent))
import bench_limits
import bench_peers

import pointmass as pm


def pit(n: int, parallel: bool) -> tuple[float, dict, str]:
    """(body-steps/s, the pile after 600 steps, a hash of its final positions)."""
    settings = pm.SolverSettings(parallel_min_contacts=0) if parallel else None
    seconds, pos, vel = bench_peers.run_pointmass(n, settings)
    _, side = bench_peers.layout(n)
    digest = hashlib.sha256(pos.tobytes() + vel.tobytes()).hexdigest()[:12]
    return n * bench_peers.STEPS / seconds, bench_peers.measure(pos, vel, side), digest


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    most = numba.config.NUMBA_NUM_THREADS
    parser.add_argument("--threads", type=int, nargs="*",
                        default=[t for t in (1, 2, 4, 8, 16) if t <= most])
    parser.add_argument("--pit", type=int, default=10_000, help="the pit's N")
    parser.add_argument("--quick", action="store_true", help="fewer steps; pit N = 1000")
    args = parser.parse_args()
    n_pit = 1000 if args.quick else args.pit
    steps, repeats = (20, 3) if args.quick else (100, 5)
    print(f"cores numba sees: {most}; threads measured: {args.threads}")
    bench_peers.run_pointmass(100)  # compile outside the timing
    pit(200, parallel=True)
    start = time.perf_counter()
    serial, serial_pile, _ = pit(n_pit, parallel=False)
    print(f"pit N = {n_pit}, serial path: {serial:.3g} body-steps/s, mean |v| "
          f"{serial_pile['mean |v|']:.3f} m/s, overlap {serial_pile['sphere overlap [mm]']:.1f} "
          f"mm  ({time.perf_counter() - start:.0f} s)")
    print(f"{'threads':>7} {'free':>10} {'fused':>10} {'ratio':>6} | {'pit par.':>10} "
          f"{'× serial':>8} {'mean|v|':>8} {'overlap':>8} {'hash':>13}")
    hashes = set()
    for threads in args.threads:
        numba.set_num_threads(threads)
        free, fused = bench_limits.bench_free(100_000, steps, repeats)
        rate, pile, digest = pit(n_pit, parallel=True)
        hashes.add(digest)
        print(f"{threads:7d} {free:10.3g} {fused:10.3g} {free / fused:6.2f} | {rate:10.3g} "
              f"{rate / serial:8.2f} {pile['mean |v|']:8.3f} "
              f"{pile['sphere overlap [mm]']:7.1f}mm {digest:>13}", flush=True)
    print("parallel pit bit-identical across thread counts:", len(hashes) == 1)


if __name__ == "__main__":
    main()
