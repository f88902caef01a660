"""Sweeps and data sets: many runs of a demo or a scene function, on every core or a Ray cluster.

    >>> from pointmass import sweep
    >>> result = sweep.run("ball_pit", "pit_sweep", fixed={"count": 300},   # doctest: +SKIP
    ...                    grid={"restitution": [0.2, 0.8]}, seeds=3, seconds=2.0,
    ...                    clip=(160, 120), probes=["positions"])
    >>> data = sweep.load("pit_sweep")                                      # doctest: +SKIP
    >>> data[0].probes()["positions"].shape    # (frames, particles, 3)     # doctest: +SKIP

The folder holds ``sweep.json`` (what every run shares), ``runs/<run id>/`` (``meta.json``,
``clip.mp4``, ``probes.npz``, ``final.npz``) and ``index.csv`` (+ ``index.parquet`` with pyarrow).
Rerunning the same call skips complete runs; see ``folder`` for how a run is committed.
"""

from __future__ import annotations

from collections.abc import Callable, Mapping, Sequence
from pathlib import Path
from typing import Any

from .driver import SweepResult, SweepTerminated, default_workers, execute
from .index import Run, SweepData, load
from .spec import BUILTIN_PROBES, RunSpec, Sweep


def run(source: str | Path | Callable | Sweep, out: str | Path, *, seconds: float = 2.0,
        fps: int = 30, clip: tuple[int, int] | None = None,
        probes: Sequence[str] | Mapping[str, Callable] = (), snapshot: bool = True,
        fixed: Mapping[str, Any] | None = None, grid: Mapping[str, Sequence] | None = None,
        random: Mapping[str, Any] | None = None, draws: int = 0, random_seed: int = 0,
        seeds: int | Sequence[int] | None = None, backend: str = "pool",
        workers: int | None = None, ray_address: str | None = "auto",
        shared_folder: bool = False, max_retries: int = 3, retry_failed: bool = False,
        progress: bool = True) -> SweepResult:
    """Run a sweep into the folder ``out`` and write its index; returns a ``SweepResult``.

    The sweep's arguments (``source`` to ``seeds``) are those of ``Sweep``; or pass a ``Sweep``
    as ``source``. Then:

    Args:
        backend: "pool" (local processes, the default), "ray" (one task per run on a Ray
            cluster; ``pip install "pointmass[cluster]"``) or "serial" (this process).
        workers: Pool processes (default: every core); for ``ray_address="local"``, the
            private cluster's CPUs.
        ray_address: "auto" (the cluster started on this machine by ``ray start``), "local"
            (a private cluster for this call) or the head's "HOST:PORT".
        shared_folder: Ray workers write into ``out`` themselves (the same path on every
            node); otherwise they send their files back to the driver.
        max_retries: Times a run whose worker process died is tried again.
        retry_failed: Run again the runs recorded as failed by an earlier call.
        progress: A progress line on stderr.

    A run that raises is recorded with its error (``result.failed``) and the others go on.
    Ctrl-C or SIGTERM stops after the runs in flight are committed or discarded; the index is
    written and the KeyboardInterrupt re-raised. Calling again with the same sweep finishes it.
    """
    if isinstance(source, Sweep):
        sweep = source
    else:
        sweep = Sweep(source, seconds=seconds, fps=fps, clip=clip, probes=probes,
                      snapshot=snapshot, fixed=fixed or {}, grid=grid or {},
                      random=random or {}, draws=draws, random_seed=random_seed, seeds=seeds)
    return execute(sweep, out, backend=backend, workers=workers, ray_address=ray_address,
                   shared_folder=shared_folder, max_retries=max_retries,
                   retry_failed=retry_failed, progress=progress)


__all__ = ["BUILTIN_PROBES", "Run", "RunSpec", "Sweep", "SweepData", "SweepResult",
           "SweepTerminated", "default_workers", "load", "run"]
