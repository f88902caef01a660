"""Draws Dear ImGui's draw lists with moderngl (no PyOpenGL, no pyglet: works headless on EGL).

imgui-bundle's own backends draw through PyOpenGL, and moderngl-window's integration breaks on
ImGui ≥ 1.92 (moderngl-window #222), so we own this thin glue (viewer-notes, section 3). It
speaks ImGui 1.92's texture protocol (``renderer_has_textures``): ImGui asks for textures to be
created, updated in rectangles, or destroyed, and we keep a moderngl texture for each.
"""

from __future__ import annotations

import ctypes

import moderngl
import numpy as np
from imgui_bundle import imgui

_VS = """#version 330
uniform mat4 ProjMtx;
in vec2 Position;
in vec2 UV;
in vec4 Color;
out vec2 Frag_UV;
out vec4 Frag_Color;
void main() {
    Frag_UV = UV;
    Frag_Color = Color;
    gl_Position = ProjMtx * vec4(Position.xy, 0.0, 1.0);
}
"""

_FS = """#version 330
uniform sampler2D Texture;
in vec2 Frag_UV;
in vec4 Frag_Color;
out vec4 Out_Color;
void main() {
    Out_Color = Frag_Color * texture(Texture, Frag_UV.st);
}
"""


class ImguiRenderer:
    """Renders ``imgui.get_draw_data()`` into the bound framebuffer.

    Create it after ``imgui.create_context()`` and release it before destroying that context.
    The caller sets ``io.display_size`` and ``io.display_framebuffer_scale`` (the window does
    this from its window and framebuffer sizes; a headless test sets them once).
    """

    def __init__(self, ctx: moderngl.Context) -> None:
        self.ctx = ctx
        io = imgui.get_io()
        io.backend_flags |= imgui.BackendFlags_.renderer_has_textures
        self.prog = ctx.program(vertex_shader=_VS, fragment_shader=_FS)
        self.vbo = ctx.buffer(reserve=imgui.VERTEX_SIZE * 8192, dynamic=True)
        self.ibo = ctx.buffer(reserve=imgui.INDEX_SIZE * 16384, dynamic=True)
        self.vao = ctx.vertex_array(self.prog, [(self.vbo, "2f 2f 4f1", "Position", "UV",
                                                 "Color")],
                                    index_buffer=self.ibo, index_element_size=imgui.INDEX_SIZE)
        self.textures: dict[int, moderngl.Texture] = {}

    # -- textures (ImGui 1.92 protocol) ---------------------------------------------------------
    def _update_texture(self, tex) -> None:
        status = imgui.ImTextureStatus
        if tex.status == status.want_create:
            t = self.ctx.texture((tex.width, tex.height), 4,
                                 data=tex.get_pixels_array().tobytes())
            self.textures[t.glo] = t
            tex.set_tex_id(t.glo)
            tex.status = status.ok
        elif tex.status == status.want_updates:
            t = self.textures[tex.tex_id]
            px = tex.get_pixels_array().reshape(tex.height, tex.width, 4)
            for r in tex.updates:
                t.write(np.ascontiguousarray(px[r.y:r.y + r.h, r.x:r.x + r.w]),
                        viewport=(r.x, r.y, r.w, r.h))
            tex.status = status.ok
        elif tex.status == status.want_destroy:
            texture = self.textures.pop(tex.tex_id, None)
            if texture is not None:
                texture.release()
            tex.set_tex_id(0)
            tex.status = status.destroyed

    # -- drawing --------------------------------------------------------------------------------
    def render(self, draw_data) -> None:
        """Draw one frame's ImGui output over whatever the bound framebuffer holds."""
        for tex in imgui.get_platform_io().textures:
            if tex.status != imgui.ImTextureStatus.ok:
                self._update_texture(tex)
        io = imgui.get_io()
        (dw, dh), (sx, sy) = io.display_size, io.display_framebuffer_scale
        if dw <= 0 or dh <= 0:
            return
        fb_w, fb_h = int(dw * sx), int(dh * sy)
        draw_data.scale_clip_rects(imgui.ImVec2(sx, sy))
        proj = np.array([[2 / dw, 0, 0, 0], [0, -2 / dh, 0, 0], [0, 0, -1, 0], [-1, 1, 0, 1]],
                        "f4")
        self.prog["ProjMtx"].write(proj.tobytes())
        ctx = self.ctx
        ctx.enable_only(moderngl.BLEND)
        ctx.blend_func = (moderngl.SRC_ALPHA, moderngl.ONE_MINUS_SRC_ALPHA,
                          moderngl.ONE, moderngl.ONE_MINUS_SRC_ALPHA)
        ctx.viewport = (0, 0, fb_w, fb_h)
        for cl in draw_data.cmd_lists:
            nv = cl.vtx_buffer.size() * imgui.VERTEX_SIZE
            ni = cl.idx_buffer.size() * imgui.INDEX_SIZE
            if nv > self.vbo.size:
                self.vbo.orphan(nv * 2)
            if ni > self.ibo.size:
                self.ibo.orphan(ni * 2)
            self.vbo.write((ctypes.c_byte * nv).from_address(cl.vtx_buffer.data_address()))
            self.ibo.write((ctypes.c_byte * ni).from_address(cl.idx_buffer.data_address()))
            for cmd in cl.cmd_buffer:
                texture = self.textures.get(cmd.tex_ref.get_tex_id())
                if texture is None:
                    continue
                texture.use(0)
                x0, y0, x1, y1 = cmd.clip_rect
                if x1 <= x0 or y1 <= y0:
                    continue
                ctx.scissor = (int(x0), int(fb_h - y1), int(x1 - x0), int(y1 - y0))
                self.vao.render(moderngl.TRIANGLES, vertices=cmd.elem_count, first=cmd.idx_offset)
        ctx.scissor = None
        ctx.disable(moderngl.BLEND)

    def release(self) -> None:
        """Free every GL object (call before ``imgui.destroy_context``)."""
        for tex in imgui.get_platform_io().textures:
            tex.set_tex_id(0)
            tex.status = imgui.ImTextureStatus.destroyed
        for texture in self.textures.values():
            texture.release()
        self.textures.clear()
        for obj in (self.vao, self.vbo, self.ibo, self.prog):
            obj.release()
