"""Invariants over random small scenes (hypothesis)."""

from __future__ import annotations

import math

import numpy as np
from hypothesis import given, settings
from hypothesis import strategies as st

import pointmass as pm
from pointmass.contacts import ContactBuffer
from pointmass.resolver import resolve_contacts

DT = 1.0 / 60.0
SETTINGS = settings(max_examples=40, deadline=None)

coordinate = st.floats(-1.0, 1.0, allow_nan=False)
vector = st.tuples(coordinate, coordinate, coordinate)
speed = st.tuples(*[st.floats(-5.0, 5.0, allow_nan=False)] * 3)


@st.composite
def scenes(draw, *, pinned: bool = True, min_size: int = 2):
    """Particles: (positions (N,3), velocities (N,3), masses (N,), radii (N,), pinned (N,))."""
    n = draw(st.integers(min_size, 8))
    positions = np.array(draw(st.lists(vector, min_size=n, max_size=n)))
    positions[:, 1] += 1.0  # above the ground
    velocities = np.array(draw(st.lists(speed, min_size=n, max_size=n)))
    masses = np.array(draw(st.lists(st.floats(0.1, 10.0), min_size=n, max_size=n)))
    radii = np.array(draw(st.lists(st.floats(0.05, 0.5), min_size=n, max_size=n)))
    fixed = np.array(draw(st.lists(st.booleans(), min_size=n, max_size=n))) if pinned \
        else np.zeros(n, bool)
    return positions, velocities, masses, radii, fixed


def _world(scene, *, springs: bool, ground: bool, e: float = 0.5) -> pm.World:
    positions, velocities, masses, radii, fixed = scene
    world = pm.World()
    world.add_particles(positions, velocities, masses=np.where(fixed, math.inf, masses),
                        radii=radii)
    for i in np.flatnonzero(fixed):
        world.particles.pin(int(i))
    n = len(masses)
    if springs:
        world.add(pm.Spring(np.arange(n - 1), np.arange(1, n), spring_constant=20.0,
                            rest_length=0.5))
    if ground:
        world.add(pm.Ground(restitution=e))
    world.add(pm.SphereCollisions(restitution=e))
    return world


@SETTINGS
@given(scenes())
def test_state_stays_finite_and_pinned_particles_stay(scene):
    """Keep every state finite and every pinned particle exactly where it was."""
    world = _world(scene, springs=True, ground=True)
    fixed = scene[4]
    start = world.particles.position[fixed].copy()
    for _ in range(60):
        world.step(DT)
        assert np.isfinite(world.particles.position).all()
        assert np.isfinite(world.particles.velocity).all()
        assert np.array_equal(world.particles.position[fixed], start)
        assert not world.particles.velocity[fixed].any()


@SETTINGS
@given(scenes(pinned=False), st.sampled_from(["worst-first", "sweep"]),
       st.floats(0.0, 1.0))
def test_resolver_alone_conserves_momentum(scene, mode, e):
    """Conserve total momentum when the resolver alone resolves sphere contacts."""
    world = _world(scene, springs=False, ground=False, e=e)
    contacts = ContactBuffer()
    for generator in world.contact_generators:
        generator.generate(world.particles, contacts)
    before = world.particles.momentum()
    resolve_contacts(world.particles, contacts, DT, mode=mode, restitution_threshold=0.0)
    scale = 1.0 + np.abs(scene[1]).max() * scene[2].sum()
    assert np.allclose(world.particles.momentum(), before, rtol=0, atol=1e-12 * scale)


@SETTINGS
@given(vector, vector, speed, speed, st.floats(0.1, 10.0), st.floats(0.1, 10.0),
       st.floats(0.0, 1.0), st.sampled_from(["worst-first", "sweep"]))
def test_single_resolved_contact_is_not_closing(p1, p2, v1, v2, m1, m2, e, mode):
    """Leave a resolved sphere pair separating (or at rest relative to each other), not closing."""
    world = pm.World(gravity=(0, 0, 0))
    a = world.add_particle(p1, v1, mass=m1, radius=2.0)
    b = world.add_particle(np.add(p2, 1e-3), v2, mass=m2, radius=2.0)
    contacts = ContactBuffer()
    pm.SphereCollisions(restitution=e).generate(world.particles, contacts)
    assert contacts.count == 1  # centres are at most √12 apart, radii sum 4: they overlap
    resolve_contacts(world.particles, contacts, DT, mode=mode, restitution_threshold=0.0)
    p, v = world.particles.position, world.particles.velocity
    first, second = contacts.a[0], contacts.b[0]  # either order: the normal points second→first
    assert {first, second} == {a, b}
    separating = (v[first] - v[second]) @ contacts.normal[0]
    assert separating >= -1e-9
    # And no longer overlapping.
    assert np.linalg.norm(p[a] - p[b]) >= 4.0 - 1e-5
