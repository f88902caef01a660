"""Sweep throughput: the process pool and a 2-CPU Ray cluster against one worker, same run.

    .venv/bin/python benchmarks/bench_sweep.py [--runs 200] [--workers 2]

The sweep of issue 28's acceptance: ball_pit with N = 300 for 2 s, a 160×120 clip and the
positions probe per run; ``--runs`` of them (10 restitution values × seeds). Three backends,
each into a fresh folder: the pool with one worker (the baseline), the pool with ``--workers``
processes, and Ray on a local cluster of ``--workers`` CPUs started here before its timing.
Per-run overhead is what a backend costs beyond the runs themselves:
wall × workers / runs − the mean run's own wall time (measured inside the worker: build, steps,
frames, encoding, writing) — worker start-up, scheduling, sending files, the index.

Ray's cluster runs in a network namespace with only loopback (the script re-runs itself under
``unshare --net``, which needs root), so nothing listens on the machine's interfaces; pass
``--no-ray`` to measure the pool alone. A shared machine moves these figures: read ``uptime``'s
load (printed before and after) before trusting a ratio.
"""

from __future__ import annotations

import argparse
import json
import os
import shutil
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

from pointmass import sweep

RESTITUTIONS = [round(0.05 + 0.1 * k, 2) for k in range(10)]


def the_sweep(runs: int) -> sweep.Sweep:
    if runs % len(RESTITUTIONS):
        raise SystemExit(f"--runs must be a multiple of {len(RESTITUTIONS)}")
    return sweep.Sweep("ball_pit", fixed={"count": 300},
                       grid={"restitution": RESTITUTIONS}, seeds=runs // len(RESTITUTIONS),
                       seconds=2.0, fps=30, clip=(160, 120), probes=["positions"])


def measure(name: str, spec: sweep.Sweep, folder: Path, workers: int, **options) -> dict:
    started = time.perf_counter()
    result = sweep.run(spec, folder, workers=workers, progress=False, **options)
    wall = time.perf_counter() - started
    rows = sweep.load(folder).rows
    run_mean = statistics.fmean(r["wall_seconds"] for r in rows)
    overhead = wall * workers / len(rows) - run_mean
    out = {"backend": name, "workers": workers, "runs": len(rows),
           "failed": len(result.failed), "wall_s": wall, "runs_per_s": len(rows) / wall,
           "mean_run_s": run_mean, "overhead_per_run_s": overhead}
    print(f"{name:<22} {workers} worker(s): {wall:7.1f} s, {out['runs_per_s']:.2f} runs/s, "
          f"mean run {run_mean:.3f} s, overhead {overhead * 1000:6.0f} ms/run, "
          f"{out['failed']} failed", flush=True)
    return out


def load_average() -> str:
    return " ".join(Path("/proc/loadavg").read_text().split()[:3])


def start_ray(temp: str, cpus: int) -> Path:
    ray = Path(sys.executable).with_name("ray")
    subprocess.run([str(ray), "start", "--head", "--node-ip-address=127.0.0.1", "--port=6379",
                    f"--num-cpus={cpus}", "--include-dashboard=false", "--disable-usage-stats",
                    f"--temp-dir={temp}"], check=True, capture_output=True)
    return ray


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--runs", type=int, default=200)
    parser.add_argument("--workers", type=int, default=2)
    parser.add_argument("--no-ray", action="store_true")
    parser.add_argument("--json", type=Path, help="also write the figures here")
    parser.add_argument("--in-namespace", action="store_true", help=argparse.SUPPRESS)
    args = parser.parse_args()
    if not args.no_ray and not args.in_namespace:
        # Re-run inside a loopback-only network namespace (see the module docstring).
        inner = [sys.executable, *sys.argv, "--in-namespace"]
        command = "ip link set lo up && exec " + " ".join(f"'{a}'" for a in inner)
        sys.exit(subprocess.call(["unshare", "--net", "sh", "-c", command]))
    spec = the_sweep(args.runs)
    print(f"{args.runs} runs of ball_pit N=300, 2 s, 160x120 clips + positions; "
          f"cores {os.cpu_count()}; load average before {load_average()}", flush=True)
    root = Path(tempfile.mkdtemp(prefix="bench-sweep-"))
    figures = []
    try:
        # Compile (numba's cache) and warm the page cache outside every timing.
        sweep.run(spec.__class__(**{**spec.__dict__, "seeds": [999], "grid": {
            "restitution": [0.5]}}), root / "warm", workers=1, progress=False)
        figures.append(measure("pool (baseline)", spec, root / "one", 1))
        figures.append(measure("pool", spec, root / "pool", args.workers))
        if not args.no_ray:
            temp = tempfile.mkdtemp(prefix="pmray-", dir="/tmp")
            ray = start_ray(temp, args.workers)
            try:
                figures.append(measure("ray", spec, root / "ray", args.workers,
                                       backend="ray", ray_address="127.0.0.1:6379"))
            finally:
                subprocess.run([str(ray), "stop", "--force"], capture_output=True, check=False)
                shutil.rmtree(temp, ignore_errors=True)
    finally:
        shutil.rmtree(root, ignore_errors=True)
    base = figures[0]["wall_s"]
    for f in figures[1:]:
        f["speedup"] = base / f["wall_s"]
        print(f"{f['backend']} with {f['workers']} workers: {f['speedup']:.2f}x one worker")
    print(f"load average after {load_average()}")
    if args.json:
        args.json.write_text(json.dumps(figures, indent=2))


if __name__ == "__main__":
    main()
