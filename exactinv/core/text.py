"""Exact values as a report prints them: one format for every result, on
polyhedra and ellipsoids alike (the pieces are :mod:`exactinv.core.digits`;
the trusted kernel prints with a copy of them, ``exactinv_check.text``).
"""

from __future__ import annotations

from fractions import Fraction
from typing import Any

from .digits import float_text, rational_text, root_text
from .polys import poly_text
from .real_algebraic import RealAlgebraic
from .scalars import Infinity

__all__ = ["exact_text", "safe_step_text"]


def exact_text(v: Any) -> str:
    """An exact value for a report line: a rational as it is (with its leading
    significant digits when it is long), an algebraic number by its certified
    significant digits, its polynomial and an isolating interval, oo as ``oo``.

    >>> exact_text(RealAlgebraic.from_isolating_interval([-12, 12, -6, 0, 1], 1, 2))
    '1.7496858314598103  (the root of x^4 - 6x^2 + 12x - 12 in [1.749685831459, 1.74968583146])'
    >>> exact_text(Fraction(1, 3 * 10**20)), exact_text(Fraction(2, 5))
    ('1/300000000000000000000  (= 3.3333333333333333e-21...)', '2/5')
    """
    if isinstance(v, RealAlgebraic):
        v.tidy()
        return root_text(v.certified_digits(17), poly_text(v.poly), v.lower, v.upper)
    if isinstance(v, (Fraction, int)) and not isinstance(v, bool):
        return rational_text(v)
    return str(v)


def safe_step_text(result: Any) -> str:
    """The safe float of a threshold-like result (``result.safe_float``) for a report
    line: "; use dt <= d" with d the largest double such that every step in [0, d]
    is valid, printed so that it reads back as d and is itself at most d (empty for
    an infinite value).

    >>> import exactinv as ei
    >>> S = ei.LinearSystem([[0, 1], [-2, -3]])
    >>> P = ei.Polyhedron([[2, 1], [-2, -1], [1, 1], [-1, -1]], [1, 1, 1, 1])
    >>> safe_step_text(ei.largest_threshold(S, P, ei.methods.rk4()))   # float(L.value) rounds up: invalid
    '; use dt <= 1.3926467817026406'
    """
    if isinstance(result.value, Infinity):
        return ""
    return f"; use dt <= {float_text(result.safe_float)}"
