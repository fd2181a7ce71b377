"""What the routes of a polyhedron share: their result objects (:class:`ValidSteplengths`,
:class:`LargestThreshold`, whose claims record P by the route's own record) and the
family test of :meth:`accepts` (docs/design.md, "The route protocol")."""

from __future__ import annotations

from typing import Any

from ..beyond.conditions import Condition, Kind
from ..core.intervals import IntervalUnion
from .families import POLYHEDRA
from .problem import ValidSetProblem
from .results import LargestThreshold, ValidSteplengths
from .route import Route, RouteConditions

__all__ = ["PolyhedralRoute", "vertex_zero"]


def vertex_zero(inequalities) -> tuple[Condition, ...]:
    """The conditions of generator 0 of kind vertex: the engine intersects them first (they
    usually bound the set, so most others are then skipped by Descartes' rule)."""
    return tuple(c for c in inequalities if c.kind == Kind.VERTEX and c.generator == 0)


class PolyhedralRoute(Route):
    """A route of P = {Gx <= b}: accepts only polyhedra (then :meth:`accepts_polyhedron`)."""

    def accepts(self, problem: ValidSetProblem) -> bool:
        return problem.family is POLYHEDRA and self.accepts_polyhedron(problem)

    def accepts_polyhedron(self, problem: ValidSetProblem) -> bool:
        return True

    def refusal(self, problem: ValidSetProblem) -> str:
        if problem.family is not POLYHEDRA:
            return f"the {self.name} route handles polyhedra, not a {problem.family.name}"
        return self.polyhedron_refusal(problem)

    def polyhedron_refusal(self, problem: ValidSetProblem) -> str:
        return ""

    def valid_result(self, problem: ValidSetProblem, found: RouteConditions, union: IntervalUnion,
                     singular: tuple, distinct: int) -> ValidSteplengths:
        d = found.details
        return ValidSteplengths(union, problem.method, singular, len(found.inequalities), distinct, problem.system,
                                problem.invariant_set, tuple(problem.Dcoeffs), d.get("pruning"), d.get("box"),
                                d.get("lp"), route=found.route)

    def largest_result(self, problem: ValidSetProblem, found: RouteConditions, value: Any, attained: bool,
                       binding: Condition | None, singular: Any, checked: tuple[Condition, ...]) -> LargestThreshold:
        d = found.details
        return LargestThreshold(value, attained, problem.method, binding, singular, problem.system,
                                problem.invariant_set, checked, tuple(problem.Dcoeffs), d.get("pruning"),
                                d.get("box"), d.get("lp"), route=found.route)
