"""Frame statistics for the panel: frames/s, real-time factor, physics ms per step, and the
history the live plot draws. Smoothed over about half a second, so the numbers are readable."""

from __future__ import annotations

from collections import deque

import numpy as np

#: Samples the live plot keeps (one per drawn frame).
HISTORY = 600


class FrameStats:
    """Running figures about the viewer; ``frame`` once per drawn frame."""

    def __init__(self, smoothing: float = 0.5) -> None:
        self.smoothing = smoothing          # seconds the averages reach back
        self.fps = 0.0
        self.realtime = 0.0                 # simulated seconds per real second
        self.step_ms = 0.0                  # physics milliseconds per step
        self.frame_ms = 0.0                 # whole frame (update + draw) [ms]
        self.gui_ms = 0.0                   # the panel: new_frame to the end of its draw [ms]
        self.physics_share = 0.0            # fraction of the frame spent stepping
        self.history: dict[str, deque] = {}

    def _blend(self, old: float, new: float, dt: float) -> float:
        a = min(1.0, dt / self.smoothing) if old else 1.0
        return old + a * (new - old)

    def frame(self, real_dt: float, sim_dt: float, steps: int, physics_s: float) -> None:
        """Record a frame that took ``real_dt`` s, advanced the simulation ``sim_dt`` s in
        ``steps`` steps, which took ``physics_s`` s."""
        if real_dt <= 0:
            return
        self.fps = self._blend(self.fps, 1.0 / real_dt, real_dt)
        self.realtime = self._blend(self.realtime, sim_dt / real_dt, real_dt)
        self.frame_ms = self._blend(self.frame_ms, real_dt * 1e3, real_dt)
        self.physics_share = self._blend(self.physics_share, min(1.0, physics_s / real_dt),
                                         real_dt)
        if steps:
            self.step_ms = self._blend(self.step_ms, physics_s * 1e3 / steps, real_dt)

    def sample(self, values: dict[str, float]) -> None:
        """Append one value per named series (time is the series "t")."""
        for name, value in values.items():
            self.history.setdefault(name, deque(maxlen=HISTORY)).append(float(value))

    def series(self, name: str) -> np.ndarray:
        return np.array(self.history.get(name, ()), dtype=np.float64)

    def clear_history(self) -> None:
        self.history.clear()
