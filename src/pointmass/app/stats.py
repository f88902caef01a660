"""Frame statistics for the panel: frames/s, real-time factor, physics ms per step. Smoothed
over about a second, so the numbers are readable. (The live plots read a Probe, not this.)"""

from __future__ import annotations

from collections import deque

import numpy as np


class FrameStats:
    """Running figures about the viewer; ``frame`` once per drawn frame.

    Figures are sums over the last ``window`` frames (not an exponential average), so a slow
    first step (numba compiling its kernels) is forgotten after a second instead of lingering.
    """

    def __init__(self, window: int = 60) -> None:
        self.fps = 0.0
        self.realtime = 0.0                 # simulated seconds per real second
        self.step_ms = 0.0                  # physics milliseconds per step
        self.frame_ms = 0.0                 # whole frame (update + draw) [ms]
        self.gui_ms = 0.0                   # the panel: new_frame to the end of its draw [ms]
        self.physics_share = 0.0            # fraction of the frame spent stepping
        self._frames: deque = deque(maxlen=window)

    def frame(self, real_dt: float, sim_dt: float, steps: int, physics_s: float) -> None:
        """Record a frame that took ``real_dt`` s, advanced the simulation ``sim_dt`` s in
        ``steps`` steps, which took ``physics_s`` s."""
        if real_dt <= 0:
            return
        self._frames.append((real_dt, sim_dt, steps, physics_s))
        real, sim, n, physics = (sum(col) for col in zip(*self._frames))
        self.fps = len(self._frames) / real
        self.realtime = sim / real
        self.frame_ms = 1e3 * real / len(self._frames)
        self.physics_share = min(1.0, physics / real)
        if n:
            self.step_ms = 1e3 * physics / n


def particle_count(scene) -> str:
    """The panel's particle count: the particles drawn, and the pool they come from when the
    scene hides some (dead fireworks, spent rounds), e.g. "137 live / 1024"; a pool size alone
    would read the same whatever is alive."""
    n = scene.world.particles.count
    if scene.hidden is None:
        return f"{n}"
    hidden = np.asarray(scene.hidden, bool).reshape(-1)[:n]
    return f"{n - int(hidden.sum())} live / {n}"
