"""Exact outward rounding to IEEE doubles: the double just below or above an
exact real (a Fraction, a RealAlgebraic or +-INF), decided in Q.

A float is used only as a first guess (``float(q)`` of a Fraction); every
decision compares ``Fraction(d)`` with the exact number, and the guess is
moved by one ulp (``math.nextafter``) until the exact comparisons hold.  So
``double_below(x) <= x`` (``< x`` with ``strict=True``) and
``double_above(x) >= x`` hold exactly, and no double lies strictly between
the answer and ``x``.  Values beyond the largest finite double round to
``+-math.inf`` on the far side only (``double_below(10**400)`` is the largest
finite double).
"""

from __future__ import annotations

import math
import sys
from fractions import Fraction

from .real_algebraic import RealAlgebraic
from .scalars import Infinity

__all__ = ["double_below", "double_above", "DOUBLE_MAX"]

DOUBLE_MAX = sys.float_info.max
"""The largest finite double, 2**1024 - 2**971."""

_MAX = Fraction(DOUBLE_MAX)
_GUESS_BITS = 64  # enclosure width (relative) before an algebraic number is rounded: one or two exact steps


def _guess(q: Fraction) -> float:
    """A double near q (a hint only: never raises)."""
    if q > _MAX:
        return math.inf
    if q < -_MAX:
        return -math.inf
    return q.numerator / q.denominator  # correctly rounded in CPython; only a starting point here


def _below_rational(q: Fraction, strict: bool) -> float:
    d = _guess(q)
    if d == math.inf:
        d = DOUBLE_MAX
    while d != -math.inf and (Fraction(d) > q or (strict and Fraction(d) == q)):
        d = math.nextafter(d, -math.inf)
    while True:  # the guess may be more than one ulp low: step up while the next double still qualifies
        up = math.nextafter(d, math.inf)
        if up == math.inf or Fraction(up) > q or (strict and Fraction(up) == q):
            return d
        d = up


def _below_algebraic(a: RealAlgebraic) -> float:
    a.refine_relative(_GUESS_BITS)  # the same number, a narrower isolating interval
    d = _below_rational(a.lower, False)  # d <= lower < a
    while True:
        up = math.nextafter(d, math.inf)
        if up == math.inf or not a > Fraction(up):  # a is irrational: a != up, so a < up
            return d
        d = up


def double_below(x: Fraction | int | RealAlgebraic | Infinity, strict: bool = False) -> float:
    """The largest double d with d <= x (d < x if ``strict``), decided exactly.

    >>> double_below(Fraction(1, 3)) < Fraction(1, 3) < Fraction(double_above(Fraction(1, 3)))
    True
    >>> double_below(Fraction(1)), double_below(Fraction(1), strict=True) == math.nextafter(1.0, 0)
    (1.0, True)
    >>> sqrt2 = RealAlgebraic.from_isolating_interval([-2, 0, 1], 1, 2)
    >>> d = double_below(sqrt2); Fraction(d) ** 2 < 2 < Fraction(math.nextafter(d, 3)) ** 2
    True
    >>> double_below(Fraction(10) ** 400) == DOUBLE_MAX
    True
    """
    if isinstance(x, Infinity):
        return DOUBLE_MAX if x.sign > 0 else -math.inf
    if isinstance(x, RealAlgebraic):
        return _below_algebraic(x)
    return _below_rational(Fraction(x), strict)


def double_above(x: Fraction | int | RealAlgebraic | Infinity, strict: bool = False) -> float:
    """The least double d with d >= x (d > x if ``strict``), decided exactly; ``math.inf``
    above the largest finite double.

    >>> double_above(Fraction(1, 3)) - double_below(Fraction(1, 3)) == math.ulp(1 / 3)
    True
    >>> double_above(Fraction(2)), double_above(Fraction(10) ** 400)
    (2.0, inf)
    """
    if isinstance(x, Infinity):
        return math.inf if x.sign > 0 else -DOUBLE_MAX
    return -double_below(-x if isinstance(x, RealAlgebraic) else -Fraction(x), strict)
