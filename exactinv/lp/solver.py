"""The exact LP engine: float solve -> exact reconstruction -> verification in Q.

Every LP has the form  max c.x  s.t.  a_r.x = b_r (equality rows), a_r.x <= b_r
(the others), x_i >= 0 (nonnegative columns; the others free), with rational
data.  :class:`ExactLPSolver` answers it as a chain of steps, each a module
testable alone (cvxpy's *transform, solve, map back*):

1. **float solve** (:mod:`~exactinv.lp.floatlp`, :mod:`~exactinv.lp.hint`):
   HiGHS' dual simplex by default, or any solver through cvxpy, on the float
   image of the data: a point, its duals and, with HiGHS, its basis (a hint);
2. **reconstruction** (:mod:`~exactinv.lp.reconstruct`): rounded to simple
   fractions (``path="float-rounded"``), else the basis solved exactly
   (``"float-basis"``), else repaired by exact pivots (``"float-basis+pivots"``);
3. **verification** (:mod:`~exactinv.lp.verify`): primal and dual feasibility
   and equal objectives in exact arithmetic -- by LP duality a proof of optimality;
4. **exact fallback** (:mod:`~exactinv.lp.exact`): PPL's exact simplex on the
   LP and its dual (``path="exact-ppl"``), verified the same way.

Infeasible and unbounded LPs get certificates too: a Farkas vector y (y_r >= 0
on inequality rows, A^T y >= 0 on nonnegative columns, = 0 on free ones, b.y <
0), resp. a feasible point and a ray, each the optimum of an *auxiliary* LP
that is bounded by construction.  Auxiliary LPs never build failure
certificates of their own, so the engine recurses at most one level, whatever
the scaling of the rows.  An :class:`LPResult` is returned only after its
certificate has been verified; otherwise :class:`~exactinv.errors.VerificationFailed`.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from enum import StrEnum
from fractions import Fraction
from functools import cached_property
from typing import NamedTuple, Sequence

import flint
import numpy as np

from ..core.flintq import fraction_of
from ..core.scalars import INF, Infinity
from ..errors import VerificationFailed
from .exact import ppl_dual, ppl_maximize
from .floatlp import FloatLP, floats_of
from .hint import resolve_hint_backend
from .hint_types import Hint, HintBackend, LPStatus
from .reconstruct import (
    COMMON_DENOMINATOR,
    basis_solution,
    exact_pivots,
    guess_basis,
    snap_tolerance,
    snapped,
    snapped_numerators,
)
from .verify import LPData, dot, optimal_values, verify_farkas, verify_optimal, verify_ray
from .verify_int import optimal_values_int

__all__ = ["LPStatus", "LPPath", "LPResult", "ExactLPSolver", "solve_lp", "OPTIMAL", "INFEASIBLE", "UNBOUNDED"]

OPTIMAL, INFEASIBLE, UNBOUNDED, UNKNOWN = LPStatus.OPTIMAL, LPStatus.INFEASIBLE, LPStatus.UNBOUNDED, LPStatus.UNKNOWN


class LPPath(StrEnum):
    """Which route produced a verified LP certificate (equal to its string)."""

    ROUNDED = "float-rounded"
    BASIS = "float-basis"
    PIVOTS = "float-basis+pivots"
    PPL = "exact-ppl"


@dataclass(frozen=True)
class LPResult:
    """A verified answer to an LP.

    ``status`` is ``"optimal"`` (then ``x`` is an optimal primal point, ``y``
    an optimal dual point and ``value`` = c.x = b.y), ``"infeasible"`` (then
    ``y`` is a Farkas certificate) or ``"unbounded"`` (then ``x`` is a feasible
    point and ``ray`` a direction of unbounded increase; ``value`` is INF).
    ``path`` records which route produced the certificate.

    >>> res = solve_lp(flint.fmpq_mat([[3, 1], [1, 3]]), [False, False], [1, 1], [1, 1], [True, True])
    >>> res.status, res.value, res.x, res.y
    (<LPStatus.OPTIMAL: 'optimal'>, Fraction(1, 2), (Fraction(1, 4), Fraction(1, 4)), (Fraction(1, 4), Fraction(1, 4)))
    """

    status: LPStatus
    value: Fraction | Infinity | None
    x_q: flint.fmpq_mat | None = field(repr=False)
    y_q: flint.fmpq_mat | None = field(repr=False)
    ray_q: flint.fmpq_mat | None = field(repr=False)
    path: LPPath

    @cached_property
    def x(self) -> tuple[Fraction, ...] | None:
        return None if self.x_q is None else _fractions(self.x_q)

    @cached_property
    def y(self) -> tuple[Fraction, ...] | None:
        return None if self.y_q is None else _fractions(self.y_q)

    @cached_property
    def ray(self) -> tuple[Fraction, ...] | None:
        return None if self.ray_q is None else _fractions(self.ray_q)


class ExactLPSolver:
    """Exact LPs sharing one constraint matrix ``A`` and row kinds.

    The float model is built once and re-solved with new costs, right-hand
    sides and sign restrictions (warm-started from the previous basis), which
    is how the m row LPs of gamma* are solved.

    ``A`` is an ``fmpq_mat`` with R rows and N columns; ``equality[r]`` tells
    whether row r is an equation (else it reads ``<=``).  ``hint`` chooses the
    float-hint backend (a name, ``"highs"`` or ``"cvxpy"``, or a
    :class:`~exactinv.lp.hint.HintBackend`); by default the one in effect
    (:func:`~exactinv.lp.hint.set_hint_backend`, :func:`~exactinv.lp.hint.hint_backend`).

    >>> solver = ExactLPSolver(flint.fmpq_mat([[1, 1], [-1, -1]]), [False, False])
    >>> solver.solve([1, 0], [1, -2], [True, True]).status
    <LPStatus.INFEASIBLE: 'infeasible'>
    >>> solver.solve([1, 0], [1, 0], [True, True]).value
    Fraction(1, 1)
    """

    def __init__(self, A: flint.fmpq_mat, equality: Sequence[bool], hint: str | HintBackend | None = None):
        self.A = A
        self.equality = tuple(bool(e) for e in equality)
        self.data = LPData(A, self.equality)
        self.R, self.N = A.nrows(), A.ncols()
        self.hint_backend = resolve_hint_backend(hint)
        self.float_lp = FloatLP(A, self.equality, self.hint_backend)

    AT = property(lambda self: self.data.AT, doc="A^T (computed once).")

    def solve(self, c: Sequence[Fraction] | flint.fmpq_mat, b: Sequence[Fraction] | flint.fmpq_mat,
              nonnegative: Sequence[bool]) -> LPResult:
        """Maximize c.x over {A x (=|<=) b, x_i >= 0 where nonnegative[i]}; verified.
        ``c`` and ``b`` are sequences of rationals or fmpq column matrices.

        >>> res = ExactLPSolver(flint.fmpq_mat([[1, -1]]), [False]).solve([1, 1], [0], [True, True])
        >>> res.status, res.value   # x1 - x2 <= 0 lets x2 grow: res.ray is such a direction
        (<LPStatus.UNBOUNDED: 'unbounded'>, INF)
        """
        return self._solve(_column(c), _column(b), tuple(bool(v) for v in nonnegative), bounded=False)

    def solve_many(self, costs: flint.fmpq_mat, rhss: flint.fmpq_mat,
                   nonnegatives: Sequence[Sequence[bool]]) -> list[LPResult]:
        """Solve K LPs that share A: LP k has cost column k of ``costs`` (N x K),
        right-hand side column k of ``rhss`` (R x K) and sign pattern
        ``nonnegatives[k]``.  The float hints are reconstructed and then
        verified all at once (:func:`~exactinv.lp.verify.optimal_mask`: two
        exact FLINT matrix products); an LP whose hint fails goes through
        :meth:`solve`'s full route.  Every result is verified exactly.

        >>> solver = ExactLPSolver(flint.fmpq_mat([[1], [-1]]), [False, False])
        >>> [r.value for r in solver.solve_many(flint.fmpq_mat([[1, -1]]), flint.fmpq_mat([[2, 3], [0, 0]]), [[False]] * 2)]
        [Fraction(2, 1), Fraction(0, 1)]
        """
        C_cols, B_cols = _LazyColumns(costs), _LazyColumns(rhss)
        C_float, B_float = C_cols.floats(), B_cols.floats()
        signs = [tuple(map(bool, nn)) for nn in nonnegatives]
        proposals = [self._batch_proposal(C_cols, B_cols, k, C_float[k], B_float[k], signs[k]) for k in range(len(signs))]
        values = None
        if proposals and all(p is not None and p.over_common for p in proposals):  # integers: the fast exact path
            Xn, Yn = (np.array([getattr(p, part) for p in proposals], dtype=float).T for part in "xy")
            values = optimal_values_int(self.data, costs, rhss, signs, Xn, Yn, COMMON_DENOMINATOR)
        if values is None:
            X, Y = _proposal_matrix(proposals, "x", self.N), _proposal_matrix(proposals, "y", self.R)
            values = optimal_values(self.data, costs, rhss, signs, X, Y)
        results = []
        for k, (proposal, value) in enumerate(zip(proposals, values)):
            if value is not None:
                x, y = _proposal_column(proposal.x, proposal), _proposal_column(proposal.y, proposal)
                results.append(LPResult(OPTIMAL, fraction_of(value), x, y, None, proposal.path))
            else:
                results.append(self._solve(C_cols[k], B_cols[k], signs[k], bounded=False))
        return results

    # ------------------------------------------------------------ the chain
    def _solve(self, cq: flint.fmpq_mat, bq: flint.fmpq_mat, nonneg: tuple[bool, ...], bounded: bool) -> LPResult | None:
        """The chain for one LP.  ``bounded``: an auxiliary LP of a failure
        certificate, bounded by construction, so a hint saying otherwise is a
        lie and the exact route is taken at once; no failure certificate is
        ever built for it (None if it has no optimum after all)."""
        hint = self.float_lp.solve(cq, bq, nonneg)
        if hint.status == OPTIMAL:
            for path, x, y in self._reconstructions(cq, bq, nonneg, hint):
                if x is not None and y is not None and verify_optimal(self.data, cq, bq, nonneg, x, y):
                    return _optimal(cq, x, y, path)
        elif not bounded:
            certificate = self._certified_failure(hint.status, cq, bq, nonneg)
            if certificate is not None:
                return certificate
        return self._exact_solve(cq, bq, nonneg, bounded)

    def _batch_proposal(self, C_cols: _LazyColumns, B_cols: _LazyColumns, k: int, cost: np.ndarray | None,
                        rhs: np.ndarray | None, nonneg: tuple[bool, ...]) -> _Proposal | None:
        """LP k's cheapest reconstruction for a batch: rounded (integer
        numerators over COMMON_DENOMINATOR), or the basis solve when rounding
        leaves large denominators (fmpq entries); None without a hint."""
        hint = self.float_lp.solve_floats(cost, rhs, nonneg)
        if hint.status != OPTIMAL:
            return None
        tol = snap_tolerance(hint.has_basis)
        x, y = snapped_numerators(hint.x, tol), snapped_numerators(hint.y, tol)
        if x is not None and y is not None:
            return _Proposal(LPPath.ROUNDED, x, y, True)
        cq, bq = C_cols[k], B_cols[k]
        pair = basis_solution(self.data, cq, bq, self._basis(hint, bq, nonneg))
        if pair is not None:
            return _Proposal(LPPath.BASIS, pair[0].entries(), pair[1].entries(), False)
        (xq, _), (yq, _) = snapped(hint.x, tol), snapped(hint.y, tol)
        return _Proposal(LPPath.ROUNDED, xq, yq, False)

    def _reconstructions(self, cq, bq, nonneg, hint: Hint):
        """Candidate exact (x, y) pairs, cheapest first."""
        tol = snap_tolerance(hint.has_basis)
        (x, _), (y, _) = snapped(hint.x, tol), snapped(hint.y, tol)
        yield LPPath.ROUNDED, flint.fmpq_mat(self.N, 1, x), flint.fmpq_mat(self.R, 1, y)
        basis = self._basis(hint, bq, nonneg)
        pair = basis_solution(self.data, cq, bq, basis)
        if pair is not None:
            yield (LPPath.BASIS, *pair)
        pair = exact_pivots(self.data, cq, bq, nonneg, basis)
        if pair is not None:
            yield (LPPath.PIVOTS, *pair)

    def _basis(self, hint: Hint, bq, nonneg):
        basis = hint.fetch_basis()
        if basis is not None:
            return basis
        return guess_basis(self.float_lp.A, self.equality, self.float_lp.rhs(bq), hint.x, hint.y, nonneg)

    # ------------------------------------- certificates of the other outcomes
    def _certified_failure(self, status: LPStatus, cq, bq, nonneg) -> LPResult | None:
        """A verified Farkas certificate (INFEASIBLE) or point and ray (UNBOUNDED), or None."""
        if status == INFEASIBLE:
            return self._farkas(bq, nonneg)
        if status == UNBOUNDED:
            return self._unbounded(cq, bq, nonneg)
        return None

    def _farkas(self, bq, nonneg) -> LPResult | None:
        """Farkas vector from the auxiliary LP  max -b.y  s.t. y dual-feasible
        for c = 0 and -b.y <= 1 (its optimum is 1 exactly when Ax<=b is empty)."""
        rows = [[-self.A[r, i] for r in range(self.R)] for i in range(self.N)] + [[-bq[r, 0] for r in range(self.R)]]
        aux = ExactLPSolver(flint.fmpq_mat(rows), [not nonneg[i] for i in range(self.N)] + [False], self.hint_backend)
        res = aux._solve(-bq, _column([0] * self.N + [1]), tuple(not e for e in self.equality), bounded=True)
        if res is None or not verify_farkas(self.data, bq, nonneg, res.x_q):
            return None
        return LPResult(INFEASIBLE, None, None, res.x_q, None, res.path)

    def _unbounded(self, cq, bq, nonneg) -> LPResult | None:
        """A feasible point (max 0 over the same set) and a ray (max c.d over the
        recession cone cut by c.d <= 1)."""
        point = self._solve(flint.fmpq_mat(self.N, 1), bq, nonneg, bounded=True)
        if point is None:
            return None
        rows = [[self.A[r, i] for i in range(self.N)] for r in range(self.R)] + [[cq[i, 0] for i in range(self.N)]]
        cone = ExactLPSolver(flint.fmpq_mat(rows), list(self.equality) + [False], self.hint_backend)
        ray = cone._solve(cq, _column([0] * self.R + [1]), nonneg, bounded=True)
        if ray is None or not verify_ray(self.data, cq, nonneg, ray.x_q):
            return None
        return LPResult(UNBOUNDED, INF, point.x_q, None, ray.x_q, ray.path)

    def _exact_solve(self, cq, bq, nonneg, bounded: bool) -> LPResult | None:
        status, x = ppl_maximize(self.A, self.equality, bq, cq, nonneg)
        if status == OPTIMAL:
            dstatus, y = ppl_dual(self.A, self.equality, bq, cq, nonneg)
            if dstatus == OPTIMAL and verify_optimal(self.data, cq, bq, nonneg, x, y):
                return _optimal(cq, x, y, LPPath.PPL)
        elif bounded:
            return None  # an auxiliary LP without optimum: the hint that asked for it lied
        else:
            certificate = self._certified_failure(status, cq, bq, nonneg)
            if certificate is not None:
                return certificate
        raise VerificationFailed(
            "exact LP: neither the float hint nor the exact PPL solve produced a verified certificate"
        )


def solve_lp(A: flint.fmpq_mat, equality: Sequence[bool], b: Sequence[Fraction], c: Sequence[Fraction],
             nonnegative: Sequence[bool], hint: str | HintBackend | None = None) -> LPResult:
    """Solve one LP exactly (see :class:`ExactLPSolver`; ``hint``: the float-hint backend).

    >>> solve_lp(flint.fmpq_mat([[7, 3], [2, 9]]), [False, False], [1, 1], [1, 1], [True, True]).value
    Fraction(11, 57)
    """
    return ExactLPSolver(A, equality, hint).solve(c, b, nonnegative)


# ------------------------------------------------------------------ helpers
def _column(v: Sequence[Fraction] | flint.fmpq_mat) -> flint.fmpq_mat:
    if isinstance(v, flint.fmpq_mat):
        return v
    entries = [flint.fmpq(x.numerator, x.denominator) if isinstance(x, Fraction) else flint.fmpq(x) for x in v]
    return flint.fmpq_mat(len(entries), 1, entries)


class _LazyColumns:
    """The columns of an fmpq matrix as fmpq column matrices, built on demand."""

    def __init__(self, M: flint.fmpq_mat):
        self.rows, self.K = M.nrows(), M.ncols()
        self.T = M.transpose().entries()

    def __getitem__(self, k: int) -> flint.fmpq_mat:
        return flint.fmpq_mat(self.rows, 1, self.T[k * self.rows:(k + 1) * self.rows])

    def floats(self) -> list[np.ndarray | None]:
        """Each column's float image (None for a column beyond double range)."""
        values = floats_of(self.T)
        if values is not None:
            return list(values.reshape(self.K, self.rows))
        return [floats_of(self.T[k * self.rows:(k + 1) * self.rows]) for k in range(self.K)]


class _Proposal(NamedTuple):
    """A batch member's reconstruction: x and y as integer numerators over
    COMMON_DENOMINATOR (``over_common``) or as fmpq entries."""

    path: LPPath
    x: list
    y: list
    over_common: bool


def _proposal_matrix(proposals: list[_Proposal | None], part: str, rows: int) -> flint.fmpq_mat:
    """The ``rows`` x K matrix whose column k is ``getattr(proposal k, part)`` (0 for no proposal):
    one integer matrix for the common-denominator columns, plus the fmpq columns if any."""
    common = [p is not None and p.over_common for p in proposals]
    zeros = [0] * rows
    flat = [v for p, c in zip(proposals, common) for v in (getattr(p, part) if c else zeros)]
    M = flint.fmpq_mat(flint.fmpz_mat(len(proposals), rows, flat)) * flint.fmpq(1, COMMON_DENOMINATOR)
    if not all(c or p is None for p, c in zip(proposals, common)):
        rest = [v for p, c in zip(proposals, common) for v in (zeros if c or p is None else getattr(p, part))]
        M += flint.fmpq_mat(len(proposals), rows, rest)
    return M.transpose()


def _proposal_column(entries: list, proposal: _Proposal) -> flint.fmpq_mat:
    """One part of a proposal as an fmpq column (from its integers in C, without fmpq objects)."""
    if proposal.over_common:
        return flint.fmpq_mat(flint.fmpz_mat(len(entries), 1, entries)) * flint.fmpq(1, COMMON_DENOMINATOR)
    return flint.fmpq_mat(len(entries), 1, entries)


def _fractions(M: flint.fmpq_mat) -> tuple[Fraction, ...]:
    zero = Fraction(0)
    return tuple(zero if v == 0 else fraction_of(v) for v in M.entries())


def _optimal(cq: flint.fmpq_mat, x: flint.fmpq_mat, y: flint.fmpq_mat, path: LPPath) -> LPResult:
    return LPResult(OPTIMAL, fraction_of(dot(cq, x)), x, y, None, path)
