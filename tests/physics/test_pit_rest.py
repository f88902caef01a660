"""Issue 26, acceptance point 4: frictionless sphere pits (bench_peers' layout: r = 0.5 m, 1 kg,
e = 0.5, μ = 0, dt = 1/60) in a default ``World()`` come to rest — mean speed ≤ 0.002 m/s by
40 s, as the soft-sphere reference (benchmarks/reference_dem_pit.py: 0.0003–0.0014 m/s) — and
are asleep by 60 s. The 100- and 1000-sphere pits are run here to 60 s (about 4 s and 15 s);
the 10 000 pit (3600 steps at ~80 ms) is measured by benchmarks/bench_pit_rest.py.

Not met yet: the solver leaves a jitter in the pile's velocities (it does not move the pile:
over 0.5 s the spheres of the 100 pit go 5 mm/s on average while their velocities read 28 mm/s)
that keeps a sphere of every island above the sleep speed at every step, so the pits never
fall asleep. The ratchets below hold what is achieved (measured when particles began to sleep)
and the issue's targets are strict xfails, to flip when the solver brings the pile to rest.
"""

from __future__ import annotations

import sys
from functools import cache
from pathlib import Path

import numpy as np
import pytest

sys.path.insert(0, str(Path(__file__).resolve().parents[2] / "benchmarks"))
from bench_peers import DT, R, layout, measure, pointmass_pit

pytestmark = pytest.mark.slow


@cache
def _run(n: int) -> dict:
    """The pit to 60 s with World() defaults: mean speed at 10 s intervals, the last 10 s'
    largest mean speed, the particles awake at 60 s and the largest overlaps then."""
    pos, side = layout(n)
    world = pointmass_pit(pos, side)
    mean = {}
    awake = []
    for s in range(1, round(60.0 / DT) + 1):
        world.step(DT)
        if s % 600 == 0:
            mean[round(world.time)] = float(np.linalg.norm(world.particles.velocity,
                                                           axis=1).mean())
            awake.append(int(world.particles.awake.sum()))
    m = measure(world.particles.position, world.particles.velocity, side)
    return {"mean": mean, "awake": awake, "overlap": m["sphere overlap [mm]"],
            "wall": m["wall overlap [mm]"], "escapes": m["escapes"]}


# Measured (this commit, one seed): mean speed at 40 s 0.026 (N = 100) and 0.021 (N = 1000)
# m/s; awake at 60 s 99 of 100 and 997 of 1000; overlaps under 3 mm. The bounds leave room
# for the pile's chaos (one seed's figure moves with any change: compare seeds as a set).
RATCHET = {100: 0.06, 1000: 0.05}


@pytest.mark.parametrize("n", [100, 1000])
def test_the_pit_settles_with_no_sphere_lost_or_sunk(n):
    got = _run(n)
    assert got["escapes"] == 0
    assert got["overlap"] < 0.01 * 2 * R * 1e3 and got["wall"] < 0.01 * 2 * R * 1e3
    assert max(got["mean"][t] for t in (40, 50, 60)) < RATCHET[n]


@pytest.mark.xfail(strict=True, reason="issue 26 point 4: the solver's velocity jitter (mean "
                   "0.02-0.03 m/s, max 0.07-0.16) keeps the pit above the reference's "
                   "0.002 m/s and every island above the sleep speed")
@pytest.mark.parametrize("n", [100, 1000])
def test_the_pit_comes_to_rest_by_40_s_and_sleeps_by_60_s(n):
    got = _run(n)
    assert got["mean"][40] <= 0.002
    assert got["awake"][-1] == 0
