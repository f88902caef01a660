"""Blob shadows lie under what casts them, seen through the demo's own camera: the sailboat's
boat floats on water 3 m above its ground, and its shadow used to be drawn on that ground,
far below the boat on screen."""

from __future__ import annotations

import numpy as np

from pointmass.demo import Simulation
from pointmass.render.camera import OrbitCamera
from pointmass.render.frame import FrameState
from pointmass.render.shadow_splat import shadow_map, shadow_region
from pointmass.render.shadows import shadow_casters

SIZE = (1280, 720)
TEXELS = 256


def shadow_centre(frame: FrameState) -> np.ndarray:
    """The darkness-weighted centre of the frame's blob shadows, in world coordinates."""
    casters = shadow_casters(frame, frame.spheres[: frame.particles])
    region = shadow_region(casters, frame.shadow_height, TEXELS)
    dark = shadow_map(casters, region, frame.shadow_height, 0.5, TEXELS)
    assert dark.sum() > 0, "nothing casts a shadow"
    i, j = np.indices(dark.shape)
    x0, z0, side = region
    x = x0 + (j + 0.5) * side / TEXELS
    z = z0 + (i + 0.5) * side / TEXELS
    w = dark / dark.sum()
    return np.array([(w * x).sum(), frame.shadow_height, (w * z).sum()])


def test_the_sailboat_shadow_is_on_the_water_under_the_boat():
    sim = Simulation("sailboat")
    sim.advance(1.0)
    frame = FrameState.capture(sim.scene)
    assert frame.shadow_height == 0.0          # the water, not the ground 3 m below
    boat = sim.scene.handles["boat"].position
    camera = OrbitCamera.from_hint(sim.scene.camera)
    camera.track(sim.scene)
    centre = shadow_centre(frame)
    # In the world: straight under the boat (the hulls straddle its centre).
    assert np.hypot(*(centre - boat)[[0, 2]]) < 0.3
    # On screen: just below the boat, not a third of the picture away.
    (bx, by), (sx, sy) = camera.project(np.array([boat, centre]), SIZE)
    assert abs(sx - bx) < 0.05 * SIZE[0], (bx, sx)
    assert 0.0 <= sy - by < 0.12 * SIZE[1], (by, sy)


def test_a_scene_without_water_casts_on_its_ground():
    sim = Simulation("box_tower")
    frame = FrameState.capture(sim.scene)
    assert frame.shadow_height == sim.scene.ground_height
