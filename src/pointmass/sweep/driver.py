"""Running a sweep: check it, skip what the folder already has, hand the rest to a backend,
write the index. Safe to stop and to rerun (see ``folder``)."""

from __future__ import annotations

import contextlib
import os
import shutil
import signal
import sys
import threading
import time
from dataclasses import dataclass, field
from pathlib import Path

from . import backends, cluster
from . import folder as layout
from .index import rows_for, write_index
from .progress import SweepProgress
from .spec import RunSpec, Sweep, accepts_seed, source_name

BACKENDS = ("pool", "ray", "serial")


@dataclass
class SweepResult:
    """What a call to ``run`` did."""

    folder: Path
    total: int                      # runs in the sweep
    executed: int = 0               # runs executed by this call
    skipped: int = 0                # runs already complete in the folder
    failed: dict[str, str] = field(default_factory=dict)  # run id -> one-line error (all)
    seconds: float = 0.0            # wall time of this call
    interrupted: bool = False

    def summary(self) -> str:
        state = "stopped early" if self.interrupted else "done"
        failed = f", {len(self.failed)} failed" if self.failed else ""
        return (f"sweep {state}: {self.executed} runs executed, {self.skipped} already done"
                f"{failed} of {self.total}, {self.seconds:.1f} s; index in "
                f"{self.folder / 'index.csv'}")


class SweepTerminated(KeyboardInterrupt):
    """SIGTERM during a sweep run from Python: stop like Ctrl-C (runs in flight are committed
    or discarded, the index is written)."""


def check_runs(sweep: Sweep, runs: list[RunSpec]) -> None:
    """Refuse bad parameter names and values before anything runs (a demo's Params say which
    exist and their ranges); a function's parameters can only be checked by calling it."""
    if isinstance(sweep.source, str):
        from .. import params as params_mod
        from ..demo import load_demo

        demo = load_demo(sweep.source)
        for run in runs:
            params = demo.default_params()
            if params is None:
                if run.params or run.seed is not None:
                    raise ValueError(f"demo {demo.name!r} has no parameters (no Params), so "
                                     "it takes no parameters or seeds")
                continue
            for name, value in run.params.items():
                params_mod.set_param(params, name, value)
            if run.seed is not None:
                if not any(s.name == "seed" for s in params_mod.param_specs(params)):
                    raise ValueError(f"seeds: demo {demo.name!r} has no 'seed' parameter, so "
                                     "every seed would give the same run")
                params_mod.set_param(params, "seed", run.seed)
    elif sweep.seed_list() != [None] and not accepts_seed(sweep.source):
        raise ValueError(f"seeds: the scene function {source_name(sweep.source)} takes no "
                         "'seed' argument")


def default_workers() -> int:
    """Every core this process may use."""
    try:
        return len(os.sched_getaffinity(0))
    except AttributeError:
        return os.cpu_count() or 1


@contextlib.contextmanager
def _sigterm_stops():
    """While a sweep runs from Python, SIGTERM stops it like Ctrl-C (a handler set by the
    caller, such as the CLI's, is kept)."""
    if threading.current_thread() is not threading.main_thread() or \
            signal.getsignal(signal.SIGTERM) is not signal.SIG_DFL:
        yield
        return

    def stop(signum, frame):
        raise SweepTerminated("SIGTERM")

    signal.signal(signal.SIGTERM, stop)
    try:
        yield
    finally:
        signal.signal(signal.SIGTERM, signal.SIG_DFL)


def execute(sweep: Sweep, out: str | Path, *, backend: str = "pool", workers: int | None = None,
            ray_address: str | None = "auto", shared_folder: bool = False,
            max_retries: int = 3, retry_failed: bool = False, progress: bool = True
            ) -> SweepResult:
    """Run ``sweep`` into the folder ``out`` (see ``pointmass.sweep.run``)."""
    if backend not in BACKENDS:
        raise ValueError(f"backend must be one of {', '.join(BACKENDS)}, got {backend!r}")
    if workers is not None and not (isinstance(workers, int) and workers >= 1):
        raise ValueError(f"workers must be an integer >= 1 or None (every core), got {workers!r}")
    if not (isinstance(max_retries, int) and max_retries >= 0):
        raise ValueError(f"max_retries must be an integer >= 0, got {max_retries!r}")
    runs = sweep.runs()
    check_runs(sweep, runs)
    disconnect = None
    if backend == "ray":  # before anything is written: no ray, or no cluster, is one line
        ray, connected = cluster.connect_ray(ray_address, workers)
        disconnect = ray.shutdown if connected else None
    try:
        return _execute(sweep, runs, Path(out), backend, workers, shared_folder, max_retries,
                        retry_failed, progress)
    finally:
        if disconnect is not None:
            disconnect()


def _execute(sweep, runs, root, backend, workers, shared_folder, max_retries, retry_failed,
             progress) -> SweepResult:
    root.mkdir(parents=True, exist_ok=True)
    (root / layout.RUNS).mkdir(exist_ok=True)
    started = time.perf_counter()
    result = SweepResult(root, len(runs))
    with layout.FolderLock(root), _sigterm_stops():
        layout.check_settings(root, sweep.settings())
        layout.remove_stale(root)
        todo = []
        for run in runs:
            meta = layout.read_meta(root, run.run_id)
            if meta is not None and meta["outcome"] == "error" and retry_failed:
                shutil.rmtree(layout.run_dir(root, run.run_id))
                meta = None
            if meta is None:
                todo.append(run)
        result.skipped = len(runs) - len(todo)
        bar = SweepProgress(len(todo), result.skipped, enabled=progress)

        def on_done(run: RunSpec, meta: dict) -> None:
            result.executed += 1
            bar.update(failed=meta["outcome"] != "ok")

        def on_crash(run: RunSpec, error: str) -> None:
            # The run never wrote its meta (its worker died, the task was lost): record it.
            from .execute import record_crash

            record_crash(sweep, run, root, error)
            on_done(run, {"outcome": "error"})

        try:
            if not todo:
                pass
            elif backend == "serial":
                backends.run_serial(sweep, todo, root, on_done, on_crash)
            elif backend == "pool":
                backends.run_pool(sweep, todo, root, on_done, on_crash,
                                  workers=workers or default_workers(), max_retries=max_retries)
            else:
                cluster.run_ray(sweep, todo, root, on_done, on_crash,
                                 max_retries=max_retries, shared_folder=shared_folder)
        except KeyboardInterrupt:
            result.interrupted = True
            raise
        finally:
            bar.close()
            # What a worker killed mid-run left (Ray with a shared folder: the worker cannot
            # clean up after its own death); nothing is in flight any more.
            layout.remove_stale(root)
            rows = rows_for(root, runs)
            write_index(root, rows)
            result.failed = {r["run_id"]: r["error"] for r in rows if r["outcome"] != "ok"}
            result.seconds = time.perf_counter() - started
            if result.interrupted and progress:
                print(f"sweep stopped: {len(rows)} of {len(runs)} runs are in {root}; run the "
                      "same sweep again to finish it", file=sys.stderr)
    return result
