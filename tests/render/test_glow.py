"""Night sky, glowing particles and their trails (Scene.sky, Scene.glow) on EGL."""

from __future__ import annotations

import numpy as np
import pytest

import pointmass as pm

pytestmark = pytest.mark.gl

SIZE = (160, 120)


@pytest.fixture
def renderer(ctx):
    from pointmass.render import Renderer

    r = Renderer(ctx, SIZE)
    yield r
    r.release()


def _camera(scene):
    from pointmass.render import OrbitCamera

    return OrbitCamera.from_hint(scene.camera)


def _sparks(positions, *, glow=True, sky="night", color=(1.0, 0.5, 0.2)) -> pm.Scene:
    world = pm.World(gravity=(0.0, 0.0, 0.0))
    world.add_particles(np.asarray(positions, float))
    return pm.Scene(world, colors=np.tile(color, (len(positions), 1)), point_radius=0.1,
                    sky=sky, glow=glow,
                    camera=pm.CameraHint(target=(0, 2, 0), distance=8, yaw=20, pitch=10))


def _shot(renderer, scene, trails=None) -> np.ndarray:
    renderer.render(scene, _camera(scene), trails=trails)
    return renderer.read_rgb().astype(float)


def _ring(rgb, centre, inner, outer) -> float:
    """Mean brightness of the pixels between ``inner`` and ``outer`` px from ``centre``."""
    ys, xs = np.mgrid[: rgb.shape[0], : rgb.shape[1]]
    d = np.hypot(xs + 0.5 - centre[0], ys + 0.5 - centre[1])
    return float(rgb[(d >= inner) & (d < outer)].sum(axis=1).mean())


def test_glow_adds_light_around_the_particle_where_the_camera_projects_it(renderer):
    """Off the centre of a glowing particle (its halo, where a lit ball of that size does not
    reach) the image is brighter than with the same particle unlit, and its core is white-hot:
    its brightest channel saturated and the others well above the color's."""
    point = (0.3, 2.4, -0.2)
    lit, glowing = _sparks([point], glow=False), _sparks([point], glow=True)
    centre = _camera(glowing).project([point], SIZE)[0]
    plain, glow = _shot(renderer, lit), _shot(renderer, glowing)
    assert _ring(glow, centre, 3.0, 7.0) > _ring(plain, centre, 3.0, 7.0) + 30.0
    core = glow[int(centre[1]), int(centre[0])]
    assert core[0] == 255 and core[1] > 0.5 * 255 + 60 and core[2] > 0.2 * 255 + 60
    far = _ring(glow, centre, 20.0, 30.0) - _ring(plain, centre, 20.0, 30.0)
    assert abs(far) < 1.0, "the halo reaches too far"


def test_overlapping_glows_add_up_in_either_order(renderer):
    """Additive: two dim sparks at one place add twice the light of one to the sky (in their
    halo, below saturation), and two sparks drawn in either order give the same image."""
    a, b = (0.0, 2.0, 0.0), (0.05, 2.0, 0.0)
    dim = (0.3, 0.1, 0.05)
    sky = _sparks([a], color=dim)
    sky.hidden = np.array([True])
    centre = _camera(sky).project([a], SIZE)[0]
    background = _shot(renderer, sky)
    one = _shot(renderer, _sparks([a], color=dim)) - background
    two = _shot(renderer, _sparks([a, a], color=dim)) - background
    halo_one, halo_two = _ring(one, centre, 3.0, 7.0), _ring(two, centre, 3.0, 7.0)
    assert halo_one > 5.0 and halo_two == pytest.approx(2.0 * halo_one, rel=0.1)
    ab = _shot(renderer, _sparks([a, b], color=dim))
    ba = _shot(renderer, _sparks([b, a], color=dim))
    assert np.abs(ab - ba).max() <= 1.0


def test_glowing_particles_cast_no_shadow(renderer):
    """A ball just above the ground darkens the ground beside it with its blob shadow; the same
    ball glowing is a light, and no shadow is cast (its halo lights that ground instead)."""
    for glow in (False, True):
        world = pm.World(gravity=(0.0, 0.0, 0.0))
        world.add_particle((0.0, 0.4, 0.0), radius=0.3)
        scene = pm.Scene(world, glow=glow, camera=pm.CameraHint(target=(0, 0.5, 0), distance=4,
                                                                yaw=20, pitch=10))
        cam = _camera(scene)
        x, y = cam.project([0.33 * cam.right], SIZE)[0].astype(int)  # ground beside the ball
        near = _shot(renderer, scene)[y, x].sum()
        cast = renderer._shadows.region[2] > 0
        scene.hidden = np.array([True])
        bare = _shot(renderer, scene)[y, x].sum()
        assert cast != glow
        assert (near < bare - 10) if not glow else (near > bare + 10)


def test_a_glow_mask_picks_which_particles_glow(renderer):
    """Lit and glowing particles side by side: only the masked one is white-hot (a red
    glow's core has a blue channel far above what a lit red ball shows)."""
    points = [(-1.0, 2.0, 0.0), (1.0, 2.0, 0.0)]
    scene = _sparks(points, glow=np.array([True, False]), color=(0.9, 0.2, 0.1))
    rgb = _shot(renderer, scene)
    (xa, ya), (xb, yb) = _camera(scene).project(points, SIZE).astype(int)
    assert rgb[ya, xa][0] == 255 and rgb[ya, xa][2] > 130    # hot core
    assert rgb[yb, xb][0] > 120 and rgb[yb, xb][2] < 90       # lit red ball


def test_night_sky_is_dark_and_unknown_skies_are_refused(renderer):
    scene = pm.Scene(pm.World(), camera=pm.CameraHint(target=(0, 1, 0), distance=8, pitch=15))
    day = _shot(renderer, scene)
    scene.sky = "night"
    night = _shot(renderer, scene)
    assert night.mean() < 0.25 * day.mean()
    assert night[0].mean() < 10 and night[-1].mean() < 25   # the sky and the dimmed ground
    scene.sky = "dusk"
    with pytest.raises(ValueError, match=r"dusk.*day.*night"):
        _shot(renderer, scene)


def test_trails_of_live_glowing_particles_are_light_streaks(renderer):
    """A glowing particle's trail adds light along its path; a hidden one's is not drawn."""
    from pointmass.trails import Trails

    scene = _sparks([(-1.5, 2.0, 0.0)], color=(0.2, 0.6, 1.0))
    scene.trails, scene.trail_length = [0], 8
    trails = Trails()
    pos = scene.world.particles.position
    for k in range(8):                       # a path from x = -1.5 to x = 1.3, left to right
        pos[0] = (-1.5 + 0.4 * k, 2.0, 0.0)
        trails.record(scene)
    cam = _camera(scene)
    mid = cam.project([(-0.1, 2.0, 0.0)], SIZE)[0].astype(int)   # on the trail, off the head
    streak = _shot(renderer, scene, trails)[mid[1], mid[0]]
    scene.hidden = np.array([True])
    gone = _shot(renderer, scene, trails)[mid[1], mid[0]]
    assert streak[2] > gone[2] + 40 and streak[2] > streak[0]
