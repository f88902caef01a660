"""Coulomb friction on contacts: sliding, slopes, energy, defaults and bad input."""

from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import example, given, settings
from hypothesis import strategies as st

import pointmass as pm
from pointmass.contacts import ContactBuffer
from pointmass.resolver import resolve_contacts

DT = 1.0 / 60.0
G = 9.81
R = 0.1


def _slider(v0: float, mu: float, resolver: str = "auto") -> pm.World:
    world = pm.World(gravity=(0, -G, 0), resolver=resolver)
    world.add_particles([[0.0, R, 0.0]], [[v0, 0.0, 0.0]], radii=R)
    world.add(pm.Ground(restitution=0.0, friction=mu))
    return world


@pytest.mark.parametrize("resolver", ["auto", "worst-first"])
@pytest.mark.parametrize("mu", [0.1, 0.5, 1.0])
def test_a_particle_sliding_on_the_ground_decelerates_at_mu_g_until_it_stops(mu, resolver):
    """Slide a particle at 3 m/s on the ground: v(t) = v0 − μ·g·t until it stops, then it stays."""
    v0 = 3.0
    world = _slider(v0, mu, resolver)
    stop = v0 / (mu * G)
    for k in range(1, int((stop + 0.5) / DT)):
        world.step(DT)
        t = k * DT
        v = world.particles.velocity[0]
        assert abs(v[1]) < 1e-9 and abs(v[2]) < 1e-12
        assert v[0] == pytest.approx(max(v0 - mu * G * t, 0.0), abs=mu * G * DT + 1e-9)
        assert v[0] >= 0.0  # friction stops it; it never pushes it back
    assert world.particles.velocity[0, 0] == 0.0
    travelled = world.particles.position[0, 0]
    assert travelled == pytest.approx(v0 * v0 / (2 * mu * G), abs=v0 * DT)
    assert world.particles.position[0, 1] == pytest.approx(R, abs=1e-9)


def test_without_friction_a_sliding_particle_keeps_its_speed():
    """Slide a particle on a frictionless (default) ground: its speed never changes."""
    world = pm.World(gravity=(0, -G, 0))
    world.add_particles([[0.0, R, 0.0]], [[3.0, 0.0, 0.0]], radii=R)
    world.add(pm.Ground(restitution=0.0))
    for _ in range(120):
        world.step(DT)
    assert world.particles.velocity[0, 0] == 3.0
    assert world.contacts.friction.tolist() == [0.0]


def _on_slope(theta_deg: float, mu: float) -> tuple[pm.World, np.ndarray]:
    """A sphere touching a plane through the origin tilted by θ about z (downhill is +x)."""
    theta = math.radians(theta_deg)
    n = np.array([math.sin(theta), math.cos(theta), 0.0])
    world = pm.World(gravity=(0, -G, 0))
    world.add_particles([n * R], radii=R)
    world.add(pm.Plane(n, 0.0, restitution=0.0, friction=mu))
    downhill = np.array([math.cos(theta), -math.sin(theta), 0.0])
    return world, downhill


@pytest.mark.parametrize(("theta", "mu"), [(20.0, 0.5), (10.0, 0.2), (44.0, 1.0)])
def test_a_sphere_on_a_slope_flatter_than_its_friction_angle_stays_put(theta, mu):
    """Rest a sphere on a slope with tan θ < μ for 3 s: it neither moves nor creeps."""
    assert math.tan(math.radians(theta)) < mu
    world, _ = _on_slope(theta, mu)
    start = world.particles.position[0].copy()
    for _ in range(180):
        world.step(DT)
    assert np.linalg.norm(world.particles.velocity[0]) < 1e-9
    assert np.linalg.norm(world.particles.position[0] - start) < 1e-9


@pytest.mark.parametrize(("theta", "mu"), [(40.0, 0.5), (30.0, 0.3), (60.0, 1.0), (30.0, 0.0)])
def test_a_sphere_on_a_slope_steeper_than_its_friction_angle_slides_at_g_sin_minus_mu_cos(
        theta, mu):
    """Rest a sphere on a slope with tan θ > μ: it slides down at a = g(sin θ − μ cos θ)."""
    t = math.radians(theta)
    assert math.tan(t) > mu
    world, downhill = _on_slope(theta, mu)
    start = world.particles.position[0].copy()
    a = G * (math.sin(t) - mu * math.cos(t))
    steps = 90
    for _ in range(steps):
        world.step(DT)
    time = steps * DT
    v = world.particles.velocity[0]
    assert v @ downhill == pytest.approx(a * time, abs=G * DT)
    assert np.linalg.norm(v - (v @ downhill) * downhill) < 1e-9  # along the slope only
    moved = (world.particles.position[0] - start) @ downhill
    assert moved == pytest.approx(0.5 * a * time * time, abs=a * time * DT + 1e-9)


@settings(max_examples=60, deadline=None)
@given(st.tuples(*[st.floats(-5.0, 5.0)] * 3), st.floats(0.0, 2.0),
       st.floats(0.0, 1.0), st.floats(-0.02, 0.005))
def test_friction_never_adds_energy_to_a_particle_hitting_the_ground(velocity, mu, e, height):
    """Step a particle near the ground at a random velocity: with friction its kinetic energy
    after the step is never above the frictionless one, and its normal motion is the same."""
    after = []
    for coefficient in (0.0, mu):
        world = pm.World(gravity=(0, -G, 0))
        world.add_particles([[0.0, R + height, 0.0]], [velocity], radii=R)
        world.add(pm.Ground(restitution=e, friction=coefficient))
        world.step(DT)
        after.append((world.kinetic_energy(), world.particles.velocity[0].copy()))
    (k0, v0), (k1, v1) = after
    assert k1 <= k0 + 1e-12
    assert v1[1] == pytest.approx(v0[1], abs=1e-12)
    # The tangential velocity only shrinks, never turns or grows.
    t0, t1 = v0[[0, 2]], v1[[0, 2]]
    assert np.linalg.norm(t1) <= np.linalg.norm(t0) + 1e-12
    assert t1 @ t0 >= -1e-12


@settings(max_examples=40, deadline=None)
@given(st.integers(0, 2**32 - 1), st.floats(0.05, 2.0))
def test_friction_never_adds_energy_when_resolving_random_touching_contacts(seed, mu):
    """Resolve random touching sphere pairs once (inelastic, cold start): kinetic energy never
    rises, and it ends no higher than the frictionless resolution of the same contacts."""
    n = 12
    energies = []
    for coefficient in (0.0, mu):
        r = np.random.default_rng(seed)
        particles = pm.Particles()
        particles.add_many(r.uniform(-1, 1, (n, 3)), r.normal(0, 1, (n, 3)),
                           masses=r.uniform(0.5, 2.0, n))
        pairs = r.integers(0, n, (20, 2))
        pairs = pairs[pairs[:, 0] != pairs[:, 1]]
        normals = r.normal(0, 1, (len(pairs), 3))
        normals /= np.linalg.norm(normals, axis=1)[:, None]
        contacts = ContactBuffer()
        contacts.add(pairs[:, 0], pairs[:, 1], normals, 0.0, 0.0, friction=coefficient)
        before = particles.kinetic_energy()
        resolve_contacts(particles, contacts, DT, mode="sequential")
        energies.append((before, particles.kinetic_energy()))
    (b0, a0), (b1, a1) = energies
    assert b0 == b1
    assert a1 <= b1 + 1e-12
    assert a0 <= b0 + 1e-12


def _pile(mu: float) -> pm.World:
    rng = np.random.default_rng(3)
    world = pm.World(gravity=(0, -G, 0))
    world.add_particles(rng.uniform((-0.5, 0.2, -0.5), (0.5, 2.0, 0.5), (40, 3)), radii=0.15)
    world.add(pm.BoxContainer((-0.8, 0.0, -0.8), (0.8, 5.0, 0.8), restitution=0.3, friction=mu))
    world.add(pm.SphereCollisions(restitution=0.3, friction=mu))
    return world


_finite = st.floats(-50.0, 50.0, allow_subnormal=False)


def _clamped_with_a_branch(x, y, z, limit):
    """The disc clamp as first written (scale only where the disc is exceeded)."""
    t2 = x * x + y * y + z * z
    if t2 > limit * limit:
        s = limit / math.sqrt(t2) if t2 > 0.0 else 0.0
        return x * s, y * s, z * s
    return x, y, z


@settings(max_examples=300, deadline=None)
@given(st.tuples(*[_finite] * 3), st.tuples(*[_finite] * 3), st.tuples(*[_finite] * 3),
       st.floats(0.0, 5.0), st.floats(0.0, 10.0))
@example(rel=(0.0, 0.0, 0.0), normal=(0.0, 0.0, 0.0), old=(0.0, 0.0, 1.1904817077486585e-199),
         k=0.0, limit=0.0)  # found by hypothesis in CI: an impulse whose square underflows
def test_the_branch_free_friction_disc_gives_the_branching_clamp_s_values_bit_for_bit(
        rel, normal, old, k, limit):
    """``kernels.coulomb_disc`` (the velocity rows' friction step, its clamp without a branch)
    against the same step clamped with a branch: the same floats, inside the disc, outside
    it, on a zero limit and a zero impulse."""
    from pointmass.solver.kernels import coulomb_disc

    n = np.array(normal)
    if np.linalg.norm(n) < 1e-3:
        n = np.array([0.0, 1.0, 0.0])
    nx, ny, nz = n / np.linalg.norm(n)
    rx, ry, rz = rel
    vn = rx * nx + ry * ny + rz * nz
    fx = old[0] - (rx - vn * nx) * k
    fy = old[1] - (ry - vn * ny) * k
    fz = old[2] - (rz - vn * nz) * k
    expected = _clamped_with_a_branch(fx, fy, fz, limit)
    got = coulomb_disc(rx, ry, rz, nx, ny, nz, *old, k, limit)
    assert got == expected
    # Inside the disc, except where the impulse is too small for its square to be a normal
    # float (under ~1.5e-154 N·s: the clamp compares squares, both versions alike).
    squared = got[0] * got[0] + got[1] * got[1] + got[2] * got[2]
    assert math.hypot(*got) <= limit * (1 + 1e-12) + 1e-300 or squared < 2.3e-308


def test_a_pile_with_friction_never_gains_energy_and_comes_to_rest():
    """Drop 40 spheres into a box with μ = 0.5: total energy never exceeds the start's, and
    after 4 s nothing moves faster than 1 cm/s."""
    world = _pile(0.5)
    energy0 = world.kinetic_energy() + world.potential_energy()
    for _ in range(240):
        world.step(DT)
        assert world.kinetic_energy() + world.potential_energy() <= energy0 + 1e-9
    assert np.linalg.norm(world.particles.velocity, axis=1).max() < 0.01


def test_friction_is_deterministic():
    """Run the same frictional pile twice: positions and velocities are bit-identical."""
    runs = []
    for _ in range(2):
        world = _pile(0.7)
        for _ in range(60):
            world.step(DT)
        runs.append((world.particles.position.copy(), world.particles.velocity.copy()))
    assert np.array_equal(runs[0][0], runs[1][0])
    assert np.array_equal(runs[0][1], runs[1][1])


def test_generators_carry_their_friction_into_the_contacts():
    """Give the box and the spheres different μ: each contact carries its generator's value."""
    world = pm.World(gravity=(0, -G, 0))
    world.add_particles([[0.0, R, 0.0], [0.0, 3 * R, 0.0]], radii=R)
    box = pm.BoxContainer((-1, 0, -1), (1, 5, 1), friction=0.25)
    world.add(box)
    world.add(pm.SphereCollisions(friction=0.75))
    world.step(DT)
    c = world.contacts
    assert sorted(c.friction.tolist()) == [0.25, 0.75]
    assert c.friction[c.b >= 0].tolist() == [0.75]
    box.friction = 0.5
    assert [plane.friction for plane in box.planes] == [0.5] * 5


def test_custom_generators_adding_contacts_positionally_stay_frictionless():
    """Add contacts as custom generators do (no friction argument): μ is 0, even in a buffer
    reused after frictional contacts."""
    contacts = ContactBuffer()
    contacts.add([0, 1], -1, (0.0, 1.0, 0.0), 0.0, 0.5, friction=0.9)
    contacts.clear()
    contacts.add([0, 1, 2], -1, (0.0, 1.0, 0.0), 0.0, 0.5)
    assert contacts.friction.tolist() == [0.0, 0.0, 0.0]


@pytest.mark.parametrize("bad", [-0.1, math.nan, math.inf, "rough", (0.1, 0.2)])
@pytest.mark.parametrize("make", [
    lambda mu: pm.Plane((0, 1, 0), 0.0, friction=mu),
    lambda mu: pm.Ground(friction=mu),
    lambda mu: pm.BoxContainer(friction=mu),
    lambda mu: pm.SphereCollisions(friction=mu),
], ids=["Plane", "Ground", "Box", "SphereCollisions"])
def test_a_bad_friction_coefficient_is_refused_by_name(make, bad):
    """Give a generator a negative, non-finite or non-numeric μ: a ValueError names friction."""
    with pytest.raises(ValueError, match="friction"):
        make(bad)


@pytest.mark.parametrize("make", [pm.Ground, pm.BoxContainer, pm.SphereCollisions],
                         ids=["Ground", "Box", "SphereCollisions"])
def test_setting_a_bad_friction_later_is_refused_by_name(make):
    """Set μ = -1 on an existing generator: a ValueError names friction, and μ is unchanged."""
    generator = make()
    with pytest.raises(ValueError, match="friction"):
        generator.friction = -1.0
    assert generator.friction == 0.0


def test_a_bad_friction_in_contact_buffer_add_is_refused_by_name():
    """Add a contact with μ < 0 directly: a ValueError names friction."""
    with pytest.raises(ValueError, match="friction"):
        ContactBuffer().add(0, -1, (0.0, 1.0, 0.0), 0.0, 0.5, friction=-0.5)
