"""The solver's policy: which stages run, how many passes, when to stop.

**"sequential"** (the default) is one method that is right on impacts, resting piles and
loaded links at once:

1. *prepare* — effective masses, the resting-contact trick's acceleration term, targets.
2. *impacts* — Millington's sequential propagation: every contact that closes faster than
   this step's acceleration explains, and did not carry load last step, bounces at once, its
   target −e·vs taken from its separating velocity when it is visited, passes repeated until
   nothing closes (Newton's cradle passes the whole momentum to the last ball; no restitution
   threshold is needed to keep piles still: a resting contact closes only by what its ends'
   accelerations explain, which the resting-contact trick does not bounce, or it carried load
   last step).
3. *warm start* — each keyed contact begins from the impulse it needed last step.
4. *solve velocities* — sequential impulses (Catto 2006, box2d-lite): accumulated impulses
   clamped at ≥ 0, targets 0 for touching contacts and gap/dt for speculative gaps, passes until
   no velocity changes by more than ``velocity_tolerance``, capped at ``max_passes``.
   Energy: from a cold start, projected Gauss–Seidel decreases f(λ) = KE − KE₀ − λ·target
   monotonically from f(0) = 0, so with targets ≤ 0 it never adds kinetic energy; a warm start
   can (a loaded cable whose direction turned: measured +204 % in one step). So the kinetic
   energy is compared before and after, and a stage that gained energy is redone cold.
   A set too large for the exact solve is over-relaxed (``large_set_relaxation``, ω < 2:
   each row's step still lowers f, only further).
5. *project positions* — mass-weighted projection until no penetration exceeds
   ``projection_tolerance × dt``: positions only, no velocity, so no energy either. A small
   set is then projected again on its contacts measured where the particles now are (Newton's
   method, ``remeasure.py``), so a link that turned within the step is held at its length:
   each Newton step solved exactly in the links' geometric-stiffness metric (a loaded link
   resists turning) and cut back by a line search until it lowers the violations. Where it
   ran, the links' velocities are then solved again, exactly, along their lines as the
   projection left them (``_link_velocities``: never adds kinetic energy).
6. *store impulses* — the sweep's impulses go to the history for the next step.

**"worst-first"** is the book's loop (resolve the worst contact, 2 × contacts times) on the same
kernels, kept for teaching and comparison; it keeps no history.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ..contacts import ContactBuffer
from ..impulse_history import ImpulseHistory
from ..particles import Particles
from . import direct, parallel, remeasure, stages
from .kernels import Bodies, ContactSet
from .partition import block_rows
from .settings import SolverSettings

MODES = ("sequential", "worst-first")
#: Older names accepted for the default mode (the resolver's "auto" and "sweep").
ALIASES = {"auto": "sequential", "sweep": "sequential"}

# The tuning numbers are ``SolverSettings`` fields (``settings.py``, on ``World``); what was
# measured when each default was chosen:
# Velocity passes stop once no contact's velocity changes by more than this [m/s] in a pass.
#   -> ``velocity_tolerance`` = 1e-4
# Impact passes stop once no contact closes faster than its acceleration by more than this.
#   -> ``impact_tolerance`` = 1e-3
# Projection stops once no penetration exceeds this × dt [m/s × s] (at 60 Hz, 1.7 µm).
#   -> ``projection_tolerance`` = 1e-4
# Default caps on the passes of each stage (they end earlier once converged).
#   -> ``max_velocity_passes`` = 15
#   -> ``max_impact_passes`` = 8
#   -> ``max_projection_passes`` = 15
# ... and on the projection of a set too large for the exact solve (more than
# ``direct_max_contacts`` rows): there the slow tail of Gauss–Seidel is all that the
# passes after the third buy. Measured on the settled 10 000-sphere pit (35 000 rows), the
# largest depth after each pass: 10.6, 2.2, 0.98, 0.88, 0.85 ... 0.69 mm at the 15th, so
# passes 5-15 cost 70 % of the projection for 0.2 mm; what is left is projected again next
# step. With 4: overlap after 600 steps 1.2 mm (1 % of the diameter is 10 mm), mean speed
# unchanged; the 1000-sphere pile's largest one-step energy rise 0.056 J (its test's bound 0.2).
#   -> ``max_large_projection_passes`` = 4
# Sets too large for the exact solve (more than ``direct_max_contacts`` rows) have
# their velocity passes over-relaxed by this factor ω (projected successive over-relaxation:
# each row steps ω times its own answer, the clamp still applied; ODE's QuickStep does the
# same), and at most ``max_large_velocity_passes`` of them. Gauss–Seidel's slow tail on a
# pile is a long-wavelength error, which plain passes shrink a little each; ω > 1 shrinks it
# faster. Measured on the pit after 600 steps (N = 1 000, seeds 0-5, mean speed over the last
# 100 steps / largest overlap): 15 plain passes 0.052 m/s / 2.1 mm; 10 plain 0.061 / 2.3; 10
# at ω = 1.3, 1.5, 1.6, 1.7: 0.066 / 1.1, 0.042 / 0.54, 0.045 / 0.45, 0.048 / 0.43; 8 at 1.5:
# 0.048 / 0.86. Seeds 0-15, mean speed over steps 400-600: 15 plain 0.063 ± 0.003, 10 at 1.5
# 0.056 ± 0.004 (the first pass left plain: 0.065 ± 0.004); largest overlap 2.1 / 0.9 mm.
# N = 10 000: 15 plain 0.076 / 1.7, 10 at 1.5 0.065 / 0.68 mm, and a third less time in the
# passes. A row with nothing else on its particles takes (1 - ω)^k of its error after k
# passes (0.1 % after 10) where plain passes solve it in one.
#   -> ``large_set_relaxation`` = 1.5
#   -> ``max_large_velocity_passes`` = 10
# A small contact set still unconverged after this many passes gets the exact solve.
#   -> ``direct_after_passes`` = 10
# A small set's projection is repeated on its contacts measured again where the particles now
# are (``remeasure.py``: Newton's method on the position constraints) until no re-measured
# violation exceeds the tolerance, at most this many times. Only sets whose particles moved
# far enough for the linear depths to be off need any: a resting pile or hanging chain needs
# none, and keeps its bits. Measured over 600 steps at dt = 1/60 of chains pinned at one end
# and released level: 30 links of 0.3 m, no iteration on 83 steps, one on 504, two on 13
# (link error 155 % → 0.001 %; 15 % of the step's time); 6 links of 0.5 m, one on half the
# steps (5 %); piles of 20 and 40 spheres in a box, none. With the geometric-stiffness
# metric and line search (issue 26): 30 links, none on 78 steps, one on 522; 6 links, one
# on 308 of 600; the swinging 1 kg rod + 1000 kg cable (dt = 1/32), 1-6 (mostly 4-6); 50
# rods + 1000 kg released level, 1-13.
#   -> ``max_newton_projections`` = 25
# Each Newton step is halved at most this many times looking for one that lowers the
# violations (the line search); after that the iterations stop (nothing can move: a rod
# between two pinned particles at the wrong distance costs one iteration a step).
#   -> ``line_search_halvings`` = 30
# ... if it is ill-conditioned the way Gauss–Seidel cannot handle: inverse masses of its
# particles this far apart, or a rod among its rows. A pile of equal spheres converges slowly
# too, but passes bring it to rest, and the exact solve cost it ~1 s a step (measured: the
# 100-sphere pit, 300 contacts, 157 active-set solves in 100 steps, 152 s of 161).
#   -> ``direct_min_mass_ratio`` = 10.0
# ... or has at most this many rows, where the exact solve costs little (a few dense solves of
# this size) and ends a slow chain at once.
#   -> ``direct_always_contacts`` = 64
# From this many contacts on, the velocity and projection passes run on every core, block by
# block (``partition.py``, ``parallel.py``); below, in row order on one. The choice depends
# on the contacts only, never on the threads, so any thread count gives the same bits.
# Measured on the 10 000-sphere pit (35 000 contacts, 2 cores shared with other work, load
# ~10): 80 ms a step serially, 108 ms on the parallel path with 1 thread and 108–138 ms with
# 2; it did not pay at any size measured, so it starts above them all. Measured again with the
# groups' rows laid out contiguously (session 21): the main phase runs 1.36× faster on two
# threads than on one (a compute-bound loop: 2.0×), still slower than the serial sweep.
#   -> ``parallel_min_contacts`` = 1_000_000


@dataclass(frozen=True)
class SolveStats:
    """What one ``Solver.solve`` did."""

    contacts: int = 0
    impact_passes: int = 0
    velocity_passes: int = 0
    position_passes: int = 0
    resolutions: int = 0
    cold_restart: bool = False


class Solver:
    """Resolves a step's contacts: velocities (restitution, resting contacts, friction) and
    interpenetration.

    Args:
        mode: "sequential" (default; see the module docstring) or "worst-first" (the book's).
        max_passes: Cap on velocity passes ("sequential") or on single-contact resolutions
            ("worst-first"); None: ``max_velocity_passes`` (``max_large_velocity_passes`` for a
            set too large for the exact solve), or 2 × contacts as in the book.
        restitution_threshold: Closing speeds below this [m/s] do not bounce; 0 (the default)
            hides no inelasticity: the resting-contact trick keeps piles still without it.
        settings: The tuning numbers (``SolverSettings``; its defaults when None).
    """

    def __init__(self, mode: str = "sequential", *, max_passes: int | None = None,
                 restitution_threshold: float = 0.0,
                 settings: SolverSettings | None = None) -> None:
        self.mode = mode
        self.max_passes = max_passes
        self.restitution_threshold = restitution_threshold
        self.settings = SolverSettings() if settings is None else settings

    @property
    def mode(self) -> str:
        return self._mode

    @mode.setter
    def mode(self, value: str) -> None:
        value = ALIASES.get(value, value)
        if value not in MODES:
            raise ValueError(f"resolver must be 'sequential' (default; also 'auto' or 'sweep') "
                             f"or 'worst-first', got {value!r}")
        self._mode = value

    def solve(self, particles: Particles, contacts: ContactBuffer, history: ImpulseHistory,
              dt: float) -> SolveStats:
        """Resolve ``contacts`` in place; afterwards ``contacts.penetration`` holds what is left."""
        m = contacts.count
        if m == 0:
            history.clear()
            return SolveStats()
        p = particles
        bod = Bodies(p.velocity, p.acceleration, p.inv_mass, np.zeros((p.count, 3)))
        con = ContactSet(contacts.a, contacts.b, contacts.normal, contacts.penetration.copy(),
                         contacts.restitution, contacts.friction, contacts.bilateral,
                         np.empty(m), np.empty(m),
                         np.empty(m), np.empty(m), np.empty(m), np.zeros(m), np.zeros((m, 3)))
        dt = float(dt)
        stages.prepare(bod, con, dt)
        if self._mode == "worst-first":
            history.clear()  # the book's resolver keeps nothing between steps
            budget = 2 * m if self.max_passes is None else int(self.max_passes)
            used = stages.worst_first(bod, con, dt, float(self.restitution_threshold), budget)
            stats = SolveStats(contacts=m, resolutions=int(used))
        else:
            stats, con = self._sequential(p, bod, con, contacts, history, dt)
        stages.current_depths(bod, con, contacts.penetration)
        position = p.position
        position += bod.disp  # every stage moved ``disp`` only (see ``kernels.Bodies``)
        return stats

    def _sequential(self, p, bod, con, contacts, history, dt) -> tuple[SolveStats, ContactSet]:
        threshold = float(self.restitution_threshold)
        st = self.settings
        history.recall(contacts.key, con.impulse, con.tangent)
        pressed = con.impulse.copy()  # last step's impulses: which contacts rest (the slop)
        blocks = block_rows(con.a, con.b, p.position) \
            if contacts.count >= st.parallel_min_contacts else None
        impact_passes, hits = stages.impacts(bod, con, dt, threshold, st.impact_tolerance,
                                             st.max_impact_passes)
        if self.max_passes is not None:
            passes = int(self.max_passes)
        else:
            passes = st.max_large_velocity_passes if _large(con, st) \
                else st.max_velocity_passes
        anchors = contacts.anchors
        anchors = _NO_ANCHORS if anchors is None else anchors
        small = _direct_may_help(con, p.position, anchors, st)
        before = (p.kinetic_energy(), p.velocity.copy(), bod.disp.copy())
        stages.warm_start(bod, con, dt)
        velocity_passes, used = self._velocities(bod, con, dt, passes, blocks, small, st)
        cold = p.kinetic_energy() > before[0] * (1.0 + 1e-9) + 1e-15
        if cold:  # the warm start added energy that the passes did not take back: redo cold
            p.velocity[:] = before[1]
            bod.disp[:] = before[2]
            con.impulse[:] = 0.0
            con.tangent[:] = 0.0
            more, used2 = self._velocities(bod, con, dt, passes, blocks, small, st)
            velocity_passes += more
            used += used2
        stages.follow_impulses(bod, con, dt)
        pcon, slop = _slopped(p.position, anchors, con, pressed, st.projection_slop)
        position_passes, measured = self._positions(bod, pcon, st.projection_tolerance * dt,
                                                    blocks, small, p.position, anchors, dt, st)
        if slop is not None:  # the depths reported are the contacts' own, not the slop's
            measured = measured._replace(depth0=measured.depth0 + slop)
        history.keep(contacts.key, con.impulse,
                     con.tangent if contacts.friction.any() else None)
        return SolveStats(contacts=contacts.count, impact_passes=int(impact_passes),
                          velocity_passes=int(velocity_passes),
                          position_passes=int(position_passes),
                          resolutions=int(hits + used), cold_restart=bool(cold)), measured

    @staticmethod
    def _velocities(bod, con, dt: float, passes: int, blocks, small: bool,
                    st: SolverSettings) -> tuple[int, int]:
        """Gauss–Seidel passes; a ``small`` set (``_direct_may_help``) still unconverged after
        ``direct_after_passes`` gets the exact solve (``direct.py``) and a few passes more for
        friction; a set too large for it is over-relaxed (``large_set_relaxation``); one split
        into ``blocks`` runs them on every core (``parallel.py``)."""
        relaxation = st.large_set_relaxation if _large(con, st) else 1.0
        if blocks is not None:
            return parallel.solve_velocities(bod, con, blocks.order, blocks.spans,
                                             blocks.phase_starts, dt, st.velocity_tolerance, passes,
                                             relaxation)
        first = min(passes, st.direct_after_passes) if small else passes
        done, used = stages.solve_velocities(bod, con, dt, st.velocity_tolerance, first,
                                             relaxation)
        if done < first or not small:
            return done, used  # converged, or a large set at its cap
        direct.solve_velocities(bod, con)
        more, used2 = stages.solve_velocities(bod, con, dt, st.velocity_tolerance,
                                              max(passes - first, 1), 1.0)
        return done + more, used + used2 + con.a.shape[0]

    @staticmethod
    def _positions(bod, con, tolerance: float, blocks, small: bool, position, anchors,
                   dt: float, st: SolverSettings):
        """Projection passes, with the exact solve for a small set that does not converge
        (on every core for a large set split into ``blocks``), then for a small set the
        exact solve on its contacts measured again (``max_newton_projections``).

        Returns (passes, the contact set whose linear depths are current: ``con`` or the
        re-measured one)."""
        if blocks is not None:
            return parallel.project_positions(bod, con, blocks.order, blocks.spans,
                                              blocks.phase_starts, tolerance,
                                              st.max_large_projection_passes)[0], con
        first = min(st.direct_after_passes, st.max_projection_passes) if small \
            else st.max_projection_passes
        if _large(con, st):
            first = st.max_large_projection_passes
        done, largest = stages.project_positions(bod, con, tolerance, first)
        if not small:
            return done, con
        if largest > tolerance:
            depths = np.empty(con.a.shape[0])
            stages.current_depths(bod, con, depths)
            direct.project_positions(bod, con, depths)
            more, _ = stages.project_positions(bod, con, tolerance,
                                               max(st.max_projection_passes - first, 1))
            done += more
        newton, measured = _remeasured(position, anchors, bod, con, tolerance, dt, st)
        return done + newton, measured


_NO_ANCHORS = np.empty((0, 3))


def _slopped(position, anchors, con, pressed, slop: float):
    """The contact set the projection works on: each resting contact's depth (``pressed``:
    last step's impulse > 0) less ``slop`` (``stages.slop_depths``; links and other rows keep
    theirs), and the slop given each row (None: none)."""
    if slop == 0.0:
        return con, None
    depth0 = np.empty_like(con.depth0)
    given = np.empty_like(con.depth0)
    if stages.slop_depths(position, anchors, con.a, con.b, con.n, con.depth0, con.bil, pressed,
                          float(slop), depth0, given) == 0:
        return con, None
    return con._replace(depth0=depth0), given


def _remeasured(position, anchors, bod, con, tolerance: float, dt: float,
                st: SolverSettings):
    """Newton iterations on the position constraints (``remeasure.py``): the exact projection
    of the contacts measured again, until no violation exceeds ``tolerance``. Each step is
    solved in the geometric-stiffness metric (``remeasure.stiff_metric``, the links' tension:
    the velocity stage's impulses × dt plus the pushes so far) and shortened by halves until
    it lowers Σ violation² (a line search: Newton's step is a descent direction of it, so a
    step that wanders is cut back instead of kept). Returns (the iterations, the contact set
    whose linear depths are current)."""
    m = con.a.shape[0]
    n = np.empty((m, 3))
    depth0 = np.empty(m)
    depths = np.empty(m)
    lengths = np.empty(m)
    worst = remeasure.relinearize(position, anchors, bod, con, n, depth0, depths, lengths)
    if worst <= tolerance:
        return 0, con  # nothing moved far enough to matter: the same bits as before
    again = con._replace(n=n, depth0=depth0)
    tension = con.impulse * dt
    col, parts = direct.columns(con.a, con.b, bod.inv_mass.shape[0])
    merit = remeasure.merit(depths, con.bil)
    start = np.empty_like(bod.disp)
    trial = (np.empty((m, 3)), np.empty(m), np.empty(m), np.empty(m))
    iterations = 0
    while iterations < st.max_newton_projections and worst > tolerance:
        iterations += 1
        start[:] = bod.disp
        metric = remeasure.stiff_metric(parts, col, bod.inv_mass, con.a, con.b, n, lengths,
                                        tension)
        pushes = direct.project_metric(con.a, con.b, n, con.bil, depths, col, parts, metric,
                                       bod.disp)
        step = bod.disp - start
        fraction = 1.0
        for _ in range(st.line_search_halvings):
            tried = remeasure.relinearize(position, anchors, bod, con, *trial)
            tried_merit = remeasure.merit(trial[2], con.bil)
            if tried_merit < merit:
                break
            fraction *= 0.5
            bod.disp[:] = start + fraction * step
        else:  # no step lowers the violations (a rod between pinned particles): stop
            bod.disp[:] = start
            break
        worst, merit = tried, tried_merit
        n[:], depth0[:], depths[:], lengths[:] = trial
        tension += fraction * pushes
    _link_velocities(position, anchors, bod, con, dt)
    remeasure.relinearize(position, anchors, bod, con, n, depth0, depths, lengths)
    return iterations, again


def _link_velocities(position, anchors, bod, con, dt: float) -> None:
    """Solve the links' velocities again at the positions the projection left (exactly,
    ``direct.py``): a rod's ends may not move apart or together along their line as it is
    now, a taut cable's not apart, a slack one's by no more than its slack in a step.

    Why: the velocity stage holds each link along its line where the contacts were generated,
    the projection then turns it, and the velocities left along the new line are what nothing
    holds: a load hanging still kept falling at g·dt a step while its positions were projected
    back, and energy grew without bound (measured: a 10-link chain with 1000 kg released level,
    30 m/s at the load after 3 s, 345 kJ gained). Run only when the projection re-measured (a
    link turned within the step), so a chain that did not keeps its bits. A projection onto a
    convex set holding v = 0 (targets ≤ 0), in the mass metric: it never adds kinetic energy."""
    m = con.a.shape[0]
    n = np.empty((m, 3))
    depth0 = np.empty(m)
    depths = np.empty(m)
    lengths = np.empty(m)
    remeasure.relinearize(position, anchors, bod, con, n, depth0, depths, lengths)
    links = np.flatnonzero(lengths > 0.0)
    if links.shape[0] == 0:
        return
    bil = con.bil[links]
    d = depths[links]
    target = np.where(bil | (d >= 0.0), 0.0, d / dt)
    direct._velocities(con.a[links], con.b[links], np.ascontiguousarray(n[links]), bil,
                       target, np.zeros(links.shape[0]), bod.vel, bod.inv_mass)


def _large(con, st: SolverSettings) -> bool:
    """Too large for the exact solve: over-relaxed velocity passes, fewer projection passes."""
    return con.a.shape[0] > st.direct_max_contacts


def _direct_may_help(con, position, anchors, st: SolverSettings) -> bool:
    """Small enough for the exact solve, and either tiny, or a chain of links (rods; cables
    and anchored links, which ``remeasure.has_links`` tells from a pile's contacts: Gauss–Seidel
    crawls along a chain, measured: a 100-cable chain released level stretched 371 %), or
    ill-conditioned as links under heavy loads are (``direct_min_mass_ratio``)."""
    if _large(con, st):
        return False
    if con.a.shape[0] <= st.direct_always_contacts or con.bil.any() \
            or remeasure.has_links(position, anchors, con):
        return True
    w = np.concatenate([con.wa, con.wb])
    w = w[w > 0.0]
    return w.shape[0] > 0 and float(w.max()) >= st.direct_min_mass_ratio * float(w.min())
