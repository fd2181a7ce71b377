"""The fast exact batch check (integers carried by doubles) agrees with the FLINT one."""

from fractions import Fraction
from math import lcm

import flint
import numpy as np
from hypothesis import given, settings
from hypothesis import strategies as st

from exactinv.lp import solve_lp
from exactinv.lp.verify import LPData, optimal_values
from exactinv.lp.verify_int import integer_image, optimal_values_int

small = st.integers(-4, 4)


def _column(values):
    return [flint.fmpq(Fraction(v).numerator, Fraction(v).denominator) for v in values]


@settings(max_examples=40, deadline=None)
@given(st.integers(1, 3).flatmap(lambda n: st.tuples(
    st.lists(st.lists(small, min_size=n, max_size=n), min_size=1, max_size=4),
    st.lists(st.lists(small, min_size=n, max_size=n), min_size=1, max_size=3),
    st.lists(st.booleans(), min_size=n, max_size=n))), st.data())
def test_fast_check_agrees_with_flint(data, draw):
    A, costs, nonneg = data
    R, N = len(A), len(A[0])
    eq = draw.draw(st.lists(st.booleans(), min_size=R, max_size=R))
    b = draw.draw(st.lists(small, min_size=R, max_size=R))
    columns = []  # (c, x, y): optimal pairs from the engine, then each perturbed by 1/d
    for c in costs:
        res = solve_lp(flint.fmpq_mat(A), eq, b, c, nonneg)
        if res.status == "optimal":
            columns.append((c, res.x, res.y))
            columns.append((c, res.x[:-1] + (res.x[-1] + Fraction(1, 7),), res.y))  # mostly not optimal
    if not columns:
        return
    K = len(columns)
    d = lcm(*(Fraction(v).denominator for _, x, y in columns for v in x + y))
    Xn = np.array([[float(v * d) for v in x] for _, x, _ in columns]).T
    Yn = np.array([[float(v * d) for v in y] for _, _, y in columns]).T
    C = flint.fmpq_mat(K, N, [v for c, _, _ in columns for v in _column(c)]).transpose()
    B = flint.fmpq_mat(K, R, [v for _ in columns for v in _column(b)]).transpose()
    X = flint.fmpq_mat(K, N, [v for _, x, _ in columns for v in _column(x)]).transpose()
    Y = flint.fmpq_mat(K, R, [v for _, _, y in columns for v in _column(y)]).transpose()
    lp = LPData(flint.fmpq_mat(A), tuple(eq))
    signs = [tuple(nonneg)] * K
    fast = optimal_values_int(lp, C, B, signs, Xn, Yn, d)
    assert fast == optimal_values(lp, C, B, signs, X, Y)
    assert all(v is not None for v in fast[::2])  # the engine's optima verify


def test_a_point_off_the_optimum_is_rejected():
    # max x1 + x2 s.t. 3x1 + x2 <= 1, x1 + 3x2 <= 1, x >= 0: x = y = (1/4, 1/4), value 1/2
    lp = LPData(flint.fmpq_mat([[3, 1], [1, 3]]), (False, False))
    C = B = flint.fmpq_mat([[1, 1, 1], [1, 1, 1]])
    Xn = np.array([[7.0, 7.0, 0.0], [7.0, 8.0, 0.0]])  # over d = 28: (1/4, 1/4), (1/4, 2/7), (0, 0)
    Yn = np.array([[7.0, 7.0, 7.0], [7.0, 7.0, 7.0]])
    values = optimal_values_int(lp, C, B, [(True, True)] * 3, Xn, Yn, 28)
    assert values == [flint.fmpq(1, 2), None, None]  # infeasible (3/4 + 2/7 > 1); objectives 0 != 1/2


def test_integers_beyond_2_to_53_take_the_flint_route():
    lp = LPData(flint.fmpq_mat([[1]]), (False,))
    one = flint.fmpq_mat([[1]])
    assert optimal_values_int(lp, one, one, [(False,)], np.array([[2.0 ** 53]]), np.array([[1.0]]), 1) is None
    big = LPData(flint.fmpq_mat([[3 ** 40]]), (False,))  # 3^40 * 3^(-40): products beyond 2^53
    assert optimal_values_int(big, one, flint.fmpq_mat([[1]]), [(False,)], np.array([[1.0]]), np.array([[1.0]]),
                              3 ** 40) is None
    assert integer_image(flint.fmpq_mat([[10 ** 400]])) is None
