"""Uniforms set only when their value changes: each write is a glUseProgram and a glUniform
from Python, and most of the renderer's uniforms (style constants, the sky's colors, the
viewport) are the same frame after frame.

Everything that writes a cached program's uniforms must go through the same cache, or the cache
would skip a write it believes was already made; the renderer's programs are its own.
"""

from __future__ import annotations

import numpy as np


class UniformCache:
    """The last value set per (program, uniform name)."""

    def __init__(self) -> None:
        self._last: dict[tuple[int, str], object] = {}

    def set(self, program, name: str, value) -> None:
        """``program[name]``'s value (a number, a tuple, or an array written as its bytes)."""
        key = (id(program), name)
        if isinstance(value, np.ndarray):
            value = value.tobytes()
            if self._last.get(key) != value:
                program[name].write(value)
                self._last[key] = value
        elif self._last.get(key) != value:
            program[name].value = value
            self._last[key] = value
