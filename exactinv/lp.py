"""The exact LP engine: float solve -> exact reconstruction -> verification in Q.

Every linear program exactinv solves has the form ::

    maximize  c.x   subject to   a_r.x  = b_r   (r an equality row)
                                 a_r.x <= b_r   (r an inequality row)
                                 x_i >= 0       (i a nonnegative column; the others are free)

with rational data.  :class:`ExactLPSolver` answers it exactly, following
cvxpy's *transform, solve, map back*:

1. **float solve** -- HiGHS' dual simplex on the float image of the data gives
   a basic solution, its duals and its basis (an untrusted hint);
2. **reconstruction** -- the hint is mapped back to Q: first by rounding the
   float values to nearby simple fractions (``path="float-rounded"``), and if
   that does not verify by solving the optimal basis' linear systems exactly
   with FLINT (``path="float-basis"``);
3. **verification** -- primal feasibility, dual feasibility and equality of the
   objectives are checked in exact arithmetic.  By LP duality these three
   facts prove optimality, so nothing else is trusted;
4. **exact fallback** -- if no reconstruction verifies, the LP (and its dual)
   are solved by PPL's exact simplex (``path="exact-ppl"``), and verified the
   same way.

Infeasible and unbounded programs get certificates too: a Farkas vector
(``y`` with y_r >= 0 on inequality rows, A^T y >= 0 on nonnegative columns,
= 0 on free ones, and b.y < 0), resp. a feasible point and a ray.  A
:class:`LPResult` is returned only after its certificate has been verified.
"""

from __future__ import annotations

from dataclasses import dataclass
from fractions import Fraction
from math import lcm
from typing import Sequence

import flint
import highspy
import numpy as np
import ppl

from .errors import VerificationFailed
from .numbers import INF, Infinity, fraction_of

__all__ = ["LPResult", "ExactLPSolver", "solve_lp", "OPTIMAL", "INFEASIBLE", "UNBOUNDED"]

OPTIMAL, INFEASIBLE, UNBOUNDED = "optimal", "infeasible", "unbounded"
_ROUNDING_DENOMINATOR = 1 << 24


@dataclass(frozen=True)
class LPResult:
    """A verified answer to an LP.

    ``status`` is ``"optimal"`` (then ``x`` is an optimal primal point, ``y``
    an optimal dual point and ``value`` = c.x = b.y), ``"infeasible"`` (then
    ``y`` is a Farkas certificate) or ``"unbounded"`` (then ``x`` is a feasible
    point and ``ray`` a direction of unbounded increase; ``value`` is INF).
    ``path`` records which route produced the certificate.
    """

    status: str
    value: Fraction | Infinity | None
    x: tuple[Fraction, ...] | None
    y: tuple[Fraction, ...] | None
    ray: tuple[Fraction, ...] | None
    path: str


class ExactLPSolver:
    """Exact LPs sharing one constraint matrix ``A`` and row kinds.

    The float model is built once and re-solved with new costs, right-hand
    sides and sign restrictions (warm-started from the previous basis), which
    is how the m row LPs of gamma* are solved.

    ``A`` is an ``fmpq_mat`` with R rows and N columns; ``equality[r]`` tells
    whether row r is an equation (else it reads ``<=``).
    """

    def __init__(self, A: flint.fmpq_mat, equality: Sequence[bool]):
        self.A = A
        self.AT = A.transpose()
        self.equality = tuple(bool(e) for e in equality)
        self.R, self.N = A.nrows(), A.ncols()
        self._highs: highspy.Highs | None = None
        self._A_float = np.array([[float(A[r, i]) for i in range(self.N)] for r in range(self.R)], dtype=float).reshape(self.R, self.N)

    # ------------------------------------------------------------------ API
    def solve(self, c: Sequence[Fraction], b: Sequence[Fraction], nonnegative: Sequence[bool]) -> LPResult:
        """Maximize c.x over {A x (=|<=) b, x_i >= 0 where nonnegative[i]}; verified."""
        cq = _column(c)
        bq = _column(b)
        nonneg = tuple(bool(v) for v in nonnegative)
        status, x_float, y_float, basis = self._float_solve(c, b, nonneg)
        if status == OPTIMAL:
            for path, x, y in self._reconstructions(cq, bq, nonneg, x_float, y_float, basis):
                if x is not None and y is not None and self._verify_optimal(cq, bq, nonneg, x, y):
                    return _optimal(cq, x, y, path)
        elif status == INFEASIBLE:
            certificate = self._farkas(bq, nonneg)
            if certificate is not None:
                return certificate
        elif status == UNBOUNDED:
            certificate = self._unbounded(cq, bq, nonneg)
            if certificate is not None:
                return certificate
        return self._exact_solve(cq, bq, nonneg)

    # ----------------------------------------------------------- float hint
    def _float_solve(self, c, b, nonneg):
        h = self._highs
        cost = np.array([-float(v) for v in c])  # HiGHS minimizes
        lower = np.array([0.0 if v else -highspy.kHighsInf for v in nonneg])
        upper = np.full(self.N, highspy.kHighsInf)
        rhs = np.array([float(v) for v in b])
        row_lower = np.where(np.array(self.equality, dtype=bool), rhs, -highspy.kHighsInf)
        if h is None:
            h = highspy.Highs()
            h.setOptionValue("output_flag", False)
            h.setOptionValue("presolve", "off")
            lp = highspy.HighsLp()
            lp.num_col_, lp.num_row_ = self.N, self.R
            lp.col_cost_, lp.col_lower_, lp.col_upper_ = cost, lower, upper
            lp.row_lower_, lp.row_upper_ = row_lower, rhs
            cols = self._A_float.T
            nz = [np.nonzero(cols[i])[0] for i in range(self.N)]
            lp.a_matrix_.format_ = highspy.MatrixFormat.kColwise
            lp.a_matrix_.start_ = np.concatenate([[0], np.cumsum([len(z) for z in nz])]).astype(np.int32)
            lp.a_matrix_.index_ = np.concatenate(nz).astype(np.int32) if nz else np.zeros(0, np.int32)
            lp.a_matrix_.value_ = np.concatenate([cols[i][z] for i, z in enumerate(nz)]) if nz else np.zeros(0)
            h.passModel(lp)
            self._highs = h
        else:
            idx = np.arange(self.N, dtype=np.int32)
            h.changeColsCost(self.N, idx, cost)
            h.changeColsBounds(self.N, idx, lower, upper)
            ridx = np.arange(self.R, dtype=np.int32)
            h.changeRowsBounds(self.R, ridx, row_lower, rhs)
        h.run()
        status = h.getModelStatus()
        S = highspy.HighsModelStatus
        if status == S.kOptimal:
            sol = h.getSolution()
            basis = h.getBasis()
            return OPTIMAL, list(sol.col_value), [-v for v in sol.row_dual], basis
        if status == S.kInfeasible:
            return INFEASIBLE, None, None, None
        if status == S.kUnbounded:
            return UNBOUNDED, None, None, None
        self._highs = None  # a model in an odd state is rebuilt next time
        return "unknown", None, None, None

    # -------------------------------------------------------- map back to Q
    def _reconstructions(self, cq, bq, nonneg, x_float, y_float, basis):
        """Candidate exact (x, y) pairs, cheapest first."""
        B = highspy.HighsBasisStatus
        basic_cols = [i for i, s in enumerate(basis.col_status) if s == B.kBasic]
        basic_rows = {r for r, s in enumerate(basis.row_status) if s == B.kBasic}
        tight_rows = [r for r in range(self.R) if r not in basic_rows]
        x = [Fraction(0)] * self.N
        for i in basic_cols:
            x[i] = _snap(x_float[i])
        y = [Fraction(0)] * self.R
        for r in tight_rows:
            y[r] = _snap(y_float[r])
        yield "float-rounded", _column(x), _column(y)
        if len(basic_cols) != len(tight_rows):
            return
        Bmat = flint.fmpq_mat(len(tight_rows), len(basic_cols), [self.A[r, i] for r in tight_rows for i in basic_cols])
        try:
            xB = Bmat.solve(flint.fmpq_mat(len(tight_rows), 1, [bq[r, 0] for r in tight_rows]))
            yB = Bmat.transpose().solve(flint.fmpq_mat(len(basic_cols), 1, [cq[i, 0] for i in basic_cols]))
        except (ZeroDivisionError, ValueError):
            return
        xq = flint.fmpq_mat(self.N, 1)
        for k, i in enumerate(basic_cols):
            xq[i, 0] = xB[k, 0]
        yq = flint.fmpq_mat(self.R, 1)
        for k, r in enumerate(tight_rows):
            yq[r, 0] = yB[k, 0]
        yield "float-basis", xq, yq

    # --------------------------------------------------------- verification
    def _primal_feasible(self, bq, nonneg, x) -> bool:
        Ax = self.A * x
        for r in range(self.R):
            if self.equality[r] and Ax[r, 0] != bq[r, 0]:
                return False
            if not self.equality[r] and Ax[r, 0] > bq[r, 0]:
                return False
        return all(x[i, 0] >= 0 for i in range(self.N) if nonneg[i])

    def _dual_feasible(self, cq, nonneg, y) -> bool:
        if any(y[r, 0] < 0 for r in range(self.R) if not self.equality[r]):
            return False
        reduced = self.AT * y - cq
        return all(reduced[i, 0] >= 0 if nonneg[i] else reduced[i, 0] == 0 for i in range(self.N))

    def _verify_optimal(self, cq, bq, nonneg, x, y) -> bool:
        return (
            self._primal_feasible(bq, nonneg, x)
            and self._dual_feasible(cq, nonneg, y)
            and _dot(cq, x) == _dot(bq, y)
        )

    def _verify_farkas(self, bq, nonneg, y) -> bool:
        zero = flint.fmpq_mat(self.N, 1)
        return self._dual_feasible(zero, nonneg, y) and _dot(bq, y) < 0

    def _verify_ray(self, cq, nonneg, d) -> bool:
        zero = flint.fmpq_mat(self.R, 1)
        return self._primal_feasible(zero, nonneg, d) and _dot(cq, d) > 0

    # ------------------------------------- certificates of the other outcomes
    def _farkas(self, bq, nonneg) -> LPResult | None:
        """Farkas vector from the auxiliary LP  max -b.y  s.t. y dual-feasible
        for c = 0 and -b.y <= 1 (its optimum is 1 exactly when Ax<=b is empty)."""
        rows = [[-self.A[r, i] for r in range(self.R)] for i in range(self.N)] + [[-bq[r, 0] for r in range(self.R)]]
        aux = ExactLPSolver(flint.fmpq_mat(rows), [not nonneg[i] for i in range(self.N)] + [False])
        res = aux.solve([-fraction_of(bq[r, 0]) for r in range(self.R)], [0] * self.N + [1], [not e for e in self.equality])
        if res.status != OPTIMAL:
            return None
        y = _column(res.x)
        if not self._verify_farkas(bq, nonneg, y):
            return None
        return LPResult(INFEASIBLE, None, None, res.x, None, res.path)

    def _unbounded(self, cq, bq, nonneg) -> LPResult | None:
        """A feasible point (max 0 over the same set) and a ray (max c.d over the
        recession cone cut by c.d <= 1)."""
        point = self.solve([0] * self.N, [fraction_of(v) for v in bq.entries()], nonneg)
        if point.status != OPTIMAL:
            return None
        rows = [[self.A[r, i] for i in range(self.N)] for r in range(self.R)] + [[cq[i, 0] for i in range(self.N)]]
        cone = ExactLPSolver(flint.fmpq_mat(rows), list(self.equality) + [False])
        ray = cone.solve([fraction_of(v) for v in cq.entries()], [0] * self.R + [1], nonneg)
        if ray.status != OPTIMAL or not self._verify_ray(cq, nonneg, _column(ray.x)):
            return None
        return LPResult(UNBOUNDED, INF, point.x, None, ray.x, ray.path)

    # ------------------------------------------------------ exact fallback
    def _exact_solve(self, cq, bq, nonneg) -> LPResult:
        status, x = _ppl_maximize(self.A, self.equality, bq, cq, nonneg)
        if status == OPTIMAL:
            # The dual:  max -b.y  s.t.  -A^T y <= -c (nonneg cols), A^T y = c (free), y_r >= 0 on <= rows.
            dual_A = flint.fmpq_mat([[-self.A[r, i] for r in range(self.R)] for i in range(self.N)])
            neg_c = flint.fmpq_mat(self.N, 1, [-v for v in cq.entries()])
            dstatus, y = _ppl_maximize(dual_A, [not v for v in nonneg], neg_c, -bq, [not e for e in self.equality])
            if dstatus == OPTIMAL and self._verify_optimal(cq, bq, nonneg, x, y):
                return _optimal(cq, x, y, "exact-ppl")
        elif status == INFEASIBLE:
            certificate = self._farkas(bq, nonneg)
            if certificate is not None:
                return certificate
        elif status == UNBOUNDED:
            certificate = self._unbounded(cq, bq, nonneg)
            if certificate is not None:
                return certificate
        raise VerificationFailed(
            "exact LP: neither the float hint nor the exact PPL solve produced a verified certificate"
        )


def solve_lp(
    A: flint.fmpq_mat,
    equality: Sequence[bool],
    b: Sequence[Fraction],
    c: Sequence[Fraction],
    nonnegative: Sequence[bool],
) -> LPResult:
    """Solve one LP exactly (see :class:`ExactLPSolver`)."""
    return ExactLPSolver(A, equality).solve(c, b, nonnegative)


# ------------------------------------------------------------------ helpers
def _snap(v: float) -> Fraction:
    return Fraction(v).limit_denominator(_ROUNDING_DENOMINATOR)


def _column(v) -> flint.fmpq_mat:
    if isinstance(v, flint.fmpq_mat):
        return v
    entries = [flint.fmpq(x.numerator, x.denominator) if isinstance(x, Fraction) else flint.fmpq(x) for x in v]
    return flint.fmpq_mat(len(entries), 1, entries)


def _dot(u: flint.fmpq_mat, v: flint.fmpq_mat) -> flint.fmpq:
    return (u.transpose() * v)[0, 0]


def _optimal(cq, x, y, path) -> LPResult:
    return LPResult(
        OPTIMAL,
        fraction_of(_dot(cq, x)),
        tuple(fraction_of(v) for v in x.entries()),
        tuple(fraction_of(v) for v in y.entries()),
        None,
        path,
    )


def _integer_expression(coeffs: Sequence[flint.fmpq], constant: flint.fmpq = flint.fmpq(0)):
    d = lcm(*(int(v.q) for v in coeffs), int(constant.q))
    return ppl.Linear_Expression([int(v * d) for v in coeffs], int(constant * d))


def _ppl_maximize(A, equality, bq, cq, nonneg):
    """PPL's exact simplex (MIP_Problem); returns (status, x as fmpq column)."""
    R, N = A.nrows(), A.ncols()
    cs = ppl.Constraint_System()
    for r in range(R):
        expr = _integer_expression([-A[r, i] for i in range(N)], bq[r, 0])  # b_r - a_r.x
        cs.insert(expr == 0 if equality[r] else expr >= 0)
    for i in range(N):
        if nonneg[i]:
            cs.insert(ppl.Variable(i) >= 0)
    objective = _integer_expression([cq[i, 0] for i in range(N)])
    problem = ppl.MIP_Problem(N, cs, objective, "maximization")
    outcome = problem.solve()["status"]
    if outcome == "unfeasible":
        return INFEASIBLE, None
    if outcome == "unbounded":
        return UNBOUNDED, None
    point = problem.optimizing_point()
    d = int(point.divisor())
    coeffs = list(point.coefficients()) + [0] * (N - len(point.coefficients()))
    return OPTIMAL, flint.fmpq_mat(N, 1, [flint.fmpq(int(v), d) for v in coeffs])
