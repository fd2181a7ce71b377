"""A balanced tie of several simple poles, decided by the closed form of c_j (issue 22).

For r = g/h with simple poles z_k only, r = q + sum_k a_k/(z - z_k) and, for j > deg q,

    c_j(kappa) = sum_k b_k (z_k + kappa)^-(j+1),        b_k = -a_k = -g(z_k)/h'(z_k).

The certificate lists every pole exactly as a Gaussian rational x + iy (``poles``).  The kernel proves:
 * they are all the poles, each simple: lc(h) prod (z - z_k) = h, multiplied out exactly in Q(i);
 * p* (the smallest positive real pole) and kappa* = the least kappa > 0 at which another pole is as far
   from -kappa as p*: each pole with Re z < p* reaches it at kappa_k = (|z|^2 - p*^2)/(2(p* - Re z))
   (|z + kappa|^2 - (p* + kappa)^2 is linear and decreasing in kappa); the tied set T = {k : kappa_k =
   kappa*}, and kappa_k > 0 for all of them;
 * every pole not in T and not p* is real and positive with b_k > 0, so its term is > 0 for every j, kappa;
 * the balance: sum_(k in T) |b_k| <= b_* (|b_k|^2 = b_k conj(b_k) is rational; its square root is exact when
   it is a rational square, else bounded above).
Then for kappa in [0, kappa*] and j > deg q, |z_k + kappa| >= p* + kappa for k in T, so
    c_j(kappa) >= b_* (p* + kappa)^-(j+1) - sum_T |b_k| (p* + kappa)^-(j+1) >= 0;
the first c_j (j <= deg q) are recomputed by the caller (claims_radius).  Beyond kappa* a tied pole is
strictly closer to -kappa than p*, so by Pringsheim some c_j < 0 or a real pole lies in [-kappa, 0]: rho = kappa*.
Exact rationals only; the sizes are bounded before any product (MAX_POLES, MAX_BITS).
"""

from __future__ import annotations

from fractions import Fraction
from math import isqrt
from typing import Any, Sequence

from .budget import MAX_POLES, charge, fraction_products_cost
from .budget import MAX_TIE_POLE_BITS as MAX_BITS
from .failure import require
from .rationals import describe

__all__ = ["prove_balanced_tie", "MAX_POLES"]


def _mul(x: tuple[Fraction, Fraction], y: tuple[Fraction, Fraction]) -> tuple[Fraction, Fraction]:
    return (x[0] * y[0] - x[1] * y[1], x[0] * y[1] + x[1] * y[0])


def _div(x: tuple[Fraction, Fraction], y: tuple[Fraction, Fraction]) -> tuple[Fraction, Fraction]:
    n = y[0] * y[0] + y[1] * y[1]
    return ((x[0] * y[0] + x[1] * y[1]) / n, (x[1] * y[0] - x[0] * y[1]) / n)


def _eval(p: Sequence[Fraction], z: tuple[Fraction, Fraction]) -> tuple[Fraction, Fraction]:
    acc = (Fraction(0), Fraction(0))
    for c in reversed(p):
        acc = _mul(acc, z)
        acc = (acc[0] + c, acc[1])
    return acc


def _sqrt_upper(q: Fraction) -> Fraction:
    """sqrt(q) exactly when q is the square of a rational, else a rational upper bound (q >= 0)."""
    n, d = q.numerator, q.denominator
    rn, rd = isqrt(n), isqrt(d)
    if rn * rn == n and rd * rd == d:
        return Fraction(rn, rd)
    s = 200
    return Fraction(isqrt(n * d * 4 ** s) + 1, d * 2 ** s)  # sqrt(n/d) = sqrt(n d)/d


def _parse(poles: Sequence[list[Fraction]]) -> list[tuple[Fraction, Fraction]]:
    require(isinstance(poles, list) and 2 <= len(poles) <= MAX_POLES, f"balanced tie: 'poles' must list 2 to "
            f"{MAX_POLES} poles")
    out = []
    for z in poles:
        require(isinstance(z, list) and len(z) == 2 and all(isinstance(c, Fraction) for c in z),
                "balanced tie: a pole is a pair [re, im] of exact rationals")
        require(all(c.numerator.bit_length() + c.denominator.bit_length() <= MAX_BITS for c in z),
                f"balanced tie: a pole's coordinates exceed {MAX_BITS} bits")
        out.append((z[0], z[1]))
    require(len(set(out)) == len(out), "balanced tie: the poles are not distinct (simple poles only)")
    return out


def prove_balanced_tie(g: Any, h: Any, poles: Any) -> Any:
    """kappa* (a rational > 0) when the listed Gaussian-rational poles prove a balanced tie of r = g/h (lowest
    terms, h(0) > 0), module docstring; CheckFailure otherwise.  ``poles``: [[re, im], ...] as Fractions."""
    zs = _parse(poles)
    require(len(zs) == len(h) - 1, "balanced tie: the number of poles is not deg h")
    bits = max(c.numerator.bit_length() + c.denominator.bit_length() for z in zs for c in z)
    charge(fraction_products_cost(4 * len(zs) ** 2 + 4 * len(zs) * (len(g) + len(h)), 2 * bits * len(zs)),
           "the balanced tie's products over Q(i)")
    prod = [(h[-1], Fraction(0))]  # lc(h) prod (z - z_k), low to high
    for z in zs:
        nxt = [(Fraction(0), Fraction(0))] * (len(prod) + 1)
        for i, c in enumerate(prod):
            m = _mul(c, z)
            nxt[i] = (nxt[i][0] - m[0], nxt[i][1] - m[1])
            nxt[i + 1] = (nxt[i + 1][0] + c[0], nxt[i + 1][1] + c[1])
        prod = nxt
    require(all(c == (x, Fraction(0)) for c, x in zip(prod, h)), "balanced tie: the listed poles are not the "
                                                                 "roots of h")
    positive = [z[0] for z in zs if z[1] == 0 and z[0] > 0]
    require(positive, "balanced tie: r has no positive real pole")
    p = min(positive)
    dh = [k * c for k, c in enumerate(h)][1:]
    b = {z: _div(_eval(g, z), _eval(dh, z)) for z in zs}
    b = {z: (-v[0], -v[1]) for z, v in b.items()}
    b_star = b[(p, Fraction(0))][0]
    require(b_star > 0, "balanced tie: the principal part at p* has the wrong sign")
    kappas = {z: (z[0] ** 2 + z[1] ** 2 - p * p) / (2 * (p - z[0])) for z in zs if z[0] < p}
    require(kappas, "balanced tie: no pole has Re z < p*, so none ever reaches p*'s distance")
    kappa = min(kappas.values())
    require(kappa > 0, "balanced tie: a pole is as close to 0 as p* (rho = 0 has its own reasons)")
    tied = [z for z, k in kappas.items() if k == kappa]
    for z in zs:
        if z == (p, Fraction(0)) or z in tied:
            continue
        require(z[1] == 0 and z[0] > p and b[z][0] > 0, "balanced tie: a pole that is not tied must be real and "
                "positive with b_k > 0 (its terms then stay positive)")
    total = sum((_sqrt_upper(b[z][0] ** 2 + b[z][1] ** 2) for z in tied), Fraction(0))
    require(total <= b_star, f"balanced tie: the tied poles' residues outweigh p*'s (sum |b_k| > b_* = {describe(b_star)})")
    return kappa
