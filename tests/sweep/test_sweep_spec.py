"""What a sweep's runs are: grid × draws × seeds, stable ids, and bad input named."""

from __future__ import annotations

import pytest

from pointmass.sweep import Sweep
from pointmass.sweep.spec import run_id


def test_grid_draws_and_seeds_multiply_in_order():
    sweep = Sweep("ball_pit", fixed={"count": 300}, grid={"restitution": [0.2, 0.8]},
                  random={"friction": (0.1, 1.0), "pour_seconds": [1.0, 2.0]}, draws=3,
                  seeds=2)
    runs = sweep.runs()
    assert len(runs) == 2 * 3 * 2
    assert [r.index for r in runs] == list(range(12))
    assert [r.params["restitution"] for r in runs] == [0.2] * 6 + [0.8] * 6
    assert [r.seed for r in runs] == [0, 1] * 6
    assert all(r.params["count"] == 300 for r in runs)
    friction = [r.params["friction"] for r in runs]
    assert all(0.1 <= f <= 1.0 for f in friction)
    assert friction[:6] == friction[6:]          # each grid point gets the same draws
    assert len(set(friction)) == 3
    assert {r.params["pour_seconds"] for r in runs} <= {1.0, 2.0}
    # The same sweep anywhere has the same runs, and the ids are distinct.
    assert [r.run_id for r in sweep.runs()] == [r.run_id for r in runs]
    assert len({r.run_id for r in runs}) == 12


def test_run_ids_depend_on_values_not_on_order_or_spelling():
    assert run_id({"a": 1, "b": 2.5}, 3) == run_id({"b": 2.5, "a": 1}, 3)
    assert run_id({"a": 1}, 3) != run_id({"a": 1}, 4)
    # A demo's float parameter given as 1 (an int), 1.0 or "1.0" (the command line) is one run.
    ids = {Sweep("ball_pit", grid={"restitution": [v]}).runs()[0].run_id
           for v in (1, 1.0, "1.0")}
    assert len(ids) == 1


def test_extending_a_sweep_keeps_the_ids_of_its_runs():
    small = Sweep("ball_pit", grid={"restitution": [0.2, 0.5]}, seeds=2).runs()
    large = Sweep("ball_pit", grid={"restitution": [0.2, 0.5, 0.8]}, seeds=3).runs()
    assert {r.run_id for r in small} <= {r.run_id for r in large}


@pytest.mark.parametrize(("kwargs", "message"), [
    ({"seconds": 0}, "seconds must be in"),
    ({"fps": 0}, "fps must be an integer"),
    ({"clip": (10, 10)}, "clip must be"),
    ({"probes": ["speed"]}, "unknown probe 'speed'"),
    ({"grid": {"restitution": []}}, r"grid\['restitution'\] must be a non-empty list"),
    ({"random": {"friction": (1.0, 0.1)}, "draws": 2}, r"random\['friction'\] as a range"),
    ({"random": {"friction": (0.1, 1.0)}}, "draws = 0"),
    ({"seeds": [1, 1]}, "seeds must be distinct"),
    ({"fixed": {"index": 1}}, "parameter name 'index' is reserved"),
    ({"fixed": {"seed": 1}}, "give seeds with seeds="),
    ({"fixed": {"count": 10}, "grid": {"count": [10, 20]}}, "'count' is given more than once"),
])
def test_bad_sweeps_are_refused_naming_the_setting(kwargs, message):
    with pytest.raises(ValueError, match=message):
        Sweep("ball_pit", **kwargs)


def test_a_float_parameter_drawn_between_integers_gets_floats():
    runs = Sweep("bridge", random={"load_mass": (0, 50), "planks": (2, 12)}, draws=5).runs()
    assert all(isinstance(r.params["load_mass"], float) for r in runs)
    assert len({r.params["load_mass"] for r in runs}) == 5
    assert all(isinstance(r.params["planks"], int) and 2 <= r.params["planks"] <= 12
               for r in runs)
