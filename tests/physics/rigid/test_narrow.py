"""Narrow phase on configurations whose contacts are worked out by hand."""

import math

import numpy as np
import pytest

from pointmass.rigid import narrow
from pointmass.rigid.box_box import EDGE_FLAG, LINEAR_SLOP
from pointmass.rigid.quaternion import quat_from_axis_angle, rotate

I = (1.0, 0.0, 0.0, 0.0)
UP = (0.0, 1.0, 0.0)


def _q(axis, angle):
    return quat_from_axis_angle(np.asarray(axis, dtype=float), angle)


def _rows(points):
    """Points as a sorted list of rounded tuples, to compare sets of corners."""
    return sorted(tuple(np.round(p, 9).tolist()) for p in points)


# -- spheres --------------------------------------------------------------------------------------
def test_sphere_plane_depth_point_and_margin():
    m = narrow.sphere_plane((2.0, 0.9, 0.0), 1.0, (0.0, 2.0, 0.0), 0.0)
    assert m.count == 1 and m.normal == pytest.approx(UP)
    assert m.depth == pytest.approx([0.1])
    assert m.points[0] == pytest.approx([2.0, -0.05, 0.0])  # midway: -0.1 and 0
    assert narrow.sphere_plane((0, 1.05, 0), 1.0, UP, 0.0).count == 0
    gap = narrow.sphere_plane((0, 1.05, 0), 1.0, UP, 0.0, margin=0.1)
    assert gap.count == 1 and gap.depth == pytest.approx([-0.05])


def test_sphere_sphere_normal_from_b_to_a_and_coincident_centres():
    m = narrow.sphere_sphere((3.0, 0.0, 0.0), 1.0, (0.0, 0.0, 0.0), 2.5)
    assert m.count == 1 and m.normal == pytest.approx([1, 0, 0])
    assert m.depth == pytest.approx([0.5])
    assert m.points[0] == pytest.approx([2.25, 0, 0])  # between 2.0 (A) and 2.5 (B)
    same = narrow.sphere_sphere((1.0, 1.0, 1.0), 1.0, (1.0, 1.0, 1.0), 1.0)
    assert same.normal == pytest.approx(UP) and same.depth == pytest.approx([2.0])
    assert narrow.sphere_sphere((3.6, 0, 0), 1.0, (0, 0, 0), 2.5).count == 0


@pytest.mark.parametrize(("centre", "normal", "depth", "point"), [
    # face region: above the top face
    ((0.3, 1.4, -0.2), (0, 1, 0), 0.1, (0.3, 0.95, -0.2)),
    # edge region: beyond the edge x = 1, y = 1, at 45°
    ((1.3, 1.3, 0.5), (1 / math.sqrt(2), 1 / math.sqrt(2), 0), 0.5 - 0.3 * math.sqrt(2), None),
    # corner region
    ((1.2, 1.2, 1.2), (1 / math.sqrt(3),) * 3, 0.5 - 0.2 * math.sqrt(3), None),
    # centre inside, nearest face x = +1
    ((0.8, 0.1, 0.0), (1, 0, 0), 0.7, (0.65, 0.1, 0.0)),  # between 0.3 and 1
])
def test_sphere_box_regions(centre, normal, depth, point):
    m = narrow.sphere_box(centre, 0.5, (0, 0, 0), I, (1.0, 1.0, 1.0))
    assert m.count == 1
    assert m.normal == pytest.approx(normal)
    assert m.depth == pytest.approx([depth])
    if point is not None:
        assert m.points[0] == pytest.approx(point)


def test_sphere_box_follows_the_box_rotation():
    # box turned 90° about z: its half-extent 2 along body x now lies along world y
    m = narrow.sphere_box((0.0, 2.4, 0.0), 0.5, (0, 0, 0), _q((0, 0, 1), math.pi / 2),
                          (2.0, 1.0, 1.0))
    assert m.normal == pytest.approx(UP) and m.depth == pytest.approx([0.1])
    assert narrow.sphere_box((1.2, 1.2, 1.2), 0.3, (0, 0, 0), I, (1, 1, 1)).count == 0


# -- box on a plane -------------------------------------------------------------------------------
def test_box_resting_flat_gives_its_four_bottom_corners():
    m = narrow.box_plane((5.0, 0.98, 0.0), I, (1.0, 1.0, 2.0), UP, 0.0)
    assert m.count == 4 and m.normal == pytest.approx(UP)
    assert m.depth == pytest.approx([0.02] * 4)
    want = [(x, -0.01, z) for x in (-1 + 5.0, 1 + 5.0) for z in (-2.0, 2.0)]
    assert _rows(m.points) == _rows(want)
    assert sorted(m.ids.tolist()) == [0, 1, 4, 5]  # corners with body y = -1


def test_box_on_an_edge_and_on_a_corner():
    edge = narrow.box_plane((0, math.sqrt(2) - 0.05, 0), _q((0, 0, 1), math.pi / 4),
                            (1, 1, 1), UP, 0.0)
    assert edge.count == 2 and edge.depth == pytest.approx([0.05, 0.05])
    assert _rows(edge.points[:, [0, 2]]) == _rows([(0, -1), (0, 1)])
    # a cube balanced on a corner: the diagonal (1,1,1) turned onto -y
    axis = np.cross([1.0, 1.0, 1.0], [0.0, -1.0, 0.0])
    q = _q(axis, math.acos(-1 / math.sqrt(3)))
    corner = narrow.box_plane((0, math.sqrt(3) - 0.01, 0), q, (1, 1, 1), UP, 0.0)
    assert corner.count == 1 and corner.depth == pytest.approx([0.01])
    assert corner.points[0] == pytest.approx([0, -0.005, 0], abs=1e-12)
    assert corner.ids[0] == 7


def test_box_sunk_deep_keeps_four_of_its_corners_deepest_first():
    q = _q((1, 0.3, 0), 0.4)
    half = np.array([1.0, 0.5, 0.7])
    m = narrow.box_plane((0, 0.0, 0), q, half, UP, 0.0, margin=10.0)  # all 8 in range
    assert m.count == 4
    corners = [rotate(q, half * [sx, sy, sz]) for sx in (-1, 1) for sy in (-1, 1)
               for sz in (-1, 1)]
    assert m.depth.max() == pytest.approx(-min(c[1] for c in corners))


# -- box on box -----------------------------------------------------------------------------------
def test_small_box_on_a_big_one_gives_its_own_four_corners():
    m = narrow.box_box((0.3, 1.4, 0.0), I, (0.5, 0.5, 0.5), (0, 0, 0), I, (1, 1, 1))
    assert m.count == 4 and m.normal == pytest.approx(UP)  # from B (below) to A
    assert m.depth == pytest.approx([0.1] * 4)
    want = [(x, 0.95, z) for x in (-0.2, 0.8) for z in (-0.5, 0.5)]
    assert _rows(m.points) == _rows(want)
    assert len(set(m.ids.tolist())) == 4 and not (m.ids & EDGE_FLAG).any()


def test_box_overhanging_an_edge_is_clipped_to_the_overlap():
    m = narrow.box_box((0.8, 1.4, 0.2), I, (0.5, 0.5, 0.5), (0, 0, 0), I, (1, 1, 1))
    assert m.count == 4
    want = [(x, 0.95, z) for x in (0.3, 1.0) for z in (-0.3, 0.7)]
    assert _rows(m.points) == _rows(want)


def test_feature_ids_survive_a_small_move():
    a = narrow.box_box((0.8, 1.4, 0.2), I, (0.5, 0.5, 0.5), (0, 0, 0), I, (1, 1, 1))
    b = narrow.box_box((0.81, 1.399, 0.19), _q(UP, 0.01), (0.5, 0.5, 0.5), (0, 0, 0), I,
                       (1, 1, 1))
    assert sorted(a.ids.tolist()) == sorted(b.ids.tolist())
    order = np.argsort(a.ids), np.argsort(b.ids)
    assert np.abs(a.points[order[0]] - b.points[order[1]]).max() < 0.02


def test_nearly_flat_faces_stay_a_face_contact():
    # a box tilted by 0.2° on another: the least-overlap axis alone might pick an edge pair
    m = narrow.box_box((0.0, 1.99, 0.0), _q((1, 0, 1), 0.0035), (1, 1, 1), (0, 0, 0), I,
                       (1, 1, 1))
    assert m.count >= 3 and not (m.ids & EDGE_FLAG).any()
    assert m.normal == pytest.approx(UP, abs=1e-2)


def test_crossed_edges_give_one_point_between_them():
    a = _q((1, 0, 0), math.pi / 4)  # an edge along x on top, at y = √2
    b = _q((0, 0, 1), math.pi / 4)  # an edge along z at the bottom
    m = narrow.box_box((0, 0, 0), a, (1, 1, 1), (0, 2 * math.sqrt(2) - 0.1, 0), b, (1, 1, 1))
    assert m.count == 1 and m.ids[0] & EDGE_FLAG
    assert m.normal == pytest.approx([0, -1, 0])
    assert m.depth == pytest.approx([0.1])
    assert m.points[0] == pytest.approx([0, math.sqrt(2) - 0.05, 0], abs=1e-12)


def test_box_turned_on_a_box_is_reduced_to_four_points_on_the_overlap():
    # same-size boxes, the top one turned 45° about y: the overlap is an octagon (8 points)
    m = narrow.box_box((0, 1.95, 0), _q(UP, math.pi / 4), (1, 1, 1), (0, 0, 0), I, (1, 1, 1))
    assert m.count == 4
    assert m.depth == pytest.approx([0.05] * 4)
    assert np.all(np.abs(m.points[:, [0, 2]]) <= 1 + 1e-12)  # inside the bottom box's top
    assert np.all(np.abs(m.points[:, 0]) + np.abs(m.points[:, 2]) <= math.sqrt(2) + 1e-12)


def test_separated_boxes_have_no_contact_unless_within_the_margin():
    assert narrow.box_box((0, 2.05, 0), I, (1, 1, 1), (0, 0, 0), I, (1, 1, 1)).count == 0
    spec = narrow.box_box((0, 2.05, 0), I, (1, 1, 1), (0, 0, 0), I, (1, 1, 1), margin=0.1)
    assert spec.count == 4 and spec.depth == pytest.approx([-0.05] * 4)
    # separated along an edge axis only (the face axes overlap)
    a = _q((1, 0, 0), math.pi / 4)
    b = _q((0, 0, 1), math.pi / 4)
    assert narrow.box_box((0, 0, 0), a, (1, 1, 1), (0, 2 * math.sqrt(2) + 0.01, 0), b,
                          (1, 1, 1)).count == 0


def test_swapping_the_boxes_flips_the_normal():
    ab = narrow.box_box((0.3, 1.4, 0.0), I, (0.5, 0.5, 0.5), (0, 0, 0), I, (1, 1, 1))
    ba = narrow.box_box((0, 0, 0), I, (1, 1, 1), (0.3, 1.4, 0.0), I, (0.5, 0.5, 0.5))
    assert ba.normal == pytest.approx(-ab.normal)
    assert _rows(ba.points) == _rows(ab.points) and ba.depth == pytest.approx(ab.depth)


@pytest.mark.parametrize(("call", "message"), [
    (lambda: narrow.sphere_plane((0, 0, 0), 0.0, UP, 0.0), r"radius must be in \(0"),
    (lambda: narrow.sphere_plane((0, 0, 0), 1.0, (0, 0, 0), 0.0), "normal must be a nonzero"),
    (lambda: narrow.box_plane((0, 0, 0), (0, 0, 0, 0), (1, 1, 1), UP, 0.0), "orientation"),
    (lambda: narrow.box_box((0, 0, 0), I, (1, -1, 1), (0, 0, 0), I, (1, 1, 1)),
     "half_extents_a must each be > 0"),
    (lambda: narrow.sphere_sphere((0, 0, 0), 1, (0, 0, 0), 1, margin=-1), r"margin must be in"),
])
def test_bad_shapes_are_refused(call, message):
    with pytest.raises(ValueError, match=message):
        call()


def _sat_overlap(pa, ra, ha, pb, rb, hb):
    """Least overlap over the 15 axes, in numpy (> 0: the boxes intersect)."""
    axes = [*ra.T, *rb.T]
    axes += [np.cross(x, y) for x in ra.T for y in rb.T]
    least = np.inf
    for n in axes:
        if np.linalg.norm(n) < 1e-6:
            continue
        n = n / np.linalg.norm(n)
        reach = np.abs(ra.T @ n) @ ha + np.abs(rb.T @ n) @ hb
        least = min(least, reach - abs(n @ (pb - pa)))
    return least


def test_random_box_pairs_agree_with_a_plain_separating_axis_test():
    from pointmass.rigid.bodies import world_rotation

    rng = np.random.default_rng(13)
    touching = 0
    for _ in range(300):
        qa, qb = rng.normal(size=4), rng.normal(size=4)
        qa, qb = qa / np.linalg.norm(qa), qb / np.linalg.norm(qb)
        ha, hb = rng.uniform(0.2, 1.0, 3), rng.uniform(0.2, 1.0, 3)
        pa, pb = np.zeros(3), rng.uniform(-1.8, 1.8, 3)
        m = narrow.box_box(pa, qa, ha, pb, qb, hb)
        overlap = _sat_overlap(pa, world_rotation(qa), ha, pb, world_rotation(qb), hb)
        assert (m.count > 0) == (overlap > 0)
        if m.count:
            touching += 1
            # the deepest point is as deep as the boxes overlap, give or take the slop by which
            # a face axis is preferred to an edge pair that overlaps less
            assert abs(m.depth.max() - overlap) <= LINEAR_SLOP + 1e-9
            for p in m.points:  # each point lies in both boxes grown by the overlap
                for c, q, h in ((pa, qa, ha), (pb, qb, hb)):
                    local = world_rotation(q).T @ (p - c)
                    assert np.all(np.abs(local) <= h + overlap + LINEAR_SLOP)
    assert touching > 100
