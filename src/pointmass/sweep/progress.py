"""The sweep's progress line on stderr: runs done, failures, elapsed and estimated time left."""

from __future__ import annotations

import sys
import time


class SweepProgress:
    """Redraws one line (``\\r``) on a terminal; prints a line per 10 % elsewhere (logs, CI)."""

    def __init__(self, total: int, skipped: int, *, stream=None, enabled: bool = True) -> None:
        self.total, self.skipped, self.enabled = total, skipped, enabled
        self.stream = stream if stream is not None else sys.stderr
        self.done = self.failed = 0
        self.start = time.perf_counter()
        isatty = getattr(self.stream, "isatty", None)
        self.terminal = bool(isatty and isatty())
        self._next_tenth = 1
        self._last = 0.0

    def update(self, *, failed: bool) -> None:
        self.done += 1
        self.failed += failed
        if not self.enabled:
            return
        now = time.perf_counter()
        if self.terminal:
            if now - self._last >= 0.2 or self.done == self.total:
                self._last = now
                self.stream.write(f"\r{self.line()} ")
                self.stream.flush()
        elif self.done * 10 // max(self.total, 1) >= self._next_tenth:
            self._next_tenth = self.done * 10 // max(self.total, 1) + 1
            self.stream.write(self.line() + "\n")
            self.stream.flush()

    def line(self) -> str:
        elapsed = time.perf_counter() - self.start
        left = (self.total - self.done) * elapsed / self.done if self.done else float("nan")
        eta = f"{int(left // 60)}:{int(left % 60):02d}" if left == left else "?:??"
        skipped = f" ({self.skipped} already done)" if self.skipped else ""
        return (f"sweep: {self.done}/{self.total} runs{skipped}, {self.failed} failed, "
                f"{elapsed:.0f} s, {eta} left")

    def close(self) -> None:
        if self.enabled and self.terminal and self.done:
            self.stream.write("\n")
            self.stream.flush()
