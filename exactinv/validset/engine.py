"""The one valid-set engine: the valid set, the largest threshold and the forward-Euler step
from any route (docs/design.md, "The route protocol").

For a route's conditions c(h) >= 0 and e(h) = 0 (:mod:`.route`) and the poles
of r(hA) (the positive roots of D), the valid set is

    V = {h >= 0 : D(h) != 0, every c(h) >= 0, every e(h) = 0},

computed exactly: each c is negative exactly on the open segments between
its own roots where its sign, tracked from the sign right of 0 through the
odd multiplicities, is negative (:func:`~exactinv.core.nonnegative.nonnegative_set`);
the route's leading conditions first, then every other one, skipped when
Descartes' rule shows it positive up to the current bound; with equalities
only their common roots (and 0) survive.  The largest threshold is the end
of the first interval, computed directly from the first sign change of each
condition and the first pole (a pole ends it, not attained).  The
forward-Euler step is the largest threshold for r(z) = 1 + z, cross-checked
against the set family's own derivation (:meth:`SetFamily.forward_euler`).

``route="auto"`` runs the accepting route of least cheap estimate
(dimension, facets, McMullen's bound on the vertex count; no vertex and no
LP): the box route on a box, the LP route when the vertex bound exceeds
:data:`~exactinv.validset.lp.LP_ABOVE`, else the vertex route, the ellipsoid
route on an ellipsoid; a route that declines while applying hands over to
the next.  A forced ``route=`` that does not accept the problem raises
:class:`~exactinv.InvalidInput` naming the route and why.  Every result has
``route``, the route that ran.
"""

from __future__ import annotations

import time
from fractions import Fraction
from typing import Any

import flint

from ..conditions.polyhedron import Condition, ConditionSet, distinct_conditions
from ..core.algebraic import ExactKey, Real, exact_lt, upper_bound
from ..core.flintq import fraction_of
from ..core.intervals import Interval, IntervalUnion, complement_of_open
from ..core.nonnegative import earliest_first, nonnegative_set
from ..core.polys import no_positive_root_below, positive_right_of_zero
from ..core.roots import nonnegative_until, positive_roots
from ..core.scalars import INF, Infinity
from ..errors import InvalidInput
from ..invariance.gamma_star import OptimalGamma
from ..model.methods import forward_euler
from .box import BoxCellRoute
from .ellipsoid import EllipsoidRoute
from .families import POLYHEDRA, family_of
from .lp import ParametricLPRoute
from .problem import ValidSetProblem
from .route import Route, RouteConditions, RouteDeclined
from .vertex import VertexRoute

__all__ = ["ROUTES", "ROUTE_NAMES", "accepting_routes", "choose_route", "apply_route", "valid_set", "largest",
           "valid_steplengths", "largest_threshold", "forward_euler_threshold", "forward_euler_with_gamma",
           "continuous_invariance", "discrete_invariance"]

ROUTES: dict[str, Route] = {r.name: r for r in (VertexRoute(), BoxCellRoute(), ParametricLPRoute(), EllipsoidRoute())}
"""Every route by name."""

ROUTE_NAMES = ("auto",) + tuple(ROUTES)
"""The values of ``route=``."""


def accepting_routes(problem: ValidSetProblem) -> list[Route]:
    """The routes that accept ``problem``, cheapest estimate first (``problem.box`` False: no box route).

    >>> import exactinv as ei
    >>> p = ValidSetProblem(ei.LinearSystem([[-1, 0], [0, -1]]), ei.Polyhedron.box([-1, -1], [1, 1]),
    ...                     ei.methods.taylor(2))
    >>> [r.name for r in accepting_routes(p)]
    ['box', 'vertex', 'lp']
    """
    found = [r for r in ROUTES.values() if (problem.box or r.name != "box") and r.accepts(problem)]
    return sorted(found, key=lambda r: r.estimate(problem))


def choose_route(problem: ValidSetProblem, route: str = "auto") -> list[Route]:
    """The routes to try in order: ``route`` alone when forced (InvalidInput if it does not accept the
    problem), else :func:`accepting_routes`.

    >>> import exactinv as ei
    >>> p = ValidSetProblem(ei.LinearSystem([[-1]]), ei.Ellipsoid([[1]]), ei.methods.taylor(2))
    >>> choose_route(p, "box")
    Traceback (most recent call last):
    ...
    exactinv.errors.InvalidInput: route: 'box' does not accept this problem: the box route handles polyhedra, not a ellipsoid
    """
    if not isinstance(route, str) or route not in ROUTE_NAMES:
        raise InvalidInput(f"route: expected one of {', '.join(map(repr, ROUTE_NAMES))}, got {route!r}")
    if route == "auto":
        return accepting_routes(problem)
    forced = ROUTES[route]
    if not forced.accepts(problem):
        raise InvalidInput(f"route: {route!r} does not accept this problem: {forced.refusal(problem)}")
    return [forced]


def apply_route(problem: ValidSetProblem, route: str, first_end: bool) -> tuple[Route, RouteConditions]:
    """(the route that ran, its conditions): the first of :func:`choose_route` that does not decline.

    >>> import exactinv as ei
    >>> p = ValidSetProblem(ei.LinearSystem([[-1]]), ei.Polyhedron.box([-1], [1]), ei.methods.taylor(1))
    >>> route, found = apply_route(p, "auto", False)
    >>> route.name, len(found.inequalities)
    ('box', 1)
    """
    reasons = []
    for r in choose_route(problem, route):
        try:
            return r, r.apply(problem, first_end)
        except RouteDeclined as exc:
            if route != "auto":
                raise InvalidInput(f"route: the {r.name} route declines this problem: {exc}") from None
            reasons.append(f"{r.name}: {exc}")
    raise InvalidInput("route: no route accepts this problem" + (f" ({'; '.join(reasons)})" if reasons else ""))


def valid_set(problem: ValidSetProblem, route: str = "auto") -> Any:
    """The exact valid set of ``problem`` by ``route`` (see the module docstring): the route's result object.

    >>> import exactinv as ei
    >>> p = ValidSetProblem(ei.LinearSystem([[-1]]), ei.Polyhedron.box([-1], [1]), ei.methods.taylor(1))
    >>> [(V.intervals, V.route) for V in (valid_set(p, r) for r in ("vertex", "box", "lp"))]
    [([0, 2], 'vertex'), ([0, 2], 'box'), ([0, 2], 'lp')]
    """
    t0 = time.perf_counter()
    r, found = apply_route(problem, route, False)
    distinct = distinct_conditions(list(found.inequalities))
    singular = [x for x, _ in positive_roots(problem.D)]
    leading = set(found.leading)
    first = found.leading_set
    if first is None:
        first = nonnegative_set(earliest_first([c.p for c in distinct.values() if c in leading]))
    union = nonnegative_set([c.p for c in distinct.values() if c not in leading],
                            first.intersect(complement_of_open([], singular)))
    if found.equalities:  # lines: only the common roots of every e survive
        allowed = None
        for e in distinct_conditions(list(found.equalities)).values():
            roots = {x for x, _ in positive_roots(e.p)}
            allowed = roots if allowed is None else {x for x in allowed if any(x == s for s in roots)}
        points = [Fraction(0)] + sorted((x for x in allowed or () if x in union), key=ExactKey)
        union = IntervalUnion(tuple(Interval(p, p, True, True) for p in points))
    found = _finished(found, t0)
    return r.valid_result(problem, found, union, tuple(singular), len(distinct))


def largest(problem: ValidSetProblem, route: str = "auto") -> Any:
    """The exact largest threshold of ``problem`` by ``route``: the end of the first interval of
    :func:`valid_set`, from the first sign change of each condition and the first pole.

    >>> import exactinv as ei
    >>> p = ValidSetProblem(ei.LinearSystem([[-1]]), ei.Polyhedron.box([-1], [1]), ei.methods.taylor(1))
    >>> L = largest(p, "vertex")
    >>> L.value, L.attained, L.binding.poly
    (Fraction(2, 1), True, (Fraction(2, 1), Fraction(-1, 1)))
    """
    t0 = time.perf_counter()
    r, found = apply_route(problem, route, True)
    distinct = list(distinct_conditions(list(found.inequalities)).values())
    poles = positive_roots(problem.D)
    singular = poles[0][0] if poles else None
    if found.equalities:
        return r.largest_result(problem, _finished(found, t0), Fraction(0), True, found.equalities[0], singular,
                                tuple(distinct))
    leading = set(found.leading)
    best: Real = INF
    binding: Condition | None = None
    for c in sorted(distinct, key=lambda c: (c not in leading, c.p(0))):
        if c.p.degree() <= 1:  # a linear condition (forward Euler): its end in closed form
            end = _linear_end(c.p)
        elif not isinstance(best, Infinity) and positive_right_of_zero(c.p) and no_positive_root_below(c.p, upper_bound(best)):
            continue  # c >= 0 on [0, best]: cannot end the first interval earlier
        else:
            end = nonnegative_until(c.p)
        if exact_lt(end, best):
            best, binding = end, c
    attained = True
    if singular is not None and not exact_lt(best, singular):
        best, binding, attained = singular, None, False
    if isinstance(best, Infinity):
        attained = True
    return r.largest_result(problem, _finished(found, t0), best, attained, binding, singular, tuple(distinct))


def _linear_end(p: flint.fmpq_poly) -> Real:
    """sup{T : c0 + c1 h >= 0 on [0, T]} for a polynomial of degree <= 1, exactly (as
    :func:`~exactinv.core.roots.nonnegative_until`): 0 if c0 < 0, -c0/c1 if c1 < 0, else INF.

    >>> _linear_end(flint.fmpq_poly([2, -1])), _linear_end(flint.fmpq_poly([0, 3])), _linear_end(flint.fmpq_poly([-1, 5]))
    (Fraction(2, 1), INF, Fraction(0, 1))
    """
    c = [fraction_of(x) for x in p.coeffs()] + [Fraction(0)] * 2
    if c[0] < 0:
        return Fraction(0)
    return -c[0] / c[1] if c[1] < 0 else INF


def _finished(found: RouteConditions, t0: float) -> RouteConditions:
    pruning = found.details.get("pruning")
    if pruning is None:
        return found
    return RouteConditions(found.route, found.inequalities, found.equalities, found.leading, found.leading_set,
                           {**found.details, "pruning": pruning.finished(time.perf_counter() - t0)})


# ------------------------------------------------------------------ the public functions


def valid_steplengths(system: Any, invariant_set: Any, method: Any, *, prune: bool = True,
                      conditions: ConditionSet | None = None, box: bool = True, route: str = "auto") -> Any:
    """The exact set {dt >= 0 : A_d(dt) S subset of S} (S a Polyhedron or an Ellipsoid) as a union
    of intervals with exact ends (open/closed marked); singular points of r(dt A) excluded.
    ``prune``: certified pruning of the vertex route (same result); ``conditions``: a shared
    :class:`~exactinv.ConditionSet` of the same polyhedral problem; ``box``: False keeps
    ``route="auto"`` off the box route; ``route``: "auto", "vertex", "box", "lp" or "ellipsoid"
    (module docstring; the same set by every route that accepts the problem, the result's
    ``route`` says which ran).

    >>> import exactinv as ei
    >>> V = valid_steplengths(ei.LinearSystem([[-1]]), ei.Polyhedron([[1], [-1]], [1, 1]), ei.methods.taylor(1))
    >>> V.intervals, V.route
    ([0, 2], 'box')
    >>> V = valid_steplengths(ei.LinearSystem([[-1]]), ei.Polyhedron([[1], [-1]], [1, 1]), ei.methods.taylor(1),
    ...                       route="lp")
    >>> V.intervals, V.route
    ([0, 2], 'lp')
    >>> valid_steplengths(ei.LinearSystem([[-1]]), ei.Ellipsoid([[1]]), ei.methods.taylor(2))
    EllipsoidValidSteplengths([0, 2], method=taylor(2))
    """
    problem = ValidSetProblem(system, invariant_set, method, conditions=conditions, prune=prune, box=box)
    return valid_set(problem, route)


def largest_threshold(system: Any, invariant_set: Any, method: Any, *, prune: bool = True,
                      conditions: ConditionSet | None = None, box: bool = True, route: str = "auto") -> Any:
    """The exact largest threshold sup{T : A_d(dt) S subset of S for all dt in [0, T)} -- the end of
    the first interval of :func:`valid_steplengths` (arguments as there).

    >>> import exactinv as ei
    >>> largest_threshold(ei.LinearSystem([[-1]]), ei.Polyhedron([[1], [-1]], [1, 1]), ei.methods.taylor(2)).value
    Fraction(2, 1)
    >>> largest_threshold(ei.LinearSystem([[-1]]), ei.Ellipsoid([[1]]), ei.methods.backward_euler()).value
    INF
    """
    problem = ValidSetProblem(system, invariant_set, method, conditions=conditions, prune=prune, box=box)
    return largest(problem, route)


def forward_euler_threshold(system: Any, invariant_set: Any) -> Any:
    """The largest forward-Euler step, exact and derived two ways: the engine's largest threshold for
    r(z) = 1 + z, and 1/gamma* (a polyhedron, Lemma 3.14) or a generalised eigenvalue (an ellipsoid).

    >>> import exactinv as ei
    >>> fe = forward_euler_threshold(ei.LinearSystem([[-1, 1], [-1, -1]]), ei.Polyhedron.box([-1, -1], [1, 1]))
    >>> fe.value, fe.by_gamma, fe.by_vertices, fe.route
    (Fraction(1, 1), Fraction(1, 1), Fraction(1, 1), 'box')
    >>> forward_euler_threshold(ei.LinearSystem([[-1, -2], [2, -1]]), ei.Ellipsoid([[1, 0], [0, 1]])).value
    Fraction(2, 5)
    """
    problem = ValidSetProblem(system, invariant_set, forward_euler(), prune=False)  # linear conditions:
    return problem.family.forward_euler(problem.system, problem.invariant_set, largest(problem))  # pruning does not pay


def forward_euler_with_gamma(system: Any, polyhedron: Any, gamma: OptimalGamma) -> Any:
    """:func:`forward_euler_threshold` on a polyhedron with gamma* already solved for this very pair
    (:func:`exactinv.interfaces.pipeline.certify` solves it once for all claims); a gamma* that is
    not this pair's is refused by the cross-check (VerificationFailed).

    >>> import exactinv as ei
    >>> S, P = ei.LinearSystem([[-1]]), ei.Polyhedron.box([-1], [1])
    >>> forward_euler_with_gamma(S, P, ei.optimal_gamma(S, P)).value     # gamma* = 1/2
    Fraction(2, 1)
    """
    problem = ValidSetProblem(system, polyhedron, forward_euler(), prune=False)
    if problem.family is not POLYHEDRA:
        raise InvalidInput("polyhedron: gamma* is of a polyhedron")
    return POLYHEDRA.forward_euler(problem.system, problem.invariant_set, largest(problem), gamma)


def continuous_invariance(system: Any, invariant_set: Any) -> Any:
    """Is the set (a Polyhedron or an Ellipsoid) invariant for x' = Ax?  Exact, with a certificate.

    >>> from exactinv import LinearSystem, Ellipsoid
    >>> continuous_invariance(LinearSystem([[-1, 0], [0, -2]]), Ellipsoid([[1, 0], [0, 1]])).holds
    True
    """
    return family_of(invariant_set).continuous_invariance(system, invariant_set)


def discrete_invariance(Ad: Any, invariant_set: Any, method: Any = None, dt: Any = None, *,
                        allow_float: bool = False) -> Any:
    """Is the set mapped into itself by x+ = A_d x (A_d a matrix, or r(dt A) from a system, a method and dt)?

    >>> from exactinv import Ellipsoid
    >>> discrete_invariance([[0, 1], [-1, 0]], Ellipsoid([[1, 0], [0, 1]])).holds
    True
    """
    return family_of(invariant_set).discrete_invariance(Ad, invariant_set, method, dt, allow_float)
