"""Where runs execute: in this process, a local process pool, or a Ray cluster.

Each backend takes the runs still to do and calls ``on_done(run, meta)`` in the driver as each
one is committed. On KeyboardInterrupt (Ctrl-C, or SIGTERM turned into one) a backend stops
handing out runs, lets the runs in flight finish and commit (pool) or cancels them so their
temporary folders are removed (Ray), then re-raises.

Every worker runs numba on one thread (NUMBA_NUM_THREADS=1): the cores are shared out by
running one run per core, which scales better than threads within a run at sweep sizes, and a
run's arithmetic is then the same whichever machine or backend executes it.
"""

from __future__ import annotations

import contextlib
import multiprocessing
import os
import pickle
import signal
import socket
import sys
from collections.abc import Callable
from concurrent.futures import FIRST_COMPLETED, ProcessPoolExecutor, wait
from concurrent.futures.process import BrokenProcessPool
from pathlib import Path

from .execute import execute_and_commit, execute_returning_files, write_returned
from .spec import RunSpec, Sweep

OnDone = Callable[[RunSpec, dict], None]
OnCrash = Callable[[RunSpec, str], None]

#: One thread per worker for numba and for the BLAS numpy calls: measured here, a ball pit's
#: probes differed by 3e-16 after 55 frames between a process with the default BLAS threads and
#: a worker with one (they match bit for bit when both use one).
WORKER_ENV = {"NUMBA_NUM_THREADS": "1", "OMP_NUM_THREADS": "1", "OPENBLAS_NUM_THREADS": "1",
              "MKL_NUM_THREADS": "1"}

RAY_MISSING = ('the Ray backend needs ray, which is not installed: pip install '
               '"pointmass[cluster]"')


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


# -- Ray -----------------------------------------------------------------------------------------
def _ray_task(sweep: Sweep, run: RunSpec, root: str | None):
    """A Ray task: one run, written to the shared ``root`` or returned as files."""
    if root is not None:
        return execute_and_commit(sweep, run, root)
    return execute_returning_files(sweep, run)


def import_ray():
    try:
        import ray
    except ImportError:
        from ..extras import MissingExtra

        raise MissingExtra(RAY_MISSING) from None
    return ray


def connect_ray(address: str | None, workers: int | None = None):
    """Connect to the cluster at ``address`` ("auto": the one started on this machine with
    ``ray start``; "local": a private one for this sweep; or "HOST:PORT" of its head); returns
    (ray, whether this call connected, so must disconnect). Fails in seconds with one line when
    there is no cluster there (Ray itself retries for minutes)."""
    ray = import_ray()
    if ray.is_initialized():
        return ray, False
    options = {"log_to_driver": False, "configure_logging": False}
    if address == "local":
        # A private single-machine cluster: it talks over loopback only, and nothing listens
        # on the machine's network interfaces.
        ray.init(num_cpus=workers, include_dashboard=False, _node_ip_address="127.0.0.1",
                 **options)
        return ray, True
    if address not in (None, "auto") and not address.startswith("ray://"):
        host, _, port = address.rpartition(":")
        if not host or not port.isdigit():
            raise ValueError(f"ray address must be auto, local or HOST:PORT, got {address!r}")
        try:
            socket.create_connection((host.strip("[]"), int(port)), timeout=10).close()
        except OSError as exc:
            raise ConnectionError(f"no Ray cluster at {address} ({exc.strerror or exc}); start "
                                  "one with `ray start --head`") from None
    try:
        ray.init(address=address, **options)
    except ConnectionError as exc:
        raise ConnectionError(f"no Ray cluster found ({str(exc).splitlines()[0]}); start one "
                              "with `ray start --head`, or pass its HOST:PORT") from None
    return ray, True


def run_ray(sweep: Sweep, runs: list[RunSpec], root: Path, on_done: OnDone, on_crash: OnCrash,
            *, max_retries: int, shared_folder: bool) -> None:
    """One Ray task per run on the connected cluster (``connect_ray``).

    A task whose worker process dies is retried by Ray up to ``max_retries`` times. With
    ``shared_folder`` the workers write into ``root`` themselves (it must be the same path on
    every node, e.g. NFS); otherwise each returns its files and the driver writes them.
    """
    ray = import_ray()
    task = ray.remote(_ray_task).options(
        num_cpus=1, max_retries=max_retries, retry_exceptions=False,
        runtime_env={"env_vars": dict(WORKER_ENV)})
    target = str(root.resolve()) if shared_folder else None
    sweep_ref = ray.put(sweep)
    refs = {task.remote(sweep_ref, run, target): run for run in runs}
    pending = list(refs)
    try:
        while pending:
            done, pending = ray.wait(pending, num_returns=1)
            for ref in done:
                _ray_result(ray, ref, refs[ref], root, shared_folder, on_done, on_crash)
    except BaseException:
        # Ctrl-C/SIGTERM: cancel what is queued or running (a running task gets a
        # KeyboardInterrupt and removes its temporary folder); keep what already finished.
        for ref in pending:
            ray.cancel(ref)
        ready, _ = ray.wait(pending, num_returns=len(pending), timeout=30)
        for ref in ready:
            with contextlib.suppress(Exception):
                _ray_result(ray, ref, refs[ref], root, shared_folder, on_done, on_crash)
        raise


def _ray_result(ray, ref, run, root, shared_folder, on_done, on_crash) -> None:
    from .execute import one_line

    try:
        result = ray.get(ref)
    except ray.exceptions.TaskCancelledError:
        return
    except ray.exceptions.RayError as exc:
        # A worker died more often than max_retries, or the task could not run at all.
        cause = getattr(exc, "cause", None)
        on_crash(run, one_line(cause if isinstance(cause, BaseException) else exc))
        return
    if shared_folder:
        on_done(run, result)
        return
    meta, files = result
    write_returned(root, meta, files)
    on_done(run, meta)
