"""The solver's acceptance (issue 8), with ``World()`` defaults and no solver option anywhere:
Newton's cradle and resting stacks at once, heavy chains that hold, no energy from nowhere,
no hidden inelasticity, and piles that settle."""

from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

import pointmass as pm

DT = 1.0 / 60.0


@pytest.mark.parametrize("gap", [0.0, 0.01, 0.05])
def test_newtons_cradle_passes_the_whole_momentum_to_the_last_ball(gap):
    """Five unit spheres (r = 0.5, e = 1, no gravity) in a row, the first at 1 m/s: the last
    leaves with ≥ 0.99 of the momentum, the others keep ≤ 0.01 (a simultaneous solver gives
    [-0.6, 0.4, 0.4, 0.4, 0.4]); with gaps of 1 cm (inside the contact margin) and 5 cm too."""
    world = pm.World(gravity=(0, 0, 0))
    world.add_particles([(i * (1.0 + gap), 0.0, 0.0) for i in range(5)], radii=0.5)
    world.particles.velocity[0] = (1.0, 0.0, 0.0)
    world.add(pm.SphereCollisions(restitution=1.0))
    for _ in range(120):
        world.step(DT)
    v = world.particles.velocity[:, 0]
    assert v[4] >= 0.99
    assert np.abs(v[:4]).max() <= 0.01
    assert world.particles.momentum()[0] == pytest.approx(1.0, abs=1e-12)


def test_a_stack_of_five_spheres_rests_on_the_ground():
    """After 1 s: max speed ≤ 1e-3 m/s, overlap ≤ 0.5 % of r, no sideways drift."""
    r = 0.5
    world = pm.World()
    world.add_particles([(0.0, r + 2 * r * i, 0.0) for i in range(5)], radii=r)
    world.add(pm.Ground(restitution=0.5))
    world.add(pm.SphereCollisions(restitution=0.5))
    for _ in range(60):
        stats = world.step(DT)
    assert np.abs(world.particles.velocity).max() <= 1e-3
    assert stats.max_penetration <= 0.005 * r
    assert np.abs(world.particles.position[:, [0, 2]]).max() == 0.0


@pytest.mark.parametrize(("load", "stretch"), [(100.0, 0.01), (1000.0, 0.02)])
def test_a_heavy_load_on_a_light_link_holds(load, stretch):
    """A 1 kg particle on an AnchoredRod (0.5 m), a load hanging from it on a Cable (0.6 m,
    e = 0), gravity, dt = 1/32, 100 steps: stretch ≤ 1 % at 100 : 1 and ≤ 2 % at 1000 : 1
    (Gauss–Seidel alone left +19 % and +2100 %; the small set gets the exact solve)."""
    world = pm.World()
    light = world.add_particle((0.0, -0.5, 0.0), mass=1.0)
    heavy = world.add_particle((0.0, -1.1, 0.0), mass=load)
    world.add(pm.AnchoredRod(light, (0.0, 0.0, 0.0), 0.5))
    world.add(pm.Cable(light, heavy, 0.6, restitution=0.0))
    passes = []
    for _ in range(100):
        passes.append(world.step(1 / 32).velocity_passes)
        p = world.particles.position
        assert abs(np.linalg.norm(p[light]) / 0.5 - 1.0) <= stretch
        assert np.linalg.norm(p[heavy] - p[light]) / 0.6 - 1.0 <= stretch
    assert max(passes) <= 40  # the exact solve after 20 passes, then a few more at most


def _two_cables() -> pm.World:
    """An anchor, 1 kg on a 0.6 m cable from it, and 100 kg moving at 1 m/s on a √0.72 m cable
    from the 1 kg one; both cables e = 0; no gravity."""
    world = pm.World(gravity=(0, 0, 0))
    anchor = world.add_particle((0.0, 0.0, 0.0), mass=math.inf)
    light = world.add_particle((0.6, 0.0, 0.0), mass=1.0)
    heavy = world.add_particle((1.2, 0.6, 0.0), velocity=(0.0, 0.0, 1.0), mass=100.0)
    world.add(pm.Cable(anchor, light, 0.6, restitution=0.0))
    world.add(pm.Cable(light, heavy, math.sqrt(0.72), restitution=0.0))
    return world


def test_links_never_make_energy_from_nowhere():
    """The cable scene that jumped +204 % at step 30 (a warm start from a turned cable): no
    step increases the kinetic energy."""
    world = _two_cables()
    energy = world.kinetic_energy()
    for _ in range(300):
        world.step(1 / 32)
        now = world.kinetic_energy()
        assert now <= energy * (1 + 1e-9) + 1e-15
        energy = now


def _random_scene(seed: int) -> pm.World:
    """Random spheres and links with random masses (some immovable), velocities and
    restitution, no forces at all."""
    rng = np.random.default_rng(seed)
    world = pm.World(gravity=(0, 0, 0))
    n = int(rng.integers(2, 10))
    masses = np.where(rng.random(n) < 0.15, math.inf, rng.uniform(0.1, 50.0, n))
    ids = world.add_particles(rng.uniform(-1.5, 1.5, (n, 3)), rng.normal(0, 2, (n, 3)),
                              masses=masses, radii=rng.uniform(0.1, 0.5, n))
    world.particles.velocity[masses == math.inf] = 0.0
    world.add(pm.SphereCollisions(restitution=float(rng.uniform(0, 1))))
    world.add(pm.BoxContainer((-2, -2, -2), (2, 2, 2), restitution=float(rng.uniform(0, 1))))
    pairs = rng.choice(n, (int(rng.integers(0, n)), 2))
    pairs = pairs[pairs[:, 0] != pairs[:, 1]]
    p = world.particles.position
    for a, b in pairs:
        length = float(np.linalg.norm(p[a] - p[b])) * rng.uniform(0.9, 1.1) + 1e-3
        if rng.random() < 0.5:
            world.add(pm.Cable(ids[a], ids[b], length, restitution=float(rng.uniform(0, 1))))
        else:
            world.add(pm.Rod(ids[a], ids[b], length))
    return world


def _check_no_energy_gain(seed: int) -> None:
    world = _random_scene(seed)
    energy = world.kinetic_energy()
    for _ in range(60):
        world.step(DT)
        now = world.kinetic_energy()
        assert now <= energy * (1 + 1e-9) + 1e-12, (seed, energy, now)
        energy = now


@settings(max_examples=40, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(st.integers(0, 2**32 - 1))
def test_no_step_adds_kinetic_energy_in_random_force_free_scenes(seed):
    """With no forces and e ≤ 1, contacts and links never increase the kinetic energy (a
    quick profile; the slow-marked test runs ≥ 1000 scenes)."""
    _check_no_energy_gain(seed)


@pytest.mark.slow
@settings(max_examples=1000, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(st.integers(0, 2**32 - 1))
def test_no_step_adds_kinetic_energy_in_1000_random_force_free_scenes(seed):
    """The same, over ≥ 1000 random scenes."""
    _check_no_energy_gain(seed)


def test_no_hidden_inelasticity_at_low_speed():
    """Two e = 1 spheres closing at 0.2 m/s separate at 0.2 m/s (a restitution threshold of
    0.25 m/s stopped them dead); the threshold is an option whose default is 0."""
    world = pm.World(gravity=(0, 0, 0))
    assert world.restitution_threshold == 0.0
    world.add_particles([(0.0, 0.0, 0.0), (1.02, 0.0, 0.0)], [(0.1, 0, 0), (-0.1, 0, 0)],
                        radii=0.5)
    world.add(pm.SphereCollisions(restitution=1.0))
    for _ in range(60):
        world.step(DT)
    assert world.particles.velocity[:, 0].tolist() == pytest.approx([-0.1, 0.1], abs=1e-12)


def ball_pit(n: int, seed: int = 0) -> pm.World:
    """The issue's pit: N spheres (r 0.5 m, 1 kg) on a jittered lattice of spacing 1.1 m,
    4 layers from 1 m above the floor, in a box of side 1.1·⌈√(N/4)⌉, e = 0.5, frictionless."""
    rng = np.random.default_rng(seed)
    per = math.ceil(math.sqrt(n / 4))
    side = 1.1 * per
    grid = np.stack(np.meshgrid(np.arange(per), np.arange(4), np.arange(per), indexing="ij"),
                    axis=-1).reshape(-1, 3)[:n]
    pos = np.column_stack([-side / 2 + 0.55 + 1.1 * grid[:, 0], 1.0 + 1.1 * grid[:, 1],
                           -side / 2 + 0.55 + 1.1 * grid[:, 2]])
    world = pm.World()
    world.add_particles(pos + rng.uniform(-0.05, 0.05, pos.shape), radii=0.5)
    world.add(pm.BoxContainer((-side / 2, 0, -side / 2), (side / 2, 50, side / 2), restitution=0.5))
    world.add(pm.SphereCollisions(restitution=0.5))
    return world


@pytest.mark.slow
def test_a_frictionless_pile_settles_without_overlap_or_sinking():
    """N = 1000 after 600 steps: overlap ≤ 1 % of the diameter, every sphere above the floor
    within 0.1 % of the diameter, the total energy falling. (Projection lifts overlapping
    spheres by up to a few mm, which shows as a few hundredths of a joule of potential energy
    in a step, against 14 000 J in the pile: measured ≤ 0.07 J.)"""
    world = ball_pit(1000)
    energies = []
    for _ in range(600):
        stats = world.step(DT)
        energies.append(world.kinetic_energy() + world.potential_energy())
    assert stats.max_penetration <= 0.01
    assert (world.particles.position[:, 1] - 0.5).min() >= -1e-3
    rises = np.diff(energies)
    assert rises.max() <= 0.2 and energies[-1] < energies[100] - 10.0


@pytest.mark.slow
@pytest.mark.xfail(reason="measured mean speed after 600 steps over seeds 0–11 (stop 37): "
                          "0.0076, 0.053, 0.071, 0.036, 0.055, 0.017, 0.0079, 0.032, 0.036, "
                          "0.065, 0.056, 0.022 m/s (target 0.02; 3 of 12 meet it): the pile "
                          "is still settling at 10 s; pits of 1 000 rest and sleep by 30 s "
                          "(tests/physics/test_pit_rest.py)",
                   strict=True)
def test_a_frictionless_pile_comes_to_rest_in_ten_seconds():
    """The issue's target: mean speed ≤ 0.02 m/s after 600 steps at N = 1000, for every
    layout (seeds 0–3; seed 0 alone met it, by chance)."""
    for seed in range(4):
        world = ball_pit(1000, seed)
        for _ in range(600):
            world.step(DT)
        assert np.linalg.norm(world.particles.velocity, axis=1).mean() <= 0.02, seed
