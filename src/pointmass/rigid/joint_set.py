"""The joints of a world: the ``Joint`` objects, their packed arrays for the kernels, and the
impulses each needed last step (its warm start), kept in the joints' order."""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from .bodies import Bodies
from .joint_rows import angular_errors
from .joints import Joint


@dataclass
class JointArrays:
    """Every joint as the kernels read it (J joints).

    Attributes:
        a, b: Bodies, shape (J,), int64; b = -1: a fixed world anchor.
        local_a, local_b: Joint points in A's / B's coordinates [m] (B's: the world anchor when
            b = -1), shape (J, 3).
        frame_a, frame_b: Joint frames (w, x, y, z) in A's / B's coordinates (B's: world), x
            being the joint axis, shape (J, 4).
        kind: ``joints.BALL``, ``CONE`` or ``HINGE``, shape (J,), int64.
        limits: (cone, low, high) [rad] per joint, shape (J, 3) (π, -inf, inf: none).
        friction: The most torque [N·m] each joint resists relative turning with, (J,).
    """

    a: np.ndarray
    b: np.ndarray
    local_a: np.ndarray
    local_b: np.ndarray
    frame_a: np.ndarray
    frame_b: np.ndarray
    kind: np.ndarray
    limits: np.ndarray
    friction: np.ndarray = None
    #: The bodies' serials when each joint was bound (``Bodies.serial``), (J,); -1: none.
    serial_a: np.ndarray = None
    serial_b: np.ndarray = None


class Joints:
    """The world's joints (``world.add(joint)``), in the order they were added."""

    def __init__(self) -> None:
        self.items: list[Joint] = []
        self._packed: JointArrays | None = None
        #: Last step's impulses: the point block's [N·s] (J, 3) and each angular slot's as a
        #: world vector [N·m·s] (J, 3, 3).
        self.point = np.zeros((0, 3))
        self.turn = np.zeros((0, 3, 3))

    def __len__(self) -> int:
        return len(self.items)

    def __iter__(self):
        return iter(self.items)

    def __contains__(self, joint) -> bool:
        return any(joint is j for j in self.items)

    def add(self, joint: Joint, bodies: Bodies) -> Joint:
        """Bind ``joint`` to ``bodies`` in their current pose and keep it."""
        joint.bind(bodies)
        self.items.append(joint)
        self.point = np.vstack([self.point, np.zeros((1, 3))])
        self.turn = np.concatenate([self.turn, np.zeros((1, 3, 3))])
        self._packed = None
        return joint

    def remove(self, joint: Joint) -> None:
        k = next(i for i, j in enumerate(self.items) if j is joint)
        del self.items[k]
        joint.unbind()
        self.point = np.delete(self.point, k, axis=0)
        self.turn = np.delete(self.turn, k, axis=0)
        self._packed = None

    def validate(self, bodies: Bodies) -> None:
        """Check every joint's bodies still exist (after a restore dropped some)."""
        for joint in self.items:
            joint.validate(bodies)

    def check_bodies(self, bodies: Bodies) -> None:
        """Refuse a joint whose body is gone even where its index exists again: a restore
        dropped it and a later body took the index (serials differ). One comparison a joint
        a step."""
        if not self.items:
            return
        j = self.arrays()
        n = bodies.count
        serial = bodies.serial
        ok_a = (j.a < n) & (serial[np.minimum(j.a, n - 1)] == j.serial_a) if n else j.a < 0
        ok_b = (j.b < 0) | ((j.b < n) & (serial[np.clip(j.b, 0, max(n - 1, 0))] == j.serial_b)
                            if n else j.b < 0)
        bad = np.flatnonzero(~(ok_a & ok_b))
        if bad.size:
            k = int(bad[0])
            joint = self.items[k]
            which = "body_a" if not ok_a[k] else "body_b"
            index = joint.a if which == "body_a" else joint.b
            now = "another body has its index now" if index < n else "no body has its index"
            raise IndexError(
                f"{type(joint).__name__} {k} ({which} = {index}) lost its body: a restore "
                f"dropped body {index}, and {now}; remove the joint with world.remove() or "
                "restore a snapshot that has its body")

    # -- warm start --------------------------------------------------------------------------
    def clear_impulses(self) -> None:
        """Forget last step's impulses (after a reset, so a replay is bit-identical)."""
        self.point[:] = 0.0
        self.turn[:] = 0.0

    def snapshot(self) -> tuple[np.ndarray, np.ndarray]:
        return self.point.copy(), self.turn.copy()

    def restore(self, snap: tuple[np.ndarray, np.ndarray]) -> None:
        if snap[0].shape[0] == len(self.items):
            self.point[:], self.turn[:] = snap
        else:
            self.clear_impulses()

    # -- for the solver and the collision filter ------------------------------------------------
    def arrays(self) -> JointArrays:
        """The packed arrays (rebuilt only after an add or a remove)."""
        if self._packed is None:
            items = self.items
            self._packed = JointArrays(
                a=np.array([j.a for j in items], np.int64),
                b=np.array([j.b for j in items], np.int64),
                local_a=np.array([j.local_a for j in items], np.float64).reshape(-1, 3),
                local_b=np.array([j.local_b for j in items], np.float64).reshape(-1, 3),
                frame_a=np.array([j.frame_a for j in items], np.float64).reshape(-1, 4),
                frame_b=np.array([j.frame_b for j in items], np.float64).reshape(-1, 4),
                kind=np.array([j.variant for j in items], np.int64),
                limits=np.array([j.limits() for j in items], np.float64).reshape(-1, 3),
                friction=np.array([j.friction for j in items], np.float64),
                serial_a=np.array([j.serials[0] for j in items], np.int64),
                serial_b=np.array([j.serials[1] for j in items], np.int64))
        return self._packed

    def angular_errors(self, bodies: Bodies) -> np.ndarray:
        """Per joint, how far [rad] it is beyond a cone, twist or hinge limit, or off its hinge
        axis, now; shape (J,), 0 where every angular row is met."""
        j = self.arrays()
        out = np.zeros(j.a.shape[0])
        angular_errors(j.a, j.b, j.frame_a, j.frame_b, j.kind, j.limits, bodies.orientation,
                       out)
        return out

    def separations(self) -> np.ndarray:
        """Per joint, the distance between its two joint points now [m], shape (J,)."""
        return np.array([j.separation() for j in self.items])

    def body_pairs(self) -> np.ndarray:
        """The (K, 2) int64 body pairs that a joint joins (a joint to the world joins none):
        for the islands, so jointed bodies sleep and wake together."""
        j = self.arrays()
        two = j.b >= 0
        return np.stack([j.a[two], j.b[two]], axis=1)

    def pair_keys(self, count: int) -> np.ndarray:
        """Sorted keys min·count + max of the body pairs a joint joins (they do not collide)."""
        pairs = [(min(j.a, j.b), max(j.a, j.b)) for j in self.items if j.b >= 0]
        if not pairs:
            return np.zeros(0, np.int64)
        keys = np.array([lo * count + hi for lo, hi in pairs], np.int64)
        return np.unique(keys)

