"""Blob shadows through a small top-down texture (the fake shadows of Cyclone's demos, soft).

Each frame, every sphere that is above the ground and low enough to cast a shadow is splatted
as one soft disc into a square darkness map that just covers them (``shadow_splat``: on the
CPU, a caster costs its few texels and no GL primitive); overlapping shadows combine as
1 - (1 - a)(1 - b). The map is uploaded into a texture that shadow_overlay.glsl lays on the
ground: one pass however many shadows overlap on screen, which is what a software rasterizer
needs with 10 000 spheres.
"""

from __future__ import annotations

import moderngl
import numpy as np

from ..scene import Scene
from .shadow_splat import SPREAD_FAR, shadow_map, shadow_region

#: Texture side [texels].
TEXELS = 512
#: Above this many shadow casters only a TEXELS/2 square of the texture is used: a quarter of
#: the fragments, softer shadows (which crowds hide anyway).
CROWD = 4000
#: Largest shadow radius relative to the sphere radius.
MAX_SPREAD = SPREAD_FAR


def shadow_casters(frame, rows: np.ndarray) -> np.ndarray:
    """(N, 4) float32 sphere rows (centre, radius) of what casts a shadow in a frame (a
    ``FrameState``): the non-glowing spheres of ``rows`` (N, 8) and every solid box, as the blob
    of a ball of about its size."""
    return np.concatenate([rows[rows[:, 7] < 0.5, :4], ShadowMap.box_rows(frame)[:, :4]])


class ShadowMap:
    """The shadow texture and the region of the ground [m] it covers."""

    def __init__(self, ctx: moderngl.Context) -> None:
        self.ctx = ctx
        self.texture = ctx.texture((TEXELS, TEXELS), 1, dtype="f4")
        self.texture.filter = (moderngl.LINEAR, moderngl.LINEAR)
        self.texture.repeat_x = self.texture.repeat_y = False
        self.region = (0.0, 0.0, 0.0)
        """x0, z0 of the covered square's corner and its side [m]; side 0: no shadows."""
        self.used = TEXELS
        """Side of the texture's corner square in use [texels] (TEXELS, or half for crowds)."""

    def update(self, scene: Scene, rows: np.ndarray, strength: float) -> None:
        """Redraw the texture for this frame.

        Args:
            rows: The shadow casters' sphere rows (N, 8) (centre, radius, ..., glow);
                glowing ones are lights and cast no shadow.
            strength: Darkness of a resting sphere's shadow, in [0, 1].
        """
        ground = float(scene.shadow_height)      # where they fall: the ground or the water
        self.used = TEXELS if len(rows) <= CROWD else TEXELS // 2
        casters = shadow_casters(scene, rows)
        self.region = shadow_region(casters, ground, self.used)
        if self.region[2] <= 0.0:
            return
        dark = shadow_map(casters, self.region, ground, strength, self.used)
        self.texture.write(dark, viewport=(0, 0, self.used, self.used))

    @staticmethod
    def box_rows(scene) -> np.ndarray:
        """Sphere rows (8 floats: centre, radius, rgb, glow 0) of the balls whose blobs the
        solid boxes cast: a box casts the blob of a ball of about its size."""
        solid = [b for b in scene.boxes if not b.wireframe]
        rows = np.zeros((len(solid), 8), np.float32)
        if solid:
            rows[:, 0:3] = [b.center for b in solid]
            rows[:, 3] = [0.75 * float(np.linalg.norm(b.half_size)) for b in solid]
        return rows

    def release(self) -> None:
        self.texture.release()

