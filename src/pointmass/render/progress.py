"""A one-line progress bar on stderr: frames done, frames per second, time left."""

from __future__ import annotations

import sys
import time

from .. import compiling


class ProgressBar:
    """Redraws at most ``rate`` times per second; ``close()`` ends the line. When the stream is
    not a terminal (a log file, CI), it prints a plain line every 10 % instead of ``\r``
    redraws. Time numba spends compiling is left out of the rate and the time left (a first
    run's minute of compiling once made 30 frames say "0.6 fps, 7:08 left")."""

    def __init__(self, total: int, *, label: str = "recording", stream=None,
                 rate: float = 8.0, width: int = 28) -> None:
        self.total, self.label, self.width = max(total, 1), label, width
        self.stream = stream if stream is not None else sys.stderr
        self.interval = 1.0 / rate
        self.start = time.perf_counter()
        self._watch = compiling.install()
        self._compiled_before = self._watch.seconds
        self._last = -1e9
        self.done = 0
        isatty = getattr(self.stream, "isatty", None)
        self.terminal = bool(isatty and isatty())
        self._next_tenth = 1

    def update(self, done: int, *, force: bool = False) -> None:
        self.done = done
        now = time.perf_counter()
        if not force and now - self._last < self.interval:
            return
        if not self.terminal:
            tenth = done * 10 // self.total
            if tenth < self._next_tenth and not force:
                return
            self._next_tenth = tenth + 1
        self._last = now
        compiling_seconds = self._watch.seconds - self._compiled_before
        elapsed = max(now - self.start - compiling_seconds, 1e-9)
        fps = done / elapsed
        left = (self.total - done) / fps if fps > 0 else float("nan")
        filled = int(self.width * done / self.total)
        bar = "#" * filled + "." * (self.width - filled)
        eta = f"{int(left // 60)}:{int(left % 60):02d}" if left == left else "?:??"
        line = f"{self.label} [{bar}] {done}/{self.total} frames {fps:5.1f} fps, {eta} left"
        self.stream.write(f"\r{line} " if self.terminal else f"{line}\n")
        self.stream.flush()

    def close(self) -> None:
        if self.terminal:
            self.update(self.done, force=True)
            self.stream.write("\n")
        elif self._next_tenth <= 10:
            self.update(self.done, force=True)
        self.stream.flush()
