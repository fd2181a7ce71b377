"""The exact LP engine (layer ``lp``): float hint -> exact reconstruction ->
verification in Q -> exact fallback.  See :mod:`exactinv.lp.solver`."""

from .solver import INFEASIBLE, OPTIMAL, UNBOUNDED, ExactLPSolver, LPResult, solve_lp

__all__ = ["LPResult", "ExactLPSolver", "solve_lp", "OPTIMAL", "INFEASIBLE", "UNBOUNDED"]
