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

import math
from fractions import Fraction
from functools import total_ordering
from typing import Any

import flint

from ..errors import InvalidInput
from .digits import significant_digits
from .float_hint import float_hint
from .polys import count_real_roots, no_root_between, poly_latex, poly_text, sign_at
from .scalars import Infinity, frac_latex, to_rational

__all__ = ["RealAlgebraic"]


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
        """Replace the isolating interval by the cell [k, k + 1] / 10**digits of the
        decimal grid that holds the root (for readable output and certificates): a
        function of the number alone, so the engine and the kernel print the same
        interval (exactinv_check.text).  The added slivers are proved root-free by
        Descartes' rule, so the new interval still isolates the same root; where
        that proof fails, the refined interval is kept.

        >>> r = RealAlgebraic.from_isolating_interval([-2, 0, 1], 1, 2).tidy(6)
        >>> r.lower == Fraction(1414213, 10**6) and r.upper == Fraction(1414214, 10**6)   # sqrt 2 = 1.41421356...
        True
        """
        scale = 10**digits
        while math.floor(self._lower * scale) != -math.floor(-self._upper * scale) - 1:  # not yet inside one cell
            self._bisect()
        lo = Fraction(math.floor(self._lower * scale), scale)  # Fraction.__floor__: exact
        hi = lo + Fraction(1, scale)
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
        # x = q a, q = s/t  <=>  p(t x/s) = 0  <=>  sum_k c_k t^k s^(d-k) x^k = 0: integers throughout
        # (FLINT's fmpz: no Fraction gcds, so a q near 10^300 on a degree-87 p costs milliseconds).
        d, s, t = self.degree, flint.fmpz(q.numerator), flint.fmpz(q.denominator)
        coeffs, power_t, power_s = [], flint.fmpz(1), [flint.fmpz(1)]
        for _ in range(d):
            power_s.append(power_s[-1] * s)
        for k, c in enumerate(self.poly.coeffs()):
            coeffs.append(c * power_t * power_s[d - k])
            power_t *= t
        p = flint.fmpz_poly(coeffs)
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
        """The nearest double, up to rounding (+-inf beyond the double range, 0.0 below it);
        never raises.  Relative precision, so 1e-30-sized values keep their digits."""
        c = self._copy().refine_relative(60)
        return float_hint((c._lower + c._upper) / 2)

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
        return f"({float_hint(c._lower)} .. {float_hint(c._upper)})"

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
        return (f"$\\text{{root of }} {poly_latex(self.poly)} \\text{{ in }} ({frac_latex(self._lower)}, "
                f"{frac_latex(self._upper)}) \\approx {self.certified_digits(10)}$")

    def __reduce__(self):
        return (_rebuild, ([int(c) for c in self.poly.coeffs()], self._lower, self._upper))


def _rebuild(coeffs: list[int], lower: Fraction, upper: Fraction) -> RealAlgebraic:
    return RealAlgebraic(flint.fmpz_poly(coeffs), lower, upper, _trusted=True)


def _gcd(a: int, b: int) -> int:
    while b:
        a, b = b, a % b
    return a
