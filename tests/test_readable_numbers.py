"""Exact numbers as a user reads them: certified significant digits, tight
enclosures of every threshold, polynomials in plain text (issue 12)."""

import math
from fractions import Fraction

import pytest

import exactinv as ei
from exactinv.core.digits import significant_digits
from exactinv.core.polys import poly_text
from exactinv.core.real_algebraic import RealAlgebraic
from exactinv.interfaces.pipeline import exact_text

SQRT2 = RealAlgebraic.from_isolating_interval([-2, 0, 1], 1, 2)
BOX_S = ei.LinearSystem([[-1, 1], [-1, -1]])
BOX = ei.Polyhedron.box([-1, -1], [1, 1])
DIAMOND = ei.Polyhedron.from_vertices([[1, 0], [0, 1], [-1, 0], [0, -1]])


@pytest.mark.parametrize("scale, text", [
    (Fraction(1), "1.4142135623730950"),
    (Fraction(1, 10**7), "1.4142135623730950e-7"),
    (Fraction(1, 10**30), "1.4142135623730950e-30"),
    (Fraction(1, 1000), "0.0014142135623730950"),
    (Fraction(10**20), "1.4142135623730950e20"),
    (Fraction(-1, 10**7), "-1.4142135623730950e-7"),
])
def test_significant_digits_never_leading_zeros(scale, text):
    assert str(SQRT2 * scale) == text


def test_every_printed_digit_is_certified():
    x = SQRT2 / 7 * Fraction(1, 10**9)  # 2.0203050891044214e-10
    for digits in range(1, 25):
        shown = Fraction(x.certified_digits(digits))
        unit = Fraction(10) ** (-10 - digits + 1)
        assert shown < x < shown + unit  # the value lies in [shown, shown + one unit of the last digit)


def test_significant_digits_of_an_enclosure():
    assert significant_digits(Fraction(1), Fraction(2), 3) is None  # too wide to certify
    assert significant_digits(Fraction(25127452049785885, 10**23), Fraction(251274520497858855, 10**24)) \
        == "2.5127452049785885e-7"


def test_polynomials_print_cleanly():
    assert poly_text([-12, 12, -6, 0, 1]) == "x^4 - 6x^2 + 12x - 12"
    assert "x^4 - 6x^2 + 12x - 12" in exact_text(ei.largest_threshold(BOX_S, BOX, ei.methods.taylor(4)).value)
    assert "x^2 - 2" in repr(SQRT2)


@pytest.mark.parametrize("P, method", [(DIAMOND, ei.methods.taylor(2)), (BOX, ei.methods.taylor(4)),
                                        (BOX, ei.methods.taylor(2))])
def test_threshold_enclosures_are_tight_and_lower_is_valid(P, method):
    L = ei.largest_threshold(BOX_S, P, method)
    assert isinstance(L.value, RealAlgebraic)
    assert 0 < L.lower < L.value < L.upper
    # lower and upper are adjacent doubles (the value is irrational, so neither equals it)
    assert float(L.lower) == L.lower and float(L.upper) == L.upper
    assert math.nextafter(float(L.lower), math.inf) == float(L.upper)
    assert ei.discrete_invariance(BOX_S, P, method, L.lower).holds
    L.value.tidy()  # a wide, decimal enclosure for a report does not loosen .lower/.upper
    assert math.nextafter(float(L.lower), math.inf) == float(L.upper)


def test_a_rational_threshold_that_is_not_attained_has_lower_below_it():
    S = ei.LinearSystem([[-1, 2], [0, 1]])
    orthant = ei.Polyhedron([[-1, 0], [0, -1]], [0, 0])
    L = ei.largest_threshold(S, orthant, ei.methods.backward_euler())
    assert L.value == 1 and not L.attained
    assert L.lower < 1 == L.upper and L.lower == Fraction(math.nextafter(1.0, 0))   # the double below 1
    assert L.safe_float == L.lower
    assert ei.discrete_invariance(S, orthant, ei.methods.backward_euler(), L.lower).holds
    t = ei.steplength_threshold(BOX_S, BOX, ei.methods.taylor(3))
    assert t.attained and t.lower == t.upper == 1


def test_small_thresholds_print_in_scientific_notation():
    S = ei.LinearSystem([["-1000000", "1000000"], ["-1000000", "-1000000"]])
    L = ei.largest_threshold(S, DIAMOND, ei.methods.taylor(2))
    assert str(L.value) == "1.4142135623730950e-6"
    assert "e-6" in exact_text(L.value) and "0.000" not in exact_text(L.value).split("(")[0]
