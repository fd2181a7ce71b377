"""Certified real roots of rational polynomials (FLINT), and first sign changes.

The paper (Section 3.1.2) needs tau_i, "the first positive zero" of f_i; what
its proof needs is the end of the first interval on which f_i >= 0, i.e. the
first root of *odd* multiplicity (a tangent root of even multiplicity does not
end nonnegativity).  This module computes it exactly:

1. cheap exact filters: all coefficients of f(start + x) nonnegative, or no
   sign variation at all (Descartes' rule of signs) => no root beyond start;
2. FLINT factors f into irreducible integer polynomials with multiplicities;
   factors of even multiplicity cannot change the sign and are dropped, and so
   are factors that Descartes' rule shows have no root beyond start;
3. each remaining irreducible factor's real roots are isolated by FLINT's
   certified (Arb) root isolation; real roots come back with an exactly zero
   imaginary part, and the rational interval read off the ball is re-checked
   by an exact sign change;
4. roots are returned as Fractions (linear factors) or
   :class:`~exactinv.RealAlgebraic` numbers, compared exactly.

No floating-point bisection happens anywhere.
"""

from __future__ import annotations

from fractions import Fraction
from typing import Any

import flint

from ..errors import InvalidInput, VerificationFailed
from .algebraic import ExactKey, FiniteReal, Real
from .flintq import dyadic_of
from .polys import (
    as_polynomial,
    integer_part,
    shift,
    sign_at,
    sign_right_of,
    sign_variations,
)
from .real_algebraic import RealAlgebraic
from .scalars import INF, to_rational

__all__ = [
    "real_roots",
    "first_sign_change",
    "root_bound_exponent",
    "nonnegative_until",
    "positive_roots",
    "negative_segments",
]


def _isolate_irreducible(p: flint.fmpz_poly) -> list[FiniteReal]:
    """The real roots of an irreducible integer polynomial, sorted."""
    if p.degree() == 1:
        a, b = (int(c) for c in p.coeffs())  # b x + a
        return [Fraction(-a, b)]
    out = []
    for z, _ in p.complex_roots():
        if not z.imag.is_zero():
            continue
        lo, hi = dyadic_of(z.real.lower()), dyadic_of(z.real.upper())
        if sign_at(p, lo) * sign_at(p, hi) >= 0:
            raise VerificationFailed(f"root isolation: Arb enclosure ({lo}, {hi}) of a root of {p} has no sign change")
        out.append(RealAlgebraic(p, lo, hi, _trusted=True))
    out.sort()
    return out


def real_roots(f: Any) -> list[tuple[FiniteReal, int]]:
    """All distinct real roots of f with their multiplicities, sorted; exact.

    >>> real_roots([2, -3, 1])                      # (x - 1)(x - 2)
    [(Fraction(1, 1), 1), (Fraction(2, 1), 1)]
    >>> [(str(r), m) for r, m in real_roots([-2, 0, 1])]
    [('-1.414213562373095...', 1), ('1.414213562373095...', 1)]
    """
    fq = as_polynomial(f)
    if fq.is_zero():
        raise InvalidInput("f: the zero polynomial has every number as a root")
    _, factors = integer_part(fq).factor()
    roots = [(r, int(m)) for p, m in factors for r in _isolate_irreducible(p)]
    roots.sort(key=lambda rm: ExactKey(rm[0]))
    return roots


def root_bound_exponent(coeffs: list[int]) -> int:
    """An integer k (of any sign) with every complex root of sum_i c_i x^i (c_d != 0, d >= 1) of
    modulus < 2^k: Fujiwara's bound 2 max_i |c_(d-i)/c_d|^(1/i), each ratio bounded by bit
    lengths (|c_(d-i)/c_d| < 2^(bits(c_(d-i)) - bits(c_d) + 1)).  Unlike Cauchy's bound
    1 + max |c_i/c_d| it scales with the roots: q(t/2^j) gets k + j, so bisecting below 2^k
    costs the same for roots near 10^60, 1 or 10^-60.

    >>> root_bound_exponent([-2, 0, 1]), root_bound_exponent([-(2**400), 0, 1])   # +-sqrt(2), +-2^200
    (2, 202)
    >>> root_bound_exponent([-1, 0, 2**400]), root_bound_exponent([0, 0, 1])      # +-2^-200; only 0
    (-198, 0)
    """
    d, top = len(coeffs) - 1, abs(coeffs[-1]).bit_length()
    k = None
    for i in range(1, d + 1):
        c = coeffs[d - i]
        if c:
            e = abs(c).bit_length() - top + 1
            bound = 1 - (-e // i)  # 1 + ceil(e / i)
            k = bound if k is None else max(k, bound)
    return 0 if k is None else k


def _first_positive_root_interval(q: flint.fmpz_poly) -> tuple[Fraction, Fraction] | Fraction | None:
    """The smallest positive root of a squarefree integer polynomial with
    q(0) != 0: an isolating open interval (a, b), a Fraction if it is a dyadic
    bisection point, or None.  Vincent-Collins-Akritas bisection: Descartes'
    rule on (0, 1) after the Moebius map, children by Taylor shifts in FLINT;
    left-first, so it stops at the first root."""
    d = q.degree()
    if d < 1:
        return None
    coeffs = [int(c) for c in q.coeffs()]
    k = root_bound_exponent(coeffs)  # every root has |z| < 2^k
    if k >= 0:  # q(2^k x), times 2^(-k d) when k < 0: integral, its roots in (0, 1)
        P0 = flint.fmpz_poly([c << (k * i) for i, c in enumerate(coeffs)])
    else:
        P0 = flint.fmpz_poly([c << (-k * (d - i)) for i, c in enumerate(coeffs)])
    unit = Fraction(2) ** k
    one_plus_x = flint.fmpz_poly([1, 1])
    stack = [(0, 0, P0)]  # interval (a/2^level, (a+1)/2^level) * 2^k, P maps (0, 1) onto it
    while stack:
        a, level, P = stack.pop()
        if not isinstance(P, flint.fmpz_poly):  # a marker: a rational root at a bisection point
            return P
        rev = flint.fmpz_poly(list(reversed([int(c) for c in P.coeffs()])))
        variations = sign_variations(rev(one_plus_x).coeffs())
        if variations == 0:
            continue
        scale = unit / 2**level
        if variations == 1:
            return a * scale, (a + 1) * scale
        left = flint.fmpz_poly([int(c) << (d - i) for i, c in enumerate(P.coeffs())])  # 2^d P(x/2)
        right = left(one_plus_x)
        stack.append((2 * a + 1, level + 1, right))
        if right(0) == 0:  # P(1/2) = 0: the midpoint is a root (after everything left of it)
            stack.append((None, None, Fraction(2 * a + 1, 2 ** (level + 1)) * unit))
        stack.append((2 * a, level + 1, left))
    return None


def first_sign_change(f: Any, start: Any = 0) -> Real:
    """The smallest t > start at which f changes sign (a root of odd
    multiplicity), or INF if there is none.  Exact.

    Descartes' rule first (no sign variation of f(start + x): no root); then the
    odd-multiplicity part of f (squarefree factorisation in FLINT), the first
    positive root isolated by Vincent-Collins-Akritas bisection, and the
    irreducible factor that owns it.

    >>> first_sign_change([4, -12, 13, -6, 1])     # (t-1)^2 (t-2)^2: tangent roots only
    INF
    >>> first_sign_change([-3, 7, -5, 1])          # (t-1)^2 (t-3)
    Fraction(3, 1)
    """
    fq = as_polynomial(f)
    start = to_rational(start, "start")
    if fq.is_zero() or fq.degree() == 0:
        return INF
    shifted = integer_part(shift(fq, start))
    if sign_variations(shifted.coeffs()) == 0:  # Descartes: no root beyond start
        return INF
    found = _first_positive_root_interval(_odd_part_beyond_0(shifted))
    if found is None:
        return INF
    if isinstance(found, Fraction):
        return start + found
    return _owning_factor_root(fq, start + found[0], start + found[1])


def _odd_part_beyond_0(f: flint.fmpz_poly) -> flint.fmpz_poly:
    """The product of f's squarefree factors of odd multiplicity, without the
    factor x (a root at 0, i.e. at start, is not beyond it)."""
    _, parts = f.factor_squarefree()
    odd = flint.fmpz_poly([1])
    for p, mult in parts:
        if mult % 2:
            odd *= p
    while odd.degree() > 0 and odd(0) == 0:
        odd = flint.fmpz_poly([int(c) for c in odd.coeffs()[1:]])
    return odd


def _owning_factor_root(fq: flint.fmpq_poly, lo: Fraction, hi: Fraction) -> Real:
    """The root in (lo, hi) of the odd-multiplicity irreducible factor of fq that changes sign there."""
    _, factors = integer_part(fq).factor()
    for p, mult in factors:
        if mult % 2 == 0:
            continue
        if p.degree() == 1:
            c0, c1 = (int(c) for c in p.coeffs())
            r = Fraction(-c0, c1)
            if lo < r < hi:
                return r
            continue
        if sign_at(p, lo) * sign_at(p, hi) < 0:
            return RealAlgebraic(p, lo, hi, _trusted=True)
    raise VerificationFailed("first_sign_change: the isolated root belongs to no factor")


def nonnegative_until(f: Any, start: Any = 0) -> Real:
    """sup{T >= start : f >= 0 on [start, T]} when f >= 0 just right of start
    (f(start) itself is not inspected); ``start`` when f < 0 just right of it.
    This is the paper's tau_i for f_i, with tangent roots stepped over.

    >>> nonnegative_until([2, -3, 1])   # (1 - t)(2 - t) >= 0 until t = 1
    Fraction(1, 1)
    >>> nonnegative_until([1, 0, 1])
    INF
    """
    start = to_rational(start, "start")
    if sign_right_of(f, start) < 0:
        return start
    return first_sign_change(f, start)


def positive_roots(p: flint.fmpq_poly) -> list[tuple[FiniteReal, int]]:
    """The distinct positive roots of p with multiplicities, sorted (none for a constant).

    >>> positive_roots(flint.fmpq_poly([4, -4, 1]) * flint.fmpq_poly([-3, 1]))   # (t - 2)^2 (t - 3)
    [(Fraction(2, 1), 2), (Fraction(3, 1), 1)]
    """
    if p.degree() < 1:
        return []
    return [(r, m) for r, m in real_roots(p) if r > 0]


def negative_segments(p: flint.fmpq_poly) -> list[tuple[Real, Real]]:
    """The open intervals (a, b) in (0, oo) where the polynomial is negative:
    its sign right of 0, flipped at every root of odd multiplicity.

    >>> negative_segments(flint.fmpq_poly([6, -5, 1]))   # (t - 2)(t - 3) < 0 on (2, 3)
    [(Fraction(2, 1), Fraction(3, 1))]
    """
    sign = sign_right_of(p, 0)
    out = []
    left: Real = Fraction(0)
    for r, m in positive_roots(p):
        if sign < 0:
            out.append((left, r))
        if m % 2:
            sign = -sign
        left = r
    if sign < 0:
        out.append((left, INF))
    return out
