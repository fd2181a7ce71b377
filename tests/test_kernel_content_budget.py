"""Red team rt-budget2 (issue 22): a polynomial's integer coefficients are priced before they are built.

polys.integer_coefficients clears denominators and removes the content.  Coefficients 1/d_k with distinct
~3300-bit d_k share a common denominator of degree x 3300 bits in every integer, and the content's gcds of
such numbers (CPython's Lehmer gcd on numbers with a huge common factor) cost about degree^3: a 200 KB
algebraic number of degree 200 kept the kernel over 60 s of CPU (not finished) before any charge, and a
degree-64 method with 3990-digit denominators 16.6 s.  Both must be refused by a price, quickly."""

import random
from fractions import Fraction
from math import gcd

from hypothesis import given, settings
from hypothesis import strategies as st
from kernel_deadline import check_within

from exactinv_check import check
from exactinv_check.budget import account
from exactinv_check.polys import integer_coefficients


def _radius_cert(value, num=("1", "1"), den=("1",)):
    return {"format": "exactinv-certificate", "version": 2,
            "problem": {"method": {"name": "rt", "numerator": list(num), "denominator": list(den)}},
            "claims": [{"type": "absolute_monotonicity_radius", "value": value, "reason": "coefficient",
                        "attained": True}]}


def _reciprocals(rng, count, digits):
    return [f"{rng.choice([-1, 1])}/{rng.randrange(10 ** (digits - 1), 10 ** digits) | 1}" for _ in range(count)]


def test_an_algebraic_number_with_coprime_huge_denominators_is_refused_by_its_price():
    rng = random.Random(1)
    poly = _reciprocals(rng, 200, 1000) + ["1"]
    report = check_within(_radius_cert({"poly": poly, "interval": ["0", "2"]}), 20)
    assert not report.ok
    assert "over the certificate's work budget: a common denominator" in str(report), str(report)[:500]


def test_a_method_with_coprime_huge_denominators_is_refused_quickly():
    rng = random.Random(1)
    num = ["1"] + [c.lstrip("-") for c in _reciprocals(rng, 64, 3990)]
    report = check_within(_radius_cert("1", num=num), 10)
    assert not report.ok and "over the" in str(report), str(report)[:500]


def test_a_fraction_algebraic_number_is_still_accepted():
    # rho(1 + z) = 1, written as the root of (2/3) x^2 - 2/3 (= (2/3)(x - 1)(x + 1)) on (1/2, 3/2)
    report = check(_radius_cert({"poly": ["-2/3", "0", "2/3"], "interval": ["1/2", "3/2"]}))
    assert report.ok, str(report)


@settings(max_examples=60, deadline=None)
@given(st.lists(st.fractions(max_denominator=10 ** 30).filter(lambda x: abs(x.numerator) < 10 ** 30),
                min_size=1, max_size=12).filter(lambda p: p[-1] != 0))
def test_integer_coefficients_are_coprime_and_proportional_under_an_account(p):
    with account():
        ints = integer_coefficients(p)
    factor = Fraction(ints[-1]) / p[-1]
    assert factor > 0
    assert [Fraction(c) for c in ints] == [factor * c for c in p]
    g = 0
    for c in ints:
        g = gcd(g, c)
    assert g == 1


def test_a_sign_is_priced_by_the_largest_coefficient_not_the_leading_one():
    # lead 1, 13000-bit middle coefficients, a 62-bit point: priced by the lead it was charged 12 times below its
    # measured CPU time (isolate's ends and Real.claimed's end signs passed no bits)
    from exactinv_check.budget import evaluation_cost
    from exactinv_check.polys import sign_at
    rng = random.Random(3)
    ints = [rng.randrange(-2 ** 13000, 2 ** 13000) for _ in range(250)] + [1]
    x = Fraction(2 ** 60 + 1, 2 ** 61)
    with account(limit=10 ** 15, time_limit=None) as acc:
        s = sign_at(ints, x)
    n, d = x.numerator, x.denominator
    assert s == (lambda v: (v > 0) - (v < 0))(sum(c * n ** k * d ** (250 - k) for k, c in enumerate(ints)))
    assert acc.spent == evaluation_cost(250, max(abs(c).bit_length() for c in ints), 62)
