"""The rotation of one body over a step: torque-free motion that keeps L and energy exactly.

Why not Box3D's step. Box3D (and our first version) solves I(ω₂ − ω₁) + h ω₂ × Iω₂ = 0 with a
Newton step (backward Euler on Euler's equations): stable, but it dissipates. Measured on a body
with I = (1, 2, 3) kg m², ω = (0.3, 4, 0.2) rad/s, h = 1/60 s: the world angular momentum drifted
8.3 % in 10 s (2.1 % at h = 1/240), so a spinning top slows and precesses at the wrong rate.

What this does. In body coordinates the angular momentum M only turns (world L = R·M is fixed)
and energy ½ M·I⁻¹M is fixed. We turn M about the axis Ω = I⁻¹·(M₀ + M₁)/2 (the body angular
velocity at mid-step) by the angle −h|Ω|, and the orientation by +h|Ω| about the same axis:

* world L is kept exactly whatever Ω is, because the body turns by exactly the rotation
  M is turned back by (R₁·M₁ = R₀·rot(hΩ)·rot(−hΩ)·M₀);
* |M| is kept exactly (a rotation);
* energy is kept because ΔM = M₁ − M₀ is perpendicular to the rotation axis Ω, so
  ΔE = ΔM·I⁻¹(M₀ + M₁)/2 = ΔM·Ω = 0 — once Ω solves its implicit equation, which a few Newton
  steps do to 1e-12 (the step's only iteration).

This is the implicit-midpoint rule for Euler's equations (which keeps both quadratic invariants)
with the exact rotation angle h|Ω| in place of its Cayley angle 2·atan(h|Ω|/2), so a body spinning
about a fixed axis turns at exactly its angular velocity, and precession periods come out right
(the Cayley angle makes a wheel at h|ω| = 1 turn 7 % too slowly). See Simo & Wong (1991) and
Dullweber, Leimkuhler & McLachlan (1997) for energy-momentum rigid-body integrators.

External torques and contact impulses change ω *before* this step (a kick); this is the drift.
"""

import math

from numba import njit

from .scalar import axis_rotate, qexp, qmul, qnormalize, qrot, qrot_inv, solve3

#: Newton iterations at most for the mid-step angular velocity; 3 to 5 are used at h|ω| ≤ 1.
MAX_ITERATIONS = 30
#: Relative residual (in angular momentum) at which the iteration stops.
TOLERANCE = 1e-13
#: ... and the residual that counts as converged when deciding to split the turn (round-off
#: keeps some turns from reaching ``TOLERANCE``; their energy is right to ~1e-12).
CONVERGED = 1e-11
#: Most times a turn whose Newton did not converge is split again into twice the pieces.
MAX_HALVINGS = 4
#: Largest turn [rad] solved in one piece (see ``free_rotation``).
MAX_TURN = 1.0
#: Most pieces one drift is split into: a body that would turn further in one step (over 64 rad,
#: 3 840 rad/s at 60 Hz; the stepper's cap is π/4 a step, only a solver's impulse gets past it)
#: is slowed to that first, energy only leaving. Without a cap a body a joint had spun to
#: 1e58 rad/s asked for 1e56 pieces: the step never returned (issue 30).
MAX_PIECES = 64


@njit(cache=True, nogil=True)
def free_rotation(qw, qx, qy, qz, wx, wy, wz, ix, iy, iz, h):
    """Turn a torque-free body for h seconds; returns the new (qw, qx, qy, qz, wx, wy, wz).

    q: orientation (unit quaternion, body -> world); w: world angular velocity [rad/s];
    (ix, iy, iz): inverse principal moments [1/(kg m²)] along the body axes (0 = infinite);
    h: step [s].

    A body with isotropic inertia, or an infinite moment about some axis, has no gyroscopic
    term to integrate (for the latter the constraint that fixes the axis would absorb it): it
    turns at its constant world ω, exactly.
    """
    if ix <= 0.0 or iy <= 0.0 or iz <= 0.0 or (ix == iy and iy == iz):
        dw, dx, dy, dz = qexp(wx, wy, wz, h)
        nw, nx, ny, nz = qnormalize(*qmul(dw, dx, dy, dz, qw, qx, qy, qz))
        return nw, nx, ny, nz, wx, wy, wz
    # Newton converges (to 1e-11 in energy) up to about 1 rad per step and fails past 3; the
    # stepper caps a step at π/4, but a contact solver may spin a body faster before this drift,
    # so a long turn is split into pieces of at most MAX_TURN (L and energy are still kept).
    turn = h * math.sqrt(wx * wx + wy * wy + wz * wz)
    if turn > MAX_PIECES * MAX_TURN:  # (also catches inf; NaN falls through to one piece)
        s = MAX_PIECES * MAX_TURN / turn
        wx *= s
        wy *= s
        wz *= s
        turn = MAX_PIECES * MAX_TURN
    pieces = max(1, math.ceil(turn / MAX_TURN)) if turn == turn else 1
    # A very flat or long body converges more slowly (a 1 kg plate with moments 46:1 at
    # 0.92 rad a step kept Newton's residual at 1e-4 after 30 iterations, and gained 1e-6 of
    # its energy a step): a turn whose Newton did not converge is done again in twice as many
    # pieces, at most ``MAX_HALVINGS`` times (the last answer stands).
    start = (qw, qx, qy, qz, wx, wy, wz)
    for _ in range(MAX_HALVINGS + 1):
        qw, qx, qy, qz, wx, wy, wz = start
        hp = h / pieces
        converged = True
        for _ in range(pieces):
            qw, qx, qy, qz, wx, wy, wz, ok = _turn(qw, qx, qy, qz, wx, wy, wz, ix, iy, iz, hp)
            converged = converged and ok
        if converged:
            break
        pieces *= 2
    return qw, qx, qy, qz, wx, wy, wz


@njit(cache=True, nogil=True)
def _turn(qw, qx, qy, qz, wx, wy, wz, ix, iy, iz, h):
    """One energy-momentum step of an asymmetric body (the module docstring's method)."""
    bx, by, bz = qrot_inv(qw, qx, qy, qz, wx, wy, wz)
    mx, my, mz = bx / ix, by / iy, bz / iz  # body angular momentum M0
    scale = math.sqrt(mx * mx + my * my + mz * mz)
    ux, uy, uz = bx, by, bz  # the mid-step body angular velocity, first guess ω0
    converged = False
    for _ in range(MAX_ITERATIONS):
        m1x, m1y, m1z = axis_rotate(ux, uy, uz, -h * math.sqrt(ux * ux + uy * uy + uz * uz),
                                    mx, my, mz)
        hx, hy, hz = 0.5 * (mx + m1x), 0.5 * (my + m1y), 0.5 * (mz + m1z)
        gx, gy, gz = ux / ix - hx, uy / iy - hy, uz / iz - hz  # residual I·u − (M0 + M1)/2
        residual = math.sqrt(gx * gx + gy * gy + gz * gz)
        if residual <= CONVERGED * scale:
            converged = True
        if residual <= TOLERANCE * scale:
            break
        # Jacobian of the residual: I − (h/2)·skew(M_mid) (rot(−hu)·M ≈ M + h·M × u)
        k = 0.5 * h
        dx, dy, dz = solve3(1.0 / ix, k * hz, -k * hy,
                            -k * hz, 1.0 / iy, k * hx,
                            k * hy, -k * hx, 1.0 / iz, gx, gy, gz)
        ux -= dx
        uy -= dy
        uz -= dz
    m1x, m1y, m1z = axis_rotate(ux, uy, uz, -h * math.sqrt(ux * ux + uy * uy + uz * uz),
                                mx, my, mz)
    dw, dx, dy, dz = qexp(ux, uy, uz, h)  # body-frame rotation: applied on the right
    nw, nx, ny, nz = qnormalize(*qmul(qw, qx, qy, qz, dw, dx, dy, dz))
    ox, oy, oz = qrot(nw, nx, ny, nz, m1x * ix, m1y * iy, m1z * iz)
    return nw, nx, ny, nz, ox, oy, oz, converged or scale == 0.0
