"""Sphere–sphere pairs (``sphere_pairs.py``) against every pair checked by brute force, on both
of the grid's paths: dense (spheres packed in a small box) and the spatial hash (spheres spread
far apart, or one far outlier that makes the box huge); and the pair list kept between steps
against a fresh search every step."""

from __future__ import annotations

import numpy as np
import pytest

import pointmass as pm
from pointmass.collide import DEFAULT_MARGIN_FRACTION
from pointmass.sphere_pairs import DENSE_CELLS_PER_SPHERE, SLOW_QUANTILE, _candidates


def _brute_force(position, radius):
    """{(i, j): penetration} for i < j closer than their radii plus 5 % of the larger."""
    found = {}
    n = position.shape[0]
    for i in range(n):
        for j in range(i + 1, n):
            d = float(np.linalg.norm(position[i] - position[j]))
            reach = radius[i] + radius[j]
            if d < reach + DEFAULT_MARGIN_FRACTION * max(radius[i], radius[j]):
                found[(i, j)] = reach - d
    return found


def _scene(kind: str, seed: int):
    rng = np.random.default_rng(seed)
    n = 300
    radius = rng.uniform(0.1, 0.4, n)
    if kind == "packed":
        position = rng.uniform(0.0, 5.0, (n, 3))
    elif kind == "spread":
        position = rng.uniform(0.0, 6.0, (n, 3)) * np.array([40.0, 1.0, 40.0])
    else:  # a packed cluster and one sphere far away
        position = rng.uniform(0.0, 5.0, (n, 3))
        position[-1] = (1e4, 0.0, 0.0)
    return position, radius


def _cells_per_sphere(position, radius):
    cell = 2.0 * radius.max() * (1.0 + DEFAULT_MARGIN_FRACTION / 2.0)
    span = np.floor(position / cell).max(axis=0) - np.floor(position / cell).min(axis=0) + 1
    return float(np.prod(span)) / position.shape[0]


@pytest.mark.parametrize("kind", ["packed", "spread", "outlier"])
@pytest.mark.parametrize("seed", [0, 1, 2])
def test_the_grid_finds_exactly_the_pairs_brute_force_finds(kind, seed):
    position, radius = _scene(kind, seed)
    dense = _cells_per_sphere(position, radius) <= DENSE_CELLS_PER_SPHERE
    assert dense == (kind == "packed"), "the scene takes the path it is meant to test"
    world = pm.World(gravity=(0, 0, 0))
    world.add_particles(position, radii=radius)
    spheres = pm.SphereCollisions()
    buffer = world.contacts
    buffer.clear()
    buffer.dt = 1 / 60
    spheres.generate(world.particles, buffer)
    a, b = buffer.a, buffer.b
    found = {(int(i), int(j)): float(d) for i, j, d in zip(a, b, buffer.penetration)}
    assert len(found) == buffer.count, "each pair once"
    assert np.all(a < b)
    expected = _brute_force(position, radius)
    assert found.keys() == expected.keys()
    for pair, depth in expected.items():
        assert found[pair] == pytest.approx(depth, abs=1e-12)
    normal = buffer.normal
    assert np.allclose(np.linalg.norm(normal, axis=1), 1.0)
    towards = np.einsum("ij,ij->i", position[a] - position[b], normal)
    assert np.all(towards > 0), "normals point from b to a"


# --- the pair list kept between steps (``sphere_pairs.PairList``) ----------------------------

def _pour(seed: int = 0, n: int = 200):
    """Spheres poured into a box: fast at first (the list is searched often), then settling."""
    rng = np.random.default_rng(seed)
    side = 4.0
    position = np.column_stack([rng.uniform(-1.6, 1.6, n), rng.uniform(0.5, 12.0, n),
                                rng.uniform(-1.6, 1.6, n)])
    world = pm.World()
    world.add_particles(position, radii=rng.uniform(0.15, 0.3, n))
    world.add(pm.BoxContainer((-side / 2, 0.0, -side / 2), (side / 2, 30.0, side / 2)))
    spheres = pm.SphereCollisions()
    world.add(spheres)
    return world, spheres


def test_a_kept_list_gives_the_trajectory_of_a_fresh_search_every_step():
    kept, kept_spheres = _pour()
    fresh, fresh_spheres = _pour()
    for _ in range(240):
        kept.step(1 / 60)
        fresh_spheres._pairs.clear()  # forget the list: the grid is searched again
        fresh.step(1 / 60)
    assert np.array_equal(kept.particles.position, fresh.particles.position)
    assert np.array_equal(kept.particles.velocity, fresh.particles.velocity)
    assert fresh_spheres._pairs.searches == 240
    assert kept_spheres._pairs.searches < 180, "the list was kept over steps (a fast pour)"
    assert kept.contacts.count > 200, "the spheres ended up touching"


def test_contacts_come_in_key_order():
    world, _ = _pour(seed=3)
    for _ in range(120):
        world.step(1 / 60)
    spheres = world.contacts.b >= 0
    keys = world.contacts.key[spheres]
    assert keys.shape[0] > 100
    assert np.all(np.diff(keys) > 0)


def test_a_sphere_moved_by_hand_is_found_at_once():
    world = pm.World(gravity=(0, 0, 0))
    world.add_particles([(0.0, 0.0, 0.0), (10.0, 0.0, 0.0)], radii=0.5)
    spheres = pm.SphereCollisions()
    world.add(spheres)
    world.step(1 / 60)
    assert world.contacts.count == 0
    world.particles.position[1] = (0.9, 0.0, 0.0)  # teleported into the first
    world.step(1 / 60)
    assert world.contacts.count == 1
    assert world.particles.position[1, 0] - world.particles.position[0, 0] >= 1.0 - 1e-6, \
        "and pushed apart"


def test_a_sphere_grown_by_hand_is_found_at_once():
    world = pm.World(gravity=(0, 0, 0))
    world.add_particles([(0.0, 0.0, 0.0), (1.5, 0.0, 0.0)], radii=0.5)
    world.add(pm.SphereCollisions())
    world.step(1 / 60)
    assert world.contacts.count == 0
    world.particles.radius[1] = 1.2
    world.step(1 / 60)
    assert world.contacts.count == 1


@pytest.mark.parametrize("kind", ["packed", "spread", "outlier"])
@pytest.mark.parametrize("seed", [0, 1, 2, 3])
def test_fast_spheres_search_around_themselves_and_no_pair_is_lost_or_doubled(kind, seed):
    """Cells are sized for the typical budget; a tenth of the spheres have budgets up to 8×
    the largest radius and search around themselves: the candidates are exactly the pairs
    closer than radii + margin + both budgets, each once."""
    position, radius = _scene(kind, seed)
    rng = np.random.default_rng(100 + seed)
    n = position.shape[0]
    budget = rng.uniform(0.0, 0.05, n)
    fast = rng.random(n) < 0.1
    budget[fast] = rng.uniform(0.1, 8.0 * radius.max(), fast.sum())
    slow = float(np.quantile(budget, SLOW_QUANTILE))
    margin = DEFAULT_MARGIN_FRACTION * radius.max()
    cell = 2.0 * radius.max() + margin + 2.0 * slow
    idx = np.arange(n)
    lo, hi = _candidates(position, radius, idx, n, cell, -1.0, DEFAULT_MARGIN_FRACTION,
                         budget, slow)
    found = list(zip(lo.tolist(), hi.tolist()))
    assert len(found) == len(set(found)), "each pair once"
    assert found == sorted(found), "key order"
    expected = []
    for i in range(n):
        for j in range(i + 1, n):
            reach = (radius[i] + radius[j] + DEFAULT_MARGIN_FRACTION * max(radius[i], radius[j])
                     + budget[i] + budget[j])
            if np.sum((position[i] - position[j]) ** 2) < reach * reach:
                expected.append((i, j))
    assert found == expected
    if kind != "spread":  # (spread spheres have few pairs at all)
        assert sum(budget[i] > slow or budget[j] > slow for i, j in expected) > 10
