"""Advance rigid bodies in two stages, so a contact solver can run between them.

``integrate_velocities`` is the kick: v += dt·(g + F/m), ω += dt·I⁻¹_world·τ, damping, and a cap
on rotation per step. ``integrate_positions`` is the drift: x += v·dt and the torque-free rotation
of ``integrate.free_rotation`` (which keeps L and energy), then I⁻¹_world from the new
orientation. ``step`` runs both with no contacts, for free bodies and tests.

Both kernels are plain loops that load, call pure helpers on scalars, and store in the loop body
(a helper that stores into arrays was 3× slower in the particles' integrator).
"""

from __future__ import annotations

import math

from numba import njit

from .. import _validate as check
from .bodies import Bodies
from .integrate import free_rotation
from .scalar import qrot

#: Most a body may turn in one step [rad]: Box2D's 0.25π. Faster spins are slowed to it (energy
#: only leaves), which keeps the rotation solve well inside its convergence range and stops a
#: blow-up from spinning a body to NaN.
MAX_ROTATION = 0.25 * math.pi


@njit(cache=True, nogil=True)
def integrate_velocities(vel, ang, force, torque, inv_mass, inv_inertia, inv_inertia_world,
                         lin_damping, ang_damping, g, dt, awake):
    """The kick for every body with ``awake`` (N,) True (a sleeping body keeps v = ω = 0).
    Gravity g [m/s²] (3,) acts only on bodies of finite mass, and a torque only about axes of
    finite inertia; bodies of infinite mass keep their velocity (kinematic)."""
    cap = MAX_ROTATION / dt
    for i in range(vel.shape[0]):
        if not awake[i]:
            continue
        w = inv_mass[i]
        if w > 0.0:
            keep = lin_damping[i] ** dt if lin_damping[i] < 1.0 else 1.0
            vel[i, 0] = (vel[i, 0] + dt * (g[0] + force[i, 0] * w)) * keep
            vel[i, 1] = (vel[i, 1] + dt * (g[1] + force[i, 1] * w)) * keep
            vel[i, 2] = (vel[i, 2] + dt * (g[2] + force[i, 2] * w)) * keep
        if inv_inertia[i, 0] > 0.0 or inv_inertia[i, 1] > 0.0 or inv_inertia[i, 2] > 0.0:
            m = inv_inertia_world[i]
            tx, ty, tz = torque[i, 0], torque[i, 1], torque[i, 2]
            keep = ang_damping[i] ** dt if ang_damping[i] < 1.0 else 1.0
            wx = (ang[i, 0] + dt * (m[0, 0] * tx + m[0, 1] * ty + m[0, 2] * tz)) * keep
            wy = (ang[i, 1] + dt * (m[1, 0] * tx + m[1, 1] * ty + m[1, 2] * tz)) * keep
            wz = (ang[i, 2] + dt * (m[2, 0] * tx + m[2, 1] * ty + m[2, 2] * tz)) * keep
            speed = math.sqrt(wx * wx + wy * wy + wz * wz)
            if speed > cap:
                s = cap / speed
                wx *= s
                wy *= s
                wz *= s
            ang[i, 0] = wx
            ang[i, 1] = wy
            ang[i, 2] = wz


@njit(cache=True, nogil=True)
def integrate_positions(pos, quat, vel, ang, inv_inertia, inv_inertia_world, dt, awake):
    """The drift for every body with ``awake`` (N,) True (a sleeping body stays exactly where
    it is); returns the first body that is not finite afterwards, or -1. (``free_rotation``
    splits a long or slowly converging turn into pieces, at most 64 × 2⁴ of them.)"""
    bad = -1
    for i in range(pos.shape[0]):
        if not awake[i]:
            continue
        pos[i, 0] += vel[i, 0] * dt
        pos[i, 1] += vel[i, 1] * dt
        pos[i, 2] += vel[i, 2] * dt
        ix, iy, iz = inv_inertia[i, 0], inv_inertia[i, 1], inv_inertia[i, 2]
        qw, qx, qy, qz, wx, wy, wz = free_rotation(
            quat[i, 0], quat[i, 1], quat[i, 2], quat[i, 3], ang[i, 0], ang[i, 1], ang[i, 2],
            ix, iy, iz, dt)
        quat[i, 0] = qw
        quat[i, 1] = qx
        quat[i, 2] = qy
        quat[i, 3] = qz
        ang[i, 0] = wx
        ang[i, 1] = wy
        ang[i, 2] = wz
        # I⁻¹_world = R diag(I⁻¹) Rᵀ, column k of R being the body axis k in world space
        r0 = qrot(qw, qx, qy, qz, 1.0, 0.0, 0.0)
        r1 = qrot(qw, qx, qy, qz, 0.0, 1.0, 0.0)
        r2 = qrot(qw, qx, qy, qz, 0.0, 0.0, 1.0)
        for a in range(3):
            for b in range(a, 3):
                v = ix * r0[a] * r0[b] + iy * r1[a] * r1[b] + iz * r2[a] * r2[b]
                inv_inertia_world[i, a, b] = v
                inv_inertia_world[i, b, a] = v
        if bad < 0 and not math.isfinite(pos[i, 0] + pos[i, 1] + pos[i, 2] + wx + wy + wz
                                         + vel[i, 0] + vel[i, 1] + vel[i, 2]):
            bad = i
    return bad


def step(bodies: Bodies, dt: float, gravity=(0.0, 0.0, 0.0)) -> None:
    """Advance free bodies by ``dt`` [s] > 0 under their accumulated forces and torques and
    ``gravity`` [m/s²] (sleeping bodies stay put: ``Bodies.awake``); clears the accumulators.
    Raises FloatingPointError naming the first body that is no longer finite."""
    dt = check.scalar(dt, "dt", low=0.0, low_open=True)
    g = check.vec3(gravity, "gravity")
    b = bodies
    integrate_velocities(b.velocity, b.angular_velocity, b.force, b.torque, b.inv_mass,
                         b.inv_inertia, b.inv_inertia_world, b.linear_damping,
                         b.angular_damping, g, dt, b.awake)
    bad = integrate_positions(b.position, b.orientation, b.velocity, b.angular_velocity,
                              b.inv_inertia, b.inv_inertia_world, dt, b.awake)
    b.clear_accumulators()
    if bad >= 0:
        raise FloatingPointError(f"body {bad} is no longer finite after a step of {dt} s")

