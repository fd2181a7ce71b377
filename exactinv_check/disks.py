"""Disks in C that provably hold the complex poles of r, and arithmetic on them.

Root inclusion (module tail, "Rigour"): float Aberth iterates are hints, refined
by exact Weierstrass steps x_i <- x_i - W_i in 2^-s fixed point; the
Gerschgorin disks |z - (x_i - W_i)| <= (d-1)|W_i| hold the roots and, when
pairwise disjoint, exactly one each.  Disks (re, im, rad) have rational
centres rounded to PREC bits and radii rounded up (outward rounding); the
Taylor coefficients of a polynomial on a disk come from the exact Taylor shift
at its centre (the centred form).  Rational bounds of square roots are exact.
"""

from __future__ import annotations

import cmath
from fractions import Fraction
from math import ceil, comb, isqrt
from typing import Any, Sequence

from .budget import FRACTION_WEIGHT, MAX_WEIERSTRASS, PYTHON_OP, active, charge, words
from .failure import CheckFailure, require
from .poly_arithmetic import primitive

PREC = 128  # bits kept in the centres of the disk arithmetic


def sqrt_bounds(x: Fraction) -> tuple[Fraction, Fraction]:
    """Rationals lo <= sqrt(x) <= hi for a Fraction x >= 0."""
    if x == 0:
        return Fraction(0), Fraction(0)
    s = max(0, (160 - x.numerator.bit_length() + x.denominator.bit_length()) // 2)
    y = x * 4 ** s
    return Fraction(isqrt(y.numerator // y.denominator), 2 ** s), Fraction(isqrt(ceil(y)) + 1, 2 ** s)


def _scale_of(x: Fraction) -> int:
    return x.numerator.bit_length() - x.denominator.bit_length()


def round_up(x: Fraction) -> Fraction:
    """A short dyadic >= x (x >= 0)."""
    if x == 0:
        return Fraction(0)
    s = Fraction(2) ** (40 - _scale_of(x))
    return ceil(x * s) / s


def _short(x: Fraction) -> Fraction:
    """x rounded to PREC significant bits."""
    if x == 0:
        return Fraction(0)
    s = Fraction(2) ** (PREC - _scale_of(x))
    return round(x * s) / s


def ball(re: int | Fraction, im: int | Fraction, rad: int | Fraction) -> tuple[Fraction, Fraction, Fraction]:
    """The disk {|z - (re + i im)| <= rad}, centre rounded, the rounding error added to the radius."""
    re2, im2 = _short(Fraction(re)), _short(Fraction(im))
    return re2, im2, round_up(rad + abs(re - re2) + abs(im - im2))


def ball_abs_upper(x: tuple[Fraction, Fraction, Fraction]) -> Fraction:
    """A rational upper bound of |z| over the disk x = (re, im, rad)."""
    return sqrt_bounds(x[0] ** 2 + x[1] ** 2)[1] + x[2]


def ball_mul(x: tuple[Fraction, Fraction, Fraction], y: tuple[Fraction, Fraction, Fraction]) -> tuple[Fraction,
             Fraction, Fraction]:
    """A disk holding every product z w, z in the disk x, w in the disk y (rounded outward)."""
    return ball(x[0] * y[0] - x[1] * y[1], x[0] * y[1] + x[1] * y[0],
                 (ball_abs_upper(x) - x[2]) * y[2] + (ball_abs_upper(y) - y[2]) * x[2] + x[2] * y[2])


def ball_inv(x: tuple[Fraction, Fraction, Fraction]) -> tuple[Fraction, Fraction, Fraction]:
    """A disk holding 1/z for every z in the disk x (not containing 0):
    |1/z - 1/c| = |z - c|/(|z||c|) <= rad/(L (L - rad)) with L <= |c|."""
    n = x[0] ** 2 + x[1] ** 2
    L = sqrt_bounds(n)[0]
    require(L > x[2], "tail: a pole's enclosure is too wide to invert a Taylor coefficient")
    return ball(x[0] / n, -x[1] / n, x[2] / (L * (L - x[2])))


def taylor_balls(p: Sequence[Fraction], z: tuple[Fraction, Fraction, Fraction], first: int,
                 count: int) -> list[tuple[Fraction, Fraction, Fraction]]:
    """Enclosures of T_i(w) = [v^i] p(w + v), i = first .. first+count-1, for all w in the disk z = (c, rho):
    exactly p(c + u) = sum_k s_k u^k (Taylor shift at the centre), so T_i(c + u) = sum_{k>=i} C(k,i) s_k u^(k-i)
    and |T_i(c + u) - s_i| <= sum_{k>i} C(k,i) |s_k| rho^(k-i)  (the centred form: no cancellation is lost)."""
    re, im, rho = z
    sr, si = [Fraction(a) for a in p], [Fraction(0)] * len(p)
    if active():  # n^2 / 2 steps of 4 Fraction products and 4 sums on numbers growing by the centre's bits each
        # step, then n^2 / 2 terms of the radii; a Fraction operation costs about 3 FRACTION_WEIGHT (3 us: its gcds),
        # measured by benchmarks/kernel_cost_model.py (prove_tail) -- 16 n^2 in all
        centre = max(_bits_of(re), _bits_of(im), 1)
        w = words(max(map(_bits_of, sr), default=0) + len(p) * centre)
        charge(len(p) ** 2 * (16 * FRACTION_WEIGHT + 2 * w * w), "a Taylor shift at a pole's disk")
    for i in range(len(p) - 1):  # repeated synthetic division by (x - c)
        for k in range(len(p) - 2, i - 1, -1):
            sr[k], si[k] = sr[k] + re * sr[k + 1] - im * si[k + 1], si[k] + re * si[k + 1] + im * sr[k + 1]
    size = [sqrt_bounds(a * a + b * b)[1] for a, b in zip(sr, si)]
    out = []
    for i in range(first, first + count):
        if i >= len(p):
            out.append(ball(0, 0, 0))
            continue
        rad = sum(comb(k, i) * size[k] * rho ** (k - i) for k in range(i + 1, len(p))) if rho else 0
        out.append(ball(sr[i], si[i], rad))
    return out



def _bits_of(x: Fraction) -> int:
    return abs(x.numerator).bit_length() + x.denominator.bit_length()


def _approx_roots(f: Any, iterations: int = 200) -> list[Any]:
    """Float approximations of the roots of f (Aberth-Ehrlich iteration): hints only."""
    d = len(f) - 1
    try:
        c = [complex(float(x / f[-1])) for x in f]
    except OverflowError:
        raise CheckFailure("tail: coefficients out of floating-point range for the root hints") from None
    R = 2 * max(abs(c[i]) ** (1 / (d - i)) for i in range(d))  # Fujiwara's bound on |roots|
    z = [R * cmath.exp(2j * cmath.pi * (k + 0.25) / d) for k in range(d)]
    for _ in range(iterations):
        charge(3 * PYTHON_OP * d * (d + 2), "a step of the float root hints")  # d Horner and d sums of d complex terms
        moved = 0.0
        for i in range(d):
            p, dp = c[-1], 0j
            for a in reversed(c[:-1]):
                p, dp = p * z[i] + a, dp * z[i] + p
            if p == 0:
                continue
            s = sum(1 / (z[i] - z[k]) for k in range(d) if k != i and z[k] != z[i])
            ratio = p / dp if dp != 0 else 1e-8
            step = ratio / (1 - ratio * s) if ratio * s != 1 else ratio
            z[i] -= step
            moved = max(moved, abs(step) / max(abs(z[i]), 1e-300))
        if moved < 1e-15:
            break
    return z


def _weierstrass(f: Any, X: Sequence[tuple[int, int]], s: int) -> list[tuple[Fraction, Fraction]]:
    """W_i = f(x_i) / (lc prod_{j != i} (x_i - x_j)) exactly, for x_i = X_i / 2^s (X_i Gaussian integers
    (re, im)) and f with integer coefficients: integer arithmetic, one division per root."""
    d, S = len(f) - 1, 1 << s
    if active():  # per root: d homogeneous Horner steps and d - 1 products, on numbers growing by s bits each
        big = words(max(abs(c).bit_length() for c in f) + s * d)
        charge(d * 2 * d * (4 * PYTHON_OP + 4 * big * words(s)), "a Weierstrass correction of the pole hints")
    out = []
    for i, (a, b) in enumerate(X):
        pr, pi, scale = f[d], 0, 1  # 2^(s d) f(x_i), homogeneous Horner
        for k in range(d - 1, -1, -1):
            scale *= S
            pr, pi = pr * a - pi * b + f[k] * scale, pr * b + pi * a
        qr, qi = f[d], 0  # 2^(s (d-1)) lc prod_{j != i} (x_i - x_j)
        for j, (u, v) in enumerate(X):
            if j != i:
                qr, qi = qr * (a - u) - qi * (b - v), qr * (b - v) + qi * (a - u)
        n = (qr * qr + qi * qi) * S
        require(n != 0, "tail: coinciding root approximations")
        out.append((Fraction(pr * qr + pi * qi, n), Fraction(pi * qr - pr * qi, n)))
    return out


def pole_disks(f: Any) -> list[tuple[Fraction, Fraction, Fraction]]:
    """Pairwise disjoint exact disks (re, im, rad), each holding exactly one root of the squarefree f: float
    hints, refined by Weierstrass steps x_i <- x_i - W_i in 2^-s fixed point, then the Gerschgorin disks."""
    f = [int(c) for c in primitive(f)]
    d = len(f) - 1
    hints = _approx_roots(f)
    s = PREC + max(0, -min(_scale_of(Fraction(abs(x))) for x in hints if x))
    hints = [x * (1 + (k + 1) * 2.0 ** -40 * (1 + 1j)) for k, x in enumerate(hints)]  # break conjugate symmetry
    X = [(round(Fraction(x.real) * 2 ** s), round(Fraction(x.imag) * 2 ** s)) for x in hints]
    for _ in range(MAX_WEIERSTRASS):
        W = _weierstrass(f, X, s)
        centres = [(Fraction(a, 2 ** s) - wr, Fraction(b, 2 ** s) - wi) for (a, b), (wr, wi) in zip(X, W)]
        if all((wr * wr + wi * wi) * 4 ** (PREC - 16) <= a * a + b * b for (wr, wi), (a, b) in zip(W, centres)):
            break
        X = [(round(a * 2 ** s), round(b * 2 ** s)) for a, b in centres]
    out = [ball(a, b, (d - 1) * sqrt_bounds(wr * wr + wi * wi)[1]) for (a, b), (wr, wi) in zip(centres, W)]
    for i, x in enumerate(out):
        for y in out[i + 1:]:
            require((x[0] - y[0]) ** 2 + (x[1] - y[1]) ** 2 > (x[2] + y[2]) ** 2,
                    "tail: the inclusion disks of two poles overlap (poles too close to separate)")
    return out

