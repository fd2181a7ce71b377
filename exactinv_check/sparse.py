"""Sparse square matrices (H, H~) read strictly: the version 3 encoding, and the dense one of versions 1 and 2.

A certificate of version 3 writes an m x m matrix such as H as
``{"sparse": [row_0, ..., row_{m-1}]}``, where row i lists its nonzero entries
as pairs ``[k, "value"]``: k a JSON integer column index, 0 <= k < m, strictly
increasing along the row, and the value an exact nonzero number.  Every row is
present (an empty row is ``[]``).  The reader is strict: a row count other
than m, an index out of range, a repeated or unsorted index, an explicit zero,
a pair that is not a two-element list, or a bool or float index rejects the
matrix.  The row count and lengths come first and price the pass over the
pairs; the structural tests of that pass come next, and the numbers are parsed
only after the whole read is priced by the length of its longest number
(:mod:`.budget`, ``sparse_read_cost``).

Whatever the version, the kernel works on the same form: a list of m rows,
each a list of ``(k, x)`` pairs with x != 0 and k increasing (a dense matrix of
version 1 or 2 is read by :func:`~exactinv_check.rationals.matrix` and its
zeros dropped).  The checks over such rows (HG = GA, Hb <= 0, signs) cost the
number of nonzero entries, never m^2.
"""

from __future__ import annotations

from fractions import Fraction
from typing import Any, Sequence

from .budget import CERTIFICATE_BUDGET, MAX_DIMENSION, sparse_read_cost, within_budget
from .failure import require
from .rationals import matrix, rational

SPARSE_VERSION = 3  # the first certificate version that writes H and H~ sparse


def read_square(value: Any, what: Any, m: Any, version: Any) -> list[list[tuple[Any, Any]]] | None:
    """The m x m matrix ``value`` of a claim, as sparse rows: the version 3 encoding
    (:func:`sparse_matrix`) from version 3 on, the dense list of rows before."""
    if version >= SPARSE_VERSION:
        return sparse_matrix(value, what, m, m)
    return [[(k, x) for k, x in enumerate(row) if x] for row in matrix(value, what, m, m)]


def sparse_matrix(value: Any, what: str, rows: int, cols: int) -> list[list[tuple[Any, Any]]] | None:
    """A ``rows`` x ``cols`` matrix in the version 3 encoding (module docstring), as lists of
    (column, nonzero Fraction) pairs, strictly increasing columns."""
    require(isinstance(value, dict) and set(value) == {"sparse"},
            f'{what}: a version 3 matrix is an object {{"sparse": [rows]}} and nothing else')
    data = value["sparse"]
    require(isinstance(data, list), f"{what}: sparse is a list of rows")
    require(len(data) == rows, f"{what}: expected {rows} rows, got {len(data)} (every row is listed, [] if empty)")
    require(cols <= MAX_DIMENSION * MAX_DIMENSION, f"{what}: too wide")
    for i, row in enumerate(data):  # the row lengths first: the count prices the pass over the pairs
        require(isinstance(row, list), f"{what}: row {i} is not a list")
        require(len(row) <= cols, f"{what}: row {i} has more entries than columns")
    total = sum(map(len, data))
    require(total <= MAX_DIMENSION * MAX_DIMENSION, f"{what}: too many entries")
    floor = sparse_read_cost(total, 1)
    within_budget(floor, f"reading the {total} entries of {what}", limit=CERTIFICATE_BUDGET)
    longest = 0
    for i, row in enumerate(data):  # structure next: one pass, no number parsed
        last = -1
        for pair in row:
            require(isinstance(pair, list) and len(pair) == 2, f"{what}: row {i}: an entry is a pair [column, value]")
            k, x = pair
            require(type(k) is int, f"{what}: row {i}: the column index {k!r} is not a JSON integer")
            require(0 <= k < cols, f"{what}: row {i}: column index {k} is out of range [0, {cols})")
            require(k > last, f"{what}: row {i}: column index {k} repeats or is out of order (columns increase strictly)")
            last = k
            if isinstance(x, str):
                longest = max(longest, len(x))
            elif type(x) is int:  # a JSON integer (the kernel reads one where a number is expected)
                longest = max(longest, x.bit_length() // 3 + 1)
    within_budget(sparse_read_cost(total, longest) - floor, f"reading the {total} entries of {what} "
                  f"(numbers of up to {longest} digits)", limit=CERTIFICATE_BUDGET)
    out = []
    for i, row in enumerate(data):
        parsed = []
        for k, x in row:
            q = rational(x, f"{what}[{i}][{k}]")
            require(q != 0, f"{what}: row {i}: column {k} is an explicit zero (version 3 lists nonzero entries only)")
            parsed.append((k, q))
        out.append(parsed)
    return out


def diagonal(rows: Any) -> Any:
    """The diagonal entries of a square matrix in sparse rows (0 where a row has none)."""
    return [next((x for k, x in row if k == i), Fraction(0)) for i, row in enumerate(rows)]


def row_dot(row: Sequence[tuple[int, Fraction]], v: Any) -> Any:
    """The sparse row times a dense vector, exactly."""
    return sum((x * v[k] for k, x in row), Fraction(0))
