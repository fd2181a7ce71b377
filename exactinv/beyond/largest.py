"""The exact largest thresholds -- beyond the paper (DESIGN.md section 1).

The valid set {dt >= 0 : A_d(dt) P subset of P} is a finite union of
intervals with algebraic ends, computed exactly from the roots (with
multiplicities) of the distinct condition polynomials (:mod:`.conditions`):
each c is negative exactly on the open segments between its own roots where
its sign, tracked from the sign right of 0 through the odd multiplicities, is
negative; dt must avoid the roots of D (where r(dt A) is singular).  A
polynomial that Descartes' rule shows nonnegative up to the current bound is
skipped, so only pairs that can actually bind reach root isolation.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from fractions import Fraction
from typing import Any

from ..core.algebraic import ExactKey, Real, exact_lt, upper_bound
from ..core.encode import encode_real, vec
from ..core.intervals import Interval, IntervalUnion, complement_of_open
from ..core.latex import latex_real
from ..core.polys import no_positive_root_below, positive_right_of_zero
from ..core.results import ExactValueMixin
from ..core.roots import negative_segments, nonnegative_until, positive_roots
from ..core.scalars import INF, Infinity, fraction_of
from ..model import LinearSystem, Method, Polyhedron
from ..model.record import certificate as make_certificate, generator_record
from ..model.validate import check_problem
from .conditions import Condition, Kind, conditions_of, distinct_conditions

__all__ = ["ValidSteplengths", "LargestThreshold", "valid_steplengths", "largest_threshold"]


@dataclass(frozen=True)
class ValidSteplengths:
    """The exact set {dt >= 0 : A_d(dt) P subset of P}.  Iterate for the
    intervals; ``dt in V`` for a rational dt."""

    intervals: IntervalUnion
    method: Method = field(repr=False)
    singular: tuple[Real, ...] = field(default=(), repr=False)
    conditions: int = field(default=0, repr=False)
    distinct: int = field(default=0, repr=False)

    system: LinearSystem | None = field(default=None, repr=False)
    polyhedron: Polyhedron | None = field(default=None, repr=False)
    determinant: tuple[Fraction, ...] = field(default=(Fraction(1),), repr=False)

    def __iter__(self):
        return iter(self.intervals)

    def __len__(self) -> int:
        return len(self.intervals)

    def claims(self) -> list[dict]:
        return [{
            "type": "valid_steplengths",
            "intervals": [{"lo": encode_real(iv.lo), "hi": encode_real(iv.hi), "lo_closed": iv.lo_closed,
                           "hi_closed": iv.hi_closed} for iv in self.intervals],
            **generator_record(self.polyhedron),
            "determinant": vec(self.determinant),
        }]

    @property
    def certificate(self) -> dict:
        """The JSON certificate for :func:`exactinv.check`."""
        return make_certificate(self.system, self.polyhedron, self.method, [self])

    def __contains__(self, t: Any) -> bool:
        return t in self.intervals

    def __repr__(self) -> str:
        return f"ValidSteplengths({self.intervals!r}, method={self.method.name})"

    def _repr_latex_(self) -> str:
        return self.intervals._repr_latex_()

    def to_latex(self) -> str:
        return self.intervals._repr_latex_().strip("$")


@dataclass(frozen=True)
class LargestThreshold(ExactValueMixin):
    """The exact largest threshold: the end of the first interval of the valid
    set, ``attained`` if that end is itself valid.  ``binding`` is the
    condition (vertex/ray, facet, polynomial) whose sign change ends the
    interval, or None when a pole of r(dt A) (``singular``) ends it."""

    value: Real
    attained: bool
    method: Method = field(repr=False)
    binding: Condition | None = None
    singular: Real | None = None
    system: LinearSystem | None = field(default=None, repr=False)
    polyhedron: Polyhedron | None = field(default=None, repr=False)
    checked: tuple[Condition, ...] = field(default=(), repr=False)
    determinant: tuple[Fraction, ...] = field(default=(Fraction(1),), repr=False)

    def claims(self) -> list[dict]:
        return [{
            "type": "largest_threshold",
            "value": encode_real(self.value),
            "attained": self.attained,
            **generator_record(self.polyhedron),
            "determinant": vec(self.determinant),
            "binding": None if self.binding is None else {
                "kind": self.binding.kind, "generator": self.binding.generator, "facet": self.binding.facet,
                "poly": vec(self.binding.poly)},
        }]

    @property
    def certificate(self) -> dict:
        """The JSON certificate for :func:`exactinv.check`."""
        return make_certificate(self.system, self.polyhedron, self.method, [self])

    def to_latex(self) -> str:
        return rf"\tau_{{\max}} = {latex_real(self.value)}\ (\text{{{'attained' if self.attained else 'not attained'}}})"

    def __repr__(self) -> str:
        return f"LargestThreshold(value={self.value}, attained={self.attained}, method={self.method.name})"


def valid_steplengths(system: LinearSystem, polyhedron: Polyhedron, method: Method) -> ValidSteplengths:
    """The exact set {dt >= 0 : A_d(dt) P subset of P} as a union of intervals
    with exact ends (open/closed marked); singular points of r(dt A) excluded."""
    check_problem(system, polyhedron, method)
    conditions, equalities, D, _ = conditions_of(system, polyhedron, method)
    distinct = distinct_conditions(conditions)
    singular = [r for r, _ in positive_roots(D)]
    # The valid set lies inside the valid set of any single generator: take the
    # conditions of the first vertex exactly, then skip every other condition
    # that Descartes' rule shows nonnegative on [0, T], T the end of that set.
    first = [c for c in distinct.values() if c.kind == Kind.VERTEX and c.generator == 0]
    bad: list[tuple[Real, Real]] = []
    for c in first:
        bad.extend(negative_segments(c.p))
    bound = complement_of_open(bad, singular)
    T = bound.intervals[-1].hi if bound.intervals else Fraction(0)
    for c in distinct.values():
        if c.kind == Kind.VERTEX and c.generator == 0:
            continue
        if not isinstance(T, Infinity) and positive_right_of_zero(c.p) and no_positive_root_below(c.p, upper_bound(T)):
            continue
        bad.extend(negative_segments(c.p))
    union = complement_of_open(bad, singular)
    if equalities:  # lines: only the common roots of every e survive
        allowed = None
        for e in distinct_conditions(equalities).values():
            roots = {r for r, _ in positive_roots(e.p)}
            allowed = roots if allowed is None else {r for r in allowed if any(r == s for s in roots)}
        points = [Fraction(0)] + sorted((r for r in allowed or () if r in union), key=ExactKey)
        union = IntervalUnion(tuple(Interval(p, p, True, True) for p in points))
    return ValidSteplengths(union, method, tuple(singular), len(conditions), len(distinct), system, polyhedron,
                            tuple(fraction_of(c) for c in D.coeffs()))


def largest_threshold(system: LinearSystem, polyhedron: Polyhedron, method: Method) -> LargestThreshold:
    """The exact largest threshold sup{T : A_d(dt) P subset of P for all dt in [0, T)}
    -- the end of the first interval of :func:`valid_steplengths` -- computed
    directly from the first sign change of each condition and the first pole."""
    check_problem(system, polyhedron, method)
    conditions, equalities, D, Dcoeffs = conditions_of(system, polyhedron, method)
    distinct = list(distinct_conditions(conditions).values())
    if equalities:
        return LargestThreshold(Fraction(0), True, method, equalities[0], None, system, polyhedron, tuple(distinct), tuple(Dcoeffs))
    best: Real = INF
    binding: Condition | None = None
    for c in sorted(distinct, key=lambda c: c.p(0)):  # the tightest pairs first
        if not isinstance(best, Infinity) and positive_right_of_zero(c.p) and no_positive_root_below(c.p, upper_bound(best)):
            continue  # c >= 0 on [0, best]: cannot end the first interval earlier
        end = nonnegative_until(c.p)
        if exact_lt(end, best):
            best, binding = end, c
    poles = positive_roots(D)
    singular = poles[0][0] if poles else None
    attained = True
    if singular is not None and not exact_lt(best, singular):
        best, binding, attained = singular, None, False
    if isinstance(best, Infinity):
        attained = True
    return LargestThreshold(best, attained, method, binding, singular, system, polyhedron, tuple(distinct), tuple(Dcoeffs))
