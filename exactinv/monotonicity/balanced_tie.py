"""A balanced tie of several simple poles, decided by the closed form of c_j (issue 22; paper, Section 3.2).

For r = g/h with simple poles z_k only, c_j(kappa) = sum_k b_k (z_k + kappa)^-(j+1) for j > deg q exactly
(b_k = -g(z_k)/h'(z_k)).  When every pole is a Gaussian rational x + iy, p* > 0 is the smallest positive real
pole and the poles that first reach p*'s distance from -kappa (all at the same kappa*) have residues whose
moduli add up to at most b_* (exactly equal: a *balanced* tie, which no Arb enclosure can decide), while every
other pole is real, positive and has b_k > 0, then on [0, kappa*]

    c_j(kappa) >= (b_* - sum_T |b_k|) (p* + kappa)^-(j+1) >= 0          (j > deg q),

and rho = kappa* (attained).  The poles go into the certificate (``poles``); the kernel
(exactinv_check.balanced_tie) re-proves everything from them in exact rationals.
"""

from __future__ import annotations

from fractions import Fraction
from math import isqrt

import flint

from ..core.polys import integer_part

__all__ = ["gaussian_poles", "balanced_tie"]


def gaussian_poles(h: list) -> list[tuple[Fraction, Fraction]] | None:
    """Every root of h as an exact Gaussian rational (x, y), when h is squarefree and every root is one; else None.
    (A quadratic factor a z^2 + b z + c has the roots (-b +- sqrt(b^2 - 4ac))/(2a), Gaussian rational iff
    4ac - b^2 is a square.)

    >>> from fractions import Fraction as F
    >>> sorted(gaussian_poles([F(20), F(-4), F(1)]))     # z^2 - 4z + 20: 2 +- 4i
    [(Fraction(2, 1), Fraction(-4, 1)), (Fraction(2, 1), Fraction(4, 1))]
    >>> gaussian_poles([F(3), F(0), F(1)]) is None        # +- i sqrt 3
    True
    """
    hq = flint.fmpq_poly([flint.fmpq(c.numerator, c.denominator) for c in h])
    _, factors = integer_part(hq).factor()
    out = []
    for f, m in factors:
        if m != 1 or f.degree() > 2:
            return None
        c = [Fraction(int(x)) for x in f.coeffs()]
        if f.degree() == 1:
            out.append((-c[0] / c[1], Fraction(0)))
            continue
        a, b, cc = c[2], c[1], c[0]
        disc = 4 * a * cc - b * b  # > 0: an irreducible quadratic over Q with real roots has disc < 0 non-square
        if disc <= 0 or isqrt(int(disc)) ** 2 != disc:
            return None
        s = Fraction(isqrt(int(disc)))
        out += [(-b / (2 * a), s / (2 * a)), (-b / (2 * a), -s / (2 * a))]
    return out


def _mul(x, y):
    return (x[0] * y[0] - x[1] * y[1], x[0] * y[1] + x[1] * y[0])


def _eval(p, z):
    acc = (Fraction(0), Fraction(0))
    for c in reversed(p):
        acc = _mul(acc, z)
        acc = (acc[0] + c, acc[1])
    return acc


def _modulus(q: Fraction) -> Fraction | None:
    n, d = isqrt(q.numerator), isqrt(q.denominator)
    return Fraction(n, d) if n * n == q.numerator and d * d == q.denominator else None


def balanced_tie(g: list, h: list) -> tuple[Fraction, tuple] | None:
    """(kappa*, poles) when r = g/h has a balanced (or p*-won) tie of Gaussian-rational simple poles decided by the
    closed form (module docstring), the poles to be listed in the certificate; else None.

    Poles 4, -6 and 2 +- 4i all reach p* = 4's distance at kappa* = 1 (radius 5 around -1), with b_* = 2,
    |b_(-6)| = 1 and |b_(2 +- 4i)| = 1/2: sum |b| = b_*, so rho = 1.

    >>> from fractions import Fraction as F
    >>> g = [F(1), F(-1049, 9000), F(-23, 6000), F(337, 36000), F(-67, 72000)]
    >>> h = [F(1), F(-17, 60), F(1, 40), F(1, 240), F(-1, 480)]      # (1 - z/4)(1 + z/6)(1 - z/5 + z^2/20)
    >>> kappa, poles = balanced_tie(g, h)
    >>> kappa, sorted(poles)
    (Fraction(1, 1), [(Fraction(-6, 1), Fraction(0, 1)), (Fraction(2, 1), Fraction(-4, 1)), (Fraction(2, 1), Fraction(4, 1)), (Fraction(4, 1), Fraction(0, 1))])
    >>> balanced_tie([F(1)], h) is None     # g = 1: the tied residues outweigh b_* (rho < kappa*, found by the scan)
    True
    """  # noqa: E501 (doctest output)
    zs = gaussian_poles(h)
    if zs is None or len(zs) < 2:
        return None
    positive = [x for x, y in zs if y == 0 and x > 0]
    if not positive:
        return None
    p = min(positive)
    dh = [k * c for k, c in enumerate(h)][1:]
    b = {}
    for z in zs:
        gz, dz = _eval(g, z), _eval(dh, z)
        n = dz[0] * dz[0] + dz[1] * dz[1]
        b[z] = (-(gz[0] * dz[0] + gz[1] * dz[1]) / n, -(gz[1] * dz[0] - gz[0] * dz[1]) / n)
    b_star = b[(p, Fraction(0))][0]
    kappas = {z: (z[0] ** 2 + z[1] ** 2 - p * p) / (2 * (p - z[0])) for z in zs if z[0] < p}
    if b_star <= 0 or not kappas:
        return None
    kappa = min(kappas.values())
    if kappa <= 0:
        return None
    tied = [z for z, k in kappas.items() if k == kappa]
    if any(not (z[1] == 0 and z[0] > p and b[z][0] > 0) for z in zs if z != (p, Fraction(0)) and z not in tied):
        return None
    moduli = [_modulus(b[z][0] ** 2 + b[z][1] ** 2) for z in tied]
    if any(m is None for m in moduli) or sum(moduli) > b_star:
        return None
    return kappa, tuple(zs)
