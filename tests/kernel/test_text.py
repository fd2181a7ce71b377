"""exactinv_check.text: numbers as the kernel prints them -- every printed digit certified by the exact value."""

from decimal import Decimal, localcontext
from fractions import Fraction as F

from hypothesis import given
from hypothesis import strategies as st

from exactinv_check.budget import MAX_PRINT_BISECTIONS
from exactinv_check.text import algebraic_text, decimal_text, poly_text, rational_text, significant_digits


# ------------------------------------------------------------------ soundness
@given(st.fractions(min_value=-10**6, max_value=10**6, max_denominator=10**6).filter(lambda q: q != 0))
def test_significant_digits_are_the_truncated_decimal_expansion(q):
    digits = significant_digits(q, q, 17)
    assert digits is not None
    with localcontext() as ctx:
        ctx.prec = 60
        exact = Decimal(q.numerator) / Decimal(q.denominator)
    shown = Decimal(digits)
    assert abs(shown) <= abs(exact) and abs(exact - shown) < abs(exact) * Decimal(10) ** -15  # truncated, 17 digits


def test_an_enclosure_across_a_digit_certifies_none():
    assert significant_digits(F(1999, 1000), F(2001, 1000), 3) is None  # 1.99.. or 2.00..: no common digits
    assert significant_digits(F(-1, 10), F(1, 10)) is None  # of both signs


@given(st.integers(-10**9, 10**9), st.integers(0, 6), st.integers(0, 6))
def test_a_decimal_prints_exactly_and_reads_back(n, twos, fives):
    q = F(n, 2**twos * 5**fives)
    assert F(decimal_text(q)) == q


def test_polynomials_and_long_rationals_by_hand():
    assert poly_text([-2, 0, 1]) == "x^2 - 2" and poly_text([F(1, 2), -3]) == "-3x + 1/2"
    assert rational_text(F(1, 3)) == "1/3" and rational_text(F(10**70 + 1)).startswith("a 71-digit integer")


def test_a_root_prints_its_certified_digits():
    text = algebraic_text([-2, 0, 1], F(1), F(2))  # sqrt 2
    assert text.startswith("1.4142135623730950") and "x^2 - 2" in text


# ------------------------------------------------------------------ resources
def test_printing_a_root_is_bounded_by_its_bisection_limit():
    # 2^300 wide: 17 digits after some 360 halvings; 2^(2 MAX_PRINT_BISECTIONS) wide: the halvings stop at the
    # limit and the enclosure is printed without digits (no digit is shown that was not certified)
    assert algebraic_text([-2, 0, 1], F(0), F(2) ** 300).startswith("1.4142135623730950")
    text = algebraic_text([-2, 0, 1], F(0), F(2) ** (2 * MAX_PRINT_BISECTIONS))
    assert text.startswith("the root of x^2 - 2 in [")
