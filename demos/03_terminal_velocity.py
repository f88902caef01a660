"""A point mass pushed off a 100 m table by a cat falls until drag balances gravity (≈ −9.42 m/s).

The cookbook's terminal-velocity experiment, step for step: a 1 kg particle at (0, 100, 0) with a
0.1 m/s nudge, GravityGenerator(9.81) and DragGenerator(0.1, 0.1), ticked at 60 Hz. After 5 s its
v_y is −9.416 (the cookbook's figure: "approximately −9.42"). The live plot shows v_y converging
to the analytic limit v_t, where k1·v + k2·v² = m·g.

Keys: none beyond the viewer's.   Run: pointmass run terminal_velocity --set k2=0.5
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from pointmass import BoxVisual, CameraHint, Drag, Gravity, Ground, Scene, World, tweak

TITLE = "Terminal velocity"
COOKBOOK_TERMINAL_VELOCITY = -9.42


@dataclass
class Params:
    k1: float = tweak(0.1, 0.0, 2.0, "Linear drag coefficient k1 [N·s/m]")
    k2: float = tweak(0.1, 0.0, 2.0, "Quadratic drag coefficient k2 [N·s²/m²]")
    gravity: float = tweak(9.81, 0.0, 30.0, "Gravity strength [m/s²]")
    mass: float = tweak(1.0, 0.1, 10.0, "Mass of the point [kg]", rebuild=True)


def terminal_velocity(k1: float, k2: float, weight: float) -> float:
    """The speed where k1·v + k2·v² equals the weight m·g [m/s], as a negative v_y."""
    if k2 == 0.0:
        return -weight / k1 if k1 > 0 else -math.inf
    return -(-k1 + math.sqrt(k1 * k1 + 4.0 * k2 * weight)) / (2.0 * k2)


def build(p: Params) -> Scene:
    world = World(gravity=(0.0, 0.0, 0.0))  # gravity comes from the cookbook's generator
    point = world.add_particle((0.0, 100.0, 0.0), (0.1, 0.0, 0.0), mass=p.mass)
    gravity = world.add(Gravity((0.0, -p.gravity, 0.0)))
    drag = world.add(Drag(p.k1, p.k2))
    world.add(Ground(0.0, restitution=0.0))
    table = BoxVisual(center=(-3.0, 98.5, 0.0), half_size=(3.0, 1.5, 3.0),
                      color=(0.55, 0.35, 0.2))
    scene = Scene(world, camera=CameraHint(target=(6.0, 50.0, 0.0), distance=150.0, yaw=25.0,
                                           pitch=5.0),
                  colors=np.array([[0.95, 0.8, 0.2]]), point_radius=1.5, trails=[point],
                  trail_length=400, boxes=[table], dt=1.0 / 60.0,
                  handles={"point": point, "gravity": gravity, "drag": drag, "params": p})
    scene.plots = {
        "v_y [m/s]": lambda s: float(s.world.particles.velocity[point, 1]),
        "terminal v_t [m/s]": lambda s: terminal_velocity(
            s.handles["drag"].k1, s.handles["drag"].k2,
            -s.handles["gravity"].g[1] * s.world.particles[point].mass),
    }
    return scene


def apply(scene: Scene, p: Params) -> None:
    scene.handles["drag"].k1 = p.k1
    scene.handles["drag"].k2 = p.k2
    scene.handles["gravity"].g = np.array([0.0, -p.gravity, 0.0])
    scene.handles["params"] = p


def on_step(scene: Scene, dt: float) -> None:
    """Remember v_y after the cookbook's 5 s (300 ticks at 60 Hz), before the next tick."""
    if "v_at_5s" not in scene.handles and scene.time >= 5.0 - 1e-9:
        point = scene.handles["point"]
        scene.handles["v_at_5s"] = float(scene.world.particles.velocity[point, 1])


def check(scene: Scene) -> None:
    """After 5 s the fall has reached the cookbook's −9.42 m/s (default parameters)."""
    p = scene.handles["params"]
    if "v_at_5s" not in scene.handles or (p.k1, p.k2, p.gravity, p.mass) != (0.1, 0.1, 9.81, 1.0):
        return
    v = scene.handles["v_at_5s"]
    assert abs(v - COOKBOOK_TERMINAL_VELOCITY) < 0.01, f"v_y after 5 s = {v}"
