"""The optimal-gain LP: min gamma over (H, F, gamma, Lambda), one LP (docs/design.md, "Control: the optimal gain").

For x' = (A + BF)x and P = {x : Gx <= b} the invariance conditions of the
paper, H off-diagonal >= 0, HG = G(A + BF), Hb <= 0, are linear in (H, F)
jointly; so are the input constraints Fx in U = {u : Eu <= e} for every x in P
(Lambda >= 0, Lambda G = EF, Lambda b <= e: Farkas' lemma row by row).  As an
LP of :mod:`exactinv.lp` (maximize c.x, rows ``=`` or ``<=``)::

    maximize  -gamma
    (1)  HG - (GB)F         = GA     m x n equations        dual Y (m x n, free)
    (2)  Hb                 <= 0     m rows                 dual mu >= 0
    (3)  -H_ii - gamma      <= 0     m rows                 dual nu >= 0
    (4)  Lambda G - EF      = 0      q x n equations        dual Z (q x n, free)
    (5)  Lambda b           <= e     q rows                 dual w >= 0
    H_ij >= 0 (i != j), Lambda >= 0; H_ii, F, gamma free.

Its dual (the optimality certificate; a Farkas certificate is the same with
nu = 0 and a negative objective)::

    minimize  <GA, Y> + e.w   subject to
    (Y G^T)_ij + mu_i b_j >= 0   (i != j)      (Y G^T)_ii + mu_i b_i = nu_i
    (GB)^T Y + E^T Z = 0                        sum_i nu_i = 1
    (Z G^T)_jk + w_j b_k >= 0                   mu, nu, w >= 0.

This module only lays out the LP and reads its solution; the exact engine
(:func:`exactinv.lp.solve_lp`: float hint, exact basis, verification in Q)
solves it.
"""

from __future__ import annotations

from dataclasses import dataclass
from fractions import Fraction
from typing import Sequence

import flint

from ..core.scalars import Matrix

__all__ = ["GainLP", "gain_lp"]


@dataclass(frozen=True)
class GainLP:
    """The LP's layout: sizes m (rows of G), n (states), p (inputs), q (rows of E),
    and the exact data ``A_lp`` (R x N), ``equality``, ``rhs``, ``cost``, ``nonnegative``.

    >>> lp = gain_lp([[0]], [[1]], [[1], [-1]], [1, 1])
    >>> lp.N, lp.R, lp.gamma_index
    (6, 6, 5)
    """

    m: int
    n: int
    p: int
    q: int
    A_lp: flint.fmpq_mat
    equality: tuple[bool, ...]
    rhs: tuple[Fraction, ...]
    cost: tuple[Fraction, ...]
    nonnegative: tuple[bool, ...]

    @property
    def N(self) -> int:
        return self.A_lp.ncols()

    @property
    def R(self) -> int:
        return self.A_lp.nrows()

    @property
    def gamma_index(self) -> int:
        return self.m * self.m + self.p * self.n

    def primal(self, x: Sequence[Fraction]) -> tuple[Matrix, Matrix, Fraction, Matrix]:
        """(H, F, gamma, Lambda) from an LP point.

        >>> lp = gain_lp([[0]], [[1]], [[1], [-1]], [1, 1])
        >>> lp.primal([1, 2, 3, 4, 5, 6])
        (((1, 2), (3, 4)), ((5,),), 6, ())
        """
        m, n, p, q = self.m, self.n, self.p, self.q
        H = _block(x, 0, m, m)
        F = _block(x, m * m, p, n)
        g = self.gamma_index
        return H, F, x[g], _block(x, g + 1, q, m)

    def dual(self, y: Sequence[Fraction]) -> dict:
        """The dual's parts {Y, mu, nu, Z, w} from an LP dual vector (rows in the order (1)-(5)).

        >>> gain_lp([[0]], [[1]], [[1], [-1]], [1, 1]).dual([1, 2, 3, 4, 5, 6])
        {'Y': ((1,), (2,)), 'mu': (3, 4), 'nu': (5, 6), 'Z': (), 'w': ()}
        """
        m, n, q = self.m, self.n, self.q
        s = m * n
        return {"Y": _block(y, 0, m, n), "mu": tuple(y[s:s + m]), "nu": tuple(y[s + m:s + 2 * m]),
                "Z": _block(y, s + 2 * m, q, n), "w": tuple(y[s + 2 * m + q * n:s + 2 * m + q * n + q])}


def _q(v) -> flint.fmpq:
    v = Fraction(v)
    return flint.fmpq(v.numerator, v.denominator)


def _block(v: Sequence[Fraction], start: int, rows: int, cols: int) -> Matrix:
    return tuple(tuple(v[start + i * cols:start + (i + 1) * cols]) for i in range(rows))


def gain_lp(A: Matrix, B: Matrix, G: Matrix, b: Sequence[Fraction],
            E: Matrix = (), e: Sequence[Fraction] = ()) -> GainLP:
    """The LP of the module docstring for exact data (A n x n, B n x p, G m x n, E q x p).

    >>> lp = gain_lp([[0]], [[1]], [[1], [-1]], [1, 1])
    >>> lp.equality, lp.nonnegative
    ((True, True, False, False, False, False), (False, True, True, False, False, False))
    """
    n, p, m, q = len(A), len(B[0]), len(G), len(E)
    Gq, Aq, Bq = (flint.fmpq_mat([[_q(v) for v in r] for r in M]) for M in (G, A, B))
    GA, GB = Gq * Aq, Gq * Bq
    N = m * m + p * n + 1 + q * m
    R = m * n + 2 * m + q * n + q
    M = flint.fmpq_mat(R, N)
    g = m * m + p * n
    for i in range(m):
        for c in range(n):
            row = i * n + c
            for k in range(m):
                M[row, i * m + k] = Gq[k, c]
            for k in range(p):
                M[row, m * m + k * n + c] = -GB[i, k]
        for k in range(m):
            M[m * n + i, i * m + k] = _q(b[k])
        M[m * n + m + i, i * m + i] = -1
        M[m * n + m + i, g] = -1
    base = m * n + 2 * m
    for j in range(q):
        for c in range(n):
            row = base + j * n + c
            for k in range(m):
                M[row, g + 1 + j * m + k] = Gq[k, c]
            for k in range(p):
                M[row, m * m + k * n + c] = -_q(E[j][k])
        for k in range(m):
            M[base + q * n + j, g + 1 + j * m + k] = _q(b[k])
    equality = tuple([True] * (m * n) + [False] * (2 * m) + [True] * (q * n) + [False] * q)
    rhs = tuple([Fraction(int(GA[i, c].p), int(GA[i, c].q)) for i in range(m) for c in range(n)]
                + [Fraction(0)] * (2 * m + q * n) + [Fraction(v) for v in e])
    cost = tuple(Fraction(-1) if k == g else Fraction(0) for k in range(N))
    nonnegative = tuple([i != k for i in range(m) for k in range(m)] + [False] * (p * n + 1) + [True] * (q * m))
    return GainLP(m, n, p, q, M, equality, rhs, cost, nonnegative)
