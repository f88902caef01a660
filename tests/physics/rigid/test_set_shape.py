"""Bodies.set_shape gives a body the mass properties of its new solid (a block breaking into
pieces); compound_boxes sums glued boxes with the parallel-axis theorem (eight octants are the
whole block; an L shape matches a sampled integral); bad input is named."""

import math

import numpy as np
import pytest

from pointmass.rigid.bodies import Bodies, world_rotation
from pointmass.rigid.quaternion import quat_from_axis_angle
from pointmass.rigid.shapes import BOX, SPHERE, Box, Sphere, compound_boxes


def test_set_shape_gives_the_new_solids_mass_and_inertia_and_keeps_the_motion():
    bodies = Bodies()
    q = quat_from_axis_angle((1.0, 2.0, 0.5), 0.7)
    i = bodies.add_box((1.0, 1.0, 1.0), (1.0, 2.0, 3.0), q, mass=8.0,
                       velocity=(1.0, -2.0, 0.5))
    bodies.angular_velocity[i] = (0.3, 0.1, -0.2)
    bodies.set_shape(i, Box((0.5, 0.25, 1.0)), mass=1.0)
    assert bodies.shape[i] == BOX and np.array_equal(bodies.size[i], (0.5, 0.25, 1.0))
    assert bodies.inv_mass[i] == 1.0
    moments = np.array([0.25**2 + 1.0, 0.5**2 + 1.0, 0.5**2 + 0.25**2]) / 3.0
    assert np.allclose(bodies.inv_inertia[i], 1.0 / moments, rtol=1e-14)
    r = world_rotation(bodies.orientation[i])
    assert np.allclose(bodies.inv_inertia_world[i], r @ np.diag(1.0 / moments) @ r.T,
                       atol=1e-14)
    assert np.array_equal(bodies.position[i], (1.0, 2.0, 3.0))
    assert np.array_equal(bodies.velocity[i], (1.0, -2.0, 0.5))
    assert np.array_equal(bodies.angular_velocity[i], (0.3, 0.1, -0.2))


def test_set_shape_by_density_and_to_a_sphere():
    bodies = Bodies()
    i = bodies.add_box((1.0, 1.0, 1.0), mass=8.0)
    bodies.set_shape(i, Sphere(0.5), density=1000.0)
    mass = 1000.0 * 4.0 / 3.0 * math.pi * 0.125
    assert bodies.shape[i] == SPHERE and bodies.size[i, 0] == 0.5
    assert 1.0 / bodies.inv_mass[i] == pytest.approx(mass, rel=1e-14)
    assert np.allclose(1.0 / bodies.inv_inertia[i], 0.4 * mass * 0.25, rtol=1e-14)


@pytest.mark.parametrize(("args", "kwargs", "error", "message"), [
    ((3, Box((1, 1, 1))), {"mass": 1.0}, IndexError, "body: 3 is not a body"),
    ((0, "box"), {"mass": 1.0}, TypeError, "shape must be a Sphere or a Box"),
    ((0, Box((1, 1, 1))), {"mass": -1.0}, ValueError, "mass"),
    ((0, Box((1, 1, 1))), {"mass": 1.0, "density": 2.0}, ValueError, "exactly one"),
    ((0, Box((1, 1, 1))), {"density": math.nan}, ValueError, "density"),
])
def test_set_shape_refuses_bad_input_by_name(args, kwargs, error, message):
    bodies = Bodies()
    bodies.add_box((1.0, 1.0, 1.0), mass=8.0)
    before = bodies.snapshot()
    with pytest.raises(error, match=message):
        bodies.set_shape(*args, **kwargs)
    for name, arr in before.items():
        assert np.array_equal(getattr(bodies, name), arr), name


def test_eight_octants_are_the_whole_block():
    half = np.array([4.0, 2.0, 1.0])
    octants = [(np.array(s) * half / 2, half / 2) for s in
               [(x, y, z) for x in (-1, 1) for y in (-1, 1) for z in (-1, 1)]]
    centre, tensor = compound_boxes(octants, 100.0)
    assert np.allclose(centre, 0.0, atol=1e-15)
    assert np.allclose(tensor, np.diag(100.0 * Box(tuple(half)).unit_inertia()), rtol=1e-14,
                       atol=1e-12)


def test_an_l_shape_matches_a_sampled_integral():
    """Off-diagonal terms: an L of two boxes against the tensor summed over a fine grid of
    equal point masses filling them (midpoint rule, error O(h²))."""
    parts = [((0.0, 0.0, 0.0), (1.0, 0.25, 0.25)), ((0.75, 0.75, 0.0), (0.25, 0.5, 0.25))]
    centre, tensor = compound_boxes(parts, 3.0)
    points = []
    for c, h in parts:
        n = np.maximum(np.round(np.array(h) * 80).astype(int), 1)
        axes = [c[k] - h[k] + (np.arange(n[k]) + 0.5) * 2 * h[k] / n[k] for k in range(3)]
        grid = np.stack(np.meshgrid(*axes, indexing="ij"), -1).reshape(-1, 3)
        points.append(grid)
    pts = np.vstack(points)  # every cell the same volume (1/80 m cells)
    m = 3.0 / len(pts)
    com = pts.mean(axis=0)
    r = pts - com
    sampled = m * ((r * r).sum(1).sum() * np.eye(3) - r.T @ r)
    assert np.allclose(centre, com, atol=1e-12)
    assert abs(tensor[0, 1]) > 0.1 * tensor[0, 0]
    assert np.allclose(tensor, sampled, rtol=1e-3, atol=1e-4 * np.abs(tensor).max())


@pytest.mark.parametrize(("parts", "mass", "message"), [
    ([], 1.0, "at least one"),
    ([((0, 0, 0), (1, 1, 1))], 0.0, "mass"),
    ([((0, 0), (1, 1, 1))], 1.0, "part centre"),
    ([((0, 0, 0), (1, -1, 1))], 1.0, "half_extents"),
])
def test_compound_boxes_refuses_bad_input_by_name(parts, mass, message):
    with pytest.raises(ValueError, match=message):
        compound_boxes(parts, mass)
