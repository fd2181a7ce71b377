"""The exact LP engine: float solve -> exact reconstruction -> verification in Q.

Every linear program exactinv solves has the form ::

    maximize  c.x   subject to   a_r.x  = b_r   (r an equality row)
                                 a_r.x <= b_r   (r an inequality row)
                                 x_i >= 0       (i a nonnegative column; the others are free)

with rational data.  :class:`ExactLPSolver` answers it exactly, following
cvxpy's *transform, solve, map back*:

1. **float solve** -- a hint backend (:mod:`exactinv.lp.hint`: HiGHS' dual
   simplex by default, or any solver through cvxpy) on the float image of the
   data gives a solution, its duals and, with HiGHS, its basis (an untrusted hint);
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

from dataclasses import dataclass, field
from fractions import Fraction
from functools import cached_property
from math import lcm
from typing import Sequence

import flint
import numpy as np
import ppl

from ..errors import VerificationFailed
from ..core.scalars import INF, Infinity, fraction_of
from .hint import Hint, HintBackend, LPStatus, resolve_hint_backend

__all__ = ["LPStatus", "LPResult", "ExactLPSolver", "solve_lp", "OPTIMAL", "INFEASIBLE", "UNBOUNDED"]

OPTIMAL, INFEASIBLE, UNBOUNDED, UNKNOWN = LPStatus.OPTIMAL, LPStatus.INFEASIBLE, LPStatus.UNBOUNDED, LPStatus.UNKNOWN
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
    x_q: flint.fmpq_mat | None = field(repr=False)
    y_q: flint.fmpq_mat | None = field(repr=False)
    ray_q: flint.fmpq_mat | None = field(repr=False)
    path: str

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
    """

    def __init__(self, A: flint.fmpq_mat, equality: Sequence[bool], hint: str | HintBackend | None = None):
        self.A = A
        self.AT = A.transpose()
        self.equality = tuple(bool(e) for e in equality)
        self.R, self.N = A.nrows(), A.ncols()
        self.hint_backend = resolve_hint_backend(hint)
        self._hint_model = None
        floats = _floats(A.entries())
        self._A_float = None
        if floats is not None:
            # Rows scaled to max-norm 1 for the float model only (PPL-made rows can
            # carry 10^15-sized integers); the hint's duals are scaled back.
            A_float = floats.reshape(self.R, self.N)
            norms = np.abs(A_float).max(axis=1) if self.N else np.ones(self.R)
            self._row_scale = np.where(norms > 0, 1.0 / np.where(norms > 0, norms, 1.0), 1.0)
            self._A_float = A_float * self._row_scale[:, None]

    @cached_property
    def _rows(self) -> list[list[tuple[int, flint.fmpq]]]:
        """Sparse rows of A (for verifying one solution: basic solutions are sparse)."""
        entries = self.A.entries()
        return [[(i, v) for i, v in enumerate(entries[r * self.N:(r + 1) * self.N]) if v != 0] for r in range(self.R)]

    @cached_property
    def _cols(self) -> list[list[tuple[int, flint.fmpq]]]:
        cols: list[list[tuple[int, flint.fmpq]]] = [[] for _ in range(self.N)]
        for r, row in enumerate(self._rows):
            for i, v in row:
                cols[i].append((r, v))
        return cols

    # ------------------------------------------------------------------ API
    def solve(self, c: Sequence[Fraction] | flint.fmpq_mat, b: Sequence[Fraction] | flint.fmpq_mat,
              nonnegative: Sequence[bool], *, _bounded: bool = False) -> LPResult:
        """Maximize c.x over {A x (=|<=) b, x_i >= 0 where nonnegative[i]}; verified.
        ``c`` and ``b`` are sequences of rationals or fmpq column matrices.
        (``_bounded``: the LP is known to have an optimum -- the auxiliary LPs
        of the failure certificates -- so a hint saying otherwise is a lie and
        the exact route is taken at once, instead of recursing on it.)"""
        cq = _column(c)
        bq = _column(b)
        nonneg = tuple(bool(v) for v in nonnegative)
        hint = self._float_solve(cq, bq, nonneg)
        if hint.status == OPTIMAL:
            for path, x, y in self._reconstructions(cq, bq, nonneg, hint):
                if x is not None and y is not None and self._verify_optimal(cq, bq, nonneg, x, y):
                    return _optimal(cq, x, y, path)
        elif not _bounded:
            certificate = self._certified_failure(hint.status, cq, bq, nonneg)
            if certificate is not None:
                return certificate
        return self._exact_solve(cq, bq, nonneg)

    def _certified_failure(self, status: str, cq, bq, nonneg) -> LPResult | None:
        """A verified Farkas certificate (INFEASIBLE) or point and ray (UNBOUNDED), or None."""
        if status == INFEASIBLE:
            return self._farkas(bq, nonneg)
        if status == UNBOUNDED:
            return self._unbounded(cq, bq, nonneg)
        return None

    def solve_many(self, costs: flint.fmpq_mat, rhss: flint.fmpq_mat,
                   nonnegatives: Sequence[Sequence[bool]]) -> list[LPResult]:
        """Solve K LPs that share A: LP k has cost column k of ``costs`` (N x K),
        right-hand side column k of ``rhss`` (R x K) and sign pattern
        ``nonnegatives[k]``.  The float hints are rounded and then verified all
        at once by two exact FLINT matrix products (primal A X, dual A^T Y);
        an LP whose rounded hint fails goes through :meth:`solve`'s full route.
        Every returned result is verified exactly, as with :meth:`solve`."""
        K = costs.ncols()
        C_cols = _columns_of(costs)
        B_cols = _columns_of(rhss)
        signs = [tuple(nn) for nn in nonnegatives]
        results: list[LPResult | None] = [None] * K
        paths = ["float-rounded"] * K
        xs, ys = [], []
        for k in range(K):
            hint = self._float_solve(C_cols[k], B_cols[k], signs[k])
            if hint.status != OPTIMAL:
                results[k] = self.solve(C_cols[k], B_cols[k], signs[k])
                xs.append(None)
                ys.append(None)
                continue
            x, x_clean = _snapped(hint.x, _snap_tolerance(hint))
            y, y_clean = _snapped(hint.y, _snap_tolerance(hint))
            if not (x_clean and y_clean):  # large denominators: rounding is unlikely to verify
                pair = self._basis_solution(C_cols[k], B_cols[k], self._basis_of(hint, B_cols[k], signs[k]))
                if pair is not None:
                    x, y = pair
                    paths[k] = "float-basis"
            xs.append(x.entries())
            ys.append(y.entries())
        zero_N, zero_R = [flint.fmpq(0)] * self.N, [flint.fmpq(0)] * self.R
        X = flint.fmpq_mat(K, self.N, [v for x in xs for v in (x if x is not None else zero_N)]).transpose()
        Y = flint.fmpq_mat(K, self.R, [v for y in ys for v in (y if y is not None else zero_R)]).transpose()
        ok = [x is not None for x in xs]
        # primal: slack = b - A x >= 0, = 0 on equality rows; x >= 0 where required
        for idx, v in enumerate((rhss - self.A * X).entries()):
            if v != 0:
                r, k = divmod(idx, K)
                if v < 0 or self.equality[r]:
                    ok[k] = False
        # dual: A^T y - c >= 0 (nonnegative columns), = 0 (free); y >= 0 on inequality rows
        for idx, v in enumerate((self.AT * Y - costs).entries()):
            if v != 0:
                i, k = divmod(idx, K)
                if v < 0 or not signs[k][i]:
                    ok[k] = False
        for k in range(K):
            if not ok[k]:
                continue
            x, y = xs[k], ys[k]
            if any(v < 0 for v, sign in zip(x, signs[k]) if sign and v != 0) or any(
                v < 0 for v, eq in zip(y, self.equality) if not eq and v != 0
            ):
                ok[k] = False
                continue
            cx = sum((c * v for c, v in zip(C_cols[k].entries(), x) if c != 0 and v != 0), flint.fmpq(0))
            by = sum((b * v for b, v in zip(B_cols[k].entries(), y) if b != 0 and v != 0), flint.fmpq(0))
            if cx != by:
                ok[k] = False
                continue
            results[k] = LPResult(OPTIMAL, fraction_of(cx), flint.fmpq_mat(self.N, 1, x), flint.fmpq_mat(self.R, 1, y),
                                  None, paths[k])
        for k in range(K):
            if results[k] is None:
                results[k] = self.solve(C_cols[k], B_cols[k], signs[k])
        return results

    # ----------------------------------------------------------- float hint
    def _float_solve(self, c, b, nonneg) -> Hint:
        """The backend's float answer (duals scaled back to the exact rows)."""
        cost, rhs = _floats(c.entries()), _floats(b.entries())
        if self._A_float is None or cost is None or rhs is None:
            return Hint(UNKNOWN)  # beyond double range: exact route only
        if self._hint_model is None:
            self._hint_model = self.hint_backend.model(self._A_float, self.equality)
        hint = self._hint_model.solve(cost, rhs * self._row_scale, nonneg)
        if hint.status == OPTIMAL:
            if (hint.x is None or hint.y is None or len(hint.x) != self.N or len(hint.y) != self.R
                    or not (np.all(np.isfinite(hint.x)) and np.all(np.isfinite(hint.y)))):
                return Hint(UNKNOWN)  # a malformed hint is no hint
            basis = hint.basis
            if basis is not None and not (
                    len(basis) == 2 and all(0 <= i < self.N for i in basis[0]) and all(0 <= r < self.R for r in basis[1])
                    and len(set(basis[0])) == len(basis[0]) and len(set(basis[1])) == len(basis[1])):
                basis = None  # a malformed basis: guess one from the point instead
            return Hint(OPTIMAL, np.asarray(hint.x, dtype=float), np.asarray(hint.y, dtype=float) * self._row_scale,
                        basis)
        return hint

    def _basis_of(self, hint: Hint, bq, nonneg) -> tuple[tuple[int, ...], tuple[int, ...]]:
        """The hint's basis, or one guessed from its float point (backends
        without bases, e.g. interior-point solvers through cvxpy).

        Columns at their bound (x_i ~ 0, nonnegative) are nonbasic; tight rows
        are picked greedily -- equality rows, then inequality rows by increasing
        slack (ties: larger dual first) -- while independent on the other
        columns; of those columns, as many as tight rows are kept basic (free
        columns first, then larger |x_i|), again greedily independent.  Float
        Gram-Schmidt on vectors of length <= min(R, N)-ish; a guess only:
        whatever it gives is solved and verified exactly."""
        if hint.basis is not None:
            return hint.basis
        x, y = hint.x, hint.y
        scale = max(1.0, float(np.abs(x).max()) if len(x) else 1.0)
        slack = (_floats(bq.entries()) * self._row_scale - self._A_float @ x) / scale
        tol = 1e-7
        off_bound = [i for i in range(self.N) if not nonneg[i] or abs(x[i]) > tol * scale]
        off_bound.sort(key=lambda i: (nonneg[i], -abs(x[i])))
        order = [r for r in range(self.R) if self.equality[r]]
        order += sorted((r for r in range(self.R) if not self.equality[r] and slack[r] <= tol),
                        key=lambda r: (slack[r], -abs(y[r])))
        tight = _independent([self._A_float[r, off_bound] for r in order], len(off_bound))
        rows = [order[k] for k in tight]
        if not rows:
            return (), ()
        sub = self._A_float[np.ix_(rows, off_bound)]
        basic = [off_bound[k] for k in _independent(list(sub.T), len(rows))]
        return tuple(sorted(basic)), tuple(sorted(rows))

    # -------------------------------------------------------- map back to Q
    def _reconstructions(self, cq, bq, nonneg, hint: Hint):
        """Candidate exact (x, y) pairs, cheapest first."""
        x, x_clean = _snapped(hint.x, _snap_tolerance(hint))
        y, y_clean = _snapped(hint.y, _snap_tolerance(hint))
        yield "float-rounded", x, y
        basis = self._basis_of(hint, bq, nonneg)
        pair = self._basis_solution(cq, bq, basis)
        if pair is not None:
            yield ("float-basis", *pair)
        pair = self._exact_pivots(cq, bq, nonneg, basis)
        if pair is not None:
            yield ("float-basis+pivots", *pair)

    def _exact_pivots(self, cq, bq, nonneg, basis, max_steps: int = 200):
        """Repair a float basis by exact simplex steps (active-set form, Bland's rule).

        A vertex is N active constraints W (tight rows and x_i = 0 bounds) with
        A_W x = b_W.  Multipliers mu solve A_W^T mu = c; if every inequality in W
        has mu >= 0 the vertex is optimal.  Otherwise leave the first such
        constraint a with mu_a < 0, move along d with A_W d = -e_a (c.d = -mu_a > 0)
        to the first constraint that becomes tight, and repeat.  Returns (x, y) or
        None (infeasible start, unboundedness, or too many steps)."""
        basic_cols, tight_rows = basis
        N, R = self.N, self.R
        basic = set(basic_cols)
        W = list(tight_rows) + [R + i for i in range(N) if nonneg[i] and i not in basic]
        if len(W) != N:
            return None
        A = self.A.entries()
        b = bq.entries()

        def row(k):
            if k < R:
                return A[k * N:(k + 1) * N]
            e = [flint.fmpq(0)] * N
            e[k - R] = flint.fmpq(-1)
            return e

        def rhs(k):
            return b[k] if k < R else flint.fmpq(0)

        candidates = [k for k in range(R) if not self.equality[k]] + [R + i for i in range(N) if nonneg[i]]
        try:
            M = flint.fmpq_mat(N, N, [v for k in W for v in row(k)])
            x = M.solve(flint.fmpq_mat(N, 1, [rhs(k) for k in W]))
            for _ in range(max_steps):
                mu = M.transpose().solve(cq)
                leaving = next((t for t, k in sorted(enumerate(W), key=lambda tk: tk[1])
                                if (k >= R or not self.equality[k]) and mu[t, 0] < 0), None)
                if leaving is None:
                    y = flint.fmpq_mat(R, 1)
                    for t, k in enumerate(W):
                        if k < R:
                            y[k, 0] = mu[t, 0]
                    return x, y
                e = flint.fmpq_mat(N, 1)
                e[leaving, 0] = -1
                d = M.solve(e)
                xs, ds = x.entries(), d.entries()
                best, entering = None, None
                active = set(W)
                for k in candidates:
                    if k in active:
                        continue
                    a = row(k)
                    rate = sum((ai * di for ai, di in zip(a, ds) if ai != 0 and di != 0), flint.fmpq(0))
                    if rate > 0:
                        step = (rhs(k) - sum((ai * xi for ai, xi in zip(a, xs) if ai != 0 and xi != 0), flint.fmpq(0))) / rate
                        if best is None or step < best:
                            best, entering = step, k
                if entering is None:
                    return None  # unbounded direction: leave it to the certificate routes
                x = x + d * best
                W[leaving] = entering
                M = flint.fmpq_mat(N, N, [v for k in W for v in row(k)])
        except (ZeroDivisionError, ValueError):
            return None
        return None

    def _basis_solution(self, cq, bq, basis) -> tuple[flint.fmpq_mat, flint.fmpq_mat] | None:
        """The exact vertex and dual of a float basis: B x_B = b_tight, B^T y = c_B."""
        basic_cols, tight_rows = basis
        if len(basic_cols) != len(tight_rows):
            return None
        A = self.A.entries()
        N = self.N
        Bmat = flint.fmpq_mat(len(tight_rows), len(basic_cols), [A[r * N + i] for r in tight_rows for i in basic_cols])
        b = bq.entries()
        c = cq.entries()
        try:
            xB = Bmat.solve(flint.fmpq_mat(len(tight_rows), 1, [b[r] for r in tight_rows]))
            yB = Bmat.transpose().solve(flint.fmpq_mat(len(basic_cols), 1, [c[i] for i in basic_cols]))
        except (ZeroDivisionError, ValueError):
            return None
        xq = flint.fmpq_mat(self.N, 1)
        for k, i in enumerate(basic_cols):
            xq[i, 0] = xB[k, 0]
        yq = flint.fmpq_mat(self.R, 1)
        for k, r in enumerate(tight_rows):
            yq[r, 0] = yB[k, 0]
        return xq, yq

    # --------------------------------------------------------- verification
    def _primal_feasible(self, bq, nonneg, x) -> bool:
        """A x (=|<=) b and the sign restrictions, by a sparse exact product."""
        Ax = [flint.fmpq(0)] * self.R
        for i, v in enumerate(x.entries()):
            if v != 0:
                if v < 0 and nonneg[i]:
                    return False
                for r, a in self._cols[i]:
                    Ax[r] += a * v
        for r, (lhs, rhs) in enumerate(zip(Ax, bq.entries())):
            if lhs > rhs or (self.equality[r] and lhs != rhs):
                return False
        return True

    def _dual_feasible(self, cq, nonneg, y) -> bool:
        """y_r >= 0 on inequality rows; A^T y - c >= 0 (nonnegative columns), = 0 (free)."""
        ATy = [flint.fmpq(0)] * self.N
        for r, v in enumerate(y.entries()):
            if v != 0:
                if v < 0 and not self.equality[r]:
                    return False
                for i, a in self._rows[r]:
                    ATy[i] += a * v
        for i, (lhs, c) in enumerate(zip(ATy, cq.entries())):
            if lhs < c or (not nonneg[i] and lhs != c):
                return False
        return True

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
        aux = ExactLPSolver(flint.fmpq_mat(rows), [not nonneg[i] for i in range(self.N)] + [False], self.hint_backend)
        res = aux.solve([-fraction_of(bq[r, 0]) for r in range(self.R)], [0] * self.N + [1], [not e for e in self.equality],
                        _bounded=True)
        if res.status != OPTIMAL:
            return None
        if not self._verify_farkas(bq, nonneg, res.x_q):
            return None
        return LPResult(INFEASIBLE, None, None, res.x_q, None, res.path)

    def _unbounded(self, cq, bq, nonneg) -> LPResult | None:
        """A feasible point (max 0 over the same set) and a ray (max c.d over the
        recession cone cut by c.d <= 1)."""
        point = self.solve(flint.fmpq_mat(self.N, 1), bq, nonneg, _bounded=True)
        if point.status != OPTIMAL:
            return None
        rows = [[self.A[r, i] for i in range(self.N)] for r in range(self.R)] + [[cq[i, 0] for i in range(self.N)]]
        cone = ExactLPSolver(flint.fmpq_mat(rows), list(self.equality) + [False], self.hint_backend)
        ray = cone.solve(cq, [0] * self.R + [1], nonneg, _bounded=True)
        if ray.status != OPTIMAL or not self._verify_ray(cq, nonneg, ray.x_q):
            return None
        return LPResult(UNBOUNDED, INF, point.x_q, None, ray.x_q, ray.path)

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
        else:
            certificate = self._certified_failure(status, cq, bq, nonneg)
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
    hint: str | HintBackend | None = None,
) -> LPResult:
    """Solve one LP exactly (see :class:`ExactLPSolver`; ``hint``: the float-hint backend)."""
    return ExactLPSolver(A, equality, hint).solve(c, b, nonnegative)


# ------------------------------------------------------------------ helpers
_SMALL_DENOMINATORS = (1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 12, 16, 24)


def _snap_tolerance(hint: Hint) -> float:
    """How close a float must be to a small-denominator fraction to be snapped:
    1e-9 for simplex hints (a basis: vertex values to machine accuracy), 1e-7
    for hints without one (interior-point solvers stop at ~1e-8)."""
    return 1e-9 if hint.basis is not None else 1e-7


def _snap(v: float, tol: float = 1e-9) -> flint.fmpq:
    """A simple fraction near the float hint v (only a hint: it is verified)."""
    for d in _SMALL_DENOMINATORS:
        scaled = v * d
        nearest = round(scaled)
        if abs(scaled - nearest) <= tol * max(1.0, abs(scaled)):
            return flint.fmpq(int(nearest), d)
    q = Fraction(v).limit_denominator(_ROUNDING_DENOMINATOR)
    return flint.fmpq(q.numerator, q.denominator)


def _snapped(values: np.ndarray, tol: float = 1e-9) -> tuple[flint.fmpq_mat, bool]:
    """The float hint as a column of simple fractions (exact zeros stay zero),
    and whether every entry was within ``tol`` (relative) of a fraction with a small
    denominator.  Only a hint: whatever it produces is verified."""
    out = flint.fmpq_mat(len(values), 1)
    idx = np.flatnonzero(values)
    v = values[idx]
    for d in _SMALL_DENOMINATORS:  # the common cases, vectorised
        if not len(idx):
            break
        scaled = v * d
        near = np.round(scaled)
        ok = np.abs(scaled - near) <= tol * np.maximum(1.0, np.abs(scaled))
        for i, num in zip(idx[ok].tolist(), near[ok].tolist()):
            if num:
                out[i, 0] = flint.fmpq(int(num), d)
        idx, v = idx[~ok], v[~ok]
    for i, value in zip(idx.tolist(), v.tolist()):
        out[i, 0] = _snap(value, tol)
    return out, not len(idx)


def _independent(vectors: list[np.ndarray], limit: int) -> list[int]:
    """Indices of a greedy linearly independent subset (in order, at most
    ``limit``), by float Gram-Schmidt with one re-orthogonalisation."""
    chosen: list[int] = []
    if not vectors or limit <= 0:
        return chosen
    Q = np.zeros((min(limit, len(vectors[0])), len(vectors[0])))
    for k, a in enumerate(vectors):
        if len(chosen) >= min(limit, len(Q)):
            break
        norm = float(np.linalg.norm(a))
        if norm == 0:
            continue
        q = Q[:len(chosen)]
        r = np.asarray(a, dtype=float)
        r = r - q.T @ (q @ r)
        r = r - q.T @ (q @ r)
        rnorm = float(np.linalg.norm(r))
        if rnorm > 1e-9 * norm:
            Q[len(chosen)] = r / rnorm
            chosen.append(k)
    return chosen


def _column(v) -> flint.fmpq_mat:
    if isinstance(v, flint.fmpq_mat):
        return v
    entries = [flint.fmpq(x.numerator, x.denominator) if isinstance(x, Fraction) else flint.fmpq(x) for x in v]
    return flint.fmpq_mat(len(entries), 1, entries)


def _dot(u: flint.fmpq_mat, v: flint.fmpq_mat) -> flint.fmpq:
    return (u.transpose() * v)[0, 0]


def _floats(values) -> np.ndarray | None:
    """The float images of exact values, or None if one overflows a double
    (the float hint is then skipped and the exact route taken)."""
    try:
        return np.array([float(v) for v in values], dtype=float)
    except OverflowError:
        return None


def _columns_of(M: flint.fmpq_mat) -> list[flint.fmpq_mat]:
    rows, K = M.nrows(), M.ncols()
    T = M.transpose().entries()
    return [flint.fmpq_mat(rows, 1, T[k * rows:(k + 1) * rows]) for k in range(K)]


def _fractions(M: flint.fmpq_mat) -> tuple[Fraction, ...]:
    zero = Fraction(0)
    return tuple(zero if v == 0 else fraction_of(v) for v in M.entries())


def _optimal(cq, x, y, path) -> LPResult:
    return LPResult(OPTIMAL, fraction_of(_dot(cq, x)), x, y, None, path)


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
