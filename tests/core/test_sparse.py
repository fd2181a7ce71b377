"""exactinv/core/sparse.py: SparseRows against the dense definitions (FLINT matrices)."""

from __future__ import annotations

from fractions import Fraction as F

import flint
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

import exactinv as ei
from exactinv.core.sparse import SparseRows


@st.composite
def dense(draw):
    m = draw(st.integers(0, 6))
    c = draw(st.integers(1, 6)) if m else 0
    entry = st.one_of(st.just(F(0)), st.fractions(max_denominator=50).filter(lambda q: abs(q) < 100))
    return [[draw(entry) for _ in range(c)] for _ in range(m)]


@settings(max_examples=150, deadline=None)
@given(dense(), st.data())
def test_sparse_rows_are_the_dense_matrix(M, data):
    S = SparseRows.of(M)
    cols = len(M[0]) if M else 0
    D = flint.fmpq_mat(len(M), cols, [flint.fmpq(x.numerator, x.denominator) for row in M for x in row])
    assert S.to_flint() == D and SparseRows.of(D) == S
    assert S.nnz == sum(1 for row in M for x in row if x)
    assert all(v != 0 for row in S.rows for _, v in row)
    v = [F(data.draw(st.integers(-9, 9)), data.draw(st.integers(1, 9))) for _ in range(cols)]
    Dv = D * flint.fmpq_mat(cols, 1, [flint.fmpq(x.numerator, x.denominator) for x in v])
    assert S.times(v) == Dv.entries()
    if M and cols == len(M):
        assert S.diagonal() == [D[i, i] for i in range(len(M))]
        idx = sorted(set(data.draw(st.lists(st.integers(0, len(M) - 1), max_size=len(M)))))
        assert S.block(idx) == flint.fmpq_mat(len(idx), len(idx), [D[i, j] for i in idx for j in idx])
    encoded = S.encode()["sparse"]
    assert [[(k, F(x)) for k, x in row] for row in encoded] == [[(k, x) for k, x in enumerate(r) if x] for r in M]


def test_bad_rows_are_refused():
    with pytest.raises(ValueError):
        SparseRows.of_rows(2, [[(0, 1), (0, 2)]])
    with pytest.raises(ValueError):
        SparseRows.of_rows(2, [[(2, 1)]])


def test_gamma_star_builds_no_dense_H():
    """The engine's H is sparse rows of at most n + 1 nonzeros each (a basic solution per row LP); its
    claim lists exactly those, and the dense view (built only on request) agrees."""
    import sys
    from pathlib import Path
    sys.path.insert(0, str(Path(__file__).resolve().parents[2] / "benchmarks"))
    from largest import polygon
    g = ei.optimal_gamma(ei.LinearSystem([[-1, F(1, 2)], [F(-1, 2), -1]]), polygon(30))
    assert "H_flint" not in g.__dict__  # not built by optimal_gamma
    H = g.H_sparse
    assert all(len(row) <= 3 for row in H.rows)
    claim = g.claims()[0]
    assert claim["H"] == H.encode() and "H_flint" not in g.__dict__
    assert SparseRows.of(g.H_flint) == H
