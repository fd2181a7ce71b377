"""Exact unions of intervals on [0, oo): the valid steplength sets.

Endpoints are Fractions, :class:`~exactinv.RealAlgebraic` numbers or ``INF``;
each end is marked closed or open.  ``dt in V`` tests a rational steplength
exactly; iterating gives the intervals in increasing order.
"""

from __future__ import annotations

from dataclasses import dataclass
from fractions import Fraction
from functools import cmp_to_key
from typing import Any, Iterator

from .algebraic import Real, exact_cmp, exact_eq, exact_lt
from .latex import latex_decimal
from .real_algebraic import RealAlgebraic
from .scalars import INF, Infinity, to_rational

__all__ = ["Interval", "IntervalUnion", "complement_of_open"]


@dataclass(frozen=True)
class Interval:
    """An interval with exact ends; ``hi`` may be INF (then open)."""

    lo: Real
    hi: Real
    lo_closed: bool = True
    hi_closed: bool = True

    def __contains__(self, t: Any) -> bool:
        t = t if isinstance(t, (Fraction, RealAlgebraic)) else to_rational(t, "dt")
        above = exact_lt(self.lo, t) or (self.lo_closed and exact_eq(self.lo, t))
        below = exact_lt(t, self.hi) or (self.hi_closed and exact_eq(self.hi, t))
        return above and below

    def __repr__(self) -> str:
        left = "[" if self.lo_closed else "("
        right = "]" if self.hi_closed else ")"
        return f"{left}{self.lo}, {self.hi}{right}"

    def _repr_latex_(self) -> str:
        left = "[" if self.lo_closed else "("
        right = "]" if self.hi_closed else ")"
        return f"${left}{_latex(self.lo)}, {_latex(self.hi)}{right}$"


def _latex(v: Real) -> str:
    if isinstance(v, Infinity):
        return r"\infty"
    if isinstance(v, RealAlgebraic):
        return latex_decimal(v, 8)
    if v.denominator == 1:
        return str(v.numerator)
    return rf"\tfrac{{{v.numerator}}}{{{v.denominator}}}"


@dataclass(frozen=True)
class IntervalUnion:
    """A finite union of disjoint intervals, sorted."""

    intervals: tuple[Interval, ...]

    def __iter__(self) -> Iterator[Interval]:
        return iter(self.intervals)

    def __len__(self) -> int:
        return len(self.intervals)

    def __getitem__(self, k: int) -> Interval:
        return self.intervals[k]

    def __contains__(self, t: Any) -> bool:
        t = t if isinstance(t, (Fraction, RealAlgebraic)) else to_rational(t, "dt")
        return any(t in iv for iv in self.intervals)

    def __repr__(self) -> str:
        return " U ".join(repr(iv) for iv in self.intervals) if self.intervals else "{}"

    def intersect(self, other: "IntervalUnion") -> "IntervalUnion":
        """The intersection, again as maximal disjoint intervals in increasing order:
        the pairwise intersections, ends compared exactly (two pieces that touched
        would lie in one interval of each union, so none touch).

        >>> A = complement_of_open([(Fraction(1), Fraction(2))], [])               # [0, 1] U [2, oo)
        >>> print(A.intersect(complement_of_open([(Fraction(2), INF)], [Fraction(1)])))   # [0, 1) U (1, 2]
        [0, 1) U [2, 2]
        """
        out, i, j = [], 0, 0
        while i < len(self.intervals) and j < len(other.intervals):
            a, b = self.intervals[i], other.intervals[j]
            lo, lo_closed = _later_start(a, b)
            c = exact_cmp(a.hi, b.hi)
            hi, hi_closed = ((a.hi, a.hi_closed) if c < 0 else (b.hi, b.hi_closed) if c > 0
                             else (a.hi, a.hi_closed and b.hi_closed))
            k = exact_cmp(lo, hi)
            if k < 0 or (k == 0 and lo_closed and hi_closed):
                out.append(Interval(lo, hi, lo_closed, hi_closed))
            i, j = i + (c <= 0), j + (c >= 0)
        return IntervalUnion(tuple(out))

    def _repr_latex_(self) -> str:
        return "$" + r" \cup ".join(iv._repr_latex_().strip("$") for iv in self.intervals) + "$"


def _later_start(a: Interval, b: Interval) -> tuple[Real, bool]:
    """The later of two left ends, closed only if closed in both where they are equal."""
    c = exact_cmp(a.lo, b.lo)
    return (a.lo, a.lo_closed) if c > 0 else (b.lo, b.lo_closed) if c < 0 else (a.lo, a.lo_closed and b.lo_closed)


def complement_of_open(bad: list[tuple[Real, Real]], points: list[Real]) -> IntervalUnion:
    """[0, oo) minus the open intervals ``bad`` (a, b) (a >= 0, b may be INF) and the ``points`` (> 0).

    >>> print(complement_of_open([(Fraction(1), Fraction(2)), (Fraction(3), INF)], [Fraction(1, 2)]))
    [0, 1/2) U (1/2, 1] U [2, 3]
    """
    bad = sorted(bad, key=cmp_to_key(lambda u, v: exact_cmp(u[0], v[0])))
    merged: list[list[Real]] = []
    for a, b in bad:
        if merged and exact_lt(a, merged[-1][1]):  # overlaps (open intervals sharing an end do not merge)
            if exact_lt(merged[-1][1], b):
                merged[-1][1] = b
        else:
            merged.append([a, b])
    # the good set between bad intervals
    pieces: list[Interval] = []
    start: Real = Fraction(0)
    start_closed = True
    for a, b in merged:
        if exact_lt(start, a) or (exact_eq(start, a) and start_closed):
            pieces.append(Interval(start, a, start_closed, True))
        start, start_closed = b, True
        if isinstance(b, Infinity):
            break
    else:
        pieces.append(Interval(start, INF, start_closed, False))
    # a zero-length piece [a, a] between (.., a) and (a, ..) is a valid point
    # remove isolated excluded points
    for p in sorted(points, key=cmp_to_key(exact_cmp)):
        new: list[Interval] = []
        for iv in pieces:
            if p not in iv:
                new.append(iv)
                continue
            if exact_lt(iv.lo, p):
                new.append(Interval(iv.lo, p, iv.lo_closed, False))
            if exact_lt(p, iv.hi):
                new.append(Interval(p, iv.hi, False, iv.hi_closed))
        pieces = new
    return IntervalUnion(tuple(pieces))
