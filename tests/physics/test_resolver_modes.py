"""The solver's two modes: the default ("sequential") and the book's worst-first."""

from __future__ import annotations

import numpy as np
import pytest

import pointmass as pm

DT = 1.0 / 60.0


def _small_pile(mode: str) -> pm.World:
    rng = np.random.default_rng(11)
    world = pm.World(resolver=mode)
    world.add_particles(rng.uniform((-0.5, 0.2, -0.5), (0.5, 2.0, 0.5), (30, 3)), radii=0.15)
    world.add(pm.BoxContainer((-0.8, 0.0, -0.8), (0.8, 5.0, 0.8), restitution=0.3))
    world.add(pm.SphereCollisions(restitution=0.3))
    return world


@pytest.mark.parametrize(("mode", "slack"), [("worst-first", 0.1), ("sequential", 0.02)])
def test_both_modes_settle_a_small_pile_inside_the_box(mode, slack):
    """Settle 30 spheres in a box with either mode: inside, little overlap, losing energy.

    ``slack`` is the overlap allowed, as a fraction of the radius (the book's budget of
    2 × contacts single resolutions leaves more than the converged default).
    """
    world = _small_pile(mode)
    energy0 = world.kinetic_energy() + world.potential_energy()
    for _ in range(300):
        stats = world.step(DT)
        assert stats.mode == mode
    p = world.particles
    assert (p.position[:, 1] - p.radius > -slack * 0.15).all()
    assert (np.abs(p.position[:, [0, 2]]) + p.radius[:, None] < 0.8 + slack * 0.15).all()
    assert stats.max_penetration < slack * 0.15
    assert world.kinetic_energy() + world.potential_energy() < energy0


def test_the_default_rests_where_the_books_budget_does_not():
    """Rest the pile with the default (warm-started) far better than worst-first's budget."""
    speeds = {}
    for mode in ("worst-first", "sequential"):
        world = _small_pile(mode)
        for _ in range(600):
            world.step(DT)
        speeds[mode] = float(np.abs(world.particles.velocity).max())
    assert speeds["sequential"] < 0.05
    assert speeds["sequential"] < speeds["worst-first"]


class _Pegs(pm.ContactGenerator):
    """A custom generator (no contact keys): each particle rests on a peg at y = 0."""

    def generate(self, particles, contacts):
        below = np.flatnonzero(particles.position[:, 1] < 0.0)
        contacts.add(below, -1, (0.0, 1.0, 0.0), -particles.position[below, 1], 0.0)


def test_one_default_for_every_kind_of_contact_and_the_old_names_still_work():
    """No policy chooses a mode from the contact count or kind: unkeyed custom contacts,
    collisions and links all get the default; "auto" and "sweep" name it too."""
    world = pm.World()
    world.add_particles([(i, -0.01, 0.0) for i in range(4)])
    world.add(_Pegs())
    stats = world.step(DT)
    assert stats.contacts == 4 and stats.mode == "sequential"
    assert (world.particles.position[:, 1] >= -1e-6).all()
    for name in ("auto", "sweep"):
        assert pm.World(resolver=name).resolver == "sequential"
    with pytest.raises(ValueError, match="resolver must be 'sequential'"):
        pm.World(resolver="fastest")
