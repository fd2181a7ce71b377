"""Float hints of exact numbers: the one place where the engine turns a rational into a double.

A float in exactinv is only ever a *hint* -- an order to try, a point to round, a
scale to work at -- that is then proved or thrown away in Q.  A hint must never
raise: ``float(Fraction(10**400))`` raises ``OverflowError``, ``math.log2(Fraction(0))``
raises ``ValueError``, and either would turn a well-posed exact problem into a
crash.  These functions take an ``int``, :class:`~fractions.Fraction`, FLINT
``fmpz``/``fmpq`` (or anything with integer ``numerator``/``denominator``) and
return a float that is

* the correctly rounded value when it is a normal double,
* ``+-inf`` beyond the double range and ``+-0.0`` (or a subnormal) below it,

and never raise for an exact input.  Scale-free work goes through
:func:`log2_hint` (log2|x| from bit lengths, finite for every nonzero x) and
:func:`ldexp_hint` (x 2^k without forming x as a double first), so that a
problem and its rescaling by 2^k get the same hints.
"""

from __future__ import annotations

import math
from fractions import Fraction
from typing import Any, Iterable

import flint
import numpy as np

__all__ = ["float_hint", "float_hints", "log2_hint", "ldexp_hint"]


def _ratio(x: Any) -> tuple[int, int]:
    """(p, q) with x = p/q, q > 0, as Python ints."""
    if isinstance(x, int):
        return int(x), 1
    if isinstance(x, flint.fmpz):
        return int(x), 1
    if isinstance(x, flint.fmpq):
        return int(x.p), int(x.q)
    if isinstance(x, Fraction):
        return x.numerator, x.denominator
    return int(x.numerator), int(x.denominator)


def float_hint(x: Any) -> float:
    """x as the nearest double, +-inf beyond the double range, +-0.0 (or subnormal) below it.
    Never raises for an exact number.

    >>> float_hint(Fraction(1, 3)), float_hint(flint.fmpz(10) ** 400), float_hint(-Fraction(10**400, 3))
    (0.3333333333333333, inf, -inf)
    >>> float_hint(Fraction(1, 10**400)), float_hint(flint.fmpq(-1, 10**400))
    (0.0, -0.0)
    """
    try:
        return float(x)  # FLINT, Fraction and int: correctly rounded; they raise only on overflow
    except OverflowError:
        return math.inf if _ratio(x)[0] > 0 else -math.inf
    except (TypeError, ValueError, ZeroDivisionError):  # not a number: no hint
        return math.nan


def float_hints(values: Iterable[Any]) -> np.ndarray:
    """:func:`float_hint` of each value, as a float array (never raises).

    >>> float_hints([flint.fmpq(1, 4), 3, flint.fmpz(10) ** 400]).tolist()
    [0.25, 3.0, inf]
    """
    return np.array([float_hint(v) for v in values], dtype=float)


def log2_hint(x: Any) -> float:
    """log2|x| to double precision (-inf for x = 0), finite for every nonzero exact x,
    however large or small.  Never raises.

    >>> log2_hint(Fraction(1, 8)), log2_hint(-1024), log2_hint(0)
    (-3.0, 10.0, -inf)
    >>> round(log2_hint(Fraction(1, 10**400)), 3)
    -1328.771
    """
    p, q = _ratio(x)
    if p == 0:
        return -math.inf
    return math.log2(abs(p)) - math.log2(q)  # math.log2 takes ints of any size


def ldexp_hint(x: Any, k: int) -> float:
    """x 2^k as a double (+-inf beyond the range, +-0.0 below), computed without forming
    x as a double first: x = 3 2^2000 and k = -2000 give 3.0.  Never raises.

    >>> ldexp_hint(3 * flint.fmpz(2) ** 2000, -2000), ldexp_hint(Fraction(1, 10**400), 1400) > 1
    (3.0, True)
    >>> ldexp_hint(Fraction(3, 4), 2), ldexp_hint(1, 5000), ldexp_hint(-1, -5000)
    (3.0, inf, -0.0)
    """
    p, q = _ratio(x)
    if p == 0:
        return 0.0
    e = abs(p).bit_length() - q.bit_length()  # |x| in (2^(e-1), 2^(e+1))
    y = p / (q << e) if e >= 0 else (p << -e) / q  # |y| in (1/2, 2): no overflow
    try:
        return math.ldexp(y, e + int(k))
    except OverflowError:
        return math.inf if p > 0 else -math.inf
