"""Blob shadows splatted on the CPU into a small top-down darkness map (no GL).

One soft disc per shadow caster, widening and fading with its height above the ground, drawn
as a point sprite would be (texel centres inside the disc), overlaps combined as
1 - (1 - a)(1 - b). On a software rasterizer each GL point costs a primitive set-up however few
texels it covers; here a caster costs only its texels (about 20 for a 12 cm ball over a 24 m
crowd), so 10 000 shadows take a fraction of a millisecond instead of several.
"""

from __future__ import annotations

import math

import numpy as np
from numba import njit

#: Height over which a resting sphere's shadow fades out: 5 radii plus this [m].
FADE_REACH = 1.5
#: Shadow radius relative to the sphere radius, resting (fade 1) and at the fade's end.
SPREAD_NEAR, SPREAD_FAR = 1.3, 2.0


@njit(cache=True, nogil=True)
def splat(spheres, region, ground, strength, out):
    """Darken ``out`` with the blob shadow of every sphere row.

    Args:
        spheres: (N, >=4) float32 rows: centre x, y, z [m], radius [m]; a radius <= 0, a
            centre below ``ground`` or one too high to cast leaves no shadow.
        region: (x0, z0, side) [m]: the ground square ``out`` covers, texel (i, j) centred at
            x = x0 + (j + 0.5) side / T, z = z0 + (i + 0.5) side / T, T = out.shape[0].
        ground: Ground height [m].
        strength: Darkness right under a sphere resting on the ground, in [0, 1].
        out: (T, T) float32 darkness in [0, 1], updated in place (clear it first).
    """
    texels = out.shape[0]
    x0, z0, side = region[0], region[1], region[2]
    scale = texels / side                       # texels per metre
    for k in range(spheres.shape[0]):
        r = spheres[k, 3]
        y = spheres[k, 1]
        if r <= 0.0 or y < ground:
            continue
        fade = 1.0 - (y - r - ground) / (5.0 * r + FADE_REACH)
        if fade <= 0.0:
            continue
        fade = min(fade, 1.0)
        alpha = strength * fade
        # Radius in texels, at least half a texel (GL's smallest point is one texel wide).
        rad = max(r * (SPREAD_NEAR + (SPREAD_FAR - SPREAD_NEAR) * (1.0 - fade)) * scale, 0.5)
        cu = (spheres[k, 0] - x0) * scale       # centre in texel units (texel j spans [j, j+1))
        cv = (spheres[k, 2] - z0) * scale
        j0 = max(math.ceil(cu - rad - 0.5), 0)
        j1 = min(math.floor(cu + rad - 0.5), texels - 1)
        i0 = max(math.ceil(cv - rad - 0.5), 0)
        i1 = min(math.floor(cv + rad - 0.5), texels - 1)
        inv = 1.0 / rad
        for i in range(i0, i1 + 1):
            dv = (i + 0.5 - cv) * inv
            for j in range(j0, j1 + 1):
                du = (j + 0.5 - cu) * inv
                q = du * du + dv * dv
                if q >= 1.0:
                    continue
                a = alpha * (1.0 - q) * (1.0 - 0.5 * q)
                out[i, j] = a + out[i, j] * (1.0 - a)


@njit(cache=True, nogil=True)
def shadow_region(spheres, ground, texels):
    """The ground square (x0, z0, side) [m] around every shadow ``splat`` would draw (side 0
    when none is cast), in one pass over the (N, >=4) sphere rows.

    Wide enough that the biggest shadow spans at most ~250 texels: soft enough, and the look of
    the GL point sprites this map was first drawn with (their size limit); a texel of margin on
    each side.
    """
    lo_x = lo_z = math.inf
    hi_x = hi_z = -math.inf
    widest = 0.0
    for k in range(spheres.shape[0]):
        x, y, z, r = spheres[k, 0], spheres[k, 1], spheres[k, 2], spheres[k, 3]
        if not (r > 0.0 and y >= ground and y - r - ground < 5.0 * r + FADE_REACH):
            continue
        spread = SPREAD_FAR * r
        lo_x, hi_x = min(lo_x, x - spread), max(hi_x, x + spread)
        lo_z, hi_z = min(lo_z, z - spread), max(hi_z, z + spread)
        widest = max(widest, spread)
    if widest == 0.0:
        return 0.0, 0.0, 0.0
    side = max(hi_x - lo_x, hi_z - lo_z, 4.5 * widest * texels / 250.0 / 2.0)
    side *= 1.0 + 2.0 / texels
    return 0.5 * (lo_x + hi_x) - 0.5 * side, 0.5 * (lo_z + hi_z) - 0.5 * side, side


def shadow_map(spheres: np.ndarray, region, ground: float, strength: float,
               texels: int) -> np.ndarray:
    """A new (texels, texels) float32 darkness map of ``spheres`` over ``region`` (see
    ``splat``)."""
    out = np.zeros((texels, texels), np.float32)
    splat(np.ascontiguousarray(spheres, np.float32), np.asarray(region, np.float64),
          float(ground), float(strength), out)
    return out


def warm() -> None:
    """Compile (or load) these kernels for the renderer's argument types, in the calling
    thread: a recording and a window call it in their physics worker before the first frame,
    so no kernel compiles in the main thread (where it held off Ctrl-C for seconds)."""
    casters = np.array([[0.0, 0.5, 0.0, 0.5]], np.float32)   # ShadowMap's rows: float32
    shadow_map(casters, shadow_region(casters, 0.0, 64), 0.0, 0.5, 64)
