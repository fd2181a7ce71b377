"""Exact real algebraic numbers with certified rational enclosures.

A :class:`RealAlgebraic` is the unique root of an irreducible integer
polynomial p (degree >= 2, primitive, positive leading coefficient) in an open
rational interval (lower, upper) with p(lower) p(upper) < 0.  Because p is
irreducible of degree >= 2 it has no rational root, so p never vanishes at a
rational point and every comparison with a rational is decided by one exact
sign evaluation.  Rational values are always represented as Fractions, never
as degree-1 algebraic numbers (:func:`algebraic` normalises).
"""

from __future__ import annotations

from fractions import Fraction
from functools import total_ordering
from typing import Any

import flint

from ..errors import InvalidInput
from .polys import count_real_roots, no_root_between, poly_latex, poly_text, sign_at
from .scalars import Infinity, frac_latex, to_rational

__all__ = ["RealAlgebraic", "Real", "FiniteReal", "ExactKey", "exact_lt", "exact_eq", "significant_digits", "exact_cmp", "upper_bound", "sign_at"]


@total_ordering
class RealAlgebraic:
    """The root of ``poly`` isolated by the open interval (``lower``, ``upper``).

    Construct it with :func:`RealAlgebraic.from_isolating_interval` (checked)
    or get it from :mod:`exactinv.roots`.  Compares exactly with ints,
    Fractions, infinities and other RealAlgebraics; ``float()``, ``str()``
    (certified decimal digits), ``to_sympy()`` and ``refine(bits)``.
    """

    _is_real_algebraic = True
    __slots__ = ("poly", "_lower", "_upper", "_sign_lower")

    def __init__(self, poly: flint.fmpz_poly, lower: Fraction, upper: Fraction, *, _trusted: bool = False):
        if not _trusted:
            poly = flint.fmpz_poly(poly)
            if poly.degree() < 2:
                raise InvalidInput("RealAlgebraic: poly must have degree >= 2 (rationals are Fractions)")
            _, factors = poly.factor()
            if len(factors) != 1 or factors[0][1] != 1:
                raise InvalidInput(f"RealAlgebraic: {poly} is not irreducible")
            if not lower < upper:
                raise InvalidInput(f"RealAlgebraic: empty interval ({lower}, {upper})")
            if sign_at(poly, lower) * sign_at(poly, upper) >= 0:
                raise InvalidInput(f"RealAlgebraic: {poly} does not change sign on ({lower}, {upper})")
            if count_real_roots(poly, lower, upper) != 1:
                raise InvalidInput(f"RealAlgebraic: ({lower}, {upper}) holds more than one root of {poly}")
            content = poly.content()
            poly = poly // content if poly.leading_coefficient() > 0 else -(poly // content)
        self.poly = poly
        self._lower = Fraction(lower)
        self._upper = Fraction(upper)
        self._sign_lower = sign_at(poly, self._lower)

    @classmethod
    def from_isolating_interval(cls, poly: Any, lower: Any, upper: Any) -> "RealAlgebraic":
        """The root of the irreducible integer polynomial ``poly`` (coefficients
        low to high, or an fmpz_poly) in (lower, upper); verified exactly.

        >>> r = RealAlgebraic.from_isolating_interval([-2, 0, 1], 1, 2)   # sqrt(2)
        >>> Fraction(141, 100) < r < Fraction(142, 100), str(r.poly)
        (True, 'x^2 + (-2)')
        """
        return cls(flint.fmpz_poly(list(poly) if not isinstance(poly, flint.fmpz_poly) else poly),
                   to_rational(lower, "lower"), to_rational(upper, "upper"))

    # -------------------------------------------------------------- enclosure
    @property
    def lower(self) -> Fraction:
        """A rational strictly below the value."""
        return self._lower

    @property
    def upper(self) -> Fraction:
        """A rational strictly above the value."""
        return self._upper

    @property
    def degree(self) -> int:
        return self.poly.degree()

    def _bisect(self) -> None:
        mid = (self._lower + self._upper) / 2
        if sign_at(self.poly, mid) == self._sign_lower:
            self._lower = mid
        else:
            self._upper = mid

    def tidy(self, digits: int = 12) -> "RealAlgebraic":
        """Replace the isolating interval by a short decimal one (for readable
        output and certificates); the added slivers are proved root-free by
        Descartes' rule, so the new interval still isolates the same root.

        >>> r = RealAlgebraic.from_isolating_interval([-2, 0, 1], 1, 2).tidy(6)
        >>> r.lower ** 2 < 2 < r.upper ** 2, r.upper - r.lower <= Fraction(1, 10**5)
        (True, True)
        """
        self.refine(int(digits * 3.33) + 4)
        scale = 10**digits
        lo = Fraction(_floor(self._lower * scale), scale)
        hi = Fraction(-_floor(-self._upper * scale), scale)
        # the widened interval adds the slivers (lo, lower] and [upper, hi): prove them root-free
        if (lo == self._lower or no_root_between(self.poly, lo, self._lower)) and \
                (hi == self._upper or no_root_between(self.poly, self._upper, hi)):
            self._lower, self._upper = lo, hi
            self._sign_lower = sign_at(self.poly, lo)
        return self

    def refine(self, bits: int = 53) -> "RealAlgebraic":
        """Shrink the isolating interval to width <= 2**-bits (exact bisection;
        the number itself is unchanged).  Returns self.

        >>> r = RealAlgebraic.from_isolating_interval([-2, 0, 1], 1, 2).refine(20)
        >>> r.upper - r.lower <= Fraction(1, 2**20), r.lower ** 2 < 2 < r.upper ** 2
        (True, True)
        """
        width = Fraction(1, 2**bits)
        while self._upper - self._lower > width:
            self._bisect()
        return self

    # ------------------------------------------------------------ comparison
    def _compare_rational(self, q: Fraction) -> int:
        if q <= self._lower:
            return 1
        if q >= self._upper:
            return -1
        # q is not a root (p is irreducible of degree >= 2): one sign decides.
        if sign_at(self.poly, q) == self._sign_lower:
            self._lower = q  # the root lies in (q, upper)
            return 1
        self._upper = q
        return -1

    def _compare(self, other: Any) -> int:
        if isinstance(other, Infinity):
            return -other.sign
        if isinstance(other, RealAlgebraic):
            if self.poly == other.poly:
                lo, hi = max(self._lower, other._lower), min(self._upper, other._upper)
                if lo < hi and sign_at(self.poly, lo) * sign_at(self.poly, hi) < 0:
                    return 0  # both isolate the single root of p in (lo, hi)
            while not (self._upper <= other._lower or other._upper <= self._lower):
                self._bisect()
                other._bisect()
            return -1 if self._upper <= other._lower else 1
        if isinstance(other, (int, Fraction)) and not isinstance(other, bool):
            return self._compare_rational(Fraction(other))
        return NotImplemented

    def __eq__(self, other: object) -> bool:
        c = self._compare(other)
        return False if c is NotImplemented else c == 0

    def __lt__(self, other: Any) -> bool:
        c = self._compare(other)
        return NotImplemented if c is NotImplemented else c < 0

    def __hash__(self) -> int:
        return hash(("RealAlgebraic", tuple(int(c) for c in self.poly.coeffs())))

    # ------------------------------------------------- exact scaling by Q
    def __neg__(self) -> "RealAlgebraic":
        coeffs = [int(c) * (-1) ** k for k, c in enumerate(self.poly.coeffs())]
        p = flint.fmpz_poly(coeffs)
        if p.leading_coefficient() < 0:
            p = -p
        return RealAlgebraic(p, -self._upper, -self._lower, _trusted=True)

    def __mul__(self, q: Any) -> "RealAlgebraic | Fraction":
        if not isinstance(q, (int, Fraction)) or isinstance(q, bool):
            return NotImplemented
        q = Fraction(q)
        if q == 0:
            return Fraction(0)
        if q < 0:
            return (-self) * (-q)
        # x = q a  <=>  p(x/q) = 0 ; clear denominators of q^-k coefficients.
        d = self.degree
        coeffs = [Fraction(int(c)) / q**k for k, c in enumerate(self.poly.coeffs())]
        scale = q**d
        ints = [c * scale for c in coeffs]
        den = 1
        for c in ints:
            den = den * c.denominator // _gcd(den, c.denominator)
        p = flint.fmpz_poly([int(c * den) for c in ints])
        p = p // p.content()
        if p.leading_coefficient() < 0:
            p = -p
        return RealAlgebraic(p, self._lower * q, self._upper * q, _trusted=True)

    __rmul__ = __mul__

    def __truediv__(self, q: Any) -> "RealAlgebraic | Fraction":
        if not isinstance(q, (int, Fraction)) or isinstance(q, bool):
            return NotImplemented
        if q == 0:
            raise ZeroDivisionError("RealAlgebraic / 0")
        return self * (1 / Fraction(q))

    def __rtruediv__(self, q: Any) -> "RealAlgebraic | Fraction":
        """q / a: a root of the reversed polynomial, scaled by q."""
        if not isinstance(q, (int, Fraction)) or isinstance(q, bool):
            return NotImplemented
        while self._lower <= 0 <= self._upper:  # isolate away from 0 (a is not 0)
            self._bisect()
        p = flint.fmpz_poly(list(reversed([int(c) for c in self.poly.coeffs()])))
        if p.leading_coefficient() < 0:
            p = -p
        lo, hi = (1 / self._upper, 1 / self._lower)
        inverse = RealAlgebraic(p, lo, hi, _trusted=True)
        return inverse * Fraction(q)

    # ----------------------------------------------------------- conversion
    def _copy(self) -> "RealAlgebraic":
        return RealAlgebraic(self.poly, self._lower, self._upper, _trusted=True)

    def __float__(self) -> float:
        c = self._copy().refine(64)
        return float((c._lower + c._upper) / 2)

    def refine_relative(self, bits: int = 53) -> "RealAlgebraic":
        """Shrink the isolating interval until it excludes 0 and its width is at
        most 2**-bits times the smaller ``abs(end)`` (relative width); returns self.

        >>> r = RealAlgebraic.from_isolating_interval([-2, 0, 1], 1, 2).refine_relative(30)
        >>> r.lower > 0 and (r.upper - r.lower) / r.lower <= Fraction(1, 2**30)
        True
        """
        while self._lower <= 0 <= self._upper:
            self._bisect()
        scale = 2**bits
        while (self._upper - self._lower) * scale > min(abs(self._lower), abs(self._upper)):
            self._bisect()
        return self

    def certified_digits(self, digits: int = 17) -> str:
        """The value to ``digits`` significant digits, every one certified: the
        value lies in [shown, shown + one unit in the last digit) (for negative
        values, mirrored).  Fixed notation for ``1e-4 <= abs(value) < 1e16``, else
        scientific, e.g. ``2.5127452049785885e-7``.

        >>> RealAlgebraic.from_isolating_interval([-2, 0, 1], 1, 2).certified_digits(5)
        '1.4142'
        """
        c = self._copy().refine_relative(int(digits * 3.33) + 8)  # keep this number's own enclosure
        for _ in range(64):
            text = significant_digits(c._lower, c._upper, digits)
            if text is not None:
                return text
            for _ in range(32):
                c._bisect()
        return f"({float(c._lower)} .. {float(c._upper)})"

    def __str__(self) -> str:
        return self.certified_digits(17)

    def __repr__(self) -> str:
        return f"RealAlgebraic({self}: the root of {poly_text(self.poly)} in ({self._lower}, {self._upper}))"

    def to_sympy(self):
        """A sympy ``CRootOf`` equal to this number.

        >>> RealAlgebraic.from_isolating_interval([-2, 0, 1], 1, 2).to_sympy()
        CRootOf(x**2 - 2, 1)
        """
        import sympy

        x = sympy.Symbol("x")
        expr = sum(int(c) * x**k for k, c in enumerate(self.poly.coeffs()))
        index = count_real_roots(self.poly, None, self._lower)
        return sympy.CRootOf(expr, index)

    def _repr_latex_(self) -> str:
        return f"$\\text{{root of }} {poly_latex(self.poly)} \\text{{ in }} ({frac_latex(self._lower)}, {frac_latex(self._upper)}) \\approx {self.certified_digits(10)}$"

    def __reduce__(self):
        return (_rebuild, ([int(c) for c in self.poly.coeffs()], self._lower, self._upper))


def _rebuild(coeffs: list[int], lower: Fraction, upper: Fraction) -> RealAlgebraic:
    return RealAlgebraic(flint.fmpz_poly(coeffs), lower, upper, _trusted=True)


FiniteReal = Fraction | RealAlgebraic
"""An exact finite real: a Fraction or a RealAlgebraic."""

Real = Fraction | RealAlgebraic | Infinity
"""An exact extended real: a Fraction, a RealAlgebraic or +-INF (the one definition)."""


def exact_lt(a: Real, b: Real) -> bool:
    """a < b for mixed exact values, in either order (the one exact ordering).

    >>> exact_lt(Fraction(1), RealAlgebraic.from_isolating_interval([-2, 0, 1], 1, 2))
    True
    """
    if isinstance(a, Fraction) and not isinstance(b, Fraction):
        return b > a
    return a < b


def exact_eq(a: Real, b: Real) -> bool:
    """a == b for mixed exact values, in either order.

    >>> r = RealAlgebraic.from_isolating_interval([-2, 0, 1], 1, 2)
    >>> s = RealAlgebraic.from_isolating_interval([-2, 0, 1], Fraction(7, 5), Fraction(3, 2))
    >>> exact_eq(r, s), exact_eq(Fraction(7, 5), r), exact_eq(Fraction(2), Fraction(4, 2))
    (True, False, True)
    """
    if isinstance(a, Fraction) and not isinstance(b, Fraction):
        return b == a
    return a == b


def exact_cmp(a: Real, b: Real) -> int:
    """-1, 0 or 1 as a <, =, > b (for ``functools.cmp_to_key``).

    >>> r = RealAlgebraic.from_isolating_interval([-2, 0, 1], 1, 2)
    >>> from exactinv.core.scalars import INF
    >>> exact_cmp(r, Fraction(3, 2)), exact_cmp(Fraction(7, 5), r), exact_cmp(INF, r)
    (-1, -1, 1)
    """
    return -1 if exact_lt(a, b) else (1 if exact_lt(b, a) else 0)


def upper_bound(v: Real) -> Fraction | Infinity:
    """A rational (or infinite) upper bound of an exact value: v itself unless algebraic.

    >>> r = RealAlgebraic.from_isolating_interval([-2, 0, 1], 1, 2)
    >>> from exactinv.core.scalars import INF
    >>> upper_bound(Fraction(1, 3)), upper_bound(r) >= r, upper_bound(INF)
    (Fraction(1, 3), True, INF)
    """
    return v.upper if isinstance(v, RealAlgebraic) else v


class ExactKey:
    """A sort key for mixed Fractions, RealAlgebraics and infinities: exact
    comparisons in either order (``min(values, key=ExactKey)``)."""

    __slots__ = ("v",)

    def __init__(self, v):
        self.v = v

    def __lt__(self, other: "ExactKey") -> bool:
        return exact_lt(self.v, other.v)


def significant_digits(lo: Fraction, hi: Fraction, digits: int = 17) -> str | None:
    """The common leading ``digits`` significant digits of every number in
    [lo, hi] (truncated towards zero; lo and hi of one sign), or None if the
    enclosure is too wide to certify them.  ``lo == hi`` gives the digits of
    that rational (exact only if nothing was cut off).

    >>> significant_digits(Fraction(251274520497858851, 10**24), Fraction(251274520497858852, 10**24))
    '2.5127452049785885e-7'
    >>> significant_digits(Fraction(1749685831459810, 10**15), Fraction(1749685831459811, 10**15), 10)
    '1.749685831'
    """
    if lo == 0 and hi == 0:
        return "0"
    if lo < 0 < hi or lo == 0 or hi == 0:
        return None
    neg = hi < 0
    a, b = (-hi, -lo) if neg else (lo, hi)
    e = _decade(a)
    if _decade(b) != e:
        return None
    unit = Fraction(10) ** (e - digits + 1)
    ma, mb = _floor(a / unit), _floor(b / unit)
    if ma != mb:
        return None
    mant = str(ma)  # exactly `digits` digits
    if -4 <= e < 16:
        if e >= digits - 1:
            text = mant + "0" * (e - digits + 1)
        elif e >= 0:
            text = mant[:e + 1] + "." + mant[e + 1:]
        else:
            text = "0." + "0" * (-e - 1) + mant
    else:
        text = mant[0] + ("." + mant[1:] if digits > 1 else "") + f"e{e}"
    return ("-" if neg else "") + text


def _decade(q: Fraction) -> int:
    """e with 10**e <= q < 10**(e+1), for q > 0."""
    e = len(str(q.numerator)) - len(str(q.denominator))
    while Fraction(10) ** e > q:
        e -= 1
    while Fraction(10) ** (e + 1) <= q:
        e += 1
    return e


def _floor(q: Fraction) -> int:
    return q.numerator // q.denominator


def _gcd(a: int, b: int) -> int:
    while b:
        a, b = b, a % b
    return a

