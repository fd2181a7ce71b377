"""Behaviour shared by exact result objects: the enclosure of ``value`` and display."""

from __future__ import annotations

from fractions import Fraction

from .algebraic import RealAlgebraic, Real
from .latex import LatexMixin
from .scalars import Infinity

__all__ = ["LatexMixin", "ExactValueMixin"]


RELATIVE_BITS = 53
"""``lower``/``upper`` of a result enclose its value with relative width <= 2**-RELATIVE_BITS."""


class ExactValueMixin(LatexMixin):
    """For results with an exact ``value``: rational ``lower``/``upper`` bounds,
    tight by default (relative width <= 2**-53, refined lazily on access) with
    ``lower`` itself a safe value (below the value when the value is not
    ``attained``), and ``refine(bits)``."""

    value: Real

    @property
    def lower(self) -> Fraction | Infinity:
        """A rational at most the value, itself valid: the value if it is rational and
        attained, else a rational below it within relative 2**-53."""
        v = self.value
        if isinstance(v, RealAlgebraic):
            return v.refine_relative(RELATIVE_BITS).lower
        if isinstance(v, Fraction) and v > 0 and not getattr(self, "attained", True):
            return v - v / 2**RELATIVE_BITS
        return v

    @property
    def upper(self) -> Fraction | Infinity:
        """A rational at least the value (the value itself when it is rational)."""
        v = self.value
        if isinstance(v, RealAlgebraic):
            return v.refine_relative(RELATIVE_BITS).upper
        return v

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
