"""The same 12-run ball-pit sweep on the process pool and on a real Ray cluster gives the same
probes (bit for bit) and index rows, with decodable clips; a Ray worker killed mid-run is
retried.

The cluster talks over loopback only: ``ray start``, the driver (ray_session.py) and ``ray stop``
all run inside a new network namespace (``unshare --net``) whose only interface is ``lo``, and
the test checks that nothing there listens on another address.
"""

from __future__ import annotations

import json
import os
import shutil
import signal
import subprocess
import sys
import tempfile
from pathlib import Path

import numpy as np
import pytest
from sweep_helpers import mp4_frames, write_spring_demo

from pointmass import sweep

pytest.importorskip("ray", reason='the Ray tests need ray: pip install "pointmass[cluster]"')

HERE = Path(__file__).resolve().parent
PIT = dict(fixed={"count": 300}, grid={"restitution": [0.2, 0.5, 0.8]}, seeds=4, seconds=2.0,
           fps=30, clip=(160, 120), probes=["positions"])


def _kill_leftovers(marker: str) -> None:
    """SIGKILL the processes whose command line names this session's temp dir (ours only)."""
    for proc in Path("/proc").iterdir():
        if not proc.name.isdigit():
            continue
        try:
            cmdline = (proc / "cmdline").read_bytes()
        except OSError:
            continue
        if marker.encode() in cmdline:
            try:
                os.kill(int(proc.name), signal.SIGKILL)
            except ProcessLookupError:
                pass


@pytest.fixture(scope="module")
def ray_runs(tmp_path_factory):
    out = tmp_path_factory.mktemp("ray")
    demo = write_spring_demo(out)
    ray = Path(sys.executable).with_name("ray")
    temp = tempfile.mkdtemp(prefix="pmray-", dir="/tmp")  # short: Ray's sockets live in it
    script = (
        "set -u; ip link set lo up || exit 3; "
        f"{ray} start --head --node-ip-address=127.0.0.1 --port=6379 --num-cpus=2 "
        f"--include-dashboard=false --disable-usage-stats --temp-dir={temp} "
        f"> {out}/ray-start.log 2>&1 || exit 4; "
        f"{sys.executable} {HERE / 'ray_session.py'} {out} {demo}; rc=$?; "
        f"{ray} stop --force > {out}/ray-stop.log 2>&1; exit $rc")
    env = dict(os.environ, RAY_USAGE_STATS_ENABLED="0")
    try:
        result = subprocess.run(["unshare", "--net", "sh", "-c", script], capture_output=True,
                                text=True, timeout=400, env=env, check=False)
    finally:
        _kill_leftovers(temp)       # a timeout or a crash must not leave a cluster running
        shutil.rmtree(temp, ignore_errors=True)
    log = (out / "ray-start.log").read_text() if (out / "ray-start.log").exists() else ""
    assert result.returncode == 0, f"{result.stdout}\n{result.stderr}\n{log}"
    return out


def test_the_cluster_listened_on_loopback_only(ray_runs):
    listening = (ray_runs / "listening.txt").read_text().splitlines()
    assert listening, "ss saw no listening socket while the cluster ran"
    for line in listening:
        local = line.split()[3]
        host = local.rsplit(":", 1)[0].strip("[]")
        assert host in ("127.0.0.1", "::ffff:127.0.0.1", "::1"), line
    interfaces = {line.split()[1] for line in
                  (ray_runs / "addresses.txt").read_text().splitlines()}
    assert interfaces == {"lo"}


def test_pool_and_ray_give_identical_probes_rows_and_clips(ray_runs, tmp_path):
    result = sweep.run("ball_pit", tmp_path / "pit", **PIT, workers=2, progress=False)
    assert result.executed == 12 and result.failed == {}
    pool, ray = sweep.load(tmp_path / "pit"), sweep.load(ray_runs / "pit")

    def rows(data):
        return [{k: v for k, v in row.items() if k != "wall_seconds"} for row in data.rows]

    assert len(pool) == 12 and rows(pool) == rows(ray)
    for ours, theirs in zip(pool, ray):
        assert ours.ok and theirs.ok
        a, b = ours.probes(), theirs.probes()
        assert a.keys() == b.keys() == {"t", "positions"}
        assert a["positions"].shape == (60, 300, 3)
        for name in a:
            np.testing.assert_array_equal(a[name], b[name])  # bit for bit
        # The pit is poured during the 2 s: sphere 0 starts parked below the floor.
        assert a["positions"][0, 0, 1] < -10 < a["positions"][-1, 0, 1]
        for run in (ours, theirs):
            assert mp4_frames(run.clip) == (60, (160, 120))
        np.testing.assert_array_equal(ours.final()["particles.position"],
                                      theirs.final()["particles.position"])


def test_a_ray_worker_killed_mid_run_is_retried(ray_runs):
    killed = ray_runs / "killed-1"
    assert killed.exists()                      # the first attempt of seed 1 killed its worker
    data = sweep.load(ray_runs / "kill")
    assert [r.row["seed"] for r in data] == [0, 1, 2, 3]
    assert data.failed == []
    retried = data[1]
    assert retried.meta["pid"] != int(killed.read_text())   # done again by another process
    assert retried.probes()["positions"].shape == (15, 2, 3)
    assert [p.name for p in (ray_runs / "kill" / "runs").iterdir()
            if p.name.startswith(".")] == []
    assert json.loads((ray_runs / "kill" / "sweep.json").read_text())["seconds"] == 0.5
