"""Behaviour shared by exact result objects: the enclosure of ``value`` and display."""

from __future__ import annotations

from fractions import Fraction

from .algebraic import RealAlgebraic, Real
from .latex import LatexMixin
from .scalars import Infinity

__all__ = ["LatexMixin", "ExactValueMixin"]


class ExactValueMixin(LatexMixin):
    """For results with an exact ``value``: rational ``lower``/``upper`` bounds
    (``lower`` is itself a safe value) and ``refine(bits)``."""

    value: Real

    @property
    def lower(self) -> Fraction | Infinity:
        return self.value.lower if isinstance(self.value, RealAlgebraic) else self.value

    @property
    def upper(self) -> Fraction | Infinity:
        return self.value.upper if isinstance(self.value, RealAlgebraic) else self.value

    def refine(self, bits: int = 53):
        """Shrink the enclosure [lower, upper] to width <= 2**-bits; returns self."""
        if isinstance(self.value, RealAlgebraic):
            self.value.refine(bits)
        return self
