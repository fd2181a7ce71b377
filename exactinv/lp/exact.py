"""Step 4 of the exact LP engine: the exact fallback, PPL's exact simplex.

Used when no reconstruction of the float hint verifies, or when the data do
not fit in doubles.  PPL (``ppl.MIP_Problem``) works over the integers, so
every row is scaled by the lcm of its denominators; its answer is still only
a proposal, verified by :mod:`exactinv.lp.verify` like any other.
"""

from __future__ import annotations

from math import lcm
from typing import Sequence

import flint
import ppl

from .hint_types import LPStatus

__all__ = ["ppl_maximize", "ppl_dual"]


def ppl_maximize(A: flint.fmpq_mat, equality: Sequence[bool], b: flint.fmpq_mat, c: flint.fmpq_mat,
                 nonneg: Sequence[bool]) -> tuple[LPStatus, flint.fmpq_mat | None]:
    """max c.x s.t. A x (= | <=) b, x_i >= 0 (nonneg) by PPL's exact simplex:
    (status, an optimal x for OPTIMAL, else None).

    >>> A = flint.fmpq_mat([[7, 3], [2, 9]])
    >>> status, x = ppl_maximize(A, (False, False), flint.fmpq_mat([[1], [1]]), flint.fmpq_mat([[1], [1]]), (True, True))
    >>> status, x.entries()
    (<LPStatus.OPTIMAL: 'optimal'>, [2/19, 5/57])
    >>> ppl_maximize(flint.fmpq_mat([[1], [-1]]), (False, False), flint.fmpq_mat([[0], [-1]]), flint.fmpq_mat([[1]]), (False,))
    (<LPStatus.INFEASIBLE: 'infeasible'>, None)
    """
    R, N = A.nrows(), A.ncols()
    cs = ppl.Constraint_System()
    for r in range(R):
        expr = _integer_expression([-A[r, i] for i in range(N)], b[r, 0])  # b_r - a_r.x
        cs.insert(expr == 0 if equality[r] else expr >= 0)
    for i in range(N):
        if nonneg[i]:
            cs.insert(ppl.Variable(i) >= 0)
    problem = ppl.MIP_Problem(N, cs, _integer_expression([c[i, 0] for i in range(N)]), "maximization")
    outcome = problem.solve()["status"]
    if outcome == "unfeasible":
        return LPStatus.INFEASIBLE, None
    if outcome == "unbounded":
        return LPStatus.UNBOUNDED, None
    point = problem.optimizing_point()
    d = int(point.divisor())
    coeffs = list(point.coefficients()) + [0] * (N - len(point.coefficients()))
    return LPStatus.OPTIMAL, flint.fmpq_mat(N, 1, [flint.fmpq(int(v), d) for v in coeffs])


def ppl_dual(A: flint.fmpq_mat, equality: Sequence[bool], b: flint.fmpq_mat, c: flint.fmpq_mat,
             nonneg: Sequence[bool]) -> tuple[LPStatus, flint.fmpq_mat | None]:
    """The dual of the LP of :func:`ppl_maximize`, by PPL:
    max -b.y  s.t.  -A^T y <= -c (nonnegative columns), A^T y = c (free),
    y_r >= 0 on inequality rows.  (status, an optimal y).

    >>> A = flint.fmpq_mat([[7, 3], [2, 9]])
    >>> status, y = ppl_dual(A, (False, False), flint.fmpq_mat([[1], [1]]), flint.fmpq_mat([[1], [1]]), (True, True))
    >>> y.entries()
    [7/57, 4/57]
    """
    R, N = A.nrows(), A.ncols()
    dual_A = flint.fmpq_mat([[-A[r, i] for r in range(R)] for i in range(N)])
    neg_c = flint.fmpq_mat(N, 1, [-v for v in c.entries()])
    return ppl_maximize(dual_A, [not v for v in nonneg], neg_c, -b, [not e for e in equality])


_ZERO = flint.fmpq(0)


def _integer_expression(coeffs: Sequence[flint.fmpq], constant: flint.fmpq = _ZERO) -> ppl.Linear_Expression:
    d = lcm(*(int(v.q) for v in coeffs), int(constant.q))
    return ppl.Linear_Expression([int(v * d) for v in coeffs], int(constant * d))
