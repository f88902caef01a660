"""Fixed-step time: physics at a constant dt with an accumulator, rendering at the display rate.

Each drawn frame hands the real seconds since the last one to ``FixedStepClock.advance``, which
says how many physics steps to run. The time scale multiplies real time (0.25: slow motion,
2: faster than real time). At most ``max_steps`` steps run per frame, and whatever is left over
is dropped: a machine too slow for real time then shows slow motion instead of spiralling
(each late frame asking for ever more steps).
"""

from __future__ import annotations

import math

#: The time scales ``-`` and ``=`` step through.
TIME_SCALES = (0.05, 0.1, 0.25, 0.5, 1.0, 2.0, 4.0)


class FixedStepClock:
    """Turns frame times into a whole number of fixed physics steps.

    Args:
        dt: The physics step [s] (> 0).
        max_steps: The most steps one frame may run (≥ 1).
        time_scale: Simulated seconds per real second (> 0).
        paused: Start paused (``advance`` then runs only requested single steps).
        max_frame_time: Real frame times are clipped to this [s], so a stall (a window drag,
            a breakpoint) does not come back as a burst of catch-up.
    """

    def __init__(self, dt: float, *, max_steps: int = 16, time_scale: float = 1.0,
                 paused: bool = False, max_frame_time: float = 0.25) -> None:
        if not (math.isfinite(dt) and dt > 0):
            raise ValueError(f"dt must be a number of seconds > 0, got {dt!r}")
        if max_steps < 1:
            raise ValueError(f"max_steps must be >= 1, got {max_steps!r}")
        self.dt = float(dt)
        self.max_steps = int(max_steps)
        self.time_scale = time_scale
        self.paused = paused
        self.max_frame_time = max_frame_time
        self.accumulator = 0.0
        self.dropped = 0.0
        """Simulated seconds dropped so far because a frame hit ``max_steps`` [s]."""
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
        self.accumulator = 0.0     # resuming starts clean: no burst of stored time

    def single_step(self) -> None:
        """Run exactly one step on the next ``advance`` (pauses first, as MuJoCo's → does)."""
        self.paused = True
        self._single += 1

    def reset(self) -> None:
        """Forget stored time (after a rebuild)."""
        self.accumulator = 0.0
        self._single = 0

    def slower(self) -> None:
        self.time_scale = _neighbour(self._time_scale, -1)

    def faster(self) -> None:
        self.time_scale = _neighbour(self._time_scale, +1)

    def advance(self, real_dt: float) -> int:
        """How many fixed steps to run for a frame that took ``real_dt`` real seconds."""
        if self.paused:
            steps, self._single = min(self._single, self.max_steps), 0
            return steps
        self.accumulator += min(max(real_dt, 0.0), self.max_frame_time) * self._time_scale
        steps = int(self.accumulator / self.dt + 1e-9)
        self.accumulator -= steps * self.dt
        if steps > self.max_steps:
            # Too slow for this time scale: drop the backlog (slow motion, not a spiral).
            self.dropped += (steps - self.max_steps) * self.dt + self.accumulator
            steps, self.accumulator = self.max_steps, 0.0
        return steps


def _neighbour(scale: float, direction: int) -> float:
    """The next entry of TIME_SCALES below (-1) or above (+1) ``scale``, clamped at the ends."""
    if direction > 0:
        bigger = [s for s in TIME_SCALES if s > scale * (1 + 1e-9)]
        return bigger[0] if bigger else TIME_SCALES[-1]
    smaller = [s for s in TIME_SCALES if s < scale * (1 - 1e-9)]
    return smaller[-1] if smaller else TIME_SCALES[0]
