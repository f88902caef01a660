"""The joints' rows for the soft step (``joint_soft``): prepare and warm start, one velocity
pass, and keeping the impulses; the kernels are in ``joint_stages`` (the
angular rows, and the point blocks of the joints the tree solve does not take) and
``joint_direct`` (the point blocks of a forest of joints, solved exactly each pass;
``joint_tree`` picks them)."""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ..rigid.joint_rows import LIMIT
from . import joint_direct as jd
from . import joint_loops as jl
from . import joint_predict
from . import joint_stages as js
from . import joint_tree as jt

#: Fraction of a joint's position error C (what it had at the start of the step, e.g. left
#: by rows in conflict) removed per step (``joint_predict``: the step's own opening is closed
#: whole); also the Baumgarte rate Ċ = −β·C/dt of the rows ``prepare`` sets, which the energy
#: guard's redo uses. Measured (a jointed pair tumbling 10 s at 2 rad/s, no
#: gravity, dt 1/60): |ΔL|/|L| 2.4 % at β 0.1, 0.68 % at 0.2, 0.13 % at 0.5, 0.06 % at 0.8;
#: the pendulum's period and energy band do not change with β.
BETA = 0.5
#: Whether the point blocks of the joints that form a forest are solved exactly
#: (``joint_direct``) rather than by Gauss–Seidel. Off, a 50-box chain at the defaults blew
#: up (30 passes leave it unconverged and the bias feeds the error: +18 kJ in 1 s); on, it
#: hangs with its joints < 1 µm apart in one pass a step. A switch for benchmarks and tests.
DIRECT = True
#: Whether the tree solve adds the tension's geometric stiffness to the bodies' inertia
#: (``joint_direct.geometric``). Off, a 50-box chain released 5° off the vertical had its top
#: links spin up to 30 rad/s within 0.3 s (their alignment mode under 490 N has ω·dt ≈ 2.5,
#: beyond symplectic Euler's 2), its joints 6.5 mm apart; on: 0.16 mm, no spin.
GEOMETRIC = True


@dataclass
class JointRows:
    """One substep's rows of the joints (J joints): arms [m] (J, 3), K (J, 3, 3), per angular
    slot the axis (J, 3, 3), mass, target [rad/s], type and accumulated impulse (J, 3)."""

    ra: np.ndarray
    rb: np.ndarray
    kmat: np.ndarray
    bias: np.ndarray
    axis: np.ndarray
    mass: np.ndarray
    target: np.ndarray
    row: np.ndarray
    lam: np.ndarray
    #: Per joint ``joint_tree.OFF``, ``ITERATIVE``, ``DIRECT`` or ``LOOP`` (J,), and the
    #: forest: its nodes in postorder, each one's parent position, the count, the factors,
    #: the LOOP joints, each body's node position (−1: none) and the loops' S⁻¹.
    mode: np.ndarray
    tree: tuple
    #: The step [s], and whether each pass aims at the predicted end pose
    #: (``joint_predict``); False: the targets ``prepare`` set stay (the energy guard's redo).
    dt: float = 0.0
    predict: bool = True
    #: What a step may leave of each joint's gap now (J, 3): (1 − β)·C (``joint_predict``).
    keep: np.ndarray | None = None
    #: Box2D's soft rows (``joint_soft``) for the Gauss–Seidel rows whose target carries a
    #: position bias: the impulse is mass_scale·(the rigid row's) − impulse_scale·(what the
    #: row has accumulated). 1 and 0: rigid rows (``prepare``'s, and every relax pass).
    mass_scale: float = 1.0
    impulse_scale: float = 0.0
    #: Fastest relative velocity [m/s] a point block's aimed target may ask for (the soft
    #: step's push-out cap, ``joint_soft``); inf: no cap (``prepare``'s).
    speed: float = math.inf
    #: Whether the LOOP joints' point blocks aim at the end pose (``joint_predict``) as the
    #: tree's do (``prepare``'s), or keep the targets ``bias`` holds (``joint_soft``:
    #: Ċ = −C/h). Rigid rows through the tree either way (``joint_loops.solve``).
    aim_loops: bool = True
    #: Per angular row (J, 3): whether it is solved through the tree as a rigid row
    #: (``joint_loops.row_solve``; ``mass`` then the tree's) rather than by Gauss–Seidel on
    #: its own two bodies (``joint_soft``: the soft step's rows of the tree's joints).
    through: np.ndarray | None = None


def prepare(bodies, joints, dt: float, beta: float = BETA, loops: bool = True,
            geometric: bool | None = None, pairs: bool = True,
            rows_through: bool = False) -> JointRows:
    """The rows of ``joints`` (a ``rigid.joint_set.Joints``) in the bodies' current pose, their
    targets Ċ = −β·C/dt (``beta``: the fraction of a position error taken back in dt);
    ``loops`` False leaves the joints that close a loop of a tree to Gauss–Seidel, ``pairs``
    False only those that close it on a pair of bodies a tree joint already joins
    (``joint_tree.unpair``); ``geometric``: whether the tree solve stiffens the inertia
    (``GEOMETRIC`` if None); ``rows_through``: whether the angular rows of the tree's joints
    are solved through it (``joint_loops.row_masses``)."""
    j = joints.arrays()
    n = j.a.shape[0]
    rows = JointRows(np.empty((n, 3)), np.empty((n, 3)), np.empty((n, 3, 3)), np.empty((n, 3)),
                     np.empty((n, 3, 3)), np.empty((n, 3)), np.empty((n, 3)),
                     np.empty((n, 3), np.int64), np.zeros((n, 3)), np.empty(n, np.int64), (),
                     dt, through=np.zeros((n, 3), np.bool_))
    b = bodies
    awake = getattr(b, "awake", None)
    movable = b.inv_mass > 0.0
    jt.choose(j.a, j.b, movable if awake is None else awake, movable, rows.mode)
    if not DIRECT:
        rows.mode[rows.mode >= jt.DIRECT] = jt.ITERATIVE
    if not loops:
        rows.mode[rows.mode == jt.LOOP] = jt.ITERATIVE
    elif not pairs:
        jt.unpair(j.a, j.b, movable, rows.mode)
    js.prepare(j.a, j.b, j.local_a, j.frame_a, j.frame_b, j.kind, j.limits, j.local_b,
               b.inv_mass, b.inv_inertia_world, b.position, b.orientation, dt,
               beta, rows.ra, rows.rb, rows.kmat, rows.bias,
               rows.axis, rows.mass, rows.target, rows.row)
    rows.tree = _factor(b, j, rows, movable, joints.point, dt,
                        GEOMETRIC if geometric is None else geometric)
    if rows_through and rows.tree:
        nodes, parent, count, dinv, low, _, where, _ = rows.tree
        jl.row_masses(nodes, parent, count, b.inv_mass.shape[0], where, j.a, j.b, rows.mode,
                      jt.DIRECT, rows.axis, rows.row, dinv, low, rows.mass, rows.through)
    # the errors now, from the Baumgarte targets js.prepare set (−β·C/dt)
    rows.keep = rows.bias * (-(1.0 - beta) * dt / beta) if beta > 0.0 else rows.bias * 0.0
    return rows


def _factor(b, j, rows: JointRows, movable: np.ndarray, point: np.ndarray, dt: float,
            geometric: bool) -> tuple:
    """Order and factor the DIRECT forest (``joint_direct``) and the LOOP joints' masses
    (``joint_loops``); a singular pivot (a body without full inertia, repeated joints) sends
    the joints back to the Gauss–Seidel rows (all of them, or the loops only)."""
    if not (rows.mode == jt.DIRECT).any():
        return ()
    size = b.inv_mass.shape[0] + j.a.shape[0]
    nodes = np.empty(size, np.int64)
    parent = np.empty(size, np.int64)
    count = jt.order(j.a, j.b, movable, rows.mode, nodes, parent)
    dinv = np.zeros((count, 6, 6))
    low = np.zeros((count, 6, 6))
    extra = np.zeros((b.inv_mass.shape[0], 3, 3))
    if geometric:
        jd.geometric(j.a, j.b, rows.mode, rows.ra, rows.rb, point, b.inv_inertia_world, dt,
                     extra)
    n = b.inv_mass.shape[0]
    loops = np.flatnonzero(rows.mode == jt.LOOP)
    where = np.full(n, -1, np.int64)
    bodies = nodes[:count] < n
    where[nodes[:count][bodies]] = np.flatnonzero(bodies)
    sinv = np.zeros((loops.shape[0], 3, 3))
    if not jd.factor(nodes, parent, count, n, j.a, rows.ra, rows.rb, b.inv_mass,
                     b.inv_inertia_world, extra, dinv, low):
        rows.mode[rows.mode >= jt.DIRECT] = jt.ITERATIVE
        return ()
    if not jl.masses(loops, nodes, parent, count, n, where, j.a, j.b, rows.ra, rows.rb, dinv,
                     low, sinv):  # a loop the tree cannot move along (a straight ring)
        rows.mode[loops] = jt.ITERATIVE
        loops = loops[:0]
    return nodes, parent, count, dinv, low, loops, where, sinv


def warm_start(bodies, joints, rows: JointRows) -> None:
    j = joints.arrays()
    b = bodies
    js.warm_start(j.a, j.b, rows.ra, rows.rb, rows.axis, rows.row, b.inv_mass,
                  b.inv_inertia_world, b.velocity, b.angular_velocity, joints.point, joints.turn,
                  rows.lam, rows.mode)


def velocity_pass(bodies, joints, rows: JointRows) -> float:
    """One pass: first the targets from the predicted end pose (``joint_predict``; unless
    ``rows.predict`` is off), then Gauss–Seidel over the rows, the tree solve and the loops;
    returns the largest predicted excess or velocity change [m/s or rad/s]."""
    j = joints.arrays()
    b = bodies
    change = 0.0
    if rows.predict:
        n = b.inv_mass.shape[0]
        change = float(joint_predict.end_targets(
            j.a, j.b, j.local_a, j.local_b, b.position, b.orientation, b.velocity,
            b.angular_velocity, b.inv_inertia, rows.dt, rows.mode, rows.ra, rows.rb, rows.keep,
            rows.bias, np.empty((n, 3)), np.empty((n, 4)), rows.speed,
            jt.LOOP if rows.aim_loops else jt.DIRECT))
    change = max(change, float(js.solve_pass(
        j.a, j.b, rows.ra, rows.rb, rows.kmat, rows.bias, rows.axis, rows.mass, rows.target,
        rows.row, b.inv_mass, b.inv_inertia_world, b.velocity, b.angular_velocity,
        joints.point, rows.lam, rows.mode, rows.mass_scale, rows.impulse_scale, rows.through)))
    if rows.tree:
        nodes, parent, count, dinv, low, loops, where, sinv = rows.tree
        n = b.inv_mass.shape[0]
        change = max(change, float(jd.solve(nodes, parent, count, n, j.a, j.b, rows.ra,
                                            rows.rb, rows.bias, dinv, low, b.velocity,
                                            b.angular_velocity, joints.point)))
        if loops.shape[0]:
            change = max(change, float(jl.solve(
                loops, nodes, parent, count, n, where, j.a, j.b, rows.ra, rows.rb, rows.bias,
                dinv, low, sinv, b.velocity, b.angular_velocity, joints.point)))
        if rows.through.any():
            change = max(change, float(jl.row_solve(
                nodes, parent, count, n, where, j.a, j.b, rows.axis, rows.row, rows.mass,
                rows.target, rows.through, dinv, low, b.velocity, b.angular_velocity,
                joints.point, rows.lam, LIMIT)))
    return change


def keep(joints, rows: JointRows) -> None:
    """Keep this step's angular impulses for the next warm start (the point block's already
    accumulate in ``joints.point``)."""
    js.keep(rows.axis, rows.row, rows.lam, joints.turn, rows.mode)
