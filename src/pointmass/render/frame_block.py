"""The camera and light every program reads, in one uniform buffer (``Frame``), written once a
frame and bound once, instead of the same matrices written into each program one uniform at a
time (each a glUseProgram and a glUniform from Python: 8 programs × 2–4 uniforms a frame).

Shaders name it with the line ``#include <frame>``, which ``shaders.stage_sources`` replaces by
``FRAME_BLOCK``; its members keep the names the programs used as plain uniforms.
"""

from __future__ import annotations

import moderngl
import numpy as np

#: The block (std140: vec3s on 16-byte boundaries, a float in the padding of the first).
FRAME_BLOCK = """layout(std140) uniform Frame {
    mat4 u_view;          // world -> eye
    mat4 u_proj;          // eye -> clip
    mat4 u_view_proj;     // world -> clip
    vec3 u_light_eye;     // unit vector toward the light, eye space
    float u_width_scale;  // line widths' scale: framebuffer height / 720, at least 1
    vec3 u_sky;           // unit world-up, eye space
    vec3 u_light_world;   // unit vector toward the light, world space
    vec2 u_viewport;      // framebuffer size [px]
};
"""
#: Binding point of the block.
BINDING = 0
#: The block's size in float32s.
FLOATS = 64


def pack(view: np.ndarray, proj: np.ndarray, view_proj: np.ndarray, light_eye, sky,
         light_world, viewport: tuple[float, float], width_scale: float,
         out: np.ndarray | None = None) -> np.ndarray:
    """The block's bytes as (FLOATS,) float32: the (4, 4) matrices in pyrr's row-vector layout
    (whose bytes are the column-major mat4 GLSL reads), vectors of 3 and the viewport."""
    out = np.zeros(FLOATS, np.float32) if out is None else out
    out[0:16] = view.reshape(16)
    out[16:32] = proj.reshape(16)
    out[32:48] = view_proj.reshape(16)
    out[48:51] = light_eye
    out[51] = width_scale
    out[52:55] = sky
    out[56:59] = light_world
    out[60:62] = viewport
    return out


class FrameUniforms:
    """The block's buffer, bound to ``BINDING`` for every program that reads it."""

    def __init__(self, ctx: moderngl.Context, programs) -> None:
        self.buffer = ctx.buffer(reserve=4 * FLOATS, dynamic=True)
        self.host = np.zeros(FLOATS, np.float32)
        for prog in programs:
            block = prog.get("Frame", None)
            if block is not None:
                block.binding = BINDING

    def write(self, *args, **kwargs) -> None:
        """Pack (``pack``'s arguments) and upload, then bind the buffer (one write, one bind
        a frame; the bind because another renderer on the context may have bound its own)."""
        pack(*args, **kwargs, out=self.host)
        self.buffer.write(self.host)
        self.buffer.bind_to_uniform_block(BINDING)

    def release(self) -> None:
        self.buffer.release()
