"""gamma*'s batched routes (invariance/gamma_batch.py: one block-diagonal float LP
for a sparse G; invariance/gamma_dense.py: warm-started rows for a dense G), both
proving every row in one integer check, against the general engine row by
row; forged rows are rejected by both checks."""

from dataclasses import replace
from fractions import Fraction

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

import exactinv as ei
from exactinv.invariance import gamma_star
from exactinv.invariance.gamma_batch import IntegerData, batch_rows, integer_G, is_sparse, verify_rows
from exactinv.invariance.gamma_dense import _verify, dense_rows
from exactinv.lp.block import block_hints
from exactinv_check import check


def _general(S, P, monkeypatch):
    """gamma* through the general engine only (every row LP alone, then re-checked)."""
    with monkeypatch.context() as patch:
        patch.setattr(gamma_star, "_row_batch", lambda S, P: None)
        return ei.optimal_gamma(S, P)


@st.composite
def _problems(draw, sparse):
    n = draw(st.integers(1, 3))
    A = [[Fraction(draw(st.integers(-4, 4)), draw(st.integers(1, 3))) for _ in range(n)] for _ in range(n)]
    if sparse:  # a box with bounds of denominators 1..6 (rounding over 5040 works) or 7, 11 (it may not)
        lo = [-Fraction(draw(st.integers(1, 5)), draw(st.sampled_from([1, 2, 3, 6, 7, 11]))) for _ in range(n)]
        hi = [Fraction(draw(st.integers(1, 5)), draw(st.sampled_from([1, 2, 4, 5, 11]))) for _ in range(n)]
        return ei.LinearSystem(A), ei.Polyhedron.box(lo, hi)
    m = draw(st.integers(n + 1, 6))
    G = [[draw(st.integers(-3, 3)) for _ in range(n)] for _ in range(m)]
    G = [row if any(row) else [1] * n for row in G]
    b = [Fraction(draw(st.integers(1, 6)), draw(st.integers(1, 3))) for _ in range(m)]
    return ei.LinearSystem(A), ei.Polyhedron(G, b)


@settings(max_examples=40, deadline=None)
@given(_problems(sparse=True))
def test_sparse_route_matches_the_general_engine(problem):
    S, P = problem
    monkeypatch = pytest.MonkeyPatch()
    g, ref = ei.optimal_gamma(S, P), _general(S, P, monkeypatch)
    assert g.value == ref.value and g.binding_row == ref.binding_row
    assert check(g.certificate).ok
    batch = batch_rows(S, P)
    if batch is not None:  # every proved row is the row LP's optimum
        for j in np.flatnonzero(batch.ok).tolist():
            assert batch.gamma(j) == ref.rows[j].gamma


@settings(max_examples=40, deadline=None)
@given(_problems(sparse=False))
def test_dense_route_matches_the_general_engine(problem):
    S, P = problem
    g, ref = ei.optimal_gamma(S, P), _general(S, P, pytest.MonkeyPatch())
    assert g.value == ref.value
    if g.witness is None:
        assert check(g.certificate).ok
    rows = dense_rows(S, P)
    if rows is not None:
        for j in np.flatnonzero(rows.ok).tolist():
            assert rows.gamma(j) == ref.rows[j].gamma
            assert rows.result(j).value == -ref.rows[j].gamma


def test_box_rows_are_all_proved_in_one_batch():
    """x' = Ax on [-1, 1]^2 with a row-dominant A: gamma* = max_i (sum_{j != i} |a_ij| - a_ii)/2 = (1 + 3)/2 = 2."""
    S, P = ei.LinearSystem([[-3, 1], [Fraction(1, 2), -2]]), ei.Polyhedron.box([-1, -1], [1, 1])
    batch = batch_rows(S, P)
    assert batch.ok.all() and max(batch.gamma(j) for j in range(4)) == 2
    g = ei.optimal_gamma(S, P)
    assert g.value == 2 and set(g.paths) == {"float-rounded"}
    assert g.H_flint == batch.H_rows().to_flint() and check(g.certificate).ok


def test_rows_that_do_not_round_go_to_the_general_engine():
    """Bounds with denominator 13 put 13ths into H, which no multiple of 1/5040 hits."""
    S, P = ei.LinearSystem([[-13, 1], [0, -1]]), ei.Polyhedron.box([-1, -1], [Fraction(1, 13), 1])
    batch = batch_rows(S, P)
    assert not batch.ok.all()
    g, ref = ei.optimal_gamma(S, P), _general(S, P, pytest.MonkeyPatch())
    assert g.value == ref.value and [r.gamma for r in g.rows] == [r.gamma for r in ref.rows]
    assert check(g.certificate).ok


def test_data_beyond_exact_doubles_skip_the_integer_batch():
    S, P = ei.LinearSystem([[-(2 ** 60)]]), ei.Polyhedron.box([-1], [1])
    assert IntegerData.of(S, P) is None and batch_rows(S, P) is None
    assert ei.optimal_gamma(S, P).value == 2 ** 59


def test_sparsity_decides_the_route():
    assert is_sparse(integer_G(ei.Polyhedron.box([-1] * 3, [1] * 3)))
    assert not is_sparse(integer_G(ei.Polyhedron([[1, 1, 1], [1, -1, 1], [-1, 1, 1], [-1, -1, -1]], [1] * 4)))
    assert not is_sparse(integer_G(ei.Polyhedron([[2 ** 60]], [1])))  # beyond exact doubles: the dense route
    assert not is_sparse((np.eye(1001), 1))  # the block LP would have 1001^2 columns


# ------------------------------------------------------------- forged rows
_S, _P = ei.LinearSystem([[-3, 1], [Fraction(1, 2), -2]]), ei.Polyhedron.box([-1, -1], [1, 1])


@pytest.mark.parametrize("forge", [
    lambda H, Y, L: H.__setitem__((0, 0), H[0, 0] + 1),  # h_00 too large: the objectives differ
    lambda H, Y, L: H.__setitem__((0, 1), H[0, 1] + 5040),  # HG != GA
    lambda H, Y, L: (H.__setitem__((0, 1), -H[0, 1] - 1)),  # a negative off-diagonal entry
    lambda H, Y, L: Y.__setitem__((0, 0), Y[0, 0] + 1),  # g_0.y + lam b_0 != 1
    lambda H, Y, L: L.__setitem__(0, -L[0]),  # lam < 0
    lambda H, Y, L: (H.__setitem__((0, 0), H[0, 0] - 5040), Y.__setitem__((0, 0), Y[0, 0] + 5040)),
])
def test_verify_rows_rejects_forged_rows(forge):
    batch = batch_rows(_S, _P)
    H, Y, L = batch.Hn.copy(), batch.Yn.copy(), batch.Ln.copy()
    forge(H, Y, L)
    ok = verify_rows(IntegerData.of(_S, _P), H, Y, L, batch.D)
    assert not ok[0] and ok[1:].all()


def test_verify_rows_refuses_integers_beyond_doubles():
    batch = batch_rows(_S, _P)
    H = batch.Hn.copy()
    H[1, 1] = 2.0 ** 60
    assert verify_rows(IntegerData.of(_S, _P), H, batch.Yn, batch.Ln, batch.D) is None


_DENSE = (ei.LinearSystem([[-1, Fraction(1, 3)], [0, -2]]),
          ei.Polyhedron([[1, 1], [1, -1], [-1, 2], [-2, -1], [3, 1]], [2, 3, 5, 7, 11]))


@pytest.mark.parametrize("field, forge", [
    ("h", lambda r: tuple(v + 1 for v in r.h)),
    ("h", lambda r: tuple(-abs(v) - 1 for v in r.h)),
    ("w", lambda r: r.w[:-1] + (-r.w[-1] - 1,)),
    ("w", lambda r: (r.w[0] + 1,) + r.w[1:]),
    ("d", lambda r: r.d * 2),
    ("e", lambda r: r.e * 3),
])
def test_dense_check_rejects_forged_rows(field, forge):
    S, P = _DENSE
    rows = dense_rows(S, P)
    assert rows.ok.all()
    GA = P.G_flint * S.A_flint
    for j in range(P.m):
        forged = list(rows.rows)
        forged[j] = replace(forged[j], **{field: forge(forged[j])})
        ok = _verify(S, P, GA, forged)
        assert not ok[j] and ok[[k for k in range(P.m) if k != j]].all()


# ------------------------------------------------------------- the block LP
@settings(max_examples=30, deadline=None)
@given(st.integers(1, 4), st.integers(1, 4), st.integers(1, 4), st.randoms(use_true_random=False))
def test_block_lp_answers_each_member_lp(R, N, K, rnd):
    """The K LPs  max c_k.x  s.t.  A x <= r_k, 0 <= x (bounded: A has a row of ones) in one block
    LP: each member's point is feasible and its objective is the member's own float optimum."""
    A = np.array([[rnd.randint(-3, 3) for _ in range(N)] for _ in range(R)] + [[1.0] * N])
    costs = np.array([[rnd.randint(-3, 3) for _ in range(N)] for _ in range(K)], dtype=float)
    rhss = np.array([[rnd.randint(0, 5) for _ in range(R + 1)] for _ in range(K)], dtype=float)
    nonneg = np.ones((K, N), dtype=bool)
    equality = np.zeros(R + 1, dtype=bool)
    hint = block_hints(A, equality, costs, rhss, nonneg)
    assert hint.status == "optimal"
    for k in range(K):
        alone = block_hints(A, equality, costs[k:k + 1], rhss[k:k + 1], nonneg[k:k + 1])
        x, y = hint.X[k], hint.Y[k]
        assert np.all(A @ x <= rhss[k] + 1e-7) and np.all(x >= -1e-9) and np.all(y >= -1e-9)
        assert abs(costs[k] @ x - costs[k] @ alone.X[0]) <= 1e-7 * (1 + abs(costs[k] @ x))
        assert abs(costs[k] @ x - rhss[k] @ y) <= 1e-7 * (1 + abs(costs[k] @ x))  # strong duality


def test_block_lp_with_an_infeasible_member_gives_no_answer():
    A, equality = np.array([[1.0], [-1.0]]), np.zeros(2, dtype=bool)
    rhss = np.array([[1.0, 0.0], [1.0, -2.0]])  # member 1: x <= 1 and x >= 2
    assert block_hints(A, equality, np.ones((2, 1)), rhss, np.ones((2, 1), dtype=bool)).status == "unknown"
