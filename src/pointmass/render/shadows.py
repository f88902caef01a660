"""Blob shadows through a small top-down texture (the fake shadows of Cyclone's demos, soft).

Each frame, every sphere that is above the ground and low enough to cast a shadow is drawn
from above as one soft point sprite into a square texture that just covers them; overlapping
shadows combine as 1 - (1 - a)(1 - b). The ground shader multiplies its color by one minus
that darkness. The cost is one point per sphere in a 512² texture, not a blended quad per
sphere on screen, which is what a software rasterizer needs with 10 000 spheres.
"""

from __future__ import annotations

import moderngl
import numpy as np

from ..scene import Scene
from . import gather
from .instances import Instances

#: Texture side [texels].
TEXELS = 512
#: Above this many shadow casters only a TEXELS/2 square of the texture is used: a quarter of
#: the fragments, softer shadows (which crowds hide anyway).
CROWD = 4000
#: Largest shadow radius relative to the sphere radius (shadow_map.glsl: 1.3 + 0.7).
MAX_SPREAD = 2.0


class ShadowMap:
    """The shadow texture and the region of the ground [m] it covers."""

    def __init__(self, ctx: moderngl.Context, program: moderngl.Program) -> None:
        self.ctx, self.program = ctx, program
        self.texture = ctx.texture((TEXELS, TEXELS), 1)
        self.texture.filter = (moderngl.LINEAR, moderngl.LINEAR)
        self.texture.repeat_x = self.texture.repeat_y = False
        self.fbo = ctx.framebuffer([self.texture])
        self.boxes = Instances(ctx, gather.SPHERE_FLOATS, lambda buf: {
            "map": ctx.vertex_array(program, [(buf, "4f 12x 1f", "in_sphere", "in_glow")])},
            capacity=16)
        self.region = (0.0, 0.0, 0.0)
        """x0, z0 of the covered square's corner and its side [m]; side 0: no shadows."""
        self.used = TEXELS
        """Side of the texture's corner square in use [texels] (TEXELS, or half for crowds)."""

    def update(self, scene: Scene, rows: np.ndarray, vao: moderngl.VertexArray,
               strength: float) -> None:
        """Redraw the texture for this frame.

        Args:
            rows: The particles' sphere rows (N, 8) as uploaded (centre, radius, ..., glow);
                glowing ones are lights and cast no shadow.
            vao: Reads those rows with ``program`` (points).
            strength: Darkness of a resting sphere's shadow, in [0, 1].
        """
        ground = float(scene.ground_height)
        solid = [b for b in scene.boxes if not b.wireframe]
        box_rows = np.zeros((len(solid), gather.SPHERE_FLOATS), np.float32)
        if solid:
            # A box casts the blob of a ball of about its size.
            box_rows[:, 0:3] = [b.center for b in solid]
            box_rows[:, 3] = [0.75 * float(np.linalg.norm(b.half_size)) for b in solid]
        self.used = TEXELS if len(rows) <= CROWD else TEXELS // 2
        casters = rows[rows[:, 7] < 0.5, :4]
        self.region = _region(np.concatenate([casters, box_rows[:, :4]]), ground, self.used)
        if self.region[2] <= 0.0:
            return
        prev = self.ctx.fbo
        self.fbo.use()
        self.fbo.clear(0.0, 0.0, 0.0, 0.0)
        self.ctx.viewport = (0, 0, self.used, self.used)
        self.ctx.enable(moderngl.BLEND | moderngl.PROGRAM_POINT_SIZE)
        self.ctx.disable(moderngl.DEPTH_TEST)
        self.ctx.blend_func = moderngl.ONE, moderngl.ONE_MINUS_SRC_COLOR
        p = self.program
        p["u_region"].value = self.region
        p["u_texels"].value = float(self.used)
        p["u_ground"].value = ground
        p["u_strength"].value = float(strength)
        if len(rows):
            vao.render(moderngl.POINTS, vertices=len(rows))
        if solid:
            self.boxes.put(box_rows)
            self.boxes.vaos["map"].render(moderngl.POINTS, vertices=len(solid))
        self.ctx.blend_func = moderngl.DEFAULT_BLENDING
        self.ctx.disable(moderngl.BLEND)
        if prev is not None:
            prev.use()

    def release(self) -> None:
        self.boxes.release()
        self.fbo.release()
        self.texture.release()


def _region(spheres: np.ndarray, ground: float, texels: int) -> tuple[float, float, float]:
    """The square (x0, z0, side) [m] around every shadow cast; side 0 when none is."""
    x, y, z, r = (spheres[:, k] for k in range(4))
    cast = (r > 0) & (y >= ground) & (y - r - ground < 5.0 * r + 1.5)
    if not cast.any():
        return (0.0, 0.0, 0.0)
    spread = MAX_SPREAD * r[cast]
    lo_x, hi_x = float((x[cast] - spread).min()), float((x[cast] + spread).max())
    lo_z, hi_z = float((z[cast] - spread).min()), float((z[cast] + spread).max())
    # Wide enough that the biggest shadow stays under the point-size limit (255 px).
    side = max(hi_x - lo_x, hi_z - lo_z, 4.5 * float(spread.max()) * texels / 250.0 / 2.0)
    side *= 1.0 + 2.0 / texels                     # a texel of margin on each side
    cx, cz = 0.5 * (lo_x + hi_x), 0.5 * (lo_z + hi_z)
    return (cx - 0.5 * side, cz - 0.5 * side, side)
