"""Quaternion helpers against analytic rotations."""

import numpy as np

from pointmass.rigid.quaternion import (
    cross,
    inv_rotate,
    quat_conj,
    quat_from_axis_angle,
    quat_from_axis_angle_numpy,
    quat_mul,
    quat_normalize,
    quat_to_matrix,
    rotate,
    skew,
    world_inv_inertia,
    world_inv_inertia_numpy,
)


def test_quarter_turn_about_z_maps_x_to_y():
    q = quat_from_axis_angle(np.array([0.0, 0.0, 2.0]), np.pi / 2)
    assert np.allclose(rotate(q, np.array([1.0, 0.0, 0.0])), [0.0, 1.0, 0.0], atol=1e-15)
    assert np.allclose(inv_rotate(q, np.array([0.0, 1.0, 0.0])), [1.0, 0.0, 0.0], atol=1e-15)


def test_product_composes_rotations_and_conjugate_inverts():
    a = quat_from_axis_angle(np.array([1.0, 0.0, 0.0]), np.pi / 2)
    b = quat_from_axis_angle(np.array([0.0, 0.0, 1.0]), np.pi / 2)
    v = np.array([1.0, 0.0, 0.0])
    # b takes x to y, then a (about x) takes y to z
    assert np.allclose(rotate(quat_mul(a, b), v), [0.0, 0.0, 1.0], atol=1e-15)
    assert np.allclose(quat_mul(a, quat_conj(a)), [1.0, 0.0, 0.0, 0.0], atol=1e-15)


def test_matrix_is_orthonormal_and_normalize_never_nans():
    q = quat_normalize(np.array([0.3, -0.5, 0.7, 0.1]))
    m = quat_to_matrix(q)
    assert np.allclose(m @ m.T, np.eye(3), atol=1e-14)
    assert np.isclose(np.linalg.det(m), 1.0)
    assert np.array_equal(quat_normalize(np.zeros(4)), [1.0, 0.0, 0.0, 0.0])


def test_cross_skew_and_world_inertia():
    a, b = np.array([1.0, 2.0, 3.0]), np.array([-4.0, 0.5, 2.0])
    assert np.allclose(cross(a, b), np.cross(a, b))
    assert np.allclose(skew(a) @ b, np.cross(a, b))
    q = quat_from_axis_angle(np.array([0.0, 0.0, 1.0]), np.pi / 2)
    w = world_inv_inertia(q, np.array([1.0, 2.0, 3.0]))
    # body x-axis now points along world y: the principal values swap on the diagonal
    assert np.allclose(w, np.diag([2.0, 1.0, 3.0]), atol=1e-15)


def test_the_numpy_world_inertia_is_the_kernels_to_the_bit():
    """Bodies added or turned from Python use the numpy twin (nothing to compile while a demo
    is built): the same bits as the kernel the step uses, so no trajectory changes."""
    rng = np.random.default_rng(7)
    for _ in range(500):
        q = rng.normal(size=4)
        q /= np.linalg.norm(q)
        inv = rng.uniform(0.0, 5.0, 3)
        inv[rng.integers(3)] *= rng.integers(2)       # some immovable axes (0)
        assert np.array_equal(world_inv_inertia_numpy(q, inv), world_inv_inertia(q, inv))


def test_the_numpy_axis_angle_quaternion_is_the_kernels_to_the_bit():
    rng = np.random.default_rng(8)
    for _ in range(500):
        axis = rng.normal(size=3)
        axis /= np.linalg.norm(axis)
        angle = rng.uniform(-4.0, 4.0)
        assert np.array_equal(quat_from_axis_angle_numpy(axis, angle),
                              quat_from_axis_angle(axis, angle))
    assert np.array_equal(quat_from_axis_angle_numpy(np.zeros(3), 1.0), [1.0, 0, 0, 0])
