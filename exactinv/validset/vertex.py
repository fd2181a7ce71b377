"""The vertex route: every generator-facet pair of P, with certified pruning (docs/design.md, "The route protocol").

A_d(h) P subset of P iff A_d(h) maps every vertex into P, every ray into the
recession cone and every line into the lineality space
(:mod:`exactinv.conditions.polyhedron`).  For more than one vertex and not too
many pairs per facet, vertex 0's conditions bound the set (or its first
interval) by a horizon T and only the pairs that can bind on [0, T] are
built (:mod:`exactinv.conditions.pruning`; rational methods in u = h/(s + h),
:mod:`exactinv.conditions.pruning_rational`): the same exact set.  It accepts
every polyhedron; its cost grows with the number of vertices.
"""

from __future__ import annotations

from ..conditions.polyhedron import Kind
from ..conditions.pruning import WORTHWHILE, bounding_horizon
from ..conditions.pruning import prune as prune_pairs
from ..conditions.pruning_rational import prune_rational
from .lp_route import vertex_bound
from .polyhedral import PolyhedralRoute, vertex_zero
from .problem import ValidSetProblem
from .route import RouteConditions

__all__ = ["VertexRoute"]


class VertexRoute(PolyhedralRoute):
    """Vertex-facet, ray-facet and line-facet conditions; pruned when ``problem.prune``."""

    name = "vertex"

    def estimate(self, problem: ValidSetProblem) -> float:
        """Pairs: facets times McMullen's bound on the vertex count (no vertex is computed).

        >>> import exactinv as ei
        >>> from exactinv.validset.problem import ValidSetProblem
        >>> t = ValidSetProblem(ei.LinearSystem([[-1, 0], [0, -1]]), ei.Polyhedron([[-1, 0], [0, -1], [1, 1]], [0, 0, 1]),
        ...                     ei.methods.taylor(1))
        >>> VertexRoute().estimate(t)     # 3 facets, a triangle's 3 vertices
        9
        """
        P = problem.invariant_set
        return P.m * vertex_bound(P.n, P.m)

    def apply(self, problem: ValidSetProblem, first_end: bool) -> RouteConditions:
        """Every pair, or vertex 0's conditions and the pairs that survive the pruning.

        x' = -x on the triangle, forward Euler: (1 - h) v stays in it iff h <= 1 (the
        vertices (1, 0) and (0, 1) on the facets x >= 0 and y >= 0).

        >>> import exactinv as ei
        >>> from exactinv.validset.problem import ValidSetProblem
        >>> t = ValidSetProblem(ei.LinearSystem([[-1, 0], [0, -1]]), ei.Polyhedron([[-1, 0], [0, -1], [1, 1]], [0, 0, 1]),
        ...                     ei.methods.taylor(1))
        >>> found = VertexRoute().apply(t, False)
        >>> sorted({c.poly for c in found.inequalities})
        [(Fraction(1, 1), Fraction(-1, 1))]
        """
        cs = problem.conditions
        P = cs.polyhedron  # each vertex lies on >= n facets, pairs that always survive: too many when n/m is large
        if problem.prune and cs.count(Kind.VERTEX) > 1 and P.n <= WORTHWHILE * P.m:
            if not cs.method.is_polynomial:  # in u = h/(s + h): [0, oo) becomes [0, 1]
                pruned = prune_rational(cs, first_end)
                if pruned is not None:
                    inequalities, equalities, pruning, vertex_zero = pruned
                    return self._found(inequalities, equalities, vertex_zero, pruning)
            else:
                T, first, seconds, vertex_zero = bounding_horizon(cs, first_end)
                if T is not None:
                    inequalities, equalities, pruning = prune_pairs(cs, T, first, seconds)
                    return self._found(inequalities, equalities, vertex_zero, pruning)
        inequalities, equalities = cs.all()
        return self._found(inequalities, equalities, None, None)

    def _found(self, inequalities, equalities, leading_set, pruning) -> RouteConditions:
        return RouteConditions(self.name, tuple(inequalities), tuple(equalities), vertex_zero(inequalities), leading_set,
                               {"pruning": pruning})
