"""The rigid-body store: mass properties, forces at points, analytic motion, bad input."""

import math

import numpy as np
import pytest

from pointmass.rigid.bodies import Bodies
from pointmass.rigid.quaternion import quat_from_axis_angle, rotate
from pointmass.rigid.shapes import BOX, SPHERE, Box, Sphere, mass_properties
from pointmass.rigid.step import MAX_ROTATION, step


def test_mass_properties_of_sphere_and_box():
    m, inertia = mass_properties(Sphere(0.5), density=1000.0)
    assert m == pytest.approx(1000.0 * 4 / 3 * math.pi * 0.125)
    assert inertia == pytest.approx(np.full(3, 0.4 * m * 0.25))
    # a 2 x 4 x 6 m box of 48 kg: I_x = m(4² + 6²)/12 = 208
    m, inertia = mass_properties(Box((1.0, 2.0, 3.0)), mass=48.0)
    assert m == 48.0
    assert inertia == pytest.approx([208.0, 160.0, 80.0])
    m, inertia = mass_properties(Box((1.0, 1.0, 1.0)), density=math.inf)
    assert m == math.inf and np.all(np.isinf(inertia))


def test_store_grows_and_derives_world_inertia():
    bodies = Bodies(capacity=1)
    q = quat_from_axis_angle(np.array([0.0, 0.0, 1.0]), np.pi / 2)
    a = bodies.add_box((1.0, 2.0, 3.0), (1.0, 2.0, 3.0), q, mass=48.0)
    b = bodies.add_sphere(0.5, density=math.inf)
    c = bodies.add(inertia=(1.0, math.inf, 2.0), mass=3.0)
    assert (a, b, c) == (0, 1, 2) and len(bodies) == 3
    assert list(bodies.shape) == [BOX, SPHERE, 0]
    assert bodies.size[1] == pytest.approx([0.5, 0, 0])
    # body x (I = 208) now lies along world y
    assert bodies.inv_inertia_world[0] == pytest.approx(np.diag([1 / 160, 1 / 208, 1 / 80]))
    assert bodies.inv_mass[1] == 0 and np.all(bodies.inv_inertia[1] == 0)
    assert bodies.inv_inertia[2] == pytest.approx([1.0, 0.0, 0.5])
    assert bodies[0].position == pytest.approx([1, 2, 3])
    assert bodies[2].mass == 3.0 and bodies[1].mass == math.inf
    assert bodies[2].inertia[1] == math.inf


def test_constant_force_and_gravity_give_the_semi_implicit_euler_answer():
    bodies = Bodies()
    i = bodies.add_sphere(0.1, (0.0, 10.0, 0.0), velocity=(1.0, 0.0, 0.0), mass=2.0)
    h, n = 0.01, 100
    for _ in range(n):
        bodies.add_force(i, (4.0, 0.0, 0.0))  # a = 2 m/s² along x
        step(bodies, h, gravity=(0.0, -9.81, 0.0))
    t = n * h
    assert bodies.velocity[i] == pytest.approx([1.0 + 2.0 * t, -9.81 * t, 0.0], rel=1e-12)
    # x_n = x0 + v0 t + a h² n(n+1)/2: the continuous ½at² plus ½a·h·t
    drop = h * h * n * (n + 1) / 2
    assert bodies.position[i] == pytest.approx([t + 2.0 * drop, 10.0 - 9.81 * drop, 0.0],
                                               rel=1e-12)
    assert np.all(bodies.force == 0.0)  # accumulators cleared


def test_constant_torque_about_a_principal_axis_turns_by_the_discrete_answer():
    bodies = Bodies()
    i = bodies.add_box((0.5, 1.0, 1.5), mass=6.0)  # asymmetric: I = (6.5, 5, 2.5)
    inertia = bodies[i].inertia
    h, n = 0.01, 50
    for _ in range(n):
        bodies.add_torque(i, (0.0, 2.0, 0.0))
        step(bodies, h)
    alpha = 2.0 / inertia[1]
    assert bodies.angular_velocity[i] == pytest.approx([0, alpha * n * h, 0], abs=1e-12)
    angle = alpha * h * h * n * (n + 1) / 2  # ω after each kick, turned exactly in each drift
    want = quat_from_axis_angle(np.array([0.0, 1.0, 0.0]), angle)
    assert bodies.orientation[i] == pytest.approx(want, abs=1e-12)


def test_force_at_a_point_is_the_force_plus_its_torque():
    bodies = Bodies()
    a = bodies.add_box((1.0, 0.5, 0.25), (1.0, 2.0, 3.0), mass=2.0)
    b = bodies.add_box((1.0, 0.5, 0.25), (1.0, 2.0, 3.0), mass=2.0)
    f, p = np.array([0.0, 3.0, -1.0]), np.array([2.0, 2.5, 3.0])
    bodies[a].add_force_at_point(f, p)
    assert bodies.force[a] == pytest.approx(f)
    assert bodies.torque[a] == pytest.approx(np.cross(p - [1.0, 2.0, 3.0], f))
    bodies.add_force(b, f)
    bodies.add_torque(b, np.cross([1.0, 0.5, 0.0], f))
    for _ in range(10):
        step(bodies, 0.02)
    assert bodies.position[a] == pytest.approx(bodies.position[b], abs=1e-15)
    assert bodies.orientation[a] == pytest.approx(bodies.orientation[b], abs=1e-15)
    assert np.linalg.norm(bodies.angular_velocity[a]) > 0.05


def test_infinite_mass_and_inertia_ignore_forces_but_keep_their_motion():
    bodies = Bodies()
    i = bodies.add_box((1.0, 1.0, 1.0), velocity=(1.0, 0.0, 0.0), density=math.inf)
    bodies[i].angular_velocity = (0.0, 0.0, 2.0)
    bodies.add_force(i, (100.0, 0.0, 0.0))
    bodies.add_torque(i, (0.0, 100.0, 0.0))
    step(bodies, 0.5, gravity=(0.0, -9.81, 0.0))
    assert bodies.velocity[i] == pytest.approx([1.0, 0.0, 0.0])
    assert bodies.angular_velocity[i] == pytest.approx([0.0, 0.0, 2.0])
    assert bodies.position[i] == pytest.approx([0.5, 0.0, 0.0])
    assert rotate(bodies.orientation[i], np.array([1.0, 0.0, 0.0])) == pytest.approx(
        [math.cos(1.0), math.sin(1.0), 0.0])


def test_a_locked_axis_takes_no_torque_about_it():
    bodies = Bodies()
    i = bodies.add(inertia=(1.0, math.inf, 1.0))
    bodies.add_torque(i, (0.0, 5.0, 1.0))
    step(bodies, 0.1)
    assert bodies.angular_velocity[i] == pytest.approx([0.0, 0.0, 0.1])


def test_damping_and_the_rotation_cap():
    bodies = Bodies()
    i = bodies.add_sphere(1.0, velocity=(2.0, 0.0, 0.0), linear_damping=0.5,
                          angular_damping=0.25)
    bodies[i].angular_velocity = (0.0, 4.0, 0.0)
    step(bodies, 0.1)
    assert bodies.velocity[i] == pytest.approx([2.0 * 0.5**0.1, 0, 0])
    assert bodies.angular_velocity[i] == pytest.approx([0, 4.0 * 0.25**0.1, 0])
    fast = bodies.add_sphere(1.0)
    bodies[fast].angular_velocity = (0.0, 0.0, 1000.0)
    step(bodies, 0.01)
    assert np.linalg.norm(bodies.angular_velocity[fast]) == pytest.approx(MAX_ROTATION / 0.01)


def test_kinetic_energy_and_angular_momentum():
    bodies = Bodies()
    i = bodies.add_box((1.0, 2.0, 3.0), velocity=(0.0, 3.0, 0.0), mass=48.0)  # I=(208,160,80)
    bodies[i].angular_velocity = (0.5, 0.0, 0.0)
    assert bodies.kinetic_energy() == pytest.approx(0.5 * 48 * 9 + 0.5 * 208 * 0.25)
    assert bodies.angular_momentum(i) == pytest.approx([104.0, 0.0, 0.0])


@pytest.mark.parametrize(("kwargs", "message"), [
    ({"mass": -1.0, "inertia": (1, 1, 1)}, "mass must be in"),
    ({"mass": 1.0, "inertia": (1, 0, 1)}, r"inertia must be three principal moments"),
    ({"mass": 1.0, "inertia": (1, math.nan, 1)}, r"inertia must be"),
    ({"mass": 1.0}, "needs inertia"),
    ({"density": 5.0, "inertia": (1, 1, 1)}, "density needs a shape"),
    ({"shape": Sphere(1.0), "mass": 1.0, "density": 2.0}, "exactly one of"),
    ({"shape": Sphere(1.0), "density": 0.0}, r"density must be in \(0"),
    ({"shape": Sphere(1.0), "orientation": (0, 0, 0, 0)}, "nonzero quaternion"),
    ({"shape": Sphere(1.0), "orientation": (1, 0, 0)}, r"quaternion \(w, x, y, z\)"),
    ({"shape": Sphere(1.0), "linear_damping": 1.5}, r"linear_damping must be in \[0, 1\]"),
    ({"shape": Sphere(1.0), "position": (0, math.inf, 0)}, "position must be finite"),
    ({"shape": "sphere"}, "shape must be a Sphere"),
])
def test_bad_bodies_are_refused_with_the_parameter_named(kwargs, message):
    with pytest.raises((ValueError, TypeError), match=message):
        Bodies().add(**kwargs)


def test_bad_shapes_indices_and_steps_are_refused():
    with pytest.raises(ValueError, match=r"radius must be in \[1e-09, 1e\+09\]"):
        Sphere(-1.0)
    with pytest.raises(ValueError, match=r"half_extents must each be in \[1e-09, 1e\+09\] m"):
        Box((1.0, 0.0, 1.0))
    bodies = Bodies()
    bodies.add_sphere(1.0)
    with pytest.raises(IndexError, match=r"body: 3 is not a body; indices must be in \[0, 0\]"):
        bodies.add_force(3, (1, 0, 0))
    with pytest.raises(ValueError, match="dt must be in"):
        step(bodies, 0.0)
    with pytest.raises(ValueError, match="gravity must be finite"):
        step(bodies, 0.1, gravity=(0, math.nan, 0))
    bodies.velocity[0] = (1e308, 0.0, 0.0)
    bodies.add_force(0, (1e308, 0.0, 0.0))
    with pytest.raises(FloatingPointError, match="body 0 is no longer finite"):
        step(bodies, 10.0)
