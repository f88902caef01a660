"""Is numba compiling now? A listener on numba's compile events, so a window, a recording or a
notebook can say "compiling physics kernels (first run only)" while it happens.

Why events and not a timer: numba fires ``numba:compile`` only for a real compilation, never
for a kernel loaded from its cache (``Dispatcher.compile`` returns a cached overload before the
event), so a warm run shows no notice and a cold one shows it from the first kernel on, whatever
the machine's speed. Compiles nest (a kernel compiles the kernels it calls) and come one after
another during a first step; they count as one *burst* until none has run for ``QUIET_SECONDS``.
numba compiles under one global lock, so bursts from several threads never interleave.
"""

from __future__ import annotations

import sys
import threading
import time

from numba.core import event

#: What every front end shows while a burst lasts.
NOTICE = "compiling physics kernels (first run only)"
#: A burst ends when no compile has run for this long [s] (kernels of one step compile one
#: after the other, with a little Python between them).
QUIET_SECONDS = 0.5


class _Watch(event.Listener):
    """numba:compile listener: nesting depth, burst start, kernels compiled."""

    def __init__(self) -> None:
        self._lock = threading.Lock()
        self.depth = 0
        self.burst_start: float | None = None
        self.last_end = -1e9
        self.kernels = 0          # outermost compiles since import
        self.seconds = 0.0        # time spent in outermost compiles since import
        self._outer_start = 0.0
        self.on_burst = None      # called (no arguments) when a burst begins

    def on_start(self, ev) -> None:
        now = time.perf_counter()
        began = False
        with self._lock:
            if self.depth == 0:
                self._outer_start = now
                if self.burst_start is None or now - self.last_end > QUIET_SECONDS:
                    self.burst_start, began = now, True
            self.depth += 1
        if began and self.on_burst is not None:
            self.on_burst()

    def on_end(self, ev) -> None:
        now = time.perf_counter()
        with self._lock:
            self.depth = max(0, self.depth - 1)
            if self.depth == 0:
                self.kernels += 1
                self.seconds += now - self._outer_start
                self.last_end = now

    def elapsed(self, now: float | None = None) -> float | None:
        """Seconds since the current burst began, or None when none is under way."""
        now = time.perf_counter() if now is None else now
        with self._lock:
            if self.burst_start is None:
                return None
            if self.depth == 0 and now - self.last_end > QUIET_SECONDS:
                return None
            return now - self.burst_start


_watch: _Watch | None = None


def install() -> _Watch:
    """Register the listener (once per process) and return it."""
    global _watch  # noqa: PLW0603 (one listener per process)
    if _watch is None:
        _watch = _Watch()
        event.register("numba:compile", _watch)
        if _in_notebook():
            _watch.on_burst = _notebook_line
    return _watch


def elapsed() -> float | None:
    """Seconds the current compile burst has run, or None when numba is not compiling."""
    return install().elapsed()


def notice(seconds: float, *, ellipsis: str = "…") -> str:
    """The line every front end shows: the notice and the seconds so far (``ellipsis="..."``
    where the font has no "…", as ImGui's default)."""
    return f"{NOTICE} {ellipsis} {seconds:.0f} s"


def _in_notebook() -> bool:
    """True inside a Jupyter kernel (its print goes to the cell that runs)."""
    return "ipykernel" in sys.modules


def _notebook_line() -> None:
    print(f"pointmass: {NOTICE} … (about a minute; later runs load them from the cache)",
          flush=True)


class TerminalNotice:
    """A line on stderr while numba compiles: ``compiling physics kernels (first run only) …
    12 s``, redrawn in place on a terminal; on a log (not a terminal) one line at the start of
    each burst and one at its end. A context manager; the polling thread is a daemon, so it
    never holds the process open."""

    def __init__(self, stream=None, *, period: float = 0.25) -> None:
        self.stream = stream if stream is not None else sys.stderr
        self.period = period
        isatty = getattr(self.stream, "isatty", None)
        self.terminal = bool(isatty and isatty())
        self._stop = threading.Event()
        self._thread = threading.Thread(target=self._run, name="pointmass-compile-notice",
                                        daemon=True)
        #: Bursts shown so far (tests read it).
        self.bursts = 0

    def __enter__(self) -> TerminalNotice:
        install()
        self._thread.start()
        return self

    def __exit__(self, *exc) -> None:
        self._stop.set()
        self._thread.join(timeout=1.0)

    def _run(self) -> None:
        showing, last = False, 0.0
        while True:
            stopping = self._stop.wait(self.period)
            seconds = elapsed()
            if seconds is not None:
                if not showing:
                    self.bursts += 1
                    if not self.terminal:
                        self._write(f"pointmass: {NOTICE} …\n")
                showing, last = True, seconds
                if self.terminal:
                    self._write(f"\rpointmass: {notice(seconds)} ")
            elif showing:
                showing = False
                done = f"pointmass: compiled physics kernels in {last:.0f} s"
                self._write(f"\r{done}\033[K\n" if self.terminal else f"{done}\n")
            if stopping:
                if showing:
                    self._write("\n" if self.terminal else "")
                return

    def _write(self, text: str) -> None:
        try:
            self.stream.write(text)
            self.stream.flush()
        except (OSError, ValueError):  # a closed stream: nothing to tell
            pass
