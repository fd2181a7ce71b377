import math
from decimal import Decimal
from fractions import Fraction

import flint
import numpy as np
import pytest
import sympy

import exactinv as ei
from exactinv.core.scalars import INF, exact_from_float, nearest_rational, to_matrix, to_rational, to_vector


@pytest.mark.parametrize(
    "value, expected",
    [
        (3, Fraction(3)),
        (Fraction(3, 4), Fraction(3, 4)),
        ("3/4", Fraction(3, 4)),
        ("-2", Fraction(-2)),
        ("0.1", Fraction(1, 10)),
        (" 1e-3 ", Fraction(1, 1000)),
        (Decimal("0.25"), Fraction(1, 4)),
        (sympy.Rational(5, 7), Fraction(5, 7)),
        (sympy.Integer(-4), Fraction(-4)),
        (flint.fmpq(2, 9), Fraction(2, 9)),
        (flint.fmpz(11), Fraction(11)),
        (np.int64(6), Fraction(6)),
    ],
)
def test_exact_scalars(value, expected):
    assert to_rational(value) == expected
    assert type(to_rational(value)) is Fraction


def test_float_refused_with_advice():
    with pytest.raises(ei.InvalidInput, match=r"A\[0\]\[1\].*float.*'0.1'.*exact_from_float"):
        ei.LinearSystem([[1, 0.1], [0, 1]])
    with pytest.raises(ei.InvalidInput, match="float"):
        to_rational(np.float64(0.5))


def test_float_opt_in_is_exact():
    assert to_rational(0.1, allow_float=True) == Fraction(3602879701896397, 36028797018963968)
    assert exact_from_float(0.5) == Fraction(1, 2)
    assert nearest_rational(0.1) == Fraction(1, 10)
    assert ei.LinearSystem([[0.5]], allow_float=True).A == ((Fraction(1, 2),),)


@pytest.mark.parametrize("bad", ["nan", "inf", "-Infinity", Decimal("NaN"), float("nan"), "abc", "1/0", True, None,
                                 sympy.sqrt(2)])
def test_bad_scalars(bad):
    with pytest.raises(ei.ExactinvError):
        to_rational(bad, "x")


def test_errors_are_value_errors():
    assert issubclass(ei.ExactinvError, ValueError)
    with pytest.raises(ValueError):
        to_rational("x")


def test_matrix_shapes_are_named():
    with pytest.raises(ei.InvalidInput, match=r"ragged.*row 1"):
        to_matrix([[1, 2], [3]], "A")
    with pytest.raises(ei.InvalidInput, match="square.*2x3"):
        to_matrix([[1, 2, 3], [4, 5, 6]], "A", square=True)
    with pytest.raises(ei.InvalidInput, match="empty"):
        to_matrix([], "A")
    with pytest.raises(ei.InvalidInput, match="expected length 3"):
        to_vector([1, 2], "b", length=3)
    assert to_matrix(np.array([[1, 2], [3, 4]]), "A")[1][0] == 3
    assert to_matrix(flint.fmpq_mat([[1, 2], [3, 4]]), "A")[0][1] == 2


def test_infinity():
    assert -INF < -10**100 < Fraction(1, 3) < INF
    minus_inf = -INF
    assert -minus_inf is INF
    assert float(INF) == math.inf and INF == math.inf
    assert max([Fraction(2), INF, -INF], key=lambda v: (v > 10**9, v if not isinstance(v, ei.Infinity) else 0)) is INF
    assert sorted([INF, Fraction(1), -INF]) == [-INF, Fraction(1), INF]
    r = ei.real_roots([-2, 0, 1])[1][0]
    assert r < INF and -INF < r
