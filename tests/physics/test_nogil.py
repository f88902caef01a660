"""The step's compiled kernels release the GIL (``nogil=True``), so the window can run physics
in a worker thread while the main thread draws (issue 9; benchmarks/bench_gil.py measures it)."""

from __future__ import annotations

import importlib
import pkgutil

import pytest
from numba.core.registry import CPUDispatcher

import pointmass

#: Every module of the core (the window and the renderer have no kernels, and import GL).
MODULES = tuple(m.name for m in pkgutil.walk_packages(pointmass.__path__, "pointmass.")
                if not m.name.startswith(("pointmass.app", "pointmass.render",
                                          "pointmass.cli", "pointmass.__main__")))


def _kernels():
    for name in MODULES:
        module = importlib.import_module(name)
        for attr, value in vars(module).items():
            if isinstance(value, CPUDispatcher) and value.__module__ == name \
                    and value.targetoptions.get("inline", "never") == "never":
                yield f"{name}.{attr}", value


@pytest.mark.parametrize("name,kernel", list(_kernels()), ids=lambda x: x if isinstance(x, str)
                         else "")
def test_step_kernels_release_the_gil(name, kernel):
    assert kernel.targetoptions.get("nogil") is True, f"{name} holds the GIL while it runs"


def test_a_step_in_a_thread_matches_one_in_line():
    import threading

    import numpy as np

    pm = pointmass

    a, b = pm.Simulation("ball_pit", overrides=["count=300"]), \
        pm.Simulation("ball_pit", overrides=["count=300"])
    a.advance(1.0)
    worker = threading.Thread(target=b.advance, args=(1.0,))
    worker.start()
    worker.join()
    assert np.array_equal(a.world.particles.position, b.world.particles.position)
    assert np.array_equal(a.world.particles.velocity, b.world.particles.velocity)
