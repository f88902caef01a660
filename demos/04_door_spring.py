"""A particle on an anchored spring oscillating like a door stopper; a live plot of its x.

The cookbook's last force example: a particle at the origin given 20 m/s along x, on an anchored
spring at (−2, 0, 0) with k = 1 and rest length 2, no gravity. The motion swings through the
anchor, so it is not simple harmonic: the plot shows the cookbook's "small and large peaks".
With no damping the spring's energy plus the kinetic energy stays constant (within the
integrator's bounded error): the oracle.

Keys: none beyond the viewer's.   Run: pointmass run door_spring --set stiffness=4
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from pointmass import AnchoredSpring, CameraHint, Scene, World, tweak

TITLE = "Door spring"


@dataclass
class Params:
    stiffness: float = tweak(1.0, 0.1, 20.0, "Spring constant k [N/m]")
    rest_length: float = tweak(2.0, 0.0, 10.0, "Rest length [m]")
    speed: float = tweak(20.0, 0.0, 40.0, "Initial push along x [m/s]", rebuild=True)
    damping: float = tweak(0.0, 0.0, 2.0, "Spring damping [N·s/m]")


def build(p: Params) -> Scene:
    world = World(gravity=(0.0, 0.0, 0.0))
    door = world.add_particle((0.0, 0.0, 0.0), (p.speed, 0.0, 0.0), mass=1.0, radius=1.0)
    spring = world.add(AnchoredSpring(door, (-2.0, 0.0, 0.0), p.stiffness, p.rest_length,
                                      damping=p.damping))
    scene = Scene(world, camera=CameraHint(target=(-1.0, 0.0, 0.0), distance=56.0, yaw=0.0,
                                           pitch=10.0),
                  colors=np.array([[0.35, 0.75, 0.4]]), show_ground=True, ground_height=-2.0,
                  dt=1.0 / 120.0, handles={"door": door, "spring": spring})
    scene.plots = {"x [m]": lambda s: float(s.world.particles.position[door, 0])}
    scene.handles["energy0"] = energy(scene)
    return scene


def energy(scene: Scene) -> float:
    """Kinetic energy plus the spring's stored energy [J]."""
    return scene.world.kinetic_energy() + scene.world.potential_energy()


def apply(scene: Scene, p: Params) -> None:
    spring = scene.handles["spring"]
    spring.spring_constant = p.stiffness
    spring.rest_length = p.rest_length
    spring.damping = p.damping
    scene.handles["energy0"] = energy(scene)  # a new spring is a new energy budget


def check(scene: Scene) -> None:
    """Undamped, the total energy stays within 5 % of where it started."""
    if scene.handles["spring"].damping.any():
        return
    start, now = scene.handles["energy0"], energy(scene)
    assert abs(now - start) <= 0.05 * start, f"energy drifted from {start:.3f} J to {now:.3f} J"
