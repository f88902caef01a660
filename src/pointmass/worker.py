"""One daemon thread that runs physics jobs in order, so the main thread stays free for a
window's drawing and for signals.

Why not ``concurrent.futures.ThreadPoolExecutor``: its threads are joined at interpreter exit,
so a Ctrl-C during a first step's numba compile (a minute, in the worker) left the process alive
until the compile ended. A daemon thread is not waited for. And why run a recording's steps here
at all: Python runs signal handlers only in the main thread, between bytecodes; a kernel
compiling in the main thread spends seconds inside LLVM, and Ctrl-C waited for it. With the
compile here, the main thread waits on a lock, which a signal interrupts at once.
"""

from __future__ import annotations

import queue
import threading
from collections.abc import Callable
from concurrent.futures import Future
from typing import Any

_STOP = object()
#: Jobs running now, over every Worker.
_busy = 0
_busy_lock = threading.Lock()


class Worker:
    """Runs submitted callables one at a time in a daemon thread (started on first use)."""

    def __init__(self, name: str = "pointmass-physics") -> None:
        self.name = name
        self._jobs: queue.SimpleQueue = queue.SimpleQueue()
        self._thread: threading.Thread | None = None
        self._lock = threading.Lock()

    def submit(self, fn: Callable[..., Any], *args: Any, **kwargs: Any) -> Future:
        future: Future = Future()
        with self._lock:
            if self._thread is None or not self._thread.is_alive():
                self._thread = threading.Thread(target=self._run, name=self.name, daemon=True)
                self._thread.start()
            self._jobs.put((future, fn, args, kwargs))
        return future

    def call(self, fn: Callable[..., Any], *args: Any, **kwargs: Any) -> Any:
        """Run ``fn`` in the worker and wait for it; a signal (Ctrl-C) interrupts the wait at
        once (the job is left to finish, or to die with the process)."""
        future = self.submit(fn, *args, **kwargs)
        while True:
            try:
                return future.result(timeout=0.1)
            except TimeoutError:
                continue

    def _run(self) -> None:
        while True:
            job = self._jobs.get()
            if job is _STOP:
                return
            future, fn, args, kwargs = job
            if not future.set_running_or_notify_cancel():
                continue
            _count(+1)
            try:
                result = fn(*args, **kwargs)
            except BaseException as exc:  # handed to the waiting thread
                _count(-1)  # before the waiter wakes: it may ask busy() at once
                future.set_exception(exc)
            else:
                _count(-1)
                future.set_result(result)

    def shutdown(self) -> None:
        """Stop after the queued jobs (does not wait)."""
        self._jobs.put(_STOP)


def _count(delta: int) -> None:
    global _busy  # noqa: PLW0603 (one count per process)
    with _busy_lock:
        _busy += delta


_shared: Worker | None = None


def shared() -> Worker:
    """The process's worker for recordings and renders."""
    global _shared  # noqa: PLW0603 (one worker per process, made on first use)
    if _shared is None:
        _shared = Worker()
    return _shared


def call(fn: Callable[..., Any], *args: Any, **kwargs: Any) -> Any:
    """``shared().call(...)``: run in the physics worker, wait interruptibly."""
    return shared().call(fn, *args, **kwargs)


def busy() -> bool:
    """True while any worker thread is inside a job (a compile or steps left behind by
    Ctrl-C)."""
    return _busy > 0
