"""Continuous collision of the soft step: a fast body is moved back along its step to where it
first comes within ``slop`` of a static body or a plane (Box2D v3's ``b2SolveContinuous``,
``src/solver.c``, with ``b2TimeOfImpact``'s target separation); a fast body and a moving one
that the step left deep in each other are parted to ``slop`` (item 6 below).

Why: the soft step finds its rows once a step, at the step's start (``rigid/collide.py``,
with the margin of what each body can travel). Measured on benchmarks/rigid_fuzz.py's
joint-free scenes (seeds 0–299, 300 steps, before this stage): 28 of 91 ended a step more than
2 cm inside something; 27 of them a fast body (one step's travel 0.3–26 × its smallest
half-extent, or spinning a corner 0.5–3.8 × that far) inside a wall or the ground, a body that
had a row against that plane at the step's start; one a pair of moving spheres. A spinning
box brings a corner that no row follows to the wall; one deflected within the step by a bounce
or a neighbour crosses what its rows did not look for; and a rough box shot at 30–60° at a
5 cm static wall turns on its friction and leaves through it
(tests/physics/rigid/test_thin_wall.py).

What (after the substeps and the restitution):

1. A body is fast, as Box2D's ``b2_isFast``, when the farthest point of its shape moved, or
   moves at its end velocity, more than ``safety`` × its smallest half-extent in the step:
   ``|Δx| + θ·R`` or ``(|v| + |ω|·R)·dt``, R its bounding radius (0 for a sphere, whose
   surface a spin does not move). A slower body's rows, found with its travel, hold it.
2. Its step is swept as Box2D sweeps it: from the pose of the step's start to the pose of its
   end, the centre along the straight line and the orientation by the shortest rotation
   between the two (a slerp), against every static body and plane its swept bounding sphere
   comes near (and not the pairs a joint joins).
3. The time of impact of each is found by conservative advancement (Mirtich 1996; Box2D's
   ``b2TimeOfImpact`` iterates on its separating axis the same way): at a pose of the sweep
   the pair's gap s along a direction n (the signed distance and its direction: sphere and
   box against a plane, a sphere, a box; box against box, the best of the 15 separating
   axes, a lower bound of the distance) bounds their signed distance from below at every
   pose, and closes at most at L = max(0, −n·Δx) + θ·R along the sweep; so advancing by
   (s − target)/L never passes the target, and a pair that does not approach along n (a
   box sliding along the ground) is done at once.
4. The target is ``slop`` (Box2D's linear slop: where a TOI stops a body), or for a pair that
   starts the step within 2·``slop`` (touching: sliding, resting, pushed), ``slop`` less than
   its separation then: a body that rests or slides on the ground is left alone, one whose
   corner the step would drive deeper than ``slop`` past where it started is stopped first.
   A body that starts the step more than ``slop`` inside a static body or a plane ends it no
   deeper: at its end pose if that is no deeper, else where it began (what the rows did not
   push out; a target ``slop`` deeper each step let it creep in, ``slop`` a step).
   A body that starts apart and that the rows stopped at the surface (its end pose no deeper
   than ``slop`` along the impact's direction, found at the time of impact: a lower bound of
   its signed distance, and behind the face for a body that went through; and no point of
   it closing ``slop`` along it in a step at its end velocity) is left there (``_held``):
   moved back, it stayed ``slop`` short of the surface with the velocity the rows gave it
   (Cyclone's R10 ball at 300 m/s, no gravity: at rest 5 mm in front of the wall for ever).
5. The body is put at the earliest time of impact's pose; its velocities are kept (Box2D's
   too; the spin in the body's frame): it arrives with them, and the next step's collision
   finds the contact within its travel and its row stops it.
6. Then pairs of a fast body and another moving one, only where the step left them more than
   ``slop`` inside each other and ``slop`` deeper than they started (what their rows did not
   hold: a pair the rows caught ends touching, so a well-caught collision is never touched
   here). While they still move the way they came in, their relative motion is rewound
   about their centre of mass, along their relative velocity, to where they are ``slop``
   apart (``_rewind``: momentum, angular momentum and energy kept to round-off); else (the
   rows turned them, or a spin took them in, which no translation undoes) both go back along
   their sweeps to the pair's time of impact, as against a static body; so do they where
   the rewind would put one deeper than ``slop`` into a plane or a static body, and deeper
   than it was (the relative velocity need not be the way a body came, as for one the ground
   bounced up under a heavy one). A body of a joint
   group is never moved alone (that opens its joints): a free body against a group goes back
   alone along its sweep to where it meets the group's body where the step left it; two
   groups (or a body a world point holds) go back whole, each body along its sweep to the
   pair's time of impact.

Momentum and energy: the stage moves poses only; a body turned back keeps its spin in its own frame,
so its kinetic energy, linear momentum and |I·ω| are those the solve gave. The angular momentum
about a fixed origin changes by Δx × p of a moved body (nothing when its end velocity is along its
step's displacement, as in free flight) and by its spin's turn back. Against static bodies and
planes that is no loss (they take momentum anyway; Box2D's clamp does not conserve it either); a
pair of moving bodies is rewound about its centre of mass where it can be, which keeps both momenta,
and swept back (changing the angular momentum as above) only where the rows turned it or a spin took
it in. Pairs the rows held are never moved. Tried before the depth gate: sweeping a fast body
against the moving bodies' end poses (Box2D's bullets), or both bodies of every fast pair back to
its time of impact, acted on collisions the rows had caught: two 0.1 m boxes colliding at 5 m/s lost
2 % of their angular momentum.

Measured (dt 1/60; before → after): the thin wall (tests/physics/rigid/test_thin_wall.py,
boxes and spheres, 0°–60°, 50–500 m/s, 16 phases): rough boxes passed in up to 4 of 16
phases and sank up to 106 mm into the wall, smooth ones up to 37 mm → none passes, deepest
overlap at a step's end 2.91 mm rough, 0.14 mm smooth; benchmarks/rigid_fuzz.py's
joint-free scenes ending a step > 2 cm deep: 28 → 5 of 91 (each a pair of moving bodies).
With item 6 (the soft step, 300 steps, seeds 0–999: 307 joint-free scenes): 19 → 5 deep
(seeds 0–299: 5 → 1 of 91), 0 explosions before and after; the stage's own step changes a
force-free scene's kinetic energy by ≤ 4e-16 relative. Its cost with sleep off, the first 120
steps: the pyramid 0.8 ms of an 89 ms step, the 1000-box pit 1.4 ms of 235 ms (before: 1.5 ms
of 85, 1.3 of 250; a loaded 2-core machine). With ``soft_energy.limit_islands`` on contact
islands too (what a pair this stage parted could gain in its next collision, seed 380): the
slow fuzz's seeds 1000–1999 at 120 steps end a step deep in 38 of 1000 scenes (main before
both: 56), 6 of the 332 joint-free (14) and 32 of the 668 jointed (42); seeds 0–299, 300
steps, joint-free: none of 91.

Jointed scenes (stop 37): of the first 19 jointed scenes of seeds 1000–1999 that ended a
step deep, 7 were a free body hitting a jointed one, which item 6 then skipped (seed 1121: a
25 g box at 48 m/s into a 10.5 kg jointed box, 14.4 cm); the other 12 a light jointed body in a
wall or the ground (mass ratios in the group of 370 to 7e5): the joint's tree, solved exactly,
drags it in against contact rows that carry only its own mass, and item 4's target let it creep
in slop a step (seed 1264: a 2.8 g plank hinged on a 4 m arm to an 805 kg box, 9.3 cm). With
item 6 on joint groups and item 4's floor (120 steps): seeds 1000–1199, 5 → 0 scenes deep;
1200–1399, 8 → 2 (1263 jointed, 1279 joint-free); 300 steps: seeds 0–199's 143 jointed,
7 → 1 (163), none gains; the 91 joint-free of 0–299 none deep, as before.
Not covered: a slow body (not fast) dragged in (its rows, found with its travel, are what hold
it); the cause itself, the contact rows of a tree's body solved with that body's mass alone
while the tree is solved exactly (rows through the tree, as ``joint_loops`` solves a loop's,
would carry the group's mass).
"""

from __future__ import annotations

import math

import numpy as np
from numba import njit

from ..rigid.collide import plane_table
from ..rigid.islands import find_root
from ..rigid.scalar import qmul, qrot, qrot_inv
from ..rigid.shapes import BOX, SPHERE
from ..rigid.sweep import _half_width
from .settings import SolverSettings

_DEFAULTS = SolverSettings()  # ``sweep_back``'s settings when none are given

# ``slop`` (Box2D's ``B2_LINEAR_SLOP``, the separation a time of impact stops a body at) and
# ``safety`` (Box2D's ``safetyFactor``) are the settings' ``continuous_slop`` and
# ``continuous_safety`` (``SolverSettings``, ``World.settings``), passed down to the kernels.
# The advancement stops within 0.25 × slop of its target (``b2TimeOfImpact``'s tolerance).

#: Conservative-advancement iterations at most (``b2TimeOfImpact``'s 20): a guard of the root
#: finder, not a tuning number; each iteration lands short of the target, so stopping early is
#: safe, only earlier.
ITERATIONS = 20


@njit(cache=True, nogil=True)
def _rotation_between(q0, q1):
    """The shortest rotation taking orientation q0 to q1, as (unit axis, angle ∈ [0, π])."""
    w, x, y, z = qmul(q1[0], q1[1], q1[2], q1[3], q0[0], -q0[1], -q0[2], -q0[3])
    if w < 0.0:
        w, x, y, z = -w, -x, -y, -z
    s = math.sqrt(x * x + y * y + z * z)
    if s < 1e-15:
        return 1.0, 0.0, 0.0, 0.0
    return x / s, y / s, z / s, 2.0 * math.atan2(s, min(w, 1.0))


@njit(cache=True, nogil=True)
def _pose_at(x0, q0, dx, ux, uy, uz, angle, t):
    """The swept pose at fraction t: x0 + t·dx and q0 turned by t·angle about u."""
    half = 0.5 * t * angle
    s = math.sin(half)
    w, x, y, z = qmul(math.cos(half), ux * s, uy * s, uz * s, q0[0], q0[1], q0[2], q0[3])
    n = math.sqrt(w * w + x * x + y * y + z * z)
    return (x0[0] + t * dx[0], x0[1] + t * dx[1], x0[2] + t * dx[2],
            w / n, x / n, y / n, z / n)


@njit(cache=True, nogil=True)
def _point_box(px, py, pz, c, qw, qx, qy, qz, h):
    """Signed distance from a point to a box (centre c, orientation q, half-extents h), and
    the unit direction from the box towards the point along which it is measured."""
    lx, ly, lz = qrot_inv(qw, qx, qy, qz, px - c[0], py - c[1], pz - c[2])
    dx = abs(lx) - h[0]
    dy = abs(ly) - h[1]
    dz = abs(lz) - h[2]
    sx = 1.0 if lx >= 0.0 else -1.0
    sy = 1.0 if ly >= 0.0 else -1.0
    sz = 1.0 if lz >= 0.0 else -1.0
    ox, oy, oz = max(dx, 0.0) * sx, max(dy, 0.0) * sy, max(dz, 0.0) * sz
    out = math.sqrt(ox * ox + oy * oy + oz * oz)
    if out > 0.0:
        nx, ny, nz = qrot(qw, qx, qy, qz, ox / out, oy / out, oz / out)
        return out, nx, ny, nz
    if dx >= dy and dx >= dz:  # inside: out through the nearest face
        nx, ny, nz = qrot(qw, qx, qy, qz, sx, 0.0, 0.0)
        return dx, nx, ny, nz
    if dy >= dz:
        nx, ny, nz = qrot(qw, qx, qy, qz, 0.0, sy, 0.0)
        return dy, nx, ny, nz
    nx, ny, nz = qrot(qw, qx, qy, qz, 0.0, 0.0, sz)
    return dz, nx, ny, nz


@njit(cache=True, nogil=True)
def _box_axes(qw, qx, qy, qz, out):
    for k in range(3):
        e = (1.0 if k == 0 else 0.0, 1.0 if k == 1 else 0.0, 1.0 if k == 2 else 0.0)
        out[k, 0], out[k, 1], out[k, 2] = qrot(qw, qx, qy, qz, e[0], e[1], e[2])


@njit(cache=True, nogil=True)
def _box_box(pa, a, ha, pb, b, hb):
    """The largest gap of two boxes (axes rows a, b) over the 15 separating axes, and that
    axis pointing from B towards A: their distance when apart along a face axis, a lower
    bound of it otherwise, and minus their penetration depth when they overlap."""
    dx, dy, dz = pb[0] - pa[0], pb[1] - pa[1], pb[2] - pa[2]
    best = -math.inf
    bx, by, bz = 1.0, 0.0, 0.0
    for k in range(15):
        if k < 3:
            lx, ly, lz = a[k, 0], a[k, 1], a[k, 2]
        elif k < 6:
            lx, ly, lz = b[k - 3, 0], b[k - 3, 1], b[k - 3, 2]
        else:
            i = (k - 6) // 3
            j = (k - 6) % 3
            lx = a[i, 1] * b[j, 2] - a[i, 2] * b[j, 1]
            ly = a[i, 2] * b[j, 0] - a[i, 0] * b[j, 2]
            lz = a[i, 0] * b[j, 1] - a[i, 1] * b[j, 0]
            n = math.sqrt(lx * lx + ly * ly + lz * lz)
            if n < 1e-6:  # parallel edges: the face axes cover them
                continue
            lx, ly, lz = lx / n, ly / n, lz / n
        along = dx * lx + dy * ly + dz * lz
        gap = abs(along) - _half_width(a, ha, lx, ly, lz) - _half_width(b, hb, lx, ly, lz)
        if gap > best:
            best = gap
            f = -1.0 if along >= 0.0 else 1.0
            bx, by, bz = f * lx, f * ly, f * lz
    return best, bx, by, bz


@njit(cache=True, nogil=True)
def _plane_gap(shape_i, size_i, px, py, pz, qw, qx, qy, qz, nx, ny, nz, offset, axes_i):
    """Signed distance of body i at pose (p, q) from the plane n·x = offset (solid below)."""
    d = px * nx + py * ny + pz * nz - offset
    if shape_i == SPHERE:
        return d - size_i[0]
    _box_axes(qw, qx, qy, qz, axes_i)
    return d - _half_width(axes_i, size_i, nx, ny, nz)


@njit(cache=True, nogil=True)
def _pair_gap(shape_i, size_i, pi, qi, shape_j, size_j, pj, qj, axes_i, axes_j):
    """Bodies i and j at poses (pi, qi), (pj, qj): (a gap s along a unit direction n from j
    towards i, n). s is the signed distance (box–box: the best separating axis's gap, a lower
    bound of it); the gap along this fixed n bounds the signed distance from below at every
    other pose too (``_impact``)."""
    if shape_i == SPHERE:
        if shape_j == SPHERE:
            ex, ey, ez = pi[0] - pj[0], pi[1] - pj[1], pi[2] - pj[2]
            d = math.sqrt(ex * ex + ey * ey + ez * ez)
            if d == 0.0:
                return -size_i[0] - size_j[0], 1.0, 0.0, 0.0
            return d - size_i[0] - size_j[0], ex / d, ey / d, ez / d
        d, nx, ny, nz = _point_box(pi[0], pi[1], pi[2], pj, qj[0], qj[1], qj[2], qj[3], size_j)
        return d - size_i[0], nx, ny, nz
    if shape_j == SPHERE:
        d, nx, ny, nz = _point_box(pj[0], pj[1], pj[2], pi, qi[0], qi[1], qi[2], qi[3], size_i)
        return d - size_j[0], -nx, -ny, -nz
    _box_axes(qi[0], qi[1], qi[2], qi[3], axes_i)
    _box_axes(qj[0], qj[1], qj[2], qj[3], axes_j)
    return _box_box(pi, axes_i, size_i, pj, axes_j, size_j)


@njit(cache=True, nogil=True)
def _pose(k, t, x_start, q_start, sweep):
    """Body k's pose at fraction t of its sweep (``sweep`` row: Δx, unit axis, angle)."""
    w = sweep[k]
    px, py, pz, qw, qx, qy, qz = _pose_at(x_start[k], q_start[k], w[0:3], w[3], w[4], w[5],
                                          w[6], t)
    return (px, py, pz), (qw, qx, qy, qz)


@njit(cache=True, nogil=True)
def _gap_at(i, j, t, x_start, q_start, sweep, shape, size, plane_n, plane_d, axes_i, axes_j):
    """The signed gap (``_impact``'s) of body i at fraction t of its sweep from body j's
    (j ≥ 0) or from plane −1 − j."""
    pi, qi = _pose(i, t, x_start, q_start, sweep)
    if j < 0:
        s = -1 - j
        return _plane_gap(shape[i], size[i], pi[0], pi[1], pi[2], qi[0], qi[1], qi[2], qi[3],
                          plane_n[s, 0], plane_n[s, 1], plane_n[s, 2], plane_d[s], axes_i)
    pj, qj = _pose(j, t, x_start, q_start, sweep)
    gap, _, _, _ = _pair_gap(shape[i], size[i], pi, qi, shape[j], size[j], pj, qj, axes_i,
                             axes_j)
    return gap


@njit(cache=True, nogil=True)
def _impact(i, j, limit, x_start, q_start, sweep, shape, size, plane_n, plane_d, axes_i,
            axes_j, slop):
    """``_impact_normal``'s fraction of the step alone."""
    return _impact_normal(i, j, limit, x_start, q_start, sweep, shape, size, plane_n, plane_d,
                          axes_i, axes_j, slop)[0]


@njit(cache=True, nogil=True)
def _impact_normal(i, j, limit, x_start, q_start, sweep, shape, size, plane_n, plane_d, axes_i,
                   axes_j, slop):
    """The fraction of the step (< ``limit``) at which body i's sweep first brings it to the
    target separation from body j's sweep (a static body's is still) or, for j < 0, from
    plane −1 − j (module docstring); ``limit`` if it does not. Returns (that fraction, the
    pair's gap at the step's start, the direction n from j towards i at the last pose
    looked at: the impact's, where one is found).

    Conservative advancement along the direction found: from the gap s along n at t, the gap
    along that same n closes at most at L = max(0, −n·(Δx_i − Δx_j)) + θ_i·R_i + θ_j·R_j
    over the sweeps (the centres' approach along n; a turn by θ moves no point of a shape
    more than θ·R), and it bounds the signed distance from below at every pose; so advancing
    by (s − target)/L never passes the target, and a pair that does not approach along n (a
    box sliding along the ground) is done at once."""
    wi = sweep[i]
    spin = wi[6] * wi[7]
    if j >= 0:
        wj = sweep[j]
        ex, ey, ez = wi[0] - wj[0], wi[1] - wj[1], wi[2] - wj[2]
        spin += wj[6] * wj[7]
    else:
        ex, ey, ez = wi[0], wi[1], wi[2]
    tolerance = 0.25 * slop
    t = 0.0
    target = 0.0
    start = 0.0
    nx, ny, nz = 0.0, 0.0, 0.0
    for it in range(ITERATIONS + 1):
        pi, qi = _pose(i, t, x_start, q_start, sweep)
        if j < 0:
            s = -1 - j
            nx, ny, nz = plane_n[s, 0], plane_n[s, 1], plane_n[s, 2]
            gap = _plane_gap(shape[i], size[i], pi[0], pi[1], pi[2], qi[0], qi[1], qi[2], qi[3],
                             nx, ny, nz, plane_d[s], axes_i)
        else:
            pj, qj = _pose(j, t, x_start, q_start, sweep)
            gap, nx, ny, nz = _pair_gap(shape[i], size[i], pi, qi, shape[j], size[j], pj, qj,
                                        axes_i, axes_j)
        if it == 0:
            start = gap
            target = min(slop, gap - slop)
            if gap < -slop and (j < 0 or (sweep[j, 9] == 0.0 and sweep[j, 6] == 0.0)):
                # deeper than slop in a static body or a plane already (what a joint pulls in
                # against the rows): kept where it began unless it ends no deeper (a target
                # slop deeper each step let it creep in, slop a step: fuzz seed 1264)
                end = _gap_at(i, j, limit, x_start, q_start, sweep, shape, size, plane_n,
                              plane_d, axes_i, axes_j)
                return (limit if end >= gap else 0.0), start, nx, ny, nz
        elif gap <= target + tolerance or it == ITERATIONS:
            return t, start, nx, ny, nz
        rate = max(0.0, -(nx * ex + ny * ey + nz * ez)) + spin
        if rate <= 0.0:
            return limit, start, nx, ny, nz
        t += (gap - target) / rate
        if t >= limit:
            return limit, start, nx, ny, nz
    return t, start, nx, ny, nz


@njit(cache=True, nogil=True)
def _held(i, j, start, nx, ny, nz, pos, quat, vel, ang, shape, size, sweep, plane_d, dt,
          axes_i, axes_j, slop):
    """Whether body i, apart from static body j (or plane −1 − j) at the step's start (by
    2·``slop`` or more: item 4's target is then ``slop``), ends the step held against it:
    its gap from j along the impact's direction n (from j towards i), a lower bound of their
    signed distance (a separating axis), is no deeper than ``slop``, and at its end velocity
    no point of it comes ``slop`` closer along n in a step (−v·n + |ω|·R, R as in item 3).
    The rows then stopped it at the surface (a speculative point caught it), and moving it
    back would leave it ``slop`` short of the surface, with the velocity the rows gave it (a
    ball shot at a wall without gravity stopped 5 mm in front of it for ever); a body that
    went through or deep is more than ``slop`` behind j's face along n. One still closing
    was not stopped: left there, its next step (touching, item 4) may end ``slop`` deeper
    (the thin wall's tumbled box, 15° at 50 m/s, ended its first step 2.4 mm deep spinning
    at 30 rad/s, its second 6.8 mm); moved back, it arrives again, as before. A pair touching
    at the start keeps item 4's rule (a spinning box's corner, which no row follows, is
    stopped where it would go ``slop`` deeper than it began: left to end each step that much
    deeper, seed 79's box crept 4 mm a step into a wall)."""
    if start < 2.0 * slop:
        return False
    spin = math.sqrt(ang[i, 0] ** 2 + ang[i, 1] ** 2 + ang[i, 2] ** 2)
    closing = -(vel[i, 0] * nx + vel[i, 1] * ny + vel[i, 2] * nz) + spin * sweep[i, 7]
    if closing * dt > slop:
        return False
    if j < 0:
        s = -1 - j
        end = _plane_gap(shape[i], size[i], pos[i, 0], pos[i, 1], pos[i, 2], quat[i, 0],
                         quat[i, 1], quat[i, 2], quat[i, 3], nx, ny, nz, plane_d[s], axes_i)
    else:
        end = (pos[i, 0] - pos[j, 0]) * nx + (pos[i, 1] - pos[j, 1]) * ny \
            + (pos[i, 2] - pos[j, 2]) * nz
        for k, axes in ((i, axes_i), (j, axes_j)):
            if shape[k] == SPHERE:
                end -= size[k, 0]
            else:
                _box_axes(quat[k, 0], quat[k, 1], quat[k, 2], quat[k, 3], axes)
                end -= _half_width(axes, size[k], nx, ny, nz)
    return end >= -slop


@njit(cache=True, nogil=True)
def _impact_still(i, j, x_start, q_start, sweep, shape, size, plane_n, plane_d, axes_i, axes_j,
                  pos, quat, slop):
    """``_impact`` of body i's sweep against body j held where the step left it (its row of
    the sweep and its start pose stood in for that while it runs, then put back)."""
    row = sweep[j].copy()
    x0 = x_start[j].copy()
    q0 = q_start[j].copy()
    sweep[j, 0:7] = 0.0
    sweep[j, 9] = 0.0
    x_start[j] = pos[j]
    q_start[j] = quat[j]
    t = _impact(i, j, 1.0, x_start, q_start, sweep, shape, size, plane_n, plane_d, axes_i,
                axes_j, slop)
    sweep[j] = row
    x_start[j] = x0
    q_start[j] = q0
    return t


@njit(cache=True, nogil=True)
def _pair_deep(i, j, pos, quat, shape, size, x_start, q_start, axes_i, axes_j, slop):
    """Whether the step left bodies i and j more than ``slop`` inside each other and more than
    ``slop`` deeper than they started: what their rows did not hold (a bounce the rows caught
    ends touching; an overlap they push out ends no deeper)."""
    end, _, _, _ = _pair_gap(shape[i], size[i], pos[i], quat[i], shape[j], size[j], pos[j],
                             quat[j], axes_i, axes_j)
    if end >= -slop:
        return False
    start, _, _, _ = _pair_gap(shape[i], size[i], x_start[i], q_start[i], shape[j], size[j],
                               x_start[j], q_start[j], axes_i, axes_j)
    return end < start - slop


@njit(cache=True, nogil=True)
def _move_back(k, t, pos, quat, ang, inv_inertia, inv_i, x_start, q_start, sweep, axes_i,
               axes_j):
    """Put body k at fraction t of its sweep, its spin kept in its own frame."""
    (px, py, pz), (qw, qx, qy, qz) = _pose(k, t, x_start, q_start, sweep)
    # the spin in the body's own frame is kept, so its kinetic energy ½ω·Iω is (a world
    # ω kept while the body turned back changed it: force-free random scenes gained
    # energy in a step, 30 of 100 against 27 without the stage)
    _box_axes(quat[k, 0], quat[k, 1], quat[k, 2], quat[k, 3], axes_j)
    wb0 = axes_j[0, 0] * ang[k, 0] + axes_j[0, 1] * ang[k, 1] + axes_j[0, 2] * ang[k, 2]
    wb1 = axes_j[1, 0] * ang[k, 0] + axes_j[1, 1] * ang[k, 1] + axes_j[1, 2] * ang[k, 2]
    wb2 = axes_j[2, 0] * ang[k, 0] + axes_j[2, 1] * ang[k, 1] + axes_j[2, 2] * ang[k, 2]
    pos[k, 0], pos[k, 1], pos[k, 2] = px, py, pz
    quat[k, 0], quat[k, 1], quat[k, 2], quat[k, 3] = qw, qx, qy, qz
    _box_axes(qw, qx, qy, qz, axes_i)  # rows: the body axes in world, R's columns
    for u in range(3):
        ang[k, u] = wb0 * axes_i[0, u] + wb1 * axes_i[1, u] + wb2 * axes_i[2, u]
    for a in range(3):
        for b in range(3):
            v = 0.0
            for u in range(3):
                v += axes_i[u, a] * inv_inertia[k, u] * axes_i[u, b]
            inv_i[k, a, b] = v


@njit(cache=True, nogil=True)
def _fixed_gap(k, pos, quat, inv_mass, solid, shape, size, sweep, plane_n, plane_d, axes_i,
               axes_j):
    """Body k's smallest gap, at its pose now, from the planes and the static bodies near it
    (its signed distance from what cannot move; box–box a separating-axis lower bound)."""
    gap = math.inf
    for s in range(plane_n.shape[0]):
        gap = min(gap, _plane_gap(shape[k], size[k], pos[k, 0], pos[k, 1], pos[k, 2],
                                  quat[k, 0], quat[k, 1], quat[k, 2], quat[k, 3], plane_n[s, 0],
                                  plane_n[s, 1], plane_n[s, 2], plane_d[s], axes_i))
    for j in range(pos.shape[0]):
        if inv_mass[j] != 0.0 or not solid[j]:
            continue
        cx, cy, cz = pos[k, 0] - pos[j, 0], pos[k, 1] - pos[j, 1], pos[k, 2] - pos[j, 2]
        if math.sqrt(cx * cx + cy * cy + cz * cz) - sweep[k, 8] - sweep[j, 8] > gap:
            continue
        g, _, _, _ = _pair_gap(shape[k], size[k], pos[k], quat[k], shape[j], size[j], pos[j],
                               quat[j], axes_i, axes_j)
        gap = min(gap, g)
    return gap


@njit(cache=True, nogil=True)
def _rewind(i, j, pos, quat, rel, share, shape, size, x_start, dt, axes_i, axes_j, slop):
    """Free moving bodies i and j that the step left deep (``_pair_deep``), if they still move
    the way they came in: how far back (a time in [0, dt]) their relative motion, at their
    relative velocity ``rel``, is to be rewound to where they are ``slop`` apart, about their
    centre of mass: i moves by −share·back·rel, j by (1 − share)·back·rel, ``share`` i's
    inverse mass over both's. Returns −1 where that does not part them: they do not
    approach along their travel (the rows turned them), or rewinding a whole step leaves them
    closer than ``slop`` (the turn of a spinning body took them in, which only the sweep
    undoes).

    Why along the relative velocity: a displacement δ_i = w_i·D, δ_j = −w_j·D (w = 1/m over
    1/m_i + 1/m_j) keeps the centre of mass, and changes the angular momentum about any
    origin by m_i·δ_i × (v_i − v_j): nothing when D is along v_i − v_j. Velocities and
    orientations are kept, so linear and angular momentum and kinetic energy are those the
    solve gave, to round-off (issue 26 point 8). (Moving each body back along its own sweep,
    as against a static body, changed a fast pair's angular momentum by 5 %.)"""
    rx, ry, rz = rel[0], rel[1], rel[2]
    closed = 0.0  # their relative velocity along their relative travel this step
    for k in range(3):
        closed += rel[k] * (pos[i, k] - x_start[i, k] - pos[j, k] + x_start[j, k])
    if closed <= 0.0:
        return -1.0  # the rows turned it: not moving on the way it came in
    wi = share
    # u over [0, 1]: from the pose rewound by a whole step (u = 0) to the step's end (u = 1);
    # conservative advancement from u = 0 to where the gap first closes to slop (translation
    # only: the gap along n closes at most at −n·rel·dt over u)
    tolerance = 0.25 * slop
    pi = np.empty(3)
    pj = np.empty(3)
    u = 0.0
    back = dt
    for it in range(ITERATIONS + 1):
        back = (1.0 - u) * dt
        for k in range(3):
            r = (rx, ry, rz)[k]
            pi[k] = pos[i, k] - wi * back * r
            pj[k] = pos[j, k] + (1.0 - wi) * back * r
        gap, nx, ny, nz = _pair_gap(shape[i], size[i], pi, quat[i], shape[j], size[j], pj,
                                    quat[j], axes_i, axes_j)
        if it == 0 and gap < slop:
            return -1.0  # a step's travel back does not part them: a turn took them in
        if gap <= slop + tolerance or it == ITERATIONS:
            break
        rate = -(nx * rx + ny * ry + nz * rz) * dt
        if rate <= 0.0:
            break  # the rest of the way does not close it along n: stop here (apart)
        u = min(1.0, u + (gap - slop) / rate)
    return back


@njit(cache=True, nogil=True)
def clamp(pos, quat, vel, ang, inv_mass, inv_inertia, inv_i, shape, size, awake, x_start,
          q_start, dt, plane_n, plane_d, exclude, anchored, slop, safety):
    """Move every fast awake body back to its earliest time of impact with a static body or a
    plane this step, then part the pairs of a fast body and a moving one that ended it deep
    (module docstring); ``x_start``, ``q_start``: the poses of the step's start;
    ``exclude``: sorted keys lo·N + hi of jointed pairs (not swept against each other, and moved
    back together); ``anchored``: the bodies a joint holds to a world point. Returns how many
    bodies it moved. ``slop``, ``safety``: the settings' ``continuous_slop``,
    ``continuous_safety``."""
    nb = pos.shape[0]
    axes_i = np.empty((3, 3))
    axes_j = np.empty((3, 3))
    # per body: Δx (3), the turn's unit axis (3) and angle, the radius a turn moves a point
    # of its surface by at most (0 for a sphere), the bounding radius, the travel
    sweep = np.zeros((nb, 10))
    fast = np.zeros(nb, np.bool_)
    solid = np.zeros(nb, np.bool_)
    for k in range(nb):
        solid[k] = shape[k] == SPHERE or shape[k] == BOX
        if not solid[k]:
            continue
        w = sweep[k]
        if shape[k] == SPHERE:
            w[8] = size[k, 0]
            smallest = size[k, 0]
        else:
            w[7] = math.sqrt(size[k, 0] ** 2 + size[k, 1] ** 2 + size[k, 2] ** 2)
            w[8] = w[7]
            smallest = min(size[k, 0], size[k, 1], size[k, 2])
        if inv_mass[k] == 0.0 or not awake[k]:
            continue  # still: no sweep
        for u in range(3):
            w[u] = pos[k, u] - x_start[k, u]
        w[3], w[4], w[5], w[6] = _rotation_between(q_start[k], quat[k])
        w[9] = math.sqrt(w[0] ** 2 + w[1] ** 2 + w[2] ** 2)
        moved = w[9] + w[6] * w[7]
        speed = math.sqrt(vel[k, 0] ** 2 + vel[k, 1] ** 2 + vel[k, 2] ** 2)
        spin = math.sqrt(ang[k, 0] ** 2 + ang[k, 1] ** 2 + ang[k, 2] ** 2)
        fast[k] = moved > 0.0 and max(moved, (speed + spin * w[7]) * dt) > safety * smallest
    best = np.ones(nb)
    for i in range(nb):
        if not fast[i]:
            continue
        wi = sweep[i]
        x0 = x_start[i]
        for s in range(plane_n.shape[0]):  # the planes its swept bounding sphere comes near
            n0 = x0[0] * plane_n[s, 0] + x0[1] * plane_n[s, 1] + x0[2] * plane_n[s, 2]
            n1 = pos[i, 0] * plane_n[s, 0] + pos[i, 1] * plane_n[s, 1] + pos[i, 2] * plane_n[s, 2]
            if min(n0, n1) - plane_d[s] - wi[8] > slop:
                continue
            t, start, nx, ny, nz = _impact_normal(i, -1 - s, best[i], x_start, q_start, sweep,
                                                  shape, size, plane_n, plane_d, axes_i, axes_j,
                                                  slop)
            if t < best[i] and not _held(i, -1 - s, start, nx, ny, nz, pos, quat, vel, ang,
                                         shape, size, sweep, plane_d, dt, axes_i, axes_j,
                                         slop):
                best[i] = t
        for j in range(nb):
            if inv_mass[j] != 0.0 or not solid[j]:  # static bodies only (module docstring)
                continue
            key = min(i, j) * nb + max(i, j)
            at = np.searchsorted(exclude, key)
            if at < exclude.shape[0] and exclude[at] == key:
                continue
            # the sphere bounding the swept volume (the middle of the centre's segment, half
            # its length plus the shape's bounding radius) against the static body's
            cx = x0[0] + 0.5 * wi[0] - pos[j, 0]
            cy = x0[1] + 0.5 * wi[1] - pos[j, 1]
            cz = x0[2] + 0.5 * wi[2] - pos[j, 2]
            if math.sqrt(cx * cx + cy * cy + cz * cz) - 0.5 * wi[9] - wi[8] - sweep[j, 8] > slop:
                continue
            t, start, nx, ny, nz = _impact_normal(i, j, best[i], x_start, q_start, sweep,
                                                  shape, size, plane_n, plane_d, axes_i, axes_j,
                                                  slop)
            if t < best[i] and not _held(i, j, start, nx, ny, nz, pos, quat, vel, ang, shape,
                                         size, sweep, plane_d, dt, axes_i, axes_j, slop):
                best[i] = t
    # bodies held together by joints go back together, to the earliest impact among them: a
    # bone moved back alone opened its joints (the ragdoll demo with the soft step: 14-46 mm)
    root = np.arange(nb)
    for e in range(exclude.shape[0]):
        a = find_root(root, exclude[e] // nb)
        b = find_root(root, exclude[e] % nb)
        root[max(a, b)] = min(a, b)
    earliest = np.ones(nb)
    for k in range(nb):
        r = find_root(root, k)
        earliest[r] = min(earliest[r], best[k])
    for k in range(nb):
        if solid[k] and inv_mass[k] != 0.0 and awake[k]:
            best[k] = earliest[find_root(root, k)]
    count = 0
    for k in range(nb):
        if best[k] < 1.0:
            _move_back(k, best[k], pos, quat, ang, inv_inertia, inv_i, x_start, q_start, sweep,
                       axes_i, axes_j)
            count += 1
    # pairs of moving bodies that the rows let end the step deep (``_pair_deep``): two free
    # bodies are rewound about their centre of mass while they still move the way they came
    # in (``_rewind``); else each body of both units goes back along its sweep to the pair's
    # time of impact, a unit being a body alone or the whole group joints hold it in (moved
    # alone, one body of a group opens its joints: the stage skipped such pairs, and a free
    # body driven into a jointed one stayed deep, fuzz seed 1121). (A group rewound as one
    # along its centre of mass's velocity relative to the other body moved that body off its
    # own path, through the ground: seed 1138.)
    members = np.zeros(nb, np.int64)
    for k in range(nb):
        members[find_root(root, k)] += 1
    for e in range(anchored.shape[0]):
        members[find_root(root, anchored[e])] += 1  # (a world point: not a body alone)
    rel = np.empty(3)
    for i in range(nb):
        if not fast[i]:
            continue
        ri = find_root(root, i)
        for j in range(nb):
            if (j == i or inv_mass[j] == 0.0 or not solid[j] or not awake[j]
                    or (fast[j] and j < i)):
                continue  # (a pair of two fast bodies once, from its lower index)
            rj = find_root(root, j)
            if rj == ri:
                continue  # one joint group: its joints and rows hold its bodies together
            cx, cy, cz = pos[i, 0] - pos[j, 0], pos[i, 1] - pos[j, 1], pos[i, 2] - pos[j, 2]
            if math.sqrt(cx * cx + cy * cy + cz * cz) > sweep[i, 8] + sweep[j, 8]:
                continue  # their bounding spheres apart
            if not _pair_deep(i, j, pos, quat, shape, size, x_start, q_start, axes_i, axes_j,
                              slop):
                continue
            if members[ri] == 1 and members[rj] == 1:
                share = inv_mass[i] / (inv_mass[i] + inv_mass[j])
                for u in range(3):
                    rel[u] = vel[i, u] - vel[j, u]
                back = _rewind(i, j, pos, quat, rel, share, shape, size, x_start, dt, axes_i,
                               axes_j, slop)
                if back >= 0.0:
                    # a rewind moves each body along the pair's relative velocity, which need
                    # not be the way it came: a body the ground bounced up while a heavy one
                    # fell on it went back down through the ground (seed 278: a 74 kg box
                    # under a 1630 kg sphere, 5.6 cm above the ground, left 2.7 cm in it); one
                    # it would put deeper than slop into a plane or a static body, and deeper
                    # than it was, goes back along its sweep (below) instead
                    before_i = _fixed_gap(i, pos, quat, inv_mass, solid, shape, size, sweep,
                                          plane_n, plane_d, axes_i, axes_j)
                    before_j = _fixed_gap(j, pos, quat, inv_mass, solid, shape, size, sweep,
                                          plane_n, plane_d, axes_i, axes_j)
                    pi_end = pos[i].copy()
                    pj_end = pos[j].copy()
                    for u in range(3):
                        pos[i, u] -= share * back * rel[u]
                        pos[j, u] += (1.0 - share) * back * rel[u]
                    after_i = _fixed_gap(i, pos, quat, inv_mass, solid, shape, size, sweep,
                                         plane_n, plane_d, axes_i, axes_j)
                    after_j = _fixed_gap(j, pos, quat, inv_mass, solid, shape, size, sweep,
                                         plane_n, plane_d, axes_i, axes_j)
                    if ((after_i >= -slop or after_i >= before_i)
                            and (after_j >= -slop or after_j >= before_j)):
                        count += 2
                        continue
                    pos[i] = pi_end
                    pos[j] = pj_end
            if (members[ri] == 1) != (members[rj] == 1):
                # a free body and a joint group: the free body alone goes back along its
                # sweep, to where it meets the group's body where the step left it (the group
                # moved back along its bodies' sweeps opened a ball joint on a 5 m arm by
                # 2.5 cm, the chord of its turn: seed 1121)
                f, o = (i, j) if members[ri] == 1 else (j, i)
                t = _impact_still(f, o, x_start, q_start, sweep, shape, size, plane_n, plane_d,
                                  axes_i, axes_j, pos, quat, slop)
                pf, qf = _pose(f, t, x_start, q_start, sweep)
                gap, _, _, _ = _pair_gap(shape[f], size[f], pf, qf, shape[o], size[o], pos[o],
                                         quat[o], axes_i, axes_j)
                if gap >= -slop:  # (else its whole sweep is in the group's body: below)
                    if t < best[f]:
                        best[f] = t
                        _move_back(f, t, pos, quat, ang, inv_inertia, inv_i, x_start,
                                   q_start, sweep, axes_i, axes_j)
                        count += 1
                    continue
            t = _impact(i, j, 1.0, x_start, q_start, sweep, shape, size, plane_n, plane_d,
                        axes_i, axes_j, slop)
            for k in range(nb):  # both units, each body along its sweep to the impact
                rk = find_root(root, k)
                if ((rk == ri or rk == rj) and solid[k] and inv_mass[k] != 0.0 and awake[k]
                        and t < best[k]):
                    best[k] = t
                    _move_back(k, t, pos, quat, ang, inv_inertia, inv_i, x_start, q_start,
                               sweep, axes_i, axes_j)
                    count += 1
    return count


def sweep_back(bodies, planes, exclude, x_start: np.ndarray, q_start: np.ndarray,
               dt: float, anchored=None, settings: SolverSettings | None = None,
               table: np.ndarray | None = None, leapfrog: bool = False) -> int:
    """``clamp`` on a ``Bodies`` and the world's ``Plane``s (``exclude``: the jointed pairs'
    keys, ``anchored``: the bodies jointed to a world point; None for none) with the slop and
    safety factor of ``settings`` (``World.settings``; the defaults when None); returns the
    bodies moved. ``table``: the planes' ``collide.plane_table`` (made here when None: the
    world makes it once a step for the collision and this). ``leapfrog``: the bodies' velocity
    is the soft step's synchronised one and the sweep reads the half-step one the step drifted
    with (``before_sweep``, ``after_sweep``, in the same compiled call)."""
    st = _DEFAULTS if settings is None else settings
    b = bodies
    if table is None:
        table = plane_table(planes)
    plane_n = np.ascontiguousarray(table[:, :3])
    plane_d = np.ascontiguousarray(table[:, 3])
    exclude = _NO_KEYS if exclude is None else exclude
    anchored = _NO_KEYS if anchored is None else np.asarray(anchored, np.int64)
    args = (b.position, b.orientation, b.velocity, b.angular_velocity, b.inv_mass, b.inv_inertia,
            b.inv_inertia_world, b.shape, b.size, b.awake, x_start, q_start, dt, plane_n,
            plane_d, exclude, anchored, st.continuous_slop, st.continuous_safety)
    if leapfrog:
        return int(_leapfrog_clamp(*args, b.half_velocity, b.half_spin, b.left_velocity,
                                   b.left_spin))
    return int(clamp(*args))


#: No keys (``sweep_back``'s ``exclude`` and ``anchored`` when None).
_NO_KEYS = np.zeros(0, np.int64)


@njit(cache=True, nogil=True)
def _leapfrog_clamp(pos, quat, vel, ang, inv_mass, inv_inertia, inv_i, shape, size, awake,
                    x_start, q_start, dt, plane_n, plane_d, exclude, anchored, slop, safety,
                    half_v, half_w, left_v, left_w):
    """``before_sweep``, ``clamp``, ``after_sweep`` in one call (a tiny world's step paid ~1 µs
    a call for the three)."""
    before_sweep(vel, ang, half_v, half_w, left_v, left_w)
    moved = clamp(pos, quat, vel, ang, inv_mass, inv_inertia, inv_i, shape, size, awake,
                  x_start, q_start, dt, plane_n, plane_d, exclude, anchored, slop, safety)
    after_sweep(awake, vel, ang, half_v, half_w, left_v, left_w)
    return moved


@njit(cache=True, nogil=True)
def before_sweep(vel, ang, half_v, half_w, left_v, left_w):
    """Before the continuous stage (``body_stage.step``): the synchronised
    velocities the step left wait in ``left_v``, ``left_w``, and the bodies take the
    half-step ones their last drift moved with, which the sweep reads (``after_sweep``)."""
    for i in range(vel.shape[0]):
        for u in range(3):
            left_v[i, u] = vel[i, u]
            left_w[i, u] = ang[i, u]
            vel[i, u] = half_v[i, u]
            ang[i, u] = half_w[i, u]


@njit(cache=True, nogil=True)
def after_sweep(awake, vel, ang, half_v, half_w, left_v, left_w):
    """After the continuous stage: each body takes back its synchronised velocity, and
    ``left_v``, ``left_w`` keep it (``leave_step``), but for a body the sweep put back with its
    velocity turned (its own-frame spin kept): it keeps the sweep's and starts the next step
    afresh from it (marked inf; its half-step velocity was of the pose before)."""
    for i in range(vel.shape[0]):
        turned = False
        for u in range(3):
            if vel[i, u] != half_v[i, u] or ang[i, u] != half_w[i, u]:
                turned = True
        for u in range(3):
            if not turned:
                vel[i, u] = left_v[i, u]
                ang[i, u] = left_w[i, u]
            if turned or not awake[i]:
                left_v[i, u] = np.inf
