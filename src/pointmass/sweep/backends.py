"""Where runs execute: in this process, or a local process pool (Ray: ``cluster``).

Each backend takes the runs still to do and calls ``on_done(run, meta)`` in the driver as each
one is committed. On KeyboardInterrupt (Ctrl-C, or SIGTERM turned into one) a backend stops
handing out runs, lets the runs in flight finish and commit (pool) or cancels them so their
temporary folders are removed (Ray), then re-raises.

Every worker runs numba and BLAS on one thread (``WORKER_ENV``): the cores are shared out by
running one run per core, which scales better than threads within a run at sweep sizes, and a
run's arithmetic is then the same whichever machine or backend executes it (the serial backend
runs in the caller's process, with its thread settings).
"""

from __future__ import annotations

import contextlib
import multiprocessing
import os
import pickle
import signal
import sys
from collections.abc import Callable
from concurrent.futures import FIRST_COMPLETED, ProcessPoolExecutor, wait
from concurrent.futures.process import BrokenProcessPool
from pathlib import Path

from .execute import execute_and_commit
from .spec import RunSpec, Sweep

OnDone = Callable[[RunSpec, dict], None]
OnCrash = Callable[[RunSpec, str], None]

#: One thread per worker for numba and for the BLAS numpy calls: measured here, a ball pit's
#: probes differed by 3e-16 after 55 frames between a process with the default BLAS threads and
#: a worker with one (they match bit for bit when both use one).
WORKER_ENV = {"NUMBA_NUM_THREADS": "1", "OMP_NUM_THREADS": "1", "OPENBLAS_NUM_THREADS": "1",
              "MKL_NUM_THREADS": "1"}


def run_serial(sweep: Sweep, runs: list[RunSpec], root: Path, on_done: OnDone,
               on_crash: OnCrash) -> None:
    """Every run in this process, one after another (debugging; a one-core baseline)."""
    for run in runs:
        on_done(run, execute_and_commit(sweep, run, str(root)))


def check_picklable(sweep: Sweep) -> bytes:
    try:
        return pickle.dumps(sweep)
    except Exception as exc:
        raise ValueError(f"the sweep cannot be sent to worker processes ({exc}): a scene "
                         "function or probe must be defined at the top level of a module "
                         "(not a lambda or a function inside another), or use "
                         "backend=\"serial\"") from None


@contextlib.contextmanager
def _environ(values: dict[str, str]):
    """Set environment variables while worker processes are spawned (they copy it then)."""
    old = {k: os.environ.get(k) for k in values}
    os.environ.update(values)
    try:
        yield
    finally:
        for k, v in old.items():
            if v is None:
                os.environ.pop(k, None)
            else:
                os.environ[k] = v


@contextlib.contextmanager
def _main_hidden(needed: bool):
    """Spawned workers normally run the parent's main script again (as ``__mp_main__``) before
    they work, which runs a script's unguarded top-level sweep in every worker. When nothing of
    the sweep lives in ``__main__`` the workers do not need it: hide it while they start (as
    loky/joblib's workers do). A scene function defined in a script still needs the usual
    ``if __name__ == "__main__":`` guard."""
    main = sys.modules.get("__main__")
    if needed or main is None:
        yield
        return
    saved = {k: main.__dict__[k] for k in ("__file__", "__spec__") if k in main.__dict__}
    main.__dict__.pop("__file__", None)
    main.__spec__ = None
    try:
        yield
    finally:
        main.__dict__.update(saved)
        if "__spec__" not in saved:
            main.__dict__.pop("__spec__", None)


def _worker_init() -> None:
    # Ctrl-C reaches the whole process group; the driver alone decides what stops, so a run in
    # flight finishes and commits instead of dying half-written.
    signal.signal(signal.SIGINT, signal.SIG_IGN)


def run_pool(sweep: Sweep, runs: list[RunSpec], root: Path, on_done: OnDone,
             on_crash: OnCrash, *, workers: int, max_retries: int) -> None:
    """A local process pool of ``workers`` spawned processes. If a worker process dies (the
    OOM killer, a segfault in a user's code), the pool is started again for the runs not yet
    done, at most ``max_retries`` times; the runs still left are then recorded as crashed."""
    needs_main = b"__main__" in check_picklable(sweep)
    if needs_main and getattr(sys.modules.get("__main__"), "__file__", None) is None:
        raise ValueError("the scene function (or a probe) is defined in a notebook or an "
                         "interactive session, which worker processes cannot import: move it "
                         "into a module, or use backend=\"ray\" or \"serial\"")
    todo = list(runs)
    for _attempt in range(max_retries + 1):
        lost = _pool_pass(sweep, todo, root, on_done, on_crash, workers, needs_main)
        if not lost:
            return
        todo = lost
    for run in todo:
        on_crash(run, f"WorkerCrashed: a worker process died {max_retries + 1} times while "
                      "this run was in flight")


def _pool_pass(sweep, runs, root, on_done, on_crash, workers, needs_main) -> list[RunSpec]:
    """One pool's life; returns the runs lost to a dead worker (or never started after it).

    Runs are handed out one per idle worker, never queued ahead: a stop then waits only for
    the runs actually executing (ProcessPoolExecutor would otherwise also run the calls it
    has already queued for its workers)."""
    context = multiprocessing.get_context("spawn")  # no fork of a process with numba threads
    size = min(workers, len(runs))
    waiting = list(reversed(runs))
    futures: dict = {}

    broken = False

    def submit() -> None:
        nonlocal broken
        # Python 3.11 starts the workers during the first submits: both take effect for them.
        with _environ(WORKER_ENV), _main_hidden(needs_main):
            try:
                future = pool.submit(execute_and_commit, sweep, waiting[-1], str(root))
            except BrokenProcessPool:  # a worker died; the runs left go to the next pool
                broken = True
                return
        futures[future] = waiting.pop()

    pool = ProcessPoolExecutor(size, mp_context=context, initializer=_worker_init)
    lost: list[RunSpec] = []
    try:
        for _ in range(size):
            submit()
        pending = set(futures)
        while pending:
            done, pending = wait(pending, return_when=FIRST_COMPLETED)
            for future in done:
                run = futures.pop(future)
                try:
                    meta = future.result()
                except BrokenProcessPool:
                    lost.append(run)
                    broken = True
                    continue
                except Exception as exc:  # the machinery failed (disk, pickling), not the run
                    from .execute import one_line

                    on_crash(run, one_line(exc))
                else:
                    on_done(run, meta)
                if waiting and not broken:
                    submit()
            # what is still out: not ``pending`` updated inside the loop above, which held the
            # other futures of ``done`` not yet handled (two finishing at once, as every one
            # does when a worker dies, made the next wait return a handled one: KeyError)
            pending = set(futures)
    except BaseException:
        # Ctrl-C/SIGTERM: nothing new starts; the runs in flight finish and commit.
        pool.shutdown(wait=True, cancel_futures=True)
        for future, run in futures.items():
            if future.done() and not future.cancelled() and future.exception() is None:
                on_done(run, future.result())
        raise
    pool.shutdown(wait=True)
    return sorted(lost + waiting, key=lambda r: r.index)
