"""The solver's stages for joints (``pointmass.rigid.joints``): a point row block and up to three
angular rows per joint, solved beside the contacts in the soft step (``joint_soft``).

Point block. The relative velocity of the two joint points, Ċ = vB + ωB×rB − vA − ωA×rA, changes
by K·P for an impulse P on B (−P on A), with K = (wA + wB)·1 − [rA]× IA⁻¹ [rA]× − [rB]× IB⁻¹ [rB]×
(the 3×3 effective mass's inverse, Box2D's ball joint); one pass solves the three rows at once
(P = −K⁻¹Ċ), so a single joint converges in one pass whatever its lever arms.

Angular rows act on the relative angular velocity along a world axis u, Ċ = u·(ωB − ωA), with
the mass 1/(u·IA⁻¹u + u·IB⁻¹u). A row is an equality (a hinge's two locks: the axes stay
together) or a limit C ≥ 0 (the cone: C = cone − swing; the twist or hinge angle: C = angle −
low or high − angle, whichever bound is nearer), whose accumulated impulse never pulls. A limit
still open by C may close by C within the step and no more (target Ċ ≥ −C/dt: the contacts'
speculative rule, so a fast swing stops at the limit instead of overshooting it).

For the joints of the exact solve (``joint_tree`` DIRECT, LOOP) the point blocks' targets set here
are replaced in every pass by ``joint_predict``'s, which aim at the pose the step ends in; these
stay for the joints left to Gauss–Seidel. Drift (the separation C the step's straight-line motion
leaves) is removed in the velocity rows by a bias, Ċ = −β·C/dt (Baumgarte; Box2D v3's soft step is
the same with a spring-damper rate: ``joint_soft`` gives these rows its soft targets). Measured
alone, projection (Box2D v2's ``SolvePositionConstraints``) moves the bodies without their
velocities, so every step the next solve throws away the mismatch: a jointed pair tumbling freely at
2 rad/s lost 18 % of its angular momentum and 8 % of its energy in 10 s (dt 1/60). The bias acts
through equal and opposite impulses at the joint points, so momentum is kept to O(C·P): 0.13 % and
0.08 % with β = 0.5, the pendulum's period (within 4e-5) and energy band unchanged.

The point blocks of the joints that form a forest (chains, ragdolls, a top on its tip) are not
swept here but solved exactly, all at once, by ``joint_direct`` (``joint_tree``: which, and
why a long chain needs it); ``mode`` says which joint goes where, and OFF leaves a sleeping
joint out of every kernel.
"""

from __future__ import annotations

import math

import numpy as np
from numba import njit

from ..rigid.joint_rows import LIMIT, OFF, angular_rows, relative_spin
from ..rigid.scalar import qrot, solve3
from .joint_tree import DIRECT as DIRECT_JOINT
from .joint_tree import OFF as OFF_JOINT


@njit(cache=True, nogil=True)
def _axis_mass(inv_i, a, b, ux, uy, uz):
    """u·IA⁻¹u + u·IB⁻¹u."""
    k = 0.0
    for side in range(2):
        i = a if side == 0 else b
        if i < 0:
            continue
        m = inv_i[i]
        k += (ux * (m[0, 0] * ux + m[0, 1] * uy + m[0, 2] * uz)
              + uy * (m[1, 0] * ux + m[1, 1] * uy + m[1, 2] * uz)
              + uz * (m[2, 0] * ux + m[2, 1] * uy + m[2, 2] * uz))
    return k


@njit(cache=True, nogil=True)
def _point_matrix(inv_mass, inv_i, a, b, rax, ray, raz, rbx, rby, rbz, k):
    """K (module docstring) into ``k`` (3, 3)."""
    w = inv_mass[a] + (inv_mass[b] if b >= 0 else 0.0)
    for u in range(3):
        for v in range(3):
            k[u, v] = w if u == v else 0.0
    for side in range(2):
        i = a if side == 0 else b
        if i < 0:
            continue
        rx, ry, rz = (rax, ray, raz) if side == 0 else (rbx, rby, rbz)
        m = inv_i[i]
        # S·M·Sᵀ with S = [r]× (= −[r]× M [r]×)
        s = ((0.0, -rz, ry), (rz, 0.0, -rx), (-ry, rx, 0.0))
        for u in range(3):
            for v in range(3):
                acc = 0.0
                for p in range(3):
                    for q in range(3):
                        acc += s[u][p] * m[p, q] * s[v][q]
                k[u, v] += acc


@njit(cache=True, nogil=True)
def _push(vel, ang, inv_mass, inv_i, i, sign, rx, ry, rz, px, py, pz):
    """Give body i the impulse sign·P at arm r (i < 0: the world, nothing)."""
    if i < 0:
        return
    w = inv_mass[i] * sign
    vel[i, 0] += w * px
    vel[i, 1] += w * py
    vel[i, 2] += w * pz
    cx = sign * (ry * pz - rz * py)
    cy = sign * (rz * px - rx * pz)
    cz = sign * (rx * py - ry * px)
    for k in range(3):
        ang[i, k] += inv_i[i, k, 0] * cx + inv_i[i, k, 1] * cy + inv_i[i, k, 2] * cz


@njit(cache=True, nogil=True)
def _spin(ang, inv_i, i, sign, lx, ly, lz):
    """Give body i the angular impulse sign·L (i < 0: nothing)."""
    if i < 0:
        return
    for k in range(3):
        ang[i, k] += sign * (inv_i[i, k, 0] * lx + inv_i[i, k, 1] * ly + inv_i[i, k, 2] * lz)


@njit(cache=True, nogil=True)
def separation(ja, jb, la, lb, pos, quat, j):
    """(C, ra, rb): C = joint point on B − joint point on A [m] now, and the current arms."""
    a = ja[j]
    b = jb[j]
    ra = qrot(quat[a, 0], quat[a, 1], quat[a, 2], quat[a, 3], la[j, 0], la[j, 1], la[j, 2])
    if b >= 0:
        rb = qrot(quat[b, 0], quat[b, 1], quat[b, 2], quat[b, 3], lb[j, 0], lb[j, 1], lb[j, 2])
        xb = (pos[b, 0] + rb[0], pos[b, 1] + rb[1], pos[b, 2] + rb[2])
    else:
        rb = (0.0, 0.0, 0.0)
        xb = (lb[j, 0], lb[j, 1], lb[j, 2])
    c = (xb[0] - pos[a, 0] - ra[0], xb[1] - pos[a, 1] - ra[1], xb[2] - pos[a, 2] - ra[2])
    return c, ra, rb


@njit(cache=True, nogil=True)
def prepare(ja, jb, la, fa, fb, kind, lim, lb, inv_mass, inv_i, pos, quat, dt, beta, ra, rb,
            kmat, bias, axis, mass, target, row):
    """Per joint: world arms ra, rb (rb: 0 for the world), K into kmat (J, 3, 3), the point
    block's target Ċ = −β·C/dt into ``bias`` (J, 3), and per angular slot the axis (J, 3, 3),
    mass (J, 3), target Ċ [rad/s] (J, 3) and type (J, 3). β = 0: no bias (projection)."""
    out = np.empty((3, 5))
    for j in range(ja.shape[0]):
        c, _, _ = separation(ja, jb, la, lb, pos, quat, j)
        for k in range(3):
            bias[j, k] = -beta * c[k] / dt
        a = ja[j]
        b = jb[j]
        ra[j, 0], ra[j, 1], ra[j, 2] = qrot(quat[a, 0], quat[a, 1], quat[a, 2], quat[a, 3],
                                            la[j, 0], la[j, 1], la[j, 2])
        if b >= 0:
            rb[j, 0], rb[j, 1], rb[j, 2] = qrot(quat[b, 0], quat[b, 1], quat[b, 2], quat[b, 3],
                                                lb[j, 0], lb[j, 1], lb[j, 2])
        else:
            rb[j, 0] = rb[j, 1] = rb[j, 2] = 0.0
        _point_matrix(inv_mass, inv_i, a, b, ra[j, 0], ra[j, 1], ra[j, 2], rb[j, 0], rb[j, 1],
                      rb[j, 2], kmat[j])
        angular_rows(quat, a, b, fa, fb, kind, lim, j, out)
        for s in range(3):
            row[j, s] = int(out[s, 4])
            axis[j, s, 0], axis[j, s, 1], axis[j, s, 2] = out[s, 0], out[s, 1], out[s, 2]
            k = _axis_mass(inv_i, a, b, out[s, 0], out[s, 1], out[s, 2]) \
                if row[j, s] != OFF else 0.0
            mass[j, s] = 1.0 / k if k > 0.0 else 0.0
            if mass[j, s] == 0.0:
                row[j, s] = OFF
            c = out[s, 3]
            if row[j, s] == LIMIT and c > 0.0:
                target[j, s] = -c / dt  # open: may close by c, no more
            else:
                target[j, s] = -beta * c / dt


@njit(cache=True, nogil=True)
def warm_start(ja, jb, ra, rb, axis, row, inv_mass, inv_i, vel, ang, point, turn, lam, mode):
    """Apply last step's impulses: ``point`` (J, 3) [N·s] as it was, and each slot's angular
    impulse ``turn`` (J, 3, 3) [N·m·s], a world vector, seen along this step's axis (a limit's
    only if it pushes); ``lam`` (J, 3) gets those scalars. Joints whose ``mode`` is
    ``joint_tree.OFF`` (asleep) are left out."""
    for j in range(ja.shape[0]):
        lam[j, 0] = lam[j, 1] = lam[j, 2] = 0.0
        if mode[j] == OFF_JOINT:
            continue
        a = ja[j]
        b = jb[j]
        if mode[j] >= DIRECT_JOINT:  # the exact solve finds the whole impulse itself
            point[j, 0] = point[j, 1] = point[j, 2] = 0.0
        px, py, pz = point[j, 0], point[j, 1], point[j, 2]
        _push(vel, ang, inv_mass, inv_i, b, 1.0, rb[j, 0], rb[j, 1], rb[j, 2], px, py, pz)
        _push(vel, ang, inv_mass, inv_i, a, -1.0, ra[j, 0], ra[j, 1], ra[j, 2], px, py, pz)
        for s in range(3):
            if row[j, s] == OFF:
                continue
            ux, uy, uz = axis[j, s, 0], axis[j, s, 1], axis[j, s, 2]
            x = turn[j, s, 0] * ux + turn[j, s, 1] * uy + turn[j, s, 2] * uz
            if row[j, s] == LIMIT and x < 0.0:
                x = 0.0
            lam[j, s] = x
            _spin(ang, inv_i, b, 1.0, x * ux, x * uy, x * uz)
            _spin(ang, inv_i, a, -1.0, x * ux, x * uy, x * uz)


@njit(cache=True, nogil=True)
def solve_pass(ja, jb, ra, rb, kmat, bias, axis, mass, target, row, inv_mass, inv_i, vel, ang,
               point, lam, mode, mass_scale, impulse_scale, through):
    """One Gauss–Seidel pass over the joints: angular rows, then the point block (the point
    last, so it is the row most exactly met when the passes stop; not for a ``mode`` DIRECT
    joint, whose point the tree solve takes, nor an angular row solved ``through`` (J, 3) the
    tree, ``joint_loops.row_solve``). A row held by a position bias is soft with
    ``mass_scale`` and ``impulse_scale`` (Box2D's ``b2Softness``; 1 and 0: rigid); an open
    limit's speculative row never is. Returns the largest change of a row's velocity in the
    pass [m/s or rad/s]."""
    largest = 0.0
    for j in range(ja.shape[0]):
        if mode[j] == OFF_JOINT:
            continue
        a = ja[j]
        b = jb[j]
        for s in range(3):
            if row[j, s] == OFF or through[j, s]:
                continue
            ux, uy, uz = axis[j, s, 0], axis[j, s, 1], axis[j, s, 2]
            rel = relative_spin(ang, a, b, ux, uy, uz)
            ms, keep = mass_scale, impulse_scale
            if row[j, s] == LIMIT and target[j, s] <= 0.0:  # open: speculative, not soft
                ms, keep = 1.0, 0.0
            total = lam[j, s] + ms * (target[j, s] - rel) * mass[j, s] - keep * lam[j, s]
            if row[j, s] == LIMIT and total < 0.0:
                total = 0.0  # a limit pushes, never pulls
            d = total - lam[j, s]
            lam[j, s] = total
            change = abs(d) / mass[j, s]
            if change > largest:
                largest = change
            _spin(ang, inv_i, b, 1.0, d * ux, d * uy, d * uz)
            _spin(ang, inv_i, a, -1.0, d * ux, d * uy, d * uz)
        if mode[j] >= DIRECT_JOINT:  # DIRECT or LOOP: the tree solve's
            continue
        rax, ray, raz = ra[j, 0], ra[j, 1], ra[j, 2]
        rbx, rby, rbz = rb[j, 0], rb[j, 1], rb[j, 2]
        cx = -(vel[a, 0] + ang[a, 1] * raz - ang[a, 2] * ray)
        cy = -(vel[a, 1] + ang[a, 2] * rax - ang[a, 0] * raz)
        cz = -(vel[a, 2] + ang[a, 0] * ray - ang[a, 1] * rax)
        if b >= 0:
            cx += vel[b, 0] + ang[b, 1] * rbz - ang[b, 2] * rby
            cy += vel[b, 1] + ang[b, 2] * rbx - ang[b, 0] * rbz
            cz += vel[b, 2] + ang[b, 0] * rby - ang[b, 1] * rbx
        cx -= bias[j, 0]
        cy -= bias[j, 1]
        cz -= bias[j, 2]
        k = kmat[j]
        px, py, pz = solve3(k[0, 0], k[0, 1], k[0, 2], k[1, 0], k[1, 1], k[1, 2], k[2, 0],
                            k[2, 1], k[2, 2], -cx, -cy, -cz)
        if mass_scale != 1.0 or impulse_scale != 0.0:  # soft: the velocity change is K·P
            px = mass_scale * px - impulse_scale * point[j, 0]
            py = mass_scale * py - impulse_scale * point[j, 1]
            pz = mass_scale * pz - impulse_scale * point[j, 2]
            cx = -(k[0, 0] * px + k[0, 1] * py + k[0, 2] * pz)
            cy = -(k[1, 0] * px + k[1, 1] * py + k[1, 2] * pz)
            cz = -(k[2, 0] * px + k[2, 1] * py + k[2, 2] * pz)
        change = math.sqrt(cx * cx + cy * cy + cz * cz)
        if change > largest:
            largest = change
        point[j, 0] += px
        point[j, 1] += py
        point[j, 2] += pz
        _push(vel, ang, inv_mass, inv_i, b, 1.0, rbx, rby, rbz, px, py, pz)
        _push(vel, ang, inv_mass, inv_i, a, -1.0, rax, ray, raz, px, py, pz)
    return largest


@njit(cache=True, nogil=True)
def keep(axis, row, lam, turn, mode):
    """Each slot's impulse as a world vector (J, 3, 3), for next step's warm start (a
    sleeping joint keeps what it had)."""
    for j in range(axis.shape[0]):
        if mode[j] == OFF_JOINT:
            continue
        for s in range(3):
            x = lam[j, s] if row[j, s] != OFF else 0.0
            for k in range(3):
                turn[j, s, k] = x * axis[j, s, k]
