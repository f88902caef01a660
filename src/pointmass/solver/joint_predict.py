"""The joints' targets from the pose the step will end in: each velocity pass predicts where
the drift (``rigid.step.integrate_positions``: x += v·dt and the exact torque-free turn) will
take the joint's bodies with the velocities they have now, and aims every point block and
its point block at closing what that pose would leave open: target Ċ = Ċ_now − C_end/dt.
Passes repeated until the predicted gaps vanish are Newton's method on C(x_end(v)) = 0 with
the Jacobian of the start pose: the step ends with the joints shut (SHAKE; Ryckaert, Ciccotti
and Berendsen 1977), and its velocity is the chord from the start pose to that end.

Why not the linear rows with a drift bias Ċ = −β·C/dt (Baumgarte, what ran before). Linear rows keep
the joint point's velocity tangent to the start pose, so the drift leaves the joint open by the
sagitta ½(ω·dt)²·r every step: a 1 m pendulum released level opened 2.7 mm at the bottom of its
swing at dt 1/60, a double pendulum of two 0.5 m boxes 5 mm at 12 rad/s (the projection's slop, in
the impulses stage that ran before the soft step). And the velocity rows only turn a velocity by
shortening it: a velocity made tangent to the start pose each step loses the fraction (ω·dt)² of its
energy a step (0.55 % at the pendulum's bottom), which the bias then gave back by chance: the
pendulum's energy wandered −9.4 % … +1.5 % in 20 s, the double pendulum's fell 36 %. The chord is
what a symplectic constrained integrator moves along (SHAKE is leapfrog on the constraint manifold):
the energy then only oscillates, by what semi-implicit Euler's own first-order error gives the same
pendulum in its angle (±2.3 % of m·g·L at dt 1/60, ±0.57 % with 4 substeps; the soft step's
leapfrog, stop 42: 0.0063 %).

Only the joints of the exact solve (``joint_tree`` DIRECT and LOOP: forests and their loops)
aim so: each pass meets all their targets at once, so the passes are Newton's. Joints left to
Gauss–Seidel (ITERATIVE: those the tree cannot take) keep the Baumgarte targets: a 50-box
chain swept by Gauss–Seidel with these targets (``joint_solver.DIRECT = False``) was left
unconverged by the 30-pass cap, and the full closure fed the error until it blew up (gaps of
1e14 m in 2 s), where β = 0.5 held it at 13 mm. The angular rows (a hinge's locks, the limits)
keep their Baumgarte and speculative targets too: aimed at the end pose, the ragdoll demo at
rest was left up to 1.0° past a limit (seeds 1–3, 3 s) against 0.57° without.

The soft step stops aiming in a pass that predicts no better than the last
(``body_soft.joint_passes``: ``JointRows.predict``): the chord's velocity can be longer than the
start's by O((ω·dt)²).
"""

from __future__ import annotations

import math

from numba import njit

from ..rigid.integrate import free_rotation
from ..rigid.scalar import qrot
from .joint_tree import DIRECT as DIRECT_JOINT


@njit(cache=True, nogil=True)
def _end_pose(pos, quat, vel, ang, inv_inertia, dt, i, xend, qend):
    """Where the drift takes body i (i < 0: the world, nothing) from its velocities now."""
    if i < 0:
        return
    for k in range(3):
        xend[i, k] = pos[i, k] + vel[i, k] * dt
    qw, qx, qy, qz, _, _, _ = free_rotation(
        quat[i, 0], quat[i, 1], quat[i, 2], quat[i, 3], ang[i, 0], ang[i, 1], ang[i, 2],
        inv_inertia[i, 0], inv_inertia[i, 1], inv_inertia[i, 2], dt)
    qend[i, 0], qend[i, 1], qend[i, 2], qend[i, 3] = qw, qx, qy, qz


@njit(cache=True, nogil=True)
def end_targets(ja, jb, la, lb, pos, quat, vel, ang, inv_inertia, dt, mode, ra, rb, keep, bias,
                xend, qend, speed, top):
    """For every joint the exact solve takes (``mode`` DIRECT or LOOP): ``bias`` (J, 3) ←
    Ċ_now − (C_end − K)/dt of its point block (C_end: the gap in the predicted end pose; K:
    what the step may leave of the gap the joint has now, ``keep`` (J, 3); ``xend`` (N, 3),
    ``qend`` (N, 4) are scratch), closing the gap now no faster than ``speed`` [m/s] (the
    soft step's push-out cap; ``inf``: none; the turn's sagitta is never capped); only
    joints whose mode is at most ``top`` (LOOP: all of them; DIRECT: the soft step's loops
    keep their targets, ``joint_soft``). Returns the largest predicted excess over dt [m/s]."""
    largest = 0.0
    for j in range(ja.shape[0]):
        if mode[j] < DIRECT_JOINT or mode[j] > top:  # Gauss–Seidel's keep their targets
            continue
        a = ja[j]
        b = jb[j]
        _end_pose(pos, quat, vel, ang, inv_inertia, dt, a, xend, qend)
        _end_pose(pos, quat, vel, ang, inv_inertia, dt, b, xend, qend)
        pax, pay, paz = qrot(qend[a, 0], qend[a, 1], qend[a, 2], qend[a, 3], la[j, 0],
                             la[j, 1], la[j, 2])
        pax += xend[a, 0]
        pay += xend[a, 1]
        paz += xend[a, 2]
        if b >= 0:
            pbx, pby, pbz = qrot(qend[b, 0], qend[b, 1], qend[b, 2], qend[b, 3], lb[j, 0],
                                 lb[j, 1], lb[j, 2])
            pbx += xend[b, 0]
            pby += xend[b, 1]
            pbz += xend[b, 2]
        else:
            pbx, pby, pbz = lb[j, 0], lb[j, 1], lb[j, 2]
        gx, gy, gz = pbx - pax - keep[j, 0], pby - pay - keep[j, 1], pbz - paz - keep[j, 2]
        largest = max(largest, math.sqrt(gx * gx + gy * gy + gz * gz) / dt)
        # Ċ now = vB + ωB×rB − vA − ωA×rA, with the start pose's arms (the rows' Jacobian)
        cx = -(vel[a, 0] + ang[a, 1] * ra[j, 2] - ang[a, 2] * ra[j, 1])
        cy = -(vel[a, 1] + ang[a, 2] * ra[j, 0] - ang[a, 0] * ra[j, 2])
        cz = -(vel[a, 2] + ang[a, 0] * ra[j, 1] - ang[a, 1] * ra[j, 0])
        if b >= 0:
            cx += vel[b, 0] + ang[b, 1] * rb[j, 2] - ang[b, 2] * rb[j, 1]
            cy += vel[b, 1] + ang[b, 2] * rb[j, 0] - ang[b, 0] * rb[j, 2]
            cz += vel[b, 2] + ang[b, 0] * rb[j, 1] - ang[b, 1] * rb[j, 0]
        if speed == math.inf:
            bias[j, 0] = cx - gx / dt
            bias[j, 1] = cy - gy / dt
            bias[j, 2] = cz - gz / dt
            continue
        # Capped (the soft step): the target is −(C_now − K)/dt − Δ/dt, Δ = C_end − C_now −
        # Ċ_now·dt being what the turn adds to the straight-line motion (the sagitta). Only
        # the first part closes a gap, and only it is capped at the push-out speed. The
        # second keeps a turning arm's joint point on its arc: a ball whirled on a 5 m arm at
        # 20 rad/s needs Δ/h ≈ ½ω²·L·h = 4.2 m/s, and with the whole target capped at 3 m/s
        # its joint opened a little more every substep (tests/physics/rigid/
        # test_joint_whirl.py). C_now (nx, ny, nz) is the gap in the pose now, from the
        # rows' arms (``prepare``d in this pose: the passes do not move the bodies).
        nx = -(pos[a, 0] + ra[j, 0])
        ny = -(pos[a, 1] + ra[j, 1])
        nz = -(pos[a, 2] + ra[j, 2])
        if b >= 0:
            nx += pos[b, 0] + rb[j, 0]
            ny += pos[b, 1] + rb[j, 1]
            nz += pos[b, 2] + rb[j, 2]
        else:
            nx += lb[j, 0]
            ny += lb[j, 1]
            nz += lb[j, 2]
        # the gap to close now, over dt, no faster than ``speed``
        ux, uy, uz = (nx - keep[j, 0]) / dt, (ny - keep[j, 1]) / dt, (nz - keep[j, 2]) / dt
        size = math.sqrt(ux * ux + uy * uy + uz * uz)
        if size > speed:
            ux, uy, uz = ux * speed / size, uy * speed / size, uz * speed / size
        # −Δ/dt = Ċ_now − (C_end − C_now)/dt
        bias[j, 0] = -ux + cx - (gx + keep[j, 0] - nx) / dt
        bias[j, 1] = -uy + cy - (gy + keep[j, 1] - ny) / dt
        bias[j, 2] = -uz + cz - (gz + keep[j, 2] - nz) / dt
    return largest
