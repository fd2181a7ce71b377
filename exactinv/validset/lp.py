"""The LP route: per facet, the pieces of [0, oo) on which one basis of the parametric LP
max g_i A_d(h) x over P is optimal (docs/design.md, "The LP route" and "The route protocol").

Wraps :func:`exactinv.validset.lp_route.lp_route` (weak duality proves each
piece's vertex a maximizer, a ray of P each ray piece's unboundedness; the
vertex-facet and ray-facet conditions of the pieces give the valid set
exactly, with no vertex list).  It accepts every P, bounded or not; a P with
lines (rank G < n) goes through :func:`exactinv.validset.lp_lines.lp_lines`
(the pieces on P' = P with the rows of a basis of ker G appended, and the
line equalities).  The rare degenerate point it cannot decide is found while
solving and declined (:class:`~exactinv.validset.route.RouteDeclined`).
"""

from __future__ import annotations

from .lp_lines import lp_lines
from .lp_route import LPRoute, LPRouteDeclined, lp_route
from .polyhedral import PolyhedralRoute, vertex_zero
from .problem import ValidSetProblem
from .route import RouteConditions, RouteDeclined

__all__ = ["ParametricLPRoute", "LP_ABOVE"]

LP_ABOVE = 5000
"""The notional cost of one facet's parametric LP in units of vertex-facet pairs: ``route="auto"``
takes the LP route when McMullen's bound on the vertex count exceeds this."""


class ParametricLPRoute(PolyhedralRoute):
    """The LP route."""

    name = "lp"

    def estimate(self, problem: ValidSetProblem) -> float:
        """Facets times :data:`LP_ABOVE` (+1: a tie goes to the vertex route).

        >>> import exactinv as ei
        >>> from exactinv.validset.problem import ValidSetProblem
        >>> p = ValidSetProblem(ei.LinearSystem([[-1]]), ei.Polyhedron.box([-1], [1]), ei.methods.taylor(1))
        >>> ParametricLPRoute().estimate(p)
        10001
        """
        return problem.invariant_set.m * LP_ABOVE + 1

    def apply(self, problem: ValidSetProblem, first_end: bool) -> RouteConditions:
        """The conditions of the pieces (:func:`~exactinv.validset.lp_route.lp_route`; RouteDeclined
        at an irrational point where all ray conditions of a facet vanish).

        >>> import exactinv as ei
        >>> from exactinv.validset.problem import ValidSetProblem
        >>> p = ValidSetProblem(ei.LinearSystem([[-1]]), ei.Polyhedron.box([-1], [1]), ei.methods.taylor(1))
        >>> found = ParametricLPRoute().apply(p, False)
        >>> [c.poly for c in found.inequalities], found.details["lp"].pieces
        ([(Fraction(2, 1), Fraction(-1, 1)), (Fraction(2, 1), Fraction(-1, 1))], 4)
        """
        cs = problem.conditions
        pieces: LPRoute
        try:
            if cs.G.rank() < problem.invariant_set.n:
                inequalities, equalities, pieces = lp_lines(cs)
            else:
                (inequalities, pieces), equalities = lp_route(cs), []
        except LPRouteDeclined as exc:
            raise RouteDeclined(str(exc)) from None
        return RouteConditions(self.name, tuple(inequalities), tuple(equalities), vertex_zero(inequalities), None,
                               {"lp": pieces})
