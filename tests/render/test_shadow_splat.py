"""The blob-shadow darkness map splatted on the CPU (render/shadow_splat.py): no GL needed."""

from __future__ import annotations

import numpy as np
import pytest

pytest.importorskip("moderngl")     # pointmass.render needs it to import

from pointmass.render.shadow_splat import FADE_REACH, SPREAD_FAR, SPREAD_NEAR, shadow_map

T = 64
REGION = (-2.0, -2.0, 4.0)          # a 4 m square, 1/16 m per texel
STRENGTH = 0.75


def _map(*rows):
    return shadow_map(np.array(rows, np.float32).reshape(-1, 4), REGION, 0.0, STRENGTH, T)


def _texel_centres():
    c = REGION[0] + (np.arange(T) + 0.5) * REGION[2] / T
    return np.meshgrid(c, c)           # x varies along columns, z along rows


def test_resting_ball_profile_matches_the_disc_formula():
    """A ball resting on the ground (gap 0): darkness strength·(1 - q)(1 - q/2) with
    q = (distance / (1.3 r))², zero outside that radius."""
    r = 0.5
    dark = _map((0.3, r, -0.2, r))
    x, z = _texel_centres()
    q = ((x - 0.3) ** 2 + (z + 0.2) ** 2) / (SPREAD_NEAR * r) ** 2
    want = np.where(q < 1.0, STRENGTH * (1.0 - q) * (1.0 - 0.5 * q), 0.0)
    np.testing.assert_allclose(dark, want, atol=2e-6)
    assert dark.max() > 0.7 * STRENGTH


def test_higher_ball_casts_wider_fainter_shadow_and_none_past_reach():
    r = 0.25
    reach = 5.0 * r + FADE_REACH
    low, high = _map((0, r, 0, r)), _map((0, r + 0.5 * reach, 0, r))
    assert high.max() < low.max()
    assert np.count_nonzero(high) > np.count_nonzero(low)
    x, z = _texel_centres()
    outside = x ** 2 + z ** 2 >= (SPREAD_FAR * r) ** 2
    assert not high[outside].any()                       # never wider than 2 r
    assert not _map((0, r + reach + 0.01, 0, r)).any()
    assert not _map((0, -0.1, 0, r)).any()               # centre under the ground
    assert not _map((0, r, 0, 0.0)).any()                # hidden (radius 0)


def test_overlapping_shadows_combine_as_one_minus_product_of_light():
    a_row, b_row = (0.0, 0.4, 0.0, 0.4), (0.3, 0.4, 0.1, 0.4)
    a, b, both = _map(a_row), _map(b_row), _map(a_row, b_row)
    np.testing.assert_allclose(both, 1.0 - (1.0 - a) * (1.0 - b), atol=1e-6)
    np.testing.assert_array_equal(_map(b_row, a_row), _map(b_row, a_row))   # same bits


def test_shadows_past_the_edge_are_clipped_not_wrapped():
    dark = _map((2.0, 0.5, 0.0, 0.5))                    # centred on the region's +x edge
    assert dark[:, -1].max() > 0.5 * STRENGTH
    assert not dark[:, : T // 2].any()
