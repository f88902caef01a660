"""Joint limits at rest in the soft step (``World(body_step="soft")``): the ragdoll demo,
thrown down and left 4.5 s, must pass its own check (limits within 0.5° of their stops at rest,
3° in the fall) as it does with the default stage.

Not met yet (issue 26, what keeps the soft step from being the default): a limit is a soft
Gauss–Seidel row sprung with its own two bones' inertia (``joint_soft``), while what leans on
it comes through the tree (the body's weight on an arm or a leg), so it gives like the rope
bridge's second anchor did before its row was sprung with the tree's mass (``joint_loops``).
Measured (main at 58bf2e8 with the soft loops, seeds 1–5): at rest 2.35°, 0.24°, 0.22°, 2.98°,
0.71°; in the fall 4.35°, 0.92°, 2.08°, 4.11°, 3.32° (before sjenergy's island energy cap, at
rest 1.15°, 0.67°, 0.18°, 2.80°, 0.52°, in the fall 2.08°, 1.82°, 2.07°, 6.27°, 3.21°).
Rigid limit rows (mass scale 1, the relax taking back their bias) were tried before that cap
and were worse in the fall (5.5°, 2.0°, 0.9°, 5.4°, 5.1°), and so were joints as stiff as
the contacts (240 Hz: better here, worse on random jointed scenes)."""

import functools

import pytest

import pointmass as pm
from pointmass.demo import load_demo

pytestmark = pytest.mark.slow

#: Seeds whose check fails with the soft step, with what it reports (measured, see above).
FAILING = {1: "2.35° at rest, 4.35° in the fall", 4: "2.98° at rest, 4.11° in the fall",
           5: "0.71° at rest, 3.32° in the fall"}


@pytest.mark.parametrize("seed", [
    pytest.param(s, marks=pytest.mark.xfail(strict=True, reason=f"soft limits give: {FAILING[s]}"))
    if s in FAILING else s for s in range(1, 6)])
def test_the_ragdoll_rests_within_its_limits_in_the_soft_step(seed, monkeypatch):
    demo = load_demo("ragdoll")
    monkeypatch.setattr(demo.module, "World", functools.partial(pm.World, body_step="soft"))
    sim = pm.Simulation(demo, overrides=[f"seed={seed}"])
    assert sim.world._body_step == "soft"
    for _ in range(round(4.5 * 30)):
        sim.advance(1 / 30)
    sim.check()
