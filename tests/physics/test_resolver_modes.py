"""The two resolver modes, and how "auto" chooses between them."""

from __future__ import annotations

import numpy as np
import pytest

import pointmass as pm

DT = 1.0 / 60.0


def _small_pile(mode: str) -> pm.World:
    rng = np.random.default_rng(11)
    world = pm.World(resolver=mode)
    world.add_particles(rng.uniform((-0.5, 0.2, -0.5), (0.5, 2.0, 0.5), (30, 3)), radii=0.15)
    world.add(pm.Box((-0.8, 0.0, -0.8), (0.8, 5.0, 0.8), restitution=0.3))
    world.add(pm.SphereCollisions(restitution=0.3))
    return world


@pytest.mark.parametrize(("mode", "slack"), [("worst-first", 0.1), ("sweep", 0.02)])
def test_both_modes_settle_a_small_pile_inside_the_box(mode, slack):
    """Settle 30 spheres in a box with either mode: inside, little overlap, losing energy.

    ``slack`` is the overlap allowed, as a fraction of the radius (the book's budget of
    2 × contacts single resolutions leaves more than the converged sweep).
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


def test_sweep_rests_where_the_books_budget_does_not():
    """Rest the pile with the sweep (warm-started) far better than 2 × contacts worst-first."""
    speeds = {}
    for mode in ("worst-first", "sweep"):
        world = _small_pile(mode)
        for _ in range(600):
            world.step(DT)
        speeds[mode] = float(np.abs(world.particles.velocity).max())
    assert speeds["sweep"] < 0.05
    assert speeds["sweep"] < speeds["worst-first"]


class _Pegs(pm.ContactGenerator):
    """A custom generator (no contact keys): each particle rests on a peg at y = 0."""

    def generate(self, particles, contacts):
        below = np.flatnonzero(particles.position[:, 1] < 0.0)
        contacts.add(below, -1, (0.0, 1.0, 0.0), -particles.position[below, 1], 0.0)


def test_auto_picks_sweep_above_threshold_and_for_keyed_contacts():
    """Choose worst-first for a few unkeyed contacts; sweep above sweep_threshold, or for
    collisions and links (keyed, so warm-started)."""
    def pegs(count: int) -> pm.World:
        world = pm.World(sweep_threshold=10)
        world.add_particles([(i, 0.0, 0.0) for i in range(count)])
        world.add(_Pegs())
        return world

    stats = pegs(4).step(DT)
    assert stats.contacts == 4 and stats.mode == "worst-first"
    stats = pegs(12).step(DT)
    assert stats.contacts == 12 and stats.mode == "sweep"
    pile = pm.World(sweep_threshold=10_000)
    pile.add_particles([(0, 0.1, 0), (0, 0.29, 0)], radii=0.1)
    pile.add(pm.Ground())
    pile.add(pm.SphereCollisions())
    assert pile.step(DT).mode == "sweep"
    chain = pm.World(sweep_threshold=10_000)
    top = chain.add_particle((0, 5, 0), mass=np.inf)
    end = chain.add_particle((0, 3, 0))
    chain.add(pm.Rod(top, end, length=2.0 - 1e-3))
    assert chain.step(DT).mode == "sweep"
