"""gamma*'s m row LPs in one pass: one float solve, one exact integer check.

Row LP j (see :mod:`~exactinv.invariance.gamma_star`) is
max h_j  s.t.  G^T h = A^T g_j,  b^T h <= 0,  h_k >= 0 (k != j),
with dual  min (A^T g_j).y  s.t.  g_k.y + lam b_k >= 0 (k != j),
g_j.y + lam b_j = 1,  lam >= 0.  When G is sparse (at most two nonzeros per
row on average, e.g. a box), all m LPs are posed as ONE block-diagonal float
LP (:func:`~exactinv.lp.block.block_hints`), which HiGHS' presolve mostly
solves outright.  The float rows of H and the duals are rounded to integers
over D = 5040 and every row is checked at once by :func:`verify_rows`:

* primal  -- (H G)_j = (G A)_j, (H b)_j <= 0, H_jk >= 0 for k != j;
* dual    -- lam_j >= 0, g_k.y_j + lam_j b_k >= 0 (k != j), = 1 (k = j);
* optimal -- (A^T g_j).y_j = H_jj.

By LP duality a row passing all three is proved optimal: gamma_j = -H_jj.
Exact: G, b, A are integers over common denominators, and every product and
sum is an integer proved (with Python integers, from the entries' bounds)
to stay below 2^53, so the numpy/BLAS arithmetic on doubles is exact (the
argument of :mod:`~exactinv.lp.verify_int`).  Rows that fail go through the
general engine; data too large for doubles skips this route.
"""

from __future__ import annotations

from dataclasses import dataclass
from fractions import Fraction
from math import lcm
from typing import Sequence

import flint
import numpy as np

from ..core.sparse import SparseRows
from ..lp import OPTIMAL, LPResult
from ..lp.block import block_hints
from ..lp.reconstruct import COMMON_DENOMINATOR
from ..lp.solver import LPPath
from ..model import LinearSystem, Polyhedron

__all__ = ["IntegerData", "RowBatch", "integer_G", "is_sparse", "batch_rows", "verify_rows"]

_EXACT = 2 ** 53
MAX_BLOCK_ROWS = 1000  # the block LP has m^2 columns: beyond this many facets, row by row (gamma_dense)
_TOLERANCE = 1e-9  # a simplex vertex: within 1e-9 (relative) of a multiple of 1/D


@dataclass(frozen=True)
class IntegerData:
    """G = Gn/dG, b = bn/db, A = An/dA with integer-valued float64 arrays
    (every |entry| < 2^53) and GA = GAn/(dG dA), GAn = Gn An exact."""

    Gn: np.ndarray
    dG: int
    bn: np.ndarray
    db: int
    An: np.ndarray
    dA: int
    GAn: np.ndarray

    @classmethod
    def of(cls, system: LinearSystem, polyhedron: Polyhedron) -> IntegerData | None:
        """The integer image of (A, G, b), or None when it is too large for exact doubles.

        >>> d = IntegerData.of(LinearSystem([[-1, Fraction(1, 2)], [0, -1]]), Polyhedron.box([-1, -1], [1, 1]))
        >>> d.An.tolist(), d.dA, d.GAn.tolist()
        ([[-2.0, 1.0], [0.0, -2.0]], 2, [[-2.0, 1.0], [0.0, -2.0], [2.0, -1.0], [0.0, 2.0]])
        """
        return cls.from_G(_integers(polyhedron.G), system, polyhedron)

    @classmethod
    def from_G(cls, G: tuple[np.ndarray, int] | None, system: LinearSystem,
               polyhedron: Polyhedron) -> IntegerData | None:
        """:meth:`of`, with G's integer image ``(Gn, dG)`` already read (None: too large).

        >>> IntegerData.from_G((np.array([[2.0]]), 1), LinearSystem([[3]]), Polyhedron([[2]], [1])).GAn.tolist()
        [[6.0]]
        """
        parts = [G, _integers([polyhedron.b]), _integers(system.A)]
        if any(p is None for p in parts):
            return None
        (Gn, dG), (bn, db), (An, dA) = parts
        n = Gn.shape[1]
        if n * _max(Gn) * _max(An) >= _EXACT:
            return None
        return cls(Gn, dG, bn[0], db, An, dA, _sparse_times(Gn, An) + 0.0)  # + 0.0: no -0.0 entries


@dataclass(frozen=True)
class RowBatch:
    """The rounded rows: H = Hn/D (m x m), duals y_j = Yn[j]/D, lam_j = Ln[j]/D;
    ``ok[j]``: row j is proved optimal (gamma_j = -Hn[j, j]/D)."""

    Hn: np.ndarray
    Yn: np.ndarray
    Ln: np.ndarray
    D: int
    ok: np.ndarray

    def gamma(self, j: int) -> Fraction:
        """gamma_j = -H_jj of a proved row.

        >>> RowBatch(np.array([[-3.0]]), np.zeros((1, 1)), np.zeros(1), 2, np.array([True])).gamma(0)
        Fraction(3, 2)
        """
        return Fraction(-int(self.Hn[j, j]), self.D)

    def path(self, j: int) -> LPPath:
        """Every row of the batch is a rounded float hint.

        >>> RowBatch(np.array([[-3.0]]), np.zeros((1, 1)), np.zeros(1), 2, np.array([True])).path(0)
        <LPPath.ROUNDED: 'float-rounded'>
        """
        return LPPath.ROUNDED

    def result(self, j: int) -> LPResult:
        """Row j as a verified :class:`~exactinv.lp.LPResult` (x = h_j, y = (y_j, lam_j)).

        >>> r = RowBatch(np.array([[-3.0]]), np.array([[4.0]]), np.array([1.0]), 2, np.array([True])).result(0)
        >>> r.value, r.x, r.y
        (Fraction(-3, 2), (Fraction(-3, 2),), (Fraction(2, 1), Fraction(1, 2)))
        """
        x = _column(self.Hn[j].tolist(), self.D)
        y = _column(self.Yn[j].tolist() + [self.Ln[j].item()], self.D)
        return LPResult(OPTIMAL, -self.gamma(j), x, y, None, LPPath.ROUNDED)

    def H_rows(self) -> SparseRows:
        """H = Hn/D by rows, its nonzero entries only.

        >>> RowBatch(np.array([[-3.0, 1.0], [2.0, 0.0]]), np.zeros((2, 1)), np.zeros(2), 2, np.ones(2, bool)).H_rows().rows
        (((0, -3/2), (1, 1/2)), ((0, 1),))
        """
        m = len(self.Hn)
        return SparseRows.of_rows(m, ([(k, flint.fmpq(int(self.Hn[j, k]), self.D)) for k in np.flatnonzero(self.Hn[j]).tolist()]
                                      for j in range(m)))


def is_sparse(G: tuple[np.ndarray, int] | None) -> bool:
    """G's integer image (see :func:`integer_G`) has at most two nonzeros per
    row on average and at most ``MAX_BLOCK_ROWS`` rows (then :func:`batch_rows`
    applies; a G beyond doubles is not sparse).

    >>> is_sparse(integer_G(Polyhedron.box([-1, -1], [1, 1])))
    True
    >>> is_sparse(integer_G(Polyhedron([[1, 1, 1], [1, -1, 1], [-1, 1, -1]], [1, 1, 1])))
    False
    """
    return G is not None and len(G[0]) <= MAX_BLOCK_ROWS and int(np.count_nonzero(G[0])) <= 2 * len(G[0])


def integer_G(polyhedron: Polyhedron) -> tuple[np.ndarray, int] | None:
    """(Gn, dG) with G = Gn/dG, Gn integer-valued float64 (|entries| < 2^53); None if too large.

    >>> Gn, dG = integer_G(Polyhedron([[1, Fraction(1, 2)]], [1]))
    >>> Gn.tolist(), dG
    ([[2.0, 1.0]], 2)
    """
    return _integers(polyhedron.G)


def batch_rows(system: LinearSystem, polyhedron: Polyhedron,
               G: tuple[np.ndarray, int] | None = None) -> RowBatch | None:
    """All m row LPs from one block-diagonal float solve, rounded and verified
    (:func:`verify_rows`); None when the route does not apply (G not sparse,
    data too large, or the float solve not optimal for every row).  ``G``:
    G's integer image if already read (:func:`integer_G`).

    x' = -x on [-1, 1]: each row LP has h = (-1/2, 1/2), y = 1/2, lam = 1/2.

    >>> batch = batch_rows(LinearSystem([[-1]]), Polyhedron.box([-1], [1]))
    >>> batch.ok.tolist(), batch.gamma(0), batch.result(1).y
    ([True, True], Fraction(1, 2), (Fraction(-1, 2), Fraction(1, 2)))
    """
    m, n = polyhedron.m, polyhedron.n
    G = integer_G(polyhedron) if G is None else G
    data = IntegerData.from_G(G, system, polyhedron) if m and n and is_sparse(G) else None
    if data is None or not fits_doubles(data):
        return None
    scale_G, scale_b = data.Gn / data.dG, data.bn / data.db
    constraint = np.vstack([scale_G.T, scale_b[None, :]])  # [G^T; b^T]: (n + 1) x m
    nonneg = ~np.eye(m, dtype=bool)
    rhss = np.hstack([data.GAn / (data.dG * data.dA), np.zeros((m, 1))])
    hint = block_hints(constraint, np.arange(n + 1) < n, np.eye(m), rhss, nonneg)
    if hint.status != OPTIMAL:
        return None
    D = COMMON_DENOMINATOR
    (Hn, h_ok), (Wn, w_ok) = _rounded(hint.X, D), _rounded(hint.Y, D)
    rounded = h_ok & w_ok
    Hn[~rounded], Wn[~rounded] = 0.0, 0.0  # rows left to the general engine
    Yn, Ln = Wn[:, :n], Wn[:, n]
    ok = verify_rows(data, Hn, Yn, Ln, D)
    return None if ok is None else RowBatch(Hn, Yn, Ln, D, ok & rounded)


def fits_doubles(data: IntegerData, D: int = COMMON_DENOMINATOR) -> bool:
    """Can :func:`verify_rows` decide anything on this data?  Its bounds hold at best for
    rows H with entries of size 1 (numerators D): m max|Gn| dA + D max|GAn| and dG db D below
    2^53.  Long data (e.g. 50-bit facet normals) fails at once, before any block LP is solved
    (gamma_star then takes the row-by-row route with the FLINT check, gamma_dense).

    >>> fits_doubles(IntegerData.of(LinearSystem([[-1]]), Polyhedron.box([-1], [1])))
    True
    >>> fits_doubles(IntegerData.of(LinearSystem([[-1]]), Polyhedron([[2**50], [-1]], [1, 1])))
    False
    """
    m = data.Gn.shape[0]
    return max(m * _max(data.Gn) * data.dA + D * _max(data.GAn), data.dG * data.db * D) < _EXACT


def verify_rows(data: IntegerData, Hn: np.ndarray, Yn: np.ndarray, Ln: np.ndarray, D: int) -> np.ndarray | None:
    """Per row j: (Hn[j]/D, (Yn[j], Ln[j])/D) is a proved optimal primal-dual
    pair of row LP j (module docstring); None when the bounds do not keep
    every integer below 2^53 (then nothing is decided here).  Exact.

    x' = -x on [-1, 1] (G = (1, -1)^T, b = (1, 1)): row 0 has h = (-1/2, 1/2),
    y = 1/2, lam = 1/2 (times D = 2: -1, 1 and 1, 1); a wrong lam fails.

    >>> data = IntegerData.of(LinearSystem([[-1]]), Polyhedron.box([-1], [1]))
    >>> H, Y = np.array([[-1.0, 1.0], [1.0, -1.0]]), np.array([[1.0], [-1.0]])
    >>> verify_rows(data, H, Y, np.array([1.0, 1.0]), 2).tolist()
    [True, True]
    >>> verify_rows(data, H, Y, np.array([1.0, 2.0]), 2).tolist()
    [True, False]
    """
    Gn, bn, GAn = data.Gn, data.bn, data.GAn
    (m, n), dG, db, dA = Gn.shape, data.dG, data.db, data.dA
    mH, mY, mL, mG, mb, mGA = (_max(M) for M in (Hn, Yn, Ln, Gn, bn, GAn))
    bounds = (m * mH * mG * dA + D * mGA,  # (H G) dA - D (G A)
              m * mH * mb,  # H b
              n * mG * mY * db + mb * mL * dG + dG * db * D,  # the dual constraints, minus dG db D
              n * mGA * mY + mH * dG * dA)  # the objectives
    if max(bounds) >= _EXACT:
        return None
    off = ~np.eye(m, dtype=bool)
    ok = ~(_times_sparse(Hn, Gn) * dA != D * GAn).any(axis=1)
    ok &= (Hn @ bn <= 0) & ~((Hn < 0) & off).any(axis=1)
    K = _sparse_times(Gn, Yn.T) * db + np.outer(bn, Ln) * dG  # column j: (g_k.y_j + lam_j b_k) dG db D
    ok &= (Ln >= 0) & (np.diagonal(K) == dG * db * D) & ~((K < 0) & off).any(axis=0)
    ok &= (GAn * Yn).sum(axis=1) == np.diagonal(Hn) * (dG * dA)
    return ok


# ------------------------------------------------------------------ helpers
def _integers(rows: Sequence[Sequence[Fraction]]) -> tuple[np.ndarray, int] | None:
    """(N, d) with rows = N/d, N integer-valued float64 (every |entry| < 2^53); None if too large."""
    d = lcm(*{v.denominator for row in rows for v in row}) if rows and rows[0] else 1
    if d >= _EXACT:
        return None
    ints = [[v.numerator * (d // v.denominator) for v in row] for row in rows]
    if any(abs(x) >= _EXACT for row in ints for x in row):  # checked as integers: no float overflow
        return None
    return np.array(ints, dtype=float).reshape(len(rows), -1), d


def _sparse_times(G: np.ndarray, Z: np.ndarray) -> np.ndarray:
    """G Z for a sparse G, column by column of G: the nonzero products only.

    Every partial sum is a partial sum of the full product, so the callers'
    bounds (< 2^53) keep it exact on doubles, in any order of summation.

    >>> _sparse_times(np.array([[2.0, 0.0], [0.0, -1.0], [1.0, 1.0]]), np.array([[1.0, 2.0], [3.0, 4.0]])).tolist()
    [[2.0, 4.0], [-3.0, -4.0], [4.0, 6.0]]
    """
    out = np.zeros((G.shape[0], Z.shape[1]))
    for j in range(G.shape[1]):
        rows = np.flatnonzero(G[:, j])  # distinct rows: a plain += is exact
        out[rows] += G[rows, j][:, None] * Z[j][None, :]
    return out


def _times_sparse(Z: np.ndarray, G: np.ndarray) -> np.ndarray:
    """Z G for a sparse G (as :func:`_sparse_times`, exact under the same bounds).

    >>> _times_sparse(np.array([[1.0, 2.0, 3.0]]), np.array([[2.0, 0.0], [0.0, -1.0], [1.0, 1.0]])).tolist()
    [[5.0, 1.0]]
    """
    out = np.zeros((Z.shape[0], G.shape[1]))
    for j in range(G.shape[1]):
        rows = np.flatnonzero(G[:, j])
        out[:, j] = Z[:, rows] @ G[rows, j]
    return out


def _max(M: np.ndarray) -> int:
    return int(np.abs(M).max(initial=0))


def _rounded(X: np.ndarray, D: int) -> tuple[np.ndarray, np.ndarray]:
    """X rounded to integers over D, and per row whether every entry was within tolerance and < 2^53."""
    scaled = X * D
    near = np.round(scaled)
    ok = (np.abs(scaled - near) <= _TOLERANCE * np.maximum(1.0, np.abs(scaled))).all(axis=1)
    ok &= (np.abs(near) < _EXACT).all(axis=1)
    return np.where(np.isfinite(near), near, 0.0) + 0.0, ok


def _column(numerators: list, D: int) -> flint.fmpq_mat:
    return flint.fmpq_mat(flint.fmpz_mat(len(numerators), 1, [int(v) for v in numerators])) / D
