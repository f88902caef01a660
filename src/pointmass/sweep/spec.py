"""What a sweep is: a scene source, the parameter values of each run, how long, and what to keep.

A run is one point of the sweep: its parameters (the fixed ones, one point of the grid, one random
draw) and its seed. Its id is a digest of exactly those, so a rerun, or a sweep extended with
more grid values or seeds, finds the runs it already has whatever their order.
"""

from __future__ import annotations

import hashlib
import inspect
import itertools
import json
import math
from collections.abc import Callable, Mapping, Sequence
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import numpy as np

#: Quantities a sweep can probe by name; each is sampled at every frame time (T samples).
BUILTIN_PROBES: dict[str, str] = {
    "positions": "particle positions [m], (T, N, 3)",
    "velocities": "particle velocities [m/s], (T, N, 3)",
    "contacts": "contacts found in the last step, (T,)",
    "kinetic_energy": "total kinetic energy [J], (T,)",
    "potential_energy": "gravitational and stored potential energy [J], (T,)",
    "body_positions": "rigid bodies' centres of mass [m], (T, B, 3)",
    "body_orientations": "rigid bodies' unit quaternions (w, x, y, z), (T, B, 4)",
}

#: Index columns a parameter may not be called (they would be overwritten).
RESERVED = ("run_id", "index", "seed", "outcome", "error", "steps", "frames", "wall_seconds",
            "sim_seconds", "path")

MAX_SECONDS = 3600.0


@dataclass(frozen=True)
class RunSpec:
    """One run: its place in the sweep, its parameters and its seed (None: the scene's own)."""

    run_id: str
    index: int
    params: dict[str, Any]
    seed: int | None


@dataclass
class Sweep:
    """A sweep's settings. ``runs()`` lists its runs; ``pointmass.sweep.run`` executes it.

    Args:
        source: A demo name or ``.py`` path, or a function building the scene: it is called
            with each run's parameters as keyword arguments (and ``seed=`` when it has a
            ``seed`` parameter) and returns a ``Scene`` or a ``Simulation``. Workers import
            it by name, so it must be defined at a module's top level (not in a notebook
            cell or a lambda) for the process pool; Ray ships it by value.
        seconds: Simulated seconds of each run (> 0).
        fps: Frames per simulated second: the clip's rate, and the probes' sampling rate
            (each frame has its ground truth).
        clip: (width, height) of an mp4 per run, or None for no clip.
        probes: Names from ``BUILTIN_PROBES``, or ``{name: function(world) -> array}``.
        snapshot: Keep the final state of every particle and body (``final.npz``).
        fixed: Parameters every run shares.
        grid: ``{name: [values]}``: every combination is a run.
        random: ``{name: (low, high)}`` (uniform; integers when both ends are ints, unless
            the demo's parameter is a float) or
            ``{name: [choices]}``, drawn ``draws`` times from ``random_seed``.
        draws: How many random draws (each combined with every grid point).
        seeds: An int n (seeds 0 … n-1), a list of seeds, or None (the scene's own seed).
            A demo receives it as its ``seed`` parameter.
    """

    source: str | Path | Callable
    seconds: float = 2.0
    fps: int = 30
    clip: tuple[int, int] | None = None
    probes: Sequence[str] | Mapping[str, Callable] = ()
    snapshot: bool = True
    fixed: Mapping[str, Any] = field(default_factory=dict)
    grid: Mapping[str, Sequence[Any]] = field(default_factory=dict)
    random: Mapping[str, Any] = field(default_factory=dict)
    draws: int = 0
    random_seed: int = 0
    seeds: int | Sequence[int] | None = None

    def __post_init__(self) -> None:
        if isinstance(self.source, Path):
            self.source = str(self.source)
        if not (isinstance(self.source, str) or callable(self.source)):
            raise TypeError(f"source must be a demo name, a demo path or a function building "
                            f"a Scene, got {self.source!r}")
        if not (isinstance(self.seconds, (int, float)) and math.isfinite(self.seconds)
                and 0 < self.seconds <= MAX_SECONDS):
            raise ValueError(f"seconds must be in (0, {MAX_SECONDS:g}], got {self.seconds!r}")
        if not (isinstance(self.fps, int) and 1 <= self.fps <= 240):
            raise ValueError(f"fps must be an integer in [1, 240], got {self.fps!r}")
        if self.clip is not None:
            if not (len(self.clip) == 2 and all(isinstance(s, int) and 16 <= s <= 8192
                                                 for s in self.clip)):
                raise ValueError(f"clip must be (width, height) with sides in [16, 8192] "
                                 f"pixels, or None; got {self.clip!r}")
            self.clip = (int(self.clip[0]), int(self.clip[1]))
        if isinstance(self.probes, str):
            self.probes = [self.probes]
        names = list(self.probes)
        if not isinstance(self.probes, Mapping):
            unknown = [n for n in names if n not in BUILTIN_PROBES]
            if unknown:
                raise ValueError(f"unknown probe {unknown[0]!r}; probes by name: "
                                 f"{', '.join(BUILTIN_PROBES)} (or pass {{name: function}})")
        else:
            for name, fn in self.probes.items():
                if not callable(fn):
                    raise TypeError(f"probe {name!r} must be a function of the world, got {fn!r}")
        if "t" in names:
            raise ValueError("probe name 't' is taken by the sample times")
        if not (isinstance(self.draws, int) and self.draws >= 0):
            raise ValueError(f"draws must be an integer >= 0, got {self.draws!r}")
        if self.random and self.draws == 0:
            raise ValueError("random ranges given but draws = 0: say how many draws to make")
        for name, values in self.grid.items():
            if isinstance(values, (str, bytes)) or not isinstance(values, Sequence) \
                    or len(values) == 0:
                raise ValueError(f"grid[{name!r}] must be a non-empty list of values, got "
                                 f"{values!r}")
        for name, space in self.random.items():
            _check_space(name, space)
        seeds = self.seed_list()
        if len(set(seeds)) != len(seeds):
            raise ValueError(f"seeds must be distinct, got {seeds}")
        given = [*self.fixed, *self.grid, *self.random]
        for name in given:
            if name in RESERVED and name != "seed":
                raise ValueError(f"parameter name {name!r} is reserved for the index table")
            if name == "seed":
                raise ValueError("give seeds with seeds=..., not as a parameter named 'seed'")
        twice = {n for n in given if given.count(n) > 1}
        if twice:
            raise ValueError(f"parameter {sorted(twice)[0]!r} is given more than once "
                             "(fixed, grid and random must not overlap)")

    # -- the runs ---------------------------------------------------------------------------------
    def seed_list(self) -> list[int | None]:
        if self.seeds is None:
            return [None]
        if isinstance(self.seeds, (int, np.integer)) and not isinstance(self.seeds, bool):
            if self.seeds < 1:
                raise ValueError(f"seeds must be >= 1 (how many), got {self.seeds}")
            return list(range(int(self.seeds)))
        seeds = list(self.seeds)
        if not seeds or not all(isinstance(s, (int, np.integer)) and not isinstance(s, bool)
                                for s in seeds):
            raise ValueError(f"seeds must be an int, a non-empty list of ints or None, got "
                             f"{self.seeds!r}")
        return [int(s) for s in seeds]

    def draw_list(self) -> list[dict[str, Any]]:
        """The random draws, the same on every machine (numpy's PCG64 from ``random_seed``)."""
        if not self.random:
            return [{}]
        rng = np.random.default_rng(self.random_seed)
        kinds = _demo_kinds(self.source)
        out = []
        for _ in range(self.draws):
            point = {}
            for name, space in self.random.items():  # insertion order: part of the sweep
                if isinstance(space, tuple):
                    low, high = space
                    if isinstance(low, int) and isinstance(high, int) \
                            and kinds.get(name, int) is int:
                        point[name] = int(rng.integers(low, high, endpoint=True))
                    else:
                        point[name] = float(rng.uniform(low, high))
                else:
                    point[name] = _plain(space[int(rng.integers(len(space)))])
            out.append(point)
        return out

    def runs(self) -> list[RunSpec]:
        """Every run, in order: grid points (last name fastest) × draws × seeds."""
        names = list(self.grid)
        points = [dict(zip(names, values))
                  for values in itertools.product(*(self.grid[n] for n in names))]
        out = []
        typed = _demo_types(self.source)
        for point, draw, seed in itertools.product(points, self.draw_list(), self.seed_list()):
            params = {k: typed(k, _plain(v)) for k, v in {**self.fixed, **point, **draw}.items()}
            out.append(RunSpec(run_id(params, seed), len(out), params, seed))
        ids = [r.run_id for r in out]
        if len(set(ids)) != len(ids):
            raise ValueError("two runs of this sweep have the same parameters and seed "
                             "(a repeated grid value?)")
        return out

    # -- what a folder remembers --------------------------------------------------------------
    def settings(self) -> dict[str, Any]:
        """What every run shares (written to ``sweep.json``; a rerun must match it)."""
        return {"source": source_name(self.source), "seconds": float(self.seconds),
                "fps": self.fps, "clip": list(self.clip) if self.clip else None,
                "probes": list(self.probes), "snapshot": bool(self.snapshot)}

    def probe_names(self) -> list[str]:
        return list(self.probes)


def _demo_kinds(source) -> dict[str, type]:
    """A demo's parameter types by name (a float parameter drawn from (0, 50) gets floats);
    empty for a scene function."""
    if not isinstance(source, str):
        return {}
    from .. import params as params_mod
    from ..demo import load_demo

    return {s.name: s.kind for s in params_mod.param_specs(load_demo(source).params_class)}


def _demo_types(source) -> Callable[[str, Any], Any]:
    """For a demo: each value as its parameter's type (1 and 1.0 are one run of a float
    parameter, "0.5" from a command line is 0.5); unknown names are left for the driver's
    check, which names them."""
    if not isinstance(source, str):
        return lambda name, value: value
    from .. import params as params_mod
    from ..demo import load_demo

    specs = {s.name: s for s in params_mod.param_specs(load_demo(source).params_class)}

    def typed(name: str, value: Any) -> Any:
        spec = specs.get(name)
        if spec is None:
            return value
        if spec.kind in (int, float) and isinstance(value, (int, float, str)) \
                and not isinstance(value, bool):
            try:
                return spec.kind(float(value)) if spec.kind is float else spec.check(value)
            except (TypeError, ValueError):
                return value
        return value

    return typed


def run_id(params: Mapping[str, Any], seed: int | None) -> str:
    """``run-`` and 12 hex digits of a digest of the parameters and seed (order-free)."""
    text = json.dumps({"params": params, "seed": seed}, sort_keys=True, separators=(",", ":"))
    return "run-" + hashlib.sha256(text.encode()).hexdigest()[:12]


def source_name(source) -> str:
    if isinstance(source, str):
        return source
    module = getattr(source, "__module__", "?")
    return f"{module}:{getattr(source, '__qualname__', repr(source))}"


def accepts_seed(fn: Callable) -> bool:
    try:
        parameters = inspect.signature(fn).parameters
    except (TypeError, ValueError):
        return False
    return "seed" in parameters or any(p.kind is p.VAR_KEYWORD for p in parameters.values())


def _check_space(name: str, space: Any) -> None:
    if isinstance(space, tuple):
        ok = len(space) == 2 and all(isinstance(v, (int, float)) and not isinstance(v, bool)
                                     and math.isfinite(v) for v in space) and space[0] <= space[1]
        if not ok:
            raise ValueError(f"random[{name!r}] as a range must be (low, high) with low <= high, "
                             f"got {space!r}")
    elif isinstance(space, list):
        if not space:
            raise ValueError(f"random[{name!r}] as choices must be a non-empty list")
    else:
        raise ValueError(f"random[{name!r}] must be (low, high) or a list of choices, got "
                         f"{space!r}")


def _plain(value: Any) -> Any:
    """numpy scalars as Python ones (JSON, the digest and CSV see the same value)."""
    if isinstance(value, np.generic):
        return value.item()
    if isinstance(value, (str, int, float, bool)) or value is None:
        return value
    raise TypeError(f"parameter values must be numbers, strings or booleans, got {value!r}")
