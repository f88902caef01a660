"""``SolverSettings``: every tuning number of the solver in one frozen value on ``World``.

Each field's default is what the engine ships with and what its tests measure; the comment on
each says what it trades and what was measured when it was chosen (the measurements in full
are in the docstrings of the stages that read it). A test or a user who wants another value
passes one (``World(settings=SolverSettings(max_velocity_passes=30))``, or
``dataclasses.replace(world.settings, ...)`` assigned to ``world.settings``), never patches a
module. Numerical guards that are not choices (the epsilons that tell a zero from round-off,
``kernels.PENETRATION_EPSILON``, ``remeasure.STIFF_CAP``) and memory layouts that change
no result (``sweeps.STREAMS``, ``partition.SLABS``) stay beside the code that needs them.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, fields


@dataclass(frozen=True)
class SolverSettings:
    """The solver's tuning numbers (see the module docstring; ``solver/solver.py`` for the
    particle stages that read them).

    Particle contacts and links, the velocity stage:

    Attributes:
        velocity_tolerance: Velocity passes stop once no contact's velocity changes by more
            than this in a pass [m/s].
        max_velocity_passes: Cap on the velocity passes of a set small enough for the exact
            solve (``World(iterations=...)`` overrides it).
        max_large_velocity_passes: ... and of a set too large for it
            (> ``direct_max_contacts`` rows).
        large_set_relaxation: Over-relaxation factor ω of the velocity passes of a large set,
            in [1, 2) (measured on the 1 000 and 10 000 pits: ω 1.5 with 10 passes halves the
            overlap and lowers the creep against 15 plain passes).
        impact_tolerance: Impact passes stop once no contact closes faster than its
            acceleration explains by more than this [m/s].
        max_impact_passes: Cap on the impact passes.

    Projection (positions):

    Attributes:
        projection_tolerance: Projection stops once no penetration exceeds this × dt [m/s·s]
            (1.7 µm at 60 Hz).
        max_projection_passes: Cap on the projection passes of a small set.
        max_large_projection_passes: ... and of a large set (measured on the settled 10 000
            pit: passes 5–15 cost 70 % of the projection for 0.2 mm).
        projection_slop: Penetration [m] the projection leaves in a resting contact (it
            pushed last step, as the impact stage tells resting from colliding; not links,
            not a contact that only got there, which is pushed out entirely): Box2D's linear
            slop (``b2_linearSlop``, 5 mm, in its position solver ``C = β·(separation +
            slop)``). Without it every step's solve left a few µm of sinking somewhere in a
            pile that the projection pushed out, moving the pile's contacts each step, so the
            warm start never caught up:
            frictionless pits of 100 and 1 000 spheres jittered at 0.02-0.03 m/s for ever
            (issue 26 point 4). Measured with the slop on every contact (pits of bench_peers,
            sleep off, mean speed at 40 s): 0.1 mm 0.022 (N = 100) / 0.0002 (N = 1000); 0.25 mm
            0.0004 / -; 0.5 mm 0.0004 / 0.0002; on resting contacts only, 0.5 mm, sleep on:
            asleep by 10 s (N = 100) and 30 s (N = 1000). 0: none.
        max_newton_projections: Newton iterations of a small set's projection on its contacts
            measured again (``remeasure.py``).
        line_search_halvings: Halvings of one Newton step looking for one that lowers the
            violations, before the iterations stop.

    The exact solve (``direct.py``), for small sets only:

    Attributes:
        direct_max_contacts: Largest set (rows) the exact solve takes.
        direct_after_passes: A small set still unconverged after this many passes gets it.
        direct_always_contacts: Sets of at most this many rows always may (it costs little).
        direct_min_mass_ratio: ... as do sets whose inverse masses are this far apart
            (ill-conditioned for Gauss–Seidel).

    Threads:

    Attributes:
        parallel_min_contacts: From this many contacts the passes run on every core, block by
            block (``partition.py``); chosen by the contacts only, so any thread count gives
            the same bits. It did not pay at any size measured, so it starts above them all.
    """

    velocity_tolerance: float = 1e-4
    max_velocity_passes: int = 15
    max_large_velocity_passes: int = 10
    large_set_relaxation: float = 1.5
    impact_tolerance: float = 1e-3
    max_impact_passes: int = 8
    projection_tolerance: float = 1e-4
    max_projection_passes: int = 15
    max_large_projection_passes: int = 4
    projection_slop: float = 5e-4
    max_newton_projections: int = 25
    line_search_halvings: int = 30
    direct_max_contacts: int = 384
    direct_after_passes: int = 10
    direct_always_contacts: int = 64
    direct_min_mass_ratio: float = 10.0
    parallel_min_contacts: int = 1_000_000

    def __post_init__(self) -> None:
        for f in fields(self):
            value = getattr(self, f.name)
            if f.type == "int":
                if isinstance(value, bool) or not isinstance(value, int):
                    raise TypeError(f"SolverSettings.{f.name} must be an int, got {value!r}")
                low = 0 if f.name in ("direct_max_contacts", "direct_always_contacts",
                                      "parallel_min_contacts", "direct_after_passes") else 1
                if value < low:
                    raise ValueError(f"SolverSettings.{f.name} must be >= {low}, got {value}")
            else:
                low_ok = f.name == "projection_slop"  # 0: no slop
                if isinstance(value, bool) or not isinstance(value, (int, float)) \
                        or not math.isfinite(value) or value < 0 or (value == 0 and not low_ok):
                    raise ValueError(f"SolverSettings.{f.name} must be a finite number "
                                     f"{'>= 0' if low_ok else '> 0'}, got {value!r}")
        if not 1.0 <= self.large_set_relaxation < 2.0:
            raise ValueError("SolverSettings.large_set_relaxation must be in [1, 2) (ω ≥ 2 "
                             f"diverges), got {self.large_set_relaxation}")
        if self.direct_min_mass_ratio < 1.0:
            raise ValueError("SolverSettings.direct_min_mass_ratio must be >= 1, got "
                             f"{self.direct_min_mass_ratio}")
