from fractions import Fraction

import flint
import pytest
import sympy
from hypothesis import given
from hypothesis import strategies as st

import exactinv as ei
from exactinv.core.polys import count_real_roots, sign_right_of
from exactinv.core.roots import first_sign_change, nonnegative_until, real_roots


def poly(*factors):
    out = flint.fmpq_poly([1])
    for f in factors:
        out *= flint.fmpq_poly(f)
    return out


def test_tangent_roots_are_stepped_over():
    assert first_sign_change(poly([-1, 1], [-1, 1], [-2, 1], [-2, 1])) == ei.INF  # paper 3.3.1
    assert first_sign_change(poly([-1, 1], [-1, 1], [-3, 1])) == 3
    assert first_sign_change(poly([-1, 1], [-1, 1], [-1, 1], [-3, 1])) == 1  # odd multiplicity 3


def test_multiplicities_and_rational_roots():
    f = poly([-1, 1], [-1, 1], [1, 2], [-2, 0, 1], [-2, 0, 1], [-2, 0, 1])
    roots = real_roots(f)
    values = [r for r, _ in roots]
    assert [m for _, m in roots] == [3, 1, 2, 3]
    assert values[1] == Fraction(-1, 2) and values[2] == 1
    assert isinstance(values[1], Fraction) and isinstance(values[0], ei.RealAlgebraic)
    assert values[0] < -1 < values[1] < values[2] < values[3] < 2


def test_no_positive_root_and_constants():
    assert first_sign_change([1, 2, 3]) == ei.INF  # nonnegative coefficients
    assert first_sign_change([1, 0, 1]) == ei.INF
    assert first_sign_change([5]) == ei.INF and first_sign_change([0]) == ei.INF
    assert first_sign_change([-5]) == ei.INF
    assert nonnegative_until([-5]) == 0 and nonnegative_until([5]) == ei.INF
    assert first_sign_change(poly([1, 1], [2, 1])) == ei.INF  # roots -1, -2 only


def test_start_parameter_and_sign_right():
    f = poly([-1, 1], [-2, 1], [-3, 1])
    assert first_sign_change(f, 1) == 2 and first_sign_change(f, "5/2") == 3 and first_sign_change(f, 3) == ei.INF
    assert sign_right_of(f, 1) == 1 and sign_right_of(poly([0, 1], [0, 1]), 0) == 1
    assert nonnegative_until([0, -1]) == 0  # f = -t is negative right after 0
    assert nonnegative_until([0, 0, 1, -1]) == 1  # t^2 (1 - t)


def test_huge_coefficients():
    big = 3**90
    f = poly([-big, big + 1], [-1, 1], [-7 * 2**200, 0, 2**201 + 1])  # roots just below 1 and sqrt(7/2)
    r = first_sign_change(f)
    assert r == Fraction(big, big + 1)
    assert first_sign_change(f, r) == 1
    third = first_sign_change(f, 1)
    assert isinstance(third, ei.RealAlgebraic) and Fraction(187, 100) < third < Fraction(188, 100)


def test_degree_60():
    roots = [Fraction(k, 7) for k in range(1, 31)]
    f = poly(*[[-r.numerator, r.denominator] for r in roots], *[[k, 0, 1] for k in range(1, 16)])
    assert f.degree() == 60
    assert first_sign_change(f) == Fraction(1, 7)
    g = flint.fmpz_poly([(k * 7919) % 257 - 128 for k in range(61)])
    expected = sorted(r for r in sympy.Poly(list(reversed([int(c) for c in g.coeffs()])), sympy.Symbol("x")).real_roots())
    ours = [r for r, _ in real_roots(g)]
    assert len(ours) == len(expected)
    for a, b in zip(ours, expected):  # sympy's exact CRootOf lies in our isolating interval
        lo, hi = (sympy.Rational(a.lower.numerator, a.lower.denominator),
                  sympy.Rational(a.upper.numerator, a.upper.denominator))
        assert bool(lo < b) and bool(b < hi)


def test_count_real_roots():
    assert count_real_roots([-2, 0, 1]) == 2
    assert count_real_roots([-2, 0, 1], 0, 2) == 1
    assert count_real_roots([1, 0, 1]) == 0


@given(st.lists(st.fractions(min_value=-5, max_value=5, max_denominator=9), min_size=1, max_size=6),
       st.lists(st.integers(1, 3), min_size=6, max_size=6))
def test_first_sign_change_matches_definition(roots, mults):
    f = poly(*[[-r.numerator, r.denominator] for r, m in zip(roots, mults) for _ in range(m)])
    odd = sorted({r for r, m in zip(roots, mults) if r > 0 and sum(mm for rr, mm in zip(roots, mults) if rr == r) % 2 == 1})
    expected = odd[0] if odd else ei.INF
    assert first_sign_change(f) == expected


def test_bad_polynomials():
    with pytest.raises(ei.InvalidInput):
        first_sign_change("x^2")
    with pytest.raises(ei.InvalidInput):
        real_roots([0, 0])
    with pytest.raises(ei.InvalidInput, match="float"):
        first_sign_change([1, 0.5])
