"""Poles on the vertical line Re z = p*, proved exactly (issue 22: complex poles with p*'s real part).

A non-real pole z = p* + iy (y != 0) of r = g/h with exactly the real part of the smallest positive pole p*
is never as close to -kappa as p* (|z + kappa|^2 = (p* + kappa)^2 + y^2), but its distance ratio tends to 1,
so its real part must be *proved* equal to p*; an enclosure cannot tell Re z = p* from Re z < p*.

The proof (p* rational).  Write f(p* + iy) = U(y) + i V(y) with U, V in Q[y] (the Taylor shift
f(p* + w) = sum_k s_k w^k, then w^k = (iy)^k: U = sum_(k even) (-1)^(k/2) s_k y^k, V = sum_(k odd)
(-1)^((k-1)/2) s_k y^k).  For real y, f(p* + iy) = 0 iff U(y) = V(y) = 0 iff G(y) = 0, G = gcd(U, V).  So a
real root y != 0 of G is a pole p* + iy on the line, exactly.  :func:`disk_on_line` proves that the one root of
f in an inclusion disk (exactinv_check.disks: pairwise disjoint, one root each) is such a pole: G has a real
root y in the chord {y : p* + iy in the disk} (a Descartes count), so p* + iy is a root of f in the disk, hence
the disk's root.

Two uses (exactinv_check.bernstein):
 * *dominance*: a pole proved on the line enters the dominance bound with delta = Re z - p* = 0, i.e.
   |e^(-(z - p*) t)| = 1 (multiplicity <= mu required);
 * *all poles on the line* (:func:`line_density`): h squarefree, every root p* + i y_k with y_k rational
   (deg G = deg h and G has deg h distinct rational roots).  Then f(t) = e^(-p* t) T(t/L),
   T(theta) = sum_k b_k e^(-i n_k theta) (L the lcm of the y_k's denominators, n_k = L y_k, b_k =
   -g(z_k)/h'(z_k) exact in Q(i)), a real trigonometric polynomial; with x = tan(theta/2),
   e^(-i n theta) = (1 - ix)^(2n)/(1 + x^2)^n, so Q(x) = (1 + x^2)^N T(theta(x)) (N = max |n_k|) is a real
   polynomial and T >= 0 on the circle iff Q >= 0 on R (theta = pi is a limit): an exact Sturm count.  This
   decides f touching 0, e.g. 1/((1 - z)(1 - z + z^2/2)): f(t) = 2 e^(-t) (1 - cos t).
 * *the line part beside other poles* (:func:`line_part`, the balanced line): with G = gcd(U, V) of h itself, whose
   real roots carry the multiplicities of h's roots on the line, B(t) = b_* + sum b_k e^(-i y_k t) (p* and every line
   pole simple) is proved >= 0 for one pair (b_*^2 >= 4|b|^2, |g|^2 and |h'|^2 at p* + i sqrt(Y) rational) or for
   rational heights (the same Q, from the line poles only, b_k = -g(z_k)/h'(z_k) with h' of the whole h).
Order in exactinv_check.bernstein: the closed form of one pair (:func:`single_pair`) first, then the density when its
Sturm count fits the budgets; an unaffordable density (N near MAX_LINE_EXPONENT) leaves the poles to the dominance
proof, which decides every f that p* dominates strictly.
For an IRRATIONAL p* the same proof runs in Q(p*)[y] (exactinv_check.line_algebraic), with the line-by-line proof
of f >= 0 for balanced lines.
Standard library only; every step is priced (exactinv_check.budget) before it runs or as it runs.
"""

from __future__ import annotations

from fractions import Fraction
from math import ceil, comb, isqrt
from math import gcd as igcd
from typing import Any, Sequence

from .budget import (
    MAX_LINE_EXPONENT,  # the largest N = max |n_k| of the trigonometric polynomial (Q has degree 2N)
    MAX_PIN,
    STURM_BUDGET,
    STURM_WORDS,
    affordable,
    charge,
    fraction_products_cost,
    sturm_cost,
    within_sturm_budget,
)
from .failure import require
from .poly_arithmetic import evaluate, integer_coefficients, mul, strip_zero_roots, trim
from .polys import affordable_gcd, count_roots, positive_roots, sign_at, sign_right_of
from .rationals import describe
from .tail import squarefree_decomposition

__all__ = ["rational_root", "line_parts", "line_gcd", "disk_on_line", "line_density", "line_part", "nonnegative_on_line",
           "single_pair", "MAX_LINE_EXPONENT"]


def _bits(p: Sequence[Fraction]) -> int:
    return max((abs(c.numerator).bit_length() + c.denominator.bit_length() for c in p), default=1)


def rational_root(p: Any, lo: Fraction, hi: Fraction) -> Any:
    """The rational root of p in the isolating data (lo, hi) (one root in the open interval, or lo = hi a
    root), or None when that root is irrational.  A rational root k/q of the integer polynomial H has
    q | lc(H): once hi - lo < 1/lc^2 the interval holds at most one such fraction, ceil(lo lc)/lc."""
    H = integer_coefficients(p)
    lc = abs(H[-1])
    if lo == hi:
        return lo if sign_at(H, lo) == 0 else None
    for _ in range(MAX_PIN):
        if (hi - lo) * lc * lc < 1:
            break
        mid = (lo + hi) / 2
        s = sign_at(H, mid)
        if s == 0:
            return mid
        lo, hi = (lo, mid) if sign_at(H, lo) * s < 0 else (mid, hi)
    else:
        return None
    q = Fraction(ceil(lo * lc), lc)
    return q if lo <= q <= hi and sign_at(H, q) == 0 else None


def _shift(f: Any, p: Any) -> list[Fraction]:
    """[w^k] f(p + w), exactly (priced)."""
    n = len(f)
    charge(fraction_products_cost(n * n, _bits(f) + n * _bits([p])), "the Taylor shift to the line Re z = p*")
    return [sum(f[k] * comb(k, i) * p ** (k - i) for k in range(i, n)) for i in range(n)]


def line_parts(f: Sequence[Fraction], p: Fraction) -> Any:
    """(U, V) with f(p + iy) = U(y) + i V(y), U, V in Q[y]."""
    s = _shift(f, p)
    U = [Fraction(0)] * len(s)
    V = [Fraction(0)] * len(s)
    for k, c in enumerate(s):
        if k % 2 == 0:
            U[k] = c * (-1) ** (k // 2)
        else:
            V[k] = c * (-1) ** ((k - 1) // 2)
    return trim(U), trim(V)


def line_gcd(f: Any, p: Any) -> list[Fraction]:
    """G = gcd(U, V), monic ([1] when coprime): its real roots y are exactly the roots p + iy of f on the line."""
    U, V = line_parts(f, p)
    G = trim(U or V) if not U or not V else trim(affordable_gcd(U, V))
    return [c / G[-1] for c in G] if G else [Fraction(1)]


def _sqrt_lower(x: Fraction) -> Fraction:
    """A rational 0 <= s <= sqrt(x) (x >= 0)."""
    if x <= 0:
        return Fraction(0)
    s = max(0, (x.denominator.bit_length() - x.numerator.bit_length()) // 2 + 64)  # about 64 significant bits
    y = x * 4 ** s
    return Fraction(isqrt(y.numerator // y.denominator), 2 ** s)


def disk_on_line(G: Sequence[Fraction], disk: tuple[Fraction, Fraction, Fraction], p: Fraction) -> Any:
    """True when the root of f in the inclusion disk (re, im, rad) is proved to be p + iy with y != 0 real:
    G (= :func:`line_gcd`) has a root in the chord [im - w, im + w] of the disk at Re z = p (w <= the half
    chord), and the chord does not contain 0."""
    re, im, rad = disk
    if len(G) <= 1:
        return False
    if (p - re) ** 2 > rad * rad:
        return False
    w = _sqrt_lower(rad * rad - (p - re) ** 2)
    if w == 0:  # the chord shrunk to the point p + i im (e.g. an exact disk of radius 0)
        return im != 0 and evaluate(G, im) == 0
    lo, hi = im - w, im + w
    if lo <= 0 <= hi:
        return False
    return count_roots(G, lo, hi) + (1 if evaluate(G, lo) == 0 else 0) > 0  # roots in (lo, hi], and lo


def _real_rational_roots(G: Any) -> Any:
    """Every real root of G as an exact rational, or None if one is irrational."""
    out = [Fraction(0)] if evaluate(G, Fraction(0)) == 0 else []
    for sign in (1, -1):
        P = strip_zero_roots([c * sign ** k for k, c in enumerate(G)])  # no root at the interval ends
        for lo, hi in positive_roots(P):
            q = rational_root(P, lo, hi)
            if q is None:
                return None
            out.append(sign * q)
    return out


def _cmul(x: Any, y: Any) -> Any:
    return (x[0] * y[0] - x[1] * y[1], x[0] * y[1] + x[1] * y[0])


def _cdiv(x: Any, y: Any) -> Any:
    n = y[0] * y[0] + y[1] * y[1]
    return ((x[0] * y[0] + x[1] * y[1]) / n, (x[1] * y[0] - x[0] * y[1]) / n)


def _ceval(p: Any, z: Any) -> Any:
    acc = (Fraction(0), Fraction(0))
    for c in reversed(p):
        acc = _cmul(acc, z)
        acc = (acc[0] + c, acc[1])
    return acc


def _cpoly_mul(a: Any, b: Any) -> Any:
    out = [(Fraction(0), Fraction(0))] * (len(a) + len(b) - 1)
    for i, x in enumerate(a):
        for j, y in enumerate(b):
            v = _cmul(x, y)
            out[i + j] = (out[i + j][0] + v[0], out[i + j][1] + v[1])
    return out


def _cpoly_pow(a: Any, n: Any) -> Any:
    out = [(Fraction(1), Fraction(0))]
    for _ in range(n):
        out = _cpoly_mul(out, a)
    return out


def line_density(g: Sequence[Fraction], h: Sequence[Fraction], p: Fraction) -> Any:
    """For h squarefree with every root on the line Re z = p (p > 0 rational) at rational heights: the
    polynomial Q with Q >= 0 on R iff f >= 0 on (0, oo) (module docstring), and a description; None when h
    is not of that kind (then no claim is made here)."""
    G = line_gcd(h, p)
    if len(G) != len(h):  # deg G = deg h: every root of h is p + iy with y a root of G
        return None
    ys = _real_rational_roots(G)
    if ys is None or len(set(ys)) != len(h) - 1:
        return None
    return _density_of(g, h, p, ys)


def _density_of(g: Any, h: Any, p: Any, ys: Any) -> Any:
    """(Q, description) for the simple poles p + i y (y in ys, rational) of h: Q(x) = (1 + x^2)^N T(2 atan x),
    T(theta) = sum_y b_y e^(-i n_y theta), b_y = -g(z)/h'(z) (h' of the whole h); None when N > MAX_LINE_EXPONENT
    or some p + iy is not a simple root of h."""
    L = 1
    for y in ys:
        L = L * y.denominator // igcd(L, y.denominator)
    ns = [int(y * L) for y in ys]
    N = max(abs(n) for n in ns)
    if N > MAX_LINE_EXPONENT:
        return None
    charge(fraction_products_cost((len(h) + 4 * N) ** 2 * len(h), _bits(g) + _bits(h) + 4 * N),
           "the trigonometric density polynomial of the line poles")
    dh = [k * c for k, c in enumerate(h)][1:]
    Q = [(Fraction(0), Fraction(0))] * (2 * N + 1)
    one_plus = [(Fraction(1), Fraction(0)), (Fraction(0), Fraction(0)), (Fraction(1), Fraction(0))]  # 1 + x^2
    for y, n in zip(ys, ns):
        z = (p, y)
        d = _ceval(dh, z)
        if d == (0, 0):  # a multiple root: b is no residue of a simple pole
            return None
        b = _cdiv(_ceval(g, z), d)
        b = (-b[0], -b[1])
        base = [(Fraction(1), Fraction(0)), (Fraction(0), Fraction(-1 if n >= 0 else 1))]  # 1 -+ ix
        term = _cpoly_mul(_cpoly_pow(base, 2 * abs(n)), _cpoly_pow(one_plus, N - abs(n)))
        for i, c in enumerate(term):
            v = _cmul(b, c)
            Q[i] = (Q[i][0] + v[0], Q[i][1] + v[1])
    require(all(c[1] == 0 for c in Q), "bernstein: the line poles' density is not real (internal)")
    return trim([c[0] for c in Q]), f"all poles on Re z = {describe(p)} at heights {[describe(y) for y in ys]}"


def line_part(g: Any, h: Any, p: Any) -> Any:
    """B(t) = sum over the poles z on the line Re z = p (p = p*, rational) of b_z e^(-i Im(z) t) is proved >= 0 on
    R, exactly: a description, or None when the line part is not of a kind decided here.  Then
    e^(p t) f(t) = B(t) + R(t) with R the part of the poles off the line (exactinv_check.bernstein: the far piece
    of the balanced case).  The line poles are the real roots y of G = gcd(U, V) for h itself (not its squarefree
    part), with their multiplicities (h(p + iy) = U(y) + iV(y) has a root of multiplicity m at y0 iff h has one at
    p + iy0, and U, V then both do): so G squarefree with G(0) = 0 says p and every line pole are simple, and
    B = b_* + sum b_k e^(-i y_k t) with b = -g(z)/h'(z).  Decided:
     * one pair, G = y^3 - Y y (Y > 0): B = b_* + 2 Re(b e^(-i sqrt(Y) t)), min B = b_* - 2|b|; B >= 0 iff b_* >= 0
       and b_*^2 >= 4 |b|^2, both rational (|g|^2, |h'|^2 at p + i sqrt(Y) are, :func:`_norm_at_line`);
     * every real root of G rational: B(t) = T(t/L) and T >= 0 iff Q >= 0 on R (:func:`_density_of`, Sturm).
    B >= 0 is exact; a line part that is negative somewhere is None (no claim)."""
    G = line_gcd(h, p)
    if len(G) < 4 or G[0] != 0 or G[1] == 0:  # p a simple root of G (p* simple) and at least one pair
        return None
    G_prime = [k * c for k, c in enumerate(G)][1:]
    if len(affordable_gcd(G, G_prime)) > 1:  # a multiple line pole: B would have t^m terms
        return None
    dh = [k * c for k, c in enumerate(h)][1:]
    b_star = -evaluate(g, p) / evaluate(dh, p)
    if len(G) == 4 and G[2] == 0 and G[3] == 1 and -G[1] > 0:
        Y = -G[1]
        b2 = _norm_at_line(g, p, Y) / _norm_at_line(dh, p, Y)
        if not (b_star > 0 and b_star * b_star >= 4 * b2):
            return None
        return (f"the line part B(t) = b_* + 2 Re(b e^(-i sqrt({describe(Y)}) t)) >= 0: b_* = {describe(b_star)}, "
                f"b_*^2 >= 4|b|^2 = {describe(4 * b2)}")
    ys = _real_rational_roots(G)
    if ys is None:
        return None
    density = _density_of(g, h, p, ys)
    if density is None:
        return None
    Q, where = density
    ints = integer_coefficients(Q)
    if len(ints) > 2:
        cost = sturm_cost(len(ints) - 1, max(abs(c).bit_length() for c in ints))
        if cost > STURM_BUDGET or not affordable(cost // STURM_WORDS):
            return None
    if not nonnegative_on_line(Q):
        return None
    return f"the line part B(t) = T(t/L) >= 0 ({where.replace('all poles', 'the line poles')}; Q >= 0 on R, Sturm)"


def _even_odd_at(P: Any, Y: Any) -> Any:
    """(A, B) with P(y) = A + y B for y^2 = Y (A, B rational): the even and odd parts of P at y = sqrt(Y)."""
    A = sum((c * Y ** (k // 2) for k, c in enumerate(P) if k % 2 == 0), Fraction(0))
    B = sum((c * Y ** (k // 2) for k, c in enumerate(P) if k % 2 == 1), Fraction(0))
    return A, B


def _norm_at_line(P: Sequence[Fraction], p: Fraction, Y: Fraction) -> Fraction:
    """|P(p + iy)|^2 for y^2 = Y, exactly: U(y) = A_U, V(y) = y B_V, so U^2 + V^2 = A_U^2 + Y B_V^2."""
    U, V = line_parts(P, p) if len(P) > 1 else (list(P), [])
    A, _ = _even_odd_at(U, Y)
    _, B = _even_odd_at(V, Y)
    norm: Fraction = A * A + Y * B * B
    return norm


def single_pair(g: Sequence[Fraction], h: Sequence[Fraction], p: Fraction) -> tuple[Fraction, Fraction] | None:
    """For h = c (z - p)((z - p)^2 + Y), Y > 0 (p* and one pair p* +- i sqrt(Y) on its line): (b_*, |b|^2),
    exact rationals, where f(t) = e^(-p* t) (b_* + 2 Re(b e^(-i sqrt(Y) t))); so f >= 0 on (0, oo) iff
    b_* >= 0 and b_*^2 >= 4 |b|^2.  (y^2 = Y is rational since (z - p)^2 + Y is a rational factor of h, and
    U, V are even and odd in y, so |g|^2 and |h'|^2 at z are rational.)  None for any other h."""
    if len(h) != 4:
        return None
    G = line_gcd(h, p)
    if len(G) != 4 or G[0] != 0 or G[2] != 0 or G[3] != 1 or not -G[1] > 0:
        return None
    Y = -G[1]
    dh = [k * c for k, c in enumerate(h)][1:]
    b_star = -evaluate(g, p) / evaluate(dh, p)
    return b_star, _norm_at_line(g, p, Y) / _norm_at_line(dh, p, Y)


def nonnegative_on_line(Q: Any) -> Any:
    """Q >= 0 on R: Q positive just right of 0 (or at 0) and no real root of odd multiplicity."""
    if not Q or len(Q) == 1:
        return bool(Q) and Q[0] > 0
    ints = integer_coefficients(Q)
    within_sturm_budget(len(ints) - 1, max(abs(c).bit_length() for c in ints), "the line density's Sturm count")
    if sign_right_of(Q, Fraction(0)) <= 0:
        return False
    odd = [Fraction(1)]
    for q, M in squarefree_decomposition(Q):
        if M % 2:
            odd = mul(odd, q)
    if len(odd) == 1:
        return True
    B = max(abs(c / odd[-1]) for c in odd) + 1
    return count_roots(odd, -B, B) == 0  # every real root lies in (-B, B) (Cauchy)
