"""The mouse spring on a rigid body: the particle grab's damped spring (``grab.spring_gains``),
attached to the body-local point that was clicked, so it pulls and turns the body.

The force F = k·(target − p) − c·v_p acts at the grabbed point p = x + R·local (v_p = v + ω×r),
with the torque r × F. It is scaled like the particle grab: k = M·ω² and c = 2ζ·√(k·M) for the
body's mass M, so a body pulled by its centre follows the cursor as a particle does. A force
at r ≠ 0 also turns the body, and the point then answers a force F with the acceleration
K·F, K = 1/M + [r]ᵀ·I⁻¹·[r] (the inverse mass matrix at the point, rigid-notes' effective
mass): the caps use its lightest direction, 1/λmax(K), as the particle grab uses the
particle's mass, so the explicit step stays stable however the body is held (a unit cube
held by a corner weighs 0.18 kg there across the lever arm).

A hand holding a body also stops it spinning: a torque −β·I·ω (β = ω of the grab, capped at
h·β ≤ 1/2) damps the rotation about the point, which the point's spring cannot (a box hanging
from the cursor would otherwise swing as a pendulum for ever; with it, a unit cube hanging by
a corner swings with damping ratio ≈ 0.36).
"""

from __future__ import annotations

import numpy as np

from ..rigid.bodies import Bodies, world_rotation
from ..rigid.forces import BodyForceGenerator
from .grab import Grab, spring_gains


def point_mass(bodies: Bodies, index: int, r) -> float:
    """The lightest effective mass [kg] of body ``index`` at lever arm ``r`` [m] (world, from
    its centre): 1/λmax of K = (1/M)·1 + [r]ᵀ·I⁻¹_world·[r]; inf for an immovable body."""
    w = float(bodies.inv_mass[index])
    skew = np.array([[0.0, -r[2], r[1]], [r[2], 0.0, -r[0]], [-r[1], r[0], 0.0]])
    k = w * np.eye(3) + skew.T @ bodies.inv_inertia_world[index] @ skew
    top = float(np.linalg.eigvalsh(k)[-1])
    return 1.0 / top if top > 0.0 else np.inf


def world_inertia(bodies: Bodies, index: int) -> np.ndarray:
    """The body's inertia tensor in world axes [kg m²], (3, 3); 0 about a locked axis."""
    inv = bodies.inv_inertia[index]
    moments = np.where(inv > 0.0, 1.0 / np.where(inv > 0.0, inv, 1.0), 0.0)
    rot = world_rotation(bodies.orientation[index])
    return rot @ np.diag(moments) @ rot.T


class BodyMouseSpring(BodyForceGenerator):
    """Pulls the point ``local`` of body ``index`` toward ``target`` [m] with a damped spring.

    Args:
        index: The grabbed body.
        local: The grabbed point in the body's coordinates [m], shape (3,).
        target: Where the cursor points [m], shape (3,); update it while dragging.
        omega: Natural angular frequency [rad/s] of the pull on the body's mass (and the rate
            [1/s] at which its spin is damped).
        zeta: Damping ratio (1: critical) of the pull.
    """

    grabs = "body"

    def __init__(self, index: int, local, target, *, omega: float = 12.0,
                 zeta: float = 1.0) -> None:
        self.index = int(index)
        self.local = np.asarray(local, dtype=np.float64).reshape(3).copy()
        self.target = np.asarray(target, dtype=np.float64).reshape(3).copy()
        self.omega = float(omega)
        self.zeta = float(zeta)

    def validate(self, bodies: Bodies) -> None:
        bodies.check_index(self.index, "index")

    def arm(self, bodies: Bodies) -> np.ndarray:
        """The lever arm r = R·local from the centre to the grabbed point [m], (3,)."""
        return world_rotation(bodies.orientation[self.index]) @ self.local

    def point(self, world) -> np.ndarray:
        """Where the grabbed point is now [m], (3,)."""
        b = world.bodies
        return b.position[self.index] + self.arm(b)

    def gains(self, bodies: Bodies, dt: float) -> tuple[float, float]:
        """(k [N/m], c [N·s/m]) for a step of ``dt`` [s], capped for stability at the point."""
        mass = 1.0 / bodies.inv_mass[self.index]
        light = point_mass(bodies, self.index, self.arm(bodies))
        return spring_gains(mass, light, self.omega, self.zeta, dt)

    def apply(self, bodies: Bodies, dt: float) -> None:
        i = self.index
        if bodies.inv_mass[i] <= 0.0:        # static or kinematic: nothing to pull
            return
        r = self.arm(bodies)
        k, c = self.gains(bodies, dt)
        spin = bodies.angular_velocity[i]
        v = bodies.velocity[i] + np.cross(spin, r)
        f = k * (self.target - (bodies.position[i] + r)) - c * v
        rate = min(self.omega, 0.5 / dt)
        bodies.force[i] += f
        bodies.torque[i] += np.cross(r, f) - rate * (world_inertia(bodies, i) @ spin)


def grab_body(world, index: int, point, normal) -> Grab:
    """Grab body ``index`` at the world ``point`` [m] (where the pick ray met it): the spring
    holds that point of the body, its target moving in the plane through it with ``normal``."""
    b = world.bodies
    local = world_rotation(b.orientation[index]).T @ (np.asarray(point, float) - b.position[index])
    return Grab(world, BodyMouseSpring(index, local, point), normal)
