"""exactinv_check.disks: disks proved to hold the complex roots (one each) and outward-rounded disk arithmetic,
against python-flint (acb roots of the same polynomials)."""

from fractions import Fraction as F

import flint
import pytest
from hypothesis import given
from hypothesis import strategies as st

from exactinv_check.disks import ball, ball_inv, ball_mul, pole_disks, sqrt_bounds
from exactinv_check.failure import CheckFailure

small = st.fractions(min_value=-5, max_value=5, max_denominator=16)


def _inside(z, disk):
    """z (a double-precision complex from flint) lies in the closed disk, up to a margin of 10^-12."""
    re, im, rad = disk
    return (F(z.real) - re) ** 2 + (F(z.imag) - im) ** 2 <= (rad + F(1, 10**12)) ** 2


# ------------------------------------------------------------------ soundness
@given(st.fractions(min_value=0, max_value=10**6, max_denominator=10**6))
def test_square_root_bounds_bracket_the_root(x):
    lo, hi = sqrt_bounds(x)
    assert lo * lo <= x <= hi * hi and 0 <= lo <= hi


@given(st.lists(st.integers(-20, 20), min_size=3, max_size=7).filter(lambda c: c[-1] != 0 and c[0] != 0))
def test_every_root_lies_in_exactly_one_disk(coeffs):
    f = flint.fmpz_poly(coeffs)
    if f.gcd(f.derivative()).degree() > 0:  # the kernel gets squarefree polynomials
        return
    disks = pole_disks([F(c) for c in coeffs])
    roots = [complex(r) for r, _ in f.complex_roots()]  # acb enclosures, to double precision
    assert len(disks) == len(coeffs) - 1
    for z in roots:
        assert sum(_inside(z, d) for d in disks) == 1


@given(small, small, small, small)
def test_disk_products_and_inverses_hold_the_exact_values(a, b, c, d):
    x, y = ball(a, b, F(1, 1000)), ball(c, d, F(1, 1000))
    prod = ball_mul(x, y)
    assert (F(a * c - b * d) - prod[0]) ** 2 + (F(a * d + b * c) - prod[1]) ** 2 <= prod[2] ** 2
    if a * a + b * b > F(1, 100):
        inv = ball_inv(x)
        n = a * a + b * b
        assert (a / n - inv[0]) ** 2 + (-b / n - inv[1]) ** 2 <= inv[2] ** 2


def test_a_disk_around_zero_cannot_be_inverted():
    with pytest.raises(CheckFailure):
        ball_inv(ball(F(1, 100), 0, F(1, 10)))


# ------------------------------------------------------------------ resources
def test_the_refinement_is_bounded_close_roots_give_a_rejection_or_disjoint_disks():
    # (x - 1)(x - 1 - 10^-30): roots 10^-30 apart; the kernel either separates them or rejects, in bounded steps
    eps = F(1, 10**30)
    coeffs = [1 + eps, -(2 + eps), F(1)]
    try:
        disks = pole_disks(coeffs)
    except CheckFailure:
        return
    assert len(disks) == 2
    (a, b, r), (c, d, s) = disks
    assert (a - c) ** 2 + (b - d) ** 2 > (r + s) ** 2  # disjoint
