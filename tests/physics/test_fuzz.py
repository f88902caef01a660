"""Fuzz: random worlds with every generator, immovable particles, links and contacts, a few
hundred steps each. Invariants: no non-finite value without a raised error, immovable
particles never move, momentum kept with no external forces, e ≤ 1 never adds kinetic energy,
cables and rods within tolerance. A quick profile by default; ≥ 1000 worlds under ``slow``."""

from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

import pointmass as pm

DT = 1.0 / 60.0
QUICK = settings(max_examples=25, deadline=None, suppress_health_check=list(HealthCheck))
THOROUGH = settings(max_examples=1000, deadline=None, suppress_health_check=list(HealthCheck))


def _world(seed: int, *, forces: bool) -> tuple[pm.World, np.ndarray, list]:
    """A random world; with ``forces`` every force generator too (gravity, drag, springs,
    bungees, anchored ones, buoyancy, a fake spring, a custom force)."""
    rng = np.random.default_rng(seed)
    world = pm.World(gravity=(0, -9.81, 0) if forces else (0, 0, 0))
    n = int(rng.integers(2, 12))
    pinned = rng.random(n) < 0.2
    masses = np.where(pinned, math.inf, rng.uniform(0.2, 20.0, n))
    world.add_particles(rng.uniform(-1.5, 1.5, (n, 3)), rng.normal(0, 2, (n, 3)),
                        masses=masses, radii=rng.uniform(0.05, 0.4, n))
    world.particles.velocity[pinned] = 0.0
    e = float(rng.uniform(0, 1))
    world.add(pm.SphereCollisions(restitution=e))
    if forces or rng.random() < 0.5:  # without walls or forces momentum must be kept exactly
        world.add(pm.BoxContainer((-2, -2, -2), (2, 2, 2), restitution=float(rng.uniform(0, 1))))
    links = []
    p = world.particles.position
    for _ in range(int(rng.integers(0, n))):
        a, b = (int(v) for v in rng.choice(n, 2, replace=False))
        length = float(np.linalg.norm(p[a] - p[b])) + 1e-3
        if length < parts_radius(world, a, b):
            continue  # a link shorter than the spheres it joins fights their collision
        if rng.random() < 0.5:
            links.append(world.add(pm.Cable(a, b, length, restitution=float(rng.uniform(0, 1)))))
        else:
            links.append(world.add(pm.Rod(a, b, length)))
    if forces:
        idx = np.arange(n)
        # Stiffness well inside the stable range at 60 Hz for the lightest particle (0.2 kg).
        world.add(pm.Drag(k1=float(rng.uniform(0, 0.5)), k2=float(rng.uniform(0, 0.2))))
        world.add(pm.Spring(idx[:-1], idx[1:], spring_constant=float(rng.uniform(1, 50)),
                            rest_length=0.5, damping=float(rng.uniform(0, 0.5))))
        world.add(pm.Bungee(idx[:1], idx[-1:], spring_constant=10.0, rest_length=1.0))
        world.add(pm.AnchoredSpring(0, (0, 1, 0), spring_constant=5.0, rest_length=0.5))
        world.add(pm.AnchoredBungee(n - 1, (0, -1, 0), spring_constant=5.0, rest_length=1.0))
        world.add(pm.Buoyancy(max_depth=0.2, volume=0.001, water_height=0.0))
        world.add(pm.FakeSpring(0, (1, 1, 1), spring_constant=50.0, damping=1.0))
        world.add(pm.CustomForce(lambda q: (0.0, 0.5 * math.sin(q.position[0]), 0.0)))
    return world, pinned, links


def parts_radius(world: pm.World, a: int, b: int) -> float:
    return float(world.particles.radius[a] + world.particles.radius[b]) + 0.01


def _run(seed: int, *, forces: bool, steps: int = 200) -> None:
    world, pinned, links = _world(seed, forces=forces)
    parts = world.particles
    start = parts.position[pinned].copy()
    momentum = parts.momentum()
    energy = world.kinetic_energy()
    for _ in range(steps):
        try:
            world.step(DT)
        except FloatingPointError:
            # A blow-up is allowed only as a raised error, and the world is left finite.
            assert np.isfinite(parts.position).all() and np.isfinite(parts.velocity).all()
            return
        assert np.isfinite(parts.position).all() and np.isfinite(parts.velocity).all()
        assert np.array_equal(parts.position[pinned], start)
        if not forces:
            now = world.kinetic_energy()
            assert now <= energy * (1 + 1e-9) + 1e-12, (seed, energy, now)
            energy = now
    isolated = not forces and not pinned.any() and not any(
        isinstance(g, pm.BoxContainer) for g in world.contact_generators)
    if isolated:  # nothing outside the particles pushes: momentum is kept
        assert np.allclose(parts.momentum(), momentum, rtol=0, atol=1e-9)
    for link in links:
        lengths = link.current_lengths(parts)
        target = link.lengths_target
        if isinstance(link, pm.Rod):
            assert np.abs(lengths / target - 1.0).max() < 0.05, (seed, lengths, target)
        else:
            assert (lengths / target - 1.0).max() < 0.05, (seed, lengths, target)


@QUICK
@given(st.integers(0, 2**32 - 1))
def test_random_force_free_worlds_keep_every_invariant(seed):
    _run(seed, forces=False)


@QUICK
@given(st.integers(0, 2**32 - 1))
def test_random_worlds_with_every_generator_stay_finite_and_pinned(seed):
    _run(seed, forces=True)


@pytest.mark.slow
@THOROUGH
@given(st.integers(0, 2**32 - 1))
def test_1000_random_worlds_with_every_generator(seed):
    _run(seed, forces=seed % 2 == 0, steps=100)
