"""Compile (or load from the cache) the kernels the demos use, before anyone waits for them:
``pointmass warmup``, run by ``scripts/setup.sh``.

Each demo is built and stepped for ``SECONDS`` of simulated time, with its fire/throw key
pressed a little after the start so the kernels of what it throws (sphere against box, ...)
compile too. numba writes every kernel it compiles to its cache (``pointmass.numba_cache``);
later runs load them in about a second.
"""

from __future__ import annotations

import sys
import time

from . import compiling

#: Simulated seconds each demo runs (contacts form, thrown things land).
SECONDS = 1.5
#: At most this many steps per demo (a fine-stepped demo stays quick).
MAX_STEPS = 150
#: Keys pressed after the first few steps: the demos' fire, throw, detonate and stir.
PRESS = ("SPACE", "CLICK")


def warm_demo(name: str) -> int:
    """Build demo ``name`` and run it briefly; returns the steps taken."""
    from .simulation import Simulation

    sim = Simulation(name)
    steps = min(MAX_STEPS, max(1, round(SECONDS / sim.dt)))
    keys = set(sim.demo.keys) if sim.demo is not None else set()
    for k in range(steps):
        if k == 5:
            for key in PRESS:
                if key in keys:
                    sim.press(key)
        sim.step()
    return steps


def warm_render() -> None:
    """The renderer's CPU kernels (the blob-shadow splat), when the render extra is there."""
    try:
        from .render import shadow_splat
    except ImportError:
        return
    shadow_splat.warm()


def warm(names: list[str] | None = None, *, stream=None) -> float:
    """Warm the cache for ``names`` (default: every demo), one progress line per demo on
    ``stream`` (stderr). Returns the wall-clock seconds taken."""
    from .demo import list_demos

    stream = sys.stderr if stream is None else stream
    names = names or [d.name for d in list_demos()]
    watch = compiling.install()
    kernels_before, started = watch.kernels, time.perf_counter()
    for i, name in enumerate(names, start=1):
        t0, k0 = time.perf_counter(), watch.kernels
        warm_demo(name)
        print(f"warmup [{i}/{len(names)}] {name}: {watch.kernels - k0} kernels compiled, "
              f"{time.perf_counter() - t0:.1f} s", file=stream, flush=True)
    t0, k0 = time.perf_counter(), watch.kernels
    warm_render()
    if watch.kernels > k0:
        print(f"warmup: renderer, {watch.kernels - k0} kernels compiled, "
              f"{time.perf_counter() - t0:.1f} s", file=stream, flush=True)
    took = time.perf_counter() - started
    from .numba_cache import cache_dir

    where = cache_dir() or "numba's default folder"
    print(f"warmup: {watch.kernels - kernels_before} kernels compiled in {took:.0f} s; cached "
          f"in {where}", file=stream, flush=True)
    return took
