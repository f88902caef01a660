"""The body stage of ``Solver``: rigid-body contact points through ``body_stages``.

It runs in the same substep and the same ``Solver`` as the particle stages, after them. The
bodies it sees may be a packed view (``rigid/particle_body.py``): the bodies, then particles
that touch them as bodies of zero inverse inertia, so particle–body points are rows like any
other; particle–particle contacts stay in the particle stages.
The velocity half runs before the bodies drift, the position half after (``World._substep``).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ..rigid.contacts import BodyContacts
from . import body_direct, joint_solver
from . import body_stages as st
from .history import ImpulseHistory

#: Velocity passes stop once no point's velocity changes by more than this [m/s] in a pass.
VELOCITY_TOLERANCE = 1e-5
#: Caps on the passes of each stage (they stop earlier once converged).
MAX_VELOCITY_PASSES = 30
MAX_POSITION_PASSES = 10


@dataclass
class BodyRows:
    """One substep's solver rows for body contact points, and what the stages return."""

    contacts: BodyContacts
    t1: np.ndarray
    t2: np.ndarray
    mass_n: np.ndarray
    mass_t1: np.ndarray
    mass_t2: np.ndarray
    target: np.ndarray
    anchor_a: np.ndarray
    anchor_b: np.ndarray
    impulse: np.ndarray
    jt1: np.ndarray
    jt2: np.ndarray
    velocity_passes: int = 0
    position_passes: int = 0
    deepest: float = 0.0
    joints: joint_solver.JointRows | None = None
    relax_passes: int = 0


def solve_velocities(bodies, contacts: BodyContacts, acceleration: np.ndarray,
                     history: ImpulseHistory, dt: float, threshold: float,
                     max_passes: int = MAX_VELOCITY_PASSES, joints=None) -> BodyRows:
    """Prepare, warm start and solve the velocities of ``contacts`` (and of ``joints``, a
    ``rigid.joint_set.Joints``, in the same passes); ``acceleration`` (N, 3) is what this
    substep's forces gave each body [m/s²] (for the resting-contact trick)."""
    m = contacts.count
    c = contacts
    rows = BodyRows(c, np.empty((m, 3)), np.empty((m, 3)), np.empty(m), np.empty(m),
                    np.empty(m), np.empty(m), np.empty((m, 3)), np.empty((m, 3)), np.zeros(m),
                    np.zeros(m), np.zeros(m))
    if joints is not None and len(joints):
        rows.joints = joint_solver.prepare(bodies, joints, dt)
    if m == 0:
        history.clear()
        if rows.joints is not None:
            joint_solver.warm_start(bodies, joints, rows.joints)
            rows.velocity_passes = _interleaved(bodies, c, rows, joints, max_passes)
        return rows
    b = bodies
    st.prepare(c.a, c.b, c.normal, c.r_a, c.r_b, c.depth, c.restitution, b.inv_mass,
               b.inv_inertia_world, b.orientation, b.velocity, b.angular_velocity, acceleration,
               dt, threshold, rows.t1, rows.t2, rows.mass_n, rows.mass_t1, rows.mass_t2,
               rows.target, rows.anchor_a, rows.anchor_b)
    friction = np.zeros((m, 3))
    history.recall(c.key, rows.impulse, friction)
    # the friction kept as a world vector, seen in this step's tangents
    rows.jt1[:] = np.einsum("ij,ij->i", friction, rows.t1)
    rows.jt2[:] = np.einsum("ij,ij->i", friction, rows.t2)
    st.warm_start(c.a, c.b, c.normal, c.r_a, c.r_b, rows.t1, rows.t2, b.inv_mass,
                  b.inv_inertia_world, b.velocity, b.angular_velocity, rows.impulse, rows.jt1,
                  rows.jt2)
    if rows.joints is not None:
        joint_solver.warm_start(b, joints, rows.joints)
    # A small set gets its exact normal impulses first (``body_direct.py``), then the passes
    # settle friction. Not after unconverged passes, as the particles do: the friction those
    # passes built on wrong normals stays (measured: a 10-box tower, μ 0.5, walked 1.1 cm in
    # 10 s with the direct solve after 10 passes, 2e-10 m with it first).
    if m <= body_direct.DIRECT_MAX_POINTS:
        body_direct.solve_normals(b, c, rows)
    if rows.joints is None:
        rows.velocity_passes = _passes(b, c, rows, max_passes)
    else:
        rows.velocity_passes = _interleaved(b, c, rows, joints, max_passes)
    return rows


#: Whether an interleaved pass visits the joints before the contacts (see ``_interleaved``).
#: Contacts first converges sooner: the ragdoll demo, seeds 1–6, 4 s each, averaged 24.6
#: velocity passes a step against 29.1 joints first (the cap is 30), same worst joint gaps.
JOINTS_FIRST = False
RELAX = 0


def _interleaved(b, c, rows: BodyRows, joints, max_passes: int) -> int:
    """Gauss–Seidel passes that visit the contacts, then the joints, until neither changes a
    velocity by more than ``VELOCITY_TOLERANCE``; returns the passes run."""
    for n in range(1, max_passes + 1):
        changed = 0.0
        if JOINTS_FIRST:
            changed = joint_solver.velocity_pass(b, joints, rows.joints)
        if c.count:
            before_v = b.velocity.copy()
            before_w = b.angular_velocity.copy()
            _passes(b, c, rows, 1)
            changed = max(changed, float(np.abs(b.velocity - before_v).max()),
                          float(np.abs(b.angular_velocity - before_w).max()))
        if not JOINTS_FIRST:
            changed = max(changed, joint_solver.velocity_pass(b, joints, rows.joints))
        if changed <= VELOCITY_TOLERANCE:
            return n
    return max_passes


def _passes(b, c, rows: BodyRows, passes: int) -> int:
    return int(st.solve_velocities(
        c.a, c.b, c.normal, c.r_a, c.r_b, rows.t1, rows.t2, c.friction, rows.mass_n,
        rows.mass_t1, rows.mass_t2, rows.target, b.inv_mass, b.inv_inertia_world, b.velocity,
        b.angular_velocity, rows.impulse, rows.jt1, rows.jt2, VELOCITY_TOLERANCE, passes))


def _project_with_joints(b, rows: BodyRows, joints) -> None:
    """Projection passes that visit the contacts, then the joints (``joint_project``: only
    what exceeds its slop), until both are within tolerance."""
    c = rows.contacts
    for n in range(1, MAX_POSITION_PASSES + 1):
        done = True
        if c.count:
            _, deepest = st.project_positions(c.a, c.b, c.normal, rows.anchor_a,
                                              rows.anchor_b, c.depth, b.inv_mass,
                                              b.inv_inertia_world, b.position, b.orientation, 1)
            rows.deepest = float(deepest)
            done = deepest <= 1.5 * st.SLOP
        done = joint_solver.position_pass(b, joints, rows.joints) and done
        rows.position_passes = n
        if done:
            return


def project_positions(bodies, rows: BodyRows, history: ImpulseHistory, joints=None) -> None:
    """After the drift: remove penetration beyond the slop (and what opened joints beyond
    theirs), refresh I⁻¹_world, keep the impulses for the next step."""
    c = rows.contacts
    b = bodies
    if rows.joints is not None:
        if RELAX:
            joint_solver.unbias(rows.joints)
            rows.relax_passes = _interleaved(b, c, rows, joints, RELAX)
        joint_solver.keep(joints, rows.joints)
        _project_with_joints(b, rows, joints)
        if c.count == 0:
            st.world_inertia(b.orientation, b.inv_inertia, b.inv_inertia_world)
            return
    if c.count == 0:
        return
    if rows.joints is None:
        passes, deepest = st.project_positions(c.a, c.b, c.normal, rows.anchor_a,
                                               rows.anchor_b, c.depth, b.inv_mass,
                                               b.inv_inertia_world, b.position, b.orientation,
                                               MAX_POSITION_PASSES)
        rows.position_passes = int(passes)
        rows.deepest = float(deepest)
    st.world_inertia(b.orientation, b.inv_inertia, b.inv_inertia_world)
    friction = rows.jt1[:, None] * rows.t1 + rows.jt2[:, None] * rows.t2
    history.keep(c.key, rows.impulse, friction)
