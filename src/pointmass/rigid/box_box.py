"""Box–box narrow phase: separating axes with a face bias, then clipping to a 4-point manifold.

Cyclone takes the axis of least overlap among the 15 and returns one point (rigid-notes R7), so
a box resting on a box flips between face and edge axes from frame to frame and rocks on one
corner. Here, as in Box3D and Jolt:

1. the 15 axes (3 faces of A, 3 of B, 9 edge crosses) give separations; any above ``margin``
   means no contact;
2. a face of B is taken over a face of A only if it separates by more than a tenth of
   ``LINEAR_SLOP``, and an edge pair over the faces only if it separates by more than
   ``LINEAR_SLOP``: resting faces stay faces;
3. face case: the incident face (the other box's face most against the reference normal) is
   clipped by the four side planes of the reference face (Sutherland–Hodgman), the points under
   the reference face (or within ``margin`` of it) are kept, and at most four of them;
4. edge case: one point, midway between the closest points of the two edges.

Feature ids (int64): a face point packs which box is the reference (bit 0), the reference face
(bits 1–3, axis·2 + side), the incident face (bits 4–6) and where the point came from (bits 7–12:
an incident corner 0–3, an incident edge cut by a side plane 4–19, or a reference-face corner
20–35). An edge point sets bit 13 and packs both edges. The same touching features give the
same ids next step, so the solver can warm start each point.
"""

import math

import numpy as np
from numba import njit

from .manifold import reduce_points
from .narrow_box import box_axes_into

#: Penetration the solver tolerates [m] (Box3D's 5 mm): the margin by which a face must lose
#: before an edge pair is preferred.
LINEAR_SLOP = 0.005
#: Set in the id of an edge–edge point.
EDGE_FLAG = 1 << 13
#: Edge crosses shorter than this (nearly parallel edges) are not tested: their direction is
#: noise, and the face axes already cover them.
PARALLEL = 1e-6


#: Sizes of the scratch arrays of ``box_box_into`` (floats, ints): one pair at a time reuses
#: them, so a pair loop allocates nothing per pair (with a fresh array per temporary, the 1000-box
#: pit's narrow phase spent most of its 0.7 µs a pair in the allocator).
WORK_FLOATS = 128
WORK_INTS = 48
#: Where ``box_box_into`` leaves, in ``fw``, the separation of the axis that showed the pair
#: apart (> margin), or −inf when no axis did (its 0 then means the clipping kept no point): a
#: pair loop skips what an axis already rules out (``collide.pair_contacts``).
APART = WORK_FLOATS - 1


@njit(cache=True, nogil=True)
def _dot(a, b):
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]


@njit(cache=True, nogil=True)
def _project(axes, h, n):
    """Half-width of a box (axes rows, half-extents h) along the unit direction n."""
    return (h[0] * abs(_dot(axes[0], n)) + h[1] * abs(_dot(axes[1], n))
            + h[2] * abs(_dot(axes[2], n)))


@njit(cache=True, nogil=True)
def box_box(pa, qa, ha, pb, qb, hb, margin, normal, points, depth, ids):
    """Box A (centre, orientation (w, x, y, z), half-extents) against box B."""
    fw, iw = np.empty(WORK_FLOATS), np.empty(WORK_INTS, np.int64)
    return box_box_into(pa, qa, ha, pb, qb, hb, margin, normal, points, depth, ids, fw, iw)


@njit(cache=True, nogil=True)
def box_box_into(pa, qa, ha, pb, qb, hb, margin, normal, points, depth, ids, fw, iw):
    """``box_box`` with its temporaries in the scratch arrays ``fw`` (``WORK_FLOATS``,) and
    ``iw`` (``WORK_INTS``,), which a pair loop allocates once."""
    fw[APART] = -math.inf
    a = fw[0:9].reshape((3, 3))
    b = fw[9:18].reshape((3, 3))
    box_axes_into(qa, a)
    box_axes_into(qb, b)
    d = fw[18:21]
    for k in range(3):
        d[k] = pb[k] - pa[k]
    # 1. faces of A, faces of B
    best_a, sep_a = 0, -math.inf
    best_b, sep_b = 0, -math.inf
    for k in range(3):
        s = abs(_dot(d, a[k])) - ha[k] - _project(b, hb, a[k])
        if s > margin:
            fw[APART] = s
            return 0
        if s > sep_a:
            best_a, sep_a = k, s
        s = abs(_dot(d, b[k])) - hb[k] - _project(a, ha, b[k])
        if s > margin:
            fw[APART] = s
            return 0
        if s > sep_b:
            best_b, sep_b = k, s
    # edge crosses
    n = fw[21:24]
    edge_i, edge_j, sep_e = -1, -1, -math.inf
    for i in range(3):
        for j in range(3):
            n[0] = a[i, 1] * b[j, 2] - a[i, 2] * b[j, 1]
            n[1] = a[i, 2] * b[j, 0] - a[i, 0] * b[j, 2]
            n[2] = a[i, 0] * b[j, 1] - a[i, 1] * b[j, 0]
            length = math.sqrt(_dot(n, n))
            if length < PARALLEL:
                continue
            for k in range(3):
                n[k] /= length
            s = abs(_dot(d, n)) - _project(a, ha, n) - _project(b, hb, n)
            if s > margin:
                fw[APART] = s
                return 0
            if s > sep_e:
                edge_i, edge_j, sep_e = i, j, s
    # 2. face bias
    # np.int64(...) on the helpers' integer arguments: a constant, or a variable first set from
    # one, passed from jitted code types as Literal[int](0), not int64, and numba compiles the
    # helper again for each (``_face_contact`` was compiled four times, ``_edge_contact``
    # twice, for one box_tower). Plain int64 arguments compile each helper once.
    face_sep = max(sep_a, sep_b)
    if edge_i >= 0 and sep_e > face_sep + LINEAR_SLOP:
        return _edge_contact(pa, a, ha, np.int64(edge_i), pb, b, hb, np.int64(edge_j), sep_e,
                             normal, points, depth, ids, fw[24:])
    if sep_b > sep_a + 0.1 * LINEAR_SLOP:
        return _face_contact(pb, b, hb, np.int64(best_b), pa, a, ha, np.int64(1), margin,
                             normal, points, depth, ids, fw[24:], iw)
    return _face_contact(pa, a, ha, np.int64(best_a), pb, b, hb, np.int64(0), margin, normal,
                         points, depth, ids, fw[24:], iw)


@njit(cache=True, nogil=True)
def _clip(poly, code, tag, count, m, off, side, out_poly, out_code, out_tag):
    """Keep the part of the polygon with m·x ≤ off. ``tag`` says what the edge leaving each
    vertex lies on (0–3 an incident edge, 4 + s the side plane s), so a new vertex gets an id
    from the two features that cross there. Returns the new vertex count."""
    out = 0
    for k in range(count):
        k2 = (k + 1) % count
        d1 = _dot(m, poly[k]) - off
        d2 = _dot(m, poly[k2]) - off
        if (d1 <= 0.0) != (d2 <= 0.0):
            f = d1 / (d1 - d2)
            for c in range(3):
                out_poly[out, c] = poly[k, c] + f * (poly[k2, c] - poly[k, c])
            t = tag[k]
            out_code[out] = 4 + 4 * t + side if t < 4 else 20 + 4 * (t - 4) + side
            out_tag[out] = 4 + side if d1 <= 0.0 else t
            out += 1
        if d2 <= 0.0:
            for c in range(3):
                out_poly[out, c] = poly[k2, c]
            out_code[out] = code[k2]
            out_tag[out] = tag[k2]
            out += 1
    return out


@njit(cache=True, nogil=True)
def _face_contact(pr, r, hr, face, pi, inc, hi, flip, margin, normal, points, depth, ids, fw,
                  iw):
    """Clip the incident box's face against the reference box's ``face`` axis. ``flip`` is 1
    when the reference box is B. Temporaries in ``fw`` (≥ 92,) and ``iw`` (≥ 44,)."""
    gap = fw[0:3]
    for k in range(3):
        gap[k] = pi[k] - pr[k]
    ref_side = 1.0 if _dot(gap, r[face]) >= 0.0 else -1.0
    nref = fw[3:6]  # out of the reference box, towards the incident one
    for k in range(3):
        nref[k] = ref_side * r[face, k]
    # incident face: the one whose outward normal is most against nref
    j, most = 0, -1.0
    for k in range(3):
        c = abs(_dot(nref, inc[k]))
        if c > most:
            j, most = k, c
    inc_side = -1.0 if _dot(nref, inc[j]) > 0.0 else 1.0
    u, v = (j + 1) % 3, (j + 2) % 3
    poly = fw[6:30].reshape((8, 3))
    code = iw[0:8]
    tag = iw[8:16]
    for k in range(4):
        su = 1.0 if k == 0 or k == 3 else -1.0
        sv = 1.0 if k < 2 else -1.0
        for c in range(3):
            poly[k, c] = (pi[c] + inc_side * hi[j] * inc[j, c] + su * hi[u] * inc[u, c]
                          + sv * hi[v] * inc[v, c])
        code[k] = k
        tag[k] = k
    count = 4
    other_poly = fw[30:54].reshape((8, 3))
    other_code = iw[16:24]
    other_tag = iw[24:32]
    m = fw[54:57]
    for side in range(4):
        axis = (face + 1 + side // 2) % 3
        sign = 1.0 if side % 2 == 0 else -1.0
        for c in range(3):
            m[c] = sign * r[axis, c]
        off = _dot(m, pr) + hr[axis]
        count = _clip(poly, code, tag, np.int64(count), m, off, side, other_poly, other_code,
                      other_tag)
        poly, other_poly = other_poly, poly
        code, other_code = other_code, code
        tag, other_tag = other_tag, tag
        if count == 0:
            return 0
    ref_off = _dot(nref, pr) + hr[face]
    cand = fw[57:81].reshape((8, 3))
    sep = fw[81:89]
    cand_code = iw[32:40]
    n = 0
    for k in range(count):
        s = _dot(nref, poly[k]) - ref_off
        if s < margin:
            for c in range(3):
                cand[n, c] = poly[k, c] - 0.5 * s * nref[c]  # midway to the reference face
            sep[n] = s
            cand_code[n] = code[k]
            n += 1
    keep = iw[40:44]
    kept = reduce_points(cand, sep, np.int64(n), nref, keep)
    out_sign = 1.0 if flip else -1.0  # the normal runs from B to A
    for c in range(3):
        normal[c] = out_sign * nref[c]
    base = (flip | ((2 * face + (0 if ref_side > 0 else 1)) << 1)
            | ((2 * j + (0 if inc_side > 0 else 1)) << 4))
    for k in range(kept):
        i = keep[k]
        for c in range(3):
            points[k, c] = cand[i, c]
        depth[k] = -sep[i]
        ids[k] = base | (cand_code[i] << 7)
    return kept


@njit(cache=True, nogil=True)
def _edge_contact(pa, a, ha, i, pb, b, hb, j, sep, normal, points, depth, ids, fw):
    """One point between edge i of A and edge j of B, the pair whose cross separates most.
    Temporaries in ``fw`` (≥ 12,)."""
    n = fw[0:3]
    n[0] = a[i, 1] * b[j, 2] - a[i, 2] * b[j, 1]
    n[1] = a[i, 2] * b[j, 0] - a[i, 0] * b[j, 2]
    n[2] = a[i, 0] * b[j, 1] - a[i, 1] * b[j, 0]
    length = math.sqrt(_dot(n, n))
    if (pb[0] - pa[0]) * n[0] + (pb[1] - pa[1]) * n[1] + (pb[2] - pa[2]) * n[2] < 0.0:
        length = -length
    for k in range(3):
        n[k] /= length  # from A towards B
    # the edges: A's edge along axis i farthest towards B, B's along j farthest towards A
    ca = fw[3:6]
    cb = fw[6:9]
    for k in range(3):
        ca[k] = pa[k]
        cb[k] = pb[k]
    id_a, id_b = 4 * i, 4 * j
    bit_a, bit_b = 0, 0
    for k in range(3):
        if k != i:
            s = 1.0 if _dot(n, a[k]) >= 0.0 else -1.0
            for u in range(3):
                ca[u] += s * ha[k] * a[k, u]
            id_a |= (1 if s > 0 else 0) << bit_a
            bit_a += 1
        if k != j:
            s = -1.0 if _dot(n, b[k]) >= 0.0 else 1.0
            for u in range(3):
                cb[u] += s * hb[k] * b[k, u]
            id_b |= (1 if s > 0 else 0) << bit_b
            bit_b += 1
    # closest points of the lines ca + s·a_i and cb + t·b_j, clamped to the edges
    rx = fw[9:12]
    for k in range(3):
        rx[k] = ca[k] - cb[k]
    c = _dot(a[i], b[j])
    ar, br = _dot(a[i], rx), _dot(b[j], rx)
    denom = 1.0 - c * c
    s = (c * br - ar) / denom if denom > 1e-12 else 0.0
    s = min(max(s, -ha[i]), ha[i])
    t = min(max(br + s * c, -hb[j]), hb[j])
    for k in range(3):
        normal[k] = -n[k]
        points[0, k] = 0.5 * (ca[k] + s * a[i, k] + cb[k] + t * b[j, k])
    depth[0] = -sep
    ids[0] = EDGE_FLAG | id_a | (id_b << 4)
    return 1
