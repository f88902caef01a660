"""The soft step's (``body_soft``) energy: its restitution returns at most the kinetic energy
the step's contacts absorbed, its friction warm start is taken back in the pose it was given
in, and a body on scenery alone, or an island of bodies that joints or contacts link, leaves
no substep with more energy than it began with.

Newton's law per point (each point leaves at −e·v₀) keeps energy for one point with e ≤ 1,
but not for several points of one body struck unevenly, nor where v₀ is an estimate (the gap's
extrapolation, a point whose closing speed other rows changed before it pushed): in the
force-free random scenes of benchmarks/rigid_fuzz.py it gave a step +62 % (seed 297). The
energy the substeps' contact stages took out, Σ KE(after the kick) − KE(after the relax), is
the budget: if the restitution passes leave more kinetic energy than before them plus that
budget, the impulses they added are scaled by the largest s ∈ [0, 1] that keeps within it
(the energy is a quadratic in s, measured at s = ½ and 1; the impulses are linear in s, so
both momenta are kept). For a single point with e ≤ 1 it never acts (it returns e² of what
that point absorbed).

Two more sources of energy were found by measuring each stage of every gaining step (kinetic
energy after the kick, warm start, soft solve, drift and relax of each substep): both are
impulses given before the drift and taken back by the relax after it, in another pose.

* ``friction_cone``: the soft solve does not revise friction, so the warm start's friction on
  points that now separate rode through the drift and the relax took it off at the arms and
  inertia of the new pose (seed 38: +2.9 % in a step). It is now brought into the cone of the
  solve's normal impulses before the drift, in the pose it was given in, so it is taken back
  exactly.
* ``limit_scenery``: against scenery a point's arm does not change, but the body's inertia
  turns: impulses held through the drift (the push-out, friction within its cone) turn it
  with a spin the incoming one did not have, and the momentum it began with is worth another
  energy in the new pose (seed 297: +6.3e-4). A body whose only rows are against scenery
  (whose momentum is not kept anyway) leaves no substep with more energy than it began with.

Measured (benchmarks/rigid_fuzz.py, force-free joint-free scenes, issue 30's 1e-9): before
both, 27 of the first 100 (40 steps; 3 > 1e-3, the worst step +2.9 %) and 15 of the 37 of
seeds 0–299 (300 steps) gained in a step; with the friction cone 2 and 2 (worst +1.2e-7 and
+6.3e-4, all on scenery alone); with both, none. Bodies touching each other keep both momenta
exactly (their rows' impulses act at one point), so a pair's rows were left as they are, and
no scene measured then gained there. Once the continuous stage parted pairs of moving bodies
that a step left deep (``body_continuous``), one did: seed 380 (three boxes, a sphere, no
joint, no gravity) gained 4.2e-7 in step 24, in the soft solve of two boxes' contact (its
push-out held through the drift and relaxed in another pose, as with a joint below).
``limit_islands`` now caps every island that rows link, by joints or by contacts (``islands``),
in both loops: seed 380 gains 3.3e-15 at worst in 300 steps, and none of the 523 force-free
scenes of the slow seeds 1000–1999 (120 steps; 169 joint-free, 354 jointed) gains.

With joints (``body_soft.step``'s loop with them) the budget and the scenery limit run as
without, and ``limit_islands`` (an island of bodies linked by joints and contacts leaves no
substep with more kinetic energy than its kick left it) was first made for them.
Measured stage by stage as above, a joint's energy came from two places, both the soft step's
method and neither bounded by it:

* the joint stages: the solve aims each joint at the pose the substep ends in (and the bias
  pulls an open one shut), the drift moves the bodies with that velocity, and the relax takes
  it back at the arms and inertia of the new pose. For a point mass on a rod this returns
  exactly the tangential speed it began with; for a body with inertia, two joints, a hinge's
  locks, it leaves O((ω·h)²) of the aim's energy each substep (seed 58: two bodies each on a
  ball joint to a fixed point, shut, +8e-6 of the energy every substep, +3.1e-5 a step);
* the restitution, which had no budget with joints (seed 48: +12 % in a step); its budget
  is now what the substeps' contact and joint stages took out together.

Box2D v3's relax is there so that position correction leaves no kinetic energy; its joints
are rigid constraints whose softness is only the solver's means of closing a gap, so a
joint that starts open (the fuzz generator pulls half of its world anchors up to 0.5 m off) is
closed by moving the bodies, as a contact's overlap is pushed out, never by launching them:
no stored energy is released, and issue 30's "no force-free step gains > 1e-9" holds for
them too. Measured (benchmarks/rigid_fuzz.py, seeds 0–199, the 61 force-free jointed scenes,
300 steps): 47 gained in a step (15 > 1e-3; 28 of the 40 whose joints start shut, 19 of the
21 with one open) before; with the budget, the scenery limit and ``limit_islands``, none.
"""

from __future__ import annotations

import math

import numpy as np
from numba import njit

from ..rigid.bodies import _kinetic_energy
from ..rigid.islands import find_root
from ..rigid.scalar import qrot, qrot_inv
from .kernels import solve_symmetric3

#: The restitution may exceed its budget by this fraction of the kinetic energy (round-off of
#: summing it) before it is scaled.
SLACK = 1e-12


def kinetic_energy(view) -> float:
    """Kinetic energy [J] of ``view`` (the bodies, or the packed view with particles)."""
    return float(_kinetic_energy(view.velocity, view.angular_velocity, view.orientation,
                                 view.inv_mass, view.inv_inertia))


@njit(cache=True, inline="always")
def _gained(before, after):
    """Whether ``after`` exceeds ``before`` by more than round-off (or is not a number)."""
    return not after <= before * (1.0 + SLACK) + 1e-300


def gained(before: float, after: float) -> bool:
    """Whether ``after`` exceeds ``before`` by more than round-off (or is not a number)."""
    return bool(_gained(before, after))


@njit(cache=True, nogil=True)
def _scaled(s, v0, w0, dv, dw, vel, ang, quat, inv_mass, inv_inertia):
    """Velocities v0 + s·dv, w0 + s·dw written to ``vel``, ``ang``; returns their energy."""
    for i in range(vel.shape[0]):
        for u in range(3):
            vel[i, u] = v0[i, u] + s * dv[i, u]
            ang[i, u] = w0[i, u] + s * dw[i, u]
    return _kinetic_energy(vel, ang, quat, inv_mass, inv_inertia)


@njit(cache=True, nogil=True)
def limit_bounce(e0, absorbed, v0, w0, i0, vel, ang, impulse, quat, inv_mass, inv_inertia):
    """After ``body_soft.restitution`` ran from velocities ``v0``, ``w0`` and impulses ``i0``
    (kinetic energy ``e0``): if it left more energy than ``e0`` + ``absorbed`` (what the
    step's contact stages took out), scale what it added by the largest s ∈ [0, 1] that keeps
    within that (module docstring). Returns s."""
    e1 = _kinetic_energy(vel, ang, quat, inv_mass, inv_inertia)
    budget = max(absorbed, 0.0)
    limit = e0 + budget
    if not _gained(limit, e1):
        return 1.0
    dv = vel - v0
    dw = ang - w0
    half = _scaled(0.5, v0, w0, dv, dw, vel, ang, quat, inv_mass, inv_inertia)
    a = 2.0 * (e1 - 2.0 * half + e0)  # KE(s) = e0 + b·s + a·s², a = KE(Δ) ≥ 0
    b = e1 - e0 - a
    if a > 0.0:
        s = (-b + math.sqrt(max(b * b + 4.0 * a * budget, 0.0))) / (2.0 * a)
    elif b > 0.0:
        s = budget / b
    else:
        s = 1.0
    s = min(max(s * (1.0 - 1e-9), 0.0), 1.0)
    if _gained(limit, _scaled(s, v0, w0, dv, dw, vel, ang, quat, inv_mass, inv_inertia)):
        s = 0.0
        _scaled(s, v0, w0, dv, dw, vel, ang, quat, inv_mass, inv_inertia)
    for c in range(impulse.shape[0]):
        impulse[c] = i0[c] + s * (impulse[c] - i0[c])
    return s


@njit(cache=True, nogil=True)
def friction_cone(start, ca, cb, n, t1, t2, fmu, radius, mass_n, inv_mass, vel, ang, impulse,
                  jt1, jt2, jtw, farm):
    """After the soft solve, before the drift: each manifold's friction and twist brought into
    the cone of the normal impulses the solve left, μ·Σλ and μ·ρ·Σλ (the relax's own limits),
    what is taken off applied at this pose's arms, as the warm start applied it. Returns the
    manifolds clamped.

    The soft solve does not revise friction (``FRICTION_IN_SOLVE``), so a warm start of
    friction whose points now separate stayed in the velocities through the drift, and the
    relax took it off at the arms and inertia of the pose after it: not the impulse the warm
    start gave, and in force-free random scenes (benchmarks/rigid_fuzz.py) the step gained
    up to +2.9 % (seed 38: a box spinning off the ground, warm started with 8.4 × the
    kinetic energy). Clamped here, in the pose it was applied in, it is taken back exactly
    (module docstring: 27 of 100 scenes gained, 2 with this)."""
    count = 0
    for k in range(t1.shape[0]):
        if fmu[k] <= 0.0:
            continue
        s0 = start[k]
        total = 0.0
        for c in range(s0, start[k + 1]):
            if mass_n[c] != 0.0:  # as ``body_soft.soft_pass`` counts it
                total += impulse[c]
        limit = fmu[k] * total
        d1 = 0.0
        d2 = 0.0
        size = math.sqrt(jt1[k] * jt1[k] + jt2[k] * jt2[k])
        if size > limit:
            f = limit / size
            d1 = jt1[k] * f - jt1[k]
            d2 = jt2[k] * f - jt2[k]
            jt1[k] += d1
            jt2[k] += d2
        dw = 0.0
        twist = limit * radius[k]
        if abs(jtw[k]) > twist:
            dw = min(max(jtw[k], -twist), twist) - jtw[k]
            jtw[k] += dw
        if d1 == 0.0 and d2 == 0.0 and dw == 0.0:
            continue
        count += 1
        a = ca[s0]
        b = cb[s0]
        wa = inv_mass[a]
        wb = inv_mass[b] if b >= 0 else 0.0
        for u in range(3):
            p = d1 * t1[k, u] + d2 * t2[k, u]
            vel[a, u] += wa * p
            ang[a, u] += d1 * farm[k, 12 + u] + d2 * farm[k, 15 + u] + dw * farm[k, 24 + u]
            if b >= 0:
                vel[b, u] -= wb * p
                ang[b, u] -= d1 * farm[k, 18 + u] + d2 * farm[k, 21 + u] \
                    + dw * farm[k, 27 + u]
    return count


@njit(cache=True, nogil=True)
def scenery_only(count, ca, cb):
    """Per body of the view (``count``): whether every row it is in this step is against
    scenery (b < 0), and it is in one. No other body shares its rows, so the contacts can only
    take energy out of it (scenery is passive), and its momentum is not kept anyway."""
    alone = np.zeros(count, np.bool_)
    for c in range(ca.shape[0]):
        if cb[c] < 0:
            alone[ca[c]] = True
    for c in range(ca.shape[0]):
        if cb[c] >= 0:
            alone[ca[c]] = False
            alone[cb[c]] = False
    return alone


@njit(cache=True, inline="always")
def _body_energy(vel, ang, quat, inv_mass, inv_inertia, i):
    """Kinetic energy [J] of body i, its spin taken into its own frame (I diagonal there)."""
    e = 0.0
    if inv_mass[i] > 0.0:
        e = 0.5 * (vel[i, 0] * vel[i, 0] + vel[i, 1] * vel[i, 1] + vel[i, 2] * vel[i, 2]) \
            / inv_mass[i]
    q = quat[i]
    w = qrot_inv(q[0], q[1], q[2], q[3], ang[i, 0], ang[i, 1], ang[i, 2])
    for u in range(3):
        if inv_inertia[i, u] > 0.0:
            e += 0.5 * w[u] * w[u] / inv_inertia[i, u]
    return e


@njit(cache=True, nogil=True)
def body_energies(alone, vel, ang, quat, inv_mass, inv_inertia, out):
    """``out[i]`` = the kinetic energy of each body with ``alone[i]`` (the others left)."""
    for i in range(alone.shape[0]):
        if alone[i]:
            out[i] = _body_energy(vel, ang, quat, inv_mass, inv_inertia, i)


@njit(cache=True, nogil=True)
def limit_scenery(alone, start, vel, ang, quat, inv_mass, inv_inertia):
    """After a substep's relax: a body touching only scenery (``scenery_only``) that has more
    kinetic energy than ``start`` (its energy after the substep's kick) has its velocity and
    spin scaled to that energy. Returns the bodies scaled.

    Its rows keep their arms (scenery does not move), but the impulses the warm start and the
    soft solve gave before the drift turned the body with a spin the incoming one did not
    have, and its inertia with it: the relax takes them back at I⁻¹ of the new pose, and the
    momentum the substep began with is worth another energy there, ½·Lᵀ(I⁻¹₁ − I⁻¹₀)·L,
    first order in h and in the impulse held through the drift (a sphere's I⁻¹ does not turn:
    none). Measured in benchmarks/rigid_fuzz.py's force-free scenes after ``friction_cone``:
    2 of 100 (+1.2e-7) and 2 of 37 at 300 steps (+6.3e-4, seed 297), every one a body on
    scenery; none with this."""
    scaled = 0
    for i in range(alone.shape[0]):
        if not alone[i]:
            continue
        e = _body_energy(vel, ang, quat, inv_mass, inv_inertia, i)
        if not _gained(start[i], e):
            continue
        s = math.sqrt(start[i] / e) if e > 0.0 else 0.0
        for u in range(3):
            vel[i, u] *= s
            ang[i, u] *= s
        scaled += 1
    return scaled


class Budget:
    """One step's energy bookkeeping for ``body_soft.step``'s loop with joints (the loop
    without them, ``body_soft.contact_step``, keeps the same two sums itself): the energy each
    substep's contact stages start from, and the energy the contacts have absorbed so far."""

    def __init__(self) -> None:
        self.start = 0.0  # KE(v_in) of this substep
        self.absorbed = 0.0  # Σ over the substeps so far of KE(v_in) − KE(relaxed)

    def begin(self, view) -> None:
        """A substep's contact stages start now (after its kick)."""
        self.start = kinetic_energy(view)

    def relaxed(self, view) -> None:
        """The substep's relax has run: what its contact stages took out is absorbed."""
        self.absorbed += self.start - kinetic_energy(view)

    def bounce(self, view, impulse: np.ndarray, restitution) -> None:
        """Run ``restitution()`` (it applies the bounce impulses to ``view`` and adds them to
        ``impulse``), then ``limit_bounce``."""
        v0 = view.velocity.copy()
        w0 = view.angular_velocity.copy()
        i0 = impulse.copy()
        e0 = kinetic_energy(view)
        restitution()
        limit_bounce(e0, self.absorbed, v0, w0, i0, view.velocity, view.angular_velocity,
                     impulse, view.orientation, view.inv_mass, view.inv_inertia)


# --- islands: a substep leaves an island no more energy than it began with ----------------------
@njit(cache=True, nogil=True)
def islands(count, ja, jb, ca, cb, inv_mass, alone, label, grounded):
    """The islands of the view's ``count`` bodies that ``limit_islands`` caps: bodies linked by
    joints (``ja``, ``jb``) and by this step's contact rows (``ca``, ``cb``), never through a
    static one (inverse mass 0: it is scenery); an island is numbered if it holds a joint or a
    body that is in a row and not on scenery alone (``alone``, ``scenery_only``: those are
    ``limit_scenery``'s, body by body). ``label[i]`` = body i's island (0 … k−1; −1 for a body
    in none), ``grounded[k]`` = whether the island holds on to the world (a joint to a world
    point or a static body, or a contact with scenery): its momentum is not kept anyway.
    Returns k."""
    parent = np.arange(count)
    held = np.zeros(count, np.bool_)  # a row of it holds on to the world
    linked = np.zeros(count, np.bool_)  # in a joint, or in a contact and not on scenery alone
    for pairs in range(2):
        rows_a = ja if pairs == 0 else ca
        rows_b = jb if pairs == 0 else cb
        for r in range(rows_a.shape[0]):
            a = rows_a[r]
            b = rows_b[r]
            if pairs == 0 or not alone[a]:
                linked[a] = True
            if b >= 0 and (pairs == 0 or not alone[b]):
                linked[b] = True
            live_a = inv_mass[a] > 0.0
            live_b = b >= 0 and inv_mass[b] > 0.0
            if live_a and live_b:
                parent[find_root(parent, a)] = find_root(parent, b)
            elif live_a:
                held[a] = True
            elif live_b:
                held[b] = True
    island = np.full(count, -1)
    k = 0
    for i in range(count):  # the linked islands are numbered
        if linked[i] and inv_mass[i] > 0.0:
            r = find_root(parent, i)
            if island[r] < 0:
                island[r] = k
                k += 1
    for i in range(count):
        label[i] = island[find_root(parent, i)] if inv_mass[i] > 0.0 else -1
        grounded[i] = False
    for i in range(count):
        if label[i] >= 0 and held[i]:
            grounded[label[i]] = True
    return k


@njit(cache=True, nogil=True)
def island_energies(label, vel, ang, quat, inv_mass, inv_inertia, out):
    """``out[k]`` = the kinetic energy of island k (``islands``)."""
    out[:] = 0.0
    for i in range(label.shape[0]):
        if label[i] >= 0:
            out[label[i]] += _body_energy(vel, ang, quat, inv_mass, inv_inertia, i)


@njit(cache=True, inline="always")
def _spinning(inv_inertia, i):
    """Whether body i has a finite moment about every axis (a particle row has none)."""
    return inv_inertia[i, 0] > 0.0 and inv_inertia[i, 1] > 0.0 and inv_inertia[i, 2] > 0.0


@njit(cache=True, nogil=True)
def limit_islands(label, grounded, start, pos, vel, ang, quat, inv_mass, inv_inertia):
    """After a substep's relax: an island (``islands``) with more kinetic energy than
    ``start`` (its energy after the substep's kick) is brought back to it by scaling its
    motion relative to its rigid motion (for a grounded island: all of it), by the
    s ∈ [0, 1] that does. Returns the islands scaled.

    A free island's rigid motion (V, Ω) is the one with its momentum P and angular momentum L
    about its centre of mass X: V = P/M, Ω = I⁻¹L (I its inertia about X). It is the
    mass-weighted projection of its velocities onto rigid motions, so the energy splits into
    ½M·V² + ½Ωᵀ·I·Ω and the rest's, and it moves every joint and contact of the island
    without opening it. Scaling the rest keeps P and L exactly, and every row of the relax:
    an equality row (Ċ = 0) is linear in the velocities, and an inequality row's Ċ ≥ t with
    t ≤ 0 (a speculative contact or an open limit) still holds at s·Ċ ≥ s·t ≥ t. Where the
    rigid motion alone has more energy than ``start`` the rows did not keep the momenta (an
    open joint's impulses at its two anchors are a couple): all of it is scaled."""
    k = start.shape[0]
    scaled = 0
    energy = np.zeros(k)
    island_energies(label, vel, ang, quat, inv_mass, inv_inertia, energy)
    for isl in range(k):
        e = energy[isl]
        if not _gained(start[isl], e):
            continue
        scaled += 1
        vv = np.zeros(3)  # the rigid motion: V, Ω and the centre X
        om = np.zeros(3)
        x = np.zeros(3)
        rigid = 0.0
        if not grounded[isl]:
            mass = 0.0
            p = np.zeros(3)
            for i in range(label.shape[0]):
                if label[i] == isl:
                    m = 1.0 / inv_mass[i]
                    mass += m
                    for u in range(3):
                        p[u] += m * vel[i, u]
                        x[u] += m * pos[i, u]
            for u in range(3):
                vv[u] = p[u] / mass
                x[u] /= mass
            inertia = np.zeros((3, 3))
            ell = np.zeros(3)
            for i in range(label.shape[0]):
                if label[i] != isl:
                    continue
                m = 1.0 / inv_mass[i]
                r = pos[i] - x
                rv = vel[i] - vv
                ell[0] += m * (r[1] * rv[2] - r[2] * rv[1])
                ell[1] += m * (r[2] * rv[0] - r[0] * rv[2])
                ell[2] += m * (r[0] * rv[1] - r[1] * rv[0])
                rr = r[0] * r[0] + r[1] * r[1] + r[2] * r[2]
                for u in range(3):
                    inertia[u, u] += m * rr
                    for w in range(3):
                        inertia[u, w] -= m * r[u] * r[w]
                if _spinning(inv_inertia, i):
                    q = quat[i]
                    s0 = qrot_inv(q[0], q[1], q[2], q[3], ang[i, 0], ang[i, 1], ang[i, 2])
                    lw = qrot(q[0], q[1], q[2], q[3], s0[0] / inv_inertia[i, 0],
                              s0[1] / inv_inertia[i, 1], s0[2] / inv_inertia[i, 2])
                    for u in range(3):
                        ell[u] += lw[u]
                    for w in range(3):  # I_world's column w
                        c0 = qrot_inv(q[0], q[1], q[2], q[3], 1.0 if w == 0 else 0.0,
                                      1.0 if w == 1 else 0.0, 1.0 if w == 2 else 0.0)
                        col = qrot(q[0], q[1], q[2], q[3], c0[0] / inv_inertia[i, 0],
                                   c0[1] / inv_inertia[i, 1], c0[2] / inv_inertia[i, 2])
                        for u in range(3):
                            inertia[u, w] += col[u]
            om = solve_symmetric3(inertia, ell)
            rigid = 0.5 * mass * (vv[0] * vv[0] + vv[1] * vv[1] + vv[2] * vv[2]) \
                + 0.5 * (om[0] * ell[0] + om[1] * ell[1] + om[2] * ell[2])
        rest = e - rigid
        if not (rest > 0.0 and start[isl] > rigid):
            # its rigid motion alone has more: the rows did not keep its momenta (a joint
            # opened across a couple), so all of it is scaled, as a grounded island's
            vv[:] = 0.0
            om[:] = 0.0
            rigid = 0.0
            rest = e
        s = min(math.sqrt(max(start[isl] - rigid, 0.0) / rest), 1.0) if rest > 0.0 else 1.0
        for i in range(label.shape[0]):
            if label[i] != isl:
                continue
            r = pos[i] - x
            base = vv + np.array((om[1] * r[2] - om[2] * r[1], om[2] * r[0] - om[0] * r[2],
                                  om[0] * r[1] - om[1] * r[0]))
            spin = _spinning(inv_inertia, i)
            for u in range(3):
                vel[i, u] = base[u] + s * (vel[i, u] - base[u])
                if spin:  # (a particle row's spin carries no energy: left as it is)
                    ang[i, u] = om[u] + s * (ang[i, u] - om[u])
    return scaled
