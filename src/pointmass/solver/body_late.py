"""Overlaps that the step's contact rows did not foresee, projected out after the drift.

A substep's rows are found before the solve, each pair with the margin it can travel at the
velocities it has then (``rigid/collide.py``). An impulse in the solve can send a body where no
row looks: a thin 3.2 t plate tumbling on a wall got 2 850 N·s at one corner and drove another,
which was 21 cm out of the wall before the solve, 6 cm into it (the fuzz suite, issue 30). The
rows' projection cannot see that corner. So after the drift the contacts are found again,
without margin or travel (overlaps only), and if one is deeper than ``LATE_DEPTH``:

1. their velocities are solved, inelastic, frictionless and cold (``body_solver``, whose
   energy guard holds here too): whatever still moves into them stops, so the next step does
   not drive the same corner in again (measured: a box pivoting on one end on the ground, its
   other end's corner missed by the four points kept, gained 0.12 m/s downwards a step, from
   gravity, for 250 steps while the projection lifted it back: energy from nowhere);
2. they are projected like the rows (``body_stages.project_positions``: positions only; a
   turned body keeps its spin in its own frame, ``body_energy.keep_spin``).

Only points that are not among the substep's rows count (by key): what the rows' own
projection left (a falling pile's, a few mm) is theirs to finish next substep, as before, and
below ``LATE_DEPTH`` so are the new ones. Measured on the 250-box pit during its drop: with
every point counted and 1 mm, the stage ran on 76 of 120 steps and took 58 % of the time.
"""

from __future__ import annotations

import numpy as np
from numba import njit

from ..impulse_history import ImpulseHistory
from ..rigid import collide
from ..rigid.contacts import BodyContacts
from ..rigid.scalar import qrot_inv
from . import body_energy, body_solver
from . import body_stages as st
from .body_solver import MAX_POSITION_PASSES

#: An overlap deeper than this [m] that no row foresaw is stopped and projected at once (the
#: next substep's rows take shallower ones). Measured on the 250-box pit's drop (120 steps):
#: at 1 mm the stage ran on 66 steps, at 5 mm on 20, at 1 cm on 8; the fuzz suite's bound is
#: 2 cm at the end of a step, and a pass removes a fifth of what is beyond ``SLOP``.
LATE_DEPTH = 0.01


def project_late(bodies, planes, exclude, contacts: BodyContacts, dt: float, known: np.ndarray,
                 active: np.ndarray | None = None) -> int:
    """Find the overlaps of ``bodies`` now (pairs not in ``exclude``, bodies of ``active``)
    into ``contacts``, keep those that are not among this substep's rows (keys ``known``:
    what the rows' projection left is theirs to finish next substep, as before) and stop and
    project them if one is deeper than ``LATE_DEPTH``; returns the projection passes run."""
    b = bodies
    collide.generate(b, planes, 0.0, contacts, margin=0.0, active=active, exclude=exclude)
    c = contacts
    if c.count == 0 or float(c.depth.max()) <= LATE_DEPTH:
        return 0
    c.keep(~np.isin(c.key, known))
    if c.count == 0 or float(c.depth.max()) <= LATE_DEPTH:
        return 0
    c.friction[:] = 0.0
    c.restitution[:] = 0.0
    still = np.zeros((b.count, 3))
    body_solver.solve_velocities(_Masked(b, inv_mass_of(b, active)), c, still, ImpulseHistory(),
                                 dt, 0.0, body_solver.MAX_VELOCITY_PASSES)
    la = np.empty((c.count, 3))
    lb = np.empty((c.count, 3))
    _anchors(c.a, c.b, c.r_a, c.r_b, b.orientation, la, lb)
    inv_mass, inv_i = inv_mass_of(b, active)
    before = b.orientation.copy()
    passes, _ = st.project_positions(c.a, c.b, c.normal, la, lb, c.depth, inv_mass, inv_i,
                                     b.position, b.orientation, MAX_POSITION_PASSES)
    body_energy.keep_spin(before, b.orientation, b.angular_velocity)
    st.world_inertia(b.orientation, b.inv_inertia, b.inv_inertia_world)
    return int(passes)


def inv_mass_of(b, active):
    """The inverse masses and world inverse inertias, zero for bodies not ``active``."""
    if active is None:
        return b.inv_mass, b.inv_inertia_world
    return (np.where(active, b.inv_mass, 0.0),
            np.where(active[:, None, None], b.inv_inertia_world, 0.0))


class _Masked:
    """The bodies as the solver sees them, with those not active immovable."""

    def __init__(self, b, masses) -> None:
        self.inv_mass, self.inv_inertia_world = masses
        self.velocity = b.velocity
        self.angular_velocity = b.angular_velocity
        self.orientation = b.orientation
        self.position = b.position
        self.inv_inertia = b.inv_inertia


@njit(cache=True, nogil=True)
def _anchors(ca, cb, ra, rb, quat, la, lb):
    """Body-fixed arms of each point (the world point for scenery), as ``body_stages.prepare``."""
    for k in range(ca.shape[0]):
        a = ca[k]
        la[k, 0], la[k, 1], la[k, 2] = qrot_inv(quat[a, 0], quat[a, 1], quat[a, 2], quat[a, 3],
                                                ra[k, 0], ra[k, 1], ra[k, 2])
        i = cb[k]
        if i >= 0:
            lb[k, 0], lb[k, 1], lb[k, 2] = qrot_inv(quat[i, 0], quat[i, 1], quat[i, 2],
                                                    quat[i, 3], rb[k, 0], rb[k, 1], rb[k, 2])
        else:
            lb[k, 0], lb[k, 1], lb[k, 2] = rb[k, 0], rb[k, 1], rb[k, 2]
