"""exactinv_check.conditions: D(h) = det h_r(hA) and N(h) = D(h) r(hA), rebuilt in integers, against r(hA)
computed from its definition in Fractions (Horner on matrices, then a solve) at rational h."""

from fractions import Fraction as F

from hypothesis import given
from hypothesis import strategies as st

from exactinv_check import poly_arithmetic as pa
from exactinv_check.budget import WORK_BUDGET
from exactinv_check.conditions import method_matrices, method_matrix_at, rebuild_size
from exactinv_check.rationals import determinant, solve

small = st.fractions(min_value=-3, max_value=3, max_denominator=4)


def _poly_at_matrix(c, X):
    """c(X) = sum c_k X^k by Horner, in Fractions."""
    n = len(X)
    out = [[F(0)] * n for _ in range(n)]
    for ck in reversed(c):
        out = [[sum(out[i][k] * X[k][j] for k in range(n)) + (ck if i == j else 0) for j in range(n)] for i in range(n)]
    return out


def _r_of(A, num, den, h):
    X = [[h * a for a in row] for row in A]
    H = _poly_at_matrix(den, X)
    return None if determinant(H) == 0 else solve(H, _poly_at_matrix(num, X))


methods = st.sampled_from([([1, 1], [1]), ([1, 1, F(1, 2)], [1]), ([1, F(1, 2)], [1, F(-1, 2)]), ([1], [1, -1]),
                           ([1, F(1, 3)], [1, F(-2, 3), F(1, 6)])])


# ------------------------------------------------------------------ soundness
@given(st.integers(1, 3).flatmap(lambda n: st.lists(st.lists(small, min_size=n, max_size=n), min_size=n,
                                                    max_size=n)), methods, st.fractions(0, 3, max_denominator=5))
def test_D_and_N_agree_with_r_of_hA_by_definition(A, method, h):
    num, den = [F(c) for c in method[0]], [F(c) for c in method[1]]
    D, N = method_matrices(A, num, den)
    r = _r_of(A, num, den, h)
    d = pa.evaluate(D, h)
    assert (d == 0) == (r is None)
    n = len(A)
    Nh = [[sum(h ** k * Nk[i][j] for k, Nk in enumerate(N)) for j in range(n)] for i in range(n)]
    if r is not None:
        assert all(Nh[i][j] == d * r[i][j] for i in range(n) for j in range(n))
        assert method_matrix_at(A, num, den, h) == r


# ------------------------------------------------------------------ resources
def test_the_rebuild_is_priced_by_its_size_before_anyone_runs_it():
    # the callers (claims, routes) compare rebuild_size's cost with the budget before method_matrices runs
    small = [[F(1), F(2)], [F(-3), F(1, 2)]]
    big = [[F(10**1000 + k, 3) for k in range(20)] for _ in range(20)]  # 20 x 20, 1000-digit entries
    taylor40 = [F(1, k + 1) for k in range(41)]
    assert rebuild_size(small, [F(1), F(1)], [F(1)])[0] < WORK_BUDGET
    assert rebuild_size(big, taylor40, [F(1)])[0] > WORK_BUDGET
    costs = [rebuild_size([[F(10**k + 1, 3)] * 4] * 4, taylor40, [F(1)])[0] for k in (10, 100, 1000)]
    assert costs == sorted(costs) and costs[0] < costs[-1]  # longer numbers, a higher price
