"""Same inputs, same trajectory: bit for bit."""

from __future__ import annotations

import numpy as np
import pytest

import pointmass as pm

DT = 1.0 / 60.0


def _ball_pit(seed: int) -> pm.World:
    """~200 spheres with springs between neighbours, dropped into a box."""
    rng = np.random.default_rng(seed)
    world = pm.World()
    n = 200
    positions = rng.uniform((-1.0, 0.5, -1.0), (1.0, 4.0, 1.0), (n, 3))
    world.add_particles(positions, rng.normal(0, 1, (n, 3)), masses=rng.uniform(0.5, 2.0, n),
                        radii=rng.uniform(0.08, 0.15, n))
    pairs = rng.choice(n, size=(60, 2), replace=False)
    world.add(pm.Spring(pairs[:, 0], pairs[:, 1], spring_constant=50.0, rest_length=0.4,
                        damping=0.5))
    world.add(pm.Drag(0.05, 0.01))
    world.add(pm.BoxContainer((-1.2, 0.0, -1.2), (1.2, 10.0, 1.2), restitution=0.5))
    world.add(pm.SphereCollisions(restitution=0.5))
    return world


def _run(seed: int, steps: int = 240) -> tuple[np.ndarray, np.ndarray, list]:
    world = _ball_pit(seed)
    stats = [world.step(DT) for _ in range(steps)]
    return world.particles.position.copy(), world.particles.velocity.copy(), stats


def test_two_runs_of_a_ball_pit_are_bit_identical():
    """Produce bit-identical positions, velocities and statistics from two identical runs."""
    pos1, vel1, stats1 = _run(3)
    pos2, vel2, stats2 = _run(3)
    assert np.array_equal(pos1, pos2)
    assert np.array_equal(vel1, vel2)
    assert stats1 == stats2
    assert sum(s.contacts for s in stats1) > 1000  # the scene really collided
    # A different seed gives a different scene: the comparison above is not vacuous.
    pos3, _, _ = _run(4, steps=10)
    assert not np.array_equal(pos1[:5], pos3[:5])


def test_snapshot_restore_replays_identically():
    """Replay identically after restoring a particle snapshot (without a warm-start history)."""
    world = _ball_pit(5)
    for _ in range(30):
        world.step(DT)
    snap = world.particles.snapshot()
    world.impulses.clear()
    for _ in range(60):
        world.step(DT)
    first = world.particles.position.copy()
    world.particles.restore(snap)
    world.impulses.clear()
    for _ in range(60):
        world.step(DT)
    assert np.array_equal(world.particles.position, first)


def test_parallel_integration_is_bit_identical_for_any_thread_count():
    """Above PARALLEL_MIN_PARTICLES the integration runs on all cores, split into fixed chunks
    (not per thread), so positions, velocities and the summed kinetic energy are the same
    bits on one thread or two."""
    import numba

    from pointmass.particles import PARALLEL_MIN_PARTICLES

    n = PARALLEL_MIN_PARTICLES + 12_345
    rng = np.random.default_rng(3)
    start = rng.normal(size=(n, 3)) + np.array([0.0, 50.0, 0.0]), rng.normal(size=(n, 3))
    masses = rng.uniform(0.5, 2.0, n)
    results = []
    saved = numba.get_num_threads()
    try:
        for threads in (1, saved):
            numba.set_num_threads(threads)
            world = pm.World()
            world.add_particles(start[0], start[1], masses=masses)
            world.add(pm.Drag(0.1, 0.01))
            energies = [world.step(1 / 60).kinetic_energy for _ in range(20)]
            results.append((world.particles.position.copy(), energies))
    finally:
        numba.set_num_threads(saved)
    assert np.array_equal(results[0][0], results[1][0])
    assert results[0][1] == results[1][1]


def test_the_step_energy_is_summed_when_read_and_only_while_its_state_lasts():
    """``StepStats.kinetic_energy`` is summed when first read (a step pays no pass for it),
    from the state the step left: on a parallel-sized world it is ``Particles.kinetic_energy``
    to the bit and ½·Σ m·|v|² to rounding; read after the next step it raises, naming the
    way to the current energy, instead of describing a later state."""
    from pointmass.particles import PARALLEL_MIN_PARTICLES

    n = PARALLEL_MIN_PARTICLES + 777
    rng = np.random.default_rng(8)
    world = pm.World()
    masses = rng.uniform(0.5, 2.0, n)
    world.add_particles(rng.normal(size=(n, 3)), rng.normal(size=(n, 3)), masses=masses)
    world.particles.pin(5)
    world.add(pm.Drag(0.1, 0.01))
    for _ in range(3):
        stats = world.step(1 / 60)
        assert stats.kinetic_energy == world.particles.kinetic_energy()
    v = world.particles.velocity
    moving = world.particles.inv_mass > 0
    exact = 0.5 * np.sum(masses[moving] * np.sum(v[moving] ** 2, axis=1))
    assert stats.kinetic_energy == pytest.approx(exact, rel=1e-12)
    unread = world.step(1 / 60)
    world.step(1 / 60)
    assert stats.kinetic_energy == pytest.approx(exact, rel=1e-12)  # read before: kept
    with pytest.raises(RuntimeError, match=r"read after step 5.*World.kinetic_energy\(\)"):
        _ = unread.kinetic_energy


def test_step_stats_copy_pickle_and_compare_without_the_world_behind_them():
    """The energy's source is not a field: ``asdict``, ``==`` and ``repr`` leave it out, and a
    pickle carries the energy once read, never the world (unread, it says so when read)."""
    import dataclasses
    import pickle

    world = pm.World(gravity=(0, 0, 0))
    world.add_particle(velocity=(2.0, 0.0, 0.0), mass=3.0)
    unread = world.step(0.1)
    read = world.step(0.1)
    assert read.kinetic_energy == 6.0
    assert "kinetic" not in repr(read) and "_energy" not in dataclasses.asdict(read)
    assert read == unread
    assert pickle.loads(pickle.dumps(read)).kinetic_energy == 6.0
    with pytest.raises(RuntimeError, match="pickled or deep-copied before"):
        _ = pickle.loads(pickle.dumps(unread)).kinetic_energy


_BLAS_SCENE = """
import hashlib, sys
import numpy as np
import pointmass as pm
from pointmass.solver import direct

calls = {"velocities": 0, "project": 0}
for name, key in (("_velocities", "velocities"), ("project_metric", "project")):
    def counted(*args, _f=getattr(direct, name), _k=key):
        calls[_k] += 1
        return _f(*args)
    setattr(direct, name, counted)
digest = hashlib.sha256()
for links, load in ((1, 100.0), (10, 1000.0)):
    world = pm.World()
    ids = world.add_particles([((i + 1) * 0.5, 0.0, 0.0) for i in range(links)],
                              masses=np.ones(links))
    heavy = world.add_particle((links * 0.5, 0.0, 0.6), mass=load)
    world.add(pm.AnchoredRod(ids[0], (0.0, 0.0, 0.0), 0.5))
    if links > 1:
        world.add(pm.Rod(ids[:-1], ids[1:], 0.5))
    world.add(pm.Cable(ids[-1], heavy, 0.6, restitution=0.0))
    for _ in range(60):
        world.step(1 / 32)
    digest.update(world.particles.position.tobytes())
    digest.update(world.particles.velocity.tobytes())
print(digest.hexdigest(), calls["velocities"], calls["project"])
"""


@pytest.mark.parametrize("library", ["OPENBLAS_NUM_THREADS", "OMP_NUM_THREADS"])
def test_the_direct_solve_gives_the_same_bits_for_any_blas_thread_count(library):
    """Heavy loads on light links reach the direct solve (``solver/direct.py``: the velocity
    LCP, the exact projection and the links' velocities at the projected positions); it uses
    no BLAS, so the trajectory's bits do not depend on how many threads OpenBLAS may use
    (numpy's matrix products and ``linalg.solve`` there, reported to differ by 3e-16)."""
    import os
    import subprocess
    import sys
    from pathlib import Path

    src = str(Path(__file__).resolve().parents[2] / "src")
    results = []
    for threads in ("1", "2"):
        env = {**os.environ, library: threads,
               "PYTHONPATH": os.pathsep.join([src, os.environ.get("PYTHONPATH", "")])}
        out = subprocess.run([sys.executable, "-c", _BLAS_SCENE], capture_output=True,
                             text=True, timeout=600, env=env, check=False)
        assert out.returncode == 0, out.stderr
        results.append(out.stdout.split())
    assert results[0] == results[1]
    _, velocity_solves, projections = results[0]
    assert int(velocity_solves) > 0 and int(projections) > 0  # the direct solve really ran
