"""exactinv_check.bernstein: the kernel's exact pieces -- exponential enclosures, f's Taylor coefficients at 0 --
against independent values (mpmath at 60 digits, and f worked out by hand)."""

from fractions import Fraction as F

import mpmath
from hypothesis import given, settings
from hypothesis import strategies as st

from exactinv_check import bernstein


@settings(deadline=None, max_examples=60)
@given(st.fractions(min_value=-60, max_value=5, max_denominator=64),
       st.fractions(min_value=-40, max_value=40, max_denominator=64),
       st.fractions(min_value=0, max_value=F(1, 4), max_denominator=1024))
def test_exponential_disk_holds_the_true_value(x, y, rad):
    """e^u for every u in the disk (x + iy, rad): the centre's value is inside, and so is the value at an edge point."""
    cx, cy, r = bernstein._exp((x, y, rad))
    with mpmath.workdps(60):
        for u in (mpmath.mpc(x.numerator, 0) / x.denominator + 1j * mpmath.mpf(y.numerator) / y.denominator,
                  mpmath.mpc(x.numerator, 0) / x.denominator + mpmath.mpf(rad.numerator) / rad.denominator
                  + 1j * mpmath.mpf(y.numerator) / y.denominator):
            value = mpmath.exp(u)
            assert abs(value - mpmath.mpc(mpmath.mpf(cx.numerator) / cx.denominator,
                                          mpmath.mpf(cy.numerator) / cy.denominator)) \
                <= mpmath.mpf(r.numerator) / r.denominator
    if rad == 0:  # a point: the enclosure is tight (relative 2^-90)
        assert r <= 2 ** -90 * max(abs(cx) + abs(cy), F(1, 2 ** 200))


def test_density_at_zero_by_hand():
    """r = (1 - z)/(1 - 2z)^4: f(t) = e^(-t/2) (t^2/32 + t^3/192) (the kernel's Sturm proof), so
    f(0) = f'(0) = 0, f''(0) = 1/16, f'''(0) = 6/192 - 3 (1/2)(2/32) = 1/32 - 3/32 = -1/16."""
    c, fs = bernstein.density_at_zero([F(1), F(-1)], [F(1), F(-8), F(24), F(-32), F(16)], 4)
    assert c == 0 and fs == [0, 0, F(1, 16), F(-1, 16)]
    c, fs = bernstein.density_at_zero([F(1), F(1, 2)], [F(1), F(-1, 2)], 3)   # trapezoid: c = -1, f = 4 e^(-2t)
    assert c == -1 and fs == [4, -8, 16]
