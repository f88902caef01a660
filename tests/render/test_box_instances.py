"""Box instance rows (geometry.box_instances) carry each box's model matrix and color."""

from __future__ import annotations

import numpy as np
import pytest

pytest.importorskip("moderngl")     # pointmass.render needs it to import

from pointmass.render import geometry
from pointmass.scene import BoxVisual


def _turn(axis, angle):
    k = np.asarray(axis, float) / np.linalg.norm(axis)
    kx = np.array([[0, -k[2], k[1]], [k[2], 0, -k[0]], [-k[1], k[0], 0]])
    return np.eye(3) + np.sin(angle) * kx + (1 - np.cos(angle)) * kx @ kx


def test_rows_are_box_model_rows_and_map_corners_like_it():
    boxes = [BoxVisual(center=(1.0, 2.0, -3.0), half_size=(0.5, 1.0, 2.0),
                       rotation=_turn((1, 2, 3), 0.7), color=(0.2, 0.4, 0.6)),
             BoxVisual(center=(0.0, 0.5, 0.0), half_size=(0.25, 0.25, 0.25),
                       rotation=np.eye(3), color=(1.0, 0.0, 0.0))]
    rows = geometry.box_instances(boxes)
    assert rows.shape == (2, geometry.BOX_FLOATS) and rows.dtype == np.float32
    for b, row in zip(boxes, rows):
        model = geometry.box_model(b.center, b.half_size, b.rotation)
        np.testing.assert_allclose(row[:12].reshape(3, 4), model[:3], atol=1e-6)
        np.testing.assert_allclose(row[12:], (*b.color, 1.0))
        corner = np.array([1.0, -1.0, 1.0, 1.0])           # a corner of the unit cube
        np.testing.assert_allclose(row[:12].reshape(3, 4) @ corner,
                                   b.center + b.rotation @ (np.array(b.half_size) * corner[:3]),
                                   atol=1e-5)
    assert geometry.box_instances([]).shape == (0, geometry.BOX_FLOATS)


def test_edge_lines_of_many_boxes_are_each_boxs_edges():
    boxes = [BoxVisual(center=(k, 0.5 * k, -k), half_size=(0.5, 0.2 + k, 1.0),
                       rotation=_turn((k, 1, 2), 0.3 * k)) for k in range(3)]
    start, end = geometry.box_edge_lines(boxes)
    assert start.shape == end.shape == (36, 3)
    for k, b in enumerate(boxes):
        s, e = geometry.box_edges(b.center, b.half_size, b.rotation)
        np.testing.assert_allclose(start[12 * k:12 * k + 12], s, atol=1e-5)
        np.testing.assert_allclose(end[12 * k:12 * k + 12], e, atol=1e-5)
