"""Collision shapes of rigid bodies and the mass properties they give at a density.

A body's shape is stored as a kind (``NONE``, ``SPHERE``, ``BOX``) and a size 3-vector: the radius
in the first slot for a sphere, the half-extents for a box, both in body coordinates. Sphere and
box have their principal axes along the body axes, so their inertia is a diagonal: the body stores
its three principal moments, never a full tensor (Jolt's storage; no rotation is needed for these).

Box inertia is m(b² + c²)/3 on *half*-extents (= m(B² + C²)/12 on full sides); Cyclone's demos use
0.3·m(...) with a different mass than the body's (rigid-notes R5), so the moments here come from
one mass and one size, always.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from .. import _validate as check

NONE = 0
SPHERE = 1
BOX = 2
#: Sizes a shape takes [m]: a radius or half-extent in [MIN_SIZE, MAX_SIZE]. Past them the
#: volume and moments (size³, size²) overflowed (Sphere(1e300): OverflowError) or rounded to 0
#: (Sphere(1e-300): "inertia must be three principal moments", though none was given).
MIN_SIZE = 1e-9
MAX_SIZE = 1e9


@dataclass(frozen=True)
class Sphere:
    """A solid sphere of ``radius`` [m] > 0 about the body origin."""

    radius: float

    def __post_init__(self) -> None:
        object.__setattr__(self, "radius", check.scalar(self.radius, "radius", low=MIN_SIZE,
                                                       high=MAX_SIZE))

    kind = SPHERE

    @property
    def size(self) -> np.ndarray:
        return np.array([self.radius, 0.0, 0.0])

    @property
    def volume(self) -> float:
        """Volume [m³]."""
        return 4.0 / 3.0 * math.pi * self.radius**3

    def unit_inertia(self) -> np.ndarray:
        """Principal moments per kilogram [m²], shape (3,): 2/5 r²."""
        return np.full(3, 0.4 * self.radius**2)


@dataclass(frozen=True)
class Box:
    """A solid box of ``half_extents`` [m] (each > 0) along the body axes, centred on the origin."""

    half_extents: tuple[float, float, float]

    def __post_init__(self) -> None:
        half = check.vec3(self.half_extents, "half_extents")
        if not ((half >= MIN_SIZE) & (half <= MAX_SIZE)).all():
            raise ValueError(f"half_extents must each be in [{MIN_SIZE:g}, {MAX_SIZE:g}] m, got "
                             f"{tuple(half.tolist())}")
        object.__setattr__(self, "half_extents", tuple(half.tolist()))

    kind = BOX

    @property
    def size(self) -> np.ndarray:
        return np.array(self.half_extents)

    @property
    def volume(self) -> float:
        """Volume [m³]."""
        a, b, c = self.half_extents
        return 8.0 * a * b * c

    def unit_inertia(self) -> np.ndarray:
        """Principal moments per kilogram [m²], shape (3,): (b² + c²)/3, ... on half-extents."""
        a, b, c = self.half_extents
        return np.array([b * b + c * c, a * a + c * c, a * a + b * b]) / 3.0


def mass_properties(shape: Sphere | Box, *, density: float | None = None,
                    mass: float | None = None) -> tuple[float, np.ndarray]:
    """Mass [kg] and principal moments [kg m²], shape (3,), of a uniform solid ``shape``.

    Give ``density`` [kg/m³] in (0, inf] or ``mass`` [kg] in (0, inf], not both; ``inf`` (either)
    makes the body static: infinite mass and infinite moments.
    """
    if (density is None) == (mass is None):
        raise ValueError("give exactly one of density [kg/m³] and mass [kg]")
    if density is not None:
        density = check.scalar(density, "density", low=0.0, low_open=True, high=math.inf) \
            if not _is_inf(density) else math.inf
        m = density * shape.volume
    else:
        m = check.scalar(mass, "mass", low=0.0, low_open=True) if not _is_inf(mass) else math.inf
    if math.isinf(m):
        return math.inf, np.full(3, math.inf)
    return m, m * shape.unit_inertia()


def _is_inf(value) -> bool:
    check.numeric(value, "mass or density")
    return isinstance(value, (int, float, np.floating)) and value == math.inf


def compound_boxes(parts, mass: float) -> tuple[np.ndarray, np.ndarray]:
    """Mass properties of solid boxes of one density glued together (a drawn vehicle).

    Args:
        parts: (centre [m], half-extents [m]) pairs along shared axes, at least one.
        mass: Total mass [kg], > 0; shared by volume.

    Returns:
        The centre of mass [m], shape (3,), and the inertia tensor about it [kg m²], shape
        (3, 3) (each box's own moments plus the parallel-axis term m(|c|²·1 − c cᵀ)).
    """
    mass = check.scalar(mass, "mass", low=0.0, low_open=True)
    boxes = [(check.vec3(c, "part centre"), Box(h)) for c, h in parts]
    if not boxes:
        raise ValueError("parts must hold at least one (centre, half_extents) pair, got none")
    volumes = np.array([box.volume for _, box in boxes])
    masses = mass * volumes / volumes.sum()
    centre = sum(m * c for m, (c, _) in zip(masses, boxes)) / mass
    tensor = np.zeros((3, 3))
    for m, (c, box) in zip(masses, boxes):
        r = c - centre
        tensor += np.diag(m * box.unit_inertia()) + m * (r @ r * np.eye(3) - np.outer(r, r))
    return centre, tensor
