"""Reading frames back without waiting for the GPU: pixel-buffer objects, two frames in flight.

``push(fbo)`` asks the GPU to copy the framebuffer into the next pixel buffer (the call returns
at once on a real GPU) and maps the oldest one, written a frame earlier and long finished, so
the CPU neither waits for the frame it just drew nor for the copy. On llvmpipe the copy is done
at once (nothing to overlap) and the pixels are the same.
"""

from __future__ import annotations

from collections import deque

import moderngl
import numpy as np


class AsyncReader:
    """``DEPTH`` pixel buffers of (width, height) RGB frames, used round robin."""

    DEPTH = 2

    def __init__(self, ctx: moderngl.Context, size: tuple[int, int]) -> None:
        self.ctx = ctx
        self.size = (int(size[0]), int(size[1]))
        w, h = self.size
        self._buffers = [ctx.buffer(reserve=w * h * 3, dynamic=False) for _ in range(self.DEPTH)]
        self._next = 0
        self._pending: deque[moderngl.Buffer] = deque()
        self._host = np.empty((h, w, 3), np.uint8)

    def push(self, fbo: moderngl.Framebuffer) -> np.ndarray | None:
        """Start reading ``fbo``'s color into a pixel buffer; return the oldest frame in flight
        when all buffers are busy ((H, W, 3) uint8, top row first), else None."""
        out = self._take() if len(self._pending) == self.DEPTH else None
        buf = self._buffers[self._next]
        self._next = (self._next + 1) % self.DEPTH
        fbo.read_into(buf, components=3, alignment=1)
        self._pending.append(buf)
        return out

    def drain(self) -> list[np.ndarray]:
        """Every frame still in flight, oldest first."""
        out = []
        while self._pending:
            out.append(self._take())
        return out

    def _take(self) -> np.ndarray:
        buf = self._pending.popleft()
        buf.read_into(self._host)
        return self._host[::-1].copy()

    def release(self) -> None:
        for buf in self._buffers:
            buf.release()
        self._buffers = []
        self._pending.clear()
