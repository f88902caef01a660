"""A Scene made without a camera keeps what it draws in view (``CameraHint.keep_in_view``).

The README's first world — a 1 kg ball launched at 30 m/s on a spring to a 20 kg one — is
projected through the camera a bare ``pm.Scene(world)`` gets, into the 3D view a window first
shows (1280 × 720 with the panel open), at 2, 5 and 10 s. Pure camera math: no GL needed.
"""

from __future__ import annotations

import numpy as np
import pytest

import pointmass as pm
from pointmass.render.camera import OrbitCamera

#: The 3D view beside the panel in a 1280 × 720 window, and the whole window.
VIEWS = [(1280 - 376, 720), (1280, 720)]


def first_world() -> pm.World:
    """The README's first world, as written there."""
    world = pm.World(gravity=(0, -9.81, 0))
    a = world.add_particle(position=(0, 2, 0), velocity=(0, 10, 30), mass=1.0, radius=0.5)
    b = world.add_particle(position=(2, 2, 2), mass=20.0, radius=0.5)
    world.add(pm.Spring(a, b, spring_constant=100.0, rest_length=2.0))
    world.add(pm.Drag(k1=0.1, k2=0.1))
    world.add(pm.Ground(height=0.0, restitution=0.5))
    world.add(pm.SphereCollisions(restitution=0.5))
    return world


def in_view(camera: OrbitCamera, points: np.ndarray, size) -> np.ndarray:
    """Which points are ahead of the eye and project inside the ``size`` view."""
    px = camera.project(points, size)
    ahead = (points - camera.eye) @ camera.forward > 0
    return ahead & (px[:, 0] >= 0) & (px[:, 0] <= size[0]) & (px[:, 1] >= 0) & \
        (px[:, 1] <= size[1])


def _run(keep: bool):
    sim = pm.Simulation(pm.Scene(first_world()))
    hint = sim.scene.camera
    assert hint.keep_in_view
    camera = OrbitCamera.from_hint(hint)
    camera.keep_in_view = keep
    seen = {}
    for t in (2.0, 5.0, 10.0):
        sim.advance(t - sim.time)
        camera.track(sim.scene)
        points = sim.world.particles.position.copy()
        seen[t] = (points, [in_view(camera, points, size) for size in VIEWS])
    return seen


def test_the_first_world_stays_in_view_at_2_5_and_10_seconds():
    """Both particles are in the default view at 2, 5 and 10 s, in the window's 3D view and in
    a full 1280 × 720 picture; they have travelled far from where the camera first looked."""
    seen = _run(keep=True)
    for t, (points, inside) in seen.items():
        for size, ok in zip(VIEWS, inside):
            assert ok.all(), f"t = {t} s, view {size}: particles at {points.round(2)} in view {ok}"
    start = np.array([[0.0, 2.0, 0.0], [2.0, 2.0, 2.0]])
    assert np.linalg.norm(seen[10.0][0] - start, axis=1).min() > 5.0


def test_without_keeping_them_in_view_the_first_world_leaves_the_view():
    """The check has teeth: the same camera left where it started (the old default) loses at
    least one of the two particles by 10 s."""
    seen = _run(keep=False)
    _, inside = seen[10.0]
    assert not inside[0].all()


def test_keeping_in_view_only_backs_away_and_is_off_for_a_demos_own_camera():
    """The distance never shrinks (no pumping as things bounce), and a scene given a camera
    (every demo's) keeps a fixed one unless it asks."""
    sim = pm.Simulation(pm.Scene(first_world()))
    camera = OrbitCamera.from_hint(sim.scene.camera)
    distances = []
    for _ in range(60):
        sim.advance(1 / 6)
        camera.track(sim.scene)
        distances.append(camera.distance)
    assert np.all(np.diff(distances) >= 0)
    own = pm.Scene(first_world(), camera=pm.CameraHint(target=(0, 1, 0), distance=8))
    assert not own.camera.keep_in_view
    assert not OrbitCamera.from_hint(own.camera).keep_in_view


@pytest.mark.parametrize("follow", ["follow", "follow_body"])
def test_following_one_thing_wins_over_keeping_all_in_view(follow):
    """A hint that follows a particle (or body) looks at it, not at the centre of everything."""
    world = first_world()
    world.add_body(pm.Sphere(0.2), (5.0, 1.0, 0.0))
    hint = pm.CameraHint(keep_in_view=True, **{follow: 1 if follow == "follow" else 0})
    camera = OrbitCamera.from_hint(hint)
    camera.track(pm.Scene(world, camera=hint))
    want = world.particles.position[1] if follow == "follow" else world.bodies.position[0]
    assert np.allclose(camera.target, want)
