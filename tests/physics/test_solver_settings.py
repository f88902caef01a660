"""``SolverSettings``: the solver's tuning numbers in one frozen value on ``World``, checked
when made (a clear error naming the field and its range), passed by tests instead of patched
modules, and acting on the step."""

from __future__ import annotations

import dataclasses

import numpy as np
import pytest

import pointmass as pm


def test_a_world_starts_with_the_default_settings_and_takes_new_ones():
    world = pm.World()
    assert world.settings == pm.SolverSettings()
    with pytest.raises(dataclasses.FrozenInstanceError):
        world.settings.max_velocity_passes = 3  # type: ignore[misc]
    world.settings = dataclasses.replace(world.settings, max_velocity_passes=3)
    assert world.settings.max_velocity_passes == 3
    assert pm.World(settings=pm.SolverSettings(max_impact_passes=2)).settings.max_impact_passes \
        == 2
    with pytest.raises(TypeError, match=r"settings must be a pm\.SolverSettings"):
        world.settings = {"max_velocity_passes": 3}  # type: ignore[assignment]


@pytest.mark.parametrize(("field", "value", "message"), [
    ("max_velocity_passes", 0, "max_velocity_passes must be >= 1"),
    ("max_velocity_passes", 2.5, "max_velocity_passes must be an int"),
    ("max_velocity_passes", True, "max_velocity_passes must be an int"),
    ("velocity_tolerance", 0.0, "velocity_tolerance must be a finite number > 0"),
    ("velocity_tolerance", float("nan"), "velocity_tolerance must be a finite number > 0"),
    ("large_set_relaxation", 2.0, r"large_set_relaxation must be in \[1, 2\)"),
    ("direct_min_mass_ratio", 0.5, "direct_min_mass_ratio must be >= 1"),
    ("parallel_min_contacts", -1, "parallel_min_contacts must be >= 0"),
])
def test_bad_settings_are_refused_naming_the_field_and_its_range(field, value, message):
    with pytest.raises((ValueError, TypeError), match=message):
        pm.SolverSettings(**{field: value})


def _chain_run(settings):
    """A 20-cable chain released level, pinned at one end: its velocity passes run to their
    cap on the first steps (Gauss–Seidel crawls along a chain)."""
    world = pm.World(settings=settings)
    ids = world.add_particles([(0.5 * i, 2.0, 0.0) for i in range(21)])
    world.particles.pin(ids[0])
    world.add(pm.Cable(ids[:-1], ids[1:], 0.5, restitution=0.0))
    passes = []
    for _ in range(30):
        passes.append(world.step(1 / 60).velocity_passes)
    return world.particles.position.copy(), passes


def test_the_settings_act_on_the_step():
    """A cap on the velocity passes is the cap the step uses, and the same settings give the
    same bits."""
    base, passes = _chain_run(pm.SolverSettings())
    again, _ = _chain_run(pm.SolverSettings())
    assert np.array_equal(base, again)
    capped, capped_passes = _chain_run(pm.SolverSettings(max_velocity_passes=2,
                                                         direct_after_passes=1))
    assert max(capped_passes) < max(passes)
    assert not np.array_equal(base, capped)
