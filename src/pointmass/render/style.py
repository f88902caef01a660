"""How things look: colors and line widths, in one place (no GL)."""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

#: Sky gradient, top and horizon (RGB in [0, 1]); the ground fades into the horizon color.
SKY_TOP = (0.13, 0.15, 0.19)
SKY_HORIZON = (0.40, 0.44, 0.50)
#: Ground fill and grid lines.
GROUND_BASE = (0.27, 0.29, 0.32)
GROUND_LINE = (0.47, 0.50, 0.55)


@dataclass(frozen=True)
class Sky:
    """A backdrop: the sky gradient (top, horizon) and the ground grid's fill and lines (RGB in
    [0, 1]); the ground fades into the horizon color far away."""

    top: tuple[float, float, float]
    horizon: tuple[float, float, float]
    ground_base: tuple[float, float, float]
    ground_line: tuple[float, float, float]


#: The backdrops a Scene's ``sky`` names. Night is dark enough that additive glow reads, and
#: its grid is dimmed to a hint of the ground so it does not compete with the fireworks.
SKIES = {
    "day": Sky(SKY_TOP, SKY_HORIZON, GROUND_BASE, GROUND_LINE),
    "night": Sky(top=(0.004, 0.006, 0.022), horizon=(0.035, 0.05, 0.11),
                 ground_base=(0.018, 0.022, 0.035), ground_line=(0.06, 0.07, 0.10)),
}


def sky(name: str) -> Sky:
    """The backdrop called ``name``; a clear error naming the choices otherwise."""
    try:
        return SKIES[name]
    except (KeyError, TypeError):
        raise ValueError(f"unknown sky {name!r}; choose one of {sorted(SKIES)}") from None


#: Darkness of a blob shadow under a sphere resting on the ground, in [0, 1].
SHADOW_STRENGTH = 0.75

#: Light direction in eye space (toward the light): above, left of and behind the viewer.
LIGHT_EYE = np.array([-0.35, 0.75, 0.55]) / np.linalg.norm([-0.35, 0.75, 0.55])

#: Anchor markers: dark grey balls this fraction of the scene's point radius.
ANCHOR_COLOR = (0.12, 0.12, 0.14)
ANCHOR_SCALE = 0.7

#: Per kind of link: width [px at 720 rows], dash period for slack links [m] (0: never dashed).
LINK_WIDTH = {"spring": 3.0, "bungee": 2.5, "cable": 2.0, "rod": 5.0, "joint": 4.0}
LINK_SLACK_DASH = {"spring": 0.0, "bungee": 0.12, "cable": 0.12, "rod": 0.0, "joint": 0.0}
#: Base colors where the strain does not color the link.
CABLE_COLOR = (0.85, 0.72, 0.50)
ROD_COLOR = (0.72, 0.77, 0.84)
BUNGEE_COLOR = (0.98, 0.62, 0.18)
#: Joints: the lines body centre → joint point → the other body's centre (a top's stem).
JOINT_COLOR = (0.92, 0.92, 0.97)
#: Spring colors: fully compressed, at rest, fully stretched (strain ±STRAIN_FULL).
SPRING_COMPRESSED = np.array([0.25, 0.50, 1.00])
SPRING_REST = np.array([0.92, 0.92, 0.85])
SPRING_STRETCHED = np.array([1.00, 0.22, 0.15])
STRAIN_FULL = 0.25

CONTACT_COLOR = (1.0, 0.85, 0.10)
TRAIL_WIDTH = 2.0
#: Trails of glowing particles: additive light streaks, this wide at the head [px at 720 rows],
#: tapering to GLOW_TRAIL_TAIL of that at the oldest point.
GLOW_TRAIL_WIDTH = 2.5
GLOW_TRAIL_TAIL = 0.3

#: Glowing particles (glow.glsl): the bright core is the drawn radius but never under
#: GLOW_MIN_CORE px (at 720 rows), and the halo reaches GLOW_HALO times the core's radius
#: with GLOW_HALO_GAIN of the color at its centre.
GLOW_MIN_CORE = 2.0
GLOW_HALO = 5.0
GLOW_HALO_GAIN = 1.0
EXTRA_WIDTH = 2.5


def strain_colors(strain: np.ndarray) -> np.ndarray:
    """Blue when compressed, pale at rest, red when stretched; shape (K, 3)."""
    t = np.clip(np.asarray(strain, dtype=np.float64) / STRAIN_FULL, -1.0, 1.0)[:, None]
    toward = np.where(t < 0, SPRING_COMPRESSED, SPRING_STRETCHED)
    return SPRING_REST + (toward - SPRING_REST) * np.abs(t)


def link_colors(kind: str, strain: np.ndarray) -> np.ndarray:
    """RGB per link of one kind, shape (K, 3)."""
    k = len(strain)
    if kind == "spring":
        return strain_colors(strain)
    if kind == "bungee":
        # Taut bungees redden like springs; slack ones keep their own orange.
        taut = np.clip(np.asarray(strain) / STRAIN_FULL, 0.0, 1.0)[:, None]
        return np.asarray(BUNGEE_COLOR) + (SPRING_STRETCHED - BUNGEE_COLOR) * taut
    if kind == "cable":
        return np.tile(CABLE_COLOR, (k, 1))
    if kind == "joint":
        return np.tile(JOINT_COLOR, (k, 1))
    return np.tile(ROD_COLOR, (k, 1))
