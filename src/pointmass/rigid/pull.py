"""A damped spring pulling one point of a rigid body toward a target: the viewer's mouse grab
on bodies (``pointmass.app.body_spring``), and the law it shares with the particle grab.

``pull_gains`` is that law: k = max(M·ω², 2·Σk) and c = 2ζ·√(k·M) for the mass M that resists
the pull (and the spring constants Σk holding the point), each capped so the explicit step
stays stable for the lightest mass m the force moves: h²·k/m ≤ 1/2 and h·c/m ≤ 1/2, so
h²ω² + 2hγ ≤ 3/2, well inside the bound of 4 (``stability.py``).

On a body the force F = k·(target − p) − c·v_p acts at the held point p = x + R·local
(v_p = v + ω×r), with the torque r × F, and M is the body's mass: held by its centre, a body
follows the cursor as a particle does. Held elsewhere it also turns, and the point answers a
force F with the acceleration K·F, K = (1/M)·1 + [r]ᵀ·I⁻¹·[r] (the inverse mass matrix at the
point): the caps use its lightest direction, m = 1/λmax(K) (a unit cube held by a corner
weighs 1/5.5 kg across the lever arm).

A hand holding a body also stops it spinning: a torque −β·I·ω (β = ω of the pull, capped at
h·β ≤ 1/2) damps the rotation about the point, which the point's spring cannot (a box hanging
from the cursor would otherwise swing as a pendulum for ever; this term alone gives a unit
cube hanging by a corner, a pendulum of 3 rad/s, a damping ratio of about 0.36).
"""

from __future__ import annotations

import math

import numpy as np
from numba import njit

from .. import _validate as check
from .bodies import Bodies
from .forces import BodyForceGenerator
from .scalar import qrot, qrot_inv


@njit(cache=True, nogil=True)
def pull_gains(resisting, light, omega, zeta, dt, stiffness=0.0):
    """(k [N/m], c [N·s/m]) pulling a ``resisting`` mass [kg] (held by springs of
    ``stiffness`` [N/m]) at ``omega`` [rad/s] with damping ratio ``zeta``, capped for a step of
    ``dt`` [s] on the ``light``est mass [kg] the force moves."""
    k = max(resisting * omega * omega, 2.0 * stiffness)
    k = min(k, 0.5 * light / (dt * dt))
    c = min(2.0 * zeta * math.sqrt(k * resisting), 0.5 * light / dt)
    return k, c


@njit(cache=True, nogil=True)
def largest_eigenvalue(a00, a01, a02, a11, a12, a22):
    """The largest eigenvalue of a symmetric 3×3 matrix, in closed form (Smith 1961: the
    three roots of the characteristic cubic as q + 2p·cos(φ + 2πk/3))."""
    off = a01 * a01 + a02 * a02 + a12 * a12
    if off == 0.0:
        return max(a00, a11, a22)
    q = (a00 + a11 + a22) / 3.0
    b00, b11, b22 = a00 - q, a11 - q, a22 - q
    p = math.sqrt((b00 * b00 + b11 * b11 + b22 * b22 + 2.0 * off) / 6.0)
    det = (b00 * (b11 * b22 - a12 * a12) - a01 * (a01 * b22 - a12 * a02)
           + a02 * (a01 * a12 - b11 * a02))
    half = min(1.0, max(-1.0, det / (2.0 * p * p * p)))
    return q + 2.0 * p * math.cos(math.acos(half) / 3.0)


@njit(cache=True, nogil=True)
def point_mass(inv_mass, m, rx, ry, rz):
    """The lightest effective mass [kg] at lever arm r [m] of a body of inverse mass
    ``inv_mass`` and world inverse inertia ``m`` (3, 3): 1/λmax((1/M)·1 + [r]ᵀ·m·[r])."""
    # S = [r]ᵀ·m·[r]: its column j is r × (m·(e_j × r)) ([r]ᵀ = −[r], [r]·e_j = −e_j × r)
    s = np.empty((3, 3))
    for j in range(3):
        cx, cy, cz = (0.0, -rz, ry) if j == 0 else ((rz, 0.0, -rx) if j == 1 else
                                                     (-ry, rx, 0.0))
        ux = m[0, 0] * cx + m[0, 1] * cy + m[0, 2] * cz
        uy = m[1, 0] * cx + m[1, 1] * cy + m[1, 2] * cz
        uz = m[2, 0] * cx + m[2, 1] * cy + m[2, 2] * cz
        s[0, j] = ry * uz - rz * uy
        s[1, j] = rz * ux - rx * uz
        s[2, j] = rx * uy - ry * ux
    top = largest_eigenvalue(inv_mass + s[0, 0], s[0, 1], s[0, 2], inv_mass + s[1, 1],
                             s[1, 2], inv_mass + s[2, 2])
    return 1.0 / top if top > 0.0 else math.inf


@njit(cache=True, nogil=True)
def _pull_kernel(pos, quat, vel, ang, inv_mass, inv_inertia, inv_inertia_world, force, torque,
                 i, local, target, omega, zeta, dt):
    """Add the pull's force at the held point, its torque and the spin damping to body i."""
    q = quat[i]
    rx, ry, rz = qrot(q[0], q[1], q[2], q[3], local[0], local[1], local[2])
    w = inv_mass[i]
    k, c = pull_gains(1.0 / w, point_mass(w, inv_inertia_world[i], rx, ry, rz), omega, zeta,
                      dt, 0.0)
    wx, wy, wz = ang[i, 0], ang[i, 1], ang[i, 2]
    fx = k * (target[0] - pos[i, 0] - rx) - c * (vel[i, 0] + wy * rz - wz * ry)
    fy = k * (target[1] - pos[i, 1] - ry) - c * (vel[i, 1] + wz * rx - wx * rz)
    fz = k * (target[2] - pos[i, 2] - rz) - c * (vel[i, 2] + wx * ry - wy * rx)
    # spin damping −β·I·ω, I·ω taken in the body's axes (0 about a locked axis)
    beta = min(omega, 0.5 / dt)
    bx, by, bz = qrot_inv(q[0], q[1], q[2], q[3], wx, wy, wz)
    inv = inv_inertia[i]
    bx = bx / inv[0] if inv[0] > 0.0 else 0.0
    by = by / inv[1] if inv[1] > 0.0 else 0.0
    bz = bz / inv[2] if inv[2] > 0.0 else 0.0
    lx, ly, lz = qrot(q[0], q[1], q[2], q[3], bx, by, bz)
    force[i, 0] += fx
    force[i, 1] += fy
    force[i, 2] += fz
    torque[i, 0] += ry * fz - rz * fy - beta * lx
    torque[i, 1] += rz * fx - rx * fz - beta * ly
    torque[i, 2] += rx * fy - ry * fx - beta * lz


class BodyPull(BodyForceGenerator):
    """Pulls the point ``local`` of body ``index`` toward ``target`` [m] with a damped spring.

    Args:
        index: The body (an int or a ``Body``).
        local: The held point in the body's coordinates [m], shape (3,).
        target: Where it is pulled [m], shape (3,); change it between steps.
        omega: Natural angular frequency [rad/s] of the pull on the body's mass (and the rate
            [1/s] at which its spin is damped), > 0.
        zeta: Damping ratio of the pull (1: critical), ≥ 0.
    """

    def __init__(self, index, local, target, *, omega: float = 12.0,
                 zeta: float = 1.0) -> None:
        self.index = int(index)
        self.local = check.vec3(local, "local")
        self.target = target
        self.omega = check.scalar(omega, "omega", low=0.0, low_open=True)
        self.zeta = check.scalar(zeta, "zeta", low=0.0)

    target = property(lambda self: self._target, lambda self, v: setattr(
        self, "_target", check.vec3(v, "target")), doc="Where the point is pulled [m].")

    def validate(self, bodies: Bodies) -> None:
        bodies.check_index(self.index, "index")

    def arm(self, bodies: Bodies) -> np.ndarray:
        """The lever arm r = R·local from the centre to the held point [m], (3,)."""
        q = bodies.orientation[self.index]
        return np.array(qrot(q[0], q[1], q[2], q[3], *self.local))

    def point_of(self, bodies: Bodies) -> np.ndarray:
        """Where the held point is now [m], (3,)."""
        return bodies.position[self.index] + self.arm(bodies)

    def gains(self, bodies: Bodies, dt: float) -> tuple[float, float]:
        """(k [N/m], c [N·s/m]) for a step of ``dt`` [s], capped for stability at the point."""
        i = self.index
        w = float(bodies.inv_mass[i])
        light = point_mass(w, bodies.inv_inertia_world[i], *self.arm(bodies))
        return pull_gains(1.0 / w, light, self.omega, self.zeta, dt, 0.0)

    def apply(self, bodies: Bodies, dt: float) -> None:
        if bodies.inv_mass[self.index] <= 0.0:     # static or kinematic: nothing to pull
            return
        _pull_kernel(bodies.position, bodies.orientation, bodies.velocity,
                     bodies.angular_velocity, bodies.inv_mass, bodies.inv_inertia,
                     bodies.inv_inertia_world, bodies.force, bodies.torque, self.index,
                     self.local, self._target, self.omega, self.zeta, dt)
