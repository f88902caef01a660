"""Torque-free rigid bodies: L and energy kept, precession at the analytic rate, the
intermediate-axis flip."""

import numpy as np

from pointmass.rigid.integrate import free_rotation
from pointmass.rigid.quaternion import inv_rotate, quat_from_axis_angle, rotate


def _run(inertia, omega_body, seconds, h=1.0 / 60.0, q=(1.0, 0.0, 0.0, 0.0)):
    """Step a free body; returns world L (S, 3), energy (S,) and body ω (S, 3) after each step."""
    inertia = np.asarray(inertia, dtype=float)
    inv = 1.0 / inertia
    q = np.asarray(q, dtype=float)
    w = rotate(q, np.asarray(omega_body, dtype=float))
    ls, es, wbs = [], [], []
    for _ in range(round(seconds / h)):
        out = free_rotation(*q, *w, *inv, h)
        q, w = np.array(out[:4]), np.array(out[4:])
        wb = inv_rotate(q, w)
        ls.append(rotate(q, inertia * wb))
        es.append(0.5 * np.dot(wb, inertia * wb))
        wbs.append(wb)
    return np.array(ls), np.array(es), np.array(wbs)


def test_kinetic_energy_never_increases():
    _, es, _ = _run([1.0, 2.0, 3.0], [0.3, 4.0, 0.2], 10.0)
    assert np.all(np.diff(es) <= 1e-12 * es[0])
    assert abs(es[-1] - es[0]) < 1e-9 * es[0]


def test_angular_momentum_kept_over_10_s():
    # was 8.3 % with the first-order implicit gyroscopic step (Box3D's)
    q0 = quat_from_axis_angle(np.array([1.0, -2.0, 0.5]), 0.7)
    ls, _, _ = _run([1.0, 2.0, 3.0], [0.3, 4.0, 0.2], 10.0, q=q0)
    l0 = rotate(q0, np.array([1.0, 2.0, 3.0]) * np.array([0.3, 4.0, 0.2]))
    rel = np.max(np.linalg.norm(ls - l0, axis=1)) / np.linalg.norm(l0)
    assert rel < 1e-3
    assert rel < 1e-10  # in fact kept to rounding


def test_fast_spin_keeps_l_and_energy():
    # h|ω| = 0.75 rad per step, near the per-step rotation cap the stepper applies
    ls, es, _ = _run([0.2, 1.0, 1.7], [45.0, 3.0, -2.0], 2.0)
    assert np.max(np.linalg.norm(ls - ls[0], axis=1)) < 1e-10 * np.linalg.norm(ls[0])
    assert np.all(np.diff(es) <= 1e-12 * es[0])


def test_a_turn_of_four_radians_in_one_step_is_split_and_still_keeps_energy():
    # faster than the stepper's cap: a contact solver may leave a body spinning like this
    ls, es, _ = _run([0.2, 1.0, 1.7], [3.0, 1.0, -2.0], 100.0, h=4.0 / np.sqrt(14.0))
    assert np.max(np.abs(es - es[0])) < 1e-9 * es[0]
    assert np.max(np.linalg.norm(ls - ls[0], axis=1)) < 1e-10 * np.linalg.norm(ls[0])


def test_symmetric_body_precesses_at_the_analytic_rate():
    i1, i3, w3 = 1.0, 2.5, 6.0
    h = 1.0 / 60.0
    _, _, wb = _run([i1, i1, i3], [1.5, 0.0, w3], 10.0, h=h)
    rate = (i3 - i1) * w3 / i1  # body ω turns about axis 3 at this rate [rad/s]
    phase = np.unwrap(np.arctan2(wb[:, 1], wb[:, 0]))
    t = h * np.arange(1, len(phase) + 1)
    measured = np.polyfit(t, phase, 1)[0]
    # the sense: Euler's equations give dω1/dt = −Ω ω2, dω2/dt = Ω ω1: counterclockwise
    assert measured > 0
    period, expected = 2 * np.pi / abs(measured), 2 * np.pi / rate
    assert abs(period - expected) / expected < 0.01
    assert np.allclose(wb[:, 2], w3, rtol=1e-12)  # ω3 stays constant


def test_intermediate_axis_spin_flips_and_the_others_do_not():
    inertia = [1.0, 2.0, 3.0]
    eps = 1e-3
    _, _, about_2 = _run(inertia, [eps, 5.0, eps], 10.0)
    assert about_2[:, 1].min() < -4.9  # turned over: ω2 reversed
    _, _, about_1 = _run(inertia, [5.0, eps, eps], 10.0)
    assert about_1[:, 0].min() > 4.99
    _, _, about_3 = _run(inertia, [eps, eps, 5.0], 10.0)
    assert about_3[:, 2].min() > 4.99


def test_isotropic_body_turns_at_exactly_its_angular_velocity():
    w = np.array([0.0, 0.0, 30.0])
    out = free_rotation(1.0, 0.0, 0.0, 0.0, *w, 2.0, 2.0, 2.0, 0.1)
    q = np.array(out[:4])
    assert np.allclose(q, quat_from_axis_angle(w, 3.0), atol=1e-14)  # 3 rad, not 2·atan(1.5)
    assert np.allclose(out[4:], w)
