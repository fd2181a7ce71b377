import pickle
from fractions import Fraction

import pytest
import sympy

import exactinv as ei
from exactinv import RealAlgebraic


def sqrt2():
    return RealAlgebraic.from_isolating_interval([-2, 0, 1], 1, 2)


def test_exact_comparisons():
    a = sqrt2()
    assert Fraction(1414, 1000) < a < Fraction(1415, 1000)
    assert a > 1 and a < 2 and a != Fraction(3, 2) and a != 1
    b = RealAlgebraic.from_isolating_interval([-4, 0, 2], "1/2", "3")  # same number, other interval
    assert a == b and hash(a) == hash(b)
    c = RealAlgebraic.from_isolating_interval([-3, 0, 1], 1, 2)
    assert a < c and c > a and a != c
    assert a < ei.INF and a > -ei.INF


def test_scaling_and_inverse():
    a = sqrt2()
    assert a * 2 == RealAlgebraic.from_isolating_interval([-8, 0, 1], 2, 3)
    assert (a * 2) / 2 == a
    assert 1 / a == a / 2
    assert -a < 0 and -a == RealAlgebraic.from_isolating_interval([-2, 0, 1], -2, -1)
    assert a * 0 == 0


def test_refine_and_strings():
    a = sqrt2().refine(100)
    assert a.upper - a.lower <= Fraction(1, 2**100)
    assert str(a) == "1.4142135623730950"  # 17 certified significant digits
    assert abs(float(a) - 2**0.5) < 1e-15
    assert (-a).certified_digits(6) == "-1.41421"
    x = sympy.Symbol("x")
    assert a.to_sympy() == sympy.CRootOf(x**2 - 2, 1)
    assert (-a).to_sympy() == sympy.CRootOf(x**2 - 2, 0)
    assert abs(a.to_sympy().evalf(40) - sympy.sqrt(2).evalf(40)) < sympy.Rational(1, 10**35)
    assert "root of" in a._repr_latex_()
    assert pickle.loads(pickle.dumps(a)) == a


def test_validation():
    with pytest.raises(ei.InvalidInput, match="irreducible"):
        RealAlgebraic.from_isolating_interval([2, -3, 1], 0, 3)
    with pytest.raises(ei.InvalidInput, match="degree"):
        RealAlgebraic.from_isolating_interval([-1, 2], 0, 1)
    with pytest.raises(ei.InvalidInput, match="sign"):
        RealAlgebraic.from_isolating_interval([-2, 0, 1], 2, 3)
    with pytest.raises(ei.InvalidInput, match="more than one"):
        RealAlgebraic.from_isolating_interval([1, 0, -4, 0, 1], "-3/5", 3)  # roots +-0.52, +-1.93
