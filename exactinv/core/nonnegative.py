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

from typing import Iterable

import flint

from .algebraic import upper_bound
from .intervals import IntervalUnion, complement_of_open
from .polys import positive_below
from .roots import negative_segments
from .scalars import Infinity

__all__ = ["nonnegative_set", "tightest_first"]

_FIRST_CHUNK = 16


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
    polys, i, size = list(polys), 0, _FIRST_CHUNK
    while i < len(polys) and V.intervals:
        chunk, T = polys[i:i + size], _bound(V)
        for p, cleared in zip(chunk, positive_below(chunk, T)):
            if cleared or not V.intervals:
                continue
            if _bound(V) != T and positive_below([p], _bound(V))[0]:
                continue  # V shrank since the chunk's test
            V = V.intersect(complement_of_open(negative_segments(p), []))
        i, size = i + size, 2 * size
    return V
