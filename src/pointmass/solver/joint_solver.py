"""The joints' part of the body stage (``body_solver``): prepare and warm start, one velocity
pass, one position pass, and keeping the impulses; the kernels are in ``joint_stages``."""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from . import joint_stages as js

#: A position pass that leaves every joint within these is the last one: separation [m], and
#: angular error beyond ``joint_stages.ANGULAR_SLOP`` [rad].
LINEAR_TOLERANCE = 1e-5
ANGULAR_TOLERANCE = 1e-4


@dataclass
class JointRows:
    """One substep's rows of the joints (J joints): arms [m] (J, 3), K (J, 3, 3), per angular
    slot the axis (J, 3, 3), mass, target [rad/s], type and accumulated impulse (J, 3)."""

    ra: np.ndarray
    rb: np.ndarray
    kmat: np.ndarray
    axis: np.ndarray
    mass: np.ndarray
    target: np.ndarray
    row: np.ndarray
    lam: np.ndarray


def prepare(bodies, joints, dt: float) -> JointRows:
    """The rows of ``joints`` (a ``rigid.joint_set.Joints``) in the bodies' current pose."""
    j = joints.arrays()
    n = j.a.shape[0]
    rows = JointRows(np.empty((n, 3)), np.empty((n, 3)), np.empty((n, 3, 3)),
                     np.empty((n, 3, 3)), np.empty((n, 3)), np.empty((n, 3)),
                     np.empty((n, 3), np.int64), np.zeros((n, 3)))
    b = bodies
    js.prepare(j.a, j.b, j.local_a, j.frame_a, j.frame_b, j.kind, j.limits, j.local_b,
               b.inv_mass, b.inv_inertia_world, b.orientation, dt, rows.ra, rows.rb, rows.kmat,
               rows.axis, rows.mass, rows.target, rows.row)
    return rows


def warm_start(bodies, joints, rows: JointRows) -> None:
    j = joints.arrays()
    b = bodies
    js.warm_start(j.a, j.b, rows.ra, rows.rb, rows.axis, rows.row, b.inv_mass,
                  b.inv_inertia_world, b.velocity, b.angular_velocity, joints.point, joints.turn,
                  rows.lam)


def velocity_pass(bodies, joints, rows: JointRows) -> float:
    """One Gauss–Seidel pass; returns the largest velocity change [m/s or rad/s]."""
    j = joints.arrays()
    b = bodies
    return float(js.solve_pass(j.a, j.b, rows.ra, rows.rb, rows.kmat, rows.axis, rows.mass,
                               rows.target, rows.row, b.inv_mass, b.inv_inertia_world,
                               b.velocity, b.angular_velocity, joints.point, rows.lam))


def keep(joints, rows: JointRows) -> None:
    """Keep this step's angular impulses for the next warm start (the point block's already
    accumulate in ``joints.point``)."""
    js.keep(rows.axis, rows.row, rows.lam, joints.turn)


def position_pass(bodies, joints) -> bool:
    """One projection pass; True when every joint was already within the tolerances."""
    j = joints.arrays()
    b = bodies
    linear, angular = js.project_pass(j.a, j.b, j.local_a, j.local_b, j.frame_a, j.frame_b,
                                      j.kind, j.limits, b.inv_mass, b.inv_inertia_world,
                                      b.position, b.orientation)
    return linear <= LINEAR_TOLERANCE and angular <= ANGULAR_TOLERANCE
