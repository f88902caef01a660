"""The solver's stages for rigid-body contact points: the particles' stages with angular terms.

A row acts at lever arms rA, rB; a unit impulse P along a direction d changes the velocity of
the point by (wa + wb + (rA×d)·IA⁻¹(rA×d) + (rB×d)·IB⁻¹(rB×d))·|P|, so the effective mass is
the inverse of that (a particle is the case r = 0, I⁻¹ = 0: 1/(wa + wb), ``stages.prepare``).
The stages, in the order a substep runs them:

1. ``prepare`` — per point, the normal effective mass and the target separating velocity:
   the bounce −e·vs with the resting-contact trick (``kernels.bounce_target``, the same kernel
   as the particles) for a point that closes within the step, else gap/dt for a speculative
   point (it may close by its gap, no more), else 0; per manifold, the friction block
   (``body_manifolds.prepare_friction``).
2. ``warm_start`` — each point begins from the normal impulse its key needed last step, each
   manifold from the friction and twist its points kept (Catto 2006).
3. ``body_passes.solve_velocities`` — sequential impulses, manifold by manifold: a twist
   about the normal (within ±μ·ρ·Λ, Λ the manifold's normal impulse), friction once at the friction
   centre on two tangents (clamped together to the disc μ·Λ; ``body_manifolds``), then each
   point's normal impulse (accumulated, clamped ≥ 0), each applied to v and ω of both bodies
   before the next row reads them.
4. (the caller drifts the bodies: x += v·dt and the free rotation)
5. ``project_positions`` — nonlinear Gauss–Seidel (Box2D v2's ``SolvePositionConstraints``):
   each point's current depth is recomputed from body-fixed anchors and the penetration beyond
   ``SLOP`` is removed in part (``BAUMGARTE``), moving positions and orientations only. No
   velocity changes, so the projection adds no energy and bounces nothing.

The stores into v and ω are written out in the loop bodies (the pure ``_kick`` computes them): an
inlined helper that stores into arrays was 4–20× slower in this code base's particle kernels,
and one loop over a manifold's rows that chose each row's kind through a 12-value helper was
2× slower than the per-point friction it replaced (measured on the pyramid).
"""

from __future__ import annotations

import math

from numba import njit

from ..rigid.scalar import qrot, qrot_inv, turn
from .kernels import bounce_target, closing_within_step

#: Penetration [m] the projection leaves alone: with none, a resting point would be nudged every
#: substep by float noise; at 0.1 mm a 10-box tower sinks at most 1 mm.
SLOP = 1e-4
#: Fraction of the penetration beyond ``SLOP`` removed per projection pass (Box2D v2's 0.2:
#: more overshoots where points share a body).
BAUMGARTE = 0.2
#: Largest correction of one point in one pass [m] (Box2D's ``b2_maxLinearCorrection``).
MAX_CORRECTION = 0.2


@njit(cache=True, inline="always")
def _arm_mass(inv_i, i, rx, ry, rz, dx, dy, dz):
    """(r×d)·I⁻¹(r×d) for body i (read only)."""
    cx = ry * dz - rz * dy
    cy = rz * dx - rx * dz
    cz = rx * dy - ry * dx
    m = inv_i[i]
    return (cx * (m[0, 0] * cx + m[0, 1] * cy + m[0, 2] * cz)
            + cy * (m[1, 0] * cx + m[1, 1] * cy + m[1, 2] * cz)
            + cz * (m[2, 0] * cx + m[2, 1] * cy + m[2, 2] * cz))


@njit(cache=True, inline="always")
def _point_velocity(vel, ang, i, rx, ry, rz):
    """v + ω × r of body i (read only)."""
    return (vel[i, 0] + ang[i, 1] * rz - ang[i, 2] * ry,
            vel[i, 1] + ang[i, 2] * rx - ang[i, 0] * rz,
            vel[i, 2] + ang[i, 0] * ry - ang[i, 1] * rx)


@njit(cache=True, inline="always")
def _basis(nx, ny, nz):
    """Two unit tangents (t1, t2) with (n, t1, t2) right-handed; a fixed function of n, so the
    friction impulse kept for warm starting means the same thing next step."""
    if abs(nx) >= 0.57735:
        s = 1.0 / math.sqrt(nx * nx + ny * ny)
        ax, ay, az = ny * s, -nx * s, 0.0
    else:
        s = 1.0 / math.sqrt(ny * ny + nz * nz)
        ax, ay, az = 0.0, nz * s, -ny * s
    return ax, ay, az, ny * az - nz * ay, nz * ax - nx * az, nx * ay - ny * ax


@njit(cache=True, nogil=True)
def prepare(ca, cb, n, ra, rb, depth, e, inv_mass, inv_i, quat, vel, ang, acc, dt, threshold,
            mass_n, target, la, lb):
    """Per point: the normal effective mass; the target separating velocity [m/s]; the
    body-fixed anchors la, lb (lb: the world point for scenery) the projection follows. (The
    friction is prepared per manifold: ``body_manifolds.prepare_friction``.)"""
    for c in range(ca.shape[0]):
        a = ca[c]
        b = cb[c]
        nx, ny, nz = n[c, 0], n[c, 1], n[c, 2]
        rax, ray, raz = ra[c, 0], ra[c, 1], ra[c, 2]
        kn = inv_mass[a] + _arm_mass(inv_i, a, rax, ray, raz, nx, ny, nz)
        vx, vy, vz = _point_velocity(vel, ang, a, rax, ray, raz)
        along = abs(acc[a, 0] * nx + acc[a, 1] * ny + acc[a, 2] * nz)
        la[c, 0], la[c, 1], la[c, 2] = qrot_inv(quat[a, 0], quat[a, 1], quat[a, 2], quat[a, 3],
                                                rax, ray, raz)
        if b >= 0:
            rbx, rby, rbz = rb[c, 0], rb[c, 1], rb[c, 2]
            kn += inv_mass[b] + _arm_mass(inv_i, b, rbx, rby, rbz, nx, ny, nz)
            ux, uy, uz = _point_velocity(vel, ang, b, rbx, rby, rbz)
            vx -= ux
            vy -= uy
            vz -= uz
            along += abs(acc[b, 0] * nx + acc[b, 1] * ny + acc[b, 2] * nz)
            lb[c, 0], lb[c, 1], lb[c, 2] = qrot_inv(quat[b, 0], quat[b, 1], quat[b, 2],
                                                    quat[b, 3], rbx, rby, rbz)
        else:
            lb[c, 0], lb[c, 1], lb[c, 2] = rb[c, 0], rb[c, 1], rb[c, 2]
        mass_n[c] = 1.0 / kn if kn > 0.0 else 0.0
        vs = vx * nx + vy * ny + vz * nz
        d = depth[c]
        bounce = 0.0
        if closing_within_step(vs, d, dt):
            bounce = bounce_target(vs, -along * dt, e[c], threshold)
        if bounce > 0.0:
            target[c] = bounce
        else:  # no bounce: a gap may close by itself, no more (lands exactly)
            target[c] = d / dt if d < 0.0 else 0.0


@njit(cache=True, inline="always")
def _kick(inv_mass, inv_i, i, rx, ry, rz, px, py, pz, tx, ty, tz):
    """What a linear impulse P at arm r plus an angular impulse τ do to body i: (Δv, Δω)."""
    w = inv_mass[i]
    lx = ry * pz - rz * py + tx
    ly = rz * px - rx * pz + ty
    lz = rx * py - ry * px + tz
    m = inv_i[i]
    return (w * px, w * py, w * pz, m[0, 0] * lx + m[0, 1] * ly + m[0, 2] * lz,
            m[1, 0] * lx + m[1, 1] * ly + m[1, 2] * lz, m[2, 0] * lx + m[2, 1] * ly + m[2, 2] * lz)


@njit(cache=True, inline="always")
def _relative_velocity(vel, ang, a, b, rax, ray, raz, rbx, rby, rbz):
    """Velocity of the point on a minus that on b (scenery, b < 0, is still)."""
    vx, vy, vz = _point_velocity(vel, ang, a, rax, ray, raz)
    if b >= 0:
        ux, uy, uz = _point_velocity(vel, ang, b, rbx, rby, rbz)
        return vx - ux, vy - uy, vz - uz
    return vx, vy, vz


@njit(cache=True, nogil=True)
def warm_start(start, ca, cb, n, ra, rb, fa, fb, t1, t2, inv_mass, inv_i, vel, ang, impulse,
               jt1, jt2, jtw):
    """Apply each point's remembered normal ``impulse`` and each manifold's remembered friction
    (``jt1``, ``jt2``) and twist ``jtw`` impulses."""
    for k in range(t1.shape[0]):
        s0 = start[k]
        a = ca[s0]
        b = cb[s0]
        for c in range(s0 - 1, start[k + 1]):
            if c < s0:  # the manifold's friction block at its centre, and its twist
                rax, ray, raz = fa[k, 0], fa[k, 1], fa[k, 2]
                rbx, rby, rbz = fb[k, 0], fb[k, 1], fb[k, 2]
                px = jt1[k] * t1[k, 0] + jt2[k] * t2[k, 0]
                py = jt1[k] * t1[k, 1] + jt2[k] * t2[k, 1]
                pz = jt1[k] * t1[k, 2] + jt2[k] * t2[k, 2]
                tx, ty, tz = jtw[k] * n[s0, 0], jtw[k] * n[s0, 1], jtw[k] * n[s0, 2]
            else:
                rax, ray, raz = ra[c, 0], ra[c, 1], ra[c, 2]
                rbx, rby, rbz = rb[c, 0], rb[c, 1], rb[c, 2]
                px, py, pz = impulse[c] * n[c, 0], impulse[c] * n[c, 1], impulse[c] * n[c, 2]
                tx = ty = tz = 0.0
            dvx, dvy, dvz, dwx, dwy, dwz = _kick(inv_mass, inv_i, a, rax, ray, raz, px, py, pz,
                                                 tx, ty, tz)
            vel[a, 0] += dvx
            vel[a, 1] += dvy
            vel[a, 2] += dvz
            ang[a, 0] += dwx
            ang[a, 1] += dwy
            ang[a, 2] += dwz
            if b >= 0:
                dvx, dvy, dvz, dwx, dwy, dwz = _kick(inv_mass, inv_i, b, rbx, rby, rbz, px, py,
                                                     pz, tx, ty, tz)
                vel[b, 0] -= dvx
                vel[b, 1] -= dvy
                vel[b, 2] -= dvz
                ang[b, 0] -= dwx
                ang[b, 1] -= dwy
                ang[b, 2] -= dwz


@njit(cache=True, inline="always")
def _depth(ca, cb, n, la, lb, depth0, pos, quat, c):
    """Current depth of point c and its current arms (depth, rax, ray, raz, rbx, rby, rbz)."""
    a = ca[c]
    b = cb[c]
    rax, ray, raz = qrot(quat[a, 0], quat[a, 1], quat[a, 2], quat[a, 3],
                         la[c, 0], la[c, 1], la[c, 2])
    xa = pos[a, 0] + rax
    ya = pos[a, 1] + ray
    za = pos[a, 2] + raz
    if b >= 0:
        rbx, rby, rbz = qrot(quat[b, 0], quat[b, 1], quat[b, 2], quat[b, 3],
                             lb[c, 0], lb[c, 1], lb[c, 2])
        xb = pos[b, 0] + rbx
        yb = pos[b, 1] + rby
        zb = pos[b, 2] + rbz
    else:
        rbx, rby, rbz = 0.0, 0.0, 0.0
        xb, yb, zb = lb[c, 0], lb[c, 1], lb[c, 2]
    d = depth0[c] - ((xa - xb) * n[c, 0] + (ya - yb) * n[c, 1] + (za - zb) * n[c, 2])
    return d, rax, ray, raz, rbx, rby, rbz


@njit(cache=True, nogil=True)
def project_positions(ca, cb, n, la, lb, depth0, inv_mass, inv_i, pos, quat, max_passes):
    """Nonlinear Gauss–Seidel on positions (module docstring, stage 5). Stops once no point is
    deeper than 1.5 × ``SLOP``; returns (passes, deepest point left [m])."""
    passes = 0
    deepest = 0.0
    while passes < max_passes:
        passes += 1
        deepest = 0.0
        for c in range(ca.shape[0]):
            d, rax, ray, raz, rbx, rby, rbz = _depth(ca, cb, n, la, lb, depth0, pos, quat, c)
            if d > deepest:
                deepest = d
            if d <= SLOP:
                continue
            a = ca[c]
            b = cb[c]
            nx, ny, nz = n[c, 0], n[c, 1], n[c, 2]
            k = inv_mass[a] + _arm_mass(inv_i, a, rax, ray, raz, nx, ny, nz)
            if b >= 0:
                k += inv_mass[b] + _arm_mass(inv_i, b, rbx, rby, rbz, nx, ny, nz)
            if k <= 0.0:
                continue
            p = min(BAUMGARTE * (d - SLOP), MAX_CORRECTION) / k
            for side in range(2):
                i = a if side == 0 else b
                if i < 0:
                    continue
                s = p if side == 0 else -p
                rx, ry, rz = (rax, ray, raz) if side == 0 else (rbx, rby, rbz)
                w = inv_mass[i]
                pos[i, 0] += w * s * nx
                pos[i, 1] += w * s * ny
                pos[i, 2] += w * s * nz
                cx = (ry * nz - rz * ny) * s
                cy = (rz * nx - rx * nz) * s
                cz = (rx * ny - ry * nx) * s
                m = inv_i[i]
                tx = m[0, 0] * cx + m[0, 1] * cy + m[0, 2] * cz
                ty = m[1, 0] * cx + m[1, 1] * cy + m[1, 2] * cz
                tz = m[2, 0] * cx + m[2, 1] * cy + m[2, 2] * cz
                turn(quat, i, tx, ty, tz)  # q += ½ (0, θ) q
        if deepest <= 1.5 * SLOP:
            break
    return passes, deepest


@njit(cache=True, nogil=True)
def current_depths(ca, cb, n, la, lb, depth0, pos, quat, out):
    """Each point's depth now [m] (for statistics)."""
    for c in range(ca.shape[0]):
        out[c] = _depth(ca, cb, n, la, lb, depth0, pos, quat, c)[0]


@njit(cache=True, nogil=True)
def world_inertia(quat, inv_inertia, out):
    """I⁻¹_world = R diag(I⁻¹) Rᵀ for every body, after the projection turned some."""
    for i in range(quat.shape[0]):
        qw, qx, qy, qz = quat[i, 0], quat[i, 1], quat[i, 2], quat[i, 3]
        ix, iy, iz = inv_inertia[i, 0], inv_inertia[i, 1], inv_inertia[i, 2]
        r0 = qrot(qw, qx, qy, qz, 1.0, 0.0, 0.0)
        r1 = qrot(qw, qx, qy, qz, 0.0, 1.0, 0.0)
        r2 = qrot(qw, qx, qy, qz, 0.0, 0.0, 1.0)
        for u in range(3):
            for v in range(u, 3):
                x = ix * r0[u] * r0[v] + iy * r1[u] * r1[v] + iz * r2[u] * r2[v]
                out[i, u, v] = x
                out[i, v, u] = x
