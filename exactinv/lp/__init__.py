"""The exact LP engine (layer ``lp``), a chain of steps each testable alone:
float hint (:mod:`~exactinv.lp.floatlp`; backends in :mod:`~exactinv.lp.hint`:
HiGHS, the default, or any solver through cvxpy) -> exact reconstruction
(:mod:`~exactinv.lp.reconstruct`) -> verification in Q
(:mod:`~exactinv.lp.verify`) -> exact fallback (:mod:`~exactinv.lp.exact`);
the chain is :mod:`exactinv.lp.solver`."""

from .backends import CvxpyHint, HighsHint
from .hint import get_hint_backend, hint_backend, set_hint_backend
from .hint_types import HintBackend
from .solver import INFEASIBLE, OPTIMAL, UNBOUNDED, ExactLPSolver, LPResult, solve_lp

__all__ = ["LPResult", "ExactLPSolver", "solve_lp", "OPTIMAL", "INFEASIBLE", "UNBOUNDED",
           "HintBackend", "HighsHint", "CvxpyHint", "set_hint_backend", "get_hint_backend", "hint_backend"]
