"""Millington's fake stiff spring: stable, finite, and on the analytic damped oscillator."""

from __future__ import annotations

import math

import numpy as np
import pytest

import pointmass as pm

DT = 1.0 / 60.0


def _analytic(k: float, d: float, x0: float, t: np.ndarray) -> np.ndarray:
    """x(t) of x'' = -k·x - d·x' from rest at x0 (under-, critically or over-damped)."""
    disc = d * d - 4 * k
    if disc < 0:
        w = math.sqrt(-disc) / 2
        return np.exp(-d * t / 2) * x0 * (np.cos(w * t) + d / (2 * w) * np.sin(w * t))
    if disc == 0:
        return np.exp(-d * t / 2) * x0 * (1 + d * t / 2)
    r1, r2 = (-d + math.sqrt(disc)) / 2, (-d - math.sqrt(disc)) / 2
    c1 = x0 * -r2 / (r1 - r2)
    return c1 * np.exp(r1 * t) + (x0 - c1) * np.exp(r2 * t)


@pytest.mark.parametrize(("k", "d", "tolerance"), [(30.0, 1.0, 1e-12), (4.0, 4.0, 1e-12),
                                                   (1.0, 10.0, 1e-12), (400.0, 90.0, 1e-12)],
                         ids=["under", "critical", "over", "stiff-over"])
def test_fake_spring_tracks_analytic_damped_oscillator(k, d, tolerance):
    """Follow the exact damped oscillator to 1e-12 m while nothing else acts, never NaN."""
    # Sleep off: the curve to its end. With sleep on, the over-damped particle, once within
    # 2.5 cm of the anchor and slower than 0.05 m/s for 0.5 s, sleeps there as a body would
    # (measured 0.54 mm from the exact curve after 3 s, stiff-over).
    world = pm.World(gravity=(0, 0, 0), sleep=False)
    i = world.add_particle(position=(0, 1.0, 0), mass=3.0)
    world.add(pm.FakeSpring(i, anchor=(0, 0, 0), spring_constant=k, damping=d))
    steps = 180
    y = np.empty(steps)
    for n in range(steps):
        world.step(DT)
        y[n] = world.particles.position[i, 1]
    assert np.isfinite(world.particles.position).all()
    assert np.isfinite(world.particles.velocity).all()
    exact = _analytic(k, d, 1.0, DT * np.arange(1, steps + 1))
    assert np.abs(y - exact).max() < tolerance


def test_over_damped_fake_spring_has_no_nan_force():
    """Give a finite force when damping² > 4k (Cyclone takes sqrt of a negative: NaN)."""
    world = pm.World(gravity=(0, 0, 0))
    i = world.add_particle(position=(0.3, -0.2, 0.5), velocity=(1, 2, 3))
    spring = world.add(pm.FakeSpring(i, anchor=(0, 0, 0), spring_constant=1.0, damping=50.0))
    world.particles.force[:] = 0
    spring.apply(world.particles, DT)
    force = world.particles.force[i]
    assert np.isfinite(force).all()
    # It pulls toward the anchor and against the velocity.
    assert force @ np.array([0.3, -0.2, 0.5]) < 0 or force @ np.array([1, 2, 3]) < 0
