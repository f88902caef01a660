"""The contact overlay for rigid bodies: where the manifold points are (no GL), and where they
land in the picture (EGL)."""

from __future__ import annotations

import math

import numpy as np
import pytest

import pointmass as pm
from pointmass.render import manifolds
from pointmass.rigid.collide import SPECULATIVE_MARGIN
from pointmass.rigid.quaternion import quat_from_axis_angle
from pointmass.rigid.shapes import Box

HALF = 0.5


def _resting_box(turn_deg: float = 30.0, seconds: float = 0.5) -> pm.Scene:
    """A unit box turned about y, settled on the ground."""
    world = pm.World(gravity=(0.0, -9.81, 0.0))
    world.add(pm.Ground())
    q = quat_from_axis_angle(np.array([0.0, 1.0, 0.0]), math.radians(turn_deg))
    world.add_body(Box((HALF, HALF, HALF)), (0.0, HALF, 0.0), q, mass=1.0)
    scene = pm.Scene(world, camera=pm.CameraHint(target=(0.0, 0.3, 0.0), distance=4.0,
                                                 yaw=20.0, pitch=35.0))
    for _ in range(round(seconds * 60)):
        world.step(1 / 60)
    return scene


def _bottom_corners(world) -> np.ndarray:
    b = world.bodies
    from pointmass.rigid.bodies import world_rotation

    rot = world_rotation(b.orientation[0])
    local = np.array([(sx, -HALF, sz) for sx in (-HALF, HALF) for sz in (-HALF, HALF)])
    return b.position[0] + local @ rot.T


def _matches(points: np.ndarray, corners: np.ndarray, tol: float) -> bool:
    """Each corner has a point within ``tol`` [m] and each point a corner."""
    d = np.linalg.norm(points[:, None, :] - corners[None, :, :], axis=2)
    return bool((d.min(axis=0) < tol).all() and (d.min(axis=1) < tol).all())


def test_a_resting_box_has_one_manifold_of_four_points_at_its_bottom_corners():
    scene = _resting_box()
    points, normals, depth, manifold, scale = manifolds.contact_points(scene.world)
    assert len(points) == 4 and (manifold == 0).all()
    assert _matches(points, _bottom_corners(scene.world), 1e-3)
    np.testing.assert_allclose(normals, np.tile([0.0, 1.0, 0.0], (4, 1)), atol=1e-9)
    assert (np.abs(depth) < 1e-3).all()                       # resting: touching, shallow
    np.testing.assert_allclose(scale, HALF)
    rows = np.concatenate(manifolds.manifold_lines(scene.world, 1.0))
    # an outline of 4 edges, 4 normals, 4 rimmed dots (rim and dot)
    assert len(rows) == 4 + 4 + 8
    assert (rows[:, 9] > 0.5).all()                           # none dimmed


def test_two_stacked_boxes_give_two_manifolds_and_the_top_ones_are_on_the_lower_box():
    world = pm.World(gravity=(0.0, -9.81, 0.0))
    world.add(pm.Ground())
    for k in range(2):
        world.add_body(Box((HALF, HALF, HALF)), (0.0, HALF + 2 * HALF * k, 0.0), mass=1.0)
    for _ in range(30):
        world.step(1 / 60)
    points, _normals, depth, manifold, _ = manifolds.contact_points(world)
    assert manifold.max() == 1 and len(points) == 8 and (np.abs(depth) < 1e-3).all()
    heights = np.sort(points[:, 1])
    np.testing.assert_allclose(heights[:4], 0.0, atol=1e-3)
    np.testing.assert_allclose(heights[4:], 2 * HALF, atol=1e-3)


def test_speculative_points_are_dimmer():
    """A box half the speculative margin above the ground, at rest, in zero gravity: its
    points are a gap inside the margin (depth −gap), drawn at the speculative alpha."""
    gap = 0.5 * SPECULATIVE_MARGIN
    world = pm.World(gravity=(0.0, 0.0, 0.0))
    world.add(pm.Ground())
    world.add_body(Box((HALF, HALF, HALF)), (0.0, HALF + gap, 0.0), mass=1.0)
    world.step(1 / 60)
    _points, _normals, depth, _, _ = manifolds.contact_points(world)
    assert len(depth) == 4
    np.testing.assert_allclose(depth, -gap, atol=1e-9)
    rows = manifolds.manifold_lines(world, 1.0)
    normals, dots = rows[1], rows[3]
    assert (normals[:, 9] == manifolds.SPECULATIVE_ALPHA).all()
    assert (dots[:, 9] == manifolds.SPECULATIVE_ALPHA).all()


def test_no_bodies_no_rows():
    assert manifolds.manifold_lines(pm.World(), 1.0) == []


@pytest.mark.gl
def test_contact_dots_of_a_resting_box_are_drawn_at_its_projected_corners(ctx):
    """Render with and without the overlay: at each bottom corner, projected through the
    camera, the overlay's pixel is the contact color; away from the corners nothing changed
    but the normals and outlines."""
    from pointmass.render import OrbitCamera, Renderer
    from pointmass.render.style import CONTACT_COLOR

    scene = _resting_box()
    size = (480, 320)
    camera = OrbitCamera.from_hint(scene.camera)
    r = Renderer(ctx, size)
    try:
        r.render(scene, camera, show_contacts=False)
        plain = r.read_rgb().astype(int)
        r.render(scene, camera, show_contacts=True)
        shown = r.read_rgb().astype(int)
    finally:
        r.release()
    want = np.array(CONTACT_COLOR) * 255
    corners = camera.project(_bottom_corners(scene.world), size)
    for px, py in corners:
        assert 0 <= px < size[0] and 0 <= py < size[1]
        x, y = int(px), int(py)
        assert np.abs(shown[y, x] - want).max() < 40, (x, y, shown[y, x])
        assert np.abs(plain[y, x] - want).max() > 60          # the box or ground is not yellow
    changed = np.abs(shown - plain).max(axis=2) > 30
    assert changed.mean() < 0.02                              # the overlay is small marks
