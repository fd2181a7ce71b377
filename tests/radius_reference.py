"""A slow, independent reference for the radius of absolute monotonicity: the exact Taylor coefficients
c_j(kappa) = [w^j] r(w - kappa) at a rational kappa, by exact Taylor shifts and series division in
Fractions (nothing from exactinv), and mpmath pole locations for equal-modulus ties."""

from fractions import Fraction
from math import comb

import mpmath


def coefficients_at(num, den, kappa, count):
    """c_0(kappa) .. c_{count-1}(kappa), exactly; None if -kappa is a pole."""
    def shift(p):
        return [sum(Fraction(p[k]) * comb(k, i) * (-kappa) ** (k - i) for k in range(i, len(p)))
                for i in range(len(p))]
    g, h = shift(num), shift(den)
    if h[0] == 0:
        return None
    c = []
    for j in range(count):
        v = g[j] if j < len(g) else Fraction(0)
        for i in range(1, min(j, len(h) - 1) + 1):
            v -= h[i] * c[j - i]
        c.append(v / h[0])
    return c


def admissible(num, den, kappa, count):
    """r has no pole in [-kappa, 0] (checked at 400 points and exactly at -kappa) and c_0..c_{count-1} >= 0."""
    c = coefficients_at(num, den, kappa, count)
    return c is not None and all(x >= 0 for x in c)


def tie_kappa(num, den, digits=40):
    """min over poles z != p* with Re z < p* of (|z|^2 - p*^2)/(2(p* - Re z)), in mpmath (a float reference)."""
    with mpmath.workdps(digits + 20):
        roots = mpmath.polyroots([mpmath.mpf(c.numerator) / c.denominator for c in reversed(den)],
                                 maxsteps=400, extraprec=400)
        positive = [mpmath.re(z) for z in roots if abs(mpmath.im(z)) < mpmath.mpf(10) ** -digits and mpmath.re(z) > 0]
        p = min(positive)
        values = [(abs(z) ** 2 - p ** 2) / (2 * (p - mpmath.re(z))) for z in roots
                  if abs(z - p) > mpmath.mpf(10) ** -digits and mpmath.re(z) < p]
        return min(values) if values else None
