"""The Ray half of test_sweep_ray.py, run inside a network namespace that has only loopback,
with a cluster started there by ``ray start --head --node-ip-address=127.0.0.1``.

    python ray_session.py OUT SPRING_DEMO
"""

from __future__ import annotations

import subprocess
import sys
from pathlib import Path

from pointmass import sweep

ADDRESS = "127.0.0.1:6379"


def main(out: Path, spring_demo: str) -> None:
    # 1. The acceptance sweep: 12 ball pits, files sent back to the driver.
    sweep.run("ball_pit", out / "pit", fixed={"count": 300}, grid={"restitution": [0.2, 0.5,
              0.8]}, seeds=4, seconds=2.0, fps=30, clip=(160, 120), probes=["positions"],
              backend="ray", ray_address=ADDRESS, progress=False)
    # 2. A worker that dies (SIGKILL) on its run's first attempt: Ray runs it again. Written
    #    by the workers straight into the (here, shared) folder.
    sweep.run(spring_demo, out / "kill", fixed={"die_on_seed": 1}, seeds=4, seconds=0.5,
              probes=["positions"], backend="ray", ray_address=ADDRESS, shared_folder=True,
              max_retries=2, progress=False)
    # 3. What listens, while the cluster still runs.
    listening = subprocess.run(["ss", "-ltnH"], capture_output=True, text=True, check=True)
    addresses = subprocess.run(["ip", "-o", "addr"], capture_output=True, text=True, check=True)
    (out / "listening.txt").write_text(listening.stdout)
    (out / "addresses.txt").write_text(addresses.stdout)


if __name__ == "__main__":
    main(Path(sys.argv[1]), sys.argv[2])
