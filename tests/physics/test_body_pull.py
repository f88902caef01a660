"""The pull on a point of a rigid body (``rigid/pull.py``, the viewer's body grab): the
particle grab's critically damped path when held by the centre, the effective mass at a
point, turning when held off the centre, and stability for light bodies held far out."""

from __future__ import annotations

import math

import numpy as np
import pytest

import pointmass as pm
from pointmass.rigid.pull import BodyPull, largest_eigenvalue, point_mass
from pointmass.rigid.shapes import Box

CUBE = (0.5, 0.5, 0.5)


def _free_cube(mass: float = 1.0) -> pm.World:
    world = pm.World(gravity=(0.0, 0.0, 0.0))
    world.add_body(Box(CUBE), (0.0, 0.0, 0.0), mass=mass)
    return world


@pytest.mark.parametrize("mass", [1.0, 10.0])
def test_a_body_held_by_its_centre_follows_the_particle_grabs_path(mass):
    """Held at the centre the spring is the particle grab's, scaled to the body's mass: the
    critically damped path x(t) = 1 − (1 + ωt)·e^(−ωt), whatever the mass, and no turn."""
    world = _free_cube(mass)
    world.add(BodyPull(0, (0.0, 0.0, 0.0), (1.0, 0.0, 0.0)))
    xs = []
    for _ in range(240):
        world.step(1 / 120)
        xs.append(world.bodies.position[0, 0])
    wt = 12 * 31 / 120
    assert xs[30] == pytest.approx(1 - (1 + wt) * math.exp(-wt), abs=0.01)
    assert max(xs) < 1.0 + 1e-3 and xs[-1] == pytest.approx(1.0, abs=1e-3)
    np.testing.assert_allclose(world.bodies.angular_velocity[0], 0.0, atol=1e-12)


def test_the_point_mass_of_a_cube_at_its_corner():
    """K = 1/m + [r]ᵀ I⁻¹ [r]; a cube's I = m·s²/6 (side s) is isotropic, so across r the
    point answers as 1/m + 6|r|²/(m s²): 1 + 4.5 for the unit cube at a corner: 1/5.5 kg."""
    world = _free_cube(1.0)
    corner = np.array(CUBE)
    inv = world.bodies.inv_inertia_world[0]
    assert point_mass(1.0, inv, *corner) == pytest.approx(1 / 5.5, rel=1e-12)
    assert point_mass(1.0, inv, 0.0, 0.0, 0.0) == pytest.approx(1.0, rel=1e-12)


def test_a_body_held_by_a_corner_turns_and_settles_with_the_corner_on_the_target():
    """Pulled by a corner, the cube turns (the force acts at the point) until the corner is
    on the target, and the grip stops it spinning: at rest, centre behind the corner."""
    world = _free_cube(1.0)
    corner = np.array(CUBE)
    spring = world.add(BodyPull(0, corner, corner + np.array([2.0, 0.0, 0.0])))
    turned = 0.0
    for _ in range(360):
        world.step(1 / 60)
        turned = max(turned, 2 * math.degrees(math.acos(min(1.0,
                                                             abs(world.bodies.orientation[0, 0])))))
    assert turned > 20.0
    np.testing.assert_allclose(spring.point_of(world.bodies), spring.target, atol=1e-3)
    assert np.abs(world.bodies.angular_velocity[0]).max() < 1e-2
    assert np.abs(world.bodies.velocity[0]).max() < 1e-2


def test_a_light_plank_held_by_its_end_stays_stable_and_hangs_by_m_g_over_k():
    """A 10 g plank 2 m long held by its tip weighs ~1.4 g across the lever arm: uncapped, the
    grab's damping would put the step far past the stability bound (h²ω² + 2hγ < 4 in the
    lightest direction); capped, it stays stable, and the tip hangs m·g/k below the cursor
    (k the gain at the substep h the world applies its forces over: the soft step's dt/4, so
    dt = 4/30 s gives h = 1/30 s)."""
    mass = 0.01
    h = 1 / 30
    dt = h * pm.SolverSettings().soft_substeps
    world = pm.World(gravity=(0.0, -9.81, 0.0))
    world.add_body(Box((1.0, 0.02, 0.1)), (0.0, 1.0, 0.0), mass=mass)
    spring = world.add(BodyPull(0, (1.0, 0.02, 0.1), (3.0, 2.0, 0.0)))
    light = point_mass(1 / mass, world.bodies.inv_inertia_world[0], *spring.arm(world.bodies))
    k_free, c_free = mass * spring.omega**2, 2 * spring.omega * mass
    assert (h * h * k_free + 2 * h * c_free) / light > 4.0
    for _ in range(600):
        world.step(dt)
    assert np.isfinite(world.bodies.position).all()
    k, _c = spring.gains(world.bodies, h)
    sag = spring.target - spring.point_of(world.bodies)
    assert sag[1] == pytest.approx(mass * 9.81 / k, rel=1e-3)
    assert abs(sag[0]) < 1e-4 and abs(sag[2]) < 1e-4


def test_largest_eigenvalue_matches_numpy():
    rng = np.random.default_rng(5)
    for _ in range(200):
        a = rng.normal(size=(3, 3))
        a = a + a.T
        want = np.linalg.eigvalsh(a)[-1]
        got = largest_eigenvalue(a[0, 0], a[0, 1], a[0, 2], a[1, 1], a[1, 2], a[2, 2])
        assert got == pytest.approx(want, abs=1e-10)
    assert largest_eigenvalue(1.0, 0.0, 0.0, 3.0, 0.0, 2.0) == 3.0


def test_bad_parameters_are_named():
    with pytest.raises(ValueError, match="omega"):
        BodyPull(0, (0, 0, 0), (0, 0, 0), omega=0.0)
    with pytest.raises(ValueError, match="zeta"):
        BodyPull(0, (0, 0, 0), (0, 0, 0), zeta=-1.0)
    with pytest.raises(ValueError, match="target"):
        BodyPull(0, (0, 0, 0), (0, math.nan, 0))
    world = pm.World()
    with pytest.raises((IndexError, ValueError), match="index"):
        world.add(BodyPull(3, (0, 0, 0), (0, 0, 0)))
