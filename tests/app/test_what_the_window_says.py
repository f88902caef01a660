"""What a demo's window tells its user at first sight: the panel's last header in view, the
demo's hint until the first key or click, a notice instead of a frozen picture while numba
compiles in the physics worker."""

from __future__ import annotations

import threading

import pytest

from pointmass.demo import Simulation

pytestmark = pytest.mark.window

DT = 1 / 60
#: The size ``pointmass run`` opens.
SIZE = (1280, 720)


def frames(window, n: int = 1) -> None:
    for _ in range(n):
        window.dispatch_events()
        window.tick(DT)


@pytest.mark.parametrize("name", ["box_tower", "flightsim", "spinning_top", "sailboat"])
def test_the_world_header_is_inside_the_window(open_viewer, name):
    """The rigid-body demos' extra statistics and plots pushed "World" below the bottom edge;
    the plots now shrink to keep it in view."""
    w = open_viewer(Simulation(name), paused=False, size=SIZE)
    frames(w, 30)                                  # the plots have data
    _x0, y0, _x1, y1 = w.viewer.panel.rects["header:World"]
    height = w.get_size()[1]
    assert y1 <= height - 8, f"World header {y0:.0f}..{y1:.0f} in a {height}-point window"


def test_big_ballistic_says_to_click_until_it_is_clicked(open_viewer):
    w = open_viewer(Simulation("big_ballistic"), paused=False, size=SIZE)
    frames(w, 2)
    assert any("click" in line.lower() for line in w.viewer.overlay_text())
    w.viewer.sim.press("CLICK")
    frames(w, 2)
    assert w.viewer.overlay_text() == []


def test_a_demo_without_keys_shows_no_hint(open_viewer):
    w = open_viewer(Simulation("projectile"), paused=False, size=SIZE)
    frames(w, 2)
    assert w.viewer.overlay_text() == []


def test_the_window_draws_a_notice_while_the_worker_compiles(open_viewer, sim, monkeypatch):
    """While numba compiles for a job in the physics worker, frames go on (the notice drawn over
    the last picture, events dropped) instead of waiting for it; once it is done the window
    is as before. (The compile watch itself: tests/test_first_run.py.)"""
    from pointmass import compiling
    from pointmass.worker import Worker

    w = open_viewer(sim, paused=False)
    viewer = w.viewer
    frames(w, 2)
    viewer.detach_compiles = True                 # as the window's own event loop does
    release = threading.Event()
    monkeypatch.setattr(compiling, "elapsed", lambda: None if release.is_set() else 12.0)
    viewer._worker = viewer._worker or Worker()
    job = viewer._worker.submit(lambda: (release.wait(30), (0, 0.0))[1])
    viewer._running, viewer._running_due = job, (0.0, 0, DT)
    assert viewer.update(DT) == 0                 # no waiting, no new steps owed
    w.switch_to()
    w.on_draw()                                   # returns at once, the worker still busy
    assert viewer.last_notice.startswith("Compiling physics kernels (first run only) ...")
    assert not job.done()
    release.set()
    job.result(30)
    viewer.detach_compiles = False
    frames(w, 2)
    assert viewer.compiling() is None and not viewer.physics_running


def test_the_first_job_never_holds_the_window(open_viewer, sim):
    """numba's start-up and its cache loads run outside its compile events: while the first
    job (the drawing's kernels) runs, the window draws "Loading physics kernels" instead of
    waiting for it (it once froze for seconds there)."""
    import time

    from pointmass.worker import Worker

    w = open_viewer(sim, paused=False)
    viewer = w.viewer
    frames(w, 2)
    viewer.detach_compiles = True
    viewer.update(DT)                 # steps owed (run by the next draw, with overlap)
    release = threading.Event()
    viewer._worker = viewer._worker or Worker()
    viewer._warming_since = time.perf_counter()
    viewer._warming = viewer._worker.submit(release.wait, 30)
    started = time.perf_counter()
    assert viewer.compiling() is not None and viewer.notice_kind == "loading"
    w.switch_to()
    w.on_draw()
    assert time.perf_counter() - started < 5.0       # did not wait for the 30 s job
    assert viewer.last_notice == "Loading physics kernels ..."
    # ...and a notice frame drops them: the next update must not run them in the main thread
    # (where a compile froze the window)
    assert viewer._due is None
    release.set()
    viewer._warming.result(30)
    assert viewer.compiling() is None and viewer._warming is None
    viewer.detach_compiles = False
    frames(w, 2)
