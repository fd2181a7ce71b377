"""What the routes of a polyhedron share: their result objects (:class:`ValidSteplengths`,
:class:`LargestThreshold`, whose claims record P by the route's own record) and the
family test of :meth:`accepts` (docs/design.md, "The route protocol")."""

from __future__ import annotations

from typing import Any

from ..conditions.polyhedron import Condition, Kind
from ..core.intervals import IntervalUnion
from .families import POLYHEDRA
from .problem import ValidSetProblem
from .results import LargestThreshold, ValidSteplengths
from .route import Route, RouteConditions

__all__ = ["PolyhedralRoute", "vertex_zero"]


def vertex_zero(inequalities) -> tuple[Condition, ...]:
    """The conditions of generator 0 of kind vertex: the engine intersects them first (they
    usually bound the set, so most others are then skipped by Descartes' rule).

    >>> import exactinv as ei
    >>> cs = ei.ConditionSet(ei.LinearSystem([[-1]]), ei.Polyhedron.box([-1], [1]), ei.methods.taylor(1))
    >>> [(c.generator, c.facet) for c in vertex_zero(cs.all()[0])]
    [(0, 0)]
    """
    return tuple(c for c in inequalities if c.kind == Kind.VERTEX and c.generator == 0)


class PolyhedralRoute(Route):
    """A route of P = {Gx <= b}: accepts only polyhedra (then its own test)."""

    def accepts(self, problem: ValidSetProblem) -> bool:
        """A polyhedron that this route's own test accepts.

        >>> import exactinv as ei
        >>> from exactinv.validset.problem import ValidSetProblem
        >>> e = ValidSetProblem(ei.LinearSystem([[-1]]), ei.Ellipsoid([[1]]), ei.methods.taylor(1))
        >>> from exactinv.validset.engine import ROUTES
        >>> ROUTES["vertex"].accepts(e)
        False
        """
        return problem.family is POLYHEDRA and self._accepts_polyhedron(problem)

    def _accepts_polyhedron(self, problem: ValidSetProblem) -> bool:
        return True

    def refusal(self, problem: ValidSetProblem) -> str:
        """Why not: another set type, or this route's own reason.

        >>> import exactinv as ei
        >>> from exactinv.validset.problem import ValidSetProblem
        >>> e = ValidSetProblem(ei.LinearSystem([[-1]]), ei.Ellipsoid([[1]]), ei.methods.taylor(1))
        >>> from exactinv.validset.engine import ROUTES
        >>> ROUTES["lp"].refusal(e)
        'the lp route handles polyhedra, not a ellipsoid'
        """
        if problem.family is not POLYHEDRA:
            return f"the {self.name} route handles polyhedra, not a {problem.family.name}"
        return self._polyhedron_refusal(problem)

    def _polyhedron_refusal(self, problem: ValidSetProblem) -> str:
        return ""

    def valid_result(self, problem: ValidSetProblem, found: RouteConditions, union: IntervalUnion,
                     singular: tuple, distinct: int) -> ValidSteplengths:
        """A :class:`ValidSteplengths` recording the route's own details (pruning, box, LP pieces).

        >>> import exactinv as ei
        >>> from exactinv.validset.problem import ValidSetProblem
        >>> p = ValidSetProblem(ei.LinearSystem([[-1]]), ei.Polyhedron.box([-1], [1]), ei.methods.taylor(1))
        >>> from exactinv.validset.engine import valid_set
        >>> V = valid_set(p, "lp")
        >>> V.route, V.lp is not None, V.box is None
        ('lp', True, True)
        """
        d = found.details
        return ValidSteplengths(union, problem.method, singular, len(found.inequalities), distinct, problem.system,
                                problem.invariant_set, tuple(problem.Dcoeffs), d.get("pruning"), d.get("box"),
                                d.get("lp"), route=found.route)

    def largest_result(self, problem: ValidSetProblem, found: RouteConditions, value: Any, attained: bool,
                       binding: Condition | None, singular: Any, checked: tuple[Condition, ...]) -> LargestThreshold:
        """A :class:`LargestThreshold` recording the route's own details.

        >>> import exactinv as ei
        >>> from exactinv.validset.problem import ValidSetProblem
        >>> p = ValidSetProblem(ei.LinearSystem([[-1]]), ei.Polyhedron.box([-1], [1]), ei.methods.taylor(1))
        >>> from exactinv.validset.engine import largest
        >>> L = largest(p, "box")
        >>> L.value, L.route, L.box.box.lo
        (Fraction(2, 1), 'box', (Fraction(-1, 1),))
        """
        d = found.details
        return LargestThreshold(value, attained, problem.method, binding, singular, problem.system,
                                problem.invariant_set, checked, tuple(problem.Dcoeffs), d.get("pruning"),
                                d.get("box"), d.get("lp"), route=found.route)
