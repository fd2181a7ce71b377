"""The exact largest thresholds -- beyond the paper (DESIGN.md section 1).

The valid set {dt >= 0 : A_d(dt) P subset of P} is a finite union of
intervals with algebraic ends, computed exactly from the roots (with
multiplicities) of the distinct condition polynomials (:mod:`.conditions`):
each c is negative exactly on the open segments between its own roots where
its sign, tracked from the sign right of 0 through the odd multiplicities, is
negative; dt must avoid the roots of D (where r(dt A) is singular).  A
polynomial that Descartes' rule shows nonnegative up to the current bound is
skipped, so only pairs that can actually bind reach root isolation.

The pairs are first pruned (:mod:`.pruning`): the conditions of vertex 0
bound the valid set (or the first interval) by a horizon T, and only the
pairs whose slack does not provably exceed the change of A_d(h)v on [0, T]
are built at all.  Rational methods are pruned in u = h/(s + h) on [0, U],
U = 1 when the valid set is unbounded (:mod:`.pruning_rational`).
``prune=False`` builds every pair (the unpruned route: the same exact
answer).  On a box {lo <= x <= hi} the conditions come from the box route
instead (:mod:`.box_conditions`: the sign patterns of the rows of N(h) on the
cells between their entries' roots, no vertex enumeration); ``box=False``
takes the general route.  For a large P the conditions come from the LP
route (:mod:`.lp_route`: per facet, the pieces of [0, oo) on which one basis
of the parametric LP max g_i A_d(h) x over P is optimal, each piece's vertex
one condition; no vertex enumeration).  ``route=`` chooses: ``"auto"`` (box
on a box, LP when McMullen's bound on the vertex count exceeds
:data:`LP_ABOVE` and the LP route accepts P, else the vertex route),
``"vertex"``, ``"box"`` or ``"lp"``; the result's ``route`` says which ran --
every route gives the same exact set.  Pass one
:class:`ConditionSet` as ``conditions=`` to share the built conditions
between the valid set, the largest threshold and the certificate.
"""

from __future__ import annotations

import time
from dataclasses import dataclass, field
from fractions import Fraction
from typing import Any

from ..core.algebraic import ExactKey, Real, exact_lt, upper_bound
from ..core.encode import encode_real, vec
from ..core.intervals import Interval, IntervalUnion, complement_of_open
from ..core.latex import latex_real
from ..core.nonnegative import earliest_first, nonnegative_set
from ..core.polys import no_positive_root_below, positive_right_of_zero
from ..core.results import ExactValueMixin
from ..core.roots import nonnegative_until, positive_roots
from ..core.scalars import INF, Infinity
from ..core.tags import ClaimType
from ..model import LinearSystem, Method, Polyhedron
from ..model.record import certificate as make_certificate, generator_record
from ..errors import InvalidInput
from .box_conditions import BoxRoute, box_route
from .conditions import Condition, ConditionSet, Kind, distinct_conditions
from .lp_route import LPRoute, LPRouteDeclined, lp_route, vertex_bound
from .pruning import VERTEX_ZERO, WORTHWHILE, Pruning, bounding_horizon, prune as prune_pairs
from .pruning_rational import prune_rational

__all__ = ["ValidSteplengths", "LargestThreshold", "valid_steplengths", "largest_threshold", "ConditionSet", "ROUTES",
           "LP_ABOVE"]

ROUTES = ("auto", "vertex", "box", "lp")
"""The values of ``route=``: how the conditions of the valid set are found (the set is the same)."""

LP_ABOVE = 5000
"""``route="auto"`` takes the LP route when McMullen's bound on the vertex count exceeds this."""


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
    pruning: Pruning | None = field(default=None, repr=False)
    box: BoxRoute | None = field(default=None, repr=False)
    lp: LPRoute | None = field(default=None, repr=False)

    @property
    def route(self) -> str:
        """Which route found the conditions: "box", "lp" or "vertex"."""
        return "box" if self.box is not None else "lp" if self.lp is not None else "vertex"

    def __iter__(self):
        return iter(self.intervals)

    def __len__(self) -> int:
        return len(self.intervals)

    def claims(self) -> list[dict]:
        """The certificate's claim: the intervals and the generators they were decided on.

        x' = -x on [-1, 1], forward Euler: 1 - dt in [-1, 1] iff dt in [0, 2].

        >>> import exactinv as ei
        >>> V = valid_steplengths(ei.LinearSystem([[-1]]), ei.Polyhedron([[1], [-1]], [1, 1]), ei.methods.taylor(1))
        >>> [(c["intervals"], c["box"]) for c in V.claims()]       # P is a box: no vertex list
        [([{'lo': '0', 'hi': '2', 'lo_closed': True, 'hi_closed': True}], {'lo': ['-1'], 'hi': ['1']})]
        >>> V = valid_steplengths(ei.LinearSystem([[-1]]), ei.Polyhedron([[1], [-1]], [1, 1]), ei.methods.taylor(1),
        ...                       box=False)
        >>> V.claims()[0]["vertices"]
        [['-1'], ['1']]
        """
        return [{
            "type": ClaimType.VALID_STEPLENGTHS,
            "intervals": [{"lo": encode_real(iv.lo), "hi": encode_real(iv.hi), "lo_closed": iv.lo_closed,
                           "hi_closed": iv.hi_closed} for iv in self.intervals],
            **_generators(self.polyhedron, self.box, self.lp),
            "determinant": vec(self.determinant),
            **({} if self.pruning is None or not self.pruning.applied else {"pruning": self.pruning.record()}),
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
        """The intervals in LaTeX (x' = -x on [-1, 1], forward Euler: [0, 2]).

        >>> import exactinv as ei
        >>> V = valid_steplengths(ei.LinearSystem([[-1]]), ei.Polyhedron([[1], [-1]], [1, 1]), ei.methods.taylor(1))
        >>> V.to_latex()
        '[0, 2]'
        """
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
    pruning: Pruning | None = field(default=None, repr=False)
    box: BoxRoute | None = field(default=None, repr=False)
    lp: LPRoute | None = field(default=None, repr=False)

    @property
    def route(self) -> str:
        """Which route found the conditions: "box", "lp" or "vertex"."""
        return "box" if self.box is not None else "lp" if self.lp is not None else "vertex"

    def claims(self) -> list[dict]:
        """The certificate's claim: the value, whether attained, and the binding condition.

        x' = -x on [-1, 1], Taylor(2): r(dt) = 1 - dt + dt^2/2 >= 1/2 > -1, and r <= 1 iff
        dt - dt^2/2 >= 0 (vertex 1 on the facet x <= 1) iff dt <= 2: tau = 2, attained.

        >>> import exactinv as ei
        >>> L = largest_threshold(ei.LinearSystem([[-1]]), ei.Polyhedron([[1], [-1]], [1, 1]), ei.methods.taylor(2))
        >>> claim = L.claims()[0]
        >>> claim["value"], claim["attained"], claim["binding"]["generator"], claim["binding"]["poly"]
        ('2', True, 1, ['0', '1', '-1/2'])
        """
        return [{
            "type": ClaimType.LARGEST_THRESHOLD,
            "value": encode_real(self.value),
            "attained": self.attained,
            **_generators(self.polyhedron, self.box, self.lp),
            "determinant": vec(self.determinant),
            "binding": None if self.binding is None else {
                "kind": self.binding.kind, "generator": self.binding.generator, "facet": self.binding.facet,
                "poly": vec(self.binding.poly)},
            **({} if self.pruning is None or not self.pruning.applied else {"pruning": self.pruning.record()}),
        }]

    @property
    def certificate(self) -> dict:
        """The JSON certificate for :func:`exactinv.check`."""
        return make_certificate(self.system, self.polyhedron, self.method, [self])

    def to_latex(self) -> str:
        """tau_max in LaTeX with whether it is attained (Taylor(2), x' = -x on [-1, 1]: 2, attained).

        >>> import exactinv as ei
        >>> L = largest_threshold(ei.LinearSystem([[-1]]), ei.Polyhedron([[1], [-1]], [1, 1]), ei.methods.taylor(2))
        >>> print(L.to_latex())
        \\tau_{\\max} = 2\\ (\\text{attained})
        """
        return rf"\tau_{{\max}} = {latex_real(self.value)}\ (\text{{{'attained' if self.attained else 'not attained'}}})"

    def __repr__(self) -> str:
        return f"LargestThreshold(value={self.value}, attained={self.attained}, method={self.method.name})"


def _generators(polyhedron: Polyhedron, box: BoxRoute | None, lp: LPRoute | None = None) -> dict:
    """The claim's record of P: the box (proved from G, b by the kernel), the LP route's
    pieces (proved by the kernel: no vertex list) or the generator lists."""
    if box is not None:
        return {"box": box.box.record()}
    if lp is not None:
        return {"lp": lp.record()}
    return generator_record(polyhedron)


def _conditions(cs: ConditionSet, first_end: bool, allow: bool, box: bool,
                route: str = "auto") -> tuple[list, list, Pruning | None, BoxRoute | None, LPRoute | None]:
    """(inequalities, equalities, pruning, box route, LP route): on a box (unless ``box`` is False
    or another route is forced) the box route's conditions; for a large P (``route`` "auto") or
    ``route="lp"`` the LP route's; else every pair, or -- for a polynomial method whose
    vertex 0 bounds the set (or its first interval) by a horizon T -- vertex 0's
    conditions, the surviving vertex pairs and every ray and line pair."""
    boxed = box_route(cs) if box and route in ("auto", "box") else None
    if boxed is not None:
        return boxed[0], [], None, boxed[1], None
    if route == "box":
        raise InvalidInput("route: 'box' needs P to be a box (every row of G one nonzero entry, every coordinate bounded)")
    P = cs.polyhedron
    if route == "lp" or (route == "auto" and vertex_bound(P.n, P.m) > LP_ABOVE):
        try:
            inequalities, lp = lp_route(cs)
            return inequalities, [], None, None, lp
        except LPRouteDeclined as exc:
            if route == "lp":
                raise InvalidInput(f"route: the LP route declines this problem: {exc}") from None
    P = cs.polyhedron  # each vertex lies on >= n facets, pairs that always survive: too many when n/m is large
    if allow and cs.count(Kind.VERTEX) > 1 and P.n <= WORTHWHILE * P.m:
        if not cs.method.is_polynomial:  # in u = h/(s + h): [0, oo) becomes [0, 1]
            pruned = prune_rational(cs, first_end)
            if pruned is not None:
                return (*pruned, None, None)
        else:
            T, first, seconds = bounding_horizon(cs, first_end)
            if T is not None:
                return (*prune_pairs(cs, T, first, seconds), None, None)
    conditions, equalities = cs.all()
    return conditions, equalities, None, None, None


def _problem(system, polyhedron, method, conditions, prune, box, route="auto"):
    for name, flag in (("prune", prune), ("box", box)):
        if not isinstance(flag, bool):
            raise InvalidInput(f"{name}: expected True or False, got {flag!r}")
    if not isinstance(route, str) or route not in ROUTES:
        raise InvalidInput(f"route: expected one of {', '.join(map(repr, ROUTES))}, got {route!r}")
    if conditions is None:
        return ConditionSet(system, polyhedron, method)  # checks the three arguments
    if not isinstance(conditions, ConditionSet):
        raise InvalidInput(f"conditions: expected a ConditionSet or None, got {type(conditions).__name__}")
    if not all(a is b or a == b for a, b in ((conditions.system, system), (conditions.polyhedron, polyhedron),
                                               (conditions.method, method))):
        raise InvalidInput("conditions: a ConditionSet of another (system, polyhedron, method)")
    return conditions


def valid_steplengths(system: LinearSystem, polyhedron: Polyhedron, method: Method, *, prune: bool = True,
                      conditions: ConditionSet | None = None, box: bool = True,
                      route: str = "auto") -> ValidSteplengths:
    """The exact set {dt >= 0 : A_d(dt) P subset of P} as a union of intervals
    with exact ends (open/closed marked); singular points of r(dt A) excluded.
    ``prune``: certified pruning of the vertex-facet pairs (same result);
    ``conditions``: a shared :class:`ConditionSet` of the same problem;
    ``box``: the box route on a box (same result; False: every vertex-facet pair);
    ``route``: "auto", "vertex", "box" or "lp" (module docstring; the same set by every route).

    >>> import exactinv as ei
    >>> V = valid_steplengths(ei.LinearSystem([[-1]]), ei.Polyhedron([[1], [-1]], [1, 1]), ei.methods.taylor(1))
    >>> V.intervals, V.route
    ([0, 2], 'box')
    >>> V = valid_steplengths(ei.LinearSystem([[-1]]), ei.Polyhedron([[1], [-1]], [1, 1]), ei.methods.taylor(1),
    ...                       route="lp")
    >>> V.intervals, V.route
    ([0, 2], 'lp')
    """
    cs = _problem(system, polyhedron, method, conditions, prune, box, route)
    t0 = time.perf_counter()
    inequalities, equalities, pruning, boxed, lp = _conditions(cs, False, prune, box, route)
    D = cs.D
    distinct = distinct_conditions(inequalities)
    singular = [r for r, _ in positive_roots(D)]
    # The valid set lies inside the valid set of any single generator: intersect the
    # conditions of the first vertex (tightest first; kept by the pruning when it ran)
    # and then every other, each skipped when proved positive up to the current bound.
    first = [c.p for c in distinct.values() if c.kind == Kind.VERTEX and c.generator == 0]
    vertex_zero = cs.derived.get(VERTEX_ZERO) if boxed is None and lp is None else None
    if vertex_zero is None:
        vertex_zero = nonnegative_set(earliest_first(first))
    union = nonnegative_set([c.p for c in distinct.values() if c.kind != Kind.VERTEX or c.generator != 0],
                            vertex_zero.intersect(complement_of_open([], singular)))
    if equalities:  # lines: only the common roots of every e survive
        allowed = None
        for e in distinct_conditions(equalities).values():
            roots = {r for r, _ in positive_roots(e.p)}
            allowed = roots if allowed is None else {r for r in allowed if any(r == s for s in roots)}
        points = [Fraction(0)] + sorted((r for r in allowed or () if r in union), key=ExactKey)
        union = IntervalUnion(tuple(Interval(p, p, True, True) for p in points))
    if pruning is not None:
        pruning = pruning.finished(time.perf_counter() - t0)
    return ValidSteplengths(union, method, tuple(singular), len(inequalities), len(distinct), system, polyhedron,
                            tuple(cs.Dcoeffs), pruning, boxed, lp)


def largest_threshold(system: LinearSystem, polyhedron: Polyhedron, method: Method, *, prune: bool = True,
                      conditions: ConditionSet | None = None, box: bool = True,
                      route: str = "auto") -> LargestThreshold:
    """The exact largest threshold sup{T : A_d(dt) P subset of P for all dt in [0, T)}
    -- the end of the first interval of :func:`valid_steplengths` -- computed
    directly from the first sign change of each condition and the first pole.
    ``prune``, ``conditions``, ``box`` and ``route`` as for :func:`valid_steplengths`.

    >>> import exactinv as ei
    >>> largest_threshold(ei.LinearSystem([[-1]]), ei.Polyhedron([[1], [-1]], [1, 1]), ei.methods.taylor(2)).value
    Fraction(2, 1)
    """
    cs = _problem(system, polyhedron, method, conditions, prune, box, route)
    t0 = time.perf_counter()
    inequalities, equalities, pruning, boxed, lp = _conditions(cs, True, prune, box, route)
    distinct = list(distinct_conditions(inequalities).values())
    Dcoeffs = tuple(cs.Dcoeffs)
    if equalities:
        return LargestThreshold(Fraction(0), True, method, equalities[0], None, system, polyhedron, tuple(distinct),
                                Dcoeffs, pruning, boxed, lp)
    best: Real = INF
    binding: Condition | None = None
    for c in sorted(distinct, key=lambda c: (c.kind != Kind.VERTEX or c.generator != 0, c.p(0))):
        if not isinstance(best, Infinity) and positive_right_of_zero(c.p) and no_positive_root_below(c.p, upper_bound(best)):
            continue  # c >= 0 on [0, best]: cannot end the first interval earlier
        end = nonnegative_until(c.p)
        if exact_lt(end, best):
            best, binding = end, c
    poles = positive_roots(cs.D)
    singular = poles[0][0] if poles else None
    attained = True
    if singular is not None and not exact_lt(best, singular):
        best, binding, attained = singular, None, False
    if isinstance(best, Infinity):
        attained = True
    if pruning is not None:
        pruning = pruning.finished(time.perf_counter() - t0)
    return LargestThreshold(best, attained, method, binding, singular, system, polyhedron, tuple(distinct), Dcoeffs,
                            pruning, boxed, lp)
