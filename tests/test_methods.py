from fractions import Fraction
from math import factorial

import pytest
import sympy

import exactinv as ei
from exactinv import methods as M

z = sympy.Symbol("z")


@pytest.mark.parametrize("method, expected", [
    (M.forward_euler(), 1 + z),
    (M.backward_euler(), 1 / (1 - z)),
    (M.trapezoid(), (1 + z / 2) / (1 - z / 2)),
    (M.theta("1/3"), (1 + sympy.Rational(2, 3) * z) / (1 - z / 3)),
    (M.heun(), 1 + z + z**2 / 2),
    (M.ssprk22(), 1 + z + z**2 / 2),
    (M.ssprk33(), 1 + z + z**2 / 2 + z**3 / 6),
    (M.rk4(), sum(z**k / factorial(k) for k in range(5))),
    (M.ssprk_s1(3), (1 + z / 3) ** 3),
    (M.radau_iia2(), (1 + z / 3) / (1 - 2 * z / 3 + z**2 / 6)),
    (M.lobatto_iiic2(), 1 / (1 - z + z**2 / 2)),
    (M.gauss2(), (1 + z / 2 + z**2 / 12) / (1 - z / 2 + z**2 / 12)),
    (M.pade(2, 2), (1 + z / 2 + z**2 / 12) / (1 - z / 2 + z**2 / 12)),
    (M.pade(0, 1), 1 / (1 - z)),
    (M.pade(3, 0), 1 + z + z**2 / 2 + z**3 / 6),
    (M.implicit_midpoint(), (1 + z / 2) / (1 - z / 2)),
])
def test_stability_functions(method, expected):
    assert sympy.simplify(method.to_sympy(z) - expected) == 0
    assert method(0) == 1


def test_pade_matches_exp_to_order():
    for k in range(4):
        for l in range(4):
            r = M.pade(k, l).to_sympy(z)
            series = sympy.series(r - sympy.exp(z), z, 0, k + l + 2).removeO()
            assert all(series.coeff(z, j) == 0 for j in range(k + l + 1))


def test_common_factors_cancel_and_normalisation():
    m = M.rational([2, 2], [2, 0, -2])  # (2 + 2z)/(2 - 2z^2) = 1/(1 - z)
    assert m.numerator == (1,) and m.denominator == (1, -1)


def test_matrix_evaluation():
    A = [[-1, 2], [0, 1]]
    Ad = M.backward_euler().matrix(A, "1/2")
    assert Ad == ((Fraction(2, 3), Fraction(4, 3)), (0, 2))
    with pytest.raises(ei.InvalidInput, match="singular"):
        M.backward_euler().matrix(A, 1)
    assert M.taylor(2).matrix([[-1, 1], [-1, -1]], 1) == ((0, 0), (0, 0))


@pytest.mark.parametrize("call, message", [
    (lambda: M.polynomial([2, 1]), "sigma_0 must be 1"),
    (lambda: M.polynomial([1, 0.5]), "float"),
    (lambda: M.taylor(0), "order"),
    (lambda: M.rational([2], [1, 1]), "r\\(0\\) must be 1"),
    (lambda: M.rational([1], [0, 1]), "vanishes at z = 0"),
    (lambda: M.rational([1], [0]), "zero polynomial"),
    (lambda: M.theta(2), "theta"),
    (lambda: M.pade(-1, 2), "k"),
    (lambda: M.from_butcher([[0, 0], [1, 0]], [1]), "length 2"),
    (lambda: M.preset("rk45"), "unknown method"),
    (lambda: M.backward_euler()(1), "pole"),
])
def test_bad_methods(call, message):
    with pytest.raises(ei.InvalidInput, match=message):
        call()


def test_latex():
    assert M.trapezoid()._repr_latex_().startswith("$r(z) = ")
