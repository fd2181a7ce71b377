"""Non-real poles with exactly p*'s real part: proved exactly, then decided (issue 22; paper, Section 3.2).

A pole z = p* + iy (y != 0) on the vertical line through the smallest positive pole p* is never as close to
-kappa as p* (|z + kappa|^2 = (p* + kappa)^2 + y^2), yet its distance ratio tends to 1 as kappa -> oo; an Arb
enclosure cannot tell Re z = p* from Re z < p* (a tie at a huge kappa).  The proof, for p* rational: with
h(p* + iy) = U(y) + i V(y) (U, V in Q[y]), the real roots y of G = gcd(U, V) are exactly the poles
p* + iy on the line; a root y of G in a pole's Arb box proves that pole to be p* + iy.

Then (:mod:`exactinv.monotonicity.bernstein`, no tie: rho = oo iff f(t) = sum b t^(m-1) e^(-z t)/(m-1)! >= 0):
* p* dominates strictly (line poles of multiplicity < mu, or = mu with sum |b| < b_*): the dominance bound
  with |e^(-(z - p*) t)| = 1;
* every pole on the line, simple, rational heights y_k = n_k/L: f(t) = e^(-p* t) T(t/L) with
  T(theta) = sum b_k e^(-i n_k theta) a real trigonometric polynomial; with x = tan(theta/2),
  Q(x) = (1 + x^2)^N T(theta) is a polynomial and T >= 0 iff Q >= 0 on R (:func:`line_density`): exact;
* p* and one pair p* +- iy (any y): min T = b_* - 2|b|, and b_*^2 - 4|b|^2 is rational (:func:`single_pair`).
The kernel re-proves each (exactinv_check.line_poles, exactinv_check.bernstein).
"""

from __future__ import annotations

from cmath import phase
from dataclasses import dataclass
from fractions import Fraction
from math import atan, gcd, pi

import flint

from exactinv_check.format import MAX_LINE_EXPONENT  # the kernel's bound (exactinv_check.line_poles)

from ..core.flintq import fmpq_of, fraction_of
from ..core.float_hint import float_hint
from ..core.polys import integer_part, sign_right_of
from ..core.roots import real_roots

__all__ = ["line_gcd", "on_line_indices", "line_density", "LinePart", "line_part", "nonnegative", "single_pair",
           "trig_minimum_points", "trig_zero_points", "pair_minimum_points"]



def _parts(f: flint.fmpq_poly, p: Fraction) -> tuple[flint.fmpq_poly, flint.fmpq_poly]:
    """(U, V) with f(p + iy) = U(y) + i V(y)."""
    s = [fraction_of(c) for c in f(flint.fmpq_poly([fmpq_of(p), 1])).coeffs()]
    U = [c * (-1) ** (k // 2) if k % 2 == 0 else 0 for k, c in enumerate(s)]
    V = [c * (-1) ** ((k - 1) // 2) if k % 2 else 0 for k, c in enumerate(s)]
    return flint.fmpq_poly([fmpq_of(Fraction(c)) for c in U]), flint.fmpq_poly([fmpq_of(Fraction(c)) for c in V])


def line_gcd(f: flint.fmpq_poly, p: Fraction) -> flint.fmpq_poly:
    """G = gcd(U, V): its real roots y are exactly the roots p + iy of f on the line Re z = p.

    >>> line_gcd(flint.fmpq_poly([2, -4, 3, -1]), Fraction(1))     # (1 - z)(z^2 - 2z + 2)... roots 1, 1 +- i
    x^3 + (-1)*x
    """
    U, V = _parts(f, p)
    G = U.gcd(V) if not U.is_zero() and not V.is_zero() else (U if V.is_zero() else V)
    return G / G.coeffs()[-1] if not G.is_zero() else flint.fmpq_poly([1])


def on_line_indices(h: flint.fmpq_poly, p: Fraction, balls, candidates) -> frozenset:
    """The indices k in ``candidates`` whose pole (the one root of h in the Arb box balls[k][0]) is proved to
    be p + iy, y != 0 real: a real root y != 0 of :func:`line_gcd` lies in the box's imaginary part (refined
    until it does or is outside) and p in its real part.

    >>> from exactinv.monotonicity.poles import pole_structure, precision, ambiguous_line_poles
    >>> from fractions import Fraction as F
    >>> h = [F(1), F(-2), F(3, 2), F(-1, 2)]                     # poles 1, 1 +- i
    >>> with precision(256):
    ...     s = pole_structure([F(1)], h, F(1))
    ...     left = ambiguous_line_poles(s)
    ...     len(left), on_line_indices(flint.fmpq_poly([2, -4, 3, -1]), F(1), s.balls, left) == frozenset(left)
    (2, True)
    """
    sq = integer_part(h)
    sq = flint.fmpq_poly(sq // sq.gcd(sq.derivative()))
    G = line_gcd(sq, p)
    if G.degree() < 1:
        return frozenset()
    ys = [y for y, _ in real_roots(G) if y != 0]
    out = set()
    for k in candidates:
        z = balls[k][0]
        re_lo, re_hi = _arb_bounds(z.real)
        if not re_lo <= p <= re_hi:  # the exact p in the box's real part
            continue
        box_lo, box_hi = _arb_bounds(z.imag)
        for y in ys:
            for bits in (0, 64, 256, 1024):
                if bits and not isinstance(y, Fraction):
                    y.refine(bits)
                y_lo, y_hi = (y, y) if isinstance(y, Fraction) else (y.lower, y.upper)
                if box_lo <= y_lo and y_hi <= box_hi:
                    out.add(k)
                    break
                if y_hi < box_lo or y_lo > box_hi:
                    break
            if k in out:
                break
    return frozenset(out)


def _arb_bounds(x: flint.arb) -> tuple[Fraction, Fraction]:
    """Rationals lo <= x <= hi (the ends of the ball, exactly: Arb ends are dyadic)."""
    lo, hi = x.lower(), x.upper()
    return _dyadic(lo), _dyadic(hi)


def _dyadic(x: flint.arb) -> Fraction:
    m, e = x.mid().man_exp()
    m, e = int(m), int(e)
    return Fraction(m * 2 ** e) if e >= 0 else Fraction(m, 2 ** -e)


def _real_rational_roots(G: flint.fmpq_poly) -> list[Fraction] | None:
    roots = real_roots(G)
    if any(not isinstance(y, Fraction) for y, _ in roots):
        return None
    return [y for y, _ in roots]


def _c(x: Fraction, y: Fraction = Fraction(0)) -> tuple[Fraction, Fraction]:
    return (Fraction(x), Fraction(y))


def _cmul(a, b):
    return (a[0] * b[0] - a[1] * b[1], a[0] * b[1] + a[1] * b[0])


def _cdiv(a, b):
    n = b[0] * b[0] + b[1] * b[1]
    return ((a[0] * b[0] + a[1] * b[1]) / n, (a[1] * b[0] - a[0] * b[1]) / n)


def _ceval(coeffs, z):
    acc = _c(Fraction(0))
    for c in reversed(coeffs):
        acc = _cmul(acc, z)
        acc = (acc[0] + c, acc[1])
    return acc


def _pmul(a, b):
    out = [_c(Fraction(0))] * (len(a) + len(b) - 1)
    for i, x in enumerate(a):
        for j, y in enumerate(b):
            v = _cmul(x, y)
            out[i + j] = (out[i + j][0] + v[0], out[i + j][1] + v[1])
    return out


def _ppow(a, n):
    out = [_c(Fraction(1))]
    for _ in range(n):
        out = _pmul(out, a)
    return out


def line_density(g: list, h: list, p: Fraction):
    """For h squarefree with every root on Re z = p at rational heights y_k: (Q, L, [(y_k, b_k)]) with
    f(t) = e^(-p t) T(t/L), Q(x) = (1 + x^2)^N T(2 atan x) (so T >= 0 iff Q >= 0 on R); None otherwise.

    1/((1 - z)(1 - z + z^2/2)), poles 1, 1 +- i: f(t) = 2 e^(-t) (1 - cos t), Q = 4x^2.

    >>> from fractions import Fraction as F
    >>> Q, L, _ = line_density([F(1)], [F(1), F(-2), F(3, 2), F(-1, 2)], F(1))
    >>> [str(c) for c in Q], L
    (['0', '0', '4'], 1)
    """
    hq = flint.fmpq_poly([fmpq_of(c) for c in h])
    if hq.gcd(hq.derivative()).degree() > 0:
        return None
    G = line_gcd(hq, p)
    if G.degree() != hq.degree():
        return None
    ys = _real_rational_roots(G)
    if ys is None or len(ys) != hq.degree():
        return None
    return _density_of(g, h, p, ys)


def _density_of(g: list, h: list, p: Fraction, ys: list[Fraction]):
    """(Q, L, [(y, b)]) for the simple roots p + iy (y in ys) of h, b = -g(z)/h'(z) with h' of the whole h:
    Q(x) = (1 + x^2)^N T(2 atan x), T(theta) = sum b_y e^(-i n_y theta); None beyond MAX_LINE_EXPONENT."""
    L = 1
    for y in ys:
        L = L * y.denominator // gcd(L, y.denominator)
    ns = [int(y * L) for y in ys]
    N = max(abs(n) for n in ns)
    if N > MAX_LINE_EXPONENT:
        return None
    dh = [k * c for k, c in enumerate(h)][1:]
    Q = [_c(Fraction(0))] * (2 * N + 1)
    one_plus = [_c(Fraction(1)), _c(Fraction(0)), _c(Fraction(1))]
    pairs = []
    for y, n in zip(ys, ns):
        z = (p, y)
        d = _ceval(dh, z)
        if d == (0, 0):
            return None
        b = _cdiv(_ceval(g, z), d)
        b = (-b[0], -b[1])
        pairs.append((y, b))
        base = [_c(Fraction(1)), _c(Fraction(0), Fraction(-1 if n >= 0 else 1))]
        term = _pmul(_ppow(base, 2 * abs(n)), _ppow(one_plus, N - abs(n)))
        for i, c in enumerate(term):
            v = _cmul(b, c)
            Q[i] = (Q[i][0] + v[0], Q[i][1] + v[1])
    Qr = [c[0] for c in Q]
    while Qr and Qr[-1] == 0:
        Qr.pop()
    return Qr, L, pairs


@dataclass(frozen=True)
class LinePart:
    """The part B(t) = b_* + sum_k b_k e^(-i y_k t) of e^(p* t) f(t) that belongs to p* and the poles on its line,
    decided exactly: ``nonnegative`` (B >= 0 on R), ``how`` (which proof), ``points``: rational t > 0 near B's
    zeros (B >= 0) or near its negative values (else) -- float hints for a witness search, never raising."""

    nonnegative: bool
    how: str
    points: tuple


def line_part(g: list, h: list, p: Fraction) -> LinePart | None:
    """B >= 0 decided exactly for p* = p rational and simple with simple line poles (G = gcd(U, V) of h itself
    squarefree, G(0) = 0): one pair (G = y^3 - Y y: B >= 0 iff b_* >= 0 and b_*^2 >= 4|b|^2, rational), or every
    line pole at a rational height (the density polynomial Q >= 0 on R, Sturm).  None for any other line part.
    The other poles of h may be anywhere (their part R is the caller's: exactinv.monotonicity.bernstein).

    1/((1 - z)(1 - z + z^2/2)(1 - z/3)): poles 1, 1 +- i and 3 off the line; B = b_* + 2 Re(b e^(-it)):

    >>> from fractions import Fraction as F
    >>> h = [F(1), F(-7, 3), F(13, 6), F(-1), F(1, 6)]     # (1 - z)(1 - z + z^2/2)(1 - z/3)
    >>> part = line_part([F(1)], h, F(1))
    >>> part.nonnegative, part.how.startswith("one pair")
    (True, True)
    """
    hq = flint.fmpq_poly([fmpq_of(c) for c in h])
    G = line_gcd(hq, p)
    c = [fraction_of(x) for x in G.coeffs()]
    if len(c) < 4 or c[0] != 0 or c[1] == 0 or G.gcd(G.derivative()).degree() > 0:
        return None
    if len(c) == 4 and c[2] == 0 and -c[1] > 0:
        Y = -c[1]
        b_star, b2 = _pair_residues(g, h, p, Y)
        ok = b_star > 0 and b_star * b_star >= 4 * b2
        return LinePart(ok, f"one pair p* +- i sqrt({Y}): B = b_* + 2 Re(b e^(-iyt)), b_*^2 = {b_star * b_star}, "
                            f"4|b|^2 = {4 * b2}", tuple(pair_minimum_points(g, h, p, Y)))
    ys = _real_rational_roots(G)
    if ys is None:
        return None
    density = _density_of(g, h, p, ys)
    if density is None:
        return None
    Q, L, _ = density
    ok = nonnegative(Q)
    points = trig_zero_points(Q, L) if ok else trig_minimum_points(Q, L)
    return LinePart(ok, f"line poles at rational heights {[str(y) for y in ys]}: B(t) = T(t/{L}), Q "
                        f"{'>=' if ok else 'not >='} 0 on R", tuple(points))


def trig_zero_points(Q: list, L: int, periods: int = 6) -> list[Fraction]:
    """Rational t > 0 near the zeros of T(t/L) (Q(tan(theta/2)) = 0 at the real roots x of Q), over a few periods
    2 pi L: float hints for a witness search (never raising; theta = pi, a zero when deg Q < 2N, is not listed).

    >>> from exactinv.core.float_hint import float_hint
    >>> [round(float_hint(t), 4) for t in trig_zero_points([0, 0, 4], 1, 2)]    # T = 2(1 - cos theta): theta = 2 pi n
    [6.2832, 12.5664]
    """
    out = []
    try:
        q = flint.fmpq_poly([fmpq_of(c) for c in Q])
        thetas = [2 * atan(float_hint(x.lower if hasattr(x, "lower") else x)) for x, _ in real_roots(q)] \
            if q.degree() > 0 else []
        for k in range(periods + 1):
            for theta in thetas:
                t = (theta % (2 * pi) + 2 * pi * k) * L
                if t > 0:
                    out.append(Fraction(t).limit_denominator(1 << 24))
    except (OverflowError, ValueError, ZeroDivisionError):
        return out
    return sorted(set(out))[: 4 * (periods + 1)]


def nonnegative(Q: list) -> bool:
    """Q >= 0 on R, exactly (positive right of 0, no real root of odd multiplicity).

    >>> nonnegative([0, 0, 4]), nonnegative([-1, 0, 1]), nonnegative([1, -2, 1])   # 4x^2; x^2 - 1; (x - 1)^2
    (True, False, True)
    """
    if not Q:
        return False
    q = flint.fmpq_poly([fmpq_of(c) for c in Q])
    if q.degree() == 0:
        return Q[0] > 0
    if sign_right_of(q, Fraction(0)) <= 0:
        return False
    return not any(m % 2 for _, m in real_roots(q))


def trig_minimum_points(Q: list, L: int) -> list[Fraction]:
    """Rational t > 0 near points where Q(tan(t/(2L))) < 0 (hints for the witness search; floats only here,
    never raising): theta = 2 atan x at the negative values of Q on a grid.

    >>> pts = trig_minimum_points([-1, 0, 1], 1)        # Q = x^2 - 1 < 0 for |x| < 1: theta in (-pi/2, pi/2)
    >>> 0 < len(pts) <= 8 and all(t > 0 for t in pts)
    True
    """
    out = []
    for k in range(-400, 401):
        x = k / 40
        try:
            v = sum(float_hint(c) * x ** i for i, c in enumerate(Q))
        except (OverflowError, ValueError):
            continue
        if v < 0:
            theta = 2 * atan(x)
            if theta <= 0:
                theta += 2 * pi
            out.append(Fraction(theta * L).limit_denominator(1 << 20))
    return out[:: max(1, len(out) // 8)][:8]


def pair_minimum_points(g: list, h: list, p: Fraction, Y: Fraction) -> list[Fraction]:
    """Rational t > 0 near the minima of b_* + 2 Re(b e^(-iyt)), z = p + iy, y = sqrt(Y), b = -g(z)/h'(z):
    yt = arg b - pi mod 2 pi (float hints only; they never raise, they may only fail to help).

    >>> from fractions import Fraction as F
    >>> from exactinv.core.float_hint import float_hint
    >>> pts = pair_minimum_points([F(1)], [F(1), F(-2), F(3, 2), F(-1, 2)], F(1), F(1))   # b = -1: minima at t = 2 pi n
    >>> [round(float_hint(t), 4) for t in pts[:2]]
    [6.2832, 12.5664]
    """
    try:
        y = float_hint(Y) ** 0.5
        z = complex(float_hint(p), y)
        gz = sum(float_hint(c) * z ** k for k, c in enumerate(g))
        dz = sum(k * float_hint(c) * z ** (k - 1) for k, c in enumerate(h) if k)
        t = (phase(-gz / dz) - pi) / y
        period = 2 * pi / y
        return [Fraction(t + k * period).limit_denominator(1 << 24) for k in range(8) if t + k * period > 0]
    except (OverflowError, ValueError, ZeroDivisionError):
        return []


def single_pair(g: list, h: list, p: Fraction):
    """For h = c (z - p)((z - p)^2 + Y), Y > 0: (b_*, |b|^2, Y) exactly (f(t) = e^(-p t)(b_* + 2 Re(b e^(-i sqrt(Y) t))),
    so f >= 0 iff b_* >= 0 and b_*^2 >= 4|b|^2); None otherwise.

    >>> from fractions import Fraction as F
    >>> single_pair([F(1)], [F(1), F(-5, 3), F(1), F(-1, 3)], F(1))   # (1 - z)(1 - 2z/3 + z^2/3): 1, 1 +- i sqrt 2
    (Fraction(3, 2), Fraction(9, 16), Fraction(2, 1))
    """
    if len(h) != 4:
        return None
    hq = flint.fmpq_poly([fmpq_of(c) for c in h])
    G = line_gcd(hq, p)
    c = [fraction_of(x) for x in G.coeffs()]
    if len(c) != 4 or c[0] != 0 or c[2] != 0 or not -c[1] > 0:
        return None
    Y = -c[1]
    b_star, b2 = _pair_residues(g, h, p, Y)
    return b_star, b2, Y


def _pair_residues(g: list, h: list, p: Fraction, Y: Fraction) -> tuple[Fraction, Fraction]:
    """(b_*, |b|^2) exactly: b = -g(z)/h'(z) at p* and at z = p + i sqrt(Y) (h' of the whole h)."""
    dh = [k * x for k, x in enumerate(h)][1:]

    def norm(P):
        U, V = _parts(flint.fmpq_poly([fmpq_of(x) for x in P]), p)
        u, v = [fraction_of(x) for x in U.coeffs()], [fraction_of(x) for x in V.coeffs()]
        A = sum((x * Y ** (k // 2) for k, x in enumerate(u) if k % 2 == 0), Fraction(0))
        B = sum((x * Y ** (k // 2) for k, x in enumerate(v) if k % 2 == 1), Fraction(0))
        return A * A + Y * B * B

    b_star = -sum(x * p ** k for k, x in enumerate(g)) / sum(x * p ** k for k, x in enumerate(dh))
    return b_star, norm(g) / norm(dh)
