"""The exact LP engine (layer ``lp``): float hint -> exact reconstruction ->
verification in Q -> exact fallback.  See :mod:`exactinv.lp.solver`; the
float-hint backends (HiGHS, the default, or any solver through cvxpy) are in
:mod:`exactinv.lp.hint`."""

from .hint import CvxpyHint, HighsHint, HintBackend, get_hint_backend, hint_backend, set_hint_backend
from .solver import INFEASIBLE, OPTIMAL, UNBOUNDED, ExactLPSolver, LPResult, solve_lp

__all__ = ["LPResult", "ExactLPSolver", "solve_lp", "OPTIMAL", "INFEASIBLE", "UNBOUNDED",
           "HintBackend", "HighsHint", "CvxpyHint", "set_hint_backend", "get_hint_backend", "hint_backend"]
