"""The particles on the GPU (the hardware path): position buffers refilled every frame and a
look buffer (radius, color) refilled only when the look changes, read by the sphere, glow and
shadow programs' SPLIT variants, one instanced draw each.

Positions go round a ring of ``RING`` buffers, one per frame: a frame writes the buffer the
GPU last read ``RING`` frames ago, long done, so the upload never waits for the GPU, and no
storage is reallocated (orphaning reallocates each frame: on llvmpipe that doubled the upload,
14 against 6.6 ms for 1 M positions).
"""

from __future__ import annotations

import moderngl
import numpy as np

from ..scene import default_colors
from .look import LOOK_DTYPE, ParticleLook
from .shadow_splat import FADE_REACH, SPREAD_FAR, SPREAD_NEAR

_PALETTE = default_colors(8).astype(np.float32)
#: Position buffers in the ring.
RING = 3
#: Width of the positions texture (links.glsl reads particle i at (i % width, i / width)); the
#: capacity is a multiple of it, so the texture is filled from a position buffer in one copy.
TEXTURE_WIDTH = 2048


class ParticleBuffers:
    """Position and look buffers for ``count`` particles, and the vertex arrays reading them.

    Args:
        programs: The renderer's programs; uses "spheres_split", "glow_split" and
            "shadow_blobs_split".
        quad: The unit quad's corner buffer (triangle strip).
    """

    def __init__(self, ctx: moderngl.Context, programs: dict, quad: moderngl.Buffer,
                 capacity: int = 1024) -> None:
        self.ctx, self.programs, self.quad = ctx, programs, quad
        self.capacity = 0
        self.count = 0
        self.palette = True
        self.glowing = False
        self.ring: list[moderngl.Buffer] = []
        self.look: moderngl.Buffer | None = None
        self.slot = 0
        """The ring's buffer holding this frame's positions."""
        self.vaos: list[dict[str, moderngl.VertexArray]] = []
        self.texture: moderngl.Texture | None = None
        self._texture_slot = -1
        self._reserve(capacity)
        for name in ("spheres_split", "glow_split"):
            programs[name]["u_palette_rgb"].write(_PALETTE.tobytes())
        blobs = programs["shadow_blobs_split"]
        for prog in (blobs, programs["shadow_blobs"]):
            prog["u_fade_reach"].value = FADE_REACH
            prog["u_spread"].value = (SPREAD_NEAR, SPREAD_FAR)

    def _reserve(self, rows: int) -> bool:
        """Room for ``rows`` particles; True when the buffers were remade (their look lost)."""
        if rows <= self.capacity:
            return False
        self.capacity = -(-max(rows, 2 * self.capacity) // TEXTURE_WIDTH) * TEXTURE_WIDTH
        self._release_gl()
        ctx, prog = self.ctx, self.programs
        self.ring = [ctx.buffer(reserve=12 * self.capacity, dynamic=True) for _ in range(RING)]
        self.look = ctx.buffer(reserve=LOOK_DTYPE.itemsize * self.capacity, dynamic=True)
        self.texture = ctx.texture((TEXTURE_WIDTH, self.capacity // TEXTURE_WIDTH), 3,
                                   dtype="f4")
        self.texture.filter = (moderngl.NEAREST, moderngl.NEAREST)
        self._texture_slot = -1
        self.vaos = []
        for positions in self.ring:
            split = [(positions, "3f/i", "in_center"),
                     (self.look, "1f 4f1/i", "in_radius", "in_rgba")]
            self.vaos.append({name: ctx.vertex_array(prog[f"{name}_split"],
                                                     [(self.quad, "2f", "in_corner"), *split])
                              for name in ("spheres", "glow", "shadow_blobs")})
        return True

    def upload(self, positions: np.ndarray, look: ParticleLook | None) -> None:
        """Send this frame's positions ((N, 3) float32) and, if it changed, the look.

        Raises:
            ValueError: when the particle count changed but no new look came with it.
        """
        n = len(positions)
        remade = self._reserve(n)
        if look is None and (remade or n != self.count):
            raise ValueError(f"{n} particles but a look for {self.count}: a new look must come "
                             "with a new count (LookTracker.reset after the buffers change)")
        self.count = n
        if n:
            self.slot = (self.slot + 1) % RING
            self.ring[self.slot].write(positions)
            self._texture_slot = -1
        if look is not None:
            if len(look.rows) != n:
                raise ValueError(f"look for {len(look.rows)} particles, positions for {n}")
            if n:
                self.look.write(look.rows)
            self.palette = look.palette
            self.glowing = look.glowing

    def positions_texture(self) -> moderngl.Texture:
        """The positions as a float texture (for links.glsl), copied on the GPU from this
        frame's position buffer the first time a frame asks."""
        if self._texture_slot != self.slot:
            rows = -(-max(self.count, 1) // TEXTURE_WIDTH)
            self.texture.write(self.ring[self.slot], viewport=(0, 0, TEXTURE_WIDTH, rows))
            self._texture_slot = self.slot
        return self.texture

    def draw(self, name: str, uniforms) -> None:
        """One instanced draw of every particle with the "spheres", "glow" or "shadow_blobs"
        program (its other uniforms set by the caller; ``uniforms`` the renderer's
        ``UniformCache``)."""
        if self.count:
            prog = self.programs[f"{name}_split"]
            if name != "shadow_blobs":
                uniforms.set(prog, "u_palette", bool(self.palette))
            self.vaos[self.slot][name].render(moderngl.TRIANGLE_STRIP, vertices=4,
                                              instances=self.count)

    def _release_gl(self) -> None:
        for vaos in self.vaos:
            for vao in vaos.values():
                vao.release()
        self.vaos = []
        for buf in (*self.ring, self.look, self.texture):
            if buf is not None:
                buf.release()
        self.ring, self.look, self.texture = [], None, None

    def release(self) -> None:
        self._release_gl()
