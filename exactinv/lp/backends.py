"""The float-hint backends: HiGHS (the default: bases, warm starts) and any
LP solver configured in cvxpy (an optional dependency, imported only when
used).  Chosen with :func:`exactinv.lp.hint.set_hint_backend` and friends.
"""

from __future__ import annotations

import importlib.util
from typing import Any, Sequence

import highspy
import numpy as np

from .highs import silence_banner, silent_highs
from .hint_types import UNKNOWN_HINT, Basis, Hint, HintBackend, HintModel, LPStatus

__all__ = ["HighsHint", "CvxpyHint"]


# ----------------------------------------------------------------- HiGHS
class HighsHint(HintBackend):
    """HiGHS' simplex through highspy: bases and warm starts (the default)."""

    name = "highs"

    def model(self, A, equality):
        """A HiGHS model of the float matrix ``A`` (built on its first solve, then warm-started).

        >>> hint = HighsHint().model(np.array([[2.0, 1.0]]), [True]).solve(np.array([1.0, 1.0]), np.array([2.0]), [True, True])
        >>> hint.status, hint.x.tolist(), hint.fetch_basis()   # max x1 + x2 on 2 x1 + x2 = 2: the vertex (0, 2)
        (<LPStatus.OPTIMAL: 'optimal'>, [0.0, 2.0], ((1,), (0,)))
        """
        return _HighsModel(A, equality)


class _HighsModel(HintModel):
    def __init__(self, A: np.ndarray, equality: Sequence[bool]):
        self.A = A
        self.equality = np.array(equality, dtype=bool)
        self.R, self.N = A.shape
        self._highs: highspy.Highs | None = None
        self._last: tuple[np.ndarray, ...] = ()

    def solve(self, cost, rhs, nonneg):
        cost = -cost  # HiGHS minimizes
        lower = np.where(np.asarray(nonneg, dtype=bool), 0.0, -highspy.kHighsInf) if self.N else np.zeros(0)
        row_lower = np.where(self.equality, rhs, -highspy.kHighsInf)
        if self._highs is None:
            self._highs = self._build(cost, lower, row_lower, rhs)
        else:
            self._update(cost, lower, row_lower, rhs)
        self._last = (cost, lower, row_lower, rhs)
        h = self._highs
        h.run()
        status = h.getModelStatus()
        S = highspy.HighsModelStatus
        if status == S.kOptimal:
            sol = h.getSolution()
            return Hint(LPStatus.OPTIMAL, np.asarray(sol.col_value), -np.asarray(sol.row_dual), basis_of=self._basis)
        if status in (S.kInfeasible, S.kUnbounded):
            return Hint(LPStatus.INFEASIBLE if status == S.kInfeasible else LPStatus.UNBOUNDED)
        self._highs = None  # a model in an odd state is rebuilt next time
        return UNKNOWN_HINT

    def _build(self, cost, lower, row_lower, rhs) -> highspy.Highs:
        h = silent_highs()
        h.setOptionValue("presolve", "off")
        lp = highspy.HighsLp()
        lp.num_col_, lp.num_row_ = self.N, self.R
        lp.col_cost_, lp.col_lower_, lp.col_upper_ = cost, lower, np.full(self.N, highspy.kHighsInf)
        lp.row_lower_, lp.row_upper_ = row_lower, rhs
        cols = self.A.T
        nz = [np.nonzero(cols[i])[0] for i in range(self.N)]
        lp.a_matrix_.format_ = highspy.MatrixFormat.kColwise
        lp.a_matrix_.start_ = np.concatenate([[0], np.cumsum([len(z) for z in nz])]).astype(np.int32)
        lp.a_matrix_.index_ = np.concatenate(nz).astype(np.int32) if nz else np.zeros(0, np.int32)
        lp.a_matrix_.value_ = np.concatenate([cols[i][z] for i, z in enumerate(nz)]) if nz else np.zeros(0)
        h.passModel(lp)
        return h

    def _update(self, cost, lower, row_lower, rhs) -> None:
        """Pass HiGHS only the entries that differ from the last LP (the row LPs
        of gamma* differ in two costs and two bounds)."""
        h = self._highs
        old_cost, old_lower, old_row_lower, old_rhs = self._last
        idx = np.flatnonzero(cost != old_cost).astype(np.int32)
        if len(idx):
            h.changeColsCost(len(idx), idx, cost[idx])
        idx = np.flatnonzero(lower != old_lower).astype(np.int32)
        if len(idx):
            h.changeColsBounds(len(idx), idx, lower[idx], np.full(len(idx), highspy.kHighsInf))
        idx = np.flatnonzero((row_lower != old_row_lower) | (rhs != old_rhs)).astype(np.int32)
        if len(idx):
            h.changeRowsBounds(len(idx), idx, row_lower[idx], rhs[idx])

    def _basis(self) -> Basis | None:
        """(basic columns, tight rows = rows whose slack is nonbasic), fetched
        only when rounding does not verify (a Python loop over all statuses).
        (Not ``getBasicVariables``: highspy 1.15 crashes on it for LPs solved without pivots.)"""
        if self._highs is None:
            return None
        basis = self._highs.getBasis()
        if not basis.valid:
            return None
        basic = highspy.HighsBasisStatus.kBasic
        return (tuple(i for i, st in enumerate(basis.col_status) if st == basic),
                tuple(r for r, st in enumerate(basis.row_status) if st != basic))


# ----------------------------------------------------------------- cvxpy
class CvxpyHint(HintBackend):
    """Any LP solver configured in cvxpy (``solver=None``: cvxpy chooses).

    The LP is written once per constraint matrix as a DPP-compliant cvxpy
    problem with parameters for the cost, the right-hand side and the sign
    mask (``mask_i x_i >= 0``), so re-solving skips cvxpy's canonicalisation.
    ``solver_options`` are passed to ``Problem.solve``.  cvxpy gives no basis:
    the engine guesses one from the float point."""

    name = "cvxpy"

    def __init__(self, solver: str | None = None, **solver_options: Any):
        if importlib.util.find_spec("cvxpy") is None:
            raise ImportError("the cvxpy hint backend needs cvxpy, an optional dependency: pip install cvxpy")
        self.solver = solver
        self.solver_options = solver_options

    def model(self, A, equality):
        """The LP as a parametrised cvxpy problem (compiled once, re-solved with new data).

        >>> hint = CvxpyHint('CLARABEL').model(np.array([[1.0, 1.0]]), [False]).solve(np.array([1.0, 0.0]), np.array([3.0]), [True, True])
        >>> hint.status, [round(float(v), 6) for v in hint.x], hint.basis   # an interior-point solver: no basis
        (<LPStatus.OPTIMAL: 'optimal'>, [3.0, 0.0], None)
        """  # noqa: E501 (doctest output)
        return _CvxpyModel(A, equality, self.solver, self.solver_options)

    def __repr__(self) -> str:
        return f"CvxpyHint(solver={self.solver!r})"


class _CvxpyModel(HintModel):
    def __init__(self, A: np.ndarray, equality: Sequence[bool], solver: str | None, options: dict):
        import cvxpy as cp  # optional dependency: imported only by this backend

        self.cp = cp
        self.solver, self.options = solver, options
        self.R, self.N = A.shape
        eq = np.array(equality, dtype=bool)
        self.eq_rows, self.le_rows = np.flatnonzero(eq), np.flatnonzero(~eq)
        self.x = cp.Variable(self.N)
        self.cost = cp.Parameter(self.N)
        self.mask = cp.Parameter(self.N, nonneg=True)
        constraints = [cp.multiply(self.mask, self.x) >= 0]
        self.b_eq = self.b_le = self.c_eq = self.c_le = None
        if len(self.eq_rows):
            self.b_eq = cp.Parameter(len(self.eq_rows))
            self.c_eq = A[self.eq_rows] @ self.x == self.b_eq
            constraints.append(self.c_eq)
        if len(self.le_rows):
            self.b_le = cp.Parameter(len(self.le_rows))
            self.c_le = A[self.le_rows] @ self.x <= self.b_le
            constraints.append(self.c_le)
        self.problem = cp.Problem(cp.Maximize(self.cost @ self.x), constraints)

    def solve(self, cost, rhs, nonneg):
        cp = self.cp
        if self.N == 0:
            return UNKNOWN_HINT
        self.cost.value = np.asarray(cost, dtype=float)
        self.mask.value = np.array([1.0 if v else 0.0 for v in nonneg])
        if self.b_eq is not None:
            self.b_eq.value = rhs[self.eq_rows]
        if self.b_le is not None:
            self.b_le.value = rhs[self.le_rows]
        silence_banner()  # cvxpy's HiGHS interface constructs highspy.Highs itself
        try:
            self.problem.solve(solver=self.solver, **self.options)
        except (cp.SolverError, ValueError, ArithmeticError):
            return UNKNOWN_HINT
        status = self.problem.status
        if status in (cp.INFEASIBLE, cp.INFEASIBLE_INACCURATE):
            return Hint(LPStatus.INFEASIBLE)
        if status in (cp.UNBOUNDED, cp.UNBOUNDED_INACCURATE):
            return Hint(LPStatus.UNBOUNDED)
        if status not in (cp.OPTIMAL, cp.OPTIMAL_INACCURATE) or self.x.value is None:
            return UNKNOWN_HINT
        y = np.zeros(self.R)
        for rows, con in ((self.eq_rows, self.c_eq), (self.le_rows, self.c_le)):
            if con is not None:
                if con.dual_value is None:
                    return UNKNOWN_HINT
                y[rows] = np.asarray(con.dual_value, dtype=float).reshape(-1)
        x = np.asarray(self.x.value, dtype=float).reshape(-1)
        if not (np.all(np.isfinite(x)) and np.all(np.isfinite(y))):
            return UNKNOWN_HINT
        return Hint(LPStatus.OPTIMAL, x, y, None)
