"""Step 2 of the exact LP engine: map an untrusted float hint back to Q.

Three reconstructions, cheapest first (each only proposes; :mod:`exactinv.lp.verify` decides):

* :func:`snapped` -- round every float to a nearby simple fraction
  (``path="float-rounded"``);
* :func:`basis_solution` -- solve the hint's optimal basis exactly,
  B x_B = b_tight and B^T y = c_B, with FLINT (``path="float-basis"``);
  backends without a basis get one guessed from the float point
  (:func:`guess_basis`);
* :func:`exact_pivots` -- repair a wrong basis by exact simplex steps
  (``path="float-basis+pivots"``).
"""

from __future__ import annotations

from fractions import Fraction
from typing import Sequence

import flint
import numpy as np

from .hint_types import Basis
from .verify import LPData

__all__ = ["Basis", "COMMON_DENOMINATOR", "snap", "snapped", "snapped_numerators", "snap_tolerance", "guess_basis",
           "basis_solution", "exact_pivots"]

ROUNDING_DENOMINATOR = 1 << 24
_SMALL_DENOMINATORS = (1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 12, 16, 24)
COMMON_DENOMINATOR = 5040  # lcm of the small denominators: each p/d is (p * 5040/d) / 5040


def snap_tolerance(has_basis: bool) -> float:
    """How close a float must be to a small-denominator fraction to be snapped:
    1e-9 for simplex hints (a basis: vertex values to machine accuracy), 1e-7
    for hints without one (interior-point solvers stop at ~1e-8).

    >>> snap_tolerance(True), snap_tolerance(False)
    (1e-09, 1e-07)
    """
    return 1e-9 if has_basis else 1e-7


def snap(v: float, tol: float = 1e-9) -> flint.fmpq:
    """A simple fraction near the float v (only a hint: it is verified).

    >>> snap(1 / 3), snap(0.1 + 0.2), snap(0.25 + 1e-6)
    (1/3, 3/10, 250001/1000000)
    """
    for d in _SMALL_DENOMINATORS:
        scaled = v * d
        nearest = round(scaled)
        if abs(scaled - nearest) <= tol * max(1.0, abs(scaled)):
            return flint.fmpq(int(nearest), d)
    q = Fraction(v).limit_denominator(ROUNDING_DENOMINATOR)
    return flint.fmpq(q.numerator, q.denominator)


def snapped(values: np.ndarray, tol: float = 1e-9) -> tuple[list[flint.fmpq], bool]:
    """The floats as simple fractions (exact zeros stay zero), and whether
    every entry was within ``tol`` (relative) of a fraction with a small
    denominator.  Vectorised over the common denominators.  Only a hint.

    >>> snapped(np.array([0.25, 0.0, 2 / 3, 1e-3]))
    ([1/4, 0, 2/3, 1/1000], False)
    >>> snapped(np.array([0.5, -7.0]))
    ([1/2, -7], True)
    """
    out = [flint.fmpq(0)] * len(values)
    idx = np.flatnonzero(values)
    v = values[idx]
    for d in _SMALL_DENOMINATORS:
        if not len(idx):
            break
        scaled = v * d
        near = np.round(scaled)
        ok = np.abs(scaled - near) <= tol * np.maximum(1.0, np.abs(scaled))
        for i, num in zip(idx[ok].tolist(), near[ok].tolist()):
            if num:
                out[i] = flint.fmpq(int(num), d)
        idx, v = idx[~ok], v[~ok]
    for i, value in zip(idx.tolist(), v.tolist()):
        out[i] = snap(value, tol)
    return out, not len(idx)


def snapped_numerators(values: np.ndarray, tol: float = 1e-9) -> list[int] | None:
    """The floats as integer numerators over ``COMMON_DENOMINATOR`` = 5040 (a
    multiple of every small denominator: 1..10, 12, 16, 24, ...), so that one
    FLINT matrix holds a whole batch with no Python object per entry; None if
    an entry is not within ``tol`` (relative) of such a fraction.  One
    vectorised pass; exact: every numerator is an integer-valued double < 2^53.

    >>> snapped_numerators(np.array([0.25, 0.0, 2 / 3, -7.0]))
    [1260, 0, 3360, -35280]
    >>> snapped_numerators(np.array([1e-3])) is None
    True
    """
    scaled = values * COMMON_DENOMINATOR
    near = np.round(scaled)
    if not np.all(np.abs(scaled - near) <= tol * np.maximum(1.0, np.abs(scaled))):
        return None
    if len(near) and np.abs(near).max() >= 2.0 ** 53:
        return None
    return near.astype(np.int64).tolist()


def guess_basis(A: np.ndarray, equality: Sequence[bool], rhs: np.ndarray, x: np.ndarray, y: np.ndarray,
                nonneg: Sequence[bool]) -> Basis:
    """A basis guessed from a float point (backends without bases, e.g.
    interior-point solvers through cvxpy).

    Columns at their bound (x_i ~ 0, nonnegative) are nonbasic; tight rows
    are picked greedily -- equality rows, then inequality rows by increasing
    slack (ties: larger dual first) -- while independent on the other
    columns; of those columns, as many as tight rows are kept basic (free
    columns first, then larger |x_i|).  A guess only: it is solved and verified.

    >>> A = np.array([[1.0, 1.0], [1.0, -1.0], [-1.0, 0.0]])
    >>> guess_basis(A, [False] * 3, np.array([2.0, 0.0, 0.0]), np.array([1.0, 1.0]), np.zeros(3), [False, False])
    ((0, 1), (0, 1))
    """
    R, N = A.shape
    scale = max(1.0, float(np.abs(x).max()) if len(x) else 1.0)
    slack = (rhs - A @ x) / scale
    tol = 1e-7
    off_bound = sorted((i for i in range(N) if not nonneg[i] or abs(x[i]) > tol * scale),
                       key=lambda i: (nonneg[i], -abs(x[i])))
    order = [r for r in range(R) if equality[r]]
    order += sorted((r for r in range(R) if not equality[r] and slack[r] <= tol), key=lambda r: (slack[r], -abs(y[r])))
    rows = [order[k] for k in _independent([A[r, off_bound] for r in order], len(off_bound))]
    if not rows:
        return (), ()
    basic = [off_bound[k] for k in _independent(list(A[np.ix_(rows, off_bound)].T), len(rows))]
    return tuple(sorted(basic)), tuple(sorted(rows))


def basis_solution(data: LPData, c: flint.fmpq_mat, b: flint.fmpq_mat,
                   basis: Basis) -> tuple[flint.fmpq_mat, flint.fmpq_mat] | None:
    """The exact vertex and dual of a basis: B x_B = b_tight, B^T y_tight = c_B
    (other entries 0); None if B is not square and invertible.

    >>> data = LPData(flint.fmpq_mat([[7, 3], [2, 9]]), (False, False))
    >>> x, y = basis_solution(data, flint.fmpq_mat([[1], [1]]), flint.fmpq_mat([[1], [1]]), ((0, 1), (0, 1)))
    >>> x.entries(), y.entries()
    ([2/19, 5/57], [7/57, 4/57])
    """
    cols, rows = basis
    if len(cols) != len(rows):
        return None
    A, N = data.entries, data.N
    B = flint.fmpq_mat(len(rows), len(cols), [A[r * N + i] for r in rows for i in cols])
    try:
        xB = B.solve(flint.fmpq_mat(len(rows), 1, [b[r, 0] for r in rows]))
        yB = B.transpose().solve(flint.fmpq_mat(len(cols), 1, [c[i, 0] for i in cols]))
    except (ZeroDivisionError, ValueError):
        return None
    return _scatter(xB, cols, N), _scatter(yB, rows, data.R)


def exact_pivots(data: LPData, c: flint.fmpq_mat, b: flint.fmpq_mat, nonneg: Sequence[bool], basis: Basis,
                 max_steps: int = 200) -> tuple[flint.fmpq_mat, flint.fmpq_mat] | None:
    """Repair a basis by exact simplex steps (active-set form, Bland's rule).

    A vertex is N active constraints W (tight rows, x_i = 0 bounds), A_W x = b_W;
    A_W^T mu = c.  If mu >= 0 on W's inequalities the vertex is optimal; else
    leave the first a with mu_a < 0, move along A_W d = -e_a (c.d = -mu_a > 0)
    to the first constraint that becomes tight, and repeat.  (x, y), or None
    (a singular start, unboundedness, more than ``max_steps`` steps).

    >>> data = LPData(flint.fmpq_mat([[1, 1], [1, -1], [-1, 0], [0, -1]]), (False,) * 4)
    >>> col = lambda *v: flint.fmpq_mat(len(v), 1, list(v))
    >>> x, y = exact_pivots(data, col(1, 2), col(4, 1, 0, 0), (False, False), ((0, 1), (1, 3)))
    >>> x.entries(), y.entries()   # from the vertex (1, 0) to the optimum (0, 4)
    ([0, 4], [2, 0, 1, 0])
    """
    W = _active_set(data, nonneg, basis)
    if W is None:
        return None
    act = _Active(data, b)
    candidates = list(data.le_rows) + [data.R + i for i in range(data.N) if nonneg[i]]
    try:
        M = act.matrix(W)
        x = M.solve(act.rhs(W))
        for _ in range(max_steps):
            mu = M.transpose().solve(c)
            leaving = _leaving(data, W, mu)
            if leaving is None:
                return x, _scatter(mu, W, data.R)
            e = flint.fmpq_mat(data.N, 1)
            e[leaving, 0] = -1
            d = M.solve(e)
            entering, step = act.ratio_test([k for k in candidates if k not in set(W)], x, d)
            if entering is None:
                return None  # an unbounded direction: left to the certificate routes
            x, W[leaving] = x + d * step, entering
            M = act.matrix(W)
    except (ZeroDivisionError, ValueError):
        return None
    return None


# ------------------------------------------------------------------ helpers
class _Active:
    """Constraint k of an LP in active-set form: row k of A (k < R) or the
    bound -x_{k-R} <= 0 (k >= R), with its right-hand side."""

    def __init__(self, data: LPData, b: flint.fmpq_mat):
        self.N, self.R = data.N, data.R
        self.A, self.b = data.entries, b.entries()

    def row(self, k: int) -> list[flint.fmpq]:
        if k < self.R:
            return self.A[k * self.N:(k + 1) * self.N]
        e = [flint.fmpq(0)] * self.N
        e[k - self.R] = flint.fmpq(-1)
        return e

    def rhs_of(self, k: int) -> flint.fmpq:
        return self.b[k] if k < self.R else flint.fmpq(0)

    def matrix(self, W: Sequence[int]) -> flint.fmpq_mat:
        return flint.fmpq_mat(len(W), self.N, [v for k in W for v in self.row(k)])

    def rhs(self, W: Sequence[int]) -> flint.fmpq_mat:
        return flint.fmpq_mat(len(W), 1, [self.rhs_of(k) for k in W])

    def ratio_test(self, candidates: Sequence[int], x: flint.fmpq_mat, d: flint.fmpq_mat):
        """The first constraint to become tight along x + t d (t > 0), and t."""
        xs, ds = x.entries(), d.entries()
        best, entering = None, None
        for k in candidates:
            a = self.row(k)
            rate = sum((ai * di for ai, di in zip(a, ds) if ai != 0 and di != 0), flint.fmpq(0))
            if rate > 0:
                step = (self.rhs_of(k) - sum((ai * xi for ai, xi in zip(a, xs) if ai != 0 and xi != 0),
                                             flint.fmpq(0))) / rate
                if best is None or step < best:
                    best, entering = step, k
        return entering, best


def _leaving(data: LPData, W: Sequence[int], mu: flint.fmpq_mat) -> int | None:
    """Bland's rule: the position in W of the lowest-numbered inequality with mu < 0 (None: optimal)."""
    return next((t for t, k in sorted(enumerate(W), key=lambda tk: tk[1])
                 if (k >= data.R or not data.equality[k]) and mu[t, 0] < 0), None)


def _active_set(data: LPData, nonneg: Sequence[bool], basis: Basis) -> list[int] | None:
    basic_cols, tight_rows = basis
    basic = set(basic_cols)
    W = list(tight_rows) + [data.R + i for i in range(data.N) if nonneg[i] and i not in basic]
    return W if len(W) == data.N else None


def _scatter(values: flint.fmpq_mat, where: Sequence[int], length: int) -> flint.fmpq_mat:
    """The column of ``length`` with values[t] at where[t] (where[t] < length), 0 elsewhere."""
    out = flint.fmpq_mat(length, 1)
    for t, i in enumerate(where):
        if i < length:
            out[i, 0] = values[t, 0]
    return out


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
