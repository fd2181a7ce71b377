"""The box route: P = {lo <= x <= hi} without vertex enumeration (docs/design.md, "The route protocol").

The conditions are those of the sign patterns of the rows of N(h) on the
cells between their entries' roots (:mod:`exactinv.conditions.box`,
which proves that their valid set is exactly that of all 2n 2^n
vertex-facet pairs).  It accepts P when every row of G has one nonzero
entry and every coordinate is bounded both ways (an O(mn) test).
"""

from __future__ import annotations

from ..conditions.box import box_route, detect_box
from .polyhedral import PolyhedralRoute, vertex_zero
from .problem import ValidSetProblem
from .route import RouteConditions

__all__ = ["BoxCellRoute"]


class BoxCellRoute(PolyhedralRoute):
    """The box route (``problem.box`` False turns it off for ``route="auto"``)."""

    name = "box"

    def _accepts_polyhedron(self, problem: ValidSetProblem) -> bool:
        P = problem.invariant_set
        return detect_box(P.G, P.b) is not None

    def _polyhedron_refusal(self, problem: ValidSetProblem) -> str:
        return "P is not a box (every row of G one nonzero entry, every coordinate bounded)"

    def estimate(self, problem: ValidSetProblem) -> float:
        """Entry polynomials: n (n + 1) (no vertex, no pair).

        >>> import exactinv as ei
        >>> from exactinv.validset.problem import ValidSetProblem
        >>> p = ValidSetProblem(ei.LinearSystem([[-1]]), ei.Polyhedron.box([-1], [1]), ei.methods.taylor(1))
        >>> BoxCellRoute().estimate(p)
        2
        """
        n = problem.invariant_set.n
        return n * (n + 1)

    def apply(self, problem: ValidSetProblem, first_end: bool) -> RouteConditions:
        """The box route's conditions and statistics (cached on the problem's ConditionSet).

        >>> import exactinv as ei
        >>> from exactinv.validset.problem import ValidSetProblem
        >>> p = ValidSetProblem(ei.LinearSystem([[-1]]), ei.Polyhedron.box([-1], [1]), ei.methods.taylor(1))
        >>> found = BoxCellRoute().apply(p, False)
        >>> [c.poly for c in found.inequalities], found.details["box"].entries
        ([(Fraction(2, 1), Fraction(-1, 1))], 2)
        """
        found = box_route(problem.conditions)
        assert found is not None  # accepts() saw the box
        inequalities, stats = found
        return RouteConditions(self.name, tuple(inequalities), (), vertex_zero(inequalities), None, {"box": stats})
