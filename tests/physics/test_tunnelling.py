"""Fast spheres do not pass through each other: pairs are found by how far they may travel in
the step (speculative contacts sized by speed), with the normal at the moment they would touch,
so a pair that passes by is left alone."""

from __future__ import annotations

import pytest

import pointmass as pm

DT = 1.0 / 60.0


@pytest.mark.parametrize("speed", [100.0, 300.0, 1000.0])
def test_fast_spheres_bounce_instead_of_passing_through(speed):
    """Two r = 0.1 spheres closing at ``speed`` m/s (they cover 17 to 167 times their size
    in a step) bounce elastically (e = 1): they swap velocities, never cross."""
    gap = 3 * speed * DT + 0.37
    world = pm.World(gravity=(0, 0, 0))
    world.add_particles([(0, 0, 0), (gap, 0, 0)], [(speed / 2, 0, 0), (-speed / 2, 0, 0)],
                        radii=0.1)
    world.add(pm.SphereCollisions(restitution=1.0))
    for _ in range(30):
        world.step(DT)
        p = world.particles.position
        assert p[1, 0] - p[0, 0] >= 0.2 - 1e-9  # never crossed, never overlapping
    assert world.particles.velocity[:, 0].tolist() == pytest.approx([-speed / 2, speed / 2])


@pytest.mark.parametrize("offset", [0.25, 0.5, 1.0])
def test_fast_spheres_that_pass_by_are_not_deflected(offset):
    """The same pair 0.25 to 1 m apart sideways (touching needs < 0.2 m) flies on untouched:
    no ghost contact from the speculative reach."""
    speed = 300.0
    world = pm.World(gravity=(0, 0, 0))
    world.add_particles([(0, 0, 0), (3 * speed * DT, offset, 0)],
                        [(speed / 2, 0, 0), (-speed / 2, 0, 0)], radii=0.1)
    world.add(pm.SphereCollisions(restitution=1.0))
    for _ in range(30):
        world.step(DT)
    assert world.particles.velocity.tolist() == [[speed / 2, 0, 0], [-speed / 2, 0, 0]]


def test_a_ballistic_round_does_not_pass_through_a_sphere():
    """A 2 g round of r = 0.05 at 500 m/s meets a resting 10 kg sphere of r = 0.5: it stops
    and bounces off (e = 0.3), and the target takes the momentum."""
    world = pm.World(gravity=(0, 0, 0))
    target = world.add_particle((20, 0, 0), mass=10.0, radius=0.5)
    bullet = world.add_particle((0, 0.2, 0), (500, 0, 0), mass=0.002, radius=0.05)
    world.add(pm.SphereCollisions(restitution=0.3))
    for _ in range(20):
        world.step(DT)
        p = world.particles.position
        assert p[bullet, 0] < p[target, 0]
    v = world.particles.velocity
    assert v[bullet, 0] < 0 < v[target, 0]
    assert world.particles.momentum() == pytest.approx([1.0, 0, 0], abs=1e-9)
