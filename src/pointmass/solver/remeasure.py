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

from numba import njit

#: A normal counts as along the centre line when its cosine with it is within this of ±1.
ALONG_CENTRES = 1e-9


@njit(cache=True, nogil=True)
def relinearize(position, anchor, bod, con, n_out, depth0_out, depths_out):
    """Write, for each contact, a normal and a generated depth (``n_out``, ``depth0_out``) whose
    linear model ``depth0 - (disp_a - disp_b)·n`` gives its depth at the current displacements
    exactly, and that depth (``depths_out``). ``position`` holds the positions the contacts were
    generated at (the solve moves them by ``bod.disp`` only at its end); ``anchor`` (M, 3) the
    scenery point of each contact against one (NaN: none), or (0, 3) when no contact has one.

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
