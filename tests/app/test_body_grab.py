"""Grabbing a rigid body with the mouse: the spring at the clicked point, without a window
(physics and camera math only; tests/app/test_body_window.py drives a real window)."""

from __future__ import annotations

import math

import numpy as np
import pytest

import pointmass as pm
from pointmass.app.body_spring import BodyMouseSpring, grab_body, point_mass
from pointmass.app.mouse import MouseControls
from pointmass.render import OrbitCamera, pick
from pointmass.rigid.shapes import Box, Sphere

SIZE = (800, 500)
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
    world.add(BodyMouseSpring(0, (0.0, 0.0, 0.0), (1.0, 0.0, 0.0)))
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
    assert point_mass(world.bodies, 0, corner) == pytest.approx(1 / 5.5, rel=1e-12)
    assert point_mass(world.bodies, 0, np.zeros(3)) == pytest.approx(1.0, rel=1e-12)


def test_a_body_held_by_a_corner_turns_and_settles_with_the_corner_on_the_target():
    """Pulled by a corner, the cube turns (the force acts at the point) until the corner is
    on the target, and the grip stops it spinning: at rest, centre behind the corner."""
    world = _free_cube(1.0)
    corner = np.array(CUBE)
    spring = world.add(BodyMouseSpring(0, corner, corner + np.array([2.0, 0.0, 0.0])))
    turned = 0.0
    for _ in range(360):
        world.step(1 / 60)
        turned = max(turned, 2 * math.degrees(math.acos(min(1.0,
                                                             abs(world.bodies.orientation[0, 0])))))
    assert turned > 20.0
    np.testing.assert_allclose(spring.point(world), spring.target, atol=1e-3)
    assert np.abs(world.bodies.angular_velocity[0]).max() < 1e-2
    assert np.abs(world.bodies.velocity[0]).max() < 1e-2


def test_a_light_plank_held_by_its_end_stays_stable_and_hangs_by_m_g_over_k():
    """A 10 g plank 2 m long held by its tip weighs ~1.4 g across the lever arm: uncapped, the
    grab's damping would put the step far past the stability bound (h²ω² + 2hγ < 4 in the
    lightest direction); capped, it stays stable, and the tip hangs m·g/k below the cursor."""
    h, mass = 1 / 30, 0.01
    world = pm.World(gravity=(0.0, -9.81, 0.0))
    world.add_body(Box((1.0, 0.02, 0.1)), (0.0, 1.0, 0.0), mass=mass)
    spring = world.add(BodyMouseSpring(0, (1.0, 0.02, 0.1), (3.0, 2.0, 0.0)))
    light = point_mass(world.bodies, 0, spring.arm(world.bodies))
    k_free, c_free = mass * spring.omega**2, 2 * spring.omega * mass
    assert (h * h * k_free + 2 * h * c_free) / light > 4.0
    for _ in range(600):
        world.step(h)
    assert np.isfinite(world.bodies.position).all()
    k, _c = spring.gains(world.bodies, h)
    sag = spring.target - spring.point(world)
    assert sag[1] == pytest.approx(mass * 9.81 / k, rel=1e-3)
    assert abs(sag[0]) < 1e-4 and abs(sag[2]) < 1e-4


def _tower():
    sim = pm.Simulation("box_tower", overrides=["count=3"])
    sim.advance(0.25)
    camera = OrbitCamera.from_hint(sim.scene.camera)
    said = []
    return sim, MouseControls(camera, sim, lambda: SIZE, say=said.append), said


def test_ctrl_drag_on_a_box_grabs_it_at_the_point_clicked_and_release_lets_go():
    sim, controls, _ = _tower()
    world = sim.world
    top = world.bodies.count - 1
    x, y = controls.camera.project(world.bodies.position[top][None], SIZE)[0]
    x, y = x + 12, y - 9                            # off the centre: the grab turns it
    controls.press(x, y, "left", ctrl=True)
    grab = controls.grab
    assert controls.mode == "grab" and grab.kind == "body" and grab.index == top
    assert grab.spring in world.body_forces
    # the held point is on the box's surface, under the cursor
    local = grab.spring.local
    assert np.abs(local).max() == pytest.approx(0.5, abs=1e-9)
    assert (np.abs(local) <= 0.5 + 1e-9).all()
    assert controls.camera.project(grab.spring.point(world)[None], SIZE)[0] == \
        pytest.approx((x, y), abs=0.5)
    controls.drag(x + 60, y, 60, 0)
    assert controls.camera.project(grab.spring.target[None], SIZE)[0] == \
        pytest.approx((x + 60, y), abs=0.5)
    start, end, _ = controls.extra_lines()[0]
    np.testing.assert_allclose(start, grab.spring.point(world))
    np.testing.assert_allclose(end, grab.spring.target)
    controls.release(x + 60, y, "left")
    assert controls.grab is None and controls.extra_lines() == []
    assert not any(isinstance(f, BodyMouseSpring) for f in world.body_forces)


def test_a_static_body_is_not_grabbed_and_the_user_is_told():
    sim, controls, said = _tower()
    world = sim.world
    wall = world.add_body(Box((0.3, 0.3, 0.3)), (0.0, 5.0, 0.0), mass=math.inf)
    x, y = controls.camera.project(wall.position[None], SIZE)[0]
    controls.press(x, y, "left", ctrl=True)
    assert controls.grab is None and controls.mode is None
    assert said[-1] == f"body {wall.index} is fixed in place: it cannot be grabbed"
    assert not world.body_forces


def test_pick_takes_the_nearer_of_a_particle_and_a_body():
    world = pm.World()
    world.add_particle((0.0, 0.0, 2.0), radius=0.25)
    world.add_body(Sphere(0.5), (0.0, 0.0, 0.0))
    scene = pm.Scene(world)
    hit = pick(scene, (0.0, 0.0, 10.0), (0.0, 0.0, -1.0))
    assert (hit.kind, hit.index) == ("particle", 0)
    np.testing.assert_allclose(hit.point, (0.0, 0.0, 2.25))
    hit = pick(scene, (0.0, 0.0, -10.0), (0.0, 0.0, 1.0))
    assert (hit.kind, hit.index) == ("body", 0) and hit.distance == pytest.approx(9.5)
    assert pick(scene, (5.0, 5.0, 10.0), (0.0, 0.0, -1.0)) is None


def test_grab_body_keeps_the_clicked_point_in_body_coordinates():
    """The held point is fixed in the body: after the body turns it is still the same
    material point (R·local + x)."""
    world = _free_cube(2.0)
    world.bodies.angular_velocity[0] = (0.0, 3.0, 0.0)
    grab = grab_body(world, 0, (0.5, 0.1, -0.2), (0.0, 0.0, -1.0))
    np.testing.assert_allclose(grab.spring.local, (0.5, 0.1, -0.2))
    world.step(1 / 60)
    b = world.bodies
    assert np.linalg.norm(grab.spring.point(world) - b.position[0]) == \
        pytest.approx(np.linalg.norm((0.5, 0.1, -0.2)), rel=1e-12)
    grab.release()
    assert not world.body_forces
