"""One run of a sweep, in whichever process executes it: build, step, sample, record, write.

The probes are sampled at the clip's frame times — frame k at k/fps, the simulation advancing
1/fps between frames exactly as ``pointmass record`` does — so frame k of ``clip.mp4`` and
sample k of ``probes.npz`` show the same instant, and a run without a clip takes the same steps
(bit-identical probes). The renderer is imported only when a clip is asked for, so a probes-only
sweep never loads GL, and one GL context per worker process is reused from run to run.
"""

from __future__ import annotations

import math
import os
import shutil
import socket
import tempfile
import time
from datetime import UTC, datetime
from pathlib import Path
from typing import Any

import numpy as np

from . import folder as layout
from .spec import RunSpec, Sweep

CLIP = "clip.mp4"
PROBES = "probes.npz"
FINAL = "final.npz"

_demos: dict[str, Any] = {}     # demo source -> loaded Demo (a worker loads each file once)
_gl: dict[str, Any] = {}        # this process's offscreen renderer, reused by every clip


def one_line(exc: BaseException) -> str:
    """``Type: first line of the message`` (what the index records for a failed run)."""
    text = str(exc).strip().splitlines()
    return f"{type(exc).__name__}: {text[0]}" if text else type(exc).__name__


def simulation_for(sweep: Sweep, run: RunSpec):
    """The run's Simulation: the demo with the run's parameters (and seed), or the function's
    Scene or Simulation."""
    from .. import params as params_mod
    from ..scene import Scene
    from ..simulation import Simulation

    if isinstance(sweep.source, str):
        from ..demo import load_demo

        demo = _demos.get(sweep.source)
        if demo is None:
            demo = _demos[sweep.source] = load_demo(sweep.source)
        params = demo.default_params()
        values = dict(run.params)
        if run.seed is not None:
            values["seed"] = run.seed
        if values and params is None:
            raise ValueError(f"demo {demo.name!r} has no parameters to set")
        for name, value in values.items():
            params_mod.set_param(params, name, value)
        return Simulation(demo, params)
    kwargs = dict(run.params)
    if run.seed is not None:
        kwargs["seed"] = run.seed
    built = sweep.source(**kwargs)
    if isinstance(built, Simulation):
        return built
    if isinstance(built, Scene):
        return Simulation(built)
    raise TypeError(f"the scene function must return a Scene or a Simulation, got "
                    f"{type(built).__name__}")


def _quantity(name: str, fn):
    if fn is not None:
        return fn
    return {
        "positions": lambda w: w.particles.position.copy(),
        "velocities": lambda w: w.particles.velocity.copy(),
        "contacts": lambda w: float(w.contacts.count),
        "kinetic_energy": lambda w: w.kinetic_energy(),
        "potential_energy": lambda w: w.potential_energy(),
        "body_positions": lambda w: w.bodies.position.copy(),
        "body_orientations": lambda w: w.bodies.orientation.copy(),
    }[name]


class _Sampler:
    """Samples the sweep's probes at each frame."""

    def __init__(self, sweep: Sweep, sim) -> None:
        self.sim = sim
        probes = sweep.probes
        self.quantities = {name: _quantity(name, probes[name] if isinstance(probes, dict)
                                           else None) for name in probes}
        self.t: list[float] = []
        self.values: dict[str, list] = {name: [] for name in self.quantities}

    def __call__(self, _frame: int = 0) -> None:
        world = self.sim.world
        self.t.append(float(world.time))
        for name, fn in self.quantities.items():
            self.values[name].append(np.array(fn(world), dtype=np.float64))

    def save(self, path: Path) -> None:
        arrays = {"t": np.array(self.t)}
        for name, values in self.values.items():
            shapes = {v.shape for v in values}
            if len(shapes) > 1:
                raise ValueError(f"probe {name!r} changed shape during the run: {sorted(shapes)}")
            arrays[name] = np.stack(values)
        np.savez(path, **arrays)


def _save_final(sim, path: Path) -> None:
    world = sim.world
    arrays = {"time": np.array(world.time)}
    arrays.update({f"particles.{k}": v for k, v in world.particles.snapshot().items()})
    if len(world.bodies):
        arrays.update({f"bodies.{k}": v for k, v in world.bodies.snapshot().items()})
    np.savez(path, **arrays)


def _clip(sim, path: Path, sweep: Sweep, on_frame) -> None:
    from ..render import Renderer, create_headless_context
    from ..render.recording import record

    if "renderer" not in _gl:
        _gl["renderer"] = Renderer(create_headless_context(), sweep.clip)
    result = record(sim, path, seconds=sweep.seconds, fps=sweep.fps, size=sweep.clip,
                    progress=False, on_frame=on_frame, renderer=_gl["renderer"])
    if not result.complete:
        raise RuntimeError(f"the clip has {result.frames} of {result.expected} frames")


def execute_into(sweep: Sweep, run: RunSpec, out: Path) -> dict[str, Any]:
    """Run ``run`` and write its outputs and ``meta.json`` into the folder ``out``; returns the
    meta. A run that raises is recorded (outcome "error", its one-line error) with no outputs;
    KeyboardInterrupt and SystemExit propagate."""
    from .. import __version__

    started = time.perf_counter()
    steps = frames = 0
    sim_seconds = 0.0
    outputs: list[str] = []
    error = None
    every_param = None
    try:
        sim = simulation_for(sweep, run)
        every_param = sim.param_values() or None  # a demo's whole Params, defaults included
        t0, dt = sim.time, sim.dt
        sampler = _Sampler(sweep, sim)
        total = max(1, round(sweep.seconds * sweep.fps))
        if sweep.clip is not None:
            _clip(sim, out / CLIP, sweep, sampler)
            outputs.append(CLIP)
        else:
            for _ in range(total):
                sampler()
                sim.advance(1.0 / sweep.fps)
        frames = len(sampler.t)
        steps = round((sim.time - t0) / dt)
        sim_seconds = sim.time - t0
        if sampler.quantities:
            sampler.save(out / PROBES)
            outputs.append(PROBES)
        if sweep.snapshot:
            _save_final(sim, out / FINAL)
            outputs.append(FINAL)
    except Exception as exc:
        error = one_line(exc)
        for child in out.iterdir():  # a failed run keeps no half-made outputs
            shutil.rmtree(child) if child.is_dir() else child.unlink()
        outputs = []
        if 'sim' in locals() and math.isfinite(sim.time - t0):
            steps = round((sim.time - t0) / dt)
            sim_seconds = sim.time - t0
    meta = {
        "run_id": run.run_id, "index": run.index, "params": run.params, "seed": run.seed,
        "demo_params": every_param,
        "source": sweep.settings()["source"], "pointmass_version": __version__,
        "outcome": "error" if error else "ok", "error": error,
        "steps": steps, "frames": frames, "sim_seconds": sim_seconds,
        "wall_seconds": time.perf_counter() - started,
        "outputs": outputs, "host": socket.gethostname(), "pid": os.getpid(),
        "finished_at": datetime.now(UTC).isoformat(timespec="seconds"),
    }
    layout.write_json(out / layout.META, meta)
    return meta


def execute_and_commit(sweep: Sweep, run: RunSpec, root: str) -> dict[str, Any]:
    """Run into a temporary folder under ``root`` and rename it into place (the worker side of
    the pool, and of Ray with a shared folder)."""
    root = Path(root)
    tmp = layout.new_tmp_dir(root, run.run_id)
    try:
        meta = execute_into(sweep, run, tmp)
        layout.commit(tmp, root, run.run_id)
    except BaseException:
        shutil.rmtree(tmp, ignore_errors=True)
        raise
    return meta


def execute_returning_files(sweep: Sweep, run: RunSpec) -> tuple[dict, dict[str, bytes]]:
    """Run into a local temporary folder and return the meta and every file's bytes (Ray
    workers that do not share the driver's disk)."""
    tmp = Path(tempfile.mkdtemp(prefix="pointmass-run-"))
    try:
        meta = execute_into(sweep, run, tmp)
        return meta, {p.name: p.read_bytes() for p in tmp.iterdir() if p.is_file()}
    finally:
        shutil.rmtree(tmp, ignore_errors=True)


def write_returned(root: Path, meta: dict, files: dict[str, bytes]) -> None:
    """The driver's side of ``execute_returning_files``: write, then commit atomically."""
    tmp = layout.new_tmp_dir(root, meta["run_id"])
    try:
        for name, data in files.items():
            if name != layout.META:
                (tmp / name).write_bytes(data)
        (tmp / layout.META).write_bytes(files[layout.META])  # last: it marks the run complete
        layout.commit(tmp, root, meta["run_id"])
    except BaseException:
        shutil.rmtree(tmp, ignore_errors=True)
        raise


def record_crash(sweep: Sweep, run: RunSpec, root: Path, error: str) -> None:
    """Commit a run that never finished (its worker died, its task was lost) as failed."""
    from .. import __version__

    tmp = layout.new_tmp_dir(root, run.run_id)
    layout.write_json(tmp / layout.META, {
        "run_id": run.run_id, "index": run.index, "params": run.params, "seed": run.seed,
        "source": sweep.settings()["source"], "pointmass_version": __version__,
        "outcome": "error", "error": error, "steps": 0, "frames": 0, "sim_seconds": 0.0,
        "wall_seconds": 0.0, "outputs": [], "host": socket.gethostname(), "pid": None,
        "finished_at": datetime.now(UTC).isoformat(timespec="seconds")})
    layout.commit(tmp, root, run.run_id)
