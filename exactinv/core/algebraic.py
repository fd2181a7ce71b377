"""The one exact ordering of exact reals -- Fractions, RealAlgebraics and +-INF --
and the aliases Real and FiniteReal.

Comparisons are exact in either order (a Fraction on the left defers to the
RealAlgebraic on the right).  :class:`RealAlgebraic` (module
:mod:`exactinv.core.real_algebraic`) is imported from there; :func:`significant_digits`
(:mod:`exactinv.core.digits`) and :func:`sign_at` (:mod:`exactinv.core.polys`) moved, and
their old spelling here warns.
"""

from __future__ import annotations

from fractions import Fraction

from .moved import moved_names
from .real_algebraic import RealAlgebraic
from .scalars import Infinity

__all__ = ["Real", "FiniteReal", "ExactKey", "exact_lt", "exact_eq", "exact_cmp", "upper_bound"]

__getattr__ = moved_names(__name__, {"significant_digits": "exactinv.core.digits", "sign_at": "exactinv.core.polys"})


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
