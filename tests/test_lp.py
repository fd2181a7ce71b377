from fractions import Fraction

import flint
import numpy as np
from hypothesis import given
from hypothesis import strategies as st

from exactinv.core.scalars import INF
from exactinv.lp import solve_lp
from exactinv.lp.backends import HighsHint
from exactinv.lp.exact import ppl_maximize
from exactinv.lp.hint_types import UNKNOWN_HINT, Hint, HintBackend, HintModel, LPStatus
from exactinv.lp.reconstruct import basis_solution, exact_pivots
from exactinv.lp.verify import LPData, verify_optimal


class _Scripted(HintBackend):
    """A hint backend that answers every LP with ``answer(highs_hint)``."""

    def __init__(self, answer):
        self.answer = answer

    def model(self, A, equality):
        inner, answer = HighsHint().model(A, equality), self.answer

        class _Model(HintModel):
            def solve(self, cost, rhs, nonneg):
                return answer(inner.solve(cost, rhs, nonneg))

        return _Model()


def _col(values):
    return flint.fmpq_mat(len(values), 1, [flint.fmpq(v.numerator, v.denominator) for v in map(Fraction, values)])


def _verify(A, eq, b, c, nonneg, res):
    """Independent re-check of a returned certificate with Fractions."""
    R, N = len(A), len(A[0])
    if res.status == "optimal":
        x, y = res.x, res.y
        for r in range(R):
            ax = sum(A[r][i] * x[i] for i in range(N))
            assert ax == b[r] if eq[r] else ax <= b[r]
            if not eq[r]:
                assert y[r] >= 0
        for i in range(N):
            red = sum(A[r][i] * y[r] for r in range(R)) - c[i]
            assert red >= 0 if nonneg[i] else red == 0
            if nonneg[i]:
                assert x[i] >= 0
        assert sum(ci * xi for ci, xi in zip(c, x)) == sum(bi * yi for bi, yi in zip(b, y)) == res.value
    elif res.status == "infeasible":
        y = res.y
        assert sum(bi * yi for bi, yi in zip(b, y)) < 0
        for i in range(N):
            s = sum(A[r][i] * y[r] for r in range(R))
            assert s >= 0 if nonneg[i] else s == 0
    else:
        d = res.ray
        assert sum(ci * di for ci, di in zip(c, d)) > 0
        for r in range(R):
            ad = sum(A[r][i] * d[i] for i in range(N))
            assert ad == 0 if eq[r] else ad <= 0


def _solve(A, eq, b, c, nonneg, hint=None):
    exact = [[flint.fmpq(Fraction(v).numerator, Fraction(v).denominator) for v in row] for row in A]
    res = solve_lp(flint.fmpq_mat(exact), eq, b, c, nonneg, hint)
    _verify(A, eq, b, c, nonneg, res)
    return res


def test_optimal_with_thirds():
    res = _solve([[3, 1], [1, 3]], [False, False], [1, 1], [1, 1], [True, True])
    assert res.status == "optimal" and res.value == Fraction(1, 2)
    assert res.x == (Fraction(1, 4), Fraction(1, 4))


def test_infeasible_has_farkas():
    res = _solve([[1, 1], [-1, -1]], [False, False], [1, -2], [1, 0], [True, True])
    assert res.status == "infeasible"


def test_unbounded_has_ray():
    res = _solve([[1, -1], [-1, 0]], [False, False], [1, 0], [1, 1], [False, False])
    assert res.status == "unbounded" and res.value == INF


def test_basis_solve_when_rounding_fails():
    # the hint's floats pushed 3e-7 off the vertex: rounding cannot verify, the basis solve does
    off = _Scripted(lambda h: Hint(h.status, h.x + 3e-7, h.y + 3e-7, h.fetch_basis()))
    res = _solve([[7, 3], [2, 9]], [False, False], [Fraction(1, 3), Fraction(2, 7)], [1, 1], [True, True], hint=off)
    assert res.path == "float-basis"


def test_basis_solution_is_the_exact_vertex():
    data = LPData(flint.fmpq_mat([[7, 3], [2, 9]]), (False, False))
    b, c = _col([Fraction(1, 3), Fraction(2, 7)]), _col([1, 1])
    x, y = basis_solution(data, c, b, ((0, 1), (0, 1)))
    # 7x1 + 3x2 = 1/3, 2x1 + 9x2 = 2/7  =>  x = (1/57 * (3 - 6/7), ...) checked by substitution
    assert 7 * x[0, 0] + 3 * x[1, 0] == flint.fmpq(1, 3) and 2 * x[0, 0] + 9 * x[1, 0] == flint.fmpq(2, 7)
    assert y.entries() == [flint.fmpq(7, 57), flint.fmpq(4, 57)]
    assert verify_optimal(data, c, b, (True, True), x, y)
    assert basis_solution(data, c, b, ((0, 1), (0,))) is None  # not square: no vertex


def test_exact_fallback_when_float_hint_is_useless():
    # an "optimal" hint at a wrong point with a basis that is not a vertex: nothing to reconstruct
    useless = _Scripted(lambda h: Hint(LPStatus.OPTIMAL, np.zeros(2), np.zeros(2), ((0, 1), (0,))))
    res = _solve([[7, 3], [2, 9]], [False, False], [Fraction(1, 3), Fraction(2, 7)], [1, 1], [True, True], hint=useless)
    assert res.path == "exact-ppl"
    # dual: 7y1 + 2y2 = 1, 3y1 + 9y2 = 1  =>  y = (7/57, 4/57)
    assert res.value == Fraction(1, 3) * Fraction(7, 57) + Fraction(2, 7) * Fraction(4, 57)


def test_exact_fallback_when_float_solver_gives_up():
    gives_up = _Scripted(lambda h: UNKNOWN_HINT)
    for status, data in [
        ("optimal", ([[1, 2]], [False], [4], [1, 1], [True, True])),
        ("infeasible", ([[1], [-1]], [False, False], [0, -1], [1], [False])),
        ("unbounded", ([[1, -1]], [False], [0], [1, 1], [True, True])),
    ]:
        res = _solve(*data, hint=gives_up)
        assert res.status == status


def test_lying_hints_cannot_change_the_answer():
    """A backend that calls every LP infeasible (or unbounded) still yields the verified answer."""
    for lie in (LPStatus.INFEASIBLE, LPStatus.UNBOUNDED):
        res = _solve([[3, 1], [1, 3]], [False, False], [1, 1], [1, 1], [True, True], hint=_Scripted(lambda h, lie=lie: Hint(lie)))
        assert res.status == "optimal" and res.value == Fraction(1, 2)


small = st.integers(-4, 4)


@given(st.integers(1, 4).flatmap(lambda n: st.tuples(
    st.lists(st.lists(small, min_size=n, max_size=n), min_size=1, max_size=5),
    st.lists(small, min_size=n, max_size=n),
    st.lists(st.booleans(), min_size=n, max_size=n),
)), st.data())
def test_random_lps_match_exact_ppl(data, draw):
    A, c, nonneg = data
    b = draw.draw(st.lists(small, min_size=len(A), max_size=len(A)))
    eq = draw.draw(st.lists(st.booleans(), min_size=len(A), max_size=len(A)))
    res = _solve(A, eq, b, c, nonneg)
    status, x = ppl_maximize(flint.fmpq_mat(A), eq, flint.fmpq_mat(len(b), 1, b), flint.fmpq_mat(len(c), 1, c), nonneg)
    assert res.status == status
    if status == "optimal":
        assert res.value == sum(ci * Fraction(int(xi.p), int(xi.q)) for ci, xi in zip(c, x.entries()))


def test_coefficients_beyond_double_range_take_the_exact_route():
    big = 10**400
    res = _solve([[big, 1], [1, -1]], [False, False], [4 * big, 1], [1, 2], [True, True])
    assert res.status == "optimal" and res.value == 8 * big and res.path == "exact-ppl"


def test_exact_pivots_repair_a_wrong_basis():
    """A float basis that is feasible but not optimal is repaired by exact simplex steps."""
    A = [[1, 1], [1, -1], [-1, 0], [0, -1]]
    data = LPData(flint.fmpq_mat(A), (False,) * 4)
    c, b = _col([1, 2]), _col([4, 1, 0, 0])
    basis = ((0, 1), (1, 3))  # basic columns 0, 1; the vertex (1, 0): tight rows 1 and 3
    x, y = exact_pivots(data, c, b, (False, False), basis)
    assert [v for v in x.entries()] == [0, 4]  # the optimum, reached by pivoting
    assert verify_optimal(data, c, b, (False, False), x, y)


def test_badly_scaled_rows_still_get_a_float_hint():
    big = 10**15
    res = _solve([[big, big], [1, -1], [-3 * big, 0]], [False] * 3, [4 * big, 1, 0], [1, 2], [False, False])
    assert res.status == "optimal" and res.path != "exact-ppl"


# ------------------------------------------------------------- issue 13, item 5
# Rows scaled by 10^k (|k| <= 30) describe the same polyhedron; the engine must end
# in the verified answer (never a RecursionError), equal to pplpy's on the unscaled rows.
from math import gcd  # noqa: E402

import ppl  # noqa: E402
import pytest  # noqa: E402
from hypothesis import settings  # noqa: E402

import exactinv as ei  # noqa: E402


def _ppl_max(G, b, c, nonneg=None, eq=None):
    """pplpy's exact max of c.x over {G x (= | <=) b, x_i >= 0 (nonneg)}: ('optimal', value) or the status."""
    n = len(c)
    cs = ppl.Constraint_System()
    for r, (row, rhs) in enumerate(zip(G, b)):
        d = 1
        for v in list(row) + [rhs]:
            d = d * Fraction(v).denominator // gcd(d, Fraction(v).denominator)
        expr = ppl.Linear_Expression([int(Fraction(v) * d) for v in row], -int(Fraction(rhs) * d))
        cs.insert(expr == 0 if eq and eq[r] else expr <= 0)
    for i in range(n):
        if nonneg and nonneg[i]:
            cs.insert(ppl.Variable(i) >= 0)
    d = 1
    for v in c:
        d = d * Fraction(v).denominator // gcd(d, Fraction(v).denominator)
    mip = ppl.MIP_Problem(n, cs, ppl.Linear_Expression([int(Fraction(v) * d) for v in c], 0), "maximization")
    status = mip.solve()["status"]
    if status != "optimized":
        return "infeasible" if status == "unfeasible" else "unbounded", None
    value = mip.optimal_value()
    return "optimal", Fraction(int(value.numerator), int(value.denominator)) / d


def _reference_gamma(G, b, A):
    """gamma* by pplpy, row by row: max_j -max{h_j : h^T G = g_j^T A, h^T b <= 0, h_k >= 0 (k != j)}."""
    m, n = len(G), len(A)
    GA = [[sum(Fraction(G[j][k]) * A[k][i] for k in range(n)) for i in range(n)] for j in range(m)]
    rows = [[G[k][i] for k in range(m)] for i in range(n)] + [list(b)]
    best = None
    for j in range(m):
        status, value = _ppl_max(rows, GA[j] + [0], [int(k == j) for k in range(m)],
                                 [k != j for k in range(m)], [True] * n + [False])
        gamma = ei.INF if status == "infeasible" else -ei.INF if status == "unbounded" else -value
        best = gamma if best is None or gamma > best else best
    return best


_scaled_rows = st.integers(1, 3).flatmap(lambda n: st.tuples(
    st.lists(st.tuples(st.lists(st.integers(-3, 3), min_size=n, max_size=n),
                       st.fractions(-3, 3, max_denominator=3), st.integers(-30, 30)), min_size=1, max_size=5),
    st.lists(st.lists(st.integers(-2, 2), min_size=n, max_size=n), min_size=n, max_size=n),
    st.lists(st.integers(-2, 2), min_size=n, max_size=n),
))


def test_badly_scaled_empty_interval_is_verified_empty():
    """The reproduction of issue 13: P = {3x <= -2/3, -2e30 x <= 0, 1e10 x <= 2e10} is empty
    (x <= -2/9 and x >= 0); a RecursionError before the engine's auxiliary LPs were bounded."""
    G, b = [[3], [-2 * 10**30], [10**10]], [Fraction(-2, 3), 0, 2 * 10**10]
    res = _solve(G, [False] * 3, b, [1], [False])
    assert res.status == "infeasible"
    with pytest.raises(ei.EmptyPolyhedron):
        ei.optimal_gamma(ei.LinearSystem([[-1]]), ei.Polyhedron(G, b))


@settings(max_examples=60, deadline=None)
@given(_scaled_rows)
def test_rows_scaled_by_powers_of_ten_match_pplpy(data):
    rows, A, c = data
    G = [[v * Fraction(10) ** k for v in row] for row, _, k in rows]
    b = [rhs * Fraction(10) ** k for _, rhs, k in rows]
    G0, b0 = [row for row, _, _ in rows], [rhs for _, rhs, _ in rows]
    n = len(c)
    res = _solve(G, [False] * len(G), b, c, [False] * n)
    status, value = _ppl_max(G0, b0, c)
    assert res.status == status
    if status == "optimal":
        assert res.value == value
    if not all(any(row) for row in G0):
        return  # Polyhedron rejects a zero row (InvalidInput); the LP above covered it
    if status == "infeasible":
        with pytest.raises(ei.EmptyPolyhedron):
            ei.optimal_gamma(ei.LinearSystem(A), ei.Polyhedron(G, b))
    else:
        assert ei.optimal_gamma(ei.LinearSystem(A), ei.Polyhedron(G, b)).value == _reference_gamma(G0, b0, A)
