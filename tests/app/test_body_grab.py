"""Grabbing a rigid body with the mouse, without a window (camera math and the controls; the
spring's physics is tested in tests/physics/test_body_pull.py, a real window in
tests/app/test_body_window.py)."""

from __future__ import annotations

import math

import numpy as np
import pytest

import pointmass as pm
from pointmass.app.body_spring import BodyMouseSpring, grab_body
from pointmass.app.mouse import MouseControls
from pointmass.render import OrbitCamera, pick
from pointmass.rigid.shapes import Box, Sphere

SIZE = (800, 500)
CUBE = (0.5, 0.5, 0.5)


def _free_cube(mass: float = 1.0) -> pm.World:
    world = pm.World(gravity=(0.0, 0.0, 0.0))
    world.add_body(Box(CUBE), (0.0, 0.0, 0.0), mass=mass)
    return world


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


def test_double_click_on_a_body_focuses_on_its_centre():
    sim, controls, _ = _tower()
    controls.clock = lambda: 100.0
    sim.press = lambda key: True                  # the demo's CLICK would throw a ball
    body = sim.world.bodies.count - 2
    centre = sim.world.bodies.position[body].copy()
    x, y = controls.camera.project((centre + np.array([0.2, 0.1, 0.0]))[None], SIZE)[0]
    for _ in range(2):
        controls.press(x, y, "left")
        controls.release(x, y, "left")
    np.testing.assert_allclose(controls.camera.target, centre)
