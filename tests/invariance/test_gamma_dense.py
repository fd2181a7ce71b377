"""gamma* on long rationals (issue 24, item 4): exactinv/invariance/gamma_dense.py.

* property: on polygons with 20-40-bit rational vertices (so G and b have long entries), the
  certified gamma* and every row's gamma_j equal the old route's (every row LP through the general
  engine), exactly, and the kernel verifies the certificate;
* data too long for the double check never builds the block LP of gamma_batch;
* a row whose float hint misleads is solved alone by PPL and proved by the same integer check;
* on the benchmark polygons every row is proved by the integer check (no general-route row).
"""

from __future__ import annotations

import sys
from fractions import Fraction as F
from pathlib import Path

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

import exactinv as ei
from exactinv.invariance import gamma_batch, gamma_dense, gamma_star
from exactinv.invariance.gamma_batch import IntegerData, fits_doubles
from exactinv.lp.solver import LPPath

sys.path.insert(0, str(Path(__file__).resolve().parents[2] / "benchmarks"))
from largest import polygon  # noqa: E402

CHECKED = {LPPath.ROUNDED, LPPath.BASIS, LPPath.PPL}  # rows proved by the integer check of gamma_dense


def _old_route(S, P, monkeypatch):
    """gamma* with every row LP through the general engine (the route before issue 24 for long data)."""
    with monkeypatch.context() as patch:
        patch.setattr(gamma_star, "_row_batch", lambda S, P: None)
        return ei.optimal_gamma(S, P)


@st.composite
def long_polygons(draw):
    """A polygon with k vertices on the unit circle, ((1 - s^2)/(1 + s^2), 2s/(1 + s^2)), s rational
    with a 20-bit denominator (vertex coordinates of 20-40 bits), and a rational A."""
    k = draw(st.integers(3, 9))
    q = draw(st.integers(2**19, 2**20))
    s = sorted(set(draw(st.lists(st.integers(-4 * q, 4 * q), min_size=k, max_size=k, unique=True))))
    pts = [((1 - F(p, q) ** 2) / (1 + F(p, q) ** 2), 2 * F(p, q) / (1 + F(p, q) ** 2)) for p in s]
    P = ei.Polyhedron.from_vertices(pts)
    entry = st.fractions(min_value=-2, max_value=2, max_denominator=7)
    A = [[draw(entry) for _ in range(2)] for _ in range(2)]
    shift = draw(st.sampled_from([F(-3), F(-1), F(0)]))
    return ei.LinearSystem([[A[0][0] + shift, A[0][1]], [A[1][0], A[1][1] + shift]]), P


@settings(max_examples=30, deadline=None)
@given(long_polygons())
def test_long_rationals_equal_the_old_route(problem):
    S, P = problem
    assert max(v.denominator.bit_length() for row in P.vertices for v in row) >= 20
    new = ei.optimal_gamma(S, P)
    with pytest.MonkeyPatch.context() as mp:
        old = _old_route(S, P, mp)
    assert new.value == old.value
    if new.witness is None:
        assert [r.gamma for r in new.rows] == [r.gamma for r in old.rows]
        assert ei.check(new.certificate).ok


def test_long_data_skips_the_block_lp(monkeypatch):
    """50-bit facet normals: the double check cannot hold, so no block LP (m^2 float columns) is solved."""
    S, P = ei.LinearSystem([[-1, F(1, 2)], [F(-1, 2), -1]]), polygon(40)
    data = IntegerData.of(S, P)
    assert gamma_batch.is_sparse(gamma_batch.integer_G(P)) and not fits_doubles(data)

    def forbidden(*args, **kwargs):
        raise AssertionError("the block LP was built")
    monkeypatch.setattr(gamma_batch, "block_hints", forbidden)
    g = ei.optimal_gamma(S, P)
    assert set(g.paths) <= CHECKED and ei.check(g.certificate).ok


def test_a_misleading_hint_is_repaired_by_ppl_and_proved(monkeypatch):
    """Row 0's proposal replaced by a wrong one: the check fails it, PPL solves row 0 alone, and the
    same integer check proves it; the value is the old route's."""
    S, P = ei.LinearSystem([[-1, F(1, 2)], [F(-1, 2), -1]]), polygon(24)
    good = gamma_dense._proposal

    def wrong_first(data, j, rhs, hint):
        row = good(data, j, rhs, hint)
        if j == 0:  # h_00 off by 1/3: primal infeasible
            return gamma_dense.SparseRow(row.support, tuple(v + row.d // 3 + 1 if k == 0 else v
                                                            for k, v in zip(row.support, row.h)), row.d, row.w,
                                         row.e, row.path)
        return row
    monkeypatch.setattr(gamma_dense, "_proposal", wrong_first)
    rows = gamma_dense.dense_rows(S, P)
    assert rows.ok.all() and rows.path(0) == LPPath.PPL
    g = ei.optimal_gamma(S, P)
    assert g.rows[0].path == LPPath.PPL and ei.check(g.certificate).ok
    assert g.value == _old_route(S, P, monkeypatch).value


@pytest.mark.parametrize("sides", [60, 200])
def test_benchmark_polygons_are_proved_by_the_integer_check(sides):
    S, P = ei.LinearSystem([[-1, F(1, 2)], [F(-1, 2), -1]]), polygon(sides)
    g = ei.optimal_gamma(S, P)
    assert set(g.paths) <= CHECKED, g.paths
    assert g.H_sparse.nnz <= (P.n + 1) * P.m  # a basic solution per row: at most n + 1 nonzeros
    cert = g.certificate
    assert cert["version"] == 3 and ei.check(cert).ok


def test_a_row_without_a_float_hint_is_solved_by_ppl(monkeypatch):
    """A row without an optimal float hint (even after the retry from a fresh model) is solved alone
    by PPL and proved by the same check; the others keep their float route; gamma* is unchanged."""
    S, P = ei.LinearSystem([[-1, F(1, 2)], [F(-1, 2), -1]]), polygon(12)
    from exactinv.lp.floatlp import FloatLP
    real = FloatLP.solve_floats

    def fail_row_3(self, cost, rhs, nonneg):
        if cost is not None and len(cost) == P.m and cost[3] == 1.0:
            from exactinv.lp.hint_types import UNKNOWN_HINT
            return UNKNOWN_HINT
        return real(self, cost, rhs, nonneg)
    monkeypatch.setattr(FloatLP, "solve_floats", fail_row_3)
    rows = gamma_dense.dense_rows(S, P)
    assert rows.ok.all() and rows.path(3) == LPPath.PPL
    assert all(rows.path(j) != LPPath.PPL for j in range(P.m) if j != 3)
    g = ei.optimal_gamma(S, P)
    monkeypatch.undo()
    assert g.value == ei.optimal_gamma(S, P).value and ei.check(g.certificate).ok
