"""A growable GL buffer of float32 instance rows, with the vertex arrays that read it."""

from __future__ import annotations

from collections.abc import Callable

import moderngl
import numpy as np


class Instances:
    """Rows of ``floats`` float32 each: a host array to fill and a GL buffer to upload into.

    ``make_vaos(buffer) -> {name: VertexArray}`` is called again whenever the buffer grows
    (capacity doubles), so callers always use ``vaos[name]``.
    """

    def __init__(self, ctx: moderngl.Context, floats: int,
                 make_vaos: Callable[[moderngl.Buffer], dict], capacity: int = 1024) -> None:
        self.ctx, self.floats, self.make_vaos = ctx, floats, make_vaos
        self.capacity = 0
        self.buffer: moderngl.Buffer | None = None
        self.vaos: dict = {}
        self.host = np.zeros((0, floats), np.float32)
        self.reserve(capacity)

    def reserve(self, rows: int) -> None:
        """Make room for ``rows`` rows (host and GL); keeps nothing already written."""
        if rows <= self.capacity:
            return
        self.capacity = max(rows, 2 * self.capacity)
        self.host = np.zeros((self.capacity, self.floats), np.float32)
        self._release_gl()
        self.buffer = self.ctx.buffer(reserve=self.capacity * self.floats * 4, dynamic=True)
        self.vaos = self.make_vaos(self.buffer)

    def upload(self, rows: int) -> None:
        """Send the first ``rows`` host rows to the GL buffer."""
        if rows:
            self.buffer.write(memoryview(self.host[:rows]))

    def put(self, data: np.ndarray) -> int:
        """Copy ``data`` (rows × floats) in and upload it; returns the row count."""
        self.reserve(len(data))
        self.host[: len(data)] = data
        self.upload(len(data))
        return len(data)

    def _release_gl(self) -> None:
        for vao in self.vaos.values():
            vao.release()
        self.vaos = {}
        if self.buffer is not None:
            self.buffer.release()
            self.buffer = None

    def release(self) -> None:
        self._release_gl()
