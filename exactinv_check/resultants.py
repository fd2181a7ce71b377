"""Resultants over Q (Euclid's algorithm), Newton interpolation, and the polynomial
whose roots are the quotients of two algebraic numbers.  Re-exported by
:mod:`exactinv_check.polys`.
"""

from __future__ import annotations

from fractions import Fraction
from typing import Any, Sequence

from .budget import MAX_DEGREE, active, charge, fraction_products_cost
from .failure import require
from .poly_arithmetic import add, divmod_, mul, strip_zero_roots, trim


def _bits(p: Sequence[Fraction]) -> int:
    return max((max(abs(c.numerator).bit_length(), c.denominator.bit_length()) for c in p), default=1)


def resultant(f: Any, g: Any) -> Any:
    """The resultant of f and g over Q (Euclid's algorithm on the defining identity
    res(f, g) = lc(g)^deg f * prod_{g(b)=0} f(b))."""
    f, g = trim(f), trim(g)
    if not f or not g:
        return Fraction(0)
    result = Fraction(1)
    while len(g) > 1:
        df, dg = len(f) - 1, len(g) - 1
        if active():  # a division step: (df - dg + 1) dg Fraction products (uncharged before: red team rt-budget)
            charge(fraction_products_cost((df - dg + 1) * (dg + 1), _bits(f) + _bits(g)), "a resultant step")
        r = divmod_(f, g)[1]
        if not r:
            return Fraction(0)
        dr = len(r) - 1
        # res(f, g) = (-1)^(df dg) res(g, f) = (-1)^(df dg) lc(g)^(df - dr) res(g, r)
        result *= (-1) ** (df * dg) * g[-1] ** (df - dr)
        f, g = g, r
    return result * g[0] ** (len(f) - 1)


def interpolate(points: Any, values: Sequence[Fraction]) -> Any:
    """The polynomial of degree < len(points) through (points, values) (Newton form)."""
    k = len(points)
    coef = list(values)
    for level in range(1, k):
        if active():  # one level of divided differences (uncharged before: red team rt-budget)
            charge(fraction_products_cost(2 * (k - level), 2 * _bits(coef)), "an interpolation step")
        for i in range(k - 1, level - 1, -1):
            coef[i] = (coef[i] - coef[i - 1]) / (points[i] - points[i - level])
    result = [coef[-1]] if coef else []
    for i in range(k - 2, -1, -1):
        result = add(mul(result, [-points[i], Fraction(1)]), [coef[i]])
    return trim(result)


def quotient_polynomial(p: Any, q: Any) -> Any:
    """A nonzero polynomial in t vanishing at a/b for every root a of p and b != 0 of q:
    res_y(p(t y), q(y)), by evaluation and interpolation."""
    p, q = strip_zero_roots(p), strip_zero_roots(q)
    dp, dq = len(p) - 1, len(q) - 1
    require(dp * dq <= MAX_DEGREE, "the quotient of two algebraic numbers has too large a degree for this kernel")
    # T = 0 would drop the degree of p(T y) and, with it, the resultant's formal
    # degree: interpolate at T = 1 .. dp dq + 1 only
    points = [Fraction(k) for k in range(1, dp * dq + 2)]
    values = [resultant([c * t ** k for k, c in enumerate(p)], q) for t in points]
    return interpolate(points, values)
