"""The renderer on EGL: output shape and orientation, options, resize, MSAA, no GL errors."""

from __future__ import annotations

import numpy as np
import pytest

import pointmass as pm

pytestmark = pytest.mark.gl


@pytest.fixture
def renderer(ctx):
    from pointmass.render import Renderer

    r = Renderer(ctx, (160, 120))
    yield r
    r.release()


def _cam(scene):
    from pointmass.render import OrbitCamera

    return OrbitCamera.from_hint(scene.camera)


def _one_ball(color=(1.0, 0.0, 0.0)):
    world = pm.World()
    world.add_particle((0.0, 1.0, 0.0), radius=0.6)
    return pm.Scene(world, colors=np.array([color]),
                    camera=pm.CameraHint(target=(0, 1, 0), distance=4, yaw=0, pitch=0))


def test_read_rgb_shape_and_centre_pixel(renderer):
    """A red ball at the target fills the image centre; the top row is sky (darker)."""
    scene = _one_ball()
    renderer.render(scene, _cam(scene))
    rgb = renderer.read_rgb()
    assert rgb.shape == (120, 160, 3) and rgb.dtype == np.uint8
    r, g, b = rgb[60, 80].astype(int)
    assert r > 120 and r > 2 * g and r > 2 * b
    assert renderer.fbo.size == (160, 120) and renderer.color_texture.components == 4


def test_image_is_top_row_first(renderer):
    """A ball above the target appears in the upper half of the image."""
    scene = _one_ball()
    scene.world.particles.position[0] = (0.0, 2.0, 0.0)
    scene.world.particles.radius[0] = 0.3
    renderer.render(scene, _cam(scene))
    red = renderer.read_rgb()[..., 0].astype(int) - renderer.read_rgb()[..., 2]
    rows = np.nonzero((red > 80).any(axis=1))[0]
    assert rows.size and rows.mean() < 60


def test_hidden_particles_are_not_drawn(renderer):
    scene = _one_ball()
    scene.hidden = np.array([True])
    renderer.render(scene, _cam(scene))
    r, g, _ = renderer.read_rgb()[60, 80].astype(int)
    assert not (r > 120 and r > 2 * g)


def test_contacts_extra_lines_trails_and_points(renderer, ctx):
    """Every optional layer draws without GL errors, and extra lines show up."""
    world = pm.World()
    a = world.add_particle((0.0, 0.5, 0.0), radius=0.5)
    world.add_particle((0.0, 2.0, 0.0))     # a point particle (drawn with point_radius)
    world.add(pm.Ground())
    world.add(pm.AnchoredRod(a, (1.0, 2.0, 0.0), 1.0))
    scene = pm.Scene(world, trails=[a],
                     camera=pm.CameraHint(target=(0, 1, 0), distance=5, yaw=0, pitch=10))
    sim = pm.Simulation(scene)
    sim.advance(0.2)
    assert len(sim.trails.points(a)) >= 2
    renderer.render(scene, _cam(scene), trails=sim.trails, show_contacts=True,
                    extra_lines=[((-2.0, 2.2, 0.0), (-0.8, 2.2, 0.0), (0.0, 1.0, 0.0))])
    rgb = renderer.read_rgb().astype(int)
    green = (rgb[..., 1] > 150) & (rgb[..., 0] < 80) & (rgb[..., 2] < 80)
    assert green.sum() > 50
    assert ctx.error == "GL_NO_ERROR"


def test_resize_and_many_particles_grow_buffers(renderer):
    renderer.resize((97, 55))
    world = pm.World()
    rng = np.random.default_rng(1)
    world.add_particles(rng.uniform(-3, 3, (5000, 3)) + np.array([0, 3, 0]), radii=0.05)
    scene = pm.Scene(world)
    renderer.render(scene, _cam(scene))
    assert renderer.read_rgb().shape == (55, 97, 3)
    with pytest.raises(ValueError):
        renderer.resize((0, 10))


def test_msaa_resolves_into_fbo(ctx):
    from pointmass.render import Renderer

    r = Renderer(ctx, (64, 48), samples=4)
    scene = _one_ball()
    r.render(scene, _cam(scene))
    assert r.read_rgb()[24, 32, 0] > 120
    r.release()


def test_rigid_bodies_are_drawn_where_the_camera_projects_them(renderer):
    """A box body and a sphere body (with its spin markers) show in their colors at the pixels
    their centres project to; turning the sphere moves its markers."""
    from pointmass.render import bodies as body_visuals
    from pointmass.rigid.quaternion import quat_from_axis_angle
    from pointmass.rigid.shapes import Box, Sphere

    world = pm.World(gravity=(0, 0, 0))
    world.add_body(Box((0.4, 0.4, 0.4)), (-0.8, 1.0, 0.0))
    ball = world.add_body(Sphere(0.4), (0.8, 1.0, 0.0))
    scene = pm.Scene(world, show_ground=False,
                     camera=pm.CameraHint(target=(0, 1, 0), distance=5, yaw=0, pitch=0))
    camera = _cam(scene)
    renderer.render(scene, camera)
    rgb = renderer.read_rgb().astype(int)
    (bx, by), (sx, sy) = camera.project(world.bodies.position, renderer.size).round().astype(int)
    r, g, b = rgb[by, bx]
    assert r > g > b and r > 100, rgb[by, bx]            # the warm box palette
    r, g, b = rgb[sy + 4, sx]                            # beside the +z marker facing us
    assert b > r and b > 100, rgb[sy + 4, sx]            # the blue sphere
    _, markers = body_visuals.sphere_rows(world.bodies, 8)
    ball.orientation = quat_from_axis_angle(np.array([0.0, 1.0, 0.0]), 1.0)
    _, turned = body_visuals.sphere_rows(world.bodies, 8)
    assert not np.allclose(markers[:, :3], turned[:, :3])
