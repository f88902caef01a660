"""A spinning top: a square plate spinning fast about its axis, its tip held by a ball joint on
a post; gravity tips it over, and it precesses instead of falling.

The top is started in steady precession (spin ω₃ along its axis plus the precession Ω about
the vertical, Ω the slow root of m·g·d = Ω·(I₃·ω₃ − I₁'·Ω·cos θ), I₁' about the tip), so it
turns about the vertical without nodding. Its precession rate is close to the fast-top value
Ω ≈ m·g·d / (I₃·ω₃) (within 1.6 % here; the exact root within 0.1 %). The line from the tip to
the plate is the joint (body centre → joint point), the top's stem.

Keys: SPACE nudges the top (it then nods while it precesses).
Run: pointmass run spinning_top --set spin=40
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from pointmass import BoxVisual, CameraHint, Scene, World, tweak
from pointmass.rigid.bodies import world_rotation
from pointmass.rigid.joints import BallJoint
from pointmass.rigid.shapes import Box

TITLE = "Spinning top (ball joint, precession)"
#: Shown over the scene until the first key or click.
HINT = "Press SPACE to nudge the top"
G = 9.81
HALF = (0.3, 0.03, 0.3)  # the plate's half extents [m]; its axis is the local y axis
TIP = np.array([0.0, 1.0, 0.0])  # the top of the post [m]


@dataclass
class Params:
    spin: float = tweak(35.0, 15.0, 45.0, "Spin ω₃ about the top's axis [rad/s]", rebuild=True)
    height: float = tweak(0.15, 0.05, 0.3, "Plate centre above the tip d [m]", rebuild=True)
    tilt: float = tweak(30.0, 5.0, 60.0, "Tilt of the axis from the vertical [deg]",
                        rebuild=True)
    mass: float = tweak(1.0, 0.1, 10.0, "Mass m [kg]", rebuild=True)


def moments(p: Params) -> tuple[float, float]:
    """(I₁ about the tip, I₃ about the axis) [kg m²] of the plate (box moments, on half
    extents: I = m(b² + c²)/3)."""
    a, b, _ = HALF
    i1 = p.mass * (a * a + b * b) / 3 + p.mass * p.height**2
    return i1, p.mass * 2 * a * a / 3


def precession_rates(p: Params) -> tuple[float, float]:
    """(the slow steady root, the fast-top approximation) of Ω [rad/s] about the vertical."""
    i1, i3 = moments(p)
    c = math.cos(math.radians(p.tilt))
    mgd = p.mass * G * p.height
    spin = i3 * p.spin
    slow = (spin - math.sqrt(spin * spin - 4 * i1 * c * mgd)) / (2 * i1 * c)
    return slow, mgd / spin


def build(p: Params) -> Scene:
    world = World(gravity=(0.0, -G, 0.0))
    th = math.radians(p.tilt)
    axis = np.array([math.sin(th), math.cos(th), 0.0])  # leaning toward +x
    turn = (math.cos(th / 2), 0.0, 0.0, -math.sin(th / 2))  # body y onto ``axis``
    slow, _ = precession_rates(p)
    omega = (p.spin - slow * math.cos(th)) * axis + (0.0, slow, 0.0)
    top = world.add_body(Box(HALF), TIP + p.height * axis, turn, mass=p.mass,
                         velocity=np.cross(omega, p.height * axis), angular_velocity=omega)
    joint = world.add(BallJoint(top, (0.0, -p.height, 0.0)))
    post = BoxVisual(center=(0.0, TIP[1] / 2, 0.0), half_size=(0.03, TIP[1] / 2, 0.03),
                     color=(0.45, 0.35, 0.25))
    return Scene(world, camera=CameraHint(target=(0.0, 0.95, 0.0), distance=2.4, yaw=25.0,
                                          pitch=42.0),
                 boxes=[post], dt=1.0 / 60.0,
                 handles={"top": top, "joint": joint, "params": p, "azimuth": [],
                          "nudged": False},
                 plots={"tilt [deg]": lambda s: tilt_of(top)})


def axis_of(top) -> np.ndarray:
    return world_rotation(top.orientation)[:, 1]


def tilt_of(top) -> float:
    return math.degrees(math.acos(min(1.0, float(axis_of(top)[1]))))


def on_step(scene: Scene, dt: float) -> None:
    """Record the azimuth of the axis (the precession angle) and the tip's separation."""
    h = scene.handles
    ax = axis_of(h["top"])
    h["azimuth"].append((scene.world.time, math.atan2(-ax[2], ax[0]), h["joint"].separation()))


def nudge(scene: Scene, p: Params) -> None:
    top = scene.handles["top"]
    top.add_force_at_point((0.0, 0.0, 30.0), top.to_world((HALF[0], 0.0, 0.0)))
    scene.handles["nudged"] = True


KEYS = {"SPACE": ("Nudge the top", nudge)}


def check(scene: Scene) -> None:
    """Precession at Ω ≈ m·g·d/(I₃·ω₃) within 3 % (and the exact slow root within 1 %), the
    tip within 2 mm of the post, the tilt steady to a degree.

    The tip's 2 mm: in a step the plate turns ω·dt ≈ 0.6 rad about an axis that misses the tip
    by r⊥ ≈ d·Ω·sin θ/ω₃, which moves the tip off by about ½(ω·dt)²·r⊥ (the velocity rows are
    linear), and the joint's bias takes back half of the separation each step: 1.1 mm at the
    defaults (0.07 mm with 4 substeps)."""
    h = scene.handles
    if h["nudged"] or len(h["azimuth"]) < 60:
        return
    t, phi, sep = (np.array(c) for c in zip(*h["azimuth"], strict=True))
    rate = np.polyfit(t, np.unwrap(phi), 1)[0]
    slow, fast = precession_rates(h["params"])
    assert abs(rate / fast - 1) < 0.03, f"precession {rate:.4f} rad/s, fast-top {fast:.4f}"
    assert abs(rate / slow - 1) < 0.01, f"precession {rate:.4f} rad/s, steady root {slow:.4f}"
    assert sep.max() < 2e-3, f"the tip left the post by {sep.max() * 1e3:.2f} mm"
    assert abs(tilt_of(h["top"]) - h["params"].tilt) < 1.0
