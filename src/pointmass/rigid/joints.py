"""Joints between rigid bodies: a ball joint (optionally with a swing cone and a twist range)
and a hinge (with an optional angle range). Added with ``world.add(joint)``.

A joint holds a point of body A on a point of body B (or on a fixed world anchor when body B is
None) with three velocity rows solved together (a 3×3 effective mass with the angular terms),
warm started from the impulse it needed last step, in the same Gauss–Seidel passes as the
contacts (``pointmass.solver.joint_stages``). That is a real two-sided point constraint, unlike
Cyclone's ``Joint`` (R11): a contact with friction 1 that acts only once the anchors are more
than 0.15 m apart and only pulls.

Angles are measured from the pose the bodies have when the joint is added to a world: the
joint's *axis* (given in body A's coordinates) is then recorded in body B's coordinates too,
with a reference direction across it, so "straight" is the pose of the build. A hinge keeps the
two axes together (2 angular rows) and may limit the angle about them; a ball joint may limit
the swing (angle between the two axes, a cone) and the twist (angle about them).
"""

from __future__ import annotations

import math

import numpy as np

from .. import _validate as check
from .bodies import Bodies, Body, body_index, world_rotation

#: Joint kinds, as the kernels read them.
BALL = 0
CONE = 1
HINGE = 2



def _angle(value, name: str, low: float, high: float) -> float:
    return check.scalar(value, name, low=low, high=high)


def _perpendicular(axis: np.ndarray) -> np.ndarray:
    """A unit vector across the unit ``axis`` (a fixed function of it)."""
    other = np.array([1.0, 0.0, 0.0]) if abs(axis[0]) < 0.57735 else np.array([0.0, 1.0, 0.0])
    p = np.cross(axis, other)
    return p / np.linalg.norm(p)


class Joint:
    """What every joint has: two bodies (B may be None: the world) and a point on each.

    Args:
        body_a: A body (``Body`` handle or index).
        local_a: The joint point in body A's coordinates [m].
        body_b: Another body, or None for a fixed world anchor.
        local_b: The joint point in body B's coordinates [m] (the world anchor [m] when
            ``body_b`` is None); None: wherever body A's point is when the joint is added.
        axis: Unit axis in body A's coordinates for the angular rows (twist / hinge axis).
        friction: The most torque [N·m] the joint resists the two bodies' relative turning
            with, in [0, inf) (0: free; Box2D's joint friction, a motor at zero speed with that
            torque): a real joint's friction, which brings a dangling limb to rest. A limb on a
            frictionless joint swings as an undamped pendulum, keeping its energy.
    """

    #: Which rows the kernels build: ``BALL``, ``CONE`` or ``HINGE``.
    variant = BALL
    #: What the renderer draws it as (a link kind, ``render.gather``).
    kind = "joint"

    def __init__(self, body_a, local_a, body_b=None, local_b=None, *, axis=(0.0, 1.0, 0.0),
                 friction: float = 0.0):
        self.a = body_index(body_a, "body_a")
        self.b = -1 if body_b is None else body_index(body_b, "body_b")
        #: The handles given (``Body``, or None for an index): checked against the world the
        #: joint is added to, so a handle of another world is refused there.
        self._handles = (body_a if isinstance(body_a, Body) else None,
                         body_b if isinstance(body_b, Body) else None)
        #: The serials of its bodies when bound: a restore that dropped one, and a new body
        #: that took its index, cannot silently take its place (``Joints.check_bodies``).
        self.serials = (-1, -1)
        if self.a == self.b:
            raise ValueError(f"body_a and body_b must be different bodies, both are {self.a}")
        self.local_a = check.vec3(local_a, "local_a")
        self.local_b: np.ndarray | None = None if local_b is None \
            else check.vec3(local_b, "local_b")
        axis = check.vec3(axis, "axis")
        size = float(np.linalg.norm(axis))
        if not size > 1e-9:
            raise ValueError(f"axis must be a non-zero vector, got {axis.tolist()}")
        self.axis = axis / size
        self.friction = check.scalar(friction, "friction", low=0.0)
        #: Frames (w, x, y, z) whose x axis is the joint axis, in A's and B's coordinates
        #: (B's: world coordinates for a world anchor); set when added to a world.
        self.frame_a: np.ndarray | None = None
        self.frame_b: np.ndarray | None = None
        self._bodies: Bodies | None = None

    def limits(self) -> tuple[float, float, float]:
        """(cone, low, high) [rad] as the kernels read them (π, -inf, inf: none)."""
        return math.pi, -math.inf, math.inf

    # -- binding to a world ----------------------------------------------------------------------
    def validate(self, bodies: Bodies) -> None:
        """Check the body indices against ``bodies`` (raise naming the parameter)."""
        for name, index in (("body_a", self.a), ("body_b", self.b)):
            if index >= bodies.count:
                raise IndexError(f"{name}: {index} is not a body; indices must be in "
                                 f"[0, {bodies.count - 1}]" if bodies.count else
                                 f"{name}: {index} is not a body; there are none yet")

    def bind(self, bodies: Bodies) -> None:
        """Record what the current pose defines: B's anchor (if not given) and the frames.
        A joint belongs to one world: binding it to a second is refused."""
        if self._bodies is not None and self._bodies is not bodies:
            raise ValueError(f"this {type(self).__name__} is already in another world: a joint "
                             "belongs to one world (remove it there first, or make another)")
        for name, handle in zip(("body_a", "body_b"), self._handles):
            if handle is not None:
                handle.checked(bodies, name)
        self.validate(bodies)
        self._bodies = bodies
        self.serials = (int(bodies.serial[self.a]),
                        -1 if self.b < 0 else int(bodies.serial[self.b]))
        qa = bodies.orientation[self.a]
        rot_a = _rotation(qa)
        if self.local_b is None:
            point = bodies.position[self.a] + rot_a @ self.local_a
            self.local_b = point if self.b < 0 else \
                _rotation(bodies.orientation[self.b]).T @ (point - bodies.position[self.b])
        across = _perpendicular(self.axis)
        frame_a = np.column_stack([self.axis, across, np.cross(self.axis, across)])
        self.frame_a = quat_from_basis(frame_a)
        world = rot_a @ frame_a
        rot_b = np.eye(3) if self.b < 0 else _rotation(bodies.orientation[self.b])
        self.frame_b = quat_from_basis(rot_b.T @ world)

    def unbind(self) -> None:
        """Forget the world (``world.remove``): the joint may then join another one."""
        self._bodies = None

    # -- drawing ---------------------------------------------------------------------------------
    def anchors(self) -> tuple[np.ndarray, np.ndarray]:
        """World positions of the joint point on A and on B [m], each (3,) (equal when held)."""
        b = self._bodies
        if b is None:
            raise RuntimeError("the joint is not in a world yet (world.add(joint))")
        assert self.local_b is not None  # ``bind`` sets it
        pa = b.position[self.a] + _rotation(b.orientation[self.a]) @ self.local_a
        if self.b < 0:
            return pa, self.local_b.copy()
        return pa, b.position[self.b] + _rotation(b.orientation[self.b]) @ self.local_b

    def separation(self) -> float:
        """Distance between the two joint points now [m] (0 for a perfect joint)."""
        pa, pb = self.anchors()
        return float(np.linalg.norm(pa - pb))

    def segments(self, particles=None):
        """Lines a renderer draws: centre of A → its joint point → B's point → centre of B
        (the world anchor has no centre). (start (K, 3), end (K, 3), strain (K,))."""
        b = self._bodies
        pa, pb = self.anchors()
        starts = [b.position[self.a], pa]
        ends = [pa, pb]
        if self.b >= 0:
            starts.append(pb)
            ends.append(b.position[self.b])
        return np.array(starts), np.array(ends), np.zeros(len(starts))


class BallJoint(Joint):
    """A ball-and-socket joint: body A's point stays on body B's point (or on a world anchor);
    any rotation is free unless limited.

    Args (besides ``Joint``'s):
        cone: Largest swing [rad] in [0, π]: the angle between the joint axis as fixed in A
            and as fixed in B (they coincide in the pose the joint was added in). None: free.
        twist: (low, high) [rad], −π < low ≤ 0 ≤ high < π: the range of A's rotation about
            the axis relative to B (right-handed about the axis). None: free.
    """

    def __init__(self, body_a, local_a, body_b=None, local_b=None, *, axis=(0.0, 1.0, 0.0),
                 cone: float | None = None, twist=None, friction: float = 0.0) -> None:
        super().__init__(body_a, local_a, body_b, local_b, axis=axis, friction=friction)
        self.cone = None if cone is None else _angle(cone, "cone", 0.0, math.pi)
        self.twist = None if twist is None else _range(twist, "twist")
        self.variant = BALL if cone is None and twist is None else CONE

    def limits(self) -> tuple[float, float, float]:
        cone = math.pi if self.cone is None else self.cone
        low, high = (-math.inf, math.inf) if self.twist is None else self.twist
        return cone, low, high


class HingeJoint(Joint):
    """A hinge: a ball joint that also keeps the two bodies' copies of ``axis`` together, so
    they turn about it only; ``limits`` (low, high) [rad] bounds the angle A has turned about
    it relative to B, right-handed (a knee: (0, 2.5) bends one way). None: free."""

    variant = HINGE

    def __init__(self, body_a, local_a, body_b=None, local_b=None, *, axis=(1.0, 0.0, 0.0),
                 limits=None, friction: float = 0.0) -> None:
        super().__init__(body_a, local_a, body_b, local_b, axis=axis, friction=friction)
        self.range = None if limits is None else _range(limits, "limits")

    def limits(self) -> tuple[float, float, float]:
        low, high = (-math.inf, math.inf) if self.range is None else self.range
        return math.pi, low, high


def _range(value, name: str) -> tuple[float, float]:
    try:
        low, high = (float(v) for v in value)
    except (TypeError, ValueError):
        raise ValueError(f"{name} must be a pair (low, high) of angles [rad], got "
                         f"{value!r}") from None
    if not (-math.pi < low <= 0.0 <= high < math.pi):
        raise ValueError(f"{name} must satisfy -pi < low <= 0 <= high < pi [rad] (the pose the "
                         f"joint is added in is angle 0), got ({low}, {high})")
    return low, high


def quat_from_basis(m: np.ndarray) -> np.ndarray:
    """Unit quaternion (w, x, y, z) of the rotation matrix ``m`` (3, 3) (Shepperd's method:
    divide by the largest of the four candidates, so no precision is lost)."""
    t = np.trace(m)
    cands = [t, m[0, 0], m[1, 1], m[2, 2]]
    k = int(np.argmax(cands))
    if k == 0:
        s = 2.0 * math.sqrt(1.0 + t)
        q = [0.25 * s, (m[2, 1] - m[1, 2]) / s, (m[0, 2] - m[2, 0]) / s, (m[1, 0] - m[0, 1]) / s]
    elif k == 1:
        s = 2.0 * math.sqrt(1.0 + m[0, 0] - m[1, 1] - m[2, 2])
        q = [(m[2, 1] - m[1, 2]) / s, 0.25 * s, (m[0, 1] + m[1, 0]) / s, (m[0, 2] + m[2, 0]) / s]
    elif k == 2:
        s = 2.0 * math.sqrt(1.0 + m[1, 1] - m[0, 0] - m[2, 2])
        q = [(m[0, 2] - m[2, 0]) / s, (m[0, 1] + m[1, 0]) / s, 0.25 * s, (m[1, 2] + m[2, 1]) / s]
    else:
        s = 2.0 * math.sqrt(1.0 + m[2, 2] - m[0, 0] - m[1, 1])
        q = [(m[1, 0] - m[0, 1]) / s, (m[0, 2] + m[2, 0]) / s, (m[1, 2] + m[2, 1]) / s, 0.25 * s]
    quat = np.array(q)
    return quat / np.linalg.norm(quat)


def _rotation(q) -> np.ndarray:
    """3×3 rotation of the unit quaternion q (w, x, y, z)."""
    return world_rotation(np.asarray(q, np.float64))
