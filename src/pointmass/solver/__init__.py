"""The contact solver, in named stages (see ``solver.py`` for the policy, ``stages.py`` for the
stages, ``kernels.py`` for the per-contact kernels, ``settings.py`` for the tuning numbers;
``pointmass.impulse_history`` keeps the warm starts)."""

from ..impulse_history import ImpulseHistory
from .settings import SolverSettings
from .solver import ALIASES, MODES, Solver, SolveStats

__all__ = ["ALIASES", "MODES", "ImpulseHistory", "SolveStats", "Solver", "SolverSettings"]
