"""AeroControl: the tensor in use is min, base, max at control −1, 0, 1 and linear in between;
the control acts on the force (a wing's lift changes with it); bad input is named."""

import math

import numpy as np
import pytest

import pointmass as pm
from pointmass.rigid.forces import AeroControl, control_tensor
from pointmass.rigid.shapes import Box

BASE = np.array([[0.0, 0.0, 0.0], [-1.0, -0.5, 0.0], [0.0, 0.0, 0.0]])
LOW = BASE + np.array([[0.0, 0.0, 0.0], [0.2, 0.0, 0.0], [0.0, 0.0, -0.1]])
HIGH = BASE + np.array([[0.3, 0.0, 0.0], [-0.4, 0.1, 0.0], [0.0, 0.0, 0.0]])


def surface(control=0.0):
    return AeroControl(0, BASE, LOW, HIGH, (1.0, 0.0, 2.0), control=control)


@pytest.mark.parametrize(("control", "expected"), [(-1.0, LOW), (0.0, BASE), (1.0, HIGH)])
def test_control_minus_one_zero_one_give_min_base_max(control, expected):
    assert np.array_equal(surface(control).tensor, expected)
    s = surface()
    s.control = control
    assert np.array_equal(s.tensor, expected)


def test_between_the_ends_the_tensor_is_the_linear_blend():
    for c in (-0.75, -0.3, 0.2, 0.9):
        other = LOW if c < 0 else HIGH
        assert np.allclose(surface(c).tensor, BASE + abs(c) * (other - BASE), atol=1e-15)
    assert np.allclose(control_tensor(BASE, LOW, HIGH, -0.5), (LOW + BASE) / 2)


def test_the_control_changes_the_lift_on_a_moving_body():
    """A body moving along −x through still air: the lift row gives F_y = −T[1,0]·v_x, so
    the lift at control c is what the blended tensor says, on the force the generator applies;
    and a step gives the body that lift (m·Δv/dt, to the 1e-4 by which the drag slows v_x
    over the step: the world finds the force again every substep, where the body then is)."""
    lifts, given = {}, {}
    for c in (-1.0, 0.0, 1.0):
        world = pm.World(gravity=(0.0, 0.0, 0.0))
        body = world.add_body(Box((0.5, 0.1, 0.5)), velocity=(-10.0, 0.0, 0.0), mass=2.0)
        control = world.add(AeroControl(body, BASE, LOW, HIGH, control=c))
        world.bodies.clear_accumulators()
        control.apply(world.bodies, 1e-3)
        lifts[c] = float(world.bodies.force[0, 1])
        world.bodies.clear_accumulators()
        world.step(1e-3)
        given[c] = body.velocity[1] * 2.0 / 1e-3  # m·Δv/dt [N]
    assert lifts[0.0] == pytest.approx(10.0, rel=1e-12)
    assert lifts[-1.0] == pytest.approx(8.0, rel=1e-12)
    assert lifts[1.0] == pytest.approx(14.0, rel=1e-12)
    for c in lifts:
        assert given[c] == pytest.approx(lifts[c], rel=2e-4)


@pytest.mark.parametrize("bad", [1.5, -1.01, math.nan, math.inf])
def test_out_of_range_control_is_refused_naming_it_and_the_range(bad):
    with pytest.raises(ValueError, match=r"control must be in \[-1, 1\]"):
        surface(bad)
    s = surface(0.5)
    with pytest.raises(ValueError, match="control"):
        s.control = bad
    assert s.control == 0.5 and np.allclose(s.tensor, BASE + 0.5 * (HIGH - BASE))


@pytest.mark.parametrize(("name", "args"), [
    ("base", (np.ones((2, 2)), LOW, HIGH)),
    ("minimum", (BASE, (0, 0, math.nan), HIGH)),
    ("maximum", (BASE, LOW, "wing")),
])
def test_bad_tensors_are_refused_by_name(name, args):
    with pytest.raises(ValueError, match=name):
        AeroControl(0, *args)
