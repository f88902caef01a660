"""A frozen copy of what the renderer reads from a Scene: one frame's state, drawable later.

``FrameState.capture`` pulls every sphere, line and piece of geometry the renderer draws out of
a Scene (and its Simulation's trails) into arrays and copies of its own. Nothing in it refers
back to the world, so once captured the simulation may step on in another thread while the
frame is drawn (the window does: ``pointmass.app.viewer``). ``Renderer.render(scene)`` is
``Renderer.draw(capture(scene))``: one path for every caller, so a frame drawn from a capture
and one drawn at once are the same pixels.
"""

from __future__ import annotations

import dataclasses
from dataclasses import dataclass

import numpy as np
from numba import njit, prange

from ..scene import BoxVisual, PlaneVisual, Scene
from . import bodies as body_visuals
from . import gather, geometry, manifolds
from .gpu_links import pair_links
from .look import LookTracker, ParticleLook
from .picking import drawn_radii

_NO_LINES = np.zeros((0, gather.LINE_FLOATS), np.float32)


@njit(cache=True, parallel=True, nogil=True)
def _to_float32(src, out):
    # The hardware path's one pass over the particles per frame, on every core (numpy's
    # astype is one thread: 5 ms for a million positions on a 16-core GPU host).
    for i in prange(src.shape[0]):
        out[i, 0] = src[i, 0]
        out[i, 1] = src[i, 1]
        out[i, 2] = src[i, 2]


def positions_float32(position: np.ndarray) -> np.ndarray:
    """A float32 copy of (N, 3) positions."""
    out = np.empty(position.shape, np.float32)
    if len(position) >= 65_536:
        _to_float32(position, out)
    else:
        out[:] = position
    return out


@dataclass(frozen=True)
class FrameState:
    """One frame of a scene, as the renderer draws it.

    Attributes:
        time: The world's clock when it was captured [s].
        particles: How many of the sphere rows cast shadows: particles and sphere bodies (spin
            markers and anchor markers follow).
        spheres: Sphere rows (``gather.SPHERE_FLOATS`` float32 each): particles, sphere bodies,
            their spin markers, anchors.
        lines: Line rows (``gather.LINE_FLOATS``): links, plain trails, box edges.
        glow_trails: Line rows of glowing particles' trails (added onto the image).
        overlay: Line rows drawn over everything: contacts (when shown: particles', rigid
            manifolds' points, normals and outlines), caller lines.
        boxes, planes: Copies of the scene's boxes and planes.
        show_ground, ground_height, sky: The scene's backdrop.
        positions: The hardware path's particle positions ((N, 3) float32, the one copy of
            the particles it makes per frame), or None (the software path: the particles
            are the first sphere rows). With them ``spheres`` holds only the rest (sphere
            bodies, their markers, anchors) and ``particles`` counts the casters among those.
        look: The hardware path's particle look when it changed since the last frame drawn
            (``look.ParticleLook``), else None.
        gpu_links: The hardware path's links between particle pairs (``gpu_links``), drawn
            from the GPU's positions; ``lines`` then holds only the others.
        body_boxes, body_casters: The hardware path's box bodies as box instance rows and as
            shadow casters, made from the bodies' arrays (``bodies.body_arrays``); ``boxes``
            then holds only the scene's own boxes. None on the software path.
        shadow_height: Where the blob shadows fall [m] (the scene's, or its ground).
    """

    time: float
    particles: int
    spheres: np.ndarray
    lines: np.ndarray
    glow_trails: np.ndarray
    overlay: np.ndarray
    boxes: tuple[BoxVisual, ...]
    planes: tuple[PlaneVisual, ...]
    show_ground: bool
    ground_height: float
    sky: object
    positions: np.ndarray | None = None
    look: ParticleLook | None = None
    gpu_links: tuple = ()
    body_boxes: np.ndarray | None = None
    body_casters: np.ndarray | None = None
    shadow_height: float = 0.0

    @classmethod
    def capture(cls, scene: Scene, *, trails=None, show_contacts: bool = False,
                extra_lines=None, width_scale: float = 1.0,
                looks: LookTracker | None = None) -> FrameState:
        """Copy what the renderer needs out of ``scene`` now.

        Args:
            trails: The running Simulation's ``Trails`` (or None: no trails).
            show_contacts: Also take the world's current contacts: particles' (lines along the
                normals) and rigid bodies' manifolds (``manifolds.py``).
            extra_lines: (start, end, rgb) triples drawn on top (the viewer's drag spring).
            width_scale: Line widths' scale (the renderer's: its height / 720, at least 1).
            looks: The hardware path's look tracker: the particles are taken as positions
                and, when it changed, their look; None: as sphere rows (the software path).
        """
        n = scene.world.particles.count
        anchors = gather.anchor_points(scene) if scene.show_links else np.zeros((0, 3))
        positions = look = None
        gpu_links: tuple = ()
        if looks is None:
            spheres = np.empty((n + len(anchors), gather.SPHERE_FLOATS), np.float32)
            gather.fill_spheres(scene, spheres, anchors)
            first = n
        else:
            positions = positions_float32(scene.world.particles.position)
            look = looks.capture(scene)
            if scene.show_links:
                gpu_links = tuple(pair_links(gather.generators(scene)))
            spheres = gather.anchor_rows(scene, anchors)
            first = 0
        # Rigid bodies: sphere bodies after the particles (they cast shadows too), their spin
        # markers with the anchors (they do not); box bodies join the scene's boxes.
        bodies = scene.world.bodies
        body_boxes = body_casters = body_edges = None
        if looks is None:
            balls, markers = body_visuals.sphere_rows(bodies, gather.SPHERE_FLOATS)
            boxes = [*scene.boxes, *body_visuals.box_visuals(bodies)]
        else:
            # No BoxVisual per body: instance rows straight from the bodies' arrays.
            arrays = body_visuals.body_arrays(bodies, gather.SPHERE_FLOATS)
            balls, markers = arrays["balls"], arrays["markers"]
            boxes = list(scene.boxes)
            body_boxes, body_casters = arrays["boxes"], arrays["casters"]
            if len(body_boxes):
                body_edges = gather.line_rows(arrays["edge_start"], arrays["edge_end"],
                                              arrays["edge_rgb"] * 0.45, 1.0, 1.5 * width_scale)
        if len(balls) or len(markers):
            spheres = np.concatenate([spheres[:first], balls, markers, spheres[first:]])
        casters = first + len(balls)

        have_trails = trails is not None and len(trails)
        parts: list[np.ndarray] = []
        if scene.show_links:
            parts += gather.link_lines(scene, width_scale, skip=gpu_links)
        if have_trails:
            parts += gather.trail_lines(scene, trails, scene.particle_colors(), width_scale)
        if boxes:
            start, end = geometry.box_edge_lines(boxes)
            wire = np.repeat([b.wireframe for b in boxes], 12)
            rgb = np.repeat([tuple(b.color)[:3] for b in boxes], 12, axis=0) \
                * np.where(wire, 1.0, 0.45)[:, None]
            width = np.where(wire, 2.0, 1.5) * width_scale
            parts.append(gather._rows(start, end, rgb, 1.0, width, 0.0))
        if body_edges is not None:
            parts.append(body_edges)
        glow = gather.trail_lines(scene, trails, scene.particle_colors(), width_scale,
                                  glowing=True) if have_trails else []
        overlay = []
        if show_contacts:
            overlay += gather.contact_lines(scene, drawn_radii(scene), width_scale)
            overlay += manifolds.manifold_lines(scene.world, width_scale)
        overlay += gather.extra_line_rows(extra_lines, width_scale)
        return cls(time=float(scene.world.time), particles=casters, spheres=spheres,
                   lines=_joined(parts), glow_trails=_joined(glow), overlay=_joined(overlay),
                   boxes=tuple(_copy_box(b) for b in boxes),
                   planes=tuple(_copy_plane(p) for p in scene.planes),
                   show_ground=bool(scene.show_ground),
                   ground_height=float(scene.ground_height), sky=scene.sky,
                   positions=positions, look=look, gpu_links=gpu_links,
                   body_boxes=body_boxes, body_casters=body_casters,
                   shadow_height=float(scene.ground_height if scene.shadow_height is None
                                       else scene.shadow_height))


def _joined(parts: list[np.ndarray]) -> np.ndarray:
    return np.concatenate(parts).astype(np.float32, copy=False) if parts else _NO_LINES


def _copy_box(b: BoxVisual) -> BoxVisual:
    return dataclasses.replace(b, center=np.array(b.center, np.float64),
                               half_size=np.array(b.half_size, np.float64),
                               rotation=np.array(b.rotation, np.float64),
                               color=tuple(float(c) for c in b.color))


def _copy_plane(p: PlaneVisual) -> PlaneVisual:
    return dataclasses.replace(p, center=np.array(p.center, np.float64),
                               normal=np.array(p.normal, np.float64),
                               half_size=tuple(float(h) for h in p.half_size),
                               color=tuple(float(c) for c in p.color))
