"""``SolverSettings``: every tuning number of the solver in one frozen value on ``World``.

Each field's default is what the engine ships with and what its tests measure; the comment on
each says what it trades and what was measured when it was chosen (the measurements in full
are in the docstrings of the stages that read it). A test or a user who wants another value
passes one (``World(settings=SolverSettings(max_velocity_passes=30))``, or
``dataclasses.replace(world.settings, ...)`` assigned to ``world.settings``), never patches a
module. Numerical guards that are not choices (the epsilons that tell a zero from round-off,
``kernels.PENETRATION_EPSILON``, ``remeasure.STIFF_CAP``) and memory layouts that change
no result (``sweeps.STREAMS``, ``partition.SLABS``) stay beside the code that needs them, as
do the choices of method that other stages rely on (``body_soft.FRICTION_IN_SOLVE``,
``joint_soft.GEOMETRIC``) and the guards of a root finder (``body_continuous.ITERATIONS``).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, fields


@dataclass(frozen=True)
class SolverSettings:
    """The solver's tuning numbers (see the module docstring; ``solver/solver.py`` for the
    particle stages that read them, ``solver/body_soft.py``, ``joint_soft.py`` and
    ``body_continuous.py`` for the soft step's).

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

    The bodies' soft step (``World()``'s body stage; ``solver/body_soft.py``, Box2D v3's
    solver), its contacts:

    Attributes:
        soft_substeps: Substeps of one body step (Box2D's ``subStepCount``): each kicks,
            solves, drifts and relaxes over h = dt / ``soft_substeps``. Fewer is cheaper and
            coarser: a pendulum's energy swings by leapfrog's O((ω·h)²) (0.0063 % of m·g·L
            at h = 1/240; 16 times that at one substep).
        contact_hertz: Stiffness of a contact as a frequency [Hz] (a spring–damper solved
            implicitly over h), doubled against scenery. Box2D's 30 Hz is too soft for a tower
            of unit boxes: a column of rocking springs k = m·ω² per corner buckles under its own
            weight above ~15 m at 30 Hz, ~24 m at 60 Hz, ~61 m at 240 Hz (measured, 20 s, sleep
            off: 20 boxes fall at 30 Hz, 30 at 60 Hz; at 240 Hz 30 boxes drift 1.3 mm). A
            body resting under a load sinks by about load / (m·(2π·hertz)²).
        contact_hertz_cap: Largest contact stiffness as a fraction of the substep rate 1/h
            (Box2D's 0.25 for joints; 1: the cap does not bind at dt 1/60, 4 substeps).
        contact_damping_ratio: Damping ratio ζ of the contact spring (Box2D's
            ``contactDampingRatio``, 10: heavily overdamped); 0: undamped.
        contact_speed: Largest speed [m/s] at which a soft row pushes an overlap out, and a
            joint's bias closes a gap (Box2D's ``contactSpeed``).
        soft_solve_passes: Passes of the biased solve per substep at most (Box2D: 1); they
            stop once no row changes a velocity by more than ``soft_tolerance``. One pass
            leaves a tall stack's Gauss–Seidel order in it (measured, 20 s, sleep off: 20 boxes
            fall with 1 + 1, drift 0.6 mm with up to 30 + 30).
        soft_relax_passes: ... of the relax stage per substep (Box2D: 1), and of the
            restitution's passes after the substeps.
        soft_tolerance: The soft passes (and the restitution's) stop once no row changes a
            velocity by more than this [m/s].
        soft_relaxation: Over-relaxation ω of the biased solve's normal rows, in (0, 2)
            (projected SOR: the soft rows' K + γ is positive definite). Measured, passes a step
            at t = 3–4 s, ω 1.0 / 1.3 / 1.5 / 1.8: the 10-box tower 83 / 59 / 48 / 77, the
            210-box pyramid 190 / 155 / 54 / 87; 1.5 with the relax plain: 32 and 40.

    Its joints (``solver/joint_soft.py``):

    Attributes:
        joint_hertz: Stiffness of a joint's position bias [Hz] (Box2D's ``jointHertz`` 60)
            for the rows solved by Gauss–Seidel; the rows solved through a tree of joints are
            rigid and do not read it.
        joint_damping_ratio: ... its damping ratio (Box2D's ``jointDampingRatio`` 2); 0:
            undamped.
        joint_hertz_cap: Largest joint stiffness as a fraction of the substep rate (Box2D's
            0.25).
        joint_passes: Joint passes per stage (solve, relax) at most; they stop once no joint
            row changes a velocity by more than ``joint_tolerance`` [m/s or rad/s].
        joint_tolerance: See ``joint_passes``.

    Its continuous collision (``solver/body_continuous.py``, Box2D v3's
    ``b2SolveContinuous``):

    Attributes:
        continuous_slop: Box2D's linear slop [m]: the separation a time of impact stops a fast
            body at, and how much deeper than at the step's start a touching pair may end it
            (the collision's speculative margin, ``collide.SPECULATIVE_MARGIN``, is the same
            5 mm: a stopped body is within it at the next step's start).
        continuous_safety: A body is fast (swept back) when a point of it moves more than
            this fraction of its smallest half-extent in a step (Box2D's ``safetyFactor``).
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
    soft_substeps: int = 4
    contact_hertz: float = 240.0
    contact_hertz_cap: float = 1.0
    contact_damping_ratio: float = 10.0
    contact_speed: float = 3.0
    soft_solve_passes: int = 30
    soft_relax_passes: int = 30
    soft_tolerance: float = 1e-5
    soft_relaxation: float = 1.5
    joint_hertz: float = 60.0
    joint_damping_ratio: float = 2.0
    joint_hertz_cap: float = 0.25
    joint_passes: int = 30
    joint_tolerance: float = 1e-5
    continuous_slop: float = 0.005
    continuous_safety: float = 0.5

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
                # 0: no slop, an undamped spring
                low_ok = f.name in ("projection_slop", "contact_damping_ratio",
                                    "joint_damping_ratio")
                if isinstance(value, bool) or not isinstance(value, (int, float)) \
                        or not math.isfinite(value) or value < 0 or (value == 0 and not low_ok):
                    raise ValueError(f"SolverSettings.{f.name} must be a finite number "
                                     f"{'>= 0' if low_ok else '> 0'}, got {value!r}")
        if not 1.0 <= self.large_set_relaxation < 2.0:
            raise ValueError("SolverSettings.large_set_relaxation must be in [1, 2) (ω ≥ 2 "
                             f"diverges), got {self.large_set_relaxation}")
        if not 0.0 < self.soft_relaxation < 2.0:
            raise ValueError("SolverSettings.soft_relaxation must be in (0, 2) (ω ≥ 2 "
                             f"diverges), got {self.soft_relaxation}")
        if self.soft_substeps > 1000:
            raise ValueError("SolverSettings.soft_substeps must be in [1, 1000], got "
                             f"{self.soft_substeps}")
        if self.direct_min_mass_ratio < 1.0:
            raise ValueError("SolverSettings.direct_min_mass_ratio must be >= 1, got "
                             f"{self.direct_min_mass_ratio}")
