"""The body stage as Box2D v3's soft step (Catto, "Solver2D", 2024; box2d ``src/solver.c``,
``src/contact_solver.c``; rigid-notes §2 and §4).

Collision runs once per step; the rows it found are then solved over ``soft_substeps`` substeps
of h = dt / ``soft_substeps``, each in the stage order of Box2D v3 (the tuning numbers named
here are ``SolverSettings`` fields, ``World.settings``):

1. kick — v += h·(g + F/m), ω += h·I⁻¹τ (Box2D's ``b2IntegrateVelocitiesTask``; ``kick``).
   The force generators (springs, buoyancy, aerodynamics) are found again before each
   substep's kick, where the bodies then are (``step``'s ``forces``): semi-implicit Euler at
   h, so a body spring's energy does not grow and a body a force holds up is at rest every
   substep. The user's own forces and torques act in every substep; without generators, a
   force keeps acting at the world point where it was found. The first substep's kick is
   the world's, before collision, so the contacts see the velocities they will be solved
   with;
2. warm start — every point's accumulated normal impulse and every manifold's friction and
   twist (Catto 2006), again each substep;
3. solve — one Gauss–Seidel pass with **soft** normal rows (``soft``: a spring–damper of
   ``contact_hertz`` and damping ratio ``contact_damping_ratio``, twice as stiff against
   scenery, its push-out capped at ``contact_speed``), then the friction block at the manifold's
   friction centre and its twist (``body_manifolds``);
   Before the drift, friction is brought into the cone of the solve's normal impulses
   (``soft_energy.friction_cone``: a warm start of friction on points that now separate is
   taken back in the pose it was given in);
4. drift — x += v·h and the torque-free rotation (``rigid/step.integrate_positions``);
5. relax — the same pass without the soft bias: the velocity the push-out made is taken back,
   so an overlap is removed by moving the bodies, never by launching them. A body whose rows
   are all against scenery then has at most the energy it began the substep with
   (``soft_energy.limit_scenery``).

After the substeps, restitution: a point that closed faster than the threshold and pushed is
given the separating velocity −e·v₀ (less the closing speed gravity alone made, the
resting-contact trick), v₀ its normal velocity at the start of the substep it first pushed
in, before any warm start (``closing``); then the impulses are kept for the next step's warm
start (``ImpulseHistory``, by contact key).

Leapfrog (stop 42). The substeps are kick–drift pairs, so their positions are leapfrog's
(velocity Verlet's): the velocity a drift moves with is the half-step one, v(t + h/2). The
step keeps that half-step velocity of each body (``Bodies.half_velocity``, ``half_spin``)
and leaves the synchronised one, v(t) = v(t − h/2) + h/2·a, in ``velocity`` (``close``): a
closing half kick with the last substep's forces, then the velocities projected on the
step's rows (the contacts' relax passes from half the last substep's impulses, the half
kick's share, their sum kept ≥ 0, so a bounce is not taken back; the joints' relax), so a
body at rest on the ground or hanging from a joint is reported at rest. The next step goes
on from the half-step velocity with a whole kick (``body_stage._open_leapfrog``; the continuous
stage reads it too); a body whose velocity the last step did not leave (just added, set by
hand, woken, put back by the sweep) starts from it with a half kick. So the contacts and
joints solve what they solved before; what changed is the start and the velocity the world
reports: a free body falls on the exact parabola, and a pendulum's energy swings by
leapfrog's O((ω·h)²), −0.0063 … 0 % of m·g·L over 20 s (semi-implicit Euler's first-order
band at the same h was ±0.57 %). A force that starts with a body's first step counts half a
substep less (leapfrog's trapezoid). Tried, and measured worse: the half kicks inside the
solve (the first substep's soft rows then see half a kick against a whole substep's warm
start, and the 1 000-box pit never came to rest: 0.28 m/s at 10 s, against 0.004 m/s), and
half kicks around every substep's relax (0.35 m/s).

Each point keeps its two body-fixed anchors from collision. Before each pass the world points
of both anchors are found again from the bodies' current poses: their gap along the normal is
the point's current separation (collision stays once a step), and the impulses act at the
midpoint of the two, with I⁻¹_world of the current pose. A sphere touching a box does so along
a normal fixed in the box: that normal turns with the box through the substeps, and the sphere
is pushed where it now touches the face (``normals``; kept fixed in the world, a face turning
under a sliding sphere let it sink or float by the slide times the turn). Equal and opposite
impulses at one point change neither Σ p nor Σ (x × p + I·ω) about any origin, and the drift
keeps both, so the step conserves linear and angular momentum by construction (Box2D keeps the
arms of the step's start, which moves the two points of application apart by the sliding of a
substep).

A separation s > 0 is a speculative point: its row lets the gap close within the substep, no
further (target velocity −s/h), so it acts only once the bodies touch; it is not soft.

Particles that touch bodies are rows with zero inverse inertia (``rigid/particle_body.py``):
the same kernels, r×n·I⁻¹ vanishing. Joints are solved in the same substeps as Box2D v3
solves them (``joint_soft``: warm start, soft solve, relax in the pose the drift left; the
point blocks of a tree of joints solved exactly, aimed at the pose the substep ends in; no
projection).

Where it stands (issue 26; ``World()``'s body stage since stop 39, its only one since stop 44).
Measured with unit boxes (1 kg, μ 0.5), dt 1/60, sleep off (the impulses stage's figures, the
stage before it, in brackets): towers
of 5, 10, 20, 30 boxes drift 0.06, 0.10, 1.3, 1.1 mm sideways in 60 s (20 and 30 fall); the
210-box pyramid's apex 0.2 mm, 0.28 mm/s at 10 s (8.0 mm); two boxes colliding without gravity
keep linear and angular momentum to 1.4e-13 (3.5e-3 with e 0, μ 0); a 1 m box dropped from
0.9–1.1 m with e 0.5 rebounds to 0.2426–0.2474·h since the leapfrog (0.27–0.31·h; at stop
41 0.2416–0.2499·h, the semi-implicit flight at h losing h·v/2 of height falling and rising).
Collision runs once a step, so fast bodies could end steps deep in
what no row followed: the world's continuous stage after this step (``body_continuous``)
moves them back to their time of impact with static bodies and planes (no box passes the
thin wall) and parts pairs of a fast and a moving body that a step left deep; 7 of the 1 000
random scenes of the slow seeds (1000–1999, 120 steps) and 9 of seeds 0–999 at 300 steps
(stop 42) still end a step deep (issue 30's bound: 1 %), most a heavy body on a gram one
(Gauss–Seidel converges at the mass ratio's rate).
Force-free random scenes gain no kinetic energy in a step, with joints or without (issue 30's
1e-9; ``soft_energy``: the restitution's budget, the friction warm start clamped to the
solve's cone before the drift, bodies on scenery alone and islands that joints or contacts
link capped at their energy after the kick; ``joint_soft``'s docstring has the jointed
counts). Tried and taken out: warm starting across steps only the points that touch,
without friction (the 30-box tower then walked 32 cm in 60 s).
"""

from __future__ import annotations

import copy
import math
from dataclasses import dataclass

import numpy as np
from numba import njit

from ..impulse_history import ImpulseHistory
from ..keys import FEATURE_LIMIT
from ..rigid.bodies import _kinetic_energy
from ..rigid.box_box import EDGE_FLAG
from ..rigid.collide import SPECULATIVE_MARGIN
from ..rigid.contacts import BodyContacts
from ..rigid.scalar import qrot, qrot_inv
from ..rigid.shapes import SPHERE
from ..rigid.step import integrate_positions, integrate_velocities
from . import body_manifolds as bm
from . import body_passes as bp
from . import joint_friction, joint_soft, joint_solver, soft_energy
from .borrow import borrowed, keep_alive, scratch, zeroed
from .kernels import bounce_target
from .settings import SolverSettings

_DEFAULTS = SolverSettings()  # the entry points' settings when none are given

# The tuning numbers (substeps, the contacts' stiffness, damping ratio and push-out speed, the
# pass caps, tolerance and over-relaxation) are ``SolverSettings`` fields, read from the
# ``settings`` each entry point is given (Box2D v3's defaults, ``src/types.c``; what was measured
# when each was chosen is in their docstring).

#: Whether the biased pass solves friction too (Box2D v3.0), or only the relax pass does
#: (Box2D v3.1: friction is not fought by the push-out). A choice of method, not a tuning
#: number: ``soft_energy.friction_cone`` relies on the biased pass leaving friction alone.
FRICTION_IN_SOLVE = False

#: How a point's normal moves within the step (``normals``, ``refresh``): it stays as the
#: collision found it, turns with body A or B (a sphere on that body's face), lies along
#: the two centres (two spheres), or turns with body A or B as the reference face of two
#: boxes touching face to face.
FIXED, WITH_A, WITH_B, CENTRES, FACE_A, FACE_B = 0, 1, 2, 3, 4, 5


def softness(hertz: float, zeta: float, h: float) -> tuple[float, float, float]:
    """Box2D's ``b2MakeSoft``: (bias rate [1/s], mass scale, impulse scale) of a spring of
    ``hertz`` and damping ratio ``zeta`` solved implicitly over a substep h."""
    omega = 2.0 * math.pi * hertz
    a1 = 2.0 * zeta + h * omega
    a2 = h * omega * a1
    a3 = 1.0 / (1.0 + a2)
    return omega / a1, a2 * a3, a3


_SOFTNESS: list = [None]  # the last (inputs, soft, static) of ``_softness_rows``


def _softness_rows(h: float, st: SolverSettings) -> tuple[np.ndarray, np.ndarray]:
    """(soft, static): the contact rows' softness (``softness``, then ``contact_speed``)
    against bodies and against scenery for a substep h, made again only when h or a
    setting changes (a tiny world's step paid for building them every step)."""
    key = (h, st.contact_hertz, st.contact_hertz_cap, st.contact_damping_ratio,
           st.contact_speed)
    last = _SOFTNESS[0]
    if last is not None and last[0] == key:
        return last[1], last[2]
    hertz = min(st.contact_hertz, st.contact_hertz_cap * (1.0 / h))
    soft = np.array((*softness(hertz, st.contact_damping_ratio, h), st.contact_speed))
    static = np.array((*softness(2.0 * hertz, st.contact_damping_ratio, h), st.contact_speed))
    _SOFTNESS[0] = (key, soft, static)
    return soft, static


@dataclass
class SoftRows:
    """One step's rows of the soft step and what it did (the world reads the counts)."""

    contacts: BodyContacts
    velocity_passes: int = 0
    position_passes: int = 0
    deepest: float = 0.0


# --- kernels -----------------------------------------------------------------------------------

@njit(cache=True, nogil=True)
def anchor(ca, cb, n, ra, rb, quat, inv_mass, inv_i, vel, ang, acc, la, lb, along, approach,
           relv):
    """Per point: the body-fixed anchors la, lb (lb: the world point for scenery), |a·n|
    summed over both bodies (for the resting-contact trick), the closing acceleration
    −(aA − aB)·n and the normal velocity now at the collision's arms (``closing`` finds it
    again at the substeps' arms)."""
    for c in range(ca.shape[0]):
        a = ca[c]
        b = cb[c]
        nx, ny, nz = n[c, 0], n[c, 1], n[c, 2]
        q = quat[a]
        la[c, 0], la[c, 1], la[c, 2] = qrot_inv(q[0], q[1], q[2], q[3], ra[c, 0], ra[c, 1],
                                                ra[c, 2])
        g = abs(acc[a, 0] * nx + acc[a, 1] * ny + acc[a, 2] * nz)
        closing = -(acc[a, 0] * nx + acc[a, 1] * ny + acc[a, 2] * nz)
        vs = _normal_velocity(vel, ang, a, ra[c, 0], ra[c, 1], ra[c, 2], nx, ny, nz)
        if b >= 0:
            q = quat[b]
            lb[c, 0], lb[c, 1], lb[c, 2] = qrot_inv(q[0], q[1], q[2], q[3], rb[c, 0],
                                                    rb[c, 1], rb[c, 2])
            g += abs(acc[b, 0] * nx + acc[b, 1] * ny + acc[b, 2] * nz)
            closing += acc[b, 0] * nx + acc[b, 1] * ny + acc[b, 2] * nz
            vs -= _normal_velocity(vel, ang, b, rb[c, 0], rb[c, 1], rb[c, 2], nx, ny, nz)
        else:
            lb[c, 0], lb[c, 1], lb[c, 2] = rb[c, 0], rb[c, 1], rb[c, 2]
        along[c] = g
        approach[c] = closing
        relv[c] = vs


@njit(cache=True, nogil=True)
def round_rows(shape, ca, cb, round_a, round_b):
    """Per point: whether its body A, B is a sphere (``refresh``: a sphere's anchor does not
    turn with it; ``normals``: two spheres touch along their centres), from the view's
    ``shape``: a particle row of a packed view (``rigid/particle_body.py``) is a sphere of the
    particle's radius."""
    for c in range(ca.shape[0]):
        round_a[c] = shape[ca[c]] == SPHERE
        round_b[c] = cb[c] >= 0 and shape[cb[c]] == SPHERE


@njit(cache=True, nogil=True)
def normals(start, ca, cb, n, r0a, r0b, depth0, quat, round_a, round_b, owner, ln, reach, size,
            key):
    """Per point, how its normal follows the bodies through the step's substeps (``owner``:
    ``FIXED``, ``WITH_A``, ``WITH_B``, ``CENTRES``, ``FACE_A``, ``FACE_B``), that normal in the
    frame of the body it turns with (``ln``), and each sphere's reach along it (``reach``: r0·n
    of A, B; of two spheres along their centres, −r_A and r_B). ``start``: the manifolds' first
    rows (``body_manifolds.find_manifolds``); ``size`` (N, 3): the bodies' sizes; ``key`` (M,):
    the points' keys, whose low bits are the collision's feature ids.

    A sphere touching a box touches it along a normal fixed in the box. Kept fixed in the
    world through the step (Box2D's manifold normal, found once a step), a face that turns by
    ω·dt under a sphere sliding over it by d measured the sphere's gap wrong by d·ω·dt and
    pushed where the sphere no longer was: a ball sliding over a spinning slab rode 3–6 mm
    above its face or sank 4–5 mm into it, and a 119 kg ball sank into a 4 g box spinning at
    11 rad/s by 4 mm a step (issue 30's random scene 217).

    Only points the collision found touching or within its margin (``SPECULATIVE_MARGIN``) at
    the step's start: a gap that a sweep carried back from its time of impact lies along the
    normal of that later pose, which the step-start pose does not turn into (turned anyway,
    fast spheres went through a sphere, tests/physics/rigid/test_thin_wall.py).

    Two spheres touch along their centres (``CENTRES``): the normal is found again from the
    centres each substep, their gap is the centres' distance less the radii, and both are
    pushed at one point on that line. Kept fixed in the world, with the push between the two
    collision points carried along by the centres, two spheres that slid past each other
    within a step were pushed off their centres: two frictionless spheres in a glancing
    collision came away spinning (0.015 rad/s each at 1 m/s), a frictionless sphere sliding
    off another spun at 0.16 rad/s, and a frictionless pit of 1 000 sphere bodies spun up to
    3.0 rad/s (it still does, 1.6 rad/s: its pour's fast impacts, below, spin it).

    Not a sweep's row at a fast glancing pair's time of impact, whose normal is the centres'
    line then, not at the step's start: its push stays at one point, exact in both momenta,
    which spins the pair (two frictionless spheres at 10 m/s: 0.76 rad/s). Tried: pushed
    through each centre along that normal, the spheres kept no spin but the pair's angular
    momentum changed by 2 % (4 % at 50 m/s: the pushes, applied before the impact, act apart
    by the centres' offset across the normal); along the centres' line of each substep, it
    was kept, but the pair came away 3.3 % of its speed off the exact outcome (0.35 % along
    the impact's normal).

    Two boxes touching face to face (``FACE_A``, ``FACE_B``): the normal is the reference
    face's, and turns with the box that face belongs to (named by the point's feature id,
    ``box_box``); both anchors stay fixed in their bodies, so the gap is the incident point's
    height over that face as it now lies. Kept fixed in the world, a frictionless 5 cm cube
    sliding at 2–4 m/s over a slab spinning at 3 rad/s rode 1.2 mm above its face or sank
    3.3 mm into it, and at 4 m/s it tripped on the face's turn and tumbled off; now within
    0.8 mm (tests/physics/rigid/test_turning_normals.py). An edge–edge point's normal is
    fixed in neither box and stays fixed in the world."""
    for c in range(ca.shape[0]):
        a = ca[c]
        b = cb[c]
        turn = FIXED
        if b >= 0 and round_a[c] and round_b[c]:
            # two spheres whose normal lies along their centres at the step's start (r0b − r0a:
            # the arms meet there), as the collision finds every pair at that pose: their gap
            # is the centres' distance less the radii
            dx = r0b[c, 0] - r0a[c, 0]
            dy = r0b[c, 1] - r0a[c, 1]
            dz = r0b[c, 2] - r0a[c, 2]
            along = n[c, 0] * dx + n[c, 1] * dy + n[c, 2] * dz
            if along > 0.0 and along * along >= (1.0 - 1e-12) * (dx * dx + dy * dy + dz * dz):
                owner[c] = CENTRES
                reach[c, 0] = -size[a, 0]
                reach[c, 1] = size[b, 0]
            else:
                owner[c] = FIXED  # a sweep's row at a glancing pair's time of impact
            continue
        if b >= 0 and depth0[c] > -SPECULATIVE_MARGIN and round_a[c] != round_b[c]:
            # a point the collision found touching or within its margin now (not a gap that a
            # sweep carried back from its time of impact), between a sphere and a box
            turn = WITH_B if round_a[c] else WITH_A
        elif b >= 0 and not round_a[c] and not round_b[c]:  # two boxes
            feature = key[c] & (FEATURE_LIMIT - 1)
            if not feature & EDGE_FLAG:  # a face point: its normal is the reference face's
                turn = FACE_B if feature & 1 else FACE_A  # (its manifold decides, below)
        owner[c] = turn
        if turn == FIXED:
            continue
        nx, ny, nz = n[c, 0], n[c, 1], n[c, 2]
        reach[c, 0] = r0a[c, 0] * nx + r0a[c, 1] * ny + r0a[c, 2] * nz
        reach[c, 1] = r0b[c, 0] * nx + r0b[c, 1] * ny + r0b[c, 2] * nz
        q = quat[a] if turn == WITH_A or turn == FACE_A else quat[b]
        ln[c, 0], ln[c, 1], ln[c, 2] = qrot_inv(q[0], q[1], q[2], q[3], nx, ny, nz)
    # two boxes' face points turn as one manifold (the passes push every point of a manifold
    # along its first point's normal: with some points turned and others not, a push and its
    # angular terms lay along different normals, which changed two spinning boxes' angular
    # momentum by 3e-6), when any point of it was found touching or within the margin now
    for k in range(start.shape[0] - 1):
        s0 = start[k]
        turn = owner[s0]
        if turn != FACE_A and turn != FACE_B:
            continue
        near = False
        for c in range(s0, start[k + 1]):
            near = near or depth0[c] > -SPECULATIVE_MARGIN
        if not near:
            for c in range(s0, start[k + 1]):
                owner[c] = FIXED


@njit(cache=True, inline="always")
def _normal_velocity(vel, ang, i, rx, ry, rz, nx, ny, nz):
    return ((vel[i, 0] + ang[i, 1] * rz - ang[i, 2] * ry) * nx
            + (vel[i, 1] + ang[i, 2] * rx - ang[i, 0] * rz) * ny
            + (vel[i, 2] + ang[i, 0] * ry - ang[i, 1] * rx) * nz)


@njit(cache=True, nogil=True)
def refresh(start, ca, cb, n, la, lb, r0a, r0b, depth0, mu, inv_mass, inv_i, pos, quat, ra, rb,
            sep, mass_n, t1, t2, fa, fb, mass_t1, mass_t2, mass_tw, radius, fmu, arm, farm,
            round_a, round_b, owner, ln, reach, carry):
    """The rows at the bodies' current pose (module docstring): each point's normal as it now
    lies (``normals``: a sphere on a box's face turns with the box); its separation from its
    two body-fixed anchors (a sphere's: its reach along that normal); its arms to one point
    of application, the midpoint of the collision's arms r0a, r0b carried along by the two
    centres (Box2D's anchors, which do not turn with the body: a rolling ball keeps its point
    at the bottom), or, for a sphere on a box, the sphere's point on the face as it now lies;
    its normal mass, the manifolds' friction blocks and every row's angular terms. Returns
    the deepest overlap."""
    deepest = 0.0
    for c in range(ca.shape[0]):
        a = ca[c]
        b = cb[c]
        turn = owner[c]
        if turn == CENTRES:  # along the centres as they now lie (``normals``)
            dx = pos[a, 0] - pos[b, 0]
            dy = pos[a, 1] - pos[b, 1]
            dz = pos[a, 2] - pos[b, 2]
            span = math.sqrt(dx * dx + dy * dy + dz * dz)
            if span > 0.0:  # (concentric: the last normal stays)
                n[c, 0], n[c, 1], n[c, 2] = dx / span, dy / span, dz / span
        elif turn != FIXED:  # the normal as it now lies (``normals``)
            q = quat[a] if turn == WITH_A or turn == FACE_A else quat[b]
            n[c, 0], n[c, 1], n[c, 2] = qrot(q[0], q[1], q[2], q[3], ln[c, 0], ln[c, 1], ln[c, 2])
        nx, ny, nz = n[c, 0], n[c, 1], n[c, 2]
        # a sphere's nearest point along n is its centre's arm of the collision, whatever
        # its spin: an anchor turning with a ball that rolls at π/4 a substep (a ball shot
        # along a wall) left the wall and let the ball through it; along the normal as it now
        # lies where that turns
        q = quat[a]
        if round_a[c]:
            if turn != FIXED:
                ax, ay, az = reach[c, 0] * nx, reach[c, 0] * ny, reach[c, 0] * nz
            else:
                ax, ay, az = r0a[c, 0], r0a[c, 1], r0a[c, 2]
        else:
            ax, ay, az = qrot(q[0], q[1], q[2], q[3], la[c, 0], la[c, 1], la[c, 2])
        px, py, pz = pos[a, 0] + ax, pos[a, 1] + ay, pos[a, 2] + az
        if b >= 0:
            q = quat[b]
            if round_b[c]:
                if turn != FIXED:
                    bx, by, bz = reach[c, 1] * nx, reach[c, 1] * ny, reach[c, 1] * nz
                else:
                    bx, by, bz = r0b[c, 0], r0b[c, 1], r0b[c, 2]
            else:
                bx, by, bz = qrot(q[0], q[1], q[2], q[3], lb[c, 0], lb[c, 1], lb[c, 2])
            ux, uy, uz = pos[b, 0] + bx, pos[b, 1] + by, pos[b, 2] + bz
        else:
            ux, uy, uz = lb[c, 0], lb[c, 1], lb[c, 2]
        s = (px - ux) * nx + (py - uy) * ny + (pz - uz) * nz
        if turn != CENTRES:  # (two spheres' points are on their surfaces: s is their gap)
            s -= depth0[c]
        sep[c] = s
        if -s > deepest:
            deepest = -s
        if turn == WITH_B:  # a sphere on a face: pushed where the sphere now is
            ra[c, 0], ra[c, 1], ra[c, 2] = ax, ay, az
            rb[c, 0], rb[c, 1], rb[c, 2] = px - pos[b, 0], py - pos[b, 1], pz - pos[b, 2]
        elif turn == WITH_A:
            ra[c, 0], ra[c, 1], ra[c, 2] = ux - pos[a, 0], uy - pos[a, 1], uz - pos[a, 2]
            rb[c, 0], rb[c, 1], rb[c, 2] = bx, by, bz
        elif turn == CENTRES:
            # one point on the line of centres, between the two spheres' points weighted by
            # inverse mass (as below): each push passes through both centres (no spin), and
            # equal and opposite at one point it keeps both momenta
            w = inv_mass[a] + inv_mass[b]
            f = inv_mass[a] / w if w > 0.0 else 0.5
            mx = f * px + (1.0 - f) * ux
            my = f * py + (1.0 - f) * uy
            mz = f * pz + (1.0 - f) * uz
            ra[c, 0], ra[c, 1], ra[c, 2] = mx - pos[a, 0], my - pos[a, 1], mz - pos[a, 2]
            rb[c, 0], rb[c, 1], rb[c, 2] = mx - pos[b, 0], my - pos[b, 1], mz - pos[b, 2]
        else:
            mx = pos[a, 0] + r0a[c, 0]
            my = pos[a, 1] + r0a[c, 1]
            mz = pos[a, 2] + r0a[c, 2]
            if b >= 0:
                # both bodies are pushed at one point between their arms' ends, weighted by
                # inverse mass: the midpoint for equal masses, body A's own point against an
                # immovable body, as against scenery (with the midpoint, a swept contact's
                # point carried back to the step's start stayed behind on the wall while a
                # ball slid along it: its push spun the ball, 156 rad/s without friction, and
                # the ball went through the 5 cm wall, tests/physics/rigid/test_thin_wall.py)
                w = inv_mass[a] + inv_mass[b]
                f = inv_mass[a] / w if w > 0.0 else 0.5
                mx = f * mx + (1.0 - f) * (pos[b, 0] + r0b[c, 0])
                my = f * my + (1.0 - f) * (pos[b, 1] + r0b[c, 1])
                mz = f * mz + (1.0 - f) * (pos[b, 2] + r0b[c, 2])
                rb[c, 0], rb[c, 1], rb[c, 2] = mx - pos[b, 0], my - pos[b, 1], mz - pos[b, 2]
            else:
                rb[c, 0], rb[c, 1], rb[c, 2] = mx, my, mz
            ra[c, 0], ra[c, 1], ra[c, 2] = mx - pos[a, 0], my - pos[a, 1], mz - pos[a, 2]
        k = inv_mass[a] + bm.arm_mass(inv_i, a, ra[c, 0], ra[c, 1], ra[c, 2], nx, ny, nz)
        if b >= 0:
            k += inv_mass[b] + bm.arm_mass(inv_i, b, rb[c, 0], rb[c, 1], rb[c, 2], nx, ny, nz)
        mass_n[c] = 1.0 / k if k > 0.0 else 0.0
    bm.prepare_friction(start, ca, cb, n, ra, rb, mu, inv_mass, inv_i, t1, t2, fa, fb, mass_t1,
                        mass_t2, mass_tw, radius, fmu, owner, carry)
    bp.prepare_arms(start, ca, cb, n, ra, rb, fa, fb, t1, t2, inv_i, arm, farm)
    return deepest


@njit(cache=True, nogil=True)
def kick(nb, vel, ang, force, torque, start, pos, turn, inv_mass, inv_inertia, inv_i, lin_d,
         ang_d, g, h, awake, acc, drift=0.0):
    """The velocity half of a substep: the bodies' kick (``integrate_velocities``; returns the
    first body whose spin is not finite, or -1), and each awake particle row after them
    (index ≥ ``nb``) its own acceleration ``acc`` (a sleeping one in the view has no rows and
    is not integrated, as a sleeping body).

    ``force`` and ``torque`` (about the centre) were found with the bodies at ``start``; each
    force keeps acting at the world point where it was found, so a body whose centre has moved
    by d since gets the torque τ − d × F (into ``turn``). Then every substep adds Σ (x × F + τ)
    · h = the moment of the step's forces at their points, whatever the bodies did: a body
    spring's equal and opposite pair keeps Σ x × p + Iω exactly. (With τ held while the centre
    moves, the pair's two points of application are carried apart across its line of action:
    two boxes on a damped spring, 2.5 s at dt 1/240, gained 3.3e-3 of angular momentum, |L|
    1.27; 1e-13 this way.) ``drift``: the drift after this kick when it is not ``h`` (the
    leapfrog's closing half kick), for the spin's cap (``integrate_velocities``)."""
    for i in range(nb):
        fx, fy, fz = force[i, 0], force[i, 1], force[i, 2]
        dx = pos[i, 0] - start[i, 0]
        dy = pos[i, 1] - start[i, 1]
        dz = pos[i, 2] - start[i, 2]
        turn[i, 0] = torque[i, 0] - (dy * fz - dz * fy)
        turn[i, 1] = torque[i, 1] - (dz * fx - dx * fz)
        turn[i, 2] = torque[i, 2] - (dx * fy - dy * fx)
    bad = integrate_velocities(vel[:nb], ang[:nb], force, turn, inv_mass[:nb],
                               inv_inertia[:nb], inv_i[:nb], lin_d, ang_d, g, h, awake[:nb],
                               drift)
    for i in range(nb, vel.shape[0]):
        if inv_mass[i] > 0.0 and awake[i]:
            for u in range(3):
                vel[i, u] += h * acc[i, u]
    return bad


@njit(cache=True, nogil=True)
def soft_pass(start, ca, cb, n, t1, t2, fmu, radius, mass_n, mass_t1, mass_t2, mass_tw, sep,
              inv_mass, vel, ang, impulse, peak, jt1, jt2, jtw, arm, farm, inv_h, use_bias,
              friction, soft, static, relaxation):
    """One Gauss–Seidel pass over the manifolds: each point's normal row (soft with
    ``use_bias``: ``soft``/``static`` = (bias rate, mass scale, impulse scale, push-out cap)
    for body pairs and against scenery, each row moving ``relaxation`` × its Gauss–Seidel step
    (projected SOR; the relax pass's rows are hard, singular for a face's 4 coplanar points,
    and stay plain: over-relaxed too, a face-down box bounced 6 % too high); a gap s > 0
    closes by s/h at most), then the
    twist and the tangents at the friction centre within μ·Λ (with ``friction``). ``peak``
    keeps each point's largest accumulated impulse this step (``closing`` reads it). Returns
    the largest velocity change of a row [m/s]."""
    count = t1.shape[0]
    largest = 0.0
    for k in range(count):
        s0 = start[k]
        s1 = start[k + 1]
        a = ca[s0]
        b = cb[s0]
        wa = inv_mass[a]
        wb = inv_mass[b] if b >= 0 else 0.0
        nx, ny, nz = n[s0, 0], n[s0, 1], n[s0, 2]
        par = soft if b >= 0 else static
        over = relaxation if use_bias else 1.0
        total = 0.0
        for c in range(s0, s1):
            if mass_n[c] == 0.0:
                continue
            vs = bp._along(vel, ang, a, nx, ny, nz, arm, c, 0)
            if b >= 0:
                vs -= bp._along(vel, ang, b, nx, ny, nz, arm, c, 3)
            s = sep[c]
            scale = 1.0
            keep = 0.0
            if s > 0.0:
                bias = s * inv_h  # speculative: close the gap, no more
            elif use_bias:
                bias = max(par[1] * par[0] * s, -par[3])
                scale = par[1]
                keep = par[2]
            else:
                bias = 0.0
            new = max(impulse[c] - over * (mass_n[c] * (scale * vs + bias) + keep * impulse[c]),
                      0.0)
            d = new - impulse[c]
            impulse[c] = new
            total += new
            if new > peak[c]:
                peak[c] = new
            if d == 0.0:
                continue
            largest = max(largest, abs(d) / mass_n[c])
            vel[a, 0] += wa * d * nx
            vel[a, 1] += wa * d * ny
            vel[a, 2] += wa * d * nz
            ang[a, 0] += d * arm[c, 6]
            ang[a, 1] += d * arm[c, 7]
            ang[a, 2] += d * arm[c, 8]
            if b >= 0:
                vel[b, 0] -= wb * d * nx
                vel[b, 1] -= wb * d * ny
                vel[b, 2] -= wb * d * nz
                ang[b, 0] -= d * arm[c, 9]
                ang[b, 1] -= d * arm[c, 10]
                ang[b, 2] -= d * arm[c, 11]
        if fmu[k] <= 0.0 or not friction:
            continue
        if mass_tw[k] != 0.0 and radius[k] != 0.0:  # twist, within ±μ·ρ·Λ
            spin = ang[a, 0] * nx + ang[a, 1] * ny + ang[a, 2] * nz
            if b >= 0:
                spin -= ang[b, 0] * nx + ang[b, 1] * ny + ang[b, 2] * nz
            limit = fmu[k] * total * radius[k]
            new = min(max(jtw[k] - spin * mass_tw[k], -limit), limit)
            d = new - jtw[k]
            jtw[k] = new
            largest = max(largest, abs(d) / mass_tw[k] * radius[k])
            for u in range(3):
                ang[a, u] += d * farm[k, 24 + u]
                if b >= 0:
                    ang[b, u] -= d * farm[k, 27 + u]
        v1 = bp._along(vel, ang, a, t1[k, 0], t1[k, 1], t1[k, 2], farm, k, 0)
        v2 = bp._along(vel, ang, a, t2[k, 0], t2[k, 1], t2[k, 2], farm, k, 3)
        if b >= 0:
            v1 -= bp._along(vel, ang, b, t1[k, 0], t1[k, 1], t1[k, 2], farm, k, 6)
            v2 -= bp._along(vel, ang, b, t2[k, 0], t2[k, 1], t2[k, 2], farm, k, 9)
        new1 = jt1[k] - v1 * mass_t1[k]
        new2 = jt2[k] - v2 * mass_t2[k]
        limit = fmu[k] * total
        size = math.sqrt(new1 * new1 + new2 * new2)
        if size > limit:
            f = limit / size
            new1 *= f
            new2 *= f
        d1 = new1 - jt1[k]
        d2 = new2 - jt2[k]
        jt1[k] = new1
        jt2[k] = new2
        largest = max(largest, abs(d1) * (1.0 / mass_t1[k] if mass_t1[k] > 0.0 else 0.0),
                      abs(d2) * (1.0 / mass_t2[k] if mass_t2[k] > 0.0 else 0.0))
        for u in range(3):
            p = d1 * t1[k, u] + d2 * t2[k, u]
            vel[a, u] += wa * p
            ang[a, u] += d1 * farm[k, 12 + u] + d2 * farm[k, 15 + u]
            if b >= 0:
                vel[b, u] -= wb * p
                ang[b, u] -= d1 * farm[k, 18 + u] + d2 * farm[k, 21 + u]

    return largest


@njit(cache=True, nogil=True)
def closing(ca, cb, n, sep, peak, arm, vel, ang, relv, gap, speed):
    """Before a substep's warm start (``speed`` True): each point that has not pushed yet
    this step (``peak`` 0) keeps its normal velocity ``relv`` and separation ``gap`` (≥ 0)
    now, the restitution's v₀ and where it was seen (Box2D's ``relativeVelocity``, found
    before the warm start). After the drift, before the relax (``speed`` False), only its gap:
    a corner that first pushes in the relax (a speculative row that the next drift would
    overrun) is extrapolated from the gap its velocity drifted it to, v₀² = v² + 2·a·gap, as
    the rebound tests derive (test_contact_acceptance; from the gap before the drift it
    touched 0.9 % faster). The velocity after the drift is not read: it still holds the soft
    solve's push-out, which the relax takes back (read there, seed 14's ragdoll still moved
    at 0.1 m/s at 3 s).

    Read after the warm start (in the first pass that pushed), v₀ held the other points'
    warm-started impulses: a bone of a ragdoll lying on the ground, whose contacts' impulses
    balance its joints' (the tree's point blocks are not warm started), was spun to 9 rad/s
    by its contacts' warm start alone, a corner seen closing at 0.19–0.30 m/s bounced at
    e·v₀ every step, and the bone ended each step at 0.03 m/s and 0.2 rad/s that the next
    step took back (demos/21_ragdoll.py, seed 14: the arm never slept)."""
    for c in range(ca.shape[0]):
        if peak[c] != 0.0:
            continue
        gap[c] = max(sep[c], 0.0)
        if not speed:
            continue
        a = ca[c]
        b = cb[c]
        vs = bp._along(vel, ang, a, n[c, 0], n[c, 1], n[c, 2], arm, c, 0)
        if b >= 0:
            vs -= bp._along(vel, ang, b, n[c, 0], n[c, 1], n[c, 2], arm, c, 3)
        relv[c] = vs


@njit(cache=True, nogil=True)
def soft_passes(start, ca, cb, n, t1, t2, fmu, radius, mass_n, mass_t1, mass_t2, mass_tw, sep,
                inv_mass, vel, ang, impulse, peak, jt1, jt2, jtw, arm, farm, inv_h, use_bias,
                friction, soft, static, max_passes, tolerance, relaxation):
    """``soft_pass`` until no row changes a velocity by more than ``tolerance`` [m/s], at
    most ``max_passes``; returns the passes run. Repeating a soft pass converges to the
    soft rows' own solution (v + bias + γλ = 0 on every pushing row), not a stiffer one.
    (Borrowed views, ``borrow.py``: each pass's call counts no references.)"""
    start, ca, cb, n, t1, t2 = (borrowed(start), borrowed(ca), borrowed(cb), borrowed(n),
                                borrowed(t1), borrowed(t2))
    fmu, radius, mass_n, mass_t1 = borrowed(fmu), borrowed(radius), borrowed(mass_n), borrowed(
        mass_t1)
    mass_t2, mass_tw, sep, inv_mass = (borrowed(mass_t2), borrowed(mass_tw), borrowed(sep),
                                       borrowed(inv_mass))
    vel, ang, impulse, peak = borrowed(vel), borrowed(ang), borrowed(impulse), borrowed(peak)
    jt1, jt2, jtw, arm, farm = (borrowed(jt1), borrowed(jt2), borrowed(jtw), borrowed(arm),
                                borrowed(farm))
    soft, static = borrowed(soft), borrowed(static)
    passes = 0
    while passes < max_passes:
        passes += 1
        if soft_pass(start, ca, cb, n, t1, t2, fmu, radius, mass_n, mass_t1, mass_t2,
                     mass_tw, sep, inv_mass, vel, ang, impulse, peak, jt1, jt2, jtw, arm, farm,
                     inv_h, use_bias, friction, soft, static, relaxation) <= tolerance:
            break
    return passes

@njit(cache=True, nogil=True)
def joint_passes(max_passes, tolerance, predict, fallback, contacts, ja, jb, la, lb, ra, rb, kmat,
                 bias, axis, mass, target, row, lam, mode, mass_scale, impulse_scale, through, keep,
                 speed, top, dt, tree, nodes, parent, count, dinv, low, loops, where, sinv, pos,
                 quat, vel, ang, inv_mass, inv_inertia, inv_i, point, c_start, c_a, c_b, c_n, c_t1,
                 c_t2, c_fmu, c_radius, c_mass_n, c_mass_t1, c_mass_t2, c_mass_tw, c_sep, c_impulse,
                 c_peak, c_jt1, c_jt2, c_jtw, c_arm, c_farm, inv_h, use_bias, friction, soft,
                 static, c_tolerance, relaxation):
    """The joints' passes of a substep's solve or relax stage in one compiled call (the loop was
    Python's: ~28 passes a step of a jointed world, each a few kernel calls; a 6-link chain stepped
    ~1.2× faster in one call): each pass ``joint_solver.pass_kernel`` (the arguments from ``ja`` to
    ``point``: ``joint_solver.kernel_args``), then, with ``contacts``, one soft pass of the contact
    rows (``soft_passes``' arguments, from ``c_start``), until no joint row changes a velocity by
    more than ``tolerance`` (at most ``max_passes``). The solve's aim at the end pose (``predict``)
    is Newton's method (``joint_predict``): where a pass leaves more to do than the one before, the
    rest of the substep keeps the bias targets (``fallback`` copied into ``bias``). Returns (the
    passes run, whether it still aims)."""
    # borrowed views (``borrow.py``): the kernels called each pass count no references
    ja, jb, la, lb, ra = borrowed(ja), borrowed(jb), borrowed(la), borrowed(lb), borrowed(ra)
    rb, kmat, bias = borrowed(rb), borrowed(kmat), borrowed(bias)
    axis, mass = borrowed(axis), borrowed(mass)
    target, row, lam = borrowed(target), borrowed(row), borrowed(lam)
    mode, through = borrowed(mode), borrowed(through)
    keep, nodes, parent = borrowed(keep), borrowed(nodes), borrowed(parent)
    dinv, low = borrowed(dinv), borrowed(low)
    loops, where, sinv = borrowed(loops), borrowed(where), borrowed(sinv)
    pos, quat = borrowed(pos), borrowed(quat)
    vel, ang, inv_mass = borrowed(vel), borrowed(ang), borrowed(inv_mass)
    inv_inertia, inv_i = borrowed(inv_inertia), borrowed(inv_i)
    point, c_start, c_a = borrowed(point), borrowed(c_start), borrowed(c_a)
    c_b, c_n = borrowed(c_b), borrowed(c_n)
    c_t1, c_t2, c_fmu = borrowed(c_t1), borrowed(c_t2), borrowed(c_fmu)
    c_radius, c_mass_n = borrowed(c_radius), borrowed(c_mass_n)
    c_mass_t1, c_mass_t2, c_mass_tw = borrowed(c_mass_t1), borrowed(c_mass_t2), borrowed(c_mass_tw)
    c_sep, c_impulse = borrowed(c_sep), borrowed(c_impulse)
    c_peak, c_jt1, c_jt2 = borrowed(c_peak), borrowed(c_jt1), borrowed(c_jt2)
    c_jtw, c_arm = borrowed(c_jtw), borrowed(c_arm)
    c_farm, soft, static = borrowed(c_farm), borrowed(soft), borrowed(static)
    fallback = borrowed(fallback)
    n_rows = inv_mass.shape[0]
    xend = np.empty((n_rows, 3))
    qend = np.empty((n_rows, 4))
    passes = 0
    last = math.inf
    while passes < max_passes:
        passes += 1
        change = joint_solver.pass_kernel(predict, ja, jb, la, lb, ra, rb, kmat, bias, axis, mass,
            target, row, lam, mode, mass_scale, impulse_scale, through, keep, speed, top, dt, tree,
            nodes, parent, count, dinv, low, loops, where, sinv, pos, quat, vel, ang, inv_mass,
            inv_inertia, inv_i, point, xend, qend)
        if change <= tolerance:
            break
        if predict and change >= last:
            predict = False
            bias[:] = fallback
        last = change
        if contacts:
            soft_passes(c_start, c_a, c_b, c_n, c_t1, c_t2, c_fmu, c_radius, c_mass_n, c_mass_t1,
                        c_mass_t2, c_mass_tw, c_sep, inv_mass, vel, ang, c_impulse, c_peak, c_jt1,
                        c_jt2, c_jtw, c_arm, c_farm, inv_h, use_bias, friction, soft, static, 1,
                        c_tolerance, relaxation)
    return passes, predict


def _joint_solve(v, c: BodyContacts, r: _Rows, contacts: bool, joints, jr, relax: bool,
                 inv_h: float, soft, static, st: SolverSettings) -> int:
    """The joints' passes of a substep's solve (``relax`` False: their soft targets, each
    followed by one biased pass of the contact rows ``r``) or relax stage (rigid rows, each
    followed by one plain contact pass), ``joint_passes``; ``contacts`` False: no contact
    pass. The angular impulses are then kept (``joints.turn``) for the relax pass and the
    next substep's warm start. Returns the passes run."""
    rows = jr.relax if relax else jr.solve
    use_bias = not relax
    passes, rows.predict = joint_passes(
        st.joint_passes, st.joint_tolerance, rows.predict, jr.bias, contacts,
        *joint_solver.kernel_args(v, joints, rows), r.start, c.a, c.b, c.normal, r.t1, r.t2,
        r.fmu, r.radius, r.mass_n, r.mass_t1, r.mass_t2, r.mass_tw, r.sep, r.impulse, r.peak,
        r.jt1, r.jt2, r.jtw, r.arm, r.farm, inv_h, use_bias, FRICTION_IN_SOLVE or not use_bias,
        soft, static, st.soft_tolerance, st.soft_relaxation)
    joint_solver.keep(joints, rows)
    return int(passes)


@njit(cache=True, nogil=True)
def warm_start(start, ca, cb, n, t1, t2, inv_mass, vel, ang, impulse, jt1, jt2, jtw, arm,
               farm):
    """Apply the accumulated impulses again (each substep), with this pose's angular terms."""
    for k in range(t1.shape[0]):
        s0 = start[k]
        a = ca[s0]
        b = cb[s0]
        wa = inv_mass[a]
        wb = inv_mass[b] if b >= 0 else 0.0
        for c in range(s0, start[k + 1]):
            d = impulse[c]
            if d == 0.0:
                continue
            for u in range(3):
                vel[a, u] += wa * d * n[c, u]
                ang[a, u] += d * arm[c, 6 + u]
                if b >= 0:
                    vel[b, u] -= wb * d * n[c, u]
                    ang[b, u] -= d * arm[c, 9 + u]
        for u in range(3):
            p = jt1[k] * t1[k, u] + jt2[k] * t2[k, u]
            vel[a, u] += wa * p
            ang[a, u] += jt1[k] * farm[k, 12 + u] + jt2[k] * farm[k, 15 + u] \
                + jtw[k] * farm[k, 24 + u]
            if b >= 0:
                vel[b, u] -= wb * p
                ang[b, u] -= jt1[k] * farm[k, 18 + u] + jt2[k] * farm[k, 21 + u] \
                    + jtw[k] * farm[k, 27 + u]


@njit(cache=True, nogil=True)
def restitution(start, ca, cb, n, e, along, approach, relv, gap, peak, mass_n, inv_mass, vel,
                ang, impulse, arm, h, threshold, resting, max_passes, tolerance):
    """After the substeps: a point that pushed and closed with v₀ leaves with −e·v₀ (zero
    below ``threshold``); a point that was already pushing last step (``resting``) less the
    closing speed one substep's acceleration made (the resting-contact trick: a body at rest
    under gravity closes by g·h each substep and must not bounce it back). A new point is an
    impact: the whole speed it came with counts, and v₀ is the speed it touches with, found
    from the speed and gap it was last seen at before it pushed and its closing acceleration
    a (v₀² = v² + 2·a·gap: a body seen 1.6 cm above the floor at 4.37 m/s touches at 4.41 m/s,
    1 % faster; 2 % more rebound height). Gauss–Seidel passes until no point's
    velocity changes by more than ``tolerance``, so the points of one face bounce together
    (one pass gave a flat box dropped on its face a spin, and 10–14 % less height).
    Returns the passes run."""
    passes = 0
    while passes < max_passes:
        passes += 1
        largest = 0.0
        for k in range(start.shape[0] - 1):
            s0 = start[k]
            a = ca[s0]
            b = cb[s0]
            wa = inv_mass[a]
            wb = inv_mass[b] if b >= 0 else 0.0
            for c in range(s0, start[k + 1]):
                if e[c] == 0.0 or peak[c] == 0.0 or mass_n[c] == 0.0:
                    continue
                acc_sep = -along[c] * h if resting[c] else 0.0
                v0 = relv[c]
                if v0 < 0.0 and gap[c] > 0.0:
                    v0 = -math.sqrt(max(v0 * v0 + 2.0 * approach[c] * gap[c], 0.0))
                target = bounce_target(v0, acc_sep, e[c], threshold)
                if target <= 0.0:
                    continue
                vs = bp._along(vel, ang, a, n[c, 0], n[c, 1], n[c, 2], arm, c, 0)
                if b >= 0:
                    vs -= bp._along(vel, ang, b, n[c, 0], n[c, 1], n[c, 2], arm, c, 3)
                new = max(impulse[c] + (target - vs) * mass_n[c], 0.0)
                d = new - impulse[c]
                if d == 0.0:
                    continue
                impulse[c] = new
                largest = max(largest, abs(d) / mass_n[c])
                for u in range(3):
                    vel[a, u] += wa * d * n[c, u]
                    ang[a, u] += d * arm[c, 6 + u]
                    if b >= 0:
                        vel[b, u] -= wb * d * n[c, u]
                        ang[b, u] -= d * arm[c, 9 + u]
        if largest <= tolerance:
            break
    return passes


@njit(cache=True, nogil=True)
def _accelerated(gravity, force, torque):
    """Whether anything accelerates the bodies (gravity, a force or a torque): without, the
    leapfrog's closing half kick is nothing and the step leaves its velocities as they are."""
    if gravity[0] != 0.0 or gravity[1] != 0.0 or gravity[2] != 0.0:
        return True
    for i in range(force.shape[0]):
        for u in range(3):
            if force[i, u] != 0.0 or torque[i, u] != 0.0:
                return True
    return False


@njit(cache=True, nogil=True)
def open_step(awake, vel, ang, left_v, left_w, half_v, half_w, fresh):
    """The leapfrog's opening (``body_stage._open_leapfrog``): each awake body whose velocity and
    spin are bit for bit the ones the last step left (``left_v``, ``left_w``; inf: none) goes
    on from the half-step ones that step drifted with (``half_v``, ``half_w``); ``fresh`` (N,)
    leaves True for every other body (a body just added, set by hand, asleep or woken)."""
    for i in range(vel.shape[0]):
        same = awake[i]
        for u in range(3):
            if vel[i, u] != left_v[i, u] or ang[i, u] != left_w[i, u]:
                same = False
        fresh[i] = not same
        if same:
            for u in range(3):
                vel[i, u] = half_v[i, u]
                ang[i, u] = half_w[i, u]


@njit(cache=True, nogil=True)
def open_and_kick(awake, vel, ang, left_v, left_w, half_v, half_w, force, torque, inv_mass,
                  inv_inertia, inv_i, lin_d, ang_d, g, h):
    """The leapfrog's opening and the first kick in one call (``body_stage._open_leapfrog``):
    ``open_step``, then a whole kick of ``h`` for the bodies that go on from their half-step
    velocity and a half kick (followed by a drift of ``h``) for the fresh ones. Returns
    (the first body whose spin is not finite, or -1; 1 if it was in the half kick)."""
    n = vel.shape[0]
    fresh = np.empty(n, np.bool_)
    open_step(awake, vel, ang, left_v, left_w, half_v, half_w, fresh)
    going = np.empty(n, np.bool_)
    for i in range(n):
        going[i] = awake[i] and not fresh[i]
        fresh[i] = awake[i] and fresh[i]
    bad = integrate_velocities(vel, ang, force, torque, inv_mass, inv_inertia, inv_i, lin_d,
                               ang_d, g, h, going)
    if bad >= 0:
        return bad, 0
    bad = integrate_velocities(vel, ang, force, torque, inv_mass, inv_inertia, inv_i, lin_d,
                               ang_d, g, 0.5 * h, fresh, h)
    return bad, 1


@njit(cache=True, nogil=True)
def leave_step(awake, vel, ang, left_v, left_w):
    """What the step left each awake body with (``open_step`` reads it); a sleeper's is
    marked none (inf): woken, by hand or by a touch, it starts afresh from rest."""
    for i in range(vel.shape[0]):
        for u in range(3):
            left_v[i, u] = vel[i, u] if awake[i] else np.inf
            left_w[i, u] = ang[i, u]


# --- the step ----------------------------------------------------------------------------------

class _Rows:
    """The per-point and per-manifold work arrays of one step."""

    def __init__(self, c: BodyContacts) -> None:
        m = c.count
        start = np.empty(m + 1, np.int64)
        k = bm.find_manifolds(c.a, c.b, c.normal, start) if m else 0
        self.start = start[:k + 1]
        self.la, self.lb, self.ra, self.rb = (np.empty((m, 3)) for _ in range(4))
        self.along, self.approach, self.relv, self.sep, self.mass_n = (
            np.empty(m) for _ in range(5))
        self.gap = np.zeros(m)
        self.impulse = np.zeros(m)
        self.peak = np.zeros(m)
        self.arm = np.empty((m, 12))
        self.t1, self.t2, self.fa, self.fb = (np.empty((k, 3)) for _ in range(4))
        self.fmu, self.radius, self.mass_t1, self.mass_t2, self.mass_tw = (
            np.empty(k) for _ in range(5))
        self.jt1, self.jt2, self.jtw = (np.zeros(k) for _ in range(3))
        self.farm = np.empty((k, 30))
        #: per point: whether body A, B is a sphere (``refresh``: its anchor does not turn)
        self.round_a, self.round_b = np.zeros(m, np.bool_), np.zeros(m, np.bool_)
        #: per point: how its normal turns, that normal in its body's frame, each ball's reach
        self.owner = np.zeros(m, np.int8)
        self.ln = np.empty((m, 3))
        self.reach = np.empty((m, 2))


def _refresh(b, c: BodyContacts, r: _Rows, carry: bool = False) -> float:
    """``refresh`` (``carry``: a later substep's, whose turning manifolds carry their
    tangents along)."""
    return float(refresh(r.start, c.a, c.b, c.normal, r.la, r.lb, c.r_a, c.r_b, c.depth,
                         c.friction,
                         b.inv_mass, b.inv_inertia_world, b.position, b.orientation, r.ra, r.rb,
                         r.sep, r.mass_n, r.t1, r.t2, r.fa, r.fb, r.mass_t1, r.mass_t2,
                         r.mass_tw, r.radius, r.fmu, r.arm, r.farm, r.round_a, r.round_b,
                         r.owner, r.ln, r.reach, carry))


def _pass(b, c: BodyContacts, r: _Rows, inv_h: float, use_bias: bool, soft, static,
          st: SolverSettings, max_passes: int = 1) -> int:
    friction = FRICTION_IN_SOLVE or not use_bias
    return int(soft_passes(
        r.start, c.a, c.b, c.normal, r.t1, r.t2, r.fmu, r.radius, r.mass_n, r.mass_t1,
        r.mass_t2, r.mass_tw, r.sep, b.inv_mass, b.velocity, b.angular_velocity, r.impulse,
        r.peak, r.jt1, r.jt2, r.jtw, r.arm, r.farm, inv_h, use_bias, friction,
        soft, static, max_passes, st.soft_tolerance, st.soft_relaxation))


@njit(cache=True, nogil=True)
def contact_step(nb, substeps, h, gravity, soft, static, threshold, pos, quat, vel, ang,
                 inv_mass, inv_inertia, inv_i, awake, lin_d, ang_d, acc, ca, cb, n, r0a, r0b,
                 depth0, mu, e, key, impulse, kept, shape, size, total, force, torque,
                 solve_passes, relax_passes, tolerance, relaxation, half_v, half_w):
    """The whole soft step of a world without joints in one compiled call (issue 26: a small
    world pays no Python per substep; measured, the 10-box tower's stage made 38 kernel calls
    a step from Python). ``impulse`` (M,) and ``kept`` (M, 3) come in with the recalled warm
    start and leave with what to keep; ``total`` (M,) leaves with the normal impulse each point
    gave over the step (Σ of the substeps' impulses, then the bounce). The same kernels, in
    the same order, as ``step``'s loop with joints: the results are bit for bit those of that
    loop.

    ``shape`` (N,) the view's shapes (a packed view's particles: spheres): which points'
    anchors do not turn (``round_rows``); ``size`` (N, 3) their sizes (a sphere's radius: two
    spheres' gap, ``normals``).
    ``solve_passes``, ``relax_passes``, ``tolerance``, ``relaxation``: the settings'
    ``soft_solve_passes``, ``soft_relax_passes``, ``soft_tolerance``, ``soft_relaxation``.

    Returns (passes, deepest overlap, error, body): error 1 is a spin that is not finite after
    a kick, 2 a body that is not finite after a drift, 3 a row whose velocity the step left
    not finite or too large to square (``_refuse_blow_up``; ``body`` names it), 0 none."""
    # Borrowed views (``borrow.py``) of the arguments and of the scratch arrays made here (each
    # ``*_own`` owner kept to the end by ``keep_alive``): the kernels called below count no
    # references. Counted, they were a third of a resting sphere's step.
    gravity, soft, static = borrowed(gravity), borrowed(soft), borrowed(static)
    pos, quat, vel, ang = borrowed(pos), borrowed(quat), borrowed(vel), borrowed(ang)
    inv_mass, inv_inertia, inv_i = borrowed(inv_mass), borrowed(inv_inertia), borrowed(inv_i)
    awake, lin_d, ang_d, acc = borrowed(awake), borrowed(lin_d), borrowed(ang_d), borrowed(acc)
    ca, cb, n, r0a, r0b = borrowed(ca), borrowed(cb), borrowed(n), borrowed(r0a), borrowed(r0b)
    depth0, mu, e, impulse = borrowed(depth0), borrowed(mu), borrowed(e), borrowed(impulse)
    key = borrowed(key)
    kept, shape, size, total = borrowed(kept), borrowed(shape), borrowed(size), borrowed(total)
    force, torque = borrowed(force), borrowed(torque)
    half_v, half_w = borrowed(half_v), borrowed(half_w)
    m = ca.shape[0]
    round_a_own, round_a = scratch(m, np.bool_)
    round_b_own, round_b = scratch(m, np.bool_)
    round_rows(shape, ca, cb, round_a, round_b)
    owner_own, owner = zeroed(m, np.int8)
    ln_own, ln = scratch((m, 3), np.float64)
    reach_own, reach = scratch((m, 2), np.float64)
    start_own, start = scratch(m + 1, np.int64)
    k = bm.find_manifolds(ca, cb, n, start) if m else 0
    start = borrowed(start_own[:k + 1])
    la_own, la = scratch((m, 3), np.float64)
    lb_own, lb = scratch((m, 3), np.float64)
    ra_own, ra = scratch((m, 3), np.float64)
    rb_own, rb = scratch((m, 3), np.float64)
    along_own, along = scratch(m, np.float64)
    approach_own, approach = scratch(m, np.float64)
    relv_own, relv = scratch(m, np.float64)
    sep_own, sep = scratch(m, np.float64)
    mass_n_own, mass_n = scratch(m, np.float64)
    gap_own, gap = zeroed(m, np.float64)
    peak_own, peak = zeroed(m, np.float64)
    arm_own, arm = scratch((m, 12), np.float64)
    t1_own, t1 = scratch((k, 3), np.float64)
    t2_own, t2 = scratch((k, 3), np.float64)
    fa_own, fa = scratch((k, 3), np.float64)
    fb_own, fb = scratch((k, 3), np.float64)
    fmu_own, fmu = scratch(k, np.float64)
    radius_own, radius = scratch(k, np.float64)
    mass_t1_own, mass_t1 = scratch(k, np.float64)
    mass_t2_own, mass_t2 = scratch(k, np.float64)
    mass_tw_own, mass_tw = scratch(k, np.float64)
    jt1_own, jt1 = zeroed(k, np.float64)
    jt2_own, jt2 = zeroed(k, np.float64)
    jtw_own, jtw = zeroed(k, np.float64)
    farm_own, farm = scratch((k, 30), np.float64)
    resting = impulse > 0.0  # pushing last step: not an impact
    if m:
        anchor(ca, cb, n, r0a, r0b, quat, inv_mass, inv_i, vel, ang, acc, la, lb, along,
               approach, relv)
        normals(start, ca, cb, n, r0a, r0b, depth0, quat, round_a, round_b, owner, ln, reach,
                size, key)
        refresh(start, ca, cb, n, la, lb, r0a, r0b, depth0, mu, inv_mass, inv_i, pos, quat, ra,
                rb, sep, mass_n, t1, t2, fa, fb, mass_t1, mass_t2, mass_tw, radius, fmu, arm,
                farm, round_a, round_b, owner, ln, reach, False)
        bm.gather_friction(start, n, t1, t2, fmu, radius, mass_tw, kept, jt1, jt2, jtw)
    # restitution returns at most what the contacts absorbed (``soft_energy``), counted only
    # where a point can bounce
    bouncy = False
    for c in range(m):
        if e[c] > 0.0:
            bouncy = True
            break
    absorbed = 0.0
    begun = 0.0
    inv_h = 1.0 / h
    start_pos_own = pos[:nb].copy()  # where the forces were found (``kick``)
    start_pos = borrowed(start_pos_own)
    turn_own, turn = scratch((nb, 3), np.float64)
    passes = 0
    deepest = 0.0
    # a body on scenery alone leaves no substep with more energy than it began with
    alone = soft_energy.scenery_only(vel.shape[0], ca, cb)
    start_energy_own, start_energy = zeroed(vel.shape[0], np.float64)
    # ... nor an island of bodies that contacts link (``soft_energy.limit_islands``)
    label_own, label = scratch(vel.shape[0], np.int64)
    grounded_own, grounded = scratch(vel.shape[0], np.bool_)
    none_own, none = scratch(0, np.int64)
    islands = soft_energy.islands(vel.shape[0], none, none, ca, cb, inv_mass, alone, label,
                                  grounded) if m else 0
    grounded = borrowed(grounded_own[:islands])
    island_energy_own, island_energy = zeroed(islands, np.float64)
    total[:] = 0.0
    for i in range(substeps):
        if i > 0:
            bad = kick(nb, vel, ang, force, torque, start_pos, pos, turn, inv_mass,
                       inv_inertia, inv_i, lin_d, ang_d, gravity, h, awake, acc)
            if bad >= 0:
                return passes, deepest, 1, bad
        if bouncy:
            begun = _kinetic_energy(vel, ang, quat, inv_mass, inv_inertia)
        if islands:
            soft_energy.island_energies(label, vel, ang, quat, inv_mass, inv_inertia,
                                        island_energy)
        if m:
            soft_energy.body_energies(alone, vel, ang, quat, inv_mass, inv_inertia,
                                      start_energy)
            closing(ca, cb, n, sep, peak, arm, vel, ang, relv, gap, True)
            warm_start(start, ca, cb, n, t1, t2, inv_mass, vel, ang, impulse, jt1, jt2, jtw,
                       arm, farm)
            passes += soft_passes(start, ca, cb, n, t1, t2, fmu, radius, mass_n, mass_t1,
                                  mass_t2, mass_tw, sep, inv_mass, vel, ang, impulse, peak,
                                  jt1, jt2, jtw, arm, farm, inv_h, True,
                                  FRICTION_IN_SOLVE, soft, static, solve_passes, tolerance,
                                  relaxation)
            # friction within the solve's cone, in this pose (``soft_energy``)
            soft_energy.friction_cone(start, ca, cb, n, t1, t2, fmu, radius, mass_n, inv_mass,
                                      vel, ang, impulse, jt1, jt2, jtw, farm)
        bad = integrate_positions(pos, quat, vel, ang, inv_inertia, inv_i, h, awake)
        if bad >= 0:
            return passes, deepest, 2, bad
        if m:
            deepest = refresh(start, ca, cb, n, la, lb, r0a, r0b, depth0, mu, inv_mass, inv_i,
                              pos, quat, ra, rb, sep, mass_n, t1, t2, fa, fb, mass_t1, mass_t2,
                              mass_tw, radius, fmu, arm, farm, round_a, round_b, owner,
                              ln, reach, True)
            closing(ca, cb, n, sep, peak, arm, vel, ang, relv, gap, False)
            passes += soft_passes(start, ca, cb, n, t1, t2, fmu, radius, mass_n, mass_t1,
                                  mass_t2, mass_tw, sep, inv_mass, vel, ang, impulse, peak,
                                  jt1, jt2, jtw, arm, farm, inv_h, False, True,
                                  soft, static, relax_passes, tolerance, relaxation)
            soft_energy.limit_scenery(alone, start_energy, vel, ang, quat, inv_mass,
                                      inv_inertia)
            if islands:
                soft_energy.limit_islands(label, grounded, island_energy, pos, vel, ang, quat,
                                          inv_mass, inv_inertia)
            if bouncy:
                absorbed += begun - _kinetic_energy(vel, ang, quat, inv_mass, inv_inertia)
            for c in range(m):  # the substep's warm start and passes gave impulse[c] in all
                total[c] += impulse[c]
    if m:
        # the next step is warm started with what held the bodies, not with the bounce (as
        # ``step``'s loop: a bounce warm started on a point that now separates gained energy)
        held = impulse.copy()
        if bouncy:
            v0 = vel.copy()
            w0 = ang.copy()
            e0 = _kinetic_energy(vel, ang, quat, inv_mass, inv_inertia)
        restitution(start, ca, cb, n, e, along, approach, relv, gap, peak, mass_n, inv_mass,
                    vel, ang, impulse, arm, h, threshold, resting, relax_passes, tolerance)
        if bouncy:
            soft_energy.limit_bounce(e0, absorbed, v0, w0, held, vel, ang, impulse, quat,
                                     inv_mass, inv_inertia)
        for c in range(m):  # the bounce's own impulse
            total[c] += impulse[c] - held[c]
        impulse[:] = held
        bm.split_friction(start, n, t1, t2, jt1, jt2, jtw, kept)
    # the leapfrog: the step drifted with these; it leaves them synchronised (``close``)
    half_v[:] = vel[:nb]
    half_w[:] = ang[:nb]
    if _accelerated(gravity, force, torque):
        rows_v = vel[nb:].copy()  # particle rows are the particle stage's to report
        rows_w = ang[nb:].copy()
        bad = kick(nb, vel[:nb], ang[:nb], force, torque, start_pos, pos, turn, inv_mass[:nb],
                   inv_inertia[:nb], inv_i[:nb], lin_d, ang_d, gravity, 0.5 * h, awake[:nb],
                   acc[:nb], h)
        if bad >= 0:
            return passes, deepest, 1, bad
        if m:  # from half the last substep's impulses: the closing half kick's share
            end = 0.5 * impulse
            e1 = 0.5 * jt1
            e2 = 0.5 * jt2
            ew = 0.5 * jtw
            warm_start(start, ca, cb, n, t1, t2, inv_mass, vel, ang, end, e1, e2, ew, arm, farm)
            passes += soft_passes(start, ca, cb, n, t1, t2, fmu, radius, mass_n, mass_t1,
                                  mass_t2, mass_tw, sep, inv_mass, vel, ang, end, np.zeros(m),
                                  e1, e2, ew, arm, farm, inv_h, False, True, soft, static,
                                  relax_passes, tolerance, relaxation)
        vel[nb:] = rows_v
        ang[nb:] = rows_w
    bad = _first_blown(vel, ang)  # ``_refuse_blow_up``'s check, without a call of its own
    if bad >= 0:
        return passes, deepest, 3, bad
    keep_alive(start_pos_own, round_a_own, round_b_own, owner_own, ln_own, reach_own, start_own,
               la_own, lb_own, ra_own, rb_own, along_own, approach_own, relv_own, sep_own,
               mass_n_own, gap_own, peak_own, arm_own, t1_own, t2_own, fa_own, fb_own, fmu_own,
               radius_own, mass_t1_own, mass_t2_own, mass_tw_own, jt1_own, jt2_own, jtw_own,
               farm_own, turn_own, start_energy_own, label_own, grounded_own, none_own,
               island_energy_own)
    return passes, deepest, 0, -1



def _contact_step(v, b, c: BodyContacts, acceleration, history: ImpulseHistory, h: float,
                  threshold: float, gravity, st: SolverSettings, soft, static, out: SoftRows):
    """``step`` without joints: recall, ``contact_step``, keep."""
    impulse = np.empty(c.count)
    kept = np.empty((c.count, 3))
    if c.count:
        history.recall(c.key, impulse, kept)
    else:
        history.clear()
    passes, deepest, error, bad = contact_step(
        b.count, st.soft_substeps, h, gravity, soft, static, threshold, v.position,
        v.orientation, v.velocity, v.angular_velocity, v.inv_mass, v.inv_inertia,
        v.inv_inertia_world, v.awake, b.linear_damping, b.angular_damping, acceleration, c.a,
        c.b, c.normal, c.r_a, c.r_b, c.depth, c.friction, c.restitution, c.key, impulse, kept,
        v.shape, v.size, c.impulse, b.force, b.torque, st.soft_solve_passes,
        st.soft_relax_passes, st.soft_tolerance, st.soft_relaxation, b.half_velocity,
        b.half_spin)
    if error == 1:
        from ..rigid.step import spin_error
        raise spin_error(b, int(bad), h)
    if error == 2:
        raise FloatingPointError(
            f"body {bad} became non-finite (position {v.position[bad].tolist()}, velocity "
            f"{v.velocity[bad].tolist()})")
    out.velocity_passes = int(passes)
    out.deepest = float(deepest)
    if c.count:
        history.keep(c.key, impulse, kept)
    if error == 3:
        raise _blow_up_error(v, b.count, int(bad))
    return out


def step(view, bodies, contacts: BodyContacts, acceleration: np.ndarray,
         history: ImpulseHistory, dt: float, threshold: float, gravity: np.ndarray,
         joints=None, compiled: bool = True, forces=None,
         settings: SolverSettings | None = None) -> SoftRows:
    """The soft step over ``dt`` (module docstring) on ``view`` (the bodies, or the packed
    view of bodies and particles) with the tuning numbers of ``settings`` (``World.settings``;
    the defaults when None), whose first kick of dt/``settings.soft_substeps`` is already done
    (``body_stage.kick``): the later kicks give gravity, damping and the forces and torques in
    ``bodies.force`` / ``bodies.torque`` (the step's, found once), ``bodies`` the damping;
    ``acceleration`` (one row per view body) what forces
    alone give each one [m/s²] (for particle rows: their kick). Without joints the step is
    one compiled call (``contact_step``); ``compiled=False`` runs the same stages from Python,
    the loop that joints need (tests compare the two: the same bits).

    ``forces``, when the world has force generators (springs, buoyancy, aerodynamics: forces
    that depend on where the bodies are and how they move), is called before each later
    substep's kick: it finds ``bodies.force`` / ``bodies.torque`` again at the bodies' current
    state and returns what they give each body [m/s²]. Found once a step and spread over the
    substeps, a position-dependent force is not semi-implicit Euler at h: a spring's energy
    grew by (1 − (n+1)/2n)·(ω·dt)² each step (1.4 % a second for ω 4.5 rad/s at dt 1/500,
    n = 4). Found every substep it is, and a body the forces hold is still at rest every
    substep."""
    st = _DEFAULTS if settings is None else settings
    v = view
    c = contacts
    b = bodies
    nb = b.count
    substeps = st.soft_substeps
    h = dt / substeps
    inv_h = 1.0 / h
    soft, static = _softness_rows(h, st)
    out = SoftRows(c)
    jointed = joints is not None and len(joints) > 0
    if not jointed and compiled and forces is None:
        if not c.count and not v.awake.any():  # all asleep: no row, nothing moves
            history.clear()
            b.half_velocity[:] = v.velocity[:nb]
            b.half_spin[:] = v.angular_velocity[:nb]
            _refuse_blow_up(v, b.count)
            return out
        # the whole step in one compiled call (it checks what it leaves: ``_refuse_blow_up``)
        return _contact_step(v, b, c, acceleration, history, h, threshold, gravity, st, soft,
                             static, out)
    r = _Rows(c)
    awake = v.awake
    if c.count:
        round_rows(v.shape, c.a, c.b, r.round_a, r.round_b)
        anchor(c.a, c.b, c.normal, c.r_a, c.r_b, v.orientation, v.inv_mass,
               v.inv_inertia_world, v.velocity, v.angular_velocity, acceleration, r.la, r.lb,
               r.along, r.approach, r.relv)
        normals(r.start, c.a, c.b, c.normal, c.r_a, c.r_b, c.depth, v.orientation, r.round_a,
                r.round_b, r.owner, r.ln, r.reach, v.size, c.key)
        kept = np.empty((c.count, 3))
        history.recall(c.key, r.impulse, kept)
        resting = r.impulse > 0.0  # pushing last step: not an impact
        _refresh(v, c, r)
        bm.gather_friction(r.start, c.normal, r.t1, r.t2, r.fmu, r.radius, r.mass_tw, kept,
                           r.jt1, r.jt2, r.jtw)
    else:
        history.clear()
    passes = 0
    total = np.zeros(c.count)  # each point's impulse over the step (``BodyContacts.impulse``)
    jr = joint_soft.prepare(v, joints, h, st) if jointed else None
    start_pos = v.position[:nb].copy()  # where the forces were found (``kick``)
    turn = np.empty((nb, 3))
    # restitution returns at most what the substeps' contacts (and joints) absorbed
    # (``soft_energy``), counted where a point can bounce
    bouncy = c.count and bool((c.restitution > 0.0).any())
    budget = soft_energy.Budget() if bouncy else None
    # a body on scenery alone leaves no substep with more energy than it began with
    alone = None
    count = v.velocity.shape[0]
    if c.count:
        alone = soft_energy.scenery_only(count, c.a, c.b)
        start_energy = np.zeros(count)
    # ... nor does an island of bodies that joints or contacts link (``soft_energy``)
    islands = 0
    if c.count or jointed:
        label = np.empty(count, np.int64)
        grounded = np.empty(count, np.bool_)
        none = np.empty(0, np.int64)
        ja_a, ja_b = (joints.arrays().a, joints.arrays().b) if jointed else (none, none)
        islands = soft_energy.islands(count, ja_a, ja_b, c.a, c.b, v.inv_mass,
                                      alone if alone is not None else np.zeros(count, np.bool_),
                                      label, grounded)
        grounded = grounded[:islands]
        island_energy = np.zeros(islands)
        if alone is not None:
            alone &= label < 0

    for i in range(substeps):
        if i > 0 and forces is not None:  # found again where the bodies are now
            acceleration[:nb] = forces()
            start_pos[:] = v.position[:nb]
        if i > 0:
            bad = kick(nb, v.velocity, v.angular_velocity, b.force, b.torque, start_pos,
                       v.position, turn, v.inv_mass, v.inv_inertia, v.inv_inertia_world,
                       b.linear_damping, b.angular_damping, gravity, h, awake, acceleration)
            if bad >= 0:
                from ..rigid.step import spin_error
                raise spin_error(b, int(bad), h)
        if budget is not None:
            budget.begin(v)
        if islands:
            soft_energy.island_energies(label, v.velocity, v.angular_velocity, v.orientation,
                                        v.inv_mass, v.inv_inertia, island_energy)
        if c.count:  # the restitution's v₀, before any warm start (``closing``)
            closing(c.a, c.b, c.normal, r.sep, r.peak, r.arm, v.velocity, v.angular_velocity,
                    r.relv, r.gap, True)
        if jointed:  # (``joint_soft``: Box2D's joint stages, the tree solved exactly)
            joint_soft.warm_start(v, joints, jr)
        if alone is not None:
            soft_energy.body_energies(alone, v.velocity, v.angular_velocity, v.orientation,
                                      v.inv_mass, v.inv_inertia, start_energy)
        if c.count:
            warm_start(r.start, c.a, c.b, c.normal, r.t1, r.t2, v.inv_mass, v.velocity,
                       v.angular_velocity, r.impulse, r.jt1, r.jt2, r.jtw, r.arm, r.farm)
            passes += _pass(v, c, r, inv_h, True, soft, static, st, st.soft_solve_passes)
        if c.count:  # friction within the solve's cone, in this pose (``soft_energy``),
            # before the joints' solve, so the velocity it takes back is one they see
            soft_energy.friction_cone(r.start, c.a, c.b, c.normal, r.t1, r.t2, r.fmu, r.radius,
                                      r.mass_n, v.inv_mass, v.velocity, v.angular_velocity,
                                      r.impulse, r.jt1, r.jt2, r.jtw, r.farm)
        if jointed:
            joint_friction.apply(v, joints, h)  # (Box2D's order: a joint's friction first)
            passes += _joint_solve(v, c, r, c.count > 0, joints, jr, False, inv_h, soft,
                                   static, st)
        bad = integrate_positions(v.position, v.orientation, v.velocity, v.angular_velocity,
                                  v.inv_inertia, v.inv_inertia_world, h, awake)
        if bad >= 0:
            raise FloatingPointError(
                f"body {bad} became non-finite (position {v.position[bad].tolist()}, velocity "
                f"{v.velocity[bad].tolist()})")
        if jointed:  # the rows in the pose the drift left: the relax's and the next solve's
            jr = joint_soft.prepare(v, joints, h, st)
            joint_soft.recall(joints, jr)
        if c.count:
            out.deepest = _refresh(v, c, r, True)
            closing(c.a, c.b, c.normal, r.sep, r.peak, r.arm, v.velocity, v.angular_velocity,
                    r.relv, r.gap, False)
            passes += _pass(v, c, r, inv_h, False, soft, static, st, st.soft_relax_passes)
            if alone is not None:
                soft_energy.limit_scenery(alone, start_energy, v.velocity, v.angular_velocity,
                                          v.orientation, v.inv_mass, v.inv_inertia)
        if jointed:
            passes += _joint_solve(v, c, r, c.count > 0, joints, jr, True, inv_h, soft,
                                   static, st)
        if islands:
            soft_energy.limit_islands(label, grounded, island_energy, v.position, v.velocity,
                                      v.angular_velocity, v.orientation, v.inv_mass,
                                      v.inv_inertia)
        if budget is not None and c.count:
            budget.relaxed(v)
        if c.count:  # the substep's warm start and passes gave r.impulse in all
            total += r.impulse
    if c.count:
        def bounce() -> None:
            restitution(r.start, c.a, c.b, c.normal, c.restitution, r.along, r.approach,
                        r.relv, r.gap, r.peak, r.mass_n, v.inv_mass, v.velocity,
                        v.angular_velocity, r.impulse, r.arm, h, threshold, resting,
                        st.soft_relax_passes, st.soft_tolerance)

        # the next step is warm started with what held the bodies, not with the bounce: a
        # bounce's impulse warm started on a point that now separates is velocity the next
        # solve must take back (it did not, fully: energy gained in force-free scenes)
        held = r.impulse.copy()
        if budget is not None:
            budget.bounce(v, r.impulse, bounce)
        else:
            bounce()
        total += r.impulse - held  # and the bounce's own
        r.impulse[:] = held
    passes += _close(v, b, c, r, joints if jointed else None, jr, acceleration, start_pos,
                     turn, gravity, h, st, soft, static)
    out.velocity_passes = passes
    if c.count:
        c.impulse[:] = total
        kept = np.empty((c.count, 3))
        bm.split_friction(r.start, c.normal, r.t1, r.t2, r.jt1, r.jt2, r.jtw, kept)
        history.keep(c.key, r.impulse, kept)
    _refuse_blow_up(v, nb)
    return out


def _close(v, b, c: BodyContacts, r: _Rows, joints, jr, acceleration, start_pos, turn,
           gravity, h: float, st: SolverSettings, soft, static) -> int:
    """The leapfrog's end of the step, as ``contact_step``'s (module docstring, "Leapfrog"):
    the bodies' half-step velocities kept (``Bodies.half_velocity``, ``half_spin``), then,
    where anything accelerates them, the closing half kick (with the last substep's forces)
    and the velocities projected on the rows: the contacts' relax passes from half the last
    substep's impulses (the half kick's share; their sum stays ≥ 0, so a bounce is not taken
    back) and the joints' relax. The particle rows, the
    joints' warm start and the contacts' impulses are left as the step left them. Returns
    the passes run."""
    nb = b.count
    b.half_velocity[:] = v.velocity[:nb]
    b.half_spin[:] = v.angular_velocity[:nb]
    if not _accelerated(gravity, b.force, b.torque):
        return 0
    # the forces of the last substep (a generator found again here would count its time
    # twice: an explosion's age): the half kick's error is then O(h²), as leapfrog's own
    rows_v, rows_w = v.velocity[nb:].copy(), v.angular_velocity[nb:].copy()
    bad = kick(nb, v.velocity[:nb], v.angular_velocity[:nb], b.force, b.torque, start_pos,
               v.position, turn, v.inv_mass[:nb], v.inv_inertia[:nb],
               v.inv_inertia_world[:nb], b.linear_damping, b.angular_damping, gravity, 0.5 * h,
               v.awake[:nb], acceleration[:nb], h)
    if bad >= 0:
        from ..rigid.step import spin_error
        raise spin_error(b, int(bad), h)
    passes = 0
    inv_h = 1.0 / h
    end = None
    if c.count:
        end = copy.copy(r)  # the rows, with accumulators of their own: from half the last
        # substep's impulses (the closing half kick's share)
        end.impulse, end.peak = 0.5 * r.impulse, np.zeros(c.count)
        end.jt1, end.jt2, end.jtw = 0.5 * r.jt1, 0.5 * r.jt2, 0.5 * r.jtw
        warm_start(r.start, c.a, c.b, c.normal, r.t1, r.t2, v.inv_mass, v.velocity,
                   v.angular_velocity, end.impulse, end.jt1, end.jt2, end.jtw, r.arm, r.farm)
        passes += _pass(v, c, end, inv_h, False, soft, static, st, st.soft_relax_passes)
    if joints is not None:
        point, turned = joints.point.copy(), joints.turn.copy()
        passes += _joint_solve(v, c, r if end is None else end, end is not None, joints, jr,
                               True, inv_h, soft, static, st)
        joints.point[:], joints.turn[:] = point, turned  # the next step's warm start
    v.velocity[nb:], v.angular_velocity[nb:] = rows_v, rows_w
    return passes


@njit(cache=True, nogil=True)
def _first_blown(vel, ang):
    """The first row whose |v|² or |ω|² is not a finite number (NaN, or too large to square:
    its energy is), or -1."""
    for i in range(vel.shape[0]):
        v = vel[i, 0] * vel[i, 0] + vel[i, 1] * vel[i, 1] + vel[i, 2] * vel[i, 2]
        w = ang[i, 0] * ang[i, 0] + ang[i, 1] * ang[i, 1] + ang[i, 2] * ang[i, 2]
        if not (math.isfinite(v) and math.isfinite(w)):
            return i
    return -1


def _refuse_blow_up(v, nb: int) -> None:
    """Raise ``FloatingPointError`` naming the body (or particle row) whose velocity the step
    left non-finite or too large to square: the kicks check the spins and the drifts the
    positions, but the relax and the restitution come after the last of them (a random
    jointed scene, seed 196, left 1e158 rad/s in its first step that only the next step's
    kick caught)."""
    bad = int(_first_blown(v.velocity, v.angular_velocity))
    if bad >= 0:
        raise _blow_up_error(v, nb, bad)


def _blow_up_error(v, nb: int, bad: int) -> FloatingPointError:
    """``_refuse_blow_up``'s error for row ``bad`` of the view."""
    if bad < nb:
        what = f"body {bad}"
    else:  # a particle touching a body: the packed view's row of it
        what = f"particle {int(v.selected[bad - nb])}"
    return FloatingPointError(
        f"{what} was left with a velocity that is not finite or too large to square by the "
        f"soft step (velocity {v.velocity[bad].tolist()} m/s, angular velocity "
        f"{v.angular_velocity[bad].tolist()} rad/s): a blow-up")
