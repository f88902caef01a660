"""The 1-D model of the soft step in benchmarks/soft_stack.py, which RESULTS.md's account of the
body stage's passes rests on (stop 45): Box2D v3's soft step, one biased and one relax pass a
substep, warm started, on a stack of 10 unit masses that cannot turn.

At Box2D's stiffness cap (ω·h = π/2: 60 Hz at 4 substeps of 1/240 s) a stack whose interfaces
are one row each comes to rest; with four identical rows an interface (a box face's manifold)
swept once a pass, as the engine's passes sweep them, it never does; with those rows solved
among themselves first it does again, and sinks a quarter as far (four springs in parallel)."""

from __future__ import annotations

import math
import sys
from pathlib import Path

import pytest

sys.path.insert(0, str(Path(__file__).resolve().parents[2] / "benchmarks"))
from soft_stack import model_stack


@pytest.mark.parametrize("points, block, settles", [(1, False, True), (4, False, False),
                                                    (4, True, True)],
                         ids=["one row", "four rows swept", "four rows solved together"])
def test_one_pass_settles_a_stack_at_box2ds_cap_unless_its_rows_are_redundant(points, block,
                                                                              settles):
    # measured: 8.4e-15, 0.27 and 7.8e-14 m/s in the 10th second
    speed, sink = model_stack(hertz=60.0, substeps=4, points=points, block=block)
    if settles:
        assert speed < 1e-9
        # the stack's sag is Σ load / k over its interfaces, k = m_eff·ω² a row: the 9 box
        # interfaces carry 9 … 1 masses at m_eff ½, the ground 10 at m_eff 1 and 2ω; four rows
        # an interface are four springs in parallel (6.38 and 1.60 mm)
        omega = 2.0 * math.pi * 60.0
        want = 9.81 * (45 / 0.5 + 10 / (1.0 * 4.0)) / omega**2
        assert sink == pytest.approx(-want / points, rel=0.02)
    else:
        assert speed > 1e-2
