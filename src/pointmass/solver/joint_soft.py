"""The joints in the soft step (``body_soft``), as Box2D v3 solves them (``src/solver.c``,
``src/joint.c`` ``b2PrepareJoint``, ``src/revolute_joint.c``): each substep, after the kick,

1. warm start — the impulse each joint needed last substep is applied again (the point
   block's and the angular rows', seen along this pose's axes), scaled to be no worse a
   start than none (below);
2. solve — the rows with a soft position bias: Ċ = −b·C, C the joint's gap and angles in the
   bodies' current pose, b the bias rate of a spring of ``joint_hertz`` and damping ratio
   ``joint_damping_ratio`` (``SolverSettings`` fields, ``World.settings``) solved implicitly
   over the substep (``body_soft.softness``);
3. (the drift, ``body_soft``);
4. relax — the rows again in the pose the drift left, without the bias (Ċ = 0, rigid): the
   velocity the bias made to close a gap is taken back, so a gap is closed by moving the
   bodies, not by launching them. An open limit stays speculative in both (it may close by its
   angle within the substep, no more).

There is no projection after the substeps (Box2D v3 has none): it moved bodies without their
velocities. What each pass solves is ``joint_solver.velocity_pass`` (the passes: one compiled
call a stage, ``body_soft.joint_passes``):

- the point blocks of a forest of joints (``joint_tree`` DIRECT: chains, ragdolls, pendulums;
  chosen by the graph's structure) exactly, all at once, each joint aimed at closing the gap
  the pose the substep ends in would leave (``joint_predict``; repeated passes are Newton's
  method, SHAKE; with the relax in the pose after the drift, RATTLE). Aimed so, a tree's
  joints end each substep shut (< 0.1 µm in the pendulums of tests/physics/rigid/
  test_joint_accuracy.py) and the energy swings as the substeps' leapfrog (``body_soft``)
  swings the exact pendulum in its angle (0.0035 % of m·g·L at h = 1/240; measured 0.0063 %;
  semi-implicit Euler's ±0.57 % before stop 42): the joints add next to nothing to it.
  Where a pass leaves more to do than the one before (a lever arm that turns through a large
  angle in a substep, joints that contradict one another) the substep falls back to the bias;
- the point blocks of the joints that close a loop of the tree (a rope bridge's second
  anchor, a ring's last joint), through the tree (``joint_loops``) as rigid rows aimed at
  closing their gap within the substep (Ċ = −C/h, no faster than the push-out speed), as
  the angular rows below are, rigid (Ċ = 0) in the relax ("Loops" below);
- the angular rows (a hinge's locks, the limits) of the tree's joints, through the tree
  (``joint_loops.row_solve``) as rigid rows aimed at closing their angle within the substep
  (Ċ = −C/h; an open limit stays speculative), each exact given the tree and the others,
  rigid in the relax too ("Angular rows" below);
- the point blocks of the joints that the tree cannot take, and their angular rows, by
  Gauss–Seidel, soft in the solve (the spring's mass and impulse scales: Box2D's rows).
  Among these are the loops that join a pair of bodies a tree joint
  already joins (``joint_tree.unpair``: a ball and a hinge on one pair, two hinges): two
  point blocks on one pair are redundant by structure, their mass through the tree singular
  along the line between them and near singular wherever either is open, and solved through
  the tree they threw random jointed scenes (benchmarks/rigid_fuzz.py) to 1e11 … 1e30 m/s
  (rigid) or 6.7e3 m/s where Gauss–Seidel keeps 46 m/s (soft rows through the tree, seed
  123); a soft row on its own bodies only pulls.

A bias closes a gap at the contacts' push-out speed (``SolverSettings.contact_speed``, Box2D's
``contactSpeed``) at most: a joint made 0.5 m open is pulled shut, not thrown shut.

What keeps random jointed scenes from exploding (benchmarks/rigid_fuzz.py, seeds 0–199, 300
steps, the soft step, 143 jointed scenes: 11 exploded before, > 1e4 m/s without
an error, 6 in 0–99 and 5 in 100–199; now 0). Most of those held a light body by two joints to
one other body (a ball and a hinge, two hinges on different axes: over-constrained) at arms of
4–9 m, with mass ratios to 1e5. Measured, each of three things threw them, and each is now
made so that it cannot add what the solve does not ask for:

- The warm start. The Gauss–Seidel rows of an over-constrained set keep a self-stress, an
  impulse that moves nothing in the pose it was found in; replayed in the next substep's
  turned pose it kicks the bodies (seed 53: 7e4 J to 3.7e6 J in one warm start), and the
  passes, capped, could not take it back. A warm start is only a first guess of the soft
  solve, whose converged result does not depend on it: the soft rows minimise
  F(λ) = ½·λᵀ(A + Γ)λ − λᵀ(t − J·v) (Gauss–Seidel with Box2D's mass and impulse scales
  is exact coordinate descent on it, Γ the springs' compliance), so the kept impulses are
  applied scaled by the α ∈ [0, 1] that minimises F along them (``warm_scale``; 1 where
  last substep's solution still holds):
  never a worse start than none, and every pass after it only lowers F. With F ≤ 0 the
  solve leaves at most the kinetic energy it began with plus ½·tᵀΓ⁻¹t, what the springs'
  bias can give.
- The geometric stiffness of the tree solve (``joint_solver.GEOMETRIC``, for one step of
  dt): off here (``GEOMETRIC``). It solves the tree's joints with a stiffened inertia while
  the angular rows, the loops and the contacts on the same bodies use the true one, so a
  pass is no longer a descent step of one objective (seed 196: 1e158 rad/s in the first
  step). At h = dt/4 the alignment mode it was for (a 50-box chain's top links at ω·dt ≈ 2.5)
  has ω·h < 1, where it added nothing anyway.
- The aim at the end pose: Newton's first step is not bounded (a long arm turning fast in a
  substep; with the two above fixed, seeds 53 and 77 still passed 1e4 m/s). The part of its
  target that closes the gap the joint has now is capped at the push-out speed, as the bias
  is (``JointRows.speed``): a joint open by more is closed over several substeps, not thrown
  shut. The rest, the sagitta's rate that keeps a turning arm's joint point on its arc, is
  not capped: capped with it, a ball whirled on a 5 m arm at 20 rad/s (½·ω²·L·h = 4.2 m/s)
  opened its joint a little more every substep (12.5 cm, half its energy lost in 10 s), and
  light bodies on long arms in random scenes tore their joints by metres
  (``joint_predict.end_targets``; tests/physics/rigid/test_joint_whirl.py).

Seeds 33 and 53 reached 4.8e3 and 4.2e3 m/s then (1.4 g and 2 g boxes spun by their over-
constrained pairs), the others ≤ 540 m/s. The joint stages add energy of their own, O((ω·h)²)
a substep (the aim at the end pose relaxed at another pose's arms and inertia):
``soft_energy.limit_islands`` takes it back off each island a joint holds (of the 61 force-
free jointed scenes, 47 gained in a step, 15 by > 1e-3; none now). Measured now, seeds 0–199,
143 jointed scenes, 300 steps: 0 explosions, fastest 2.2e3 m/s (seed 53), 9 end a step with
an overlap > 2 cm.

Angular rows. As Box2D's soft rows (sprung at ``joint_hertz`` with their own two bones'
inertia, Gauss–Seidel beside the tree) a ragdoll's locks and limits gave under the loads that
reach them through contacts and the tree: an elbow's lock under the torso lying on the arm
carried 14 N·m on a spring of I·ω² = 347 N·m/rad and rested 2.35° off its axis (seed 1);
seeds 1, 4, 5 rested 2.35°, 2.98°, 0.71° past their stops (gate 0.5°) and swung to 4.35°,
4.11°, 3.32° in the fall (gate 3°). A spring's give under a load is the load over its
stiffness, so no hertz holds every load; sprung with the tree's mass (S⁻¹, as the loops were)
the elbow's spring hardly changed (the load is local) and seeds 1, 4 rested 4.2°, 1.8°.
Rigid, a row's give is none whatever the load: the row aims at Ċ = −C/h, so the drift
closes the angle, and the relax (Ċ = 0) takes back the velocity that closed it, as the
tree's point blocks aimed at the end pose do. Rigid rows by Gauss–Seidel on their own two
bones did not converge against the tree (in the fall 5.5°, 2.0°, 0.9°, 5.4°, 5.1°, before
``soft_energy.limit_islands``); through the tree each row is exact given the others, and the
ragdoll's seeds 0–19 rest within 0.1° and fall within 1.7° (``tests/physics/rigid/
test_joint_limits_soft.py``).

Loops. A soft row's spring holds a load F with a gap: with its own two bodies' mass (Box2D's
row, K⁻¹) K·F/ω², so the 50-plank rope bridge's second anchor (tests/physics/rigid/
test_joint_chains.py), holding the weight of the bridge with the spring of one plank, opened
2.749 mm; sprung with the mass the tree shows it (S⁻¹, S its mobility through the tree)
S·F/ω², 0.085 mm. Rigid, a row's give is none whatever the load: aimed at Ċ = −C/h through
the tree (each pass exact given the tree), the drift closes the gap and the relax takes back
the velocity that closed it, and the bridge stays within 3.5e-7 m (600 steps). Aimed at the
pose the substep ends in, as the tree's joints are (``joint_predict``), it
stayed within 1.5e-10 m, but in random loops (rings and chains anchored at both ends, 2–6
bodies of 1 g–10 t, 60 scenes of 200 steps) one threw a body 4e18 m within a substep: a
four-bar held by a hinge's rigid rows and the loop's near its toggle pose, where the end-pose
targets, found again every pass, ran away before a pass could fall back to the bias. Aimed at
−C/h, a target fixed for the substep, no scene did (largest gap 21 m against 10 m with the
soft rows, in scenes whose joints tear either way; half the scenes end with their gaps < 0.07 m
against 0.11 m). A loop on a pair of bodies that a tree joint already joins is left to the soft
Gauss–Seidel rows (above).

Why the relax pass needs the pose after the drift. A pendulum turning at ω: the drift carries
the bob along the tangent of the pose the substep started in, so the joint opens by the
sagitta ½(ω·h)²·L; the bias then pulls the bob in at about ½ω²·L·h, and in the relax pass,
seen from the turned arm, that inward velocity has a tangential part that gives back what
making the velocity tangent to the new arm takes (ω·h)² of the energy a substep. Relaxed
along the old arm instead, the pendulum loses that energy every substep.
"""

from __future__ import annotations

import copy
import math
from dataclasses import dataclass

import numpy as np
from numba import njit

from ..rigid.joint_rows import LIMIT, OFF
from . import joint_solver
from .joint_tree import DIRECT as DIRECT_JOINT
from .joint_tree import LOOP as LOOP_JOINT
from .joint_tree import OFF as OFF_JOINT
from .settings import SolverSettings

_DEFAULTS = SolverSettings()  # the entry points' settings when none are given

# The joints' tuning numbers (the bias's hertz, damping ratio and cap, the passes and their
# tolerance) are ``SolverSettings`` fields (Box2D v3's ``constraintHertz`` 60,
# ``constraintDampingRatio`` 2, the hertz capped at a quarter of the substep rate), read from
# the ``settings`` each entry point is given.

#: Whether the tree solve stiffens the inertia by the joints' tension (``joint_solver``): a
#: choice of method, not a tuning number: off, as the module docstring says why (with it,
#: random jointed seed 196 reached 1e158 rad/s in its first step; without it the 50-plank
#: bridge kept its 2.749 mm gap, the pendulum tests their figures, and a 20-box chain released
#: level whips to 12.4 mm, 13.6 mm with it).
GEOMETRIC = False


@dataclass
class SoftJointRows:
    """One pose's joint rows, as the solve (soft bias) and as the relax pass (no bias) read
    them: both share the arms, masses, the tree's factors and the accumulated impulses."""

    solve: joint_solver.JointRows
    relax: joint_solver.JointRows
    #: The solve's targets of the point blocks before any aiming (Ċ = −b·C), to fall back on.
    bias: np.ndarray


def softness(h: float, settings: SolverSettings = _DEFAULTS) -> tuple[float, float, float]:
    """(bias rate [1/s], mass scale, impulse scale) of the joints' spring over a substep h."""
    from .body_soft import softness as make_soft  # (body_soft imports this module)

    hertz = min(settings.joint_hertz, settings.joint_hertz_cap / h)
    return make_soft(hertz, settings.joint_damping_ratio, h)


def prepare(view, joints, h: float, settings: SolverSettings = _DEFAULTS) -> SoftJointRows:
    """The joints' rows in the bodies' pose now (arms, masses, axes, limits, the tree's
    factors), targets for the solve (Ċ = −b·C) and for the relax pass (0), with the tuning
    numbers of ``settings`` (``World.settings``)."""
    rate, mass_scale, impulse_scale = softness(h, settings)
    rows = joint_solver.prepare(view, joints, h, beta=rate * h, loops=True,
                                geometric=GEOMETRIC, pairs=False, rows_through=True)
    rows.mass_scale = mass_scale
    rows.impulse_scale = impulse_scale
    rows.aim_loops = False
    speed = settings.contact_speed
    rows.speed = speed  # a gap is closed at the push-out speed at most, and so is the aim
    relax = copy.copy(rows)  # (sharing the arms, masses, the tree and the accumulators)
    relax.target = np.empty_like(rows.target)
    _soften(rows.mode, rows.row, rows.through, rows.bias, rows.target, relax.target, rate * h,
            speed)
    relax.bias = np.zeros_like(rows.bias)
    relax.mass_scale, relax.impulse_scale, relax.predict = 1.0, 0.0, False
    return SoftJointRows(rows, relax, rows.bias.copy())


@njit(cache=True, nogil=True)
def _soften(mode, row, through, bias, target, relax_target, rate_h, speed):
    """The soft rows' targets from the Baumgarte ones ``joint_solver.prepare`` set with
    β = ``rate_h`` (the bias rate × h), in place, and the relax pass's into ``relax_target``:

    - the loops: rigid rows through the tree, aimed at closing their gap within the substep
      (Ċ = −C/h, as the angular rows below; module docstring, "Loops");
    - a gap is closed at the contacts' push-out speed ``speed`` at most (Box2D's
      ``contactSpeed``);
    - the angular rows of the tree's joints: rigid through the tree, aimed at closing their
      angle within the substep (module docstring, "Angular rows");
    - relax: no bias; a limit still open keeps its speculative target (≤ 0), a violated one
      (target > 0) and every equality row aim at Ċ = 0."""
    for j in range(bias.shape[0]):
        if mode[j] == LOOP_JOINT:
            for k in range(3):
                bias[j, k] /= rate_h
        size = math.sqrt(bias[j, 0] * bias[j, 0] + bias[j, 1] * bias[j, 1]
                         + bias[j, 2] * bias[j, 2])
        scale = min(1.0, speed / max(size, 1e-300))
        for k in range(3):
            bias[j, k] *= scale
        for s in range(3):
            limit = row[j, s] == LIMIT
            if through[j, s] and not (limit and target[j, s] <= 0.0):
                target[j, s] /= rate_h
            relax_target[j, s] = target[j, s] if limit and target[j, s] < 0.0 else 0.0


def warm_start(view, joints, rows: SoftJointRows) -> float:
    """Apply the impulses the joints needed last substep (``joints.point``, ``joints.turn``),
    scaled by the α ∈ [0, 1] that best starts the solve (``warm_scale``); returns α."""
    j = joints.arrays()
    r = rows.solve
    alpha = float(warm_scale(j.a, j.b, r.ra, r.rb, r.axis, r.row, r.mode, r.kmat, r.mass,
                             r.target, r.bias, view.inv_mass, view.inv_inertia_world,
                             view.velocity, view.angular_velocity, joints.point, joints.turn,
                             r.impulse_scale / r.mass_scale, r.through))
    joint_solver.warm_start(view, joints, r)
    return alpha


@njit(cache=True, nogil=True)
def warm_scale(ja, jb, ra, rb, axis, row, mode, kmat, mass, target, bias, inv_mass, inv_i,
               vel, ang, point, turn, soft, rigid):
    """Scale the kept impulses λ (``point`` of the Gauss–Seidel joints, every ``turn``) in
    place by the α ∈ [0, 1] that minimises the soft solve's objective along them,
    F(α·λ) = ½α²·λᵀ(A + Γ)λ − α·λᵀ(t − J·v), and return α (module docstring, "The warm
    start"). A = J·M⁻¹·Jᵀ, Γ = ``soft``·diag(A) the soft rows' compliance (an open limit is
    rigid, and so is a row marked ``rigid`` (J, 3): solved through the tree), t their targets,
    v the velocities now. A DIRECT joint's point block is not warm started
    (``joint_stages.warm_start``) and takes no part."""
    n = vel.shape[0]
    load = np.zeros((n, 6))  # per body: the impulse and the angular impulse λ applies
    aim = 0.0  # λᵀt
    compliance = 0.0  # λᵀΓλ
    for j in range(ja.shape[0]):
        if mode[j] == OFF_JOINT:
            continue
        a = ja[j]
        b = jb[j]
        if mode[j] < DIRECT_JOINT:
            px, py, pz = point[j, 0], point[j, 1], point[j, 2]
            _load(load, b, 1.0, rb[j, 0], rb[j, 1], rb[j, 2], px, py, pz)
            _load(load, a, -1.0, ra[j, 0], ra[j, 1], ra[j, 2], px, py, pz)
            aim += px * bias[j, 0] + py * bias[j, 1] + pz * bias[j, 2]
            k = kmat[j]
            compliance += soft * (px * (k[0, 0] * px + k[0, 1] * py + k[0, 2] * pz)
                                  + py * (k[1, 0] * px + k[1, 1] * py + k[1, 2] * pz)
                                  + pz * (k[2, 0] * px + k[2, 1] * py + k[2, 2] * pz))
        for s in range(3):
            if row[j, s] == OFF:
                continue
            ux, uy, uz = axis[j, s, 0], axis[j, s, 1], axis[j, s, 2]
            x = turn[j, s, 0] * ux + turn[j, s, 1] * uy + turn[j, s, 2] * uz
            if row[j, s] == LIMIT and x < 0.0:
                x = 0.0
            for side in range(2):
                i = b if side == 0 else a
                if i >= 0:
                    sign = 1.0 if side == 0 else -1.0
                    load[i, 3] += sign * x * ux
                    load[i, 4] += sign * x * uy
                    load[i, 5] += sign * x * uz
            aim += x * target[j, s]
            if not (rigid[j, s] or (row[j, s] == LIMIT and target[j, s] <= 0.0)):
                compliance += soft * x * x / mass[j, s]
    square = 0.0  # λᵀAλ
    along = 0.0  # λᵀJ·v
    for i in range(n):
        w = inv_mass[i]
        for k in range(3):
            square += w * load[i, k] * load[i, k]
            along += load[i, k] * vel[i, k] + load[i, 3 + k] * ang[i, k]
            for m in range(3):
                square += load[i, 3 + k] * inv_i[i, k, m] * load[i, 3 + m]
    total = square + compliance
    if not total > 0.0:
        return 1.0
    alpha = min(1.0, max(0.0, (aim - along) / total))
    if alpha < 1.0:
        for j in range(ja.shape[0]):
            if mode[j] == OFF_JOINT:
                continue
            for k in range(3):
                if mode[j] < DIRECT_JOINT:
                    point[j, k] *= alpha
                for s in range(3):
                    turn[j, s, k] *= alpha
    return alpha


@njit(cache=True, inline="always")
def _load(load, i, sign, rx, ry, rz, px, py, pz):
    """Body i (i < 0: the world, nothing) takes sign·P at arm r."""
    if i < 0:
        return
    load[i, 0] += sign * px
    load[i, 1] += sign * py
    load[i, 2] += sign * pz
    load[i, 3] += sign * (ry * pz - rz * py)
    load[i, 4] += sign * (rz * px - rx * pz)
    load[i, 5] += sign * (rx * py - ry * px)


def recall(joints, rows: SoftJointRows) -> None:
    """Take the angular impulses kept (``joints.turn``) as this pose's accumulated ones
    without applying them again (the relax pass goes on from what the solve reached)."""
    _recall(joints.turn, rows.solve.axis, rows.solve.row, rows.solve.mode, rows.solve.lam)


@njit(cache=True, nogil=True)
def _recall(turn, axis, row, mode, lam):
    for j in range(axis.shape[0]):
        for s in range(3):
            x = 0.0
            if mode[j] != OFF_JOINT and row[j, s] != OFF:
                x = (turn[j, s, 0] * axis[j, s, 0] + turn[j, s, 1] * axis[j, s, 1]
                     + turn[j, s, 2] * axis[j, s, 2])
                if row[j, s] == LIMIT and x < 0.0:
                    x = 0.0
            lam[j, s] = x
