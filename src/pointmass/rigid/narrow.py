"""Narrow phase from Python: check the shapes, call a kernel, return a ``Manifold``.

The kernels (``narrow_sphere``, ``narrow_box``, ``box_box``) are what a compiled pair loop will
call; these wrappers are for tests, tools and one-off queries. Spheres are (centre, radius),
boxes (centre, orientation (w, x, y, z), half-extents), planes (normal, offset) with the solid on
the side −normal. The normal of the result runs from the second shape to the first.
"""

from __future__ import annotations

import numpy as np

from .. import _validate as check
from .bodies import _unit_quaternion
from .box_box import box_box as _box_box
from .manifold import Manifold, empty_outputs
from .narrow_box import box_plane as _box_plane
from .narrow_sphere import sphere_box as _sphere_box
from .narrow_sphere import sphere_plane as _sphere_plane
from .narrow_sphere import sphere_sphere as _sphere_sphere


def sphere_plane(centre, radius, normal, offset, *, margin: float = 0.0) -> Manifold:
    """Sphere against the plane normal·x = offset."""
    c, r = check.vec3(centre, "centre"), _radius(radius)
    n, d = _plane(normal, offset)
    return _run(_sphere_plane, c, r, n, d, _margin(margin))


def sphere_sphere(centre_a, radius_a, centre_b, radius_b, *, margin: float = 0.0) -> Manifold:
    """Sphere A against sphere B."""
    return _run(_sphere_sphere, check.vec3(centre_a, "centre_a"), _radius(radius_a, "radius_a"),
                check.vec3(centre_b, "centre_b"), _radius(radius_b, "radius_b"), _margin(margin))


def sphere_box(centre, radius, box_centre, box_orientation, half_extents, *,
               margin: float = 0.0) -> Manifold:
    """Sphere A against box B."""
    return _run(_sphere_box, check.vec3(centre, "centre"), _radius(radius),
                *_box(box_centre, box_orientation, half_extents), _margin(margin))


def box_plane(centre, orientation, half_extents, normal, offset, *,
              margin: float = 0.0) -> Manifold:
    """Box A against the plane normal·x = offset: up to four corners."""
    return _run(_box_plane, *_box(centre, orientation, half_extents), *_plane(normal, offset),
                _margin(margin))


def box_box(centre_a, orientation_a, half_extents_a, centre_b, orientation_b, half_extents_b,
            *, margin: float = 0.0) -> Manifold:
    """Box A against box B: up to four points with feature ids."""
    return _run(_box_box, *_box(centre_a, orientation_a, half_extents_a, "_a"),
                *_box(centre_b, orientation_b, half_extents_b, "_b"), _margin(margin))


def _run(kernel, *args) -> Manifold:
    normal, points, depth, ids = empty_outputs()
    count = int(kernel(*args, normal, points, depth, ids))
    return Manifold(count, normal, points[:count], depth[:count], ids[:count])


def _radius(value, name: str = "radius") -> float:
    return check.scalar(value, name, low=0.0, low_open=True)


def _margin(value) -> float:
    return check.scalar(value, "margin", low=0.0)


def _plane(normal, offset) -> tuple[np.ndarray, float]:
    n = check.vec3(normal, "normal")
    length = float(np.sqrt(n @ n))
    if not length > 1e-12:
        raise ValueError(f"normal must be a nonzero 3-vector, got {tuple(n.tolist())}")
    return n / length, check.scalar(offset, "offset")


def _box(centre, orientation, half_extents, suffix: str = ""):
    c = check.vec3(centre, "centre" + suffix)
    q = _unit_quaternion(orientation)
    h = check.vec3(half_extents, "half_extents" + suffix)
    if not (h > 0.0).all():
        raise ValueError(f"half_extents{suffix} must each be > 0 m, got {tuple(h.tolist())}")
    return c, q, h
