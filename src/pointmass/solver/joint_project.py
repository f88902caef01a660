"""The joints' position stage: after the drift, take back what the step's motion opened beyond
a slop (nonlinear Gauss–Seidel on the real separation and angles, Box2D v2's
``SolvePositionConstraints`` with its slops).

Why a slop. The velocity rows are linear: in a step a bone turning at ω opens its joint by
about ½(ω·dt)²·r, 8 mm for a forearm whipping at 20 rad/s at 60 Hz; the bias of the velocity
rows (``joint_stages``) takes back half of it per step, so a ragdoll's joints opened by up to
8 cm in a fall, and the bias velocities fed the spin that opened them. Projecting it all back
fixes that but moves bodies without their velocities, which costs a freely tumbling jointed
pair 18 % of its angular momentum in 10 s. Projecting only what exceeds the slop does both:
the tumbling pair (gaps < 1 mm) is never projected and keeps its momentum, a falling ragdoll's
joints stay within the slop.
"""

from __future__ import annotations

import math

import numpy as np
from numba import njit

from ..rigid.joint_rows import EQUAL, OFF, angular_rows
from ..rigid.scalar import solve3, turn
from .joint_stages import OFF_JOINT, _axis_mass, _point_matrix, separation

#: Separation [m] and angle [rad] left to the velocity rows' bias (Box2D's linear slop 5 mm;
#: its angular slop is 2°, half that here so limits hold within a degree or two).
LINEAR_SLOP = 0.005
ANGULAR_SLOP = math.radians(1.0)
#: Largest correction of one joint in one pass (Box2D's 0.2 m and 8°).
MAX_CORRECTION = 0.2
MAX_ANGULAR_CORRECTION = math.radians(8.0)


@njit(cache=True, nogil=True)
def _turn_by(quat, inv_i, i, sign, lx, ly, lz):
    """Turn body i by sign·I⁻¹·L (the position-stage twin of an angular impulse L)."""
    if i < 0:
        return
    m = inv_i[i]
    turn(quat, i, sign * (m[0, 0] * lx + m[0, 1] * ly + m[0, 2] * lz),
          sign * (m[1, 0] * lx + m[1, 1] * ly + m[1, 2] * lz),
          sign * (m[2, 0] * lx + m[2, 1] * ly + m[2, 2] * lz))


@njit(cache=True, nogil=True)
def _move(pos, quat, inv_mass, inv_i, i, sign, rx, ry, rz, px, py, pz):
    """Move and turn body i by the 'impulse' sign·P at arm r (the twin of a point impulse)."""
    if i < 0:
        return
    w = inv_mass[i] * sign
    pos[i, 0] += w * px
    pos[i, 1] += w * py
    pos[i, 2] += w * pz
    _turn_by(quat, inv_i, i, sign, ry * pz - rz * py, rz * px - rx * pz, rx * py - ry * px)


@njit(cache=True, nogil=True)
def _angle_beyond(c, row):
    """The part of a row's position value beyond the slop (0 within it)."""
    if row == EQUAL:
        if c > ANGULAR_SLOP:
            return c - ANGULAR_SLOP
        if c < -ANGULAR_SLOP:
            return c + ANGULAR_SLOP
        return 0.0
    return min(c + ANGULAR_SLOP, 0.0)  # a limit: only a violation counts


@njit(cache=True, nogil=True)
def project_pass(ja, jb, la, lb, fa, fb, kind, lim, inv_mass, inv_i, pos, quat, mode):
    """One pass over the joints (not those whose ``mode`` is OFF: asleep): each one's
    angular rows, then its separation, brought back to the slops. Returns the largest excess
    met [m] and [rad]."""
    out = np.empty((3, 5))
    k = np.empty((3, 3))
    worst = 0.0
    worst_angle = 0.0
    for j in range(ja.shape[0]):
        if mode[j] == OFF_JOINT:
            continue
        a = ja[j]
        b = jb[j]
        angular_rows(quat, a, b, fa, fb, kind, lim, j, out)
        for s in range(3):
            if out[s, 4] == OFF:
                continue
            err = _angle_beyond(out[s, 3], out[s, 4])
            km = _axis_mass(inv_i, a, b, out[s, 0], out[s, 1], out[s, 2])
            if err == 0.0 or km <= 0.0:
                continue
            worst_angle = max(worst_angle, abs(err))
            fix = -max(-MAX_ANGULAR_CORRECTION, min(err, MAX_ANGULAR_CORRECTION)) / km
            _turn_by(quat, inv_i, b, 1.0, out[s, 0] * fix, out[s, 1] * fix, out[s, 2] * fix)
            _turn_by(quat, inv_i, a, -1.0, out[s, 0] * fix, out[s, 1] * fix, out[s, 2] * fix)
        c, ra, rb = separation(ja, jb, la, lb, pos, quat, j)
        size = math.sqrt(c[0] * c[0] + c[1] * c[1] + c[2] * c[2])
        if size <= LINEAR_SLOP:
            continue
        worst = max(worst, size - LINEAR_SLOP)
        scale = min(size - LINEAR_SLOP, MAX_CORRECTION) / size
        _point_matrix(inv_mass, inv_i, a, b, ra[0], ra[1], ra[2], rb[0], rb[1], rb[2], k)
        px, py, pz = solve3(k[0, 0], k[0, 1], k[0, 2], k[1, 0], k[1, 1], k[1, 2], k[2, 0],
                            k[2, 1], k[2, 2], -c[0] * scale, -c[1] * scale, -c[2] * scale)
        _move(pos, quat, inv_mass, inv_i, b, 1.0, rb[0], rb[1], rb[2], px, py, pz)
        _move(pos, quat, inv_mass, inv_i, a, -1.0, ra[0], ra[1], ra[2], px, py, pz)
    return worst, worst_angle
