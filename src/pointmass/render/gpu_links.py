"""Links between particle pairs on the hardware path: springs, bungees, cables and rods whose
both ends are particles become one instance buffer of (a, b, rest length, kind, width, dash),
uploaded when the set of links changes, drawn in one instanced call by links.glsl, which reads
the ends from the particles' positions on the GPU and computes each link's strain and color.

Anchored links (one end a fixed point) and joints stay line rows gathered on the CPU: there are
few of them, and their anchors may move.
"""

from __future__ import annotations

import moderngl
import numpy as np

from . import style

#: Kind codes of links.glsl.
KINDS = {"spring": 0, "bungee": 1, "cable": 2, "rod": 3}

LINK_DTYPE = np.dtype([("ends", np.int32, 2), ("link", np.float32, 4)])


def pair_links(generators) -> list:
    """The generators drawn by the GPU: a kind of KINDS, particle index arrays ``a`` and ``b``
    and a rest length per link (springs' ``rest_length``, links' ``lengths_target``), and no
    anchors."""
    out = []
    for gen in generators:
        if getattr(gen, "kind", None) not in KINDS:
            continue
        if getattr(gen, "a", None) is None or getattr(gen, "b", None) is None:
            continue
        anchors = getattr(gen, "_anchors", None)
        if anchors is not None and anchors() is not None:
            continue
        if _rest(gen) is None:
            continue
        out.append(gen)
    return out


def _rest(gen):
    rest = getattr(gen, "rest_length", None)
    if rest is None:
        rest = getattr(gen, "lengths_target", None)
    return rest


def link_rows(generators) -> np.ndarray:
    """The instance rows of ``pair_links`` generators (widths at 720 rows)."""
    parts = []
    for gen in generators:
        a = np.asarray(gen.a)
        rows = np.zeros(len(a), LINK_DTYPE)
        rows["ends"][:, 0] = a
        rows["ends"][:, 1] = np.asarray(gen.b)
        rows["link"][:, 0] = np.broadcast_to(np.asarray(_rest(gen), np.float64), (len(a),))
        rows["link"][:, 1] = KINDS[gen.kind]
        rows["link"][:, 2] = style.LINK_WIDTH[gen.kind]
        rows["link"][:, 3] = style.LINK_SLACK_DASH[gen.kind]
        parts.append(rows)
    return np.concatenate(parts) if parts else np.zeros(0, LINK_DTYPE)


def links_key(generators) -> tuple:
    """What identifies a set of links: the generators, their index and rest arrays."""
    return tuple((id(g), id(g.a), id(g.b), len(g.a), id(_rest(g))) for g in generators)


class LinkBuffers:
    """The links' instance buffer and vertex array (links.glsl)."""

    def __init__(self, ctx: moderngl.Context, program: moderngl.Program,
                 corners: moderngl.Buffer) -> None:
        self.ctx, self.program, self.corners = ctx, program, corners
        self.count = 0
        self.key: tuple | None = None
        self.buffer: moderngl.Buffer | None = None
        self.vao: moderngl.VertexArray | None = None
        program["u_strain_full"].value = float(style.STRAIN_FULL)
        for name, rgb in (("u_compressed", style.SPRING_COMPRESSED),
                          ("u_rest", style.SPRING_REST),
                          ("u_stretched", style.SPRING_STRETCHED),
                          ("u_bungee", style.BUNGEE_COLOR), ("u_cable", style.CABLE_COLOR),
                          ("u_rod", style.ROD_COLOR)):
            program[name].value = tuple(float(x) for x in rgb)

    def sync(self, generators) -> int:
        """Upload the links of ``generators`` (pair_links) if they changed; returns the count."""
        key = links_key(generators)
        if key != self.key:
            rows = link_rows(generators)
            self.key = key
            self.count = len(rows)
            if self.count:
                if self.buffer is None or self.buffer.size < rows.nbytes:
                    self._release_gl()
                    self.buffer = self.ctx.buffer(reserve=max(rows.nbytes, 1024))
                    self.vao = self.ctx.vertex_array(self.program, [
                        (self.corners, "2f", "in_corner"),
                        (self.buffer, "2i 4f/i", "in_ends", "in_link")])
                self.buffer.write(rows)
        return self.count

    def draw(self) -> None:
        if self.count:
            self.vao.render(moderngl.TRIANGLE_STRIP, vertices=4, instances=self.count)

    def _release_gl(self) -> None:
        for obj in (self.vao, self.buffer):
            if obj is not None:
                obj.release()
        self.vao = self.buffer = None

    def release(self) -> None:
        self._release_gl()
