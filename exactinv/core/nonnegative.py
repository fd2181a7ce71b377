"""The set {t >= 0 : p(t) >= 0 for every p} of many polynomials, condition by condition.

Start from a set V (default [0, oo)) and replace V by V n {p >= 0} for each p in
turn -- an exact identity, so the last V is the answer whatever the order.  A step
is skipped when p is proved > 0 on (0, T), T a rational bound of V's end (then
p >= 0 on [0, T] by continuity, V n {p >= 0} = V): all remaining p at once by
:func:`~exactinv.core.polys.positive_below` (one FLINT product), in chunks of
doubling size so the bound tightens as V shrinks.  Any other p has its negative
segments (:func:`~exactinv.core.roots.negative_segments`: every positive root
isolated, exactly) removed from V.  Tightest conditions first
(:func:`tightest_first`) make V small early, so most p are skipped unisolated.
This mirrors the kernel's valid set (exactinv_check/validset.py).
"""

from __future__ import annotations

import math
import statistics
from fractions import Fraction
from typing import Callable, Iterable, Iterator

import flint
import numpy as np

from .algebraic import ExactKey, Real, upper_bound
from .float_hint import ldexp_hint, log2_hint
from .intervals import IntervalUnion, complement_of_open
from .polys import positive_below
from .roots import negative_segments, nonnegative_until
from .scalars import INF, Infinity

__all__ = ["nonnegative_set", "first_end", "tightest_first", "earliest_first", "time_scale"]

_FIRST_CHUNK = 16
_GRID = 512  # points of earliest_first's grid (ratio 1.037)


def tightest_first(polys: Iterable[flint.fmpq_poly]) -> list[flint.fmpq_poly]:
    """The polynomials by |p(0)| / max_k |p_k|, smallest first (stable): those close
    to binding at t = 0 first.  Only an order -- any order gives the same set.

    >>> tightest_first([flint.fmpq_poly([3, -1]), flint.fmpq_poly([1, -4]), flint.fmpq_poly([0, 1])])
    [x, (-4)*x + 1, (-1)*x + 3]
    """
    def key(p):
        cs = p.coeffs()
        return abs(cs[0]) / max(abs(c) for c in cs) if cs else flint.fmpq(0)
    return sorted(polys, key=key)


def earliest_first(polys: Iterable[flint.fmpq_poly]) -> list[flint.fmpq_poly]:
    """The polynomials by the first point of a geometric grid on s [10^-4, 10^4] where a float
    evaluation is negative (never negative: last), :func:`tightest_first` among equals: the
    condition likely to end the set first comes first.  The floats only choose the order --
    any order gives the same set, exactly.  The scale s is a power of two read off the
    coefficients (:func:`time_scale`), and each p(s t) is evaluated with its coefficients
    scaled by a power of two (:func:`~exactinv.core.float_hint.ldexp_hint`): no coefficient
    is too large or too small for a double, nothing raises, and p(2^k t) gets the order of p(t).

    >>> earliest_first([flint.fmpq_poly([3, -1]), flint.fmpq_poly([0, 1]), flint.fmpq_poly([1, -4])])
    [(-4)*x + 1, (-1)*x + 3, x]
    >>> big = [flint.fmpq_poly([3, -10**300]), flint.fmpq_poly([0, 1]), flint.fmpq_poly([1, -4 * 10**300])]
    >>> earliest_first(big)[0] == big[2]
    True
    """
    polys = tightest_first(polys)
    if not polys:
        return polys
    e = time_scale(polys)
    width = max(p.degree() for p in polys) + 1
    C = np.zeros((len(polys), width))
    for i, p in enumerate(polys):
        cs = p.coeffs()
        logs = [log2_hint(c) + k * e for k, c in enumerate(cs)]
        top = max(logs, default=-math.inf)
        shift = 0 if top == -math.inf else int(top)  # row i / 2^shift: the largest |c_k s^k| near 1
        C[i, :len(cs)] = [ldexp_hint(c, k * e - shift) for k, c in enumerate(cs)]
    grid = np.geomspace(1e-4, 1e4, _GRID)
    with np.errstate(all="ignore"):
        negative = C @ grid[None, :] ** np.arange(width)[:, None] < 0
    first = np.where(negative.any(axis=1), negative.argmax(axis=1), _GRID)
    return [polys[i] for i in np.argsort(first, kind="stable")]


def time_scale(polys: Iterable[flint.fmpq_poly]) -> int:
    """e with 2^e a typical scale of t at which the polynomials turn (a hint, never raises):
    the median over p of min_k log2 |c_j/c_k|^(1/(k-j)), c_j the lowest nonzero coefficient
    (where a higher term overtakes the lowest one), from bit lengths -- so p(2^k t) gives e - k.

    >>> time_scale([flint.fmpq_poly([1, -4]), flint.fmpq_poly([1, 0, -16])])   # 1/4 and 1/4
    -2
    >>> time_scale([flint.fmpq_poly([1, -4 * 10**300])]), time_scale([flint.fmpq_poly([2])])
    (-999, 0)
    """
    turns = []
    for p in polys:
        logs = [(k, log2_hint(c)) for k, c in enumerate(p.coeffs()) if c != 0]
        if len(logs) > 1:
            j, low = logs[0]
            turns.append(min((low - lk) / (k - j) for k, lk in logs[1:]))
    if not turns:
        return 0
    return int(round(statistics.median(turns)))  # not np.median: its first call imports numpy.ma (~20-36 ms)


def _bound(V: IntervalUnion):
    """A rational T >= every point of V (None if V is unbounded)."""
    end = V.intervals[-1].hi
    return None if isinstance(end, Infinity) else upper_bound(end)


def nonnegative_set(polys: Iterable[flint.fmpq_poly], start: IntervalUnion | None = None) -> IntervalUnion:
    """``start`` (default [0, oo)) intersected with {t >= 0 : p(t) >= 0} for every p: maximal
    intervals with exact ends (see the module docstring).

    >>> ps = [flint.fmpq_poly([6, -5, 1]), flint.fmpq_poly([4, -1]), flint.fmpq_poly([9, -1])]
    >>> print(nonnegative_set(ps))          # (t - 2)(t - 3) >= 0, t <= 4, t <= 9
    [0, 2] U [3, 4]
    """
    V = start if start is not None else complement_of_open([], [])
    # the bound is read lazily, at each step: V as it is then (late binding is the point)
    for p in _unskipped(list(polys), lambda: _bound(V) if V.intervals else Fraction(0)):  # noqa: B023
        V = V.intersect(complement_of_open(negative_segments(p), []))
    return V


def first_end(polys: Iterable[flint.fmpq_poly]) -> Real:
    """min over p of sup{T : p >= 0 on [0, T]} (:func:`~exactinv.core.roots.nonnegative_until`; 0 for a p
    negative right of 0), INF for none: earliest first, each p skipped when proved positive on
    (0, best so far) -- it cannot end earlier.  Exact.

    >>> first_end([flint.fmpq_poly([3, -1]), flint.fmpq_poly([2, -3, 1]), flint.fmpq_poly([1])])
    Fraction(1, 1)
    """
    best: Real = INF
    # the bound is read lazily, at each step: the best end so far (late binding is the point)
    for p in _unskipped(earliest_first(polys), lambda: upper_bound(best) if not isinstance(best, Infinity) else None):  # noqa: B023
        best = min(best, nonnegative_until(p), key=ExactKey)
    return best


def _unskipped(polys: list, bound: Callable[[], Fraction | None]) -> Iterator[flint.fmpq_poly]:
    """The polys, in order, except those proved > 0 on (0, bound()) (None: on (0, oo)), the bound
    read again as the caller tightens it: chunks of doubling size tested at once
    (:func:`~exactinv.core.polys.positive_below`), a p of a chunk tested again alone if the
    bound moved since."""
    i, size = 0, _FIRST_CHUNK
    while i < len(polys):
        chunk, T = polys[i:i + size], bound()
        for p, cleared in zip(chunk, positive_below(chunk, T)):
            if cleared or (bound() != T and positive_below([p], bound())[0]):
                continue
            yield p
        i, size = i + size, 2 * size
