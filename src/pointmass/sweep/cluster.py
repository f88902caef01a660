"""The Ray backend: one task per run on a Ray cluster (``pip install "pointmass[cluster]"``).

Ray is imported only here, and only when asked for. See ``backends`` for what a backend does
on a stop, and why workers run one thread.
"""

from __future__ import annotations

import contextlib
import socket
from pathlib import Path

from .backends import WORKER_ENV, OnCrash, OnDone
from .execute import execute_and_commit, execute_returning_files, write_returned
from .spec import RunSpec, Sweep

RAY_MISSING = ('the Ray backend needs ray, which is not installed: pip install '
               '"pointmass[cluster]"')


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
