"""Behaviour shared by exact result objects: the enclosure of ``value`` by the two
adjacent doubles around it, the safe float, and display."""

from __future__ import annotations

import math
from fractions import Fraction

from .algebraic import Real
from .doubles import DOUBLE_MAX, double_above, double_below
from .latex import LatexMixin
from .real_algebraic import RealAlgebraic
from .scalars import INF, Infinity

__all__ = ["LatexMixin", "ExactValueMixin"]


class ExactValueMixin(LatexMixin):
    """For results with an exact ``value`` (a threshold, a step, a radius: the
    valid set is [0, value] when ``attained``, else [0, value)):

    * ``lower`` -- the largest double below the value that is itself valid (at
      most the value when attained, strictly below it when not), as an exact
      Fraction: ``float(x.lower) == x.lower`` exactly;
    * ``upper`` -- the least double at least the value, as a Fraction (``INF``
      beyond the largest finite double);
    * ``safe_float`` -- ``lower`` as a float: the largest double d with [0, d]
      inside the valid set, the number a float user steps with;
    * ``refine(bits)`` -- a narrower isolating interval of an algebraic value.

    Every rounding is decided exactly (:mod:`exactinv.core.doubles`).
    """

    value: Real

    def _strict(self) -> bool:
        """Is the value itself outside the valid set (a positive value not attained)?"""
        v = self.value
        return not getattr(self, "attained", True) and not isinstance(v, Infinity) and v > 0

    @property
    def lower(self) -> Fraction | Infinity:
        """A double-representable rational at most the value (strictly below it
        when the value is not ``attained``), itself valid, with no double between
        it and the value: ``float(lower) == lower``.  ``INF`` if the value is.

        >>> class Step(ExactValueMixin):
        ...     value, attained = Fraction(1, 3), True
        >>> lo = Step().lower
        >>> float(lo) == lo < Fraction(1, 3) < Fraction(math.nextafter(float(lo), 1))
        True
        """
        v = self.value
        if isinstance(v, Infinity) and v.sign > 0:
            return v
        return Fraction(double_below(v, strict=self._strict()))

    @property
    def upper(self) -> Fraction | Infinity:
        """The least double at least the value, as a Fraction (``INF`` for an infinite
        value or one beyond the largest finite double).

        >>> class Step(ExactValueMixin):
        ...     value, attained = Fraction(1, 3), True
        >>> s = Step(); s.upper > Fraction(1, 3) and s.upper - s.lower == Fraction(math.ulp(1 / 3))
        True
        """
        v = self.value
        if isinstance(v, Infinity):
            return v
        d = double_above(v)
        return INF if math.isinf(d) else Fraction(d)

    @property
    def safe_float(self) -> float:
        """The largest double d such that every step in [0, d] is valid: the largest
        double <= the value when it is attained, < the value when it is not;
        ``DOUBLE_MAX`` (the largest finite double) for an infinite value.  Decided
        exactly: ``Fraction(d)`` is compared with the exact value.

        >>> class Step(ExactValueMixin):
        ...     value, attained = Fraction(1), False      # valid on [0, 1)
        >>> Step().safe_float == math.nextafter(1.0, 0)
        True
        """
        v = self.value
        if isinstance(v, Infinity) and v.sign > 0:
            return DOUBLE_MAX
        return double_below(v, strict=self._strict())

    def refine(self, bits: int = 53):
        """Shrink the enclosure of an algebraic value to absolute width <= 2**-bits; returns self.

        >>> class Root(ExactValueMixin):
        ...     value = RealAlgebraic.from_isolating_interval([-2, 0, 1], 1, 2)
        >>> r = Root().refine(40).value
        >>> r.upper - r.lower <= Fraction(1, 2**40), r.lower ** 2 < 2 < r.upper ** 2
        (True, True)
        """
        if isinstance(self.value, RealAlgebraic):
            self.value.refine(bits)
        return self
