"""Particles with a radius meet rigid bodies (issue 13): they rest on boxes, push them and spin
them, momentum conserved; the particle is a body of zero inverse inertia in the body stage."""

import numpy as np
import pytest

import pointmass as pm
from pointmass.keys import body_pair_key, body_plane_key, particle_body_key, particle_of_key
from pointmass.rigid.shapes import Box, Sphere

DT = 1 / 60


def _grounded():
    world = pm.World(gravity=(0.0, -9.81, 0.0))
    world.add(pm.Ground(0.0, restitution=0.0, friction=0.5))
    return world


def test_particle_dropped_on_a_box_rests_on_its_top_face_within_a_millimetre_for_5_s():
    world = _grounded()
    box = world.add_body(Box((0.5, 0.5, 0.5)), (0.0, 0.5, 0.0), mass=10.0)
    p = world.add_particle((0.1, 2.0, 0.05), radius=0.1, mass=1.0)
    for _ in range(60):  # lands after 0.4 s
        world.step(DT)
    heights = []
    for _ in range(300):
        stats = world.step(DT)
        heights.append(world.particles.position[p, 1])
    assert np.abs(np.array(heights) - (1.0 + 0.1)).max() < 1e-3
    # the box and the particle on it fell asleep as one island (particle_sleep.py): the box's 4
    # corners on the ground and the particle's point on it leave the solve
    assert not box.awake and not world.particles.awake[p] and stats.body_contacts == 0
    assert world.particles.island[p] == world.bodies.island[box.index]
    assert np.abs(world.particles.velocity[p]).max() < 1e-6
    assert np.linalg.norm(box.position - (0.0, 0.5, 0.0)) < 1e-3


def _free_world(e):
    world = pm.World(gravity=(0.0, 0.0, 0.0))
    world.particle_friction = 0.0
    world.particle_restitution = e
    return world


def test_head_on_hit_conserves_momentum_and_exchanges_velocities_at_e_1():
    world = _free_world(1.0)
    box = world.add_body(Box((0.5, 0.5, 0.5)), (0.0, 0.0, 0.0), mass=1.0, friction=0.0,
                         restitution=1.0)
    p = world.add_particle((-2.0, 0.0, 0.0), (3.0, 0.0, 0.0), radius=0.1, mass=1.0)
    momentum = world.particles.velocity[p] + box.velocity
    for _ in range(60):
        stats = world.step(DT)
        now = world.particles.velocity[p] + box.velocity
        assert np.abs(now - momentum).max() < 1e-9
        assert stats.kinetic_energy == pytest.approx(4.5, rel=1e-8)  # ½·1·3², kept at e = 1
    assert np.abs(world.particles.velocity[p]).max() < 1e-9
    assert np.abs(box.velocity - (3.0, 0.0, 0.0)).max() < 1e-9
    assert np.abs(box.angular_velocity).max() < 1e-9


def _angular_momentum(world, p, box, mp, mb):
    inertia = np.linalg.inv(world.bodies.inv_inertia_world[box.index])
    return (mp * np.cross(world.particles.position[p], world.particles.velocity[p])
            + mb * np.cross(box.position, box.velocity) + inertia @ box.angular_velocity)


@pytest.mark.parametrize(("e", "tolerance"), [(1.0, 1e-9), (0.5, 1e-9), (0.0, 5e-4)])
def test_off_centre_hit_spins_the_box_and_conserves_angular_momentum(e, tolerance):
    """With e > 0 the two part after one impulse through the particle's centre: L to 1e-9.
    With e = 0 the particle slides on the turning face for the rest of the run and the
    position projection (positions only, along n) moves L: 1.1e-4 of |L| = 0.95 after 1 s
    (measured)."""
    world = _free_world(e)
    box = world.add_body(Box((0.5, 0.5, 0.5)), (0.0, 0.0, 0.0), mass=2.0, friction=0.0)
    p = world.add_particle((-2.0, 0.3, 0.1), (3.0, 0.0, 0.0), radius=0.1, mass=1.0)
    before = _angular_momentum(world, p, box, 1.0, 2.0)
    momentum = world.particles.velocity[p] + 2.0 * box.velocity
    for _ in range(60):
        world.step(DT)
        assert np.abs(_angular_momentum(world, p, box, 1.0, 2.0) - before).max() < tolerance
        assert np.abs(world.particles.velocity[p] + 2.0 * box.velocity - momentum).max() < 1e-9
    assert abs(box.angular_velocity[2]) > 0.5  # a hit above the centre turns it about −z
    assert box.angular_velocity[2] < 0.0


def test_particle_bounces_off_a_sphere_body_along_the_line_of_centres():
    world = _free_world(1.0)
    ball = world.add_body(Sphere(0.5), (0.0, 0.0, 0.0), mass=1.0, friction=0.0, restitution=1.0)
    p = world.add_particle((-2.0, 0.0, 0.0), (2.0, 0.0, 0.0), radius=0.25, mass=1.0)
    for _ in range(90):
        world.step(DT)
    assert np.abs(world.particles.velocity[p]).max() < 1e-9
    assert np.abs(ball.velocity - (2.0, 0.0, 0.0)).max() < 1e-9


def test_pile_of_fifty_particles_stays_on_a_box():
    world = _grounded()
    world.add(pm.SphereCollisions(restitution=0.0, friction=0.5))
    box = world.add_body(Box((1.0, 0.25, 1.0)), (0.0, 0.25, 0.0), mass=50.0)
    rng = np.random.default_rng(1)
    start = np.c_[rng.uniform(-0.6, 0.6, 50), 0.8 + 0.12 * np.arange(50),
                  rng.uniform(-0.6, 0.6, 50)]
    world.add_particles(start, radii=0.08, masses=0.1)
    for _ in range(300):
        stats = world.step(DT)
    pos = world.particles.position
    on_top = (np.abs(pos[:, 0]) < 1.0) & (np.abs(pos[:, 2]) < 1.0) & (pos[:, 1] > 0.5 + 0.07)
    assert on_top.all()
    assert np.abs(world.particles.velocity).max() < 1e-3
    assert stats.max_penetration < 2e-3
    assert np.linalg.norm(box.position - (0.0, 0.25, 0.0)) < 2e-3


def _scene():
    world = _grounded()
    world.add(pm.SphereCollisions(restitution=0.2, friction=0.3))
    world.add_body(Box((0.5, 0.2, 0.4)), (0.0, 0.2, 0.0), (0.96, 0.0, 0.28, 0.0), mass=5.0)
    world.add_body(Sphere(0.3), (1.2, 0.3, 0.0), mass=2.0)
    rng = np.random.default_rng(7)
    world.add_particles(np.c_[rng.uniform(-0.5, 1.5, 30), rng.uniform(0.8, 2.0, 30),
                              rng.uniform(-0.4, 0.4, 30)],
                        rng.normal(0.0, 1.0, (30, 3)), radii=0.06, masses=0.2)
    return world


def test_reruns_are_bit_identical():
    runs = []
    for _ in range(2):
        world = _scene()
        for _ in range(120):
            world.step(DT)
        runs.append((world.particles.position.copy(), world.particles.velocity.copy(),
                     world.bodies.position.copy(), world.bodies.orientation.copy()))
    for a, b in zip(*runs, strict=True):
        assert np.array_equal(a, b)


def test_bodies_move_as_alone_while_no_particle_touches_them():
    alone = _grounded()
    alone.add_body(Box((0.5, 0.5, 0.5)), (0.0, 1.0, 0.0), (0.9, 0.1, 0.3, 0.2), mass=1.0)
    near = _grounded()
    near.add_body(Box((0.5, 0.5, 0.5)), (0.0, 1.0, 0.0), (0.9, 0.1, 0.3, 0.2), mass=1.0)
    near.add_particle((5.0, 0.1, 0.0), radius=0.1)
    for _ in range(120):
        alone.step(DT)
        near.step(DT)
    for name in ("position", "orientation", "velocity", "angular_velocity"):
        assert np.array_equal(getattr(alone.bodies, name), getattr(near.bodies, name)), name


def test_points_without_radius_pass_through_bodies():
    world = _free_world(0.0)
    world.add_body(Box((0.5, 0.5, 0.5)), (0.0, 0.0, 0.0), mass=1.0)
    p = world.add_particle((-2.0, 0.0, 0.0), (3.0, 0.0, 0.0))
    for _ in range(120):
        world.step(DT)
    assert world.particles.velocity[p, 0] == 3.0


def test_particle_body_keys_are_their_own_family():
    keys = {particle_body_key(i, j, f) for i in (0, 1, 2**34) for j in (0, 1, 2**19)
            for f in range(7)}
    assert len(keys) == 3 * 3 * 7
    others = {body_pair_key(a, b, f) for a in (0, 1) for b in (0, 1, 2) for f in range(7)}
    others |= {body_plane_key(a, s, f) for a in (0, 1) for s in (0, 1) for f in range(7)}
    assert not keys & others
    assert all(k >= 0 for k in keys)
    assert particle_of_key(particle_body_key(2**34 + 5, 2**19, 6)) == 2**34 + 5


@pytest.mark.parametrize(("name", "value"), [("particle_friction", -0.1),
                                             ("particle_restitution", 1.5)])
def test_bad_particle_material_names_itself(name, value):
    with pytest.raises(ValueError, match=name):
        setattr(pm.World(), name, value)
