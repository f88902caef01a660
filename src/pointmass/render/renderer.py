"""The renderer: draws a Scene into one offscreen framebuffer.

A window blits ``renderer.fbo`` to its screen; screenshots, videos and notebook clips read it with
``read_rgb``. Nothing here reads the default framebuffer (Mesa leaves GL errors when one does).

Per frame: ``capture`` copies what to draw out of the scene (a ``FrameState``: every sphere
as centre, radius, color in float32 rows, every line), ``draw`` uploads it in one buffer each;
then the background and ground grid (kept from the last frame while the camera stays put),
sphere impostors, boxes and opaque planes, the blob shadows (a darkness map splatted on the
CPU, laid on the ground in one pass), lines, translucent planes, and last the glowing
particles and their trails, added onto the image (order-free, so never sorted). The hardware
path draws the ground and sky after the opaque things instead, so the GPU skips their hidden
fragments. The camera and light reach every program through one uniform buffer
(``frame_block``); other uniforms are set only when they change (``uniforms``).
"""

from __future__ import annotations

import math
import time
from pathlib import Path

import moderngl
import numpy as np

from ..scene import Scene
from . import gather, geometry, style
from .camera import OrbitCamera
from .frame import FrameState
from .frame_block import FrameUniforms
from .gpu_links import LinkBuffers
from .instances import Instances
from .look import LookTracker
from .particle_buffers import ParticleBuffers
from .path import choose_path
from .readback import AsyncReader
from .shaders import load_program
from .shadows import ShadowMap
from .uniforms import UniformCache

_QUAD = np.array([-1, -1, 1, -1, -1, 1, 1, 1], np.float32)       # triangle strip, [-1, 1]^2
_PROGRAMS = ("background", "ground", "spheres", "shadow_overlay", "lines", "mesh", "glow")
#: Stages of ``Renderer.stats`` (ms, the last frame): the renderer's own CPU work, apart from
#: the GL calls that draw (``draw_calls``: the driver's, where llvmpipe also rasterizes).
STAGES = ("capture", "shadows", "upload", "draw_calls")
_LINE_QUAD = np.array([0, -1, 1, -1, 0, 1, 1, 1], np.float32)    # along x, across y


class Renderer:
    """Draws scenes into ``fbo`` (an RGBA8 color texture plus depth) of ``size`` pixels.

    Args:
        ctx: A moderngl context (``create_headless_context()`` or a window's).
        size: Framebuffer (width, height) [px].
        samples: MSAA samples (0: none; llvmpipe renders fastest at 0). With samples > 0 the
            scene is drawn multisampled and resolved into ``fbo``.
        shader_dir: Where the ``.glsl`` files are (default: found automatically).
        path: "hardware" (particles in GPU buffers, shadows drawn by the GPU), "software"
            (sphere rows and CPU-splatted shadows, for llvmpipe) or "auto"; default
            ``$POINTMASS_RENDER_PATH``, else auto: software when the GL renderer is a software
            rasterizer (``path.py``).

    ``path`` says which was taken; ``stats`` holds the last frame's CPU milliseconds by stage
    (``STAGES``).
    """

    def __init__(self, ctx: moderngl.Context, size: tuple[int, int] = (1280, 720), *,
                 samples: int = 0, shader_dir: str | Path | None = None,
                 path: str | None = None) -> None:
        self.ctx = ctx
        self.samples = int(samples)
        self.path = choose_path(ctx, path)
        self.stats = dict.fromkeys(STAGES, 0.0)
        prog = {name: load_program(ctx, name, shader_dir) for name in _PROGRAMS}
        prog["lines_dashed"] = load_program(ctx, "lines", shader_dir, defines=("DASHED",))
        prog["mesh_instanced"] = load_program(ctx, "mesh", shader_dir, defines=("INSTANCED",))
        if self.path == "hardware":
            prog["shadow_blobs"] = load_program(ctx, "shadow_blobs", shader_dir)
            for name in ("spheres", "glow", "shadow_blobs"):
                prog[f"{name}_split"] = load_program(ctx, name, shader_dir, defines=("SPLIT",))
            prog["links"] = load_program(ctx, "links", shader_dir)
        self.programs = prog
        # The camera and light: one uniform buffer for every program; the programs' other
        # uniforms are set only when they change (uniforms.py).
        self._frame_block = FrameUniforms(ctx, prog.values())
        self._uniforms = UniformCache()
        self._quad = ctx.buffer(_QUAD.tobytes())
        self._line_quad = ctx.buffer(_LINE_QUAD.tobytes())
        self._cube = ctx.buffer(geometry.cube_mesh().tobytes())
        self._plane = ctx.buffer(geometry.quad_mesh().tobytes())
        self._vaos = {
            "background": ctx.vertex_array(prog["background"], []),
            "ground": ctx.vertex_array(prog["ground"], [(self._quad, "2f", "in_corner")]),
            "shadow_overlay": ctx.vertex_array(prog["shadow_overlay"],
                                               [(self._quad, "2f", "in_corner")]),
            "plane": ctx.vertex_array(prog["mesh"], [(self._plane, "3f 3f", "in_position",
                                                       "in_normal")]),
        }
        self._spheres = Instances(ctx, gather.SPHERE_FLOATS, lambda buf: {
            "spheres": ctx.vertex_array(prog["spheres"], [
                (self._quad, "2f", "in_corner"),
                (buf, "4f 4f/i", "in_sphere", "in_color")]),
            "glow": ctx.vertex_array(prog["glow"], [
                (self._quad, "2f", "in_corner"),
                (buf, "4f 4f/i", "in_sphere", "in_color")]),
        })
        # Solid boxes: one instanced draw of the cube for all (one draw call per box costs
        # llvmpipe ~0.1 ms each: 30 ms a frame in the box pit).
        self._boxes = Instances(ctx, geometry.BOX_FLOATS, lambda buf: {
            "boxes": ctx.vertex_array(prog["mesh_instanced"], [
                (self._cube, "3f 3f", "in_position", "in_normal"),
                (buf, "4f 4f 4f 4f/i", "in_model_x", "in_model_y", "in_model_z", "in_color")])},
            capacity=64)
        self._shadows = ShadowMap(ctx)
        self._particles = self._looks = self._casters = self._links = None
        if self.path == "hardware":
            self._particles = ParticleBuffers(ctx, prog, self._quad)
            self._links = LinkBuffers(ctx, prog["links"], self._line_quad)
            self._looks = LookTracker()
            # Shadow casters that are not particles (sphere bodies, boxes as balls).
            self._casters = Instances(ctx, gather.SPHERE_FLOATS, lambda buf: {
                "shadow_blobs": ctx.vertex_array(prog["shadow_blobs"], [
                    (self._quad, "2f", "in_corner"),
                    (buf, "4f 4f/i", "in_sphere", "in_color")])}, capacity=64)
        self._reader: AsyncReader | None = None
        def line_vaos(buf, program="lines"):
            return {"lines": ctx.vertex_array(prog[program], [
                (self._line_quad, "2f", "in_corner"),
                (buf, "3f 3f 4f 2f/i", "in_start", "in_end", "in_color", "in_style")])}

        self._lines = Instances(ctx, gather.LINE_FLOATS, line_vaos)
        # Dashed rows (slack cables and bungees) apart: only their program discards.
        self._dashed = Instances(ctx, gather.LINE_FLOATS,
                                 lambda buf: line_vaos(buf, "lines_dashed"), capacity=64)
        # Contacts and caller lines (a mouse spring) are drawn on top of everything: they
        # start inside the spheres they belong to.
        self._overlay = Instances(ctx, gather.LINE_FLOATS, line_vaos, capacity=64)
        # Trails of glowing particles: light streaks, blended additively with the sprites.
        self._glow_trails = Instances(ctx, gather.LINE_FLOATS, line_vaos, capacity=256)
        self.fbo: moderngl.Framebuffer | None = None
        self.color_texture: moderngl.Texture | None = None
        self._depth = None
        self._msaa = None
        self._read = None
        self._backdrop = None
        self._backdrop_key = None
        self.shadows = True
        """Draw the blob shadows (False: none; a measure of what they cost)."""
        self.cache_backdrop = self.path == "software"
        """Keep the sky and ground between frames while the camera stays put (no MSAA): the
        software path's saving. Not on the hardware path: there redrawing them costs well under
        a millisecond, while a depth buffer copied in (a blit) loses the GPU's hierarchical
        depth, so no hidden fragment is rejected early (a million spheres at 1080p on an H100:
        47 ms a frame with the copy, 13 without)."""
        self.size = (0, 0)
        self.resize(size)

    # -- framebuffers --------------------------------------------------------------------------
    def resize(self, size: tuple[int, int]) -> None:
        """Make the framebuffer (width, height) pixels (no-op when unchanged)."""
        w, h = int(size[0]), int(size[1])
        if w < 1 or h < 1:
            raise ValueError(f"framebuffer size must be at least 1x1, got {size}")
        if (w, h) == self.size:
            return
        self._release_targets()
        self.size = (w, h)
        self.color_texture = self.ctx.texture((w, h), 4)
        self._depth = self.ctx.depth_renderbuffer((w, h))
        self.fbo = self.ctx.framebuffer([self.color_texture], self._depth)
        if self.samples > 0:
            self._msaa = self.ctx.framebuffer(
                [self.ctx.renderbuffer((w, h), 4, samples=self.samples)],
                self.ctx.depth_renderbuffer((w, h), samples=self.samples))
        self._read = np.empty((h, w, 3), np.uint8)
        self._backdrop = self.ctx.framebuffer([self.ctx.texture((w, h), 4)],
                                              self.ctx.depth_renderbuffer((w, h)))
        self._backdrop_key = None

    def _release_targets(self) -> None:
        # Never leave a deleted framebuffer bound: moderngl rebinds "the current one" after
        # making the next, which is then GL_INVALID_OPERATION.
        if self.fbo is not None and self.ctx.fbo in (self.fbo, self._msaa):
            default = self.ctx.screen or self.ctx.detect_framebuffer(0)
            default.use()
        if self._msaa is not None:
            for att in (*self._msaa.color_attachments, self._msaa.depth_attachment):
                att.release()
            self._msaa.release()
            self._msaa = None
        if self._backdrop is not None:
            if self.ctx.fbo is self._backdrop:
                (self.ctx.screen or self.ctx.detect_framebuffer(0)).use()
            for att in (*self._backdrop.color_attachments, self._backdrop.depth_attachment):
                att.release()
            self._backdrop.release()
            self._backdrop = None
        for obj in (self.fbo, self.color_texture, self._depth):
            if obj is not None:
                obj.release()

    # -- drawing -------------------------------------------------------------------------------
    def render(self, scene: Scene, camera: OrbitCamera, *, trails=None,
               show_contacts: bool = False, extra_lines=None) -> None:
        """Draw ``scene`` as seen by ``camera`` into ``fbo`` (``draw(capture(scene))``).

        Args:
            trails: The running Simulation's ``Trails`` (recorded paths of ``scene.trails``), or
                None to draw none.
            show_contacts: Also draw the world's current contacts (a short line along each
                normal).
            extra_lines: Optional list of (start (3,), end (3,), rgb) [m], e.g. a mouse spring.
        """
        self.draw(self.capture(scene, trails=trails, show_contacts=show_contacts,
                               extra_lines=extra_lines), camera)

    def capture(self, scene: Scene, *, trails=None, show_contacts: bool = False,
                extra_lines=None) -> FrameState:
        """What ``render`` would draw of ``scene`` now, copied (``FrameState``): draw it later
        with ``draw``, while the simulation steps on (the window does)."""
        t0 = time.perf_counter()
        frame = FrameState.capture(scene, trails=trails, show_contacts=show_contacts,
                                   extra_lines=extra_lines,
                                   width_scale=max(1.0, self.size[1] / 720.0),
                                   looks=self._looks)
        self.stats["capture"] = 1e3 * (time.perf_counter() - t0)
        return frame

    def draw(self, frame: FrameState, camera: OrbitCamera) -> None:
        """Draw a captured frame as seen by ``camera`` into ``fbo``."""
        ctx = self.ctx
        w, h = self.size
        view = camera.view_matrix()
        proj = camera.projection_matrix(w / h)
        vp = (view @ proj).astype(np.float32)
        rot = view[:3, :3].astype(np.float64)           # world -> eye rotation (row vectors)
        light_world = rot @ style.LIGHT_EYE              # eye -> world: v @ rot.T
        sky_eye = np.array([0.0, 1.0, 0.0]) @ rot

        t0 = time.perf_counter()
        hardware = frame.positions is not None
        if hardware:
            if self._particles is None:
                raise ValueError("a hardware-path frame given to a software-path renderer")
            self._particles.upload(frame.positions, frame.look)
            if frame.look is not None:
                self._looks.drawn(frame.look)
        # One write of the camera and light for every program (frame_block.py).
        self._frame_block.write(view, proj, vp, style.LIGHT_EYE, sky_eye, light_world,
                                (float(w), float(h)), max(1.0, h / 720.0))
        n_spheres = self._spheres.put(frame.spheres) if len(frame.spheres) else 0
        n_links = self._links.sync(frame.gpu_links) if hardware else 0
        n_dashed = n_lines = 0
        if len(frame.lines):
            dashed = frame.lines[:, 11] > 0.0
            n_dashed = self._dashed.put(frame.lines[dashed]) if dashed.any() else 0
            n_lines = self._lines.put(frame.lines[~dashed] if n_dashed else frame.lines) \
                if len(frame.lines) > n_dashed else 0
        n_glow_trails = self._glow_trails.put(frame.glow_trails) if len(frame.glow_trails) \
            else 0
        n_glow = int(self._spheres.host[:n_spheres, 7].sum()) if n_spheres else 0
        glow_particles = hardware and self._particles.glowing
        n_overlay = self._overlay.put(frame.overlay) if len(frame.overlay) else 0
        scene = frame                                # the backdrop, boxes and planes
        t1 = time.perf_counter()
        n_casters = 0
        shadows = scene.show_ground and self.shadows
        if shadows:
            n = frame.particles                      # anchors cast no shadow
            if hardware:
                parts = [p for p in (self._spheres.host[:n], self._shadows.box_rows(scene),
                                     frame.body_casters) if p is not None and len(p)]
                if parts:
                    n_casters = self._casters.put(np.concatenate(parts))
            else:
                self._shadows.update(scene, self._spheres.host[:n], style.SHADOW_STRENGTH)
        t2 = time.perf_counter()
        self.stats["upload"] = 1e3 * (t1 - t0)
        self.stats["shadows"] = 1e3 * (t2 - t1)

        target = self._msaa if self._msaa is not None else self.fbo
        cached = not hardware and self._msaa is None and self.cache_backdrop
        if cached:
            # The backdrop (sky and ground grid) only changes with the camera and the ground,
            # so it is drawn once into a cache and copied (color and depth) while they stay
            # put: a recording or a still camera pays one copy per frame instead of two
            # full-screen passes.
            key = (view.tobytes(), proj.tobytes(), bool(scene.show_ground),
                   float(scene.ground_height), scene.sky)
            if key != self._backdrop_key:
                self._clear(self._backdrop, scene)
                ctx.enable(moderngl.DEPTH_TEST)
                ctx.disable(moderngl.BLEND | moderngl.CULL_FACE)
                self._draw_backdrop(scene, camera)
                self._backdrop_key = key
            ctx.copy_framebuffer(target, self._backdrop)
            target.use()
            ctx.viewport = (0, 0, w, h)
        else:
            self._clear(target, scene)
        ctx.enable(moderngl.DEPTH_TEST)
        ctx.disable(moderngl.BLEND | moderngl.CULL_FACE)
        if not cached and not hardware:
            self._draw_backdrop(scene, camera)
        if n_spheres:
            self._spheres.vaos["spheres"].render(moderngl.TRIANGLE_STRIP, vertices=4,
                                                 instances=n_spheres)
        if hardware and self._particles.count:
            self._particles.draw("spheres", self._uniforms)
        self._draw_meshes(scene, translucent=False)
        if hardware:
            # The hardware path draws the backdrop after the opaque things: the GPU then
            # rejects the ground's and sky's fragments hidden behind them before shading them.
            self._draw_backdrop(scene, camera)

        ctx.enable(moderngl.BLEND)
        if hardware and shadows:
            self._draw_shadow_blobs(target, scene, n_casters)
        elif shadows and self._shadows.region[2] > 0:
            # Shadows after the spheres: ground hidden behind a sphere is skipped early.
            target.depth_mask = False
            so = self.programs["shadow_overlay"]
            u = self._uniforms
            u.set(so, "u_shadow_region", self._shadows.region)
            u.set(so, "u_ground", float(scene.shadow_height))
            u.set(so, "u_shadow", 0)
            u.set(so, "u_uv_scale", self._shadows.used / self._shadows.texture.width)
            self._shadows.texture.use(0)
            self._vaos["shadow_overlay"].render(moderngl.TRIANGLE_STRIP, vertices=4)
            target.depth_mask = True
        if n_lines or n_dashed:
            for lines, n in ((self._lines, n_lines), (self._dashed, n_dashed)):
                if n:
                    self._uniforms.set(lines.vaos["lines"].program, "u_caps", 1.0)
                    lines.vaos["lines"].render(moderngl.TRIANGLE_STRIP, vertices=4,
                                               instances=n)
        if n_links:
            self._uniforms.set(self.programs["links"], "u_positions", 0)
            self._particles.positions_texture().use(0)
            self._links.draw()
        # Translucent planes, glow and the overlay test depth but do not write it.
        translucent = any(len(p.color) == 4 and p.color[3] < 1.0 for p in scene.planes)
        if translucent or n_glow or n_glow_trails or glow_particles or n_overlay:
            target.depth_mask = False
            self._draw_meshes(scene, translucent=True)
            if n_glow or n_glow_trails or glow_particles:
                self._draw_glow(n_spheres if n_glow else 0, n_glow_trails, glow_particles)
            if n_overlay:
                ctx.disable(moderngl.DEPTH_TEST)
                self._uniforms.set(self.programs["lines"], "u_caps", 1.0)
                self._overlay.vaos["lines"].render(moderngl.TRIANGLE_STRIP, vertices=4,
                                                   instances=n_overlay)
            target.depth_mask = True
        ctx.disable(moderngl.BLEND | moderngl.DEPTH_TEST | moderngl.PROGRAM_POINT_SIZE)

        if self._msaa is not None:
            ctx.copy_framebuffer(self.fbo, self._msaa)
        self.stats["draw_calls"] = 1e3 * (time.perf_counter() - t2)

    def _draw_shadow_blobs(self, target: moderngl.Framebuffer, scene: FrameState,
                           n_casters: int) -> None:
        """The hardware path's shadows: a soft disc on the ground per caster, multiplied into
        the image (after the spheres, so ground hidden behind them is skipped early)."""
        if not (n_casters or self._particles.count):
            return
        self.ctx.blend_func = moderngl.ZERO, moderngl.ONE_MINUS_SRC_ALPHA
        target.depth_mask = False
        for name in ("shadow_blobs", "shadow_blobs_split"):
            prog = self.programs[name]
            self._uniforms.set(prog, "u_ground", float(scene.shadow_height))  # or the water
            self._uniforms.set(prog, "u_strength", float(style.SHADOW_STRENGTH))
        if n_casters:
            self._casters.vaos["shadow_blobs"].render(moderngl.TRIANGLE_STRIP, vertices=4,
                                                      instances=n_casters)
        self._particles.draw("shadow_blobs", self._uniforms)
        target.depth_mask = True
        self.ctx.blend_func = moderngl.DEFAULT_BLENDING

    def _draw_glow(self, n_spheres: int, n_trails: int, particles: bool = False) -> None:
        """Trails of glowing particles, then the particles (the sphere rows, of which glow.glsl
        keeps the glowing ones), added onto the image: depth tested but not written, so the
        ground and solid things still hide what is behind them."""
        ctx = self.ctx
        h = self.size[1]
        if n_trails:
            ctx.blend_func = moderngl.SRC_ALPHA, moderngl.ONE
            self._uniforms.set(self.programs["lines"], "u_caps", 0.0)
            self._glow_trails.vaos["lines"].render(moderngl.TRIANGLE_STRIP, vertices=4,
                                                   instances=n_trails)
        if n_spheres:
            ctx.blend_func = moderngl.ONE, moderngl.ONE
            _set_glow_uniforms(self._uniforms, self.programs["glow"], h)
            self._spheres.vaos["glow"].render(moderngl.TRIANGLE_STRIP, vertices=4,
                                              instances=n_spheres)
        if particles:
            ctx.blend_func = moderngl.ONE, moderngl.ONE
            _set_glow_uniforms(self._uniforms, self.programs["glow_split"], h)
            self._particles.draw("glow", self._uniforms)
        ctx.blend_func = moderngl.DEFAULT_BLENDING

    def _clear(self, fbo: moderngl.Framebuffer, scene: FrameState) -> None:
        """Bind ``fbo`` and clear it to the sky's top color and the far depth."""
        fbo.use()
        self.ctx.viewport = (0, 0, *self.size)
        fbo.depth_mask = True
        self.ctx.clear(*style.sky(scene.sky).top, 1.0, depth=1.0)

    def _draw_backdrop(self, scene: FrameState, camera: OrbitCamera) -> None:
        """Draw the ground grid and the sky gradient into the bound framebuffer: the sky only
        where nothing was drawn yet (the far plane, depth test <=)."""
        ctx = self.ctx
        sky = style.sky(scene.sky)
        if scene.show_ground:
            self._draw_ground(scene, camera, sky)
        ctx.depth_func = "<="
        bg = self.programs["background"]
        self._uniforms.set(bg, "u_top", sky.top)
        self._uniforms.set(bg, "u_bottom", sky.horizon)
        self._vaos["background"].render(moderngl.TRIANGLE_STRIP, vertices=3)
        ctx.depth_func = "<"

    def _draw_ground(self, scene: FrameState, camera: OrbitCamera, sky: style.Sky) -> None:
        g = self.programs["ground"]
        u = self._uniforms
        t = camera.target
        u.set(g, "u_center", (float(t[0]), float(scene.ground_height), float(t[2])))
        u.set(g, "u_extent", float(max(30.0, 8.0 * camera.distance)))
        # 1 m cells from 5 m to 50 m away, 10 cm closer, 10 m further.
        u.set(g, "u_spacing", float(10.0 ** math.floor(math.log10(max(camera.distance, 1e-3)
                                                                  / 5.0))))
        u.set(g, "u_base", sky.ground_base)
        u.set(g, "u_line", sky.ground_line)
        u.set(g, "u_fog", sky.horizon)
        self._vaos["ground"].render(moderngl.TRIANGLE_STRIP, vertices=4)

    def _draw_meshes(self, scene: FrameState, translucent: bool) -> None:
        if not translucent:
            rows = None
            solid = [b for b in scene.boxes if not b.wireframe]
            if solid:
                rows = geometry.box_instances(solid)
            if scene.body_boxes is not None and len(scene.body_boxes):
                rows = scene.body_boxes if rows is None else \
                    np.concatenate([rows, scene.body_boxes])
            if rows is not None and len(rows):
                n = self._boxes.put(rows)
                self._boxes.vaos["boxes"].render(moderngl.TRIANGLES, instances=n)
        if not scene.planes:
            return
        mesh = self.programs["mesh"]
        for p in scene.planes:
            rgba = tuple(p.color) if len(p.color) == 4 else (*p.color, 1.0)
            if (rgba[3] < 1.0) == translucent:
                model = geometry.plane_model(p.center, p.normal, p.half_size)
                mesh["u_model"].write(geometry.gl_matrix(model))
                mesh["u_color"].value = tuple(float(x) for x in rgba)
                self._vaos["plane"].render(moderngl.TRIANGLES)

    # -- reading -------------------------------------------------------------------------------
    def read_rgb(self) -> np.ndarray:
        """The last rendered image, (H, W, 3) uint8, top row first (a new array)."""
        self.fbo.read_into(self._read, components=3, alignment=1)
        return self._read[::-1].copy()

    def read_rgb_later(self) -> np.ndarray | None:
        """Start reading the last rendered image into a pixel-buffer object and return the
        image started ``AsyncReader.DEPTH - 1`` calls ago (None until there is one): the GPU
        copies while the CPU goes on, so a recording waits on neither. ``read_pending()``
        returns what is still in flight, oldest first."""
        if self._reader is None or self._reader.size != self.size:
            self._reader = self._replace_reader()
        return self._reader.push(self.fbo)

    def read_pending(self) -> list[np.ndarray]:
        """The images ``read_rgb_later`` started and has not returned yet, oldest first."""
        if self._reader is None:
            return []
        return self._reader.drain()

    def _replace_reader(self) -> AsyncReader:
        if self._reader is not None:
            self._reader.release()
        return AsyncReader(self.ctx, self.size)

    def release(self) -> None:
        """Free every GL object this renderer made."""
        self._release_targets()
        self._spheres.release()
        self._shadows.release()
        self._frame_block.release()
        for part in (self._particles, self._casters, self._reader, self._links):
            if part is not None:
                part.release()
        self._lines.release()
        self._dashed.release()
        self._boxes.release()
        self._overlay.release()
        self._glow_trails.release()
        for vao in self._vaos.values():
            vao.release()
        for buf in (self._quad, self._line_quad, self._cube, self._plane):
            buf.release()
        for p in self.programs.values():
            p.release()
        self.fbo = self.color_texture = None


def _set_glow_uniforms(uniforms, program: moderngl.Program, h: int) -> None:
    """The glow's own uniforms (the camera is the Frame block's), the same for the sphere
    rows' program and the particle buffers'."""
    uniforms.set(program, "u_min_core", style.GLOW_MIN_CORE * max(0.5, h / 720.0))
    uniforms.set(program, "u_halo", style.GLOW_HALO)
    uniforms.set(program, "u_halo_gain", style.GLOW_HALO_GAIN)
