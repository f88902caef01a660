"""Projection on contacts measured again where the particles are now (Newton's method).

The projection stages move particles along each contact's normal *as it was generated*, with a
depth patched linearly (``kernels.py``): exact for planes, and for two particles as long as
their centre line hardly turns within the step. A link that swings fast does turn: a 0.3 m rod
turning 0.6 rad in a step is 18 % longer than the linear depth says, and the projection, pushing
along the old line, lengthens the neighbours it corrects (measured: a 30-link chain of 0.3 m
rods, pinned at one end and released level, reached 155 % link error at dt = 1/60; 0.2 % with
two substeps).

For a contact between two particles whose normal lies along their centre line (sphere pairs,
rods and cables: every generator of the library), the depth is a function of the distance
between the centres, so it can be measured again from the positions plus the displacements so
far, along the centre line as it is now. ``relinearize`` does that and writes a contact set
whose linear model is exact at the current displacements; projecting it again is one Newton
step on the non-linear position constraints, and repeating until nothing is left converges
where the particles move a lot (the chain above: every link within 1e-5 after 300 steps).
Anchored links are measured the same way from their anchor points (``ContactBuffer.anchors``);
planes keep their linear model (exact), as do contacts whose normal is not along the centre line
(a user's generator).
"""

from __future__ import annotations

import math

import numpy as np
from numba import njit

#: A normal counts as along the centre line when its cosine with it is within this of ±1.
ALONG_CENTRES = 1e-9


@njit(cache=True, nogil=True)
def relinearize(position, anchor, bod, con, n_out, depth0_out, depths_out, length_out):
    """Write, for each contact, a normal and a generated depth (``n_out``, ``depth0_out``) whose
    linear model ``depth0 - (disp_a - disp_b)·n`` gives its depth at the current displacements
    exactly, and that depth (``depths_out``); ``length_out``: for a link (a contact whose depth
    grows with the distance between its ends: a rod or cable) that distance now, else 0.
    ``position`` holds the positions the contacts were generated at (the solve moves them by
    ``bod.disp`` only at its end); ``anchor`` (M, 3) the scenery point of each contact against
    one (NaN: none), or (0, 3) when no contact has one.

    Returns the largest violation left: a penetration, or a bilateral contact's error either way."""
    ca, cb, n, depth0, bil, disp = con.a, con.b, con.n, con.depth0, con.bil, bod.disp
    anchored = anchor.shape[0] > 0
    worst = 0.0
    for c in range(ca.shape[0]):
        a = ca[c]
        b = cb[c]
        nx, ny, nz = n[c, 0], n[c, 1], n[c, 2]
        d0 = depth0[c]
        # The other end: a particle, an anchor point, or neither (a plane: linear is exact).
        if b >= 0:
            ox, oy, oz = position[b, 0], position[b, 1], position[b, 2]
            mx, my, mz = disp[b, 0], disp[b, 1], disp[b, 2]
            centred = True
        elif anchored and not math.isnan(anchor[c, 0]):
            ox, oy, oz = anchor[c, 0], anchor[c, 1], anchor[c, 2]
            mx, my, mz = 0.0, 0.0, 0.0
            centred = True
        else:
            ox, oy, oz = 0.0, 0.0, 0.0
            mx, my, mz = 0.0, 0.0, 0.0
            centred = False
        length_out[c] = 0.0
        if centred:
            gx = position[a, 0] - ox
            gy = position[a, 1] - oy
            gz = position[a, 2] - oz
            g = math.sqrt(gx * gx + gy * gy + gz * gz)
            cosine = (nx * gx + ny * gy + nz * gz) / g if g > 0.0 else 0.0
            if abs(abs(cosine) - 1.0) <= ALONG_CENTRES:
                # sign +1: n from b to a (a sphere pair: farther apart, shallower);
                # -1: n from a to b (a link: farther apart, deeper).
                sign = 1.0 if cosine > 0.0 else -1.0
                ux = gx + disp[a, 0] - mx
                uy = gy + disp[a, 1] - my
                uz = gz + disp[a, 2] - mz
                u = math.sqrt(ux * ux + uy * uy + uz * uz)
                if u > 0.0:
                    if sign < 0.0:
                        length_out[c] = u
                    depth = d0 - sign * (u - g)
                    nx, ny, nz = sign * ux / u, sign * uy / u, sign * uz / u
                    d0 = depth + ((disp[a, 0] - mx) * nx + (disp[a, 1] - my) * ny
                                  + (disp[a, 2] - mz) * nz)
        n_out[c, 0] = nx
        n_out[c, 1] = ny
        n_out[c, 2] = nz
        depth0_out[c] = d0
        depth = d0 - ((disp[a, 0] - mx) * nx + (disp[a, 1] - my) * ny + (disp[a, 2] - mz) * nz)
        depths_out[c] = depth
        worst = max(worst, abs(depth) if bil[c] else depth)
    return worst


@njit(cache=True, nogil=True)
def has_links(position, anchor, con):
    """Whether some contact is a link: its normal along the line between its ends but pointing
    from a to b (farther apart is deeper: a cable or rod), or measured from an anchor point.
    A pile's contacts push their ends apart, along n from b to a."""
    if anchor.shape[0] > 0:
        return True
    ca, cb, n = con.a, con.b, con.n
    for c in range(ca.shape[0]):
        a = ca[c]
        b = cb[c]
        if b >= 0 and ((position[a, 0] - position[b, 0]) * n[c, 0]
                       + (position[a, 1] - position[b, 1]) * n[c, 1]
                       + (position[a, 2] - position[b, 2]) * n[c, 2]) < 0.0:
            return True
    return False


@njit(cache=True, nogil=True)
def merit(depths, bil):
    """Σ violation² (a penetration, or a bilateral contact's error either way): what each
    Newton step of the re-measured projection must lower (its line search)."""
    total = 0.0
    for c in range(depths.shape[0]):
        d = depths[c]
        if bil[c]:
            total += d * d
        elif d > 0.0:
            total += d * d
    return total


#: The largest w·(λ/ℓ) a particle's metric takes (see ``stiff_metric``): a million times its
#: inverse mass is a direction as good as rigid, and keeps the 3×3 adjugate's cancellation
#: to ~1e-4 of a determinant ≥ 1.
STIFF_CAP = 1e6


@njit(cache=True, nogil=True)
def stiff_metric(parts, col, inv_mass, ca, cb, n, length, tension):
    """The inverse of each particle's metric for the Newton step (K, 3, 3): its mass plus the
    *geometric stiffness* of the links on it, m·I + Σ (λ/ℓ)(I − n·nᵀ) (the second derivative of
    a link's length, times its tension λ ≥ 0 [kg·m, a position multiplier], over its length ℓ;
    Tournier et al., "Stable Constrained Dynamics", 2015), block-diagonal: the coupling
    between a link's two ends is left out.

    Why: the plain step moves each particle by its inverse mass alone. A light particle between
    two loaded links that are nearly in line (a knee about to straighten) is then the cheapest
    thing to move, and the linear step throws it sideways by ~(error)/(2·√(m_light/m_load))
    (16× the error at 1000 : 1), where the lengths change to second order: Newton diverges
    (measured: the swinging 1000 kg chain, 25 iterations, 3 % → 3471 %). A link under tension
    λ resists turning in proportion to λ/ℓ, which is what the curvature term says; with it
    the knee stays in line and the load, not the knee, is moved."""
    k = parts.shape[0]
    stiff = np.zeros((k, 3, 3))
    for c in range(ca.shape[0]):
        if length[c] <= 0.0 or tension[c] <= 0.0:
            continue
        s = tension[c] / length[c]
        if not math.isfinite(s):
            continue
        for p_index in (ca[c], cb[c]):
            if p_index < 0:
                continue
            p = col[p_index]
            for i in range(3):
                for j in range(3):
                    stiff[p, i, j] += s * ((1.0 if i == j else 0.0) - n[c, i] * n[c, j])
    out = np.zeros((k, 3, 3))
    for p in range(k):
        w = inv_mass[parts[p]]
        if w <= 0.0:
            continue  # immovable: a zero block
        # w·(I + w·H)⁻¹, H the stiffness (a symmetric 3×3 inverse by its adjugate). w·H is
        # capped at STIFF_CAP: past it a direction is as good as rigid, and the adjugate of a
        # larger one lost the determinant to cancellation (0, then a division by zero: a
        # random force-free scene, hypothesis seed 733907, a link of a few µm under tension).
        largest = w * max(stiff[p, 0, 0], stiff[p, 1, 1], stiff[p, 2, 2])
        q = w if largest <= STIFF_CAP else w * STIFF_CAP / largest
        a00 = 1.0 + q * stiff[p, 0, 0]
        a11 = 1.0 + q * stiff[p, 1, 1]
        a22 = 1.0 + q * stiff[p, 2, 2]
        a01 = q * stiff[p, 0, 1]
        a02 = q * stiff[p, 0, 2]
        a12 = q * stiff[p, 1, 2]
        c00 = a11 * a22 - a12 * a12
        c01 = a02 * a12 - a01 * a22
        c02 = a01 * a12 - a02 * a11
        c11 = a00 * a22 - a02 * a02
        c12 = a01 * a02 - a00 * a12
        c22 = a00 * a11 - a01 * a01
        det = a00 * c00 + a01 * c01 + a02 * c02  # ≥ 1 in exact arithmetic (I + PSD)
        if not det > 0.5:
            continue  # not finite, or still lost: the particle waits for the next iteration
        f = w / det
        out[p, 0, 0] = c00 * f
        out[p, 0, 1] = out[p, 1, 0] = c01 * f
        out[p, 0, 2] = out[p, 2, 0] = c02 * f
        out[p, 1, 1] = c11 * f
        out[p, 1, 2] = out[p, 2, 1] = c12 * f
        out[p, 2, 2] = c22 * f
    return out
