"""Sparse exact matrices by rows: H and H~ without an m x m object.

A row LP's basic solution has at most n + 1 nonzero entries of its m, so the
certificate H of gamma* on a polytope with m facets has O(m n) nonzero entries,
not m^2.  :class:`SparseRows` holds them row by row as FLINT rationals
(``fmpq``) and does what the engine needs without ever expanding the matrix:
products with a vector, the diagonal, the off-diagonal graph, principal blocks
(dense only on a block, for a characteristic polynomial), and the version 3
certificate encoding.  Exact: entries are rationals, never rounded.
"""

from __future__ import annotations

from dataclasses import dataclass
from fractions import Fraction
from typing import Iterable, Sequence

import flint

from .encode import sparse_mat

__all__ = ["SparseRows"]

Row = tuple[tuple[int, flint.fmpq], ...]


def _fmpq(v) -> flint.fmpq:
    if isinstance(v, flint.fmpq):
        return v
    q = Fraction(v)
    return flint.fmpq(q.numerator, q.denominator)


@dataclass(frozen=True)
class SparseRows:
    """An ``m`` x ``cols`` rational matrix by rows: row i is a tuple of (column, nonzero fmpq)
    pairs with strictly increasing columns.  Immutable.

    >>> H = SparseRows.of_rows(2, [[(1, Fraction(1, 2)), (0, -1)], [(1, 0)]])
    >>> H
    SparseRows(2 x 2, 2 nonzero entries)
    >>> H.rows[0], H.diagonal(), H.to_flint()
    (((0, -1), (1, 1/2)), [-1, 0], [-1, 1/2]
    [ 0,   0])
    """

    rows: tuple[Row, ...]
    cols: int

    @classmethod
    def of_rows(cls, cols: int, rows: Iterable[Iterable[tuple[int, object]]]) -> SparseRows:
        """From rows of (column, value) pairs (any exact rationals; zeros are dropped, columns sorted).

        >>> SparseRows.of_rows(3, [[(2, Fraction(1, 3)), (0, 0)], []]).rows
        (((2, 1/3),), ())
        """
        out = []
        for row in rows:
            entries = sorted((int(k), _fmpq(v)) for k, v in row)
            entries = [(k, v) for k, v in entries if v != 0]
            if any(a[0] == b[0] for a, b in zip(entries, entries[1:])) or any(not 0 <= k < cols for k, _ in entries):
                raise ValueError("SparseRows: a column repeats or is out of range")
            out.append(tuple(entries))
        return cls(tuple(out), cols)

    @classmethod
    def of(cls, M: flint.fmpq_mat | SparseRows | Sequence[Sequence[object]]) -> SparseRows:
        """A :class:`SparseRows` from itself, an fmpq matrix or a dense list of rows (their nonzero entries).

        >>> SparseRows.of(flint.fmpq_mat([[0, 2], [3, 0]])).rows
        (((1, 2),), ((0, 3),))
        """
        if isinstance(M, SparseRows):
            return M
        if isinstance(M, flint.fmpq_mat):
            m, c = M.nrows(), M.ncols()
            entries = M.entries()
            return cls(tuple(tuple((k, v) for k, v in enumerate(entries[i * c:(i + 1) * c]) if v != 0)
                             for i in range(m)), c)
        rows = [list(r) for r in M]
        cols = len(rows[0]) if rows else 0
        return cls.of_rows(cols, ([(k, v) for k, v in enumerate(r)] for r in rows))

    @property
    def m(self) -> int:
        return len(self.rows)

    @property
    def nnz(self) -> int:
        """The number of nonzero entries."""
        return sum(map(len, self.rows))

    def diagonal(self) -> list[flint.fmpq]:
        """H_ii for every row (0 where the row has none).

        >>> SparseRows.of([[1, 2], [3, 0]]).diagonal()
        [1, 0]
        """
        zero = flint.fmpq(0)
        return [next((v for k, v in row if k == i), zero) for i, row in enumerate(self.rows)]

    def times(self, v: Sequence[object]) -> list[flint.fmpq]:
        """H v for a dense vector v, exactly.

        >>> SparseRows.of([[1, 2], [0, 3]]).times([1, Fraction(1, 3)])
        [5/3, 1]
        """
        q = [_fmpq(x) for x in v]
        zero = flint.fmpq(0)
        return [sum((x * q[k] for k, x in row), zero) for row in self.rows]

    def successors(self) -> list[list[int]]:
        """The graph i -> k (k != i, H_ik != 0).

        >>> SparseRows.of([[1, 2, 0], [0, 3, 4], [5, 0, 6]]).successors()
        [[1], [2], [0]]
        """
        return [[k for k, _ in row if k != i] for i, row in enumerate(self.rows)]

    def block(self, indices: Sequence[int]) -> flint.fmpq_mat:
        """The principal submatrix on ``indices`` (dense: a block, not the whole matrix).

        >>> SparseRows.of([[1, 2, 0], [0, 3, 4], [5, 0, 6]]).block([0, 2])
        [1, 0]
        [5, 6]
        """
        where = {g: i for i, g in enumerate(indices)}
        B = flint.fmpq_mat(len(indices), len(indices))
        for i, g in enumerate(indices):
            for k, v in self.rows[g]:
                if k in where:
                    B[i, where[k]] = v
        return B

    def to_flint(self) -> flint.fmpq_mat:
        """The dense fmpq matrix (m x cols) -- for a user who asks; the engine never needs it.

        >>> SparseRows.of_rows(2, [[(1, 5)], []]).to_flint()
        [0, 5]
        [0, 0]
        """
        M = flint.fmpq_mat(self.m, self.cols)
        for i, row in enumerate(self.rows):
            for k, v in row:
                M[i, k] = v
        return M

    def encode(self) -> dict:
        """The version 3 certificate encoding ``{"sparse": [[[k, "v"], ...], ...]}``.

        >>> SparseRows.of([[0, Fraction(-1, 2)], [0, 0]]).encode()
        {'sparse': [[[1, '-1/2']], []]}
        """
        return sparse_mat(self.rows)

    def __repr__(self) -> str:
        return f"SparseRows({self.m} x {self.cols}, {self.nnz} nonzero entries)"
