"""Issue 26, acceptance point 4: frictionless sphere pits (bench_peers' layout: r = 0.5 m, 1 kg,
e = 0.5, μ = 0, dt = 1/60) in a default ``World()`` come to rest — mean speed ≤ 0.002 m/s by
40 s, as the soft-sphere reference (benchmarks/reference_dem_pit.py: 0.0003–0.0014 m/s) — and
are asleep by 60 s, with no sphere lost and overlaps under 1 % of the diameter.

They do since the projection leaves a resting contact's last ``SolverSettings.projection_slop``
(0.5 mm) of penetration (Box2D's linear slop, ``stages.slop_depths``): before, every step's velocity
passes left µm of sinking somewhere in the pile, the projection pushed it out, the contacts
moved, and the warm start never caught up (a jitter of 0.02–0.03 m/s for ever: measured at
40 s 0.026 m/s with N = 100, 0.021 with N = 1000, and never asleep).

The 10 000 pit does not yet (measured with benchmarks/bench_pit_rest.py, sleep on, from the
pit saved at 30 s): what moves is the velocity passes' unconverged remainder, not the pile's
own settling. At 30 s the median sphere creeps at 5 mm/s, mostly sideways (rms 7 mm/s
horizontal, 3 mm/s vertical), in every layer (the floor layer 4.9 mm/s); the creep opens holes
that spheres drop into at 0.5-0.9 m/s (~100 spheres over 5 cm/s at any time: the bursts, which
keep the pit's one island awake). From that same state, 20 / 40 / 200 velocity passes a step
instead of 10 give 0.0062 / 0.0082 / 0.0021 m/s at 40 s, and with 200 the whole pit sleeps at
43 s and stays asleep to 60 s: a converged solve meets point 4 at N = 10 000. A pass on the
30 s pile lowers Σ|Δv| by ~1.5 % (33 -> 3.4 m/s over 200 passes): Gauss–Seidel's slowest modes
span the pit, so the passes needed grow with its width (3 000 spheres, 31 m: asleep by 30 s;
5 000, 40 m: 0.0137 m/s at 40 s, asleep by 60 s; 10 000, 55 m: awake at 60 s). Tried from the
30 s state at the same cost, none helps: the rows swept backward every other pass or step or
sorted by height, ω 1.0 / 1.8, a nonsmooth conjugate-gradient step between passes, conjugate
gradients on the pressed rows, 15 projection passes, a 2 mm slop, no impact stage.
"""

from __future__ import annotations

import sys
from functools import cache
from pathlib import Path

import numpy as np
import pytest

sys.path.insert(0, str(Path(__file__).resolve().parents[2] / "benchmarks"))
from bench_peers import DT, R, layout, measure, pointmass_pit


@cache
def _run(n: int) -> dict:
    """The pit to 60 s with World() defaults: mean speed at 10 s intervals, the particles
    awake then, and the largest overlaps and escapes at 60 s."""
    pos, side = layout(n)
    world = pointmass_pit(pos, side)
    mean = {}
    awake = {}
    for s in range(1, round(60.0 / DT) + 1):
        world.step(DT)
        if s % 600 == 0:
            mean[round(world.time)] = float(np.linalg.norm(world.particles.velocity,
                                                           axis=1).mean())
            awake[round(world.time)] = int(world.particles.awake.sum())
    m = measure(world.particles.position, world.particles.velocity, side)
    return {"mean": mean, "awake": awake, "overlap": m["sphere overlap [mm]"],
            "wall": m["wall overlap [mm]"], "escapes": m["escapes"]}


SIZES = [100, pytest.param(1000, marks=pytest.mark.slow),
         pytest.param(10_000, marks=pytest.mark.slow)]


@pytest.mark.parametrize("n", [100, pytest.param(1000, marks=pytest.mark.slow)])
def test_the_pit_comes_to_rest_by_40_s_and_sleeps_by_60_s(n):
    # Measured (this commit, the layout's seed 0): asleep at 10 s (N = 100), 30 s (N = 1000).
    got = _run(n)
    assert got["mean"][40] <= 0.002, got["mean"]
    assert got["awake"][60] == 0, got["awake"]


@pytest.mark.slow
def test_the_10_000_pit_settles_as_the_soft_sphere_reference_does():
    # The soft-sphere reference (RESULTS.md, seed 0) is still at 0.015 m/s at 40 s, but a
    # converged rigid solve is at rest by then (the module docstring). Measured on main
    # (stop 36, sleep on): mean |v| 0.045,
    # 0.028, 0.0082, 0.0114, 0.0185 at 10, 20, 30, 40, 60 s, 9 983 awake at 60 s, the
    # fastest sphere at 0.5–0.9 m/s throughout (one island: a sphere still moving keeps the
    # pile awake; the mean is not monotone); the same on sparticle's tip with
    # bench_pit_rest.py (an earlier form of the slop gave 0.0085 / 0.0055 at 40 / 60 s);
    # before the slop 0.014 at 40 s. Where the motion comes from: the module docstring.
    # Ratchets at what main measures (a chaotic pile: any change to the particle stages moves
    # these figures, hence the room); the target is the strict xfail below.
    got = _run(10_000)
    assert got["mean"][40] <= 0.015 and got["mean"][60] <= 0.025, got["mean"]


@pytest.mark.slow
@pytest.mark.xfail(strict=True, reason="issue 26 point 4 at N = 10 000: 10 Gauss–Seidel passes "
                   "a step leave the 55 m pile creeping (0.0114 m/s at 40 s) and awake at 60 s; "
                   "200 passes bring it to 0.0021 m/s at 40 s and asleep at 43 s (docstring)")
def test_the_10_000_pit_comes_to_rest_by_40_s_and_sleeps_by_60_s():
    got = _run(10_000)
    assert got["mean"][40] <= 0.002
    assert got["awake"][60] == 0


@pytest.mark.parametrize("n", SIZES)
def test_the_pit_loses_no_sphere_and_overlaps_under_1_percent(n):
    got = _run(n)
    assert got["escapes"] == 0
    # the slop (0.5 mm) is what is left; 1 % of the diameter is 10 mm
    assert got["overlap"] < 0.01 * 2 * R * 1e3 and got["wall"] < 0.01 * 2 * R * 1e3, got
