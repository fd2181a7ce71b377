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


def from_partial_fractions(terms, constant=None):
    """(g, h) with h(0) = 1 for r = c + sum_k a_k/(z - z_k), a_k = -b_k, from [((x_k, y_k), (u_k, v_k))]: simple
    poles z_k = x_k + i y_k with b_k = u_k + i v_k (conjugate pairs listed both), Fractions; c is chosen so that
    r(0) = 1 unless given.  Exact arithmetic in Q(i), nothing from exactinv."""
    def mul(a, b):
        out = [(Fraction(0), Fraction(0))] * (len(a) + len(b) - 1)
        for i, x in enumerate(a):
            for j, y in enumerate(b):
                out[i + j] = (out[i + j][0] + x[0] * y[0] - x[1] * y[1], out[i + j][1] + x[0] * y[1] + x[1] * y[0])
        return out
    zs = [z for z, _ in terms]
    h = [(Fraction(1), Fraction(0))]
    for z in zs:
        h = mul(h, [(-z[0], -z[1]), (Fraction(1), Fraction(0))])
    num = [(Fraction(0), Fraction(0))] * len(h)
    for k, (_z, b) in enumerate(terms):
        q = [(Fraction(1), Fraction(0))]
        for i, w in enumerate(zs):
            if i != k:
                q = mul(q, [(-w[0], -w[1]), (Fraction(1), Fraction(0))])
        for i, c in enumerate(q):
            num[i] = (num[i][0] - b[0] * c[0] + b[1] * c[1], num[i][1] - b[0] * c[1] - b[1] * c[0])
    assert all(c[1] == 0 for c in h + num), "the poles and residues must come in conjugate pairs"
    h, num = [c[0] for c in h], [c[0] for c in num]
    c = 1 - num[0] / h[0] if constant is None else constant
    g = [c * h[i] + (num[i] if i < len(num) else 0) for i in range(len(h))]
    g, h = [x / h[0] for x in g], [x / h[0] for x in h]
    while len(g) > 1 and g[-1] == 0:
        g.pop()
    return g, h


def product(*factors):
    """The product of polynomials (coefficient lists, low to high) as Fractions."""
    out = [Fraction(1)]
    for f in factors:
        nxt = [Fraction(0)] * (len(out) + len(f) - 1)
        for i, a in enumerate(out):
            for j, b in enumerate(f):
                nxt[i + j] += a * Fraction(b)
        out = nxt
    return out


def sextic(a, d, y):
    """(w^2 - d)((w^2 + d + y^2)^2 - 4 d w^2) with w = z - a, normalised to the value 1 at z = 0: the poles
    a +- sqrt d (real) and a +- sqrt d +- iy (a pair on each real pole's vertical line).  (2, 2, 1) is issue 22's
    ((z - 2)^2 - 2)((z - 2)^4 - 2(z - 2)^2 + 9)."""
    q = [d + y * y, Fraction(0), Fraction(1)]
    quartic = [u - v for u, v in zip(product(q, q), [0, 0, 4 * d, 0, 0])]
    p = product([-d, 0, 1], quartic)
    out = [sum(c * comb(k, i) * (-a) ** (k - i) for k, c in enumerate(p) if k >= i) for i in range(len(p))]
    return [c / out[0] for c in out]
