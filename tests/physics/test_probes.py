"""Probes record the right samples at the right times, against analytic solutions, and survive
a round trip through .npz and .csv."""

from __future__ import annotations

import math

import numpy as np
import pytest

import pointmass as pm

DT = 1.0 / 60.0


def test_a_probe_on_free_fall_records_every_step_exactly():
    """Semi-implicit Euler from y0 = 10, v0 = 2 m/s: after n steps y = y0 + v0·n·h
    - g·h²·n(n+1)/2 and v = v0 - g·n·h (the discrete solution, to rounding)."""
    g = 9.81
    world = pm.World(gravity=(0, -g, 0))
    ball = world.add_particle((0, 10, 0), (0, 2, 0))
    probe = world.add_probe(pm.Probe(y=pm.probes.position(ball, axis=1),
                                     v=pm.probes.velocity(ball), ke=pm.probes.kinetic_energy))
    for _ in range(90):
        world.step(DT)
    n = np.arange(1, 91)
    assert len(probe) == 90
    assert probe.t == pytest.approx(n * DT, abs=1e-12)
    assert probe["y"] == pytest.approx(10 + 2 * n * DT - g * DT**2 * n * (n + 1) / 2, abs=1e-9)
    assert probe["v"].shape == (90, 3)
    assert probe["v"][:, 1] == pytest.approx(2 - g * n * DT, abs=1e-9)
    assert probe["ke"] == pytest.approx(0.5 * (2 - g * n * DT) ** 2, abs=1e-9)


def test_a_probe_on_a_spring_sees_its_period_and_its_length():
    """A 1 kg particle on an anchored spring of k = 4π² N/m (period 1 s): the recorded x
    crosses zero upward once a second, and the link length probe matches |x|."""
    world = pm.World(gravity=(0, 0, 0))
    p = world.add_particle((0.1, 0, 0))
    spring = world.add(pm.AnchoredSpring(p, (0, 0, 0), spring_constant=4 * math.pi**2,
                                         rest_length=0.0))
    probe = world.add_probe(pm.Probe(x=pm.probes.position(p, axis=0),
                                     length=pm.probes.link_length(spring)))
    for _ in range(600):
        world.step(1 / 600)
    x = probe["x"]
    up = np.flatnonzero((x[:-1] < 0) & (x[1:] >= 0))
    assert len(up) == 1 and probe.t[up[0]] == pytest.approx(0.75, abs=0.01)
    assert probe["length"] == pytest.approx(np.abs(x), abs=1e-12)


def test_npz_and_csv_round_trip(tmp_path):
    world = pm.World()
    p = world.add_particle((0, 1, 0), (1, 0, 0))
    probe = world.add_probe(pm.Probe(pos=pm.probes.position(p), contacts=pm.probes.contacts))
    world.add(pm.Ground())
    for _ in range(30):
        world.step(DT)
    for path in (probe.to_npz(tmp_path / "p.npz"), probe.to_csv(tmp_path / "p.csv")):
        data = pm.Probe.load(path)
        assert np.array_equal(data["t"], probe.t)
        assert np.array_equal(data["pos"], probe["pos"])
        assert np.array_equal(data["contacts"], probe["contacts"])


def test_bad_probes_are_refused():
    with pytest.raises(ValueError, match="at least one quantity"):
        pm.Probe()
    with pytest.raises(TypeError, match="quantity 'y' must be a function"):
        pm.Probe(y=3.0)
    with pytest.raises(TypeError, match="add_probe takes a Probe"):
        pm.World().add_probe(object())
