"""exactinv_check.poly_arithmetic: Q[x] as coefficient lists (x^0 first), against python-flint's fmpq_poly."""

from fractions import Fraction as F

import flint
import pytest
from hypothesis import given
from hypothesis import strategies as st

from exactinv_check import poly_arithmetic as pa
from exactinv_check.budget import MAX_ALGEBRAIC_DEGREE, MAX_DEGREE
from exactinv_check.failure import CheckFailure

coefficient = st.fractions(min_value=-50, max_value=50, max_denominator=12)
poly = st.lists(coefficient, min_size=0, max_size=8)


def _flint(p):
    return flint.fmpq_poly([flint.fmpq(c.numerator, c.denominator) for c in p])


def _back(q):
    return pa.trim([F(int(c.p), int(c.q)) for c in q.coeffs()])


# ------------------------------------------------------------------ soundness
@given(poly, poly)
def test_ring_operations_agree_with_flint(p, q):
    assert pa.add(p, q) == _back(_flint(p) + _flint(q))
    assert pa.sub(p, q) == _back(_flint(p) - _flint(q))
    assert pa.mul(p, q) == _back(_flint(p) * _flint(q))
    assert pa.derivative(p) == _back(_flint(p).derivative())


@given(poly, poly.filter(lambda d: any(d)))
def test_division_with_remainder_agrees_with_flint(p, d):
    quotient, remainder = pa.divmod_(p, d)
    assert pa.trim(quotient) == _back(_flint(p) // _flint(d)) and pa.trim(remainder) == _back(_flint(p) % _flint(d))
    assert len(pa.trim(remainder)) < len(pa.trim(d))


@given(poly, poly, poly)
def test_the_gcd_is_the_monic_gcd(a, b, c):
    g = pa.gcd(pa.mul(a, c), pa.mul(b, c))
    expected = _flint(a) * _flint(c)
    expected = expected.gcd(_flint(b) * _flint(c))
    assert g == (_back(expected / expected.coeffs()[-1]) if expected.degree() >= 0 else [])


@given(poly, st.fractions(min_value=-9, max_value=9, max_denominator=9))
def test_evaluation_and_integer_coefficients_keep_the_value_and_signs(p, x):
    value = _flint(p)(flint.fmpq(x.numerator, x.denominator))
    assert pa.evaluate(p, x) == F(int(value.p), int(value.q))
    ints = pa.integer_coefficients(p)
    assert all(isinstance(c, int) for c in ints)
    if pa.trim(p):  # a positive multiple: the same sign everywhere
        assert pa.sign(pa.evaluate(ints, x)) == pa.sign(pa.evaluate(p, x))


def test_strip_zero_roots_and_exact_quotient_by_hand():
    assert pa.strip_zero_roots([F(0), F(0), F(3), F(1)]) == [F(3), F(1)]
    assert pa.exact_quotient([-1, 0, 1], [1, 1]) == [-1, 1]  # x^2 - 1 = (x + 1)(x - 1)
    with pytest.raises(CheckFailure):
        pa.exact_quotient([1, 0, 1], [1, 1])  # x + 1 does not divide x^2 + 1


# ------------------------------------------------------------------ resources
def test_a_polynomial_over_the_degree_bound_is_rejected_before_any_gcd():
    # gcds are charged as they run, so they take up to MAX_ALGEBRAIC_DEGREE (a genuine rho of degree 272)
    big = [F(1)] * (MAX_ALGEBRAIC_DEGREE + 2)
    with pytest.raises(CheckFailure, match="exceeds the kernel's bound"):
        pa.gcd(big, [F(1), F(1)])
    with pytest.raises(CheckFailure, match="exceeds the kernel's bound"):
        pa.bounded([F(1)] * (MAX_DEGREE + 2))
    assert pa.bounded([F(1)] * (MAX_DEGREE + 1))  # degree MAX_DEGREE itself is allowed
    assert pa.bounded([F(1)] * (MAX_ALGEBRAIC_DEGREE + 1), MAX_ALGEBRAIC_DEGREE)
