"""The joints' rows for the soft step (``joint_soft``): prepare and warm start, one velocity
pass, and keeping the impulses; the kernels are in ``joint_stages`` (the
angular rows, and the point blocks of the joints the tree solve does not take) and
``joint_direct`` (the point blocks of a forest of joints, solved exactly each pass;
``joint_tree`` picks them)."""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from numba import njit

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
                     dt, through=np.zeros((n, 3), np.bool_), keep=np.empty((n, 3)))
    b = bodies
    awake = getattr(b, "awake", None)
    if awake is None:
        awake = b.inv_mass > 0.0
    tree = prepare_kernel(
        j.a, j.b, j.local_a, j.frame_a, j.frame_b, j.kind, j.limits, j.local_b, b.inv_mass,
        b.inv_inertia_world, b.position, b.orientation, awake, joints.point, dt, beta, DIRECT,
        loops, pairs, GEOMETRIC if geometric is None else geometric, rows_through, rows.ra,
        rows.rb, rows.kmat, rows.bias, rows.axis, rows.mass, rows.target, rows.row, rows.mode,
        rows.through, rows.keep)
    rows.tree = tree[1:] if tree[0] else ()
    return rows


@njit(cache=True, nogil=True)
def prepare_kernel(ja, jb, la, fa, fb, kind, lim, lb, inv_mass, inv_i, pos, quat, awake, point,
                   dt, beta, direct, loops, pairs, geometric, rows_through, ra, rb, kmat, bias,
                   axis, mass, target, row, mode, through, keep):
    """``prepare`` in one compiled call (the arguments: ``prepare``'s, and the rows' arrays it
    fills; ``direct``: ``DIRECT``): the joints' modes (``joint_tree``), their rows
    (``joint_stages.prepare``), the forest's order and factors (``_factor``) and the rows
    through it, and ``keep``. Returns (whether there is a forest, then its order, factors and
    loops as ``JointRows.tree`` holds them; placeholders without one)."""
    movable = inv_mass > 0.0
    jt.choose(ja, jb, awake, movable, mode)
    if not direct:
        for k in range(mode.shape[0]):
            if mode[k] >= jt.DIRECT:
                mode[k] = jt.ITERATIVE
    if not loops:
        for k in range(mode.shape[0]):
            if mode[k] == jt.LOOP:
                mode[k] = jt.ITERATIVE
    elif not pairs:
        jt.unpair(ja, jb, movable, mode)
    js.prepare(ja, jb, la, fa, fb, kind, lim, lb, inv_mass, inv_i, pos, quat, dt, beta, ra, rb,
               kmat, bias, axis, mass, target, row)
    tree, nodes, parent, count, dinv, low, cycles, where, sinv = _factor(
        ja, jb, movable, mode, ra, rb, point, inv_mass, inv_i, dt, geometric)
    if rows_through and tree:
        jl.row_masses(nodes, parent, count, inv_mass.shape[0], where, ja, jb, mode, jt.DIRECT,
                      axis, row, dinv, low, mass, through)
    # the errors now, from the Baumgarte targets js.prepare set (−β·C/dt)
    scale = -(1.0 - beta) * dt / beta if beta > 0.0 else 0.0
    for k in range(bias.shape[0]):
        for i in range(3):
            keep[k, i] = bias[k, i] * scale
    return tree, nodes, parent, count, dinv, low, cycles, where, sinv


@njit(cache=True, nogil=True)
def _factor(ja, jb, movable, mode, ra, rb, point, inv_mass, inv_i, dt, geometric):
    """Order and factor the DIRECT forest (``joint_direct``) and the LOOP joints' masses
    (``joint_loops``); a singular pivot (a body without full inertia, repeated joints) sends
    the joints back to the Gauss–Seidel rows (all of them, or the loops only). Returns
    (whether there is a forest, its order, parents, node count, factors, loops, each body's
    node position and the loops' S⁻¹)."""
    n = inv_mass.shape[0]
    none = (False, np.empty(0, np.int64), np.empty(0, np.int64), 0, np.zeros((0, 6, 6)),
            np.zeros((0, 6, 6)), np.empty(0, np.int64), np.empty(0, np.int64),
            np.zeros((0, 3, 3)))
    if not (mode == jt.DIRECT).any():
        return none
    size = n + ja.shape[0]
    nodes = np.empty(size, np.int64)
    parent = np.empty(size, np.int64)
    count = jt.order(ja, jb, movable, mode, nodes, parent)
    dinv = np.zeros((count, 6, 6))
    low = np.zeros((count, 6, 6))
    extra = np.zeros((n, 3, 3))
    if geometric:
        jd.geometric(ja, jb, mode, ra, rb, point, inv_i, dt, extra)
    loops = np.flatnonzero(mode == jt.LOOP)
    where = np.full(n, -1, np.int64)
    for p in range(count):
        if nodes[p] < n:
            where[nodes[p]] = p
    sinv = np.zeros((loops.shape[0], 3, 3))
    if not jd.factor(nodes, parent, count, n, ja, ra, rb, inv_mass, inv_i, extra, dinv, low):
        for k in range(mode.shape[0]):
            if mode[k] >= jt.DIRECT:
                mode[k] = jt.ITERATIVE
        return none
    if not jl.masses(loops, nodes, parent, count, n, where, ja, jb, ra, rb, dinv, low,
                     sinv):  # a loop the tree cannot move along (a straight ring)
        for k in range(loops.shape[0]):
            mode[loops[k]] = jt.ITERATIVE
        loops = np.empty(0, np.int64)
    return True, nodes, parent, count, dinv, low, loops, where, sinv


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
    n = bodies.inv_mass.shape[0]
    return float(pass_kernel(rows.predict, *kernel_args(bodies, joints, rows),
                             np.empty((n, 3)), np.empty((n, 4))))


#: What ``kernel_args`` gives for a forest that has no DIRECT joint (``JointRows.tree`` ()).
_NO_TREE = (np.empty(0, np.int64), np.empty(0, np.int64), 0, np.empty((0, 6, 6)),
            np.empty((0, 6, 6)), np.empty(0, np.int64), np.empty(0, np.int64),
            np.empty((0, 3, 3)))


def kernel_args(bodies, joints, rows: JointRows) -> tuple:
    """``pass_kernel``'s arguments after ``predict`` and before its scratch arrays: the joints',
    the rows', the tree's (placeholders for none) and the bodies'."""
    j = joints.arrays()
    b = bodies
    tree = rows.tree if rows.tree else _NO_TREE
    return (j.a, j.b, j.local_a, j.local_b, rows.ra, rows.rb, rows.kmat, rows.bias, rows.axis,
            rows.mass, rows.target, rows.row, rows.lam, rows.mode, rows.mass_scale,
            rows.impulse_scale, rows.through, rows.keep, rows.speed,
            jt.LOOP if rows.aim_loops else jt.DIRECT, rows.dt, bool(rows.tree), *tree,
            b.position, b.orientation, b.velocity, b.angular_velocity, b.inv_mass,
            b.inv_inertia, b.inv_inertia_world, joints.point)


@njit(cache=True, nogil=True)
def pass_kernel(predict, ja, jb, la, lb, ra, rb, kmat, bias, axis, mass, target, row, lam, mode,
                mass_scale, impulse_scale, through, keep, speed, top, dt, tree, nodes, parent,
                count, dinv, low, loops, where, sinv, pos, quat, vel, ang, inv_mass,
                inv_inertia, inv_i, point, xend, qend):
    """``velocity_pass`` in one compiled call (the arguments: ``kernel_args``; ``xend`` (N, 3)
    and ``qend`` (N, 4) are the prediction's scratch): the same kernels in the same order."""
    n = inv_mass.shape[0]
    change = 0.0
    if predict:
        change = joint_predict.end_targets(ja, jb, la, lb, pos, quat, vel, ang, inv_inertia, dt,
                                           mode, ra, rb, keep, bias, xend, qend, speed, top)
    change = max(change, js.solve_pass(ja, jb, ra, rb, kmat, bias, axis, mass, target, row,
                                       inv_mass, inv_i, vel, ang, point, lam, mode, mass_scale,
                                       impulse_scale, through))
    if tree:
        change = max(change, jd.solve(nodes, parent, count, n, ja, jb, ra, rb, bias, dinv, low,
                                      vel, ang, point))
        if loops.shape[0]:
            change = max(change, jl.solve(loops, nodes, parent, count, n, where, ja, jb, ra, rb,
                                          bias, dinv, low, sinv, vel, ang, point))
        if through.any():
            change = max(change, jl.row_solve(nodes, parent, count, n, where, ja, jb, axis, row,
                                              mass, target, through, dinv, low, vel, ang, point,
                                              lam, LIMIT))
    return change


def keep(joints, rows: JointRows) -> None:
    """Keep this step's angular impulses for the next warm start (the point block's already
    accumulate in ``joints.point``)."""
    js.keep(rows.axis, rows.row, rows.lam, joints.turn, rows.mode)
