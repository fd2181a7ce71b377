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
from exactinv_check.poly_arithmetic import integer_coefficients


def _radius_cert(value, num=("1", "1"), den=("1",)):
    return {"format": "exactinv-certificate", "version": 2,
            "problem": {"method": {"name": "rt", "numerator": list(num), "denominator": list(den)}},
            "claims": [{"type": "absolute_monotonicity_radius", "value": value, "reason": "coefficient",
                        "attained": True}]}


def _reciprocals(rng, count, digits):
    return [f"{rng.choice([-1, 1])}/{rng.randrange(10 ** (digits - 1), 10 ** digits) | 1}" for _ in range(count)]


# r = 1 + z + z^2/2 + z^3/6 + z^4 + z^5: rho is the smaller root (6 - sqrt 21)/30 of 60 x^2 - 24 x + 1 (c_3 ends
# first; worked out by hand: c_3(kappa) = 1/6 - 4 kappa + 10 kappa^2 = (60 kappa^2 - 24 kappa + 1)/6), attained.
_NUM = ["1", "1", "1/2", "1/6", "1", "1"]


_P = [1, -24, 60]


def _times(a, b):
    out = [0] * (len(a) + len(b) - 1)
    for i, x in enumerate(a):
        for j, y in enumerate(b):
            out[i + j] += x * y
    return out


def _sqrt_bounds(n, k=60):
    """Rationals lo < sqrt(n) < hi, 2^-k apart (n not a square)."""
    from math import isqrt
    r = isqrt(n << (2 * k))
    return Fraction(r, 1 << k), Fraction(r + 1, 1 << k)


def _root_interval(sign):
    lo, hi = _sqrt_bounds(21)  # (6 +- sqrt 21) / 30
    return sorted(((6 + sign * lo) / 30, (6 + sign * hi) / 30))


def _value(poly, interval):
    return {"poly": [str(c) for c in poly], "interval": [str(x) for x in interval]}


def _cert_attained(value, attained):
    cert = _radius_cert(value, num=_NUM)
    cert["claims"][0]["attained"] = attained
    return cert


# ------------------------------------------------------------------ soundness

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


def test_radius_values_right_and_wrong_at_an_irrational_rho():
    Q = _times(_times(_P, [-2, 0, 1]), [-100, 1])  # rho's polynomial times (x^2 - 2)(x - 100)
    s2lo, s2hi = _sqrt_bounds(2)
    rho = _root_interval(-1)
    true_values = [_value(_P, rho), _value(Q, rho)]  # (and P (x^990 + 3): verified too, 30 s, left out of the test)
    lo, hi = rho
    wrong_values = [_value(Q, _root_interval(1)), _value(Q, (s2lo, s2hi)), _value(Q, (-s2hi, -s2lo)),
                    _value(Q, (Fraction(99), Fraction(101))), _value(Q, (Fraction(0), Fraction(200))),
                    _value(_P, (Fraction(-100), Fraction(100))),
                    str(lo - Fraction(1, 10 ** 30)), str(hi + Fraction(1, 10 ** 30)),
                    _value([1 + c for c in _times(_P, [-2, 0, 1])[:1]] + _times(_P, [-2, 0, 1])[1:], rho)]
    for v in true_values:
        assert check(_cert_attained(v, True)).ok, v
        assert not check(_cert_attained(v, False)).ok
    for v in wrong_values:
        for attained in (True, False):
            assert not check(_cert_attained(v, attained)).ok, v


def test_kronecker_products_at_the_packing_boundaries_equal_schoolbook_products():
    """claims_radius.kronecker_mul against the schoolbook product, coefficients at +-(2^b - 1) and +-2^(b-1)
    for b at and around byte and word boundaries (the packing's digit size), zeros and mixed signs."""
    from exactinv_check.claims_radius import kronecker_mul
    from exactinv_check.poly_arithmetic import mul_integers, trim
    rng = random.Random(5)
    for _ in range(1500):
        ba, bb = rng.choice([1, 7, 8, 9, 63, 64, 65, 127, 128, 129, 300]), rng.choice([1, 8, 9, 64, 65, 200])

        def coefficient(b):
            return rng.choice([0, 2 ** b - 1, 1 - 2 ** b, 2 ** (b - 1), -2 ** (b - 1), rng.randrange(1 - 2 ** b, 2 ** b)])
        a = [coefficient(ba) for _ in range(rng.randint(1, 12))]
        b = [coefficient(bb) for _ in range(rng.randint(1, 12))]
        if rng.random() < 0.3:  # the largest product coefficients: every term of one sign at the top of the range
            a, b = [2 ** ba - 1] * len(a), [1 - 2 ** bb] * len(b)
        assert trim(kronecker_mul(a, b)) == trim(mul_integers(a, b)), (a, b)


# ------------------------------------------------------------------ resource

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
