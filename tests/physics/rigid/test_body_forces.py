"""Rigid force generators: springs push both ends (momenta kept, the two-body frequency), aero
feels the surface point's velocity (Cyclone's R3), the explosion throws outward with falloff and
stops, buoyancy floats a box where its weight equals the displaced water; bad input is named."""

import math

import numpy as np
import pytest

import pointmass as pm
from pointmass.rigid.bodies import world_rotation
from pointmass.rigid.forces import (
    Aero,
    AnchoredBodySpring,
    BodyBuoyancy,
    BodyForce,
    BodySpring,
    Explosion,
)
from pointmass.rigid.shapes import Box, Sphere

#: The solver's tuning numbers as World() has them (``pm.SolverSettings``)
DEFAULTS = pm.SolverSettings()


def momenta(world):
    b = world.bodies
    m = 1.0 / b.inv_mass
    linear = (m[:, None] * b.velocity).sum(axis=0)
    angular = np.cross(b.position, m[:, None] * b.velocity).sum(axis=0)
    for i in range(b.count):
        angular += b.angular_momentum(i)
    return linear, angular


def test_body_spring_keeps_linear_and_angular_momentum():
    """Equal and opposite at the two attachment points: Σ p and Σ x × p + Iω kept to 1e-9
    (the soft step gives the spring's force in each of its substeps, at the world points it
    was found at; holding the torque about a centre that moves instead gained 3.3e-3 here)."""
    world = pm.World(gravity=(0.0, 0.0, 0.0))
    a = world.add_body(Box((0.3, 0.2, 0.5)), (0.0, 0.0, 0.0), (0.9, 0.2, -0.3, 0.1), mass=2.0,
                       velocity=(0.5, -0.2, 0.1), angular_velocity=(1.0, 0.5, -2.0))
    b = world.add_body(Box((0.4, 0.4, 0.2)), (2.0, 0.5, -0.3), (0.7, -0.1, 0.4, 0.3), mass=3.0,
                       velocity=(-0.3, 0.1, 0.0), angular_velocity=(-0.5, 2.0, 0.7))
    world.add(BodySpring(a, (0.3, 0.1, -0.4), b, (-0.2, 0.4, 0.1), k=40.0, rest=1.0,
                         damping=1.5))
    p0, l0 = momenta(world)
    for _ in range(600):
        world.step(1 / 240)
    p1, l1 = momenta(world)
    assert np.abs(p1 - p0).max() < 1e-9
    assert np.abs(l1 - l0).max() < 1e-9
    # and it did something: the bodies turned
    assert np.abs(world.bodies.angular_velocity[0] - (1.0, 0.5, -2.0)).max() > 0.1


def test_centred_body_spring_oscillates_at_the_two_body_frequency():
    m1, m2, k = 1.0, 3.0, 100.0
    world = pm.World(gravity=(0.0, 0.0, 0.0))
    a = world.add_body(Sphere(0.1), (0.0, 0.0, 0.0), mass=m1)
    b = world.add_body(Sphere(0.1), (1.2, 0.0, 0.0), mass=m2)
    world.add(BodySpring(a, (0, 0, 0), b, (0, 0, 0), k=k, rest=1.0))
    dt = 1 / 1000
    stretch, times = [], []
    for n in range(2000):
        world.step(dt)
        stretch.append(b.position[0] - a.position[0] - 1.0)
        times.append((n + 1) * dt)
    s = np.array(stretch)
    up = np.flatnonzero((s[:-1] < 0) & (s[1:] >= 0))
    # linear interpolation of the upward zero crossings
    t = np.array(times)
    crossings = t[up] + (t[up + 1] - t[up]) * (-s[up]) / (s[up + 1] - s[up])
    period = float(np.mean(np.diff(crossings)))
    expected = 2 * math.pi / math.sqrt(k / (m1 * m2 / (m1 + m2)))
    assert len(crossings) >= 3
    assert period == pytest.approx(expected, rel=0.01)


def test_anchored_spring_hangs_a_body_at_its_stretch():
    """At rest a damped spring holds m·g at the stretch m·g/k, whatever its damping, and the
    body is at rest at the end of every step. (The soft step gave the spring's whole impulse
    in the first of its 4 substeps and gravity in each: the body ended each step at
    v = −(4 − 1)/2·g·h = −0.031 m/s, which the damper (c = 5) read, holding it at 1.6106 m.)"""
    world = pm.World(gravity=(0.0, -9.81, 0.0))
    body = world.add_body(Sphere(0.2), (0.0, 1.0, 0.0), mass=2.0, linear_damping=0.05)
    world.add(AnchoredBodySpring(body, (0, 0, 0), (0.0, 3.0, 0.0), k=50.0, rest=1.0,
                                 damping=5.0))
    for _ in range(1200):
        world.step(1 / 120)
    assert body.position[1] == pytest.approx(3.0 - 1.0 - 2.0 * 9.81 / 50.0, abs=1e-4)
    assert abs(body.velocity[1]) < 1e-9


def test_a_spring_at_its_equilibrium_holds_the_body_still_every_step():
    """Hung at y = 3 − 1 − m·g/k at rest, the body stays there, v = 0 at every step's end
    (to rounding): the spring's force and gravity act in the same substeps."""
    m, k = 2.0, 50.0
    world = pm.World(gravity=(0.0, -9.81, 0.0))
    body = world.add_body(Sphere(0.2), (0.0, 3.0 - 1.0 - m * 9.81 / k, 0.0), mass=m)
    world.add(AnchoredBodySpring(body, (0, 0, 0), (0.0, 3.0, 0.0), k=k, rest=1.0, damping=5.0))
    start = body.position.copy()
    for _ in range(240):
        world.step(1 / 120)
        assert np.abs(body.velocity).max() < 1e-12
    assert np.abs(body.position - start).max() < 1e-12


def test_aero_uses_the_surface_velocity_so_a_spinning_plate_slows():
    """Cyclone's Aero (centre velocity, R3) leaves a spinning plate with a still centre alone;
    with the point velocity v + ω × r the plate's edges feel the air and the spin decays."""
    tensor = np.diag([0.0, -2.0, 0.0])  # a flat plate: drag across its normal (y)

    def spin(point_velocity: bool) -> float:
        world = pm.World(gravity=(0.0, 0.0, 0.0))
        plate = world.add_body(Box((0.5, 0.02, 1.0)), (0.0, 0.0, 0.0), mass=1.0,
                               angular_velocity=(5.0, 0.0, 0.0))
        for z in (-0.9, 0.9):
            if point_velocity:
                world.add(Aero(plate, tensor, (0.0, 0.0, z)))
            else:
                def cyclone(bodies, i, dt, z=z):
                    r = world_rotation(bodies.orientation[i])
                    force = r @ tensor @ r.T @ bodies.velocity[i]  # the centre's velocity
                    return force, np.cross(r @ (0.0, 0.0, z), force)
                world.add(BodyForce(cyclone, [plate]))
        for _ in range(120):
            world.step(1 / 120)
        return float(np.linalg.norm(plate.angular_velocity))

    assert spin(point_velocity=False) == pytest.approx(5.0, abs=1e-9)
    assert spin(point_velocity=True) < 0.5 * 5.0


def test_aero_in_still_air_matches_cyclone_for_a_moving_body_and_wind_is_relative():
    world = pm.World(gravity=(0.0, 0.0, 0.0))
    body = world.add_body(Box((0.5, 0.1, 0.5)), (0, 0, 0), mass=1.0, velocity=(0.0, -2.0, 0.0))
    aero = world.add(Aero(body, (0.0, -3.0, 0.0)))
    aero.apply(world.bodies, 1 / 60)
    assert world.bodies.force[0] == pytest.approx((0.0, 6.0, 0.0))
    world.bodies.clear_accumulators()
    aero.wind = (0.0, -2.0, 0.0)  # moving with the wind: no air speed, no force
    aero.apply(world.bodies, 1 / 60)
    assert world.bodies.force[0] == pytest.approx((0.0, 0.0, 0.0))


def test_explosion_pushes_outward_with_falloff_and_stops():
    world = pm.World(gravity=(0.0, 0.0, 0.0))
    radius, size = 6.0, 0.25
    directions = np.array([[1, 0, 0], [0, 1, 0], [0, 0, -1], [-1, 1, 0], [1, 1, 1]], float)
    directions /= np.linalg.norm(directions, axis=1)[:, None]
    distances = np.array([1.0, 2.0, 3.5, 5.0, 8.0])  # the last is out of reach
    bodies = [world.add_body(Sphere(size), d * r, mass=2.0)
              for d, r in zip(directions, distances, strict=True)]
    box = world.add_body(Box((size, size, size)), (0.0, -2.0, 0.0), (0.9, 0.3, 0.1, 0.2),
                         mass=2.0)
    dt = 1 / 70  # the blast ends inside a step: that step gets only its share
    # one step at rest first: a body's first step opens with leapfrog's half kick (``body_soft``,
    # "Leapfrog"), which would count a force that starts with it for half a substep less
    world.step(dt)
    blast = world.add(Explosion((0.0, 0.0, 0.0), strength=10.0, radius=radius, duration=0.05))
    for _ in range(5):
        world.step(dt)
    assert blast.done
    after = world.bodies.velocity.copy()
    for _ in range(20):
        world.step(dt)
    assert np.array_equal(world.bodies.velocity, after)  # nothing after the blast
    for body, d, r in zip(bodies, directions, distances, strict=True):
        # impulse / mass, outward; the falloff is read each step, and the body moves ~0.2 m
        # away during the blast, so the impulse is a little under that of its first distance
        reach = max(0.0, 1.0 - (r - size) / radius)
        v = body.velocity
        assert np.linalg.norm(np.cross(v, d)) < 1e-12 and v @ d >= 0.0
        assert v @ d == pytest.approx(10.0 * reach / 2.0, rel=0.02, abs=1e-12)
        assert v @ d <= 10.0 * reach / 2.0
    speeds = [np.linalg.norm(b.velocity) for b in bodies]
    assert speeds[0] > speeds[1] > speeds[2] > speeds[3] > 0.0 and speeds[4] == 0.0
    assert box.velocity[1] < 0.0 and abs(box.velocity[0]) < 1e-12
    assert np.linalg.norm(box.angular_velocity) > 0.0  # pushed at its near corner: it tumbles
    blast.detonate((0.0, -4.0, 0.0))
    world.step(dt)
    assert box.velocity[1] > after[5, 1]  # pushed back up from below


@pytest.mark.parametrize("density", [300.0, 700.0])
def test_buoyancy_floats_a_box_where_weight_equals_displaced_water(density):
    """The box settles where its weight equals the water it displaces, and stops there: its
    motion over a step, Δy/dt, and its velocity at the step's end. (The soft step gave the
    buoyancy's impulse once a step, in the first of 4 substeps, and gravity in each: a
    floating box at rest ended each step at v = −(4 − 1)/2·g·h = −0.0307 m/s at dt 1/120.)"""
    half = 0.5
    world = pm.World(gravity=(0.0, -9.81, 0.0))
    box = world.add_body(Box((half, half, half)), (0.0, 1.0, 0.0), density=density,
                         linear_damping=0.2, angular_damping=0.2)
    world.add(BodyBuoyancy(box, (0.0, 0.0, 0.0), max_depth=half, volume=(2 * half) ** 3,
                           water_height=0.0))
    for _ in range(120 * 20):
        world.step(1 / 120)
    submerged = half - box.position[1]  # depth of the bottom face below the water
    displaced = submerged * (2 * half) ** 2 * 1000.0
    assert displaced == pytest.approx(box.mass, rel=0.01)
    before = box.position[1]
    world.step(1 / 120)
    assert abs(box.position[1] - before) * 120 < 1e-3
    assert abs(box.velocity[1]) < 1e-3


def test_a_box_floating_at_its_waterline_stays_at_rest():
    """A 300 kg/m³ box of 1 m³ put at rest where it floats (0.3 m under the water) stays there:
    v = 0 at every step's end (to rounding), the box unmoved."""
    half = 0.5
    world = pm.World(gravity=(0.0, -9.81, 0.0))
    box = world.add_body(Box((half, half, half)), (0.0, half - 0.3, 0.0), density=300.0)
    world.add(BodyBuoyancy(box, (0.0, 0.0, 0.0), max_depth=half, volume=(2 * half) ** 3,
                           water_height=0.0))
    for _ in range(120):
        world.step(1 / 120)
        assert np.abs(box.velocity).max() < 1e-12
    assert abs(box.position[1] - (half - 0.3)) < 1e-12


def test_constant_force_and_torque_give_momenta_f_t_and_tau_t():
    """A box spinning about a tilted axis and drifting, pushed by a constant force through its
    centre and a constant torque, without gravity: p = p₀ + F·t and, about the origin,
    L = L₀ + Σ x_k × F·h + τ·t (1e-9 relative): the force acts through the centre x_k where
    each integration step of h starts (the soft step's substep, which finds its forces
    again), at x₀ + k·h·v₀ plus a multiple of F, which x × F does not see. Leapfrog (the soft
    step) kicks by h/2 at x₀, by h at x₁ … x_{N−1},
    and its reported velocity takes the closing half kick of the last substep's force, found at
    x_{N−1}: (N·x₀ + h·v₀·(N² − 1)/2) × F·h."""
    force, torque = np.array([0.3, -0.2, 0.5]), np.array([0.4, 0.1, -0.25])
    world = pm.World(gravity=(0.0, 0.0, 0.0))
    box = world.add_body(Box((0.3, 0.2, 0.5)), (0.5, 1.0, -0.2), (0.9, 0.2, -0.3, 0.1),
                         mass=2.0, velocity=(0.5, -0.2, 0.1), angular_velocity=(1.0, 0.5, -2.0))
    world.add(BodyForce(lambda bodies, i, dt: (force, torque), [box]))
    p0, l0 = momenta(world)
    dt, steps = 1 / 60, 240
    parts = DEFAULTS.soft_substeps
    n, h = steps * parts, dt / parts
    pairs = (n * n - 1) / 2
    moment = np.cross(n * box.position + h * box.velocity * pairs, force) * h
    for _ in range(steps):
        world.step(dt)
    p1, l1 = momenta(world)
    t = steps * dt
    np.testing.assert_allclose(p1, p0 + force * t, rtol=0, atol=1e-9 * np.linalg.norm(p1))
    np.testing.assert_allclose(l1, l0 + moment + torque * t, rtol=0,
                               atol=1e-9 * np.linalg.norm(l1))
    assert np.linalg.norm(box.angular_velocity - (1.0, 0.5, -2.0)) > 0.5  # it spun up


def test_generators_add_to_user_forces_for_each_substep_only():
    """A user force lasts the whole step; generator forces are recomputed each substep."""
    world = pm.World(gravity=(0.0, 0.0, 0.0), substeps=4)
    body = world.add_body(Sphere(0.2), (0, 0, 0), mass=1.0)
    world.add(BodyForce(lambda bodies, i, dt: (1.0, 0.0, 0.0)))
    body.add_force((0.0, 2.0, 0.0))
    world.step(0.1)
    assert body.velocity == pytest.approx((0.1, 0.2, 0.0))
    assert not world.bodies.force.any()


def test_world_add_and_remove_body_generators():
    world = pm.World()
    a = world.add_body(Sphere(0.2))
    spring = world.add(AnchoredBodySpring(a, (0, 0, 0), (0, 1, 0), 1.0, 0.0))
    with pytest.raises(ValueError, match="already"):
        world.add(spring)
    world.remove(spring)
    assert not world.body_forces
    with pytest.raises(IndexError, match="body_b"):
        world.add(BodySpring(a, (0, 0, 0), 3, (0, 0, 0), 1.0, 0.0))


def test_a_generator_on_a_body_dropped_by_restore_fails_naming_it():
    world = pm.World()
    a = world.add_body(Sphere(0.2))
    snap = world.bodies.snapshot()
    b = world.add_body(Sphere(0.2), (2, 0, 0))
    world.add(BodySpring(a, (0, 0, 0), b, (0, 0, 0), 1.0, 1.0))
    world.step(1 / 60)
    world.bodies.restore(snap)
    with pytest.raises(IndexError, match=r"BodySpring.*no longer exists"):
        world.step(1 / 60)


def test_spring_energy_counts_in_the_world():
    world = pm.World(gravity=(0.0, 0.0, 0.0))
    a = world.add_body(Sphere(0.1), (0, 0, 0), mass=1.0)
    b = world.add_body(Sphere(0.1), (2.5, 0, 0), mass=1.0)  # swings 0.5 m each way: no touch
    world.add(BodySpring(a, (0, 0, 0), b, (0, 0, 0), k=10.0, rest=2.0))
    assert world.potential_energy() == pytest.approx(1.25)
    e0 = world.kinetic_energy() + world.potential_energy()
    for _ in range(500):
        world.step(1 / 500)
    # symplectic Euler: the energy wobbles by O(ω·dt) = 0.9 % at most, and does not drift
    assert world.kinetic_energy() + world.potential_energy() == pytest.approx(e0, rel=5e-3)


def test_a_body_spring_keeps_its_energy_over_twenty_seconds():
    """The spring above at dt 1/60 for 20 s (ω = √(k/μ) = 4.5 rad/s, ω·dt = 0.075): semi-
    implicit Euler's energy wobbles by about ω·h/2 (h its integration step, the soft step's
    dt/4) and does not grow. The soft step found the forces once a step and spread them
    over its substeps; for a force that depends on where the bodies are, that is not semi-
    implicit Euler, and the energy grew by (1 − 5/8)·(ω·dt)² a step: 12× in 20 s. It finds
    them again every substep. Measured: 0 … +0.026 % (leapfrog since stop 42, O((ω·h)²);
    ±0.94 % with semi-implicit Euler, ±3.9 % with the impulses stage at h = dt); bound ω·h."""
    world = pm.World(gravity=(0.0, 0.0, 0.0))
    a = world.add_body(Sphere(0.1), (0, 0, 0), mass=1.0)
    b = world.add_body(Sphere(0.1), (2.5, 0, 0), mass=1.0)
    world.add(BodySpring(a, (0, 0, 0), b, (0, 0, 0), k=10.0, rest=2.0))
    e0 = world.kinetic_energy() + world.potential_energy()
    energies = []
    for _ in range(1200):
        world.step(1 / 60)
        energies.append(world.kinetic_energy() + world.potential_energy())
    band = math.sqrt(10.0 / 0.5) / 60 / DEFAULTS.soft_substeps
    assert (1 - band) * e0 < min(energies) and max(energies) < (1 + band) * e0


@pytest.mark.parametrize(("make", "word"), [
    (lambda: BodySpring(0, (0, 0, 0), 1, (0, 0, 0), k=-1.0, rest=1.0), "k"),
    (lambda: BodySpring(0, (0, 0, 0), 1, (0, 0, 0), k=1.0, rest=-1.0), "rest"),
    (lambda: BodySpring(0, (0, 0, 0), 1, (0, 0, 0), k=1.0, rest=1.0, damping=-2), "damping"),
    (lambda: BodySpring(0, (0, 0, 0), 0, (0, 0, 0), k=1.0, rest=1.0), "different"),
    (lambda: BodySpring(0, (0, 0), 1, (0, 0, 0), k=1.0, rest=1.0), "local_a"),
    (lambda: AnchoredBodySpring(0, (0, 0, 0), (0, math.nan, 0), 1.0, 1.0), "anchor"),
    (lambda: Aero(0, np.ones((2, 2))), "tensor"),
    (lambda: Aero(0, (0, 0, math.inf)), "tensor"),
    (lambda: Aero(0, (1, 1, 1), wind=(0, 0)), "wind"),
    (lambda: BodyBuoyancy(0, (0, 0, 0), 0.0, 1.0), "max_depth"),
    (lambda: BodyBuoyancy(0, (0, 0, 0), 1.0, -1.0), "volume"),
    (lambda: BodyBuoyancy(0, (0, 0, 0), 1.0, 1.0, liquid_density=-5), "liquid_density"),
    (lambda: Explosion((0, 0, 0), -1.0, 1.0), "strength"),
    (lambda: Explosion((0, 0, 0), 1.0, 0.0), "radius"),
    (lambda: Explosion((0, 0, 0), 1.0, 1.0, duration=0.0), "duration"),
])
def test_bad_input_names_the_parameter(make, word):
    with pytest.raises(ValueError, match=word):
        make()


def test_bad_body_and_callable_are_refused():
    with pytest.raises(TypeError, match="body"):
        Aero("wing", (1, 1, 1))
    with pytest.raises(TypeError, match="fn"):
        BodyForce(3)
    world = pm.World()
    world.add_body(Sphere(0.2))
    world.add(BodyForce(lambda bodies, i, dt: (math.nan, 0, 0)))
    with pytest.raises(ValueError, match="finite"):
        world.step(1 / 60)
