"""The book's name for the contact solver: ``resolve_contacts`` runs ``pointmass.solver`` once
on a contact buffer (for tests, teaching and custom pipelines). ``World.step`` uses the solver
directly, with an impulse history that lives in the world."""

from __future__ import annotations

from .contacts import ContactBuffer
from .particles import Particles
from .solver import ALIASES, MODES, ImpulseHistory, Solver

RESOLVER_MODES = MODES + tuple(ALIASES)


def resolve_contacts(particles: Particles, contacts: ContactBuffer, dt: float, *,
                     mode: str = "worst-first", iterations: int | None = None,
                     restitution_threshold: float = 0.0,
                     history: ImpulseHistory | None = None) -> int:
    """Resolve ``contacts`` in place (velocities and positions of ``particles``); returns the
    single-contact resolutions made. ``history`` carries warm-start impulses between calls
    (None: a cold start). Afterwards ``contacts.penetration`` holds what is left."""
    solver = Solver(mode, max_passes=iterations, restitution_threshold=restitution_threshold)
    stats = solver.solve(particles, contacts, history if history is not None
                         else ImpulseHistory(), dt)
    return stats.resolutions
