"""The one running simulation: a demo (or a bare Scene), its parameters and its one clock.

Every driver moves time through this class — the window, ``pointmass record``, snapshots,
notebook clips, probes and the tests — so a demo does exactly the same thing everywhere:

- ``World.time`` is the only clock. ``advance(seconds)`` is the one place that turns time into
  steps: it runs whole fixed steps of ``scene.dt`` and carries the remainder to the next call,
  so a window at any frame rate, a 25 or 30 fps recording and a probe run take the same steps
  and produce bit-identical trajectories.
- Before every step the demo's ``on_step(scene, dt)`` runs, and ``on_keys_held(scene, keys,
  dt)`` while keys are held (``keys_down``, kept up to date by the window; scripts and tests
  may set it).
- After every step, trails take their points on simulated time (``pointmass.trails``) and
  probes added with ``add_probe`` sample the world (they follow the world through a reset).

Drawing code never steps physics: it draws whatever state this object is in.
"""

from __future__ import annotations

import dataclasses
import math
import time as _time
from pathlib import Path
from typing import Any

from . import params as params_mod
from .scene import Scene
from .trails import Trails
from .world import StepStats


class Simulation:
    """A demo or a Scene, running.

    Args:
        source: A loaded ``Demo``, a demo name or ``.py`` path, or a ``Scene`` built in a script.
        params: The demo's parameters (default: its ``Params()``).
        overrides: ``name=value`` strings applied to the parameters (``--set``).
        title: A title for windows (default: the demo's title, or "pointmass").

    Example:
        >>> import pointmass as pm
        >>> sim = pm.Simulation("projectile")
        >>> sim.dt == 1 / 60
        True
        >>> sim.advance(0.5)                  # whole fixed steps of dt
        30
        >>> round(sim.time, 6)
        0.5
    """

    def __init__(self, source, params: Any = None, overrides: list[str] | None = None, *,
                 title: str | None = None) -> None:
        from .demo import Demo, load_demo

        if isinstance(source, (str, Path)):
            source = load_demo(source)
        if isinstance(source, Scene):
            if params is not None or overrides:
                raise ValueError("a bare Scene has no parameters to set; build a demo for that")
            self.demo, self.params = None, None
            self.scene = source
            self._initial = _world_state(source.world)
        elif isinstance(source, Demo):
            self.demo = source
            self.params = params if params is not None else source.default_params()
            if self.params is not None:
                params_mod.validate(self.params)
                params_mod.apply_overrides(self.params, overrides or [])
            elif overrides:
                raise ValueError(f"demo {source.name!r} has no parameters to --set")
            self.scene = source.build(self.params)
        else:
            raise TypeError(f"Simulation takes a Scene, a demo name or path, or a Demo; got "
                            f"{type(source).__name__}")
        self.title = title or (f"pointmass - {self.demo.title}" if self.demo else "pointmass")
        #: Keys held right now (names like "W"), kept up to date by the window.
        self.keys_down: set[str] = set()
        #: The recorded paths of the scene's trailed particles.
        self.trails = Trails()
        #: Probes sampled after every step; re-attached to the new world after a rebuild.
        self.probes: list = []
        self.last_stats: StepStats | None = None
        #: Simulated seconds given up because ``advance`` hit its step or time cap [s].
        self.dropped = 0.0
        #: Demo keys and clicks handled so far (the window's hint shows until the first).
        self.presses = 0
        self._owed = 0.0
        self.trails.record(self.scene)

    def _hook(self, name: str):
        return self.demo.hook(name) if self.demo is not None else None

    # -- what is running ----------------------------------------------------------------------
    @property
    def world(self):
        return self.scene.world

    @property
    def time(self) -> float:
        """Simulated seconds since the scene was built: the world's clock."""
        return self.scene.world.time

    @property
    def dt(self) -> float:
        """The fixed physics step [s] (the scene's)."""
        return self.scene.dt

    # -- time -------------------------------------------------------------------------------------
    def step(self) -> StepStats:
        """One fixed step of ``dt``: the demo's hooks, the world's step, trails."""
        scene, dt = self.scene, self.scene.dt
        if self.keys_down and (on_keys_held := self._hook("on_keys_held")) is not None:
            on_keys_held(scene, frozenset(self.keys_down), dt)
        if (on_step := self._hook("on_step")) is not None:
            on_step(scene, dt)
        self.last_stats = scene.world.step(dt)
        self.trails.sample(scene, scene.world.time)
        return self.last_stats

    def advance(self, seconds: float, *, max_steps: int | None = None,
                max_wall_seconds: float | None = None) -> int:
        """Move simulated time forward by ``seconds`` in whole fixed steps; returns how many ran.

        What does not make a whole step is owed to the next call, so many short calls take the
        same steps as one long one. A window passes ``max_steps`` and ``max_wall_seconds``:
        steps beyond them are dropped (slow motion instead of a spiral of ever longer frames)
        and counted in ``dropped``.
        """
        if not (math.isfinite(seconds) and seconds >= 0):
            raise ValueError(f"seconds must be a finite number >= 0, got {seconds!r}")
        dt = self.scene.dt
        self._owed += seconds
        due = math.floor(self._owed / dt + 1e-9)
        self._owed = max(0.0, self._owed - due * dt)
        if max_steps is not None and due > max_steps:
            self.dropped += (due - max_steps) * dt
            due = max_steps
        started = _time.perf_counter()
        for done in range(1, due + 1):
            self.step()
            if (max_wall_seconds is not None and done < due
                    and _time.perf_counter() - started > max_wall_seconds):
                self.dropped += (due - done) * dt
                return done
        return due

    def forget_owed(self) -> None:
        """Drop the part of a step still owed (a pause or a reset starts clean)."""
        self._owed = 0.0

    # -- probes -----------------------------------------------------------------------------------
    def add_probe(self, probe):
        """Sample ``probe`` after every step, in this world and in every rebuilt one."""
        self.probes.append(probe)
        self.world.add_probe(probe)
        return probe

    def remove_probe(self, probe) -> None:
        self.probes.remove(probe)
        if probe in self.world.probes:
            self.world.probes.remove(probe)

    # -- changes from the user ------------------------------------------------------------------
    def rebuild(self) -> None:
        """Start again: a demo builds its scene anew from the current parameters; a bare Scene
        puts its world back as it was when the Simulation was made (particles, time, warm
        start; a generator's own state, such as a timer inside a user callable, stays)."""
        if self.demo is not None:
            self.scene = self.demo.build(self.params)
        else:
            _restore_world_state(self.scene.world, self._initial)
        world = self.scene.world
        for probe in self.probes:
            probe.clear()
            if probe not in world.probes:
                world.add_probe(probe)
        self.last_stats = None
        self._owed = 0.0
        self.trails.clear()
        self.trails.record(self.scene)

    reset = rebuild

    def set_param(self, name: str, value: Any) -> None:
        """Change one parameter: live ones go through the demo's ``apply``, others rebuild."""
        if self.params is None:
            raise ValueError(f"this scene has no parameters (got {name!r})")
        spec = params_mod.set_param(self.params, name, value)
        apply = self._hook("apply")
        if spec.rebuild or apply is None:
            self.rebuild()
        else:
            apply(self.scene, self.params)

    def press(self, key: str) -> bool:
        """Run the demo's binding for ``key``; False when the demo binds nothing to it."""
        binding = self.demo.keys.get(key) if self.demo is not None else None
        if binding is None:
            return False
        binding[1](self.scene, self.params)
        self.presses += 1
        return True

    @property
    def hint(self) -> str | None:
        """What to do, for the window to show until the first key or click (the demo's
        ``HINT``; None for a bare Scene)."""
        return self.demo.hint if self.demo is not None else None

    def check(self) -> None:
        """Run the demo's oracle, if it has one."""
        check = self.demo.hook("check") if self.demo is not None else None
        if check is not None:
            check(self.scene)

    def param_values(self) -> dict[str, Any]:
        return dataclasses.asdict(self.params) if self.params is not None else {}


def _world_state(world) -> tuple:
    return world.particles.snapshot(), world.bodies.snapshot(), world.time


def _restore_world_state(world, state: tuple) -> None:
    particles, bodies, time = state
    world.particles.restore(particles)
    world.bodies.restore(bodies)
    world.time = time
    world.impulses.clear()
    world.body_impulses.clear()
    world.sleeping_impulses.clear()
    world.joints.clear_impulses()
