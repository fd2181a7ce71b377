"""Signs of rational polynomials at and just right of an exact real, and the next sign change.

The LP route (:mod:`exactinv.beyond.lp_route`) starts a piece at a breakpoint t,
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

from fractions import Fraction

import flint

from .algebraic import FiniteReal, Real, RealAlgebraic
from .polys import integer_part, no_root_between, sign_at, sign_right_of
from .roots import first_sign_change, real_roots
from .scalars import INF

__all__ = ["sign_right_of_real", "next_sign_change", "rational_right_of"]


def _sign_at_algebraic(r: flint.fmpz_poly, alpha: RealAlgebraic) -> int:
    """sign r(alpha) for r with r(alpha) != 0: refine alpha until r has no root on its closed enclosure."""
    bits = 16
    while True:
        lo, hi = alpha.lower, alpha.upper
        if sign_at(r, lo) != 0 and sign_at(r, hi) != 0 and no_root_between(r, lo, hi):
            return sign_at(r, lo)
        alpha.refine(bits)
        bits *= 2


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
    q = flint.fmpz_poly(t.poly)
    r, k = integer_part(p), 0
    while True:
        quotient, remainder = divmod(r, q)
        if not remainder.is_zero():
            break
        r, k = quotient, k + 1
    sign = _sign_at_algebraic(r, t)
    if k % 2:
        sign *= sign_at(q, t.upper)  # q's sign right of its simple root alpha: (alpha, upper) holds no other root
    return sign


def next_sign_change(p: flint.fmpq_poly, t: FiniteReal) -> Real:
    """The least root of odd multiplicity of p greater than t (INF if none): where p,
    of one sign just right of t, first takes the other one.

    >>> sqrt2 = RealAlgebraic.from_isolating_interval([-2, 0, 1], 1, 2)
    >>> next_sign_change(flint.fmpq_poly([6, -5, 1]), sqrt2)     # (x - 2)(x - 3)
    Fraction(2, 1)
    >>> next_sign_change(flint.fmpq_poly([4, -4, 1]), Fraction(0))   # (x - 2)^2: tangent only
    INF
    """
    if p.is_zero() or p.degree() < 1:
        return INF
    if not isinstance(t, RealAlgebraic):
        return first_sign_change(p, Fraction(t))
    # Descartes first: no sign variation of p(lower + x) means no root beyond t at all
    from_lower = first_sign_change(p, t.lower)
    if from_lower == INF or from_lower > t:
        return from_lower
    for root, multiplicity in real_roots(p):
        if multiplicity % 2 and root > t:
            return root
    return INF


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
