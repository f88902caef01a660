"""One test per Cyclone bug listed in DESIGN.md: pointmass must not repeat it."""

from __future__ import annotations

import math

import numpy as np
import pytest

import pointmass as pm
from pointmass.contacts import ContactBuffer
from pointmass.resolver import resolve_contacts

DT = 1.0 / 60.0


def _forces(world: pm.World) -> np.ndarray:
    world.particles.force[:] = 0.0
    for generator in world.forces:
        generator.apply(world.particles, DT)
    return world.particles.force.copy()


def test_compressed_spring_pushes_its_ends_apart():
    """Push a compressed spring's ends apart (Cyclone's abs(extension) pulls them together)."""
    world = pm.World(gravity=(0, 0, 0))
    a = world.add_particle(position=(0, 0, 0))
    b = world.add_particle(position=(1, 0, 0))
    world.add(pm.Spring(a, b, spring_constant=10.0, rest_length=3.0))
    force = _forces(world)
    assert np.allclose(force[a], [-20.0, 0, 0]) and np.allclose(force[b], [20.0, 0, 0])
    # Stretched, it pulls: the sign follows the extension.
    world.particles.position[b] = (5, 0, 0)
    force = _forces(world)
    assert np.allclose(force[a], [20.0, 0, 0]) and np.allclose(force[b], [-20.0, 0, 0])


def test_anchored_spring_pushes_when_compressed():
    """Push a particle away from the anchor when the anchored spring is compressed."""
    world = pm.World(gravity=(0, 0, 0))
    i = world.add_particle(position=(0, 1, 0))
    world.add(pm.AnchoredSpring(i, anchor=(0, 0, 0), spring_constant=2.0, rest_length=3.0))
    assert np.allclose(_forces(world)[i], [0, 4.0, 0])


def test_bungee_pulls_when_stretched_and_is_slack_when_compressed():
    """Pull a stretched bungee's ends together (Cyclone pushes) and do nothing when slack."""
    world = pm.World(gravity=(0, 0, 0))
    a = world.add_particle(position=(0, 0, 0))
    b = world.add_particle(position=(0, 4, 0))
    world.add(pm.Bungee(a, b, spring_constant=3.0, rest_length=1.0))
    force = _forces(world)
    assert np.allclose(force[a], [0, 9.0, 0]) and np.allclose(force[b], [0, -9.0, 0])
    world.particles.position[b] = (0, 0.5, 0)
    assert np.array_equal(_forces(world), np.zeros((2, 3)))


def test_anchored_bungee_is_slack_when_compressed():
    """Leave a particle alone inside an anchored bungee's rest length, pull it outside."""
    world = pm.World(gravity=(0, 0, 0))
    i = world.add_particle(position=(0.5, 0, 0))
    world.add(pm.AnchoredBungee(i, anchor=(0, 0, 0), spring_constant=1.0, rest_length=1.0))
    assert np.array_equal(_forces(world)[i], [0, 0, 0])
    world.particles.position[i] = (3, 0, 0)
    assert np.allclose(_forces(world)[i], [-2.0, 0, 0])


@pytest.mark.parametrize(("height", "fraction"), [(0.0, 0.5), (-0.25, 0.75), (0.25, 0.25),
                                                  (-2.0, 1.0), (2.0, 0.0)])
def test_buoyancy_lifts_by_the_submerged_fraction(height, fraction):
    """Lift a half-submerged object by +ρVg/2 (Cyclone pushes it down and forgets g)."""
    world = pm.World(gravity=(0, 0, 0))
    i = world.add_particle(position=(0, height, 0))
    world.add(pm.Buoyancy(max_depth=0.5, volume=0.1, water_height=0.0, liquid_density=1000.0,
                          gravity=9.81))
    force = _forces(world)[i]
    assert force[1] == pytest.approx(1000.0 * 0.1 * 9.81 * fraction, abs=1e-9)
    assert force[1] >= 0.0 and force[0] == force[2] == 0.0


def test_resolver_leaves_no_particle_embedded_after_an_early_return():
    """Clear per-contact movement on early returns: a sphere pushed out of the ground stays out.

    Contact 0 (sphere–sphere) is closing but not penetrating, so the book's penetration step
    returns early; contact 1 (the same sphere in the ground by 0.2) then moves the sphere.
    Cyclone re-applied the stale movement of the previous contact to the shared particle's
    other contacts, leaving it embedded (0.2 turned into -0.3).
    """
    world = pm.World(gravity=(0, 0, 0))
    low = world.add_particle(position=(0, 0.3, 0), velocity=(0, -1, 0), radius=0.5)
    high = world.add_particle(position=(0, 1.3, 0), velocity=(0, -3, 0), radius=0.5)
    for mode in ("worst-first", "sweep"):
        p = world.particles
        p.position[:] = [(0, 0.3, 0), (0, 1.3, 0)]
        p.velocity[:] = [(0, -1, 0), (0, -3, 0)]
        contacts = ContactBuffer()
        contacts.add(high, low, (0, 1, 0), 0.0, 0.0)   # touching, closing at 2 m/s
        contacts.add(low, -1, (0, 1, 0), 0.2, 0.0)     # low is 0.2 into the ground
        resolve_contacts(p, contacts, DT, mode=mode, iterations=200)
        ground_gap = p.position[low, 1] - 0.5
        pair_gap = p.position[high, 1] - p.position[low, 1] - 1.0
        assert ground_gap >= -2e-6, mode  # the sweep stops once within tolerance·dt
        assert pair_gap >= -2e-6, mode
        # The reported remaining penetrations agree with the geometry.
        assert contacts.penetration[1] == pytest.approx(-ground_gap, abs=1e-12)
        assert contacts.penetration[0] == pytest.approx(-pair_gap, abs=1e-12)


def test_a_rod_is_held_both_ways_without_comparing_floats():
    """Cyclone compares rod lengths with float == (so a contact appears or not by rounding).
    A rod here always reports one bilateral contact with its signed error as depth: at its
    exact length that is 0 and the solver moves nothing; a micron long, the depth is 1e-6,
    a micron short -1e-6, and solving restores the length either way."""
    world = pm.World(gravity=(0, 0, 0))
    a = world.add_particle(position=(0, 0, 0))
    b = world.add_particle(position=(1, 0, 0))
    rod = world.add(pm.Rod(a, b, length=1.0))
    contacts = ContactBuffer()
    rod.generate(world.particles, contacts)
    assert contacts.count == 1 and contacts.bilateral.all() and not contacts.penetration.any()
    world.step(DT)
    assert world.particles.position[b].tolist() == [1.0, 0.0, 0.0]
    for error in (1e-6, -1e-6):
        world.particles.position[b] = world.particles.position[a] + (1 + error, 0, 0)
        contacts.clear()
        rod.generate(world.particles, contacts)
        assert contacts.penetration.tolist() == pytest.approx([error], rel=1e-6)
        world.step(DT)
        length = np.linalg.norm(world.particles.position[b] - world.particles.position[a])
        assert length == pytest.approx(1.0, abs=1e-12)


def test_pinned_particle_has_no_finite_mass_and_gets_no_gravity():
    """Report has_finite_mass False for pinned particles and give them no gravity force."""
    world = pm.World(gravity=(0, 0, 0))
    free = world.add_particle(mass=2.0)
    pinned = world.add_particle(mass=math.inf)
    pinned_later = world.add_particle(mass=1.0)
    world.particles.pin(pinned_later)
    world.add(pm.Gravity((0, -9.81, 0)))
    assert world.particles[free].has_finite_mass
    assert not world.particles[pinned].has_finite_mass
    assert not world.particles[pinned_later].has_finite_mass
    force = _forces(world)
    assert np.allclose(force[free], [0, -19.62, 0])
    assert not force[[pinned, pinned_later]].any()
    for _ in range(10):
        world.step(DT)
    assert np.array_equal(world.particles.position[[pinned, pinned_later]], np.zeros((2, 3)))
