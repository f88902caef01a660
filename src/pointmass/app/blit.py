"""Copies the renderer's colour texture to the window with a fullscreen triangle.

``ctx.copy_framebuffer(screen, fbo)`` blits colour *and* depth, and the window's depth format
(from the X visual) differs from the FBO's, which Mesa refuses with GL_INVALID_OPERATION. A
textured triangle has no such constraint and costs about the same.
"""

from __future__ import annotations

import moderngl

_VS = """#version 330
out vec2 uv;
void main() {
    vec2 p = vec2(float((gl_VertexID & 1) << 2) - 1.0, float((gl_VertexID & 2) << 1) - 1.0);
    uv = p * 0.5 + 0.5;
    gl_Position = vec4(p, 0.0, 1.0);
}
"""

_FS = """#version 330
uniform sampler2D image;
in vec2 uv;
out vec4 color;
void main() {
    color = vec4(texture(image, uv).rgb, 1.0);
}
"""


class Blitter:
    """Draws a texture over the whole bound framebuffer."""

    def __init__(self, ctx: moderngl.Context) -> None:
        self.ctx = ctx
        self.prog = ctx.program(vertex_shader=_VS, fragment_shader=_FS)
        self.vao = ctx.vertex_array(self.prog, [])

    def draw(self, texture: moderngl.Texture, target: moderngl.Framebuffer, *,
             x: int = 0) -> None:
        """Draw ``texture`` at its own size, ``x`` pixels from the target's left edge."""
        target.use()
        self.ctx.viewport = (x, 0, *texture.size)
        self.ctx.disable(moderngl.DEPTH_TEST | moderngl.BLEND)
        texture.filter = (moderngl.NEAREST, moderngl.NEAREST)
        texture.use(0)
        self.vao.render(moderngl.TRIANGLES, vertices=3)

    def release(self) -> None:
        self.vao.release()
        self.prog.release()
