"""The body velocity passes' prepared angular terms (``solver/body_passes.py``), checked against
the rigid-body formulas written out here with numpy.

A normal row along n at arms rA, rB has the effective mass 1/(wA + wB + (rA×n)·IA⁻¹(rA×n) +
(rB×n)·IB⁻¹(rB×n)); an impulse of that mass times the velocity error, applied through the
prepared terms, must leave the point's separating velocity exactly at its target in one pass
(a single row is solved exactly), whatever the bodies' orientations and spins.
"""

import numpy as np
import pytest

from pointmass.solver import body_passes as bp


def _spd(rng):
    """A random symmetric positive definite inverse inertia (3, 3) [1/(kg·m²)]."""
    m = rng.normal(size=(3, 3))
    return m @ m.T + 0.5 * np.eye(3)


def _one_manifold(rng, scenery):
    """One point between body 0 and body 1 (or the scenery): the kernels' inputs."""
    n = rng.normal(size=3)
    n /= np.linalg.norm(n)
    ra = rng.normal(size=(1, 3))
    rb = rng.normal(size=(1, 3))
    inv_i = np.stack([_spd(rng), _spd(rng)])
    t1 = np.cross(n, rng.normal(size=3))
    t1 /= np.linalg.norm(t1)
    t2 = np.cross(n, t1)
    return dict(start=np.array([0, 1]), ca=np.array([0]), cb=np.array([-1 if scenery else 1]),
                n=n[None, :], ra=ra, rb=rb, fa=ra.copy(), fb=rb.copy(), t1=t1[None, :],
                t2=t2[None, :], inv_i=inv_i)


@pytest.mark.parametrize("scenery", [False, True])
def test_prepared_terms_are_the_cross_products_and_inertia_responses(scenery):
    rng = np.random.default_rng(3)
    c = _one_manifold(rng, scenery)
    arm = np.full((1, 12), np.nan)
    farm = np.full((1, 30), np.nan)
    bp.prepare_arms(c["start"], c["ca"], c["cb"], c["n"], c["ra"], c["rb"], c["fa"], c["fb"],
                    c["t1"], c["t2"], c["inv_i"], arm, farm)
    n, ra, rb, ia, ib = c["n"][0], c["ra"][0], c["rb"][0], c["inv_i"][0], c["inv_i"][1]
    zero = np.zeros(3)
    b_side = (lambda v: zero) if scenery else (lambda v: v)
    want = np.concatenate([np.cross(ra, n), b_side(np.cross(rb, n)), ia @ np.cross(ra, n),
                           b_side(ib @ np.cross(rb, n))])
    np.testing.assert_allclose(arm[0], want, rtol=1e-14, atol=1e-14)
    t1, t2 = c["t1"][0], c["t2"][0]
    want_f = np.concatenate([np.cross(ra, t1), np.cross(ra, t2), b_side(np.cross(rb, t1)),
                             b_side(np.cross(rb, t2)), ia @ np.cross(ra, t1),
                             ia @ np.cross(ra, t2), b_side(ib @ np.cross(rb, t1)),
                             b_side(ib @ np.cross(rb, t2)), ia @ n, b_side(ib @ n)])
    np.testing.assert_allclose(farm[0], want_f, rtol=1e-14, atol=1e-14)


@pytest.mark.parametrize("scenery", [False, True])
def test_one_normal_row_reaches_its_target_in_one_pass(scenery):
    rng = np.random.default_rng(7)
    c = _one_manifold(rng, scenery)
    n, ra, rb = c["n"][0], c["ra"][0], c["rb"][0]
    inv_mass = np.array([0.7, 1.9])
    ia, ib = c["inv_i"]
    vel = rng.normal(size=(2, 3))
    ang = rng.normal(size=(2, 3))

    def separating(v, w):
        vs = (v[0] + np.cross(w[0], ra)) @ n
        return vs if scenery else vs - (v[1] + np.cross(w[1], rb)) @ n

    k = inv_mass[0] + np.cross(ra, n) @ ia @ np.cross(ra, n)
    if not scenery:
        k += inv_mass[1] + np.cross(rb, n) @ ib @ np.cross(rb, n)
    target = separating(vel, ang) + 0.3  # the point must open 0.3 m/s faster: a push
    arm = np.empty((1, 12))
    farm = np.empty((1, 30))
    bp.prepare_arms(c["start"], c["ca"], c["cb"], c["n"], ra[None], rb[None], c["fa"], c["fb"],
                    c["t1"], c["t2"], c["inv_i"], arm, farm)
    impulse = np.zeros(1)
    mu = radius = mass_t1 = mass_t2 = mass_tw = np.zeros(1)  # μ = 0: the normal row alone
    jt1, jt2, jtw = np.zeros(1), np.zeros(1), np.zeros(1)
    passes = bp.solve_velocities(
        c["start"], c["ca"], c["cb"], c["n"], c["t1"], c["t2"], mu, radius, np.array([1 / k]),
        mass_t1, mass_t2, mass_tw, np.array([target]), inv_mass, vel, ang, impulse, jt1, jt2,
        jtw, arm, farm, 1e-12, 5)
    assert separating(vel, ang) == pytest.approx(target, abs=1e-12)
    assert impulse[0] == pytest.approx(0.3 / k, rel=1e-12)
    assert passes == 2  # the second pass changes nothing
