"""The soft step's prepared angular terms of its contact rows (``solver/body_passes.py``),
checked against the rigid-body formulas written out here with numpy (r×d and I⁻¹(r×d) per row,
whatever the bodies' orientations)."""

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
