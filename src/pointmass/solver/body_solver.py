"""The body stage of ``Solver``: rigid-body contact points through ``body_stages``.

It runs in the same substep and the same ``Solver`` as the particle stages, after them. The
bodies it sees may be a packed view (``rigid/particle_body.py``): the bodies, then particles
that touch them as bodies of zero inverse inertia, so particle–body points are rows like any
other; particle–particle contacts stay in the particle stages.
The velocity half runs before the bodies drift, the position half after (``World._substep``).

Neither half adds kinetic energy: a velocity solve that gained is redone the way that cannot
(``body_energy``), and the projections move positions only, each turned body keeping its spin
in its own frame. After both, overlaps that no row foresaw are stopped and projected
(``body_late``, called by the world).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ..impulse_history import ImpulseHistory
from ..rigid.contacts import BodyContacts
from . import body_direct, body_energy, joint_solver
from . import body_manifolds as bm
from . import body_passes as bp
from . import body_stages as st

#: Velocity passes stop once no point's velocity changes by more than this [m/s] in a pass.
VELOCITY_TOLERANCE = 1e-5
#: Caps on the passes of each stage (they stop earlier once converged).
MAX_VELOCITY_PASSES = 30
MAX_POSITION_PASSES = 10


@dataclass
class BodyRows:
    """One substep's solver rows for body contact points, and what the stages return.

    Per point (M,): ``mass_n``, ``target``, ``anchor_a``/``anchor_b`` (M, 3), ``impulse``. Per
    manifold (K,; ``body_manifolds``), rows ``start[k]`` to ``start[k + 1]``: tangents ``t1``,
    ``t2`` (K, 3), arms ``fa``, ``fb`` (K, 3) to the friction centre, μ ``mu``, twist radius
    ``radius`` [m], effective masses ``mass_t1``, ``mass_t2``, ``mass_tw`` and the friction
    and twist impulses ``jt1``, ``jt2``, ``jtw`` [N·s, N·m·s]. The rows' angular terms
    (``body_passes``): ``arm`` (M, 12) per point, ``farm`` (K, 30) per manifold."""

    contacts: BodyContacts
    start: np.ndarray
    mass_n: np.ndarray
    target: np.ndarray
    anchor_a: np.ndarray
    anchor_b: np.ndarray
    impulse: np.ndarray
    t1: np.ndarray
    t2: np.ndarray
    fa: np.ndarray
    fb: np.ndarray
    mu: np.ndarray
    radius: np.ndarray
    mass_t1: np.ndarray
    mass_t2: np.ndarray
    mass_tw: np.ndarray
    jt1: np.ndarray
    jt2: np.ndarray
    jtw: np.ndarray
    arm: np.ndarray
    farm: np.ndarray
    velocity_passes: int = 0
    position_passes: int = 0
    deepest: float = 0.0
    joints: joint_solver.JointRows | None = None

    @classmethod
    def empty(cls, contacts: BodyContacts) -> BodyRows:
        """Rows for ``contacts``, the manifolds found, every impulse zero."""
        m = contacts.count
        start = np.empty(m + 1, np.int64)
        k = bm.find_manifolds(contacts.a, contacts.b, contacts.normal, start) if m else 0
        return cls(contacts, start[:k + 1], np.empty(m), np.empty(m), np.empty((m, 3)),
                   np.empty((m, 3)), np.zeros(m), *(np.empty((k, 3)) for _ in range(4)),
                   *(np.empty(k) for _ in range(5)), *(np.zeros(k) for _ in range(3)),
                   np.empty((m, 12)), np.empty((k, 30)))


def solve_velocities(bodies, contacts: BodyContacts, acceleration: np.ndarray,
                     history: ImpulseHistory, dt: float, threshold: float,
                     max_passes: int = MAX_VELOCITY_PASSES, joints=None) -> BodyRows:
    """Prepare, warm start and solve the velocities of ``contacts`` (and of ``joints``, a
    ``rigid.joint_set.Joints``, in the same passes); ``acceleration`` (N, 3) is what this
    substep's forces gave each body [m/s²] (for the resting-contact trick).

    A solve that would add kinetic energy is redone the way that cannot (``body_energy``)."""
    b = bodies
    v0 = b.velocity.copy()
    w0 = b.angular_velocity.copy()
    energy0 = body_energy.kinetic_energy(b)
    rows = _solve(b, contacts, acceleration, history, dt, threshold, max_passes, joints)
    if body_energy.gained(energy0, body_energy.kinetic_energy(b)):
        import sys
        body_energy.redo(sys.modules[__name__], b, contacts, rows, joints, v0, w0, energy0,
                         max_passes)
    return rows


def _solve(bodies, contacts: BodyContacts, acceleration: np.ndarray, history: ImpulseHistory,
           dt: float, threshold: float, max_passes: int, joints) -> BodyRows:
    """The fast solve: warm started, bounce targets, joint bias, the exact solves."""
    c = contacts
    rows = BodyRows.empty(c)
    if joints is not None and len(joints):
        rows.joints = joint_solver.prepare(bodies, joints, dt)
    if c.count == 0:
        history.clear()
        if rows.joints is not None:
            joint_solver.warm_start(bodies, joints, rows.joints)
            rows.velocity_passes = _interleaved(bodies, c, rows, joints, max_passes)
        return rows
    b = bodies
    r = rows
    st.prepare(c.a, c.b, c.normal, c.r_a, c.r_b, c.depth, c.restitution, b.inv_mass,
               b.inv_inertia_world, b.orientation, b.velocity, b.angular_velocity, acceleration,
               dt, threshold, r.mass_n, r.target, r.anchor_a, r.anchor_b)
    bm.prepare_friction(r.start, c.a, c.b, c.normal, c.r_a, c.r_b, c.friction, b.inv_mass,
                        b.inv_inertia_world, r.t1, r.t2, r.fa, r.fb, r.mass_t1,
                        r.mass_t2, r.mass_tw, r.radius, r.mu)
    bp.prepare_arms(r.start, c.a, c.b, c.normal, c.r_a, c.r_b, r.fa, r.fb, r.t1, r.t2,
                    b.inv_inertia_world, r.arm, r.farm)
    kept = np.empty((c.count, 3))
    history.recall(c.key, r.impulse, kept)
    bm.gather_friction(r.start, c.normal, r.t1, r.t2, r.mu, r.radius, r.mass_tw, kept, r.jt1,
                       r.jt2, r.jtw)
    st.warm_start(r.start, c.a, c.b, c.normal, c.r_a, c.r_b, r.fa, r.fb, r.t1, r.t2,
                  b.inv_mass, b.inv_inertia_world, b.velocity, b.angular_velocity, r.impulse,
                  r.jt1, r.jt2, r.jtw)
    if rows.joints is not None:
        joint_solver.warm_start(b, joints, rows.joints)
    # A small set gets its exact normal impulses first (``body_direct.py``), then the passes
    # settle friction. Not after unconverged passes, as the particles do: the friction those
    # passes built on wrong normals stays (measured: a 10-box tower, μ 0.5, walked 1.1 cm in
    # 10 s with the direct solve after 10 passes, 2e-10 m with it first).
    if c.count <= body_direct.DIRECT_MAX_POINTS:
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


def _passes(b, c, r: BodyRows, passes: int) -> int:
    return int(bp.solve_velocities(
        r.start, c.a, c.b, c.normal, r.t1, r.t2, r.mu, r.radius, r.mass_n, r.mass_t1,
        r.mass_t2, r.mass_tw, r.target, b.inv_mass, b.velocity, b.angular_velocity, r.impulse,
        r.jt1, r.jt2, r.jtw, r.arm, r.farm, VELOCITY_TOLERANCE, passes))


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
    theirs), refresh I⁻¹_world, keep the impulses for the next step. A body the projection
    turns keeps its angular velocity in its own frame (``body_energy.keep_spin``), so its
    kinetic energy is unchanged."""
    c = rows.contacts
    if rows.joints is None and c.count == 0:
        return
    before = bodies.orientation.copy()
    _project(bodies, rows, history, joints)
    body_energy.keep_spin(before, bodies.orientation, bodies.angular_velocity)


def _project(bodies, rows: BodyRows, history: ImpulseHistory, joints) -> None:
    c = rows.contacts
    b = bodies
    if rows.joints is not None:
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
    kept = np.empty((c.count, 3))
    bm.split_friction(rows.start, c.normal, rows.t1, rows.t2, rows.jt1, rows.jt2, rows.jtw, kept)
    history.keep(c.key, rows.impulse, kept)
    c.impulse[:] = rows.impulse  # one velocity stage a substep: its impulse is the step's
