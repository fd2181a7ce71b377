from fractions import Fraction

import flint
from hypothesis import given
from hypothesis import strategies as st

import numpy as np

from exactinv.core.scalars import INF
from exactinv.lp import ExactLPSolver, solve_lp
from exactinv.lp.exact import ppl_maximize
from exactinv.lp.hint import UNKNOWN_HINT, Hint, HighsHint, HintBackend, HintModel, LPStatus
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
    res = solve_lp(flint.fmpq_mat(A), eq, b, c, nonneg, hint)
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
    off = _Scripted(lambda h: Hint(h.status, h.x + 3e-7, h.y + 3e-7, h.basis))
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
        res = _solve([[3, 1], [1, 3]], [False, False], [1, 1], [1, 1], [True, True], hint=_Scripted(lambda h: Hint(lie)))
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
