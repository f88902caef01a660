"""The window's playback: how much simulated time a drawn frame asks for.

The window hands each frame's real seconds to ``PlaybackClock.seconds``, which scales them
(0.25: slow motion, 2: faster than real time), clips a stall (a window drag, a breakpoint) to
``max_frame_time`` so it does not come back as a burst of catch-up, and gives 0 while paused.
The Simulation turns those seconds into fixed steps (``Simulation.advance``, the only place
that does), so a window, a recording and a probe run take the same steps. Single steps while
paused (``.`` as in MuJoCo's viewer) are counted here and run by the viewer.
"""

from __future__ import annotations

import math

#: The time scales ``-`` and ``=`` step through.
TIME_SCALES = (0.05, 0.1, 0.25, 0.5, 1.0, 2.0, 4.0)


class PlaybackClock:
    """Real frame time to simulated time: time scale, pause, single steps.

    Args:
        max_steps: The most physics steps one frame may run (≥ 1); the viewer passes it to
            ``Simulation.advance``, which drops what is beyond (slow motion, not a spiral).
        time_scale: Simulated seconds per real second (> 0).
        paused: Start paused.
        max_frame_time: Real frame times are clipped to this [s].
    """

    def __init__(self, *, max_steps: int = 16, time_scale: float = 1.0, paused: bool = False,
                 max_frame_time: float = 0.25) -> None:
        if max_steps < 1:
            raise ValueError(f"max_steps must be >= 1, got {max_steps!r}")
        self.max_steps = int(max_steps)
        self.time_scale = time_scale
        self.paused = paused
        self.max_frame_time = max_frame_time
        self._single = 0

    @property
    def time_scale(self) -> float:
        return self._time_scale

    @time_scale.setter
    def time_scale(self, value: float) -> None:
        if not (math.isfinite(value) and value > 0):
            raise ValueError(f"time_scale must be > 0, got {value!r}")
        self._time_scale = float(value)

    def toggle_pause(self) -> None:
        self.paused = not self.paused

    def single_step(self) -> None:
        """Ask for exactly one step on the next frame (pauses first, as MuJoCo's → does)."""
        self.paused = True
        self._single += 1

    def take_single_steps(self) -> int:
        """The single steps asked for since the last frame (at most ``max_steps``)."""
        steps, self._single = min(self._single, self.max_steps), 0
        return steps

    def reset(self) -> None:
        """Forget requested single steps (after a rebuild)."""
        self._single = 0

    def seconds(self, real_dt: float) -> float:
        """Simulated seconds a frame that took ``real_dt`` real seconds asks for (0 paused)."""
        if self.paused:
            return 0.0
        return min(max(real_dt, 0.0), self.max_frame_time) * self._time_scale

    def slower(self) -> None:
        self.time_scale = _neighbour(self._time_scale, -1)

    def faster(self) -> None:
        self.time_scale = _neighbour(self._time_scale, +1)


def _neighbour(scale: float, direction: int) -> float:
    """The next entry of TIME_SCALES below (-1) or above (+1) ``scale``, clamped at the ends."""
    if direction > 0:
        bigger = [s for s in TIME_SCALES if s > scale * (1 + 1e-9)]
        return bigger[0] if bigger else TIME_SCALES[-1]
    smaller = [s for s in TIME_SCALES if s < scale * (1 - 1e-9)]
    return smaller[-1] if smaller else TIME_SCALES[0]
