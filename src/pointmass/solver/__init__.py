"""The contact solver, in named stages (see ``solver.py`` for the policy, ``stages.py`` for the
stages, ``kernels.py`` for the per-contact kernels and ``history.py`` for warm starting)."""

from ..impulse_history import ImpulseHistory
from .solver import ALIASES, MODES, Solver, SolveStats

__all__ = ["ALIASES", "MODES", "ImpulseHistory", "SolveStats", "Solver"]
