"""Orbit camera math, without GL."""

from __future__ import annotations

import numpy as np
import pytest

pytest.importorskip("pyrr")

from pointmass import CameraHint
from pointmass.render.camera import OrbitCamera

SIZE = (640, 480)


def test_target_projects_to_the_image_centre():
    """The point looked at lands in the middle of the image."""
    cam = OrbitCamera(target=np.array([1.0, 2.0, 3.0]), distance=7.0, yaw=40.0, pitch=25.0)
    assert np.allclose(cam.project([cam.target], SIZE), [[320.0, 240.0]], atol=1e-6)


def test_eye_is_distance_from_target_at_yaw_and_pitch():
    """yaw 0 / pitch 0 puts the eye on +z; pitch lifts it; distance is kept."""
    cam = OrbitCamera(target=np.zeros(3), distance=5.0, yaw=0.0, pitch=0.0)
    assert np.allclose(cam.eye, [0.0, 0.0, 5.0])
    cam = OrbitCamera(target=np.zeros(3), distance=5.0, yaw=90.0, pitch=30.0)
    assert np.allclose(cam.eye, [5 * np.cos(np.radians(30)), 5 * np.sin(np.radians(30)), 0.0])
    assert np.isclose(np.linalg.norm(cam.eye - cam.target), 5.0)


def test_projection_of_known_points():
    """A point one unit right of the target at yaw 0 lands right of centre by f·1/d pixels."""
    cam = OrbitCamera(target=np.zeros(3), distance=10.0, yaw=0.0, pitch=0.0, fov=90.0)
    w, h = SIZE
    focal = (h / 2) / np.tan(np.radians(45.0))   # pixels per unit at unit depth
    px = cam.project([[1.0, 0.0, 0.0], [0.0, 1.0, 0.0]], SIZE)
    assert np.allclose(px[0], [w / 2 + focal / 10.0, h / 2], atol=1e-4)
    assert np.allclose(px[1], [w / 2, h / 2 - focal / 10.0], atol=1e-4)   # up is smaller y


def test_ray_through_the_centre_hits_the_target():
    """The ray through the middle pixel starts at the eye and passes through the target."""
    cam = OrbitCamera(target=np.array([0.5, 1.0, -2.0]), distance=4.0, yaw=-70.0, pitch=35.0)
    origin, direction = cam.ray(320.0, 240.0, SIZE)
    assert np.allclose(origin, cam.eye)
    assert np.isclose(np.linalg.norm(direction), 1.0)
    assert np.allclose(origin + direction * cam.distance, cam.target, atol=1e-6)


def test_ray_and_project_are_inverse():
    """A point on the ray through a pixel projects back to that pixel."""
    cam = OrbitCamera(target=np.zeros(3), distance=6.0, yaw=15.0, pitch=10.0)
    origin, direction = cam.ray(100.0, 400.0, SIZE)
    assert np.allclose(cam.project([origin + 3.0 * direction], SIZE), [[100.0, 400.0]],
                       atol=1e-4)


def test_orbit_clamps_pitch_and_wraps_yaw():
    """Pitch stays inside (-89, 89) degrees; yaw wraps to [0, 360)."""
    cam = OrbitCamera()
    cam.orbit(350.0, 500.0)
    assert cam.pitch == 89.0
    assert 0.0 <= cam.yaw < 360.0
    cam.orbit(0.0, -1000.0)
    assert cam.pitch == -89.0


def test_zoom_scales_and_clamps_distance():
    """zoom multiplies the distance, within [min_distance, max_distance]; factor must be > 0."""
    cam = OrbitCamera(distance=10.0)
    cam.zoom(0.5)
    assert cam.distance == 5.0
    cam.zoom(1e-9)
    assert cam.distance == cam.min_distance
    cam.zoom(1e12)
    assert cam.distance == cam.max_distance
    with pytest.raises(ValueError):
        cam.zoom(0.0)


def test_pan_moves_target_in_the_view_plane_and_focus_sets_it():
    """Panning right moves the target along the camera's right vector, scaled by distance."""
    cam = OrbitCamera(target=np.zeros(3), distance=4.0, yaw=0.0, pitch=0.0)
    cam.pan(0.5, 0.0)
    assert np.allclose(cam.target, [2.0, 0.0, 0.0])
    cam.pan(0.0, 0.25)
    assert np.allclose(cam.target, [2.0, 1.0, 0.0])
    cam.focus((1, 2, 3))
    assert np.allclose(cam.target, [1, 2, 3])


def test_from_hint_and_matrices():
    """A CameraHint sets the pose; matrices are (4, 4) float32 and compose."""
    hint = CameraHint(target=(1.0, 2.0, 3.0), distance=12.0, yaw=10.0, pitch=5.0, fov=60.0)
    cam = OrbitCamera.from_hint(hint)
    assert np.allclose(cam.target, hint.target) and cam.distance == 12.0 and cam.fov == 60.0
    view, proj = cam.view_matrix(), cam.projection_matrix(1.5)
    assert view.shape == proj.shape == (4, 4) and view.dtype == np.float32
    assert np.allclose(cam.view_projection(1.5), view @ proj)
    eye_h = np.r_[cam.eye, 1.0] @ view
    assert np.allclose(eye_h[:3], 0.0, atol=1e-4)     # the eye is the origin of eye space


def test_track_keeps_the_followed_particle_at_the_target():
    """A camera hint that follows a particle puts the target on it, wherever it goes."""
    from pointmass import Scene, World

    world = World()
    world.add_particle((0.0, 0.0, 0.0))
    ball = world.add_particle((3.0, 4.0, -2.0))
    scene = Scene(world, camera=CameraHint(target=(0.0, 1.0, 0.0), follow=ball))
    cam = OrbitCamera.from_hint(scene.camera)
    yaw, distance = cam.yaw, cam.distance
    cam.track(scene)
    assert np.array_equal(cam.target, [3.0, 4.0, -2.0])
    world.particles.position[ball] = (5.0, 1.0, 0.0)
    cam.track(scene)
    assert np.array_equal(cam.target, [5.0, 1.0, 0.0])
    assert (cam.yaw, cam.distance) == (yaw, distance)
    scene.camera.follow = None
    cam.track(scene)
    assert np.array_equal(cam.target, [5.0, 1.0, 0.0])


def test_track_keeps_the_followed_body_at_the_target():
    """``follow_body`` does for a rigid body what ``follow`` does for a particle."""
    from pointmass import Scene, World
    from pointmass.rigid.shapes import Box

    world = World()
    world.add_body(Box((0.5, 0.5, 0.5)), (0.0, 0.0, 0.0))
    plane = world.add_body(Box((1.0, 0.2, 0.3)), (2.0, 3.0, 1.0))
    scene = Scene(world, camera=CameraHint(target=(0.0, 1.0, 0.0), follow_body=plane.index))
    cam = OrbitCamera.from_hint(scene.camera)
    cam.track(scene)
    assert np.array_equal(cam.target, [2.0, 3.0, 1.0])
    plane.position = (7.0, 8.0, -1.0)
    cam.track(scene)
    assert np.array_equal(cam.target, [7.0, 8.0, -1.0])


def test_a_scene_without_a_camera_hint_frames_its_particles():
    """The README's first script: after 600 steps its particles are ~9 m down the z axis; a
    Scene made without a CameraHint looks at them, and they project inside the view, neither
    lost nor filling it."""
    import pointmass as pm

    world = pm.World(gravity=(0, -9.81, 0))
    a = world.add_particle(position=(0, 2, 0), velocity=(0, 10, 30), mass=1.0, radius=0.5)
    b = world.add_particle(position=(2, 2, 2), mass=20.0, radius=0.5)
    world.add(pm.Spring(a, b, spring_constant=100.0, rest_length=2.0))
    world.add(pm.Drag(k1=0.1, k2=0.1))
    world.add(pm.Ground(height=0.0, restitution=0.5))
    world.add(pm.SphereCollisions(restitution=0.5))
    for _ in range(600):
        world.step(1 / 60)
    scene = pm.Scene(world)
    camera = OrbitCamera.from_hint(scene.camera)
    size = (1280, 720)
    pts = camera.project(world.particles.position, size)
    assert ((pts[:, 0] > 0.2 * size[0]) & (pts[:, 0] < 0.8 * size[0])).all(), pts
    assert ((pts[:, 1] > 0.2 * size[1]) & (pts[:, 1] < 0.8 * size[1])).all(), pts
    # A hint still wins, and an empty world gets the default view (keeping in view what is
    # added later, as every Scene made without a hint does).
    hinted = pm.Scene(world, camera=pm.CameraHint(distance=3.0))
    assert hinted.camera.distance == 3.0
    assert pm.Scene(pm.World()).camera == pm.CameraHint(keep_in_view=True)
