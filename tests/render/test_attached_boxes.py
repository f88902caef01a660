"""BoxVisual.attach: a box drawn in a body's coordinates lands where the body carries it (no GL)."""

from __future__ import annotations

import numpy as np

import pointmass as pm
from pointmass import BoxVisual
from pointmass.rigid.bodies import world_rotation
from pointmass.rigid.quaternion import quat_from_axis_angle
from pointmass.rigid.shapes import Box


def test_an_attached_box_follows_the_body_point_and_turns_with_it():
    world = pm.World()
    body = world.add_body(Box((1.0, 0.2, 0.3)), (1.0, 2.0, 3.0),
                          quat_from_axis_angle((0.0, 1.0, 0.0), np.pi / 2))
    wing = BoxVisual(half_size=(0.1, 0.05, 2.0))
    wing.attach(body, (0.0, 0.0, 2.0))
    # a quarter turn about y takes body +z to world +x
    assert np.allclose(wing.center, (3.0, 2.0, 3.0), atol=1e-12)
    assert np.allclose(wing.rotation, world_rotation(body.orientation), atol=1e-15)
    flip = np.diag([1.0, -1.0, -1.0])
    wing.attach(body, (0.0, 1.0, 0.0), flip)
    assert np.allclose(wing.center, (1.0, 3.0, 3.0), atol=1e-12)
    assert np.allclose(wing.rotation, world_rotation(body.orientation) @ flip, atol=1e-15)
    body.position = (0.0, 0.0, 0.0)
    wing.attach(body, (0.0, 0.0, 2.0))
    assert np.allclose(wing.center, (2.0, 0.0, 0.0), atol=1e-12)
