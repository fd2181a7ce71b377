"""Step 3 of the exact LP engine: verification in Q (the only step that is trusted).

For the LP ::

    maximize  c.x   subject to   a_r.x (= | <=) b_r,   x_i >= 0 (i nonnegative)

a pair (x, y) is proved optimal by three exact facts (LP duality):

* primal feasibility -- A x (= | <=) b row by row, and x_i >= 0 on nonnegative columns;
* dual feasibility   -- y_r >= 0 on inequality rows, (A^T y - c)_i >= 0 on
  nonnegative columns and = 0 on free ones;
* equal objectives   -- c.x = b.y.

A Farkas vector y (dual feasible for c = 0 with b.y < 0) proves the LP
infeasible; a ray d (primal feasible for b = 0 with c.d > 0) together with a
feasible point proves it unbounded.

There is ONE implementation, batched: K LPs sharing A are checked by two FLINT
matrix products (A X and A^T Y for the N x K and R x K columns); a single LP is
the batch K = 1.  Exact: every comparison is between fmpq values, no tolerance.
"""

from __future__ import annotations

from dataclasses import dataclass
from functools import cached_property
from operator import mul
from typing import Sequence

import flint
import numpy as np

__all__ = ["LPData", "optimal_mask", "optimal_values", "primal_mask", "dual_mask", "verify_optimal", "verify_farkas",
           "verify_ray", "dot"]


@dataclass(frozen=True, eq=False)
class LPData:
    """The exact constraint data shared by a family of LPs: the R x N matrix
    ``A`` and ``equality[r]`` (row r an equation, else ``<=``).

    >>> data = LPData(flint.fmpq_mat([[1, 1], [1, -1]]), (True, False))
    >>> data.R, data.N, data.eq_rows, data.le_rows
    (2, 2, (0,), (1,))
    """

    A: flint.fmpq_mat
    equality: tuple[bool, ...]

    @property
    def R(self) -> int:
        return self.A.nrows()

    @property
    def N(self) -> int:
        return self.A.ncols()

    @cached_property
    def AT(self) -> flint.fmpq_mat:
        return self.A.transpose()

    @cached_property
    def entries(self) -> list[flint.fmpq]:
        """The entries of A, row by row (read out of FLINT once per family).

        >>> LPData(flint.fmpq_mat([[1, 2], [3, 4]]), (False, False)).entries
        [1, 2, 3, 4]
        """
        return self.A.entries()

    @cached_property
    def eq_rows(self) -> tuple[int, ...]:
        return tuple(r for r, e in enumerate(self.equality) if e)

    @cached_property
    def le_rows(self) -> tuple[int, ...]:
        return tuple(r for r, e in enumerate(self.equality) if not e)

    def eq_part(self, M: flint.fmpq_mat) -> flint.fmpq_mat:
        """The equality rows of an R-row matrix M.

        >>> data = LPData(flint.fmpq_mat([[1, 2], [3, 4]]), (False, True))
        >>> data.eq_part(flint.fmpq_mat([[5], [6]])).entries()
        [6]
        """
        return M if len(self.eq_rows) == self.R else self._select_eq * M

    def le_part(self, M: flint.fmpq_mat) -> flint.fmpq_mat:
        """The inequality rows of an R-row matrix M.

        >>> data = LPData(flint.fmpq_mat([[1, 2], [3, 4]]), (False, True))
        >>> data.le_part(data.A).entries()
        [1, 2]
        """
        return M if len(self.le_rows) == self.R else self._select_le * M

    @cached_property
    def _select_eq(self) -> flint.fmpq_mat:
        return _selection(self.eq_rows, self.R)

    @cached_property
    def _select_le(self) -> flint.fmpq_mat:
        return _selection(self.le_rows, self.R)

    @cached_property
    def _A_eq(self) -> flint.fmpq_mat:
        return self.eq_part(self.A)

    @cached_property
    def _A_le(self) -> flint.fmpq_mat:
        return self.le_part(self.A)


def dot(u: flint.fmpq_mat, v: flint.fmpq_mat) -> flint.fmpq:
    """The exact inner product of two columns.

    >>> dot(flint.fmpq_mat(2, 1, [1, flint.fmpq(1, 3)]), flint.fmpq_mat(2, 1, [2, 3]))
    3
    """
    return sum(map(mul, u.entries(), v.entries()), flint.fmpq(0))


def optimal_mask(data: LPData, C: flint.fmpq_mat, B: flint.fmpq_mat, signs: Sequence[Sequence[bool]],
                 X: flint.fmpq_mat, Y: flint.fmpq_mat) -> list[bool]:
    """For K LPs (cost column k of C, right-hand side column k of B, sign
    pattern ``signs[k]``): whether (column k of X, column k of Y) is a proved
    optimal primal-dual pair.  Exact.

    >>> data = LPData(flint.fmpq_mat([[3, 1], [1, 3]]), (False, False))
    >>> col = lambda *v: flint.fmpq_mat(len(v), 1, [flint.fmpq(*t) for t in v])
    >>> optimal_mask(data, col((1,), (1,)), col((1,), (1,)), [(True, True)], col((1, 4), (1, 4)), col((1, 4), (1, 4)))
    [True]
    >>> optimal_mask(data, col((1,), (1,)), col((1,), (1,)), [(True, True)], col((1, 4), (1, 5)), col((1, 4), (1, 4)))
    [False]
    """
    return [v is not None for v in optimal_values(data, C, B, signs, X, Y)]


def optimal_values(data: LPData, C: flint.fmpq_mat, B: flint.fmpq_mat, signs: Sequence[Sequence[bool]],
                   X: flint.fmpq_mat, Y: flint.fmpq_mat) -> list[flint.fmpq | None]:
    """As :func:`optimal_mask`, with the proved optimum c.x = b.y of each LP (None: not proved).

    >>> data = LPData(flint.fmpq_mat([[1], [-1]]), (False, False))
    >>> optimal_values(data, flint.fmpq_mat([[1, 1]]), flint.fmpq_mat([[2, 2], [0, 0]]), [(False,)] * 2,
    ...                flint.fmpq_mat([[2, 1]]), flint.fmpq_mat([[1, 1], [0, 0]]))
    [2, None]
    """
    free = _free_indices(signs)
    X_cols, Y_cols = _IntColumns(X), _IntColumns(Y)
    ok = [p and d for p, d in zip(_primal_ok(data, B, free, X, X_cols), _dual_ok(data, C, free, Y, Y_cols))]
    values = []
    for k, cx, by in zip(range(len(ok)), _IntColumns(C).dots(X_cols), _IntColumns(B).dots(Y_cols)):
        values.append(cx if ok[k] and cx == by else None)
    return values


def primal_mask(data: LPData, B: flint.fmpq_mat, signs: Sequence[Sequence[bool]], X: flint.fmpq_mat) -> list[bool]:
    """Column k of X satisfies A x (= | <=) (column k of B) and the sign
    restrictions ``signs[k]``.

    >>> data = LPData(flint.fmpq_mat([[1, 1]]), (True,))
    >>> primal_mask(data, flint.fmpq_mat([[2, 2]]), [(True, True), (True, True)], flint.fmpq_mat([[1, 3], [1, -1]]))
    [True, False]
    """
    return _primal_ok(data, B, _free_indices(signs), X, _IntColumns(X))


def dual_mask(data: LPData, C: flint.fmpq_mat, signs: Sequence[Sequence[bool]], Y: flint.fmpq_mat) -> list[bool]:
    """Column k of Y is >= 0 on inequality rows and A^T y - (column k of C)
    is >= 0 on nonnegative columns and = 0 on free ones.

    >>> data = LPData(flint.fmpq_mat([[1], [-1]]), (False, False))
    >>> dual_mask(data, flint.fmpq_mat([[0, 0]]), [(False,), (True,)], flint.fmpq_mat([[1, 2], [1, 1]]))
    [True, True]
    >>> dual_mask(data, flint.fmpq_mat([[0]]), [(False,)], flint.fmpq_mat([[2], [1]]))
    [False]
    """
    return _dual_ok(data, C, _free_indices(signs), Y, _IntColumns(Y))


def verify_optimal(data: LPData, c: flint.fmpq_mat, b: flint.fmpq_mat, nonneg: Sequence[bool],
                   x: flint.fmpq_mat, y: flint.fmpq_mat) -> bool:
    """(x, y) is a proved optimal pair of one LP (the batch K = 1 of :func:`optimal_mask`).

    >>> data = LPData(flint.fmpq_mat([[1]]), (False,))
    >>> one = flint.fmpq_mat([[1]])
    >>> verify_optimal(data, one, one, (True,), one, one), verify_optimal(data, one, one, (True,), one, one * 2)
    (True, False)
    """
    return optimal_mask(data, c, b, [nonneg], x, y)[0]


def verify_farkas(data: LPData, b: flint.fmpq_mat, nonneg: Sequence[bool], y: flint.fmpq_mat) -> bool:
    """y proves {x : A x (= | <=) b, x_i >= 0 (nonneg)} empty: y is dual
    feasible for the cost 0 and b.y < 0 (Farkas' lemma).

    >>> data = LPData(flint.fmpq_mat([[1], [-1]]), (False, False))   # x <= 0 and -x <= -1
    >>> verify_farkas(data, flint.fmpq_mat([[0], [-1]]), (False,), flint.fmpq_mat([[1], [1]]))
    True
    """
    zero = flint.fmpq_mat(data.N, 1)
    return dual_mask(data, zero, [nonneg], y)[0] and dot(b, y) < 0


def verify_ray(data: LPData, c: flint.fmpq_mat, nonneg: Sequence[bool], d: flint.fmpq_mat) -> bool:
    """d is a direction of unbounded increase: A d (= | <=) 0, the sign
    restrictions, and c.d > 0.

    >>> data = LPData(flint.fmpq_mat([[1, -1]]), (False,))
    >>> verify_ray(data, flint.fmpq_mat([[1], [1]]), (True, True), flint.fmpq_mat([[1], [1]]))
    True
    """
    zero = flint.fmpq_mat(data.R, 1)
    return primal_mask(data, zero, [nonneg], d)[0] and dot(c, d) > 0


# ------------------------------------------------------------------ helpers
class _IntColumns:
    """The columns of an fmpq matrix M as integer numerators, column k over
    its own denominator d_k > 0 (so every sign and zero test is on fmpz
    values, ten times faster than on fmpq ones, and exact: M_ik = cols[k][i] / d_k;
    per column, because one common denominator of many basis solutions can
    have thousands of digits)."""

    def __init__(self, M: flint.fmpq_mat):
        R, K = M.nrows(), M.ncols()
        T = M.transpose().entries()
        self.cols, self.ds = [], []
        for k in range(K):
            numerators, d = flint.fmpq_mat(R, 1, T[k * R:(k + 1) * R]).numer_denom()
            self.cols.append(numerators.entries())
            self.ds.append(d)

    def nonnegative(self, rows: Sequence[int] | None = None) -> list[bool]:
        """Per column: entries >= 0 (all entries, or those in ``rows``)."""
        zero = flint.fmpz(0)
        if rows is None:
            return [not col or min(col) >= zero for col in self.cols]
        if len(rows) and rows[-1] - rows[0] == len(rows) - 1:  # consecutive rows: one slice
            return [min(col[rows[0]:rows[-1] + 1]) >= zero for col in self.cols]
        return [all(col[i] >= zero for i in rows) for col in self.cols]

    def dots(self, other: _IntColumns) -> list[flint.fmpq]:
        """Per column k: the inner product of column k here and in ``other``."""
        zero = flint.fmpz(0)
        return [flint.fmpq(sum(map(mul, u, v), zero), d * e)
                for u, v, d, e in zip(self.cols, other.cols, self.ds, other.ds)]


def _primal_ok(data: LPData, B: flint.fmpq_mat, free: list[list[int]], X: flint.fmpq_mat,
               X_cols: _IntColumns) -> list[bool]:
    ok = [_nonnegative_except(col, f) for col, f in zip(X_cols.cols, free)]
    if data.eq_rows:
        slack = data.eq_part(B) - data._A_eq * X
        if slack != flint.fmpq_mat(slack.nrows(), slack.ncols()):  # all zero: decided in C
            ok = [o and not any(col) for o, col in zip(ok, _IntColumns(slack).cols)]
    if data.le_rows:
        slack = data.le_part(B) - data._A_le * X
        ok = [o and n for o, n in zip(ok, _IntColumns(slack).nonnegative())]
    return ok


def _dual_ok(data: LPData, C: flint.fmpq_mat, free: list[list[int]], Y: flint.fmpq_mat,
             Y_cols: _IntColumns) -> list[bool]:
    ok = Y_cols.nonnegative(data.le_rows)
    reduced = _IntColumns(data.AT * Y - C)
    for k, (col, nonneg) in enumerate(zip(reduced.cols, reduced.nonnegative())):
        ok[k] = ok[k] and nonneg and not any(col[i] for i in free[k])
    return ok


def _nonnegative_except(col: list[flint.fmpz], free: list[int]) -> bool:
    """col >= 0 except at the indices ``free``."""
    zero = flint.fmpz(0)
    if free:
        col = list(col)
        for i in free:
            col[i] = zero
    return not col or min(col) >= zero


def _selection(rows: Sequence[int], R: int) -> flint.fmpq_mat:
    """The 0/1 matrix S with S M = the rows ``rows`` of M (a product in C, no Python objects per entry)."""
    S = flint.fmpq_mat(len(rows), R)
    for t, r in enumerate(rows):
        S[t, r] = 1
    return S


def _free_indices(signs: Sequence[Sequence[bool]]) -> list[list[int]]:
    """For each sign pattern, the indices of its free (False) entries."""
    if not signs or not len(signs[0]):
        return [[] for _ in signs]
    mask = ~np.array(signs, dtype=bool)
    rows, cols = np.nonzero(mask)
    out: list[list[int]] = [[] for _ in signs]
    for k, i in zip(rows.tolist(), cols.tolist()):
        out[k].append(i)
    return out
