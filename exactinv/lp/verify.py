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
from itertools import chain
from operator import mul
from typing import Sequence

import flint

__all__ = ["LPData", "optimal_mask", "verify_optimal", "verify_farkas", "verify_ray", "dot"]


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
    def eq_rows(self) -> tuple[int, ...]:
        return tuple(r for r, e in enumerate(self.equality) if e)

    @cached_property
    def le_rows(self) -> tuple[int, ...]:
        return tuple(r for r, e in enumerate(self.equality) if not e)

    @cached_property
    def _A_eq(self) -> flint.fmpq_mat:
        return _select_rows(self.A, self.eq_rows)

    @cached_property
    def _A_le(self) -> flint.fmpq_mat:
        return _select_rows(self.A, self.le_rows)


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
    ok = [p and d for p, d in zip(primal_mask(data, B, signs, X), dual_mask(data, C, signs, Y))]
    K = len(ok)
    for k, cx, by in zip(range(K), _column_dots(C, X), _column_dots(B, Y)):
        ok[k] = ok[k] and cx == by
    return ok


def primal_mask(data: LPData, B: flint.fmpq_mat, signs: Sequence[Sequence[bool]], X: flint.fmpq_mat) -> list[bool]:
    """Column k of X satisfies A x (= | <=) (column k of B) and the sign
    restrictions ``signs[k]``.

    >>> data = LPData(flint.fmpq_mat([[1, 1]]), (True,))
    >>> primal_mask(data, flint.fmpq_mat([[2, 2]]), [(True, True), (True, True)], flint.fmpq_mat([[1, 3], [1, -1]]))
    [True, False]
    """
    ok = _signs_ok(X, [[not s for s in sk] for sk in signs])
    if data.eq_rows:
        slack = _select_rows(B, data.eq_rows) - data._A_eq * X
        ok = [o and not any(col) for o, col in zip(ok, _columns(slack))]
    if data.le_rows:
        slack = _select_rows(B, data.le_rows) - data._A_le * X
        ok = [o and min(col) >= 0 for o, col in zip(ok, _columns(slack))]
    return ok


def dual_mask(data: LPData, C: flint.fmpq_mat, signs: Sequence[Sequence[bool]], Y: flint.fmpq_mat) -> list[bool]:
    """Column k of Y is >= 0 on inequality rows and A^T y - (column k of C)
    is >= 0 on nonnegative columns and = 0 on free ones.

    >>> data = LPData(flint.fmpq_mat([[1], [-1]]), (False, False))
    >>> dual_mask(data, flint.fmpq_mat([[0, 0]]), [(False,), (True,)], flint.fmpq_mat([[1, 2], [1, 1]]))
    [True, True]
    >>> dual_mask(data, flint.fmpq_mat([[0]]), [(False,)], flint.fmpq_mat([[2], [1]]))
    [False]
    """
    K = Y.ncols()
    ok = _signs_ok(Y, [data.equality] * K)
    reduced = data.AT * Y - C
    for k, col in enumerate(_columns(reduced)):
        ok[k] = ok[k] and (not col or min(col) >= 0) and not any(col[i] for i, s in enumerate(signs[k]) if not s)
    return ok


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
def _select_rows(M: flint.fmpq_mat, rows: Sequence[int]) -> flint.fmpq_mat:
    K = M.ncols()
    if len(rows) == M.nrows():
        return M
    E = M.entries()
    return flint.fmpq_mat(len(rows), K, list(chain.from_iterable(E[r * K:(r + 1) * K] for r in rows)))


def _columns(M: flint.fmpq_mat) -> list[list[flint.fmpq]]:
    """The columns of M as lists (one transpose, then C-level slices)."""
    R, K = M.nrows(), M.ncols()
    T = M.transpose().entries()
    return [T[k * R:(k + 1) * R] for k in range(K)]


def _signs_ok(M: flint.fmpq_mat, free: Sequence[Sequence[bool]]) -> list[bool]:
    """Column k of M is >= 0 wherever ``free[k][i]`` is false."""
    ok = []
    for k, col in enumerate(_columns(M)):
        ok.append(not col or min(col) >= 0 or all(free[k][i] for i, v in enumerate(col) if v < 0))
    return ok


def _column_dots(U: flint.fmpq_mat, V: flint.fmpq_mat) -> list[flint.fmpq]:
    zero = flint.fmpq(0)
    return [sum(map(mul, u, v), zero) for u, v in zip(_columns(U), _columns(V))]
