"""A Simulation-like wrapper around a bare Scene, for ``show(scene)`` from a script.

It has what the viewer uses of ``pointmass.demo.Simulation`` (step, rebuild, press, set_param,
params, scene, last_stats) but no demo file: no parameters, no keys, and reset restores the
particles' state as it was when the window opened (their positions and velocities), since there
is no ``build`` to run again.
"""

from __future__ import annotations

from ..scene import Scene
from ..world import StepStats


class SceneSimulation:
    """Drives a Scene built in a script.

    Args:
        scene: The scene to show.
        title: The window title.
    """

    params = None

    def __init__(self, scene: Scene, title: str = "pointmass") -> None:
        if not isinstance(scene, Scene):
            raise TypeError(f"show() takes a Scene or a Simulation, got {type(scene).__name__}")
        self.scene = scene
        self.title = title
        self.last_stats: StepStats | None = None
        p = scene.world.particles
        self._saved = (p.position.copy(), p.velocity.copy(), scene.time, scene.world.time)

    @property
    def world(self):
        return self.scene.world

    def step(self, dt: float | None = None) -> StepStats:
        dt = self.scene.dt if dt is None else dt
        self.last_stats = self.scene.world.step(dt)
        self.scene.time += dt
        return self.last_stats

    def rebuild(self) -> None:
        """Put the particles back where they were when the window opened."""
        pos, vel, t, wt = self._saved
        p = self.scene.world.particles
        n = min(len(pos), p.count)
        p.position[:n], p.velocity[:n] = pos[:n], vel[:n]
        self.scene.time, self.scene.world.time = t, wt
        self.scene.clear_trails()
        self.last_stats = None

    def press(self, key: str) -> bool:
        return False

    def set_param(self, name: str, value) -> None:
        raise ValueError(f"this scene has no parameters (got {name!r})")
