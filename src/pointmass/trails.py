"""Trails: the recent path of chosen particles, sampled on simulated time (no GL here).

A scene says *which* particles leave a trail (``Scene.trails``) and how many points a trail
keeps (``Scene.trail_length``); the running ``Simulation`` owns the recorded points. Points are
taken every ``interval`` simulated seconds, not once per drawn frame, so a trail looks the same
in a 144 Hz window, a 30 fps recording and a snapshot, and recording never needs to slice time
into frames to give a trail its points.

A trail restarts when its particle leaves ``Scene.trails`` or is hidden: a pooled slot that is
reused (a new firework round) does not draw a line from where the old one died.
"""

from __future__ import annotations

import numpy as np

#: Simulated seconds between two trail points (a 30 fps recording's frame time).
TRAIL_INTERVAL = 1.0 / 30.0


class Trails:
    """Recorded paths of a scene's trailed particles.

    Args:
        interval: Simulated seconds between points (> 0).
    """

    def __init__(self, interval: float = TRAIL_INTERVAL) -> None:
        if not interval > 0:
            raise ValueError(f"interval must be > 0 s, got {interval!r}")
        self.interval = float(interval)
        self._points: dict[int, list[np.ndarray]] = {}
        self._next_time: float | None = None

    def sample(self, scene, time: float) -> None:
        """After a step: end the trails of particles that left the list or were hidden (every
        step, so a slot reused a few steps later starts afresh), and take a point for every
        trailed particle if ``time`` reached the next sample time."""
        self._prune(scene)
        if self._next_time is not None and time + 1e-9 < self._next_time:
            return
        ticks = np.floor(time / self.interval + 1e-9)
        self._next_time = (ticks + 1) * self.interval
        self._append(scene)

    def record(self, scene) -> None:
        """Take a point for every trailed particle now."""
        self._prune(scene)
        self._append(scene)

    @staticmethod
    def _gone(scene, i: int) -> bool:
        hidden = scene.hidden
        return i >= scene.world.particles.count or (
            hidden is not None and i < len(hidden) and bool(hidden[i]))

    def _prune(self, scene) -> None:
        if not self._points:
            return
        wanted = set(scene.trails)
        for i in list(self._points):
            if i not in wanted or self._gone(scene, i):
                del self._points[i]

    def _append(self, scene) -> None:
        pos = scene.world.particles.position
        for i in scene.trails:
            if self._gone(scene, i):
                continue
            buf = self._points.setdefault(i, [])
            buf.append(pos[i].copy())
            if len(buf) > scene.trail_length:
                del buf[: len(buf) - scene.trail_length]

    def clear(self, index: int | None = None) -> None:
        """Forget one particle's path, or every path (a reset)."""
        if index is None:
            self._points.clear()
            self._next_time = None
        else:
            self._points.pop(index, None)

    def points(self, index: int) -> np.ndarray:
        """The recorded path of one particle, oldest first, shape (T, 3)."""
        buf = self._points.get(index)
        return np.array(buf) if buf else np.zeros((0, 3))

    def __iter__(self):
        """The particle indices that have a path."""
        return iter(list(self._points))

    def __len__(self) -> int:
        return len(self._points)
