"""Sphere–sphere pairs from the grid (``collide._sphere_pairs``) against every pair checked
by brute force, on both of its paths: the dense grid (spheres packed in a small box) and the
spatial hash (spheres spread far apart, or one far outlier that makes the box huge)."""

from __future__ import annotations

import numpy as np
import pytest

import pointmass as pm
from pointmass.collide import DEFAULT_MARGIN_FRACTION, DENSE_CELLS_PER_SPHERE


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
