"""Signs of rational polynomials at and just right of an exact real, and the next sign change.

The LP route (:mod:`exactinv.validset.lp_route`) starts a piece at a breakpoint t,
a Fraction or a :class:`~exactinv.RealAlgebraic` (a root of an irreducible
integer polynomial q, isolated).  It needs, exactly:

* the sign of p just right of t (:func:`sign_right_of_real`): for a rational t
  the first nonzero Taylor coefficient; for t = alpha algebraic, write
  p = q^k r with q not dividing r (q irreducible, so alpha is a simple root of q
  and r(alpha) != 0); then sign p(alpha + eps) = sign(q right of alpha)^k
  sign r(alpha), where q right of alpha has the sign of q at the isolating
  interval's upper end, and r(alpha) the sign of r on an enclosure of alpha
  that Descartes' rule proves root-free for r;
* the first point after t where p changes sign (:func:`next_sign_change`): the
  least root of odd multiplicity of p greater than t (FLINT's certified roots);
* a rational strictly right of t and within a given width (:func:`rational_right_of`).

No float anywhere.
"""

from __future__ import annotations

import math
from fractions import Fraction

import flint

from .algebraic import FiniteReal, Real
from .flintq import dyadic_of, fmpq_of
from .float_hint import float_hint
from .polys import ONE_PLUS_X, integer_part, no_root_between, sign_at, sign_right_of, sign_variations
from .real_algebraic import RealAlgebraic
from .roots import first_sign_change
from .scalars import INF

__all__ = ["sign_right_of_real", "next_sign_change", "rational_right_of", "interval_signs", "narrowed",
           "positive_after", "sign_change_near"]


def narrowed(alpha: FiniteReal) -> FiniteReal:
    """alpha itself, for an algebraic alpha with a narrow isolating interval.  First a float hint:
    Newton's iteration from the enclosure's midpoint, a dyadic x, and the enclosure
    [x - 2^-44 (1 + |x|), x + 2^-44 (1 + |x|)] kept only if it lies inside the old one and an exact
    sign change of the polynomial confirms it (the old enclosure holds one root, so it is alpha).
    Then the enclosure of the matching root from FLINT's certified complex roots (Arb balls), checked
    the same way; else exact bisection to width 2^-48.

    >>> r = narrowed(RealAlgebraic.from_isolating_interval([-2, 0, 1], 1, 2))
    >>> r.upper - r.lower < Fraction(1, 2**40), r.lower ** 2 < 2 < r.upper ** 2
    (True, True)
    """
    if not isinstance(alpha, RealAlgebraic):
        return alpha
    p = alpha.poly
    hint = _newton(p, alpha.lower, alpha.upper)
    if hint is not None:
        return hint
    for z, _ in p.complex_roots():
        if not z.imag.is_zero():
            continue
        lo = dyadic_of(z.real.lower())
        hi = dyadic_of(z.real.upper())
        if alpha.lower <= lo < hi <= alpha.upper and sign_at(p, lo) * sign_at(p, hi) < 0:
            return RealAlgebraic(p, lo, hi, _trusted=True)
    return alpha.refine(48)


def _newton(p: flint.fmpz_poly, lower: Fraction, upper: Fraction) -> RealAlgebraic | None:
    """A narrow enclosure of p's one root in (lower, upper) from a float Newton iteration, proved by an
    exact sign change inside (lower, upper); None when the hint does not help (never raises)."""
    try:
        c = [float_hint(v) for v in p.coeffs()]
        dc = [k * c[k] for k in range(1, len(c))]
        x = (float_hint(lower) + float_hint(upper)) / 2
        for _ in range(30):
            f = df = 0.0
            for v in reversed(c):
                f = f * x + v
            for v in reversed(dc):
                df = df * x + v
            if not df or not math.isfinite(f / df):
                return None
            step = f / df
            x -= step
            if abs(step) <= 1e-15 * (1 + abs(x)):
                break
        if not math.isfinite(x):
            return None
        mid = Fraction(x)
    except (OverflowError, ValueError, ZeroDivisionError):
        return None
    width = (1 + abs(mid)) / 2**44
    width = Fraction(1, 2 ** max(0, -(width.numerator.bit_length() - width.denominator.bit_length())))
    lo, hi = mid - width, mid + width
    if lower <= lo and hi <= upper and sign_at(p, lo) * sign_at(p, hi) < 0:
        return RealAlgebraic(p, lo, hi, _trusted=True)
    return None


def interval_signs(M: flint.fmpq_mat | flint.fmpz_mat, lo: Fraction, hi: Fraction | None) -> list[int]:
    """For each row of M (the coefficients, constant first, of a polynomial p): +1 if Descartes'
    rule proves p > 0 on the open interval (lo, hi) (hi None: (lo, oo)) or p = 0, -1 if it proves
    p < 0 there, 0 if it proves nothing.  All rows at once: p(lo + y) by one product with the
    Taylor-shift matrix, then for a finite hi = lo + H the coefficients of
    (1 + y)^d p(lo + H y/(1 + y)), whose sign variations bound p's roots in (lo, hi)
    (as in :func:`exactinv.core.polys.positive_below`).  Exact: on integers (M's numerators and the
    transform's, each over one positive common denominator, which changes no sign).

    >>> M = flint.fmpq_mat([[2, -3, 1], [-2, 0, 1], [0, 0, 0], [-1, 0, -1]])  # (x-1)(x-2), x^2-2, 0, -1-x^2
    >>> # (x-1)(x-2) > 0 and x^2 - 2 < 0 on (0, 1); beyond 2 every one keeps its sign
    >>> interval_signs(M, Fraction(0), Fraction(1)), interval_signs(M, Fraction(2), None)
    ([1, -1, 1, -1], [1, 1, 1, -1])
    >>> interval_signs(flint.fmpz_mat([[2, -3, 1], [-2, 0, 1]]), Fraction(0), Fraction(1))
    [1, -1]
    """
    W = M.ncols()
    if isinstance(M, flint.fmpq_mat):
        M = M.numer_denom()[0]  # a positive common denominator: the same signs
    T = _descartes_matrix(W, lo, hi)
    entries = (M * T).entries()
    out = []
    zero = flint.fmpz(0)  # fmpz against fmpz: compared in C
    for r in range(M.nrows()):
        row = entries[r * W:(r + 1) * W]
        positive = negative = False
        for c in row:
            if c > zero:
                positive = True
            elif c < zero:
                negative = True
        out.append(0 if positive and negative else -1 if negative else 1)
    return out


def _descartes_matrix(W: int, lo: Fraction, hi: Fraction | None) -> flint.fmpz_mat:
    """The W x W integer matrix T (times a positive integer) of :func:`interval_signs`: row k holds the
    coefficients of (lo + y)^k (hi None), or of (lo + hi y)^k (1 + y)^(d - k), d = W - 1."""
    d = W - 1
    if hi is None:  # (a + q y)^k / q^k for lo = a/q: times q^d, row k is (a + q y)^k q^(d - k)
        a, q = lo.numerator, lo.denominator
        base, one = flint.fmpz_poly([a, q]), flint.fmpz_poly([q])
    else:  # lo = a/q, hi = c/r: (lo + hi y)^k (1 + y)^(d-k) times (q r)^d: (a r + c q y)^k ((1 + y) q r)^(d-k)
        a, q, c, r = lo.numerator, lo.denominator, hi.numerator, hi.denominator
        base, one = flint.fmpz_poly([a * r, c * q]), flint.fmpz_poly([q * r, q * r])
    rows: list = []
    power, other = flint.fmpz_poly([1]), [flint.fmpz_poly([1])]
    for _ in range(d):
        other.append(other[-1] * one)
    for k in range(W):
        c = (power * other[d - k]).coeffs()
        rows.extend(c + [0] * (W - len(c)))
        power = power * base
    return flint.fmpz_mat(W, W, rows)


def _sign_at_algebraic(r: flint.fmpz_poly, alpha: RealAlgebraic) -> int:
    """sign r(alpha) for r with r(alpha) != 0: first r on a ball holding alpha's enclosure (Arb's
    rigorous ball arithmetic: a ball that excludes 0 decides); else alpha refined until r has no
    root on its closed enclosure (Descartes), and r's sign at an end."""
    ball = flint.arb(flint.fmpq(alpha.lower.numerator, alpha.lower.denominator)).union(
        flint.arb(flint.fmpq(alpha.upper.numerator, alpha.upper.denominator)))
    value = flint.arb_poly([flint.arb(c) for c in r.coeffs()])(ball)
    if value > 0:
        return 1
    if value < 0:
        return -1
    bits = 16
    while True:
        lo, hi = alpha.lower, alpha.upper
        if sign_at(r, lo) != 0 and sign_at(r, hi) != 0 and no_root_between(r, lo, hi):
            return sign_at(r, lo)
        alpha.refine(bits)
        bits *= 2


def _split(p: flint.fmpq_poly, alpha: RealAlgebraic) -> tuple[flint.fmpz_poly, flint.fmpz_poly, int]:
    """(q, r, k): c p = q^k r for a c > 0 (integers), q = alpha's minimal polynomial, q not dividing r:
    r(alpha) != 0."""
    q = flint.fmpz_poly(alpha.poly)
    r, k = integer_part(p), 0
    while True:
        quotient, remainder = divmod(r, q)
        if not remainder.is_zero():
            return q, r, k
        r, k = quotient, k + 1


def sign_at_real(p: flint.fmpq_poly, t: FiniteReal) -> int:
    """The exact sign of p at t, rational or algebraic (0 when t's minimal polynomial divides p).

    >>> sqrt2 = RealAlgebraic.from_isolating_interval([-2, 0, 1], 1, 2)
    >>> [sign_at_real(flint.fmpq_poly(c), sqrt2) for c in ([-2, 0, 1], [-3, 2], [2, -1, 0, 0, 1])]
    [0, -1, 1]
    """
    if p.is_zero():
        return 0
    if not isinstance(t, RealAlgebraic):
        return sign_at(p, Fraction(t))
    _, r, k = _split(p, t)
    return 0 if k else _sign_at_algebraic(r, t)


def sign_right_of_real(p: flint.fmpq_poly, t: FiniteReal) -> int:
    """The sign of p on (t, t + eps) for small eps > 0 (0 only for p = 0); exact.

    >>> sqrt2 = RealAlgebraic.from_isolating_interval([-2, 0, 1], 1, 2)
    >>> p = flint.fmpq_poly([2, 0, -1])                       # 2 - x^2: zero at sqrt 2, negative after
    >>> sign_right_of_real(p, sqrt2), sign_right_of_real(p * p, sqrt2), sign_right_of_real(p + 1, sqrt2)
    (-1, 1, 1)
    """
    if not isinstance(t, RealAlgebraic):
        return sign_right_of(p, Fraction(t))
    if p.is_zero():
        return 0
    q, r, k = _split(p, t)
    sign = _sign_at_algebraic(r, t)
    if k % 2:
        sign *= sign_at(q, t.upper)  # q's sign right of its simple root alpha: (alpha, upper) holds no other root
    return sign


def positive_after(p: flint.fmpq_poly, t: FiniteReal, bound: Fraction, right: int | None = None) -> bool:
    """True proves p > 0 on the open (t, bound) (a rational bound); False says nothing.  ``right``,
    if given, is :func:`sign_right_of_real` (p, t), already known.  For t = alpha algebraic,
    c p = q^k r (:func:`_split`): r has no root on [lower, bound) and q none on [upper, bound)
    (Descartes; q's only root in (lower, upper) is alpha), so p keeps its sign right of alpha.

    >>> sqrt2 = RealAlgebraic.from_isolating_interval([-2, 0, 1], 1, 2)
    >>> p = flint.fmpq_poly([-2, 0, 1]) * flint.fmpq_poly([-3, 1]) * -1     # (x^2 - 2)(3 - x)
    >>> positive_after(p, sqrt2, Fraction(3)), positive_after(p, sqrt2, Fraction(4))
    (True, False)
    """
    if p.is_zero():
        return False
    if right is None:
        right = sign_right_of_real(p, t)
    if right <= 0:
        return False
    if not isinstance(t, RealAlgebraic):
        return Fraction(t) < bound and no_root_between(p, Fraction(t), bound)
    if not t.upper < bound:
        return False
    q, r, k = _split(p, t)
    if r.degree() > 0 and not (sign_at(r, t.lower) != 0 and no_root_between(r, t.lower, bound)):
        return False
    return k == 0 or no_root_between(q, t.upper, bound)


def next_sign_change(p: flint.fmpq_poly, t: FiniteReal) -> Real:
    """The least root of odd multiplicity of p greater than t (INF if none): where p,
    of one sign just right of t, first takes the other one.

    For t = alpha algebraic: p = q^k r as above; alpha is refined until r has no root on
    its closed enclosure [lower, upper] (which holds no other root of q either), and the
    answer is the first sign change beyond ``upper`` of r, and of q when k is odd.

    >>> sqrt2 = RealAlgebraic.from_isolating_interval([-2, 0, 1], 1, 2)
    >>> next_sign_change(flint.fmpq_poly([6, -5, 1]), sqrt2)     # (x - 2)(x - 3)
    Fraction(2, 1)
    >>> next_sign_change(flint.fmpq_poly([-2, 0, 1]) * flint.fmpq_poly([-3, 1]), sqrt2)   # (x^2 - 2)(x - 3)
    Fraction(3, 1)
    >>> next_sign_change(flint.fmpq_poly([4, -4, 1]), Fraction(0))   # (x - 2)^2: tangent only
    INF
    """
    if p.is_zero() or p.degree() < 1:
        return INF
    if not isinstance(t, RealAlgebraic):
        return first_sign_change(p, Fraction(t))
    q, r, k = _split(p, t)
    bits = 16
    while not (r.degree() < 1 or (sign_at(r, t.lower) != 0 and sign_at(r, t.upper) != 0
                                   and no_root_between(r, t.lower, t.upper))):
        t.refine(bits)
        bits *= 2
    end = first_sign_change(flint.fmpq_poly(r), t.upper) if r.degree() > 0 else INF
    if k % 2:
        other = first_sign_change(flint.fmpq_poly(q), t.upper)
        if other < end:
            end = other
    return end


def sign_change_near(p: flint.fmpq_poly, t: FiniteReal, left: float, right: float) -> Real | None:
    """The least root of odd multiplicity of p greater than t (as :func:`next_sign_change`), when a float
    hint is right; None when it is not (then nothing is proved).  The hint: p(left) >= 0 > p(right) in
    floats, t < left < right.  A float root x in [left, right] (safeguarded Newton), and then, exactly,
    with dyadics lo < x < hi (hi - lo about 2^-43 (1 + |x|)) and a = t (t.lower for an algebraic t):

    * lo > t (lo > t.upper), Descartes proves no root of p in (a, lo), and p(lo) > 0: p > 0 on (t, lo];
    * p(hi) < 0: p has a root of odd multiplicity in (lo, hi), so the least one beyond t lies there;
    * of p's irreducible factors of odd multiplicity, exactly one has a root in (lo, hi), and exactly one
      (Descartes: one sign variation), the others none (no variation).

    Then that root is the answer: a Fraction (a linear factor) or a :class:`RealAlgebraic` isolated by
    (lo, hi), already narrow.  One exact factorisation and a few Descartes tests, no root isolation.

    >>> r = sign_change_near(flint.fmpq_poly([2, 0, -1]), Fraction(0), 1.0, 2.0)     # 2 - x^2: sqrt 2
    >>> str(r.poly), r.upper - r.lower <= Fraction(1, 2**42)
    ('x^2 + (-2)', True)
    >>> sign_change_near(flint.fmpq_poly([6, -5, 1]), Fraction(0), 1.0, 2.5)     # (x - 2)(x - 3): 2
    Fraction(2, 1)
    >>> sign_change_near(flint.fmpq_poly([6, -5, 1]), Fraction(0), 2.5, 2.9) is None   # a wrong hint
    True
    """
    x = _float_root(p, left, right)
    if x is None:
        return None
    # dyadics lo < x < hi, hi - lo = 2^(1 - k) <= 2^-43 (1 + |x|): fmpq throughout, Fractions once at the end
    _, top_exponent = math.frexp(1 + abs(x))
    k = 45 - top_exponent
    width = flint.fmpq(1, 2**k) if k >= 0 else flint.fmpq(2 ** -k)
    mid = flint.fmpq(*x.as_integer_ratio())
    lo, hi = mid - width, mid + width
    if isinstance(t, RealAlgebraic):
        a, top = fmpq_of(t.lower), fmpq_of(t.upper)
    else:
        a = top = fmpq_of(Fraction(t))
    if not (top < lo and p(lo) > 0 and p(hi) < 0 and _variations_between(p, a, lo) == 0):
        return None
    _, factors = integer_part(p).factor()
    found: Real | None = None
    for f, m in factors:
        if m % 2 == 0:
            continue
        count = _variations_between(f, lo, hi)
        if count == 0:
            continue
        if count > 1 or found is not None:
            return None
        if f.degree() == 1:
            c0, c1 = (int(c) for c in f.coeffs())
            found = Fraction(-c0, c1)
        else:
            f = f if f.leading_coefficient() > 0 else -f
            found = RealAlgebraic(f, _fraction(lo), _fraction(hi), _trusted=True)
    return found


def _fraction(x: flint.fmpq) -> Fraction:
    return Fraction(int(x.p), int(x.q))


def _variations_between(f: flint.fmpz_poly | flint.fmpq_poly, lo: flint.fmpq, hi: flint.fmpq) -> int:
    """The sign variations of (1 + y)^d f((lo + hi y)/(1 + y)): by Descartes' rule at least the number of
    f's roots in (lo, hi), of the same parity (0: none; 1: exactly one)."""
    shifted = flint.fmpq_poly(f)(flint.fmpq_poly([lo, hi - lo]))
    return sign_variations(flint.fmpq_poly(list(reversed(shifted.coeffs())))(ONE_PLUS_X).coeffs())


def _float_root(p: flint.fmpq_poly, left: float, right: float) -> float | None:
    """A float root of p in [left, right] where p(left) >= 0 > p(right) in floats (safeguarded Newton on
    the bracket); None when the floats do not show that bracket.  A hint: never raises."""
    try:
        c = [float_hint(v) for v in integer_part(p).coeffs()]
        scale = max((abs(v) for v in c), default=0.0)
        if not (scale > 0 and math.isfinite(scale)):
            return None
        c = [v / scale for v in c]

        def value(x: float) -> tuple[float, float]:
            f = df = 0.0
            for v in reversed(c):
                df = df * x + f
                f = f * x + v
            return f, df

        a, b = left, right
        if not (math.isfinite(a) and math.isfinite(b) and a < b and value(a)[0] >= 0 > value(b)[0]):
            return None
        x = (a + b) / 2
        for _ in range(200):
            f, df = value(x)
            if f >= 0:
                a = x
            else:
                b = x
            step = x - f / df if df else math.nan
            x_next = step if a < step < b else (a + b) / 2
            if b - a <= 1e-15 * (1 + abs(x)) or abs(x_next - x) <= 1e-16 * (1 + abs(x)):
                return x_next
            x = x_next
        return x
    except (OverflowError, ValueError, ZeroDivisionError):
        return None


def rational_right_of(t: FiniteReal, width: Fraction) -> Fraction:
    """A rational s with t < s <= t + width (width > 0).

    >>> rational_right_of(Fraction(1), Fraction(1, 4))
    Fraction(5, 4)
    >>> s = rational_right_of(RealAlgebraic.from_isolating_interval([-2, 0, 1], 1, 2), Fraction(1, 100))
    >>> 2 < s * s and s < Fraction(14242, 10000)      # sqrt 2 < s <= sqrt 2 + 1/100
    True
    """
    if not isinstance(t, RealAlgebraic):
        return Fraction(t) + width
    bits = 8
    while t.upper - t.lower > width / 2:
        t.refine(bits)
        bits *= 2
    return t.upper + width / 2  # t < upper and upper + width/2 < t + width/2 + width/2
