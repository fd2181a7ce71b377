"""Float hints for max c^T x over P = {x : G x <= b} (x free, many rows), from HiGHS on the dual form.

The LP route (:mod:`exactinv.validset.lp_route`) asks for the optimal basis of
max c^T x s.t. G x <= b at many costs c that a warm start has not seen (other
facets, other Taylor directions).  With m rows and n << m columns, HiGHS' basis
on that form has dimension m; on its LP dual

    min b^T y  s.t.  G^T y = c,  y >= 0

the basis has dimension n, a new c only changes the right-hand side (the last
basis stays dual feasible: a dual simplex warm start), and a solve costs about
half as much (R^20 with 200 rows: 1.4 ms against 3.4 ms for 600 such costs).
An optimal basis of the dual form with n basic columns y_r names n rows of G:
a basis of the primal (B = those rows), which the caller verifies in Q.

Only a hint: anything odd (not optimal, fewer than n basic columns, a value
beyond double range, a HiGHS error) gives None, and nothing here raises.
"""

from __future__ import annotations

from typing import Any

import highspy
import numpy as np

from .highs import silent_highs

__all__ = ["DualFormHint"]


class DualFormHint:
    """The dual form of max c^T x s.t. G x <= b (x free) as one HiGHS model, re-solved for each new cost.

    ``G`` (m x n) and ``b`` (m) are floats; the rows are scaled to max-norm 1 for the model only.

    >>> DualFormHint(np.array([[2.0, 0.0], [0.0, 1.0], [-1.0, -1.0]]), np.array([2.0, 1.0, 0.0])).basis_rows(np.array([1.0, 1.0]))
    (0, 1)
    """

    def __init__(self, G: np.ndarray, b: np.ndarray):
        self.m, self.n = G.shape
        norms = np.abs(G).max(axis=1) if self.n else np.ones(self.m)
        scale = 1.0 / np.where(norms > 0, norms, 1.0)
        self.GT = (G * scale[:, None]).T.copy()  # n x m: the dual form's rows
        self.cost = b * scale
        self._highs: highspy.Highs | None = None
        self._idx = np.arange(self.n, dtype=np.int32)
        self.solves = 0
        self.degenerate = False  # the last solve was optimal but named no vertex basis (ask the primal form)

    def _build(self) -> highspy.Highs:
        h = silent_highs()
        h.setOptionValue("presolve", "off")
        lp = highspy.HighsLp()
        lp.num_col_, lp.num_row_ = self.m, self.n
        lp.col_cost_ = self.cost
        lp.col_lower_, lp.col_upper_ = np.zeros(self.m), np.full(self.m, highspy.kHighsInf)
        lp.row_lower_, lp.row_upper_ = np.zeros(self.n), np.zeros(self.n)
        lp.a_matrix_.format_ = highspy.MatrixFormat.kRowwise
        lp.a_matrix_.start_ = np.arange(0, self.m * self.n + 1, self.m, dtype=np.int32)
        lp.a_matrix_.index_ = np.tile(np.arange(self.m, dtype=np.int32), self.n)
        lp.a_matrix_.value_ = self.GT.reshape(-1).copy()
        h.passModel(lp)
        return h

    def basis_rows(self, c: np.ndarray) -> tuple[int, ...] | None:
        """The rows of G of an optimal basis of max c^T x over P (sorted), or None.  HiGHS starts from the
        model's last basis (still dual feasible for the new c: a vertex of P).  When the optimum is found but
        its basis has a logical column and the optimal x (the dual form's row duals, a point of the optimal
        face, not always a vertex) has too few tight rows to complete it, ``degenerate`` is set: the
        primal form's simplex, which ends at a vertex, may still name one.

        >>> hint = DualFormHint(np.array([[1.0, 0.0], [0.0, 1.0], [-1.0, -1.0]]), np.array([1.0, 1.0, 0.0]))
        >>> hint.basis_rows(np.array([1.0, 2.0]))    # the vertex (1, 1): rows 0 and 1 tight
        (0, 1)
        >>> hint.basis_rows(np.array([-1.0, -1.0])) in {(0, 2), (1, 2)}  # the optimal face x1 + x2 = 0: either end
        True
        >>> hint.basis_rows(np.array([-1.0, 0.0]))   # the vertex (-1, 1)
        (1, 2)
        >>> hint.basis_rows(np.array([0.0, 1.0])) in {(0, 1), (1, 2)}  # y = e_1 alone: completed by a row tight at x
        True
        >>> square = DualFormHint(np.array([[1.0, 0.0], [0.0, 1.0], [-1.0, 0.0], [0.0, -1.0]]), np.ones(4))
        >>> square.basis_rows(np.array([1.0, 0.0])), square.degenerate  # x = (1, 0): inside the face x1 = 1
        (None, True)
        >>> DualFormHint(np.array([[1.0]]), np.array([1.0])).basis_rows(np.array([-1.0]))  # unbounded: no basis
        """
        self.degenerate = False
        if len(c) != self.n or not np.all(np.isfinite(c)) or not np.all(np.isfinite(self.cost)):
            return None
        try:
            if self._highs is None:
                self._highs = self._build()
            h: Any = self._highs  # highspy's stubs lack the change* methods
            h.changeRowsBounds(self.n, self._idx, c, c)
            h.run()
            self.solves += 1
            if h.getModelStatus() != highspy.HighsModelStatus.kOptimal:
                return None
            y = np.asarray(h.getSolution().col_value)
            positive = np.flatnonzero(y > 0)  # basic: a nonbasic y_r sits at its bound 0
            if len(positive) == self.n:
                return tuple(int(r) for r in positive)
            basis = h.getBasis()  # degenerate (a basic y_r at 0): the statuses tell the basis
            if not basis.valid:
                return None
            basic = highspy.HighsBasisStatus.kBasic
            rows: tuple[int, ...] | None = tuple(r for r, st in enumerate(basis.col_status) if st == basic)
            if rows is not None and len(rows) < self.n:  # a logical is basic: complete by rows tight at the optimal x
                rows = self._completed(rows, np.asarray(h.getSolution().row_dual))
                self.degenerate = rows is None
        except Exception:  # noqa: BLE001 -- a hint never raises: a failed solve only gives no hint
            self._highs = None  # a model in an odd state is rebuilt next time
            return None
        return rows if rows is not None and len(rows) == self.n else None

    def _completed(self, rows: tuple[int, ...], x: np.ndarray) -> tuple[int, ...] | None:
        """``rows`` (independent, y_r > 0 on them) completed to n independent rows of G tight at x, the
        optimal point of max c^T x (the dual form's row duals), the tightest first; None if there are not n."""
        if len(x) != self.n or not np.all(np.isfinite(x)):
            return None
        G = self.GT.T
        slack = self.cost - G @ x
        tight = [int(r) for r in np.argsort(slack) if slack[r] <= 1e-9 * (1.0 + abs(self.cost[r])) and r not in rows]
        chosen = list(rows)
        for r in tight:
            if len(chosen) == self.n:
                break
            if np.linalg.matrix_rank(G[chosen + [r]]) == len(chosen) + 1:
                chosen.append(r)
        return tuple(sorted(chosen)) if len(chosen) == self.n else None
