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

import numpy as np
from numba import njit

from .. import _validate as check
from .bodies import Bodies
from .integrate import free_rotation
from .scalar import qrot

#: Most a body may turn in one step [rad]: Box2D's 0.25π (47.1 rad/s at 60 Hz, 94.2 at 120).
#: Faster spins are slowed to it in the kick (energy only leaves), which keeps the rotation
#: solve well inside its convergence range. Measured against the demos that spin (largest |ω|
#: over 4 s at their defaults, as a fraction of the cap): spinning top 35 rad/s (0.74; 45.0 at
#: its top spin=45, 0.955), ragdoll 0.60, fracture 0.36, tennis racket 6.1 rad/s (0.06): none
#: reaches it, so none depends on it.
MAX_ROTATION = 0.25 * math.pi
#: A spin whose size is not finite (|ω|² overflowed: |ω| ≳ 1e154 rad/s, or NaN) is a blow-up,
#: not a spin to slow down: the kick returns the body and the world raises FloatingPointError
#: (|ω| = 1e300 used to be scaled by cap/inf to exactly 0, silently). A finite spin past the
#: cap is slowed to it, however large (Cyclone's R2: a huge torque turns a body a quarter turn).


@njit(cache=True, nogil=True)
def force_acceleration(inv_mass, force, g):
    """(N, 3) what gravity ``g`` and the forces alone give each body [m/s²], 0 for a static
    one: numpy's ``np.where(w > 0, g + F·w, 0)`` in one call, the same arithmetic (the
    resting-contact trick reads it)."""
    out = np.empty(force.shape)
    for i in range(force.shape[0]):
        w = inv_mass[i]
        for k in range(3):
            out[i, k] = g[k] + force[i, k] * w if w > 0.0 else 0.0
    return out


@njit(cache=True, nogil=True)
def integrate_velocities(vel, ang, force, torque, inv_mass, inv_inertia, inv_inertia_world,
                         lin_damping, ang_damping, g, dt, awake, drift=0.0):
    """The kick for every body with ``awake`` (N,) True (a sleeping body keeps v = ω = 0).
    Gravity g [m/s²] (3,) acts only on bodies of finite mass, and a torque only about axes of
    finite inertia; bodies of infinite mass keep their velocity (kinematic). Returns the first
    body whose spin's size is not finite (left as it was), or -1; a finite spin past
    ``MAX_ROTATION`` a drift is slowed to it (the drift ``dt``, or ``drift`` [s] when given:
    a leapfrog's half kick of dt/2 is followed by a drift of dt)."""
    cap = MAX_ROTATION / (drift if drift > 0.0 else dt)
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
            if not math.isfinite(speed):  # never scaled by cap/inf to 0
                return i
            if speed > cap:
                s = cap / speed
                wx *= s
                wy *= s
                wz *= s
            ang[i, 0] = wx
            ang[i, 1] = wy
            ang[i, 2] = wz
    return -1


def spin_error(bodies: Bodies, i: int, dt: float, time: float | None = None) -> FloatingPointError:
    """The error for body ``i``, whose spin the kick refused."""
    w = bodies.angular_velocity[i]
    when = "" if time is None else f" at t = {time:.6g} s"
    return FloatingPointError(
        f"body {i} spins too fast{when}: ω = {w.tolist()} rad/s, whose size squared is not a "
        f"finite number (a blow-up; finite spins past {MAX_ROTATION:.3g} rad a step, "
        f"{MAX_ROTATION / dt:.3g} rad/s at dt = {dt:.4g} s, are slowed to it: README's rigid "
        "bodies)")


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
    spun = integrate_velocities(b.velocity, b.angular_velocity, b.force, b.torque, b.inv_mass,
                                b.inv_inertia, b.inv_inertia_world, b.linear_damping,
                                b.angular_damping, g, dt, b.awake)
    if spun >= 0:
        b.clear_accumulators()
        raise spin_error(b, spun, dt)
    bad = integrate_positions(b.position, b.orientation, b.velocity, b.angular_velocity,
                              b.inv_inertia, b.inv_inertia_world, dt, b.awake)
    b.clear_accumulators()
    if bad >= 0:
        raise FloatingPointError(f"body {bad} is no longer finite after a step of {dt} s")

