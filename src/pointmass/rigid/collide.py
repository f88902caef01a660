"""Contact generation for rigid bodies: broadphase pairs and planes through the narrow-phase
kernels into ``BodyContacts``.

Each pair's margin is ``margin`` plus how far its two bodies can travel this step (the
broadphase's ``reach``), so a point that can close within the step is already a (speculative)
row, which the solver lets close only by its gap: no contact that appears only once it is
deep. A pair not touching now is narrow-phased at the pose where it first comes within the
margin in the step (``sweep``), so its row holds it along the normal it will touch by: a
fast box does not pass a thin wall at any angle, and a pair that flies past gets no row.
Planes are the particles' ``Plane``/``Ground`` (n·x = offset, the solid on the −n side);
bodies meet every plane of the world.

Materials: μ = √(μa·μb), e = max(ea, eb) (a plane counts as a surface with its own μ and e);
a plane whose μ or e was never set (``Plane.body_friction``/``body_restitution`` None, passed
here as −1) leaves the body's own.
"""

from __future__ import annotations

import math

import numpy as np
from numba import njit

from ..keys import BODY_KEY_LIMIT, body_pair_key, body_plane_key
from .box_box import APART, WORK_FLOATS, WORK_INTS, box_box_into
from .broadphase import find_pairs
from .contacts import BodyContacts
from .manifold import MAX_POINTS
from .narrow_box import box_plane
from .narrow_sphere import sphere_box, sphere_plane, sphere_sphere
from .shapes import BOX, SPHERE
from .sweep import box_box_enter, sphere_box_enter, sphere_sphere_enter

#: Gap [m] below which a pair reports speculative points, besides what the bodies can travel
#: in the step (the broadphase's ``reach``, which already covers any approach at the speeds
#: of the step's start). Box3D keeps 4 × its 5 mm slop = 2 cm because it adds no travel;
#: with the travel added, 2 cm made a third of the 210-box pyramid's rows gaps between
#: resting neighbours 2 cm apart that never close (760 of 2360); 5 mm drops them (1600 rows,
#: the same after-run state: apex drift 1.3 cm, box overlap 0.1 mm).
SPECULATIVE_MARGIN = 0.005


@njit(cache=True, nogil=True)
def _emit(count, a, b, pa, pb, normal, points, depth, ids, n_points, mu, e, plane,
          out_a, out_b, out_n, out_ra, out_rb, out_d, out_mu, out_e, out_key):
    """Append the ``n_points`` points of one manifold; b < 0 means the plane of serial
    ``plane``. Returns the new count."""
    for j in range(n_points):
        out_a[count] = a
        out_b[count] = b
        for k in range(3):
            out_n[count, k] = normal[k]
            out_ra[count, k] = points[j, k] - pa[k]
            out_rb[count, k] = points[j, k] - (pb[k] if b >= 0 else 0.0)
        out_d[count] = depth[j]
        out_mu[count] = mu
        out_e[count] = e
        if b >= 0:
            out_key[count] = body_pair_key(a, b, ids[j])
        else:
            out_key[count] = body_plane_key(a, plane, ids[j])
        count += 1
    return count


@njit(cache=True, nogil=True, inline="always")
def _narrow(si, sj, pa, qa, ha, pb, qb, hb, m, normal, points, depth, ids, fw, iw):
    """The kernel for a sphere–sphere, sphere–box (sphere A) or box–box pair."""
    if si == SPHERE and sj == SPHERE:
        return sphere_sphere(pa, ha[0], pb, hb[0], m, normal, points, depth, ids)
    if si == SPHERE:
        return sphere_box(pa, ha[0], pb, qb, hb, m, normal, points, depth, ids)
    return box_box_into(pa, qa, ha, pb, qb, hb, m, normal, points, depth, ids, fw, iw)


@njit(cache=True, nogil=True, inline="always")
def _enter(si, sj, pa, qa, ha, pb, qb, hb, move, m, fw):
    """The fraction of the step at which the pair first comes within ``m`` (``sweep``)."""
    if si == SPHERE and sj == SPHERE:
        return sphere_sphere_enter(pa, ha[0], pb, hb[0], move, m)
    if si == SPHERE:
        return sphere_box_enter(pa, ha[0], pb, qb, hb, move, m)
    return box_box_enter(pa, qa, ha, pb, qb, hb, move, m, fw)


@njit(cache=True, nogil=True)
def pair_contacts(pos, quat, vel, turn, shape, size, inv_mass, friction, restitution, first,
                  second, reach, margin, dt, out_a, out_b, out_n, out_ra, out_rb, out_d, out_mu,
                  out_e, out_key):
    """Narrow phase over the broadphase pairs. A sphere is always body A of a sphere–box pair
    (the kernel's convention), so a pair keeps its orientation and its keys from step to
    step. Returns the rows written.

    A pair with a point within ``margin`` plus ``turn`` of both (how far each body's spin can
    carry a point in the step, ``spin_reach``) now is taken at its pose now, with the margin
    grown by the bodies' whole reach, as the broadphase found it. Any other pair is swept
    (``sweep``: each body at its step-start velocity): one that comes within the margin at a
    fraction u of the step is taken at that pose, where its normal and points are the ones it
    will touch by; each point's gap is carried back to the step's start along that normal
    (gap + closing speed·u·dt), and the point moves back with the bodies (weighted by inverse
    mass: with the moving body against a static one), so the row closes the pair by its gap
    along the right normal and no more.
    A pair that stays apart all step gets no row.

    What the solver must do with a row of depth d < 0 (a gap): let its bodies close along its
    normal by at most −d within the step (the soft step's speculative row, ``body_soft``, as
    Box2D v3's with s·inv_h), and follow the point from the body-fixed anchors
    r_a, r_b, which coincide at the step's start."""
    normal = np.zeros(3)
    points = np.zeros((MAX_POINTS, 3))
    depth = np.zeros(MAX_POINTS)
    ids = np.zeros(MAX_POINTS, np.int64)
    fw = np.empty(WORK_FLOATS)
    iw = np.empty(WORK_INTS, np.int64)
    move = np.empty(3)
    at_a = np.empty(3)
    at_b = np.empty(3)
    count = 0
    for p in range(first.shape[0]):
        i = first[p]
        j = second[p]
        si = shape[i]
        sj = shape[j]
        if (si != SPHERE and si != BOX) or (sj != SPHERE and sj != BOX):
            continue
        a, b = (j, i) if si == BOX and sj == SPHERE else (i, j)
        sa, sb = shape[a], shape[b]
        m = margin + turn[a] + turn[b]
        # the pose now first (with the broadphase's margin, as a pair that can only close by
        # its gap has always been taken): a point within m of touching now says the pair is
        # touching, and resting pairs, most of a pile's, cost one narrow phase as before
        m_now = margin + reach[i] + reach[j]
        got = _narrow(sa, sb, pos[a], quat[a], size[a], pos[b], quat[b], size[b], m_now,
                      normal, points, depth, ids, fw, iw)
        # none: farther than m_now on an axis (or, for a sphere, at all), which is m plus
        # at least their relative travel, so they stay apart all step; a box pair that no
        # axis showed apart (its clipping kept no point) is swept
        if got == 0 and (sa == SPHERE or sb == SPHERE or fw[APART] > m_now):
            continue
        touching = False
        for q in range(got):
            touching = touching or depth[q] >= -m
        if not touching:
            for k in range(3):
                move[k] = (vel[a, k] - vel[b, k]) * dt
            u = _enter(sa, sb, pos[a], quat[a], size[a], pos[b], quat[b], size[b], move, m,
                       fw)
            if u < 0.0:
                continue
            if u > 0.0:
                for k in range(3):
                    at_a[k] = pos[a, k] + u * dt * vel[a, k]
                    at_b[k] = pos[b, k] + u * dt * vel[b, k]
                # the margin from here: m plus what is left of the travel, so every feature
                # that can touch in the rest of the step is a row (a box that meets the wall
                # with an edge spins onto its face within the step; with only the edge's row,
                # the spin that row gives carries the face through); and m again, for
                # rounding at the touch
                rest = (1.0 - u) * math.sqrt(move[0] ** 2 + move[1] ** 2 + move[2] ** 2)
                got = _narrow(sa, sb, at_a, quat[a], size[a], at_b, quat[b], size[b],
                              2.0 * m + rest, normal, points, depth, ids, fw, iw)
                closing = u * (move[0] * normal[0] + move[1] * normal[1]
                               + move[2] * normal[2])
                w = inv_mass[a] + inv_mass[b]  # > 0: the broadphase drops static pairs
                wa = inv_mass[a] / w if w > 0.0 else 0.5
                for q in range(got):
                    depth[q] += closing
                    for k in range(3):
                        points[q, k] -= u * dt * (wa * vel[a, k] + (1.0 - wa) * vel[b, k])
        if got == 0:
            continue
        mu = math.sqrt(friction[a] * friction[b])
        e = max(restitution[a], restitution[b])
        # np.int64: plain int64 arguments, not Literal[int] ones, so _emit compiles once (see
        # box_box_into).
        count = _emit(np.int64(count), a, b, pos[a], pos[b], normal, points, depth, ids, got,
                      mu, e, np.int64(0), out_a, out_b, out_n, out_ra, out_rb, out_d, out_mu,
                      out_e, out_key)
    return count


@njit(cache=True, nogil=True)
def plane_contacts(pos, quat, shape, size, inv_mass, friction, restitution, reach, margin,
                   plane_n, plane_d, plane_mu, plane_e, plane_serial, start,
                   out_a, out_b, out_n, out_ra, out_rb, out_d, out_mu, out_e, out_key):
    """Every movable body against every plane its bounding sphere comes within the margin of,
    written from row ``start``; returns the count."""
    normal = np.zeros(3)
    points = np.zeros((MAX_POINTS, 3))
    depth = np.zeros(MAX_POINTS)
    ids = np.zeros(MAX_POINTS, np.int64)
    count = start
    for i in range(pos.shape[0]):
        if inv_mass[i] == 0.0:
            continue
        # the bounding sphere: a plane farther than it (plus the margin) has no point to give
        # (the pit's boxes met all 5 planes: 10 % of its step in the narrow phase)
        bound = size[i, 0] if shape[i] == SPHERE else math.sqrt(
            size[i, 0] ** 2 + size[i, 1] ** 2 + size[i, 2] ** 2)
        for s in range(plane_n.shape[0]):
            m = margin + reach[i]
            if (pos[i, 0] * plane_n[s, 0] + pos[i, 1] * plane_n[s, 1] + pos[i, 2] * plane_n[s, 2]
                    - plane_d[s] - bound >= m):
                continue
            if shape[i] == SPHERE:
                got = sphere_plane(pos[i], size[i, 0], plane_n[s], plane_d[s], m, normal,
                                   points, depth, ids)
            elif shape[i] == BOX:
                got = box_plane(pos[i], quat[i], size[i], plane_n[s], plane_d[s], m, normal,
                                points, depth, ids)
            else:
                continue
            if got == 0:
                continue
            mu = friction[i] if plane_mu[s] < 0.0 else math.sqrt(friction[i] * plane_mu[s])
            e = restitution[i] if plane_e[s] < 0.0 else max(restitution[i], plane_e[s])
            count = _emit(np.int64(count), i, np.int64(-1), pos[i], pos[i], normal, points,
                          depth, ids, got, mu, e, plane_serial[s], out_a, out_b, out_n, out_ra,
                          out_rb, out_d, out_mu, out_e, out_key)
    return count


@njit(cache=True, nogil=True)
def spin_reach(ang, shape, size, dt):
    """(N,) how far [m] each body's spin can carry a point of its shape in ``dt``."""
    n = ang.shape[0]
    turn = np.empty(n)
    for i in range(n):
        if shape[i] == SPHERE:
            radius = size[i, 0]
        else:
            radius = math.sqrt(size[i, 0] ** 2 + size[i, 1] ** 2 + size[i, 2] ** 2)
        spin = math.sqrt(ang[i, 0] ** 2 + ang[i, 1] ** 2 + ang[i, 2] ** 2)
        turn[i] = spin * radius * dt
    return turn


@njit(cache=True, nogil=True)
def _collide_all(pos, quat, vel, ang, shape, size, inv_mass, friction, restitution, margin, dt,
                 plane, active, exclude, out_a, out_b, out_n, out_ra, out_rb, out_d, out_mu,
                 out_e, out_key):
    """``generate`` in one compiled call (a tiny world's collision was ~12 numpy calls and 4
    kernel calls a step): the broadphase (``find_pairs``), the pairs with an awake body
    (``active``; empty: all) that are not excluded (``exclude``: sorted keys lo·N + hi),
    ``spin_reach``, the pairs' and the awake bodies' planes' narrow phase. ``plane`` (P, 7):
    each plane's normal, offset, μ, e (−1: the body's) and serial. Writes the rows a, b,
    normal, r_a, r_b, depth, μ, e, key into the ``out_*`` buffers (``BodyContacts.room``)
    and returns their count; or, when the buffers have fewer rows than the pairs could make,
    −that many, writing nothing (the caller grows them and calls again). Written into the
    caller's buffers, not returned: numba boxes each array it returns to Python (~2.5 µs
    apiece, a dtype unpickled each time), and the nine returned arrays were ~15 % of a tiny
    world's step."""
    n = pos.shape[0]
    every = active.shape[0] == 0  # no mask: every body is active
    first, second, reach = find_pairs(pos, quat, vel, ang, shape, size, inv_mass, margin, dt)
    keep = 0
    for k in range(first.shape[0]):
        i, j = first[k], second[k]
        if not (every or active[i] or active[j]):
            continue
        if exclude.shape[0]:
            key = i * n + j
            at = np.searchsorted(exclude, key)
            if at < exclude.shape[0] and exclude[at] == key:
                continue
        first[keep], second[keep] = i, j
        keep += 1
    first = first[:keep]
    second = second[:keep]
    on_planes = np.empty(n)  # the plane kernel skips w = 0: sleeping bodies
    for i in range(n):
        on_planes[i] = inv_mass[i] if every or active[i] else 0.0
    turn = spin_reach(ang, shape, size, dt)
    pairs = keep
    n_planes = plane.shape[0]
    rows = MAX_POINTS * (pairs + n * n_planes)
    if rows > out_a.shape[0]:
        return -rows
    count = pair_contacts(pos, quat, vel, turn, shape, size, inv_mass, friction, restitution,
                          first, second, reach, margin, dt, out_a, out_b, out_n, out_ra, out_rb,
                          out_d, out_mu, out_e, out_key)
    if n_planes:
        plane_n = np.empty((n_planes, 3))
        plane_d = np.empty(n_planes)
        plane_mu = np.empty(n_planes)
        plane_e = np.empty(n_planes)
        serial = np.empty(n_planes, np.int64)
        for s in range(n_planes):
            plane_n[s, 0], plane_n[s, 1], plane_n[s, 2] = plane[s, 0], plane[s, 1], plane[s, 2]
            plane_d[s] = plane[s, 3]
            plane_mu[s] = plane[s, 4]
            plane_e[s] = plane[s, 5]
            serial[s] = np.int64(plane[s, 6])
        count = plane_contacts(pos, quat, shape, size, on_planes, friction, restitution, reach,
                               margin, plane_n, plane_d, plane_mu, plane_e, serial, count,
                               out_a, out_b, out_n, out_ra, out_rb, out_d, out_mu, out_e,
                               out_key)
    return count


#: ``_collide_all``'s "no mask" and "no pair left out", shared (empty: nothing can be written
#: into them), so a step allocates neither.
_ALL_ACTIVE = np.zeros(0, np.bool_)
_NONE_EXCLUDED = np.zeros(0, np.int64)


def plane_table(planes) -> np.ndarray:
    """(P, 7) float64: each plane's normal, offset, μ and e for bodies (−1: a material the
    plane leaves to the body, not set; see pointmass.collide) and its serial."""
    table = np.empty((len(planes), 7))  # row by row: np.array of a list of tuples of numpy
    for i, p in enumerate(planes):       # scalars took twice as long, every step
        n = p.normal
        friction, restitution = p.body_friction, p.body_restitution
        table[i] = (n[0], n[1], n[2], p.offset, -1.0 if friction is None else friction,
                    -1.0 if restitution is None else restitution, p.serial)
    return table


def generate(bodies, planes, dt: float, contacts: BodyContacts,
             margin: float = SPECULATIVE_MARGIN, active: np.ndarray | None = None,
             exclude: np.ndarray | None = None, table: np.ndarray | None = None) -> None:
    """Fill ``contacts`` with every body–body and body–plane point of ``bodies`` (a
    ``Bodies``) for a step of ``dt`` [s]; ``planes`` is a sequence of ``pointmass.Plane``
    (its normal, offset, friction, restitution; the particle selection does not apply).
    With ``active`` (N,) bool (sleeping, ``islands.py``), only pairs with an active body and
    active bodies on planes are narrow-phased: sleeping and static bodies are left alone.
    ``exclude``: sorted keys lo·N + hi of body pairs that never collide (jointed bodies).
    ``table``: ``plane_table(planes)``, when the caller made it already (once a step)."""
    b = bodies
    if b.count > BODY_KEY_LIMIT:
        raise ValueError(f"at most {BODY_KEY_LIMIT} bodies collide (contact keys have 20 bits "
                         f"for a body), got {b.count}")
    if active is None:
        active = _ALL_ACTIVE
    if exclude is None:
        exclude = _NONE_EXCLUDED
    if table is None:
        table = plane_table(planes)
    rows = 0
    while True:
        room = contacts.room(rows)
        count = _collide_all(b.position, b.orientation, b.velocity, b.angular_velocity, b.shape,
                             b.size, b.inv_mass, b.friction, b.restitution, float(margin),
                             float(dt), table, active, exclude, *room)
        if count >= 0:
            break
        rows = -count
    contacts.take_room(count)
