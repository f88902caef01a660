"""The pool's bookkeeping when several runs finish at once (as every run in flight does when a
worker dies): each is handled once, none is waited for again. Driven by an executor whose
futures are finished when submitted, so every wait returns all of them together."""

from __future__ import annotations

from concurrent.futures import Future
from types import SimpleNamespace

from pointmass.sweep import backends


class _FinishedAtOnce:
    """A stand-in for ProcessPoolExecutor: each submit returns a future already done."""

    def __init__(self, *args, **kwargs) -> None:
        self.submitted = 0

    def submit(self, fn, *args):
        self.submitted += 1
        future: Future = Future()
        future.set_result({"run": self.submitted})
        return future

    def shutdown(self, wait: bool = True, cancel_futures: bool = False) -> None:
        pass


def test_runs_finishing_together_are_each_handled_once(monkeypatch, tmp_path):
    """Three runs on two workers: the first two finish in one wait, the third is handed out
    while the second is still to be handled (before the fix, the next wait returned the
    handled second again: KeyError, seen in CI when a worker was killed)."""
    monkeypatch.setattr(backends, "ProcessPoolExecutor", _FinishedAtOnce)
    runs = [SimpleNamespace(index=i) for i in range(3)]
    done = []
    lost = backends._pool_pass(None, runs, tmp_path, lambda run, meta: done.append(run.index),
                               lambda run, why: None, 2, False)
    assert lost == []
    assert sorted(done) == [0, 1, 2]
