"""A sweep folder across calls (serial backend, a tiny spring): reruns skip, extensions add only
the new runs, a changed sweep is refused, failed runs can be retried, the index reads back the
same from CSV and Parquet, and a scene function works like a demo."""

from __future__ import annotations

import json

import numpy as np
import pytest
from sweep_helpers import write_spring_demo

from pointmass import Scene, Spring, World, sweep
from pointmass.sweep import folder as layout
from pointmass.sweep.index import PARQUET, read_rows


def _run(demo, out, **kwargs):
    options = dict(seconds=0.25, fps=20, probes=["positions", "kinetic_energy"],
                   backend="serial", progress=False)
    return sweep.run(str(demo), out, **{**options, **kwargs})


def test_rerun_extend_refuse_and_retry(tmp_path):
    demo = write_spring_demo(tmp_path)
    out = tmp_path / "out"
    first = _run(demo, out, grid={"stiffness": [10.0, 1e7]})
    assert (first.executed, first.skipped, len(first.failed)) == (2, 0, 1)
    again = _run(demo, out, grid={"stiffness": [10.0, 1e7]})
    assert (again.executed, again.skipped) == (0, 2)
    more = _run(demo, out, grid={"stiffness": [10.0, 1e7, 20.0]})
    assert (more.executed, more.skipped) == (1, 2)
    assert [r["stiffness"] for r in sweep.load(out).rows] == [10.0, 1e7, 20.0]
    with pytest.raises(ValueError, match=r"holds a sweep with seconds = 0\.25, not 0\.5"):
        _run(demo, out, grid={"stiffness": [10.0]}, seconds=0.5)
    retried = _run(demo, out, grid={"stiffness": [10.0, 1e7, 20.0]}, retry_failed=True)
    assert (retried.executed, retried.skipped, len(retried.failed)) == (1, 2, 1)
    # The energy probe is a spring's: ½·k·x² at rest stretch 0.2 m goes into motion and back.
    run = sweep.load(out)[0]
    energy = run.probes()["kinetic_energy"]
    assert energy[0] == 0.0 and 0 < energy.max() <= 0.5 * 10.0 * 0.2**2
    assert run.meta["demo_params"]["stiffness"] == 10.0
    assert run.meta["demo_params"]["stretch"] == 0.2       # defaults recorded too


def test_index_reads_back_the_same_from_csv_and_parquet(tmp_path):
    pytest.importorskip("pyarrow")
    demo = write_spring_demo(tmp_path)
    _run(demo, tmp_path / "out", grid={"stiffness": [10.0, 1e7]}, seeds=[3, 4])
    from_parquet = read_rows(tmp_path / "out")
    (tmp_path / "out" / PARQUET).unlink()
    from_csv = read_rows(tmp_path / "out")
    assert from_csv == from_parquet
    assert [r["seed"] for r in from_csv] == [3, 4, 3, 4]
    assert from_csv[2]["error"].startswith("UnstableStepError:") and from_csv[0]["error"] is None


def test_one_sweep_per_folder_at_a_time(tmp_path):
    demo = write_spring_demo(tmp_path)
    (tmp_path / "out").mkdir()
    with layout.FolderLock(tmp_path / "out"), \
            pytest.raises(RuntimeError, match="another sweep is writing to"):
        _run(demo, tmp_path / "out")


def two_springs(stiffness: float, seed: int) -> Scene:
    """A scene function: the stretch comes from the seed."""
    rng = np.random.default_rng(seed)
    world = World(gravity=(0.0, 0.0, 0.0))
    a = world.add_particle((0.0, 0.0, 0.0), mass=1.0)
    b = world.add_particle((1.0 + rng.uniform(0.1, 0.3), 0.0, 0.0), mass=1.0)
    world.add(Spring(a, b, stiffness, 1.0))
    return Scene(world, dt=1 / 120)


def test_a_scene_function_with_seeds(tmp_path):
    result = sweep.run(two_springs, tmp_path / "out", grid={"stiffness": [5.0]}, seeds=2,
                       seconds=0.1, probes=["positions"], backend="serial", progress=False)
    assert result.failed == {}
    data = sweep.load(tmp_path / "out")
    x = [run.probes()["positions"][0, 1, 0] for run in data]
    assert x[0] != x[1]                                    # the seed reached the scene
    settings = json.loads((tmp_path / "out" / "sweep.json").read_text())
    assert settings["source"].endswith(":two_springs")


def test_a_notebook_function_is_refused_for_the_pool_with_the_way_out(tmp_path):
    namespace: dict = {"__name__": "__main__"}
    exec("def build(stiffness):\n    pass\n", namespace)
    fn = namespace["build"]
    fn.__module__ = "__main__"
    import sys

    saved = getattr(sys.modules["__main__"], "__file__", None)
    sys.modules["__main__"].__dict__.pop("__file__", None)
    sys.modules["__main__"].build = fn
    try:
        with pytest.raises(ValueError, match=r'notebook.*backend="ray" or "serial"'):
            sweep.run(fn, tmp_path / "out", grid={"stiffness": [1.0]}, seconds=0.1,
                      progress=False)
    finally:
        del sys.modules["__main__"].build
        if saved is not None:
            sys.modules["__main__"].__file__ = saved


def test_a_sweep_without_clips_loads_no_renderer(tmp_path):
    """The physics core stays free of GL: only a sweep that keeps clips imports the renderer
    (in the worker that records them)."""
    import subprocess
    import sys

    demo = write_spring_demo(tmp_path)
    code = ("import sys\nfrom pointmass import sweep\n"
            f"sweep.run({str(demo)!r}, {str(tmp_path / 'out')!r}, seconds=0.1, "
            "probes=['positions'], backend='serial', progress=False)\n"
            "print([m for m in ('moderngl', 'av', 'PIL', 'pyglet') if m in sys.modules])")
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                         check=True, timeout=120)
    assert out.stdout.strip().splitlines()[-1] == "[]"
