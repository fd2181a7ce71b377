"""The ellipsoid route: E = {x : x^T Q x <= 1} (docs/design.md, "The route protocol"; docs/ellipsoids.md).

A_d(h) E subset of E iff q_k(h) >= 0 for k = 1..n and h > 0 with h(hA)
regular, q_k the coefficient polynomials of H^T Q H - G^T Q G divided by h
(:mod:`exactinv.conditions.ellipsoid`), and h = 0 is always valid.
So the route's conditions are c_k(h) = h q_k(h) >= 0: the same set for
h > 0, and c_k(0) = 0 keeps h = 0.  The engine treats them like any other
route's conditions (q_1, the trace, first: it usually bounds the set).
"""

from __future__ import annotations

from typing import Any

import flint

from ..conditions.polyhedron import Condition, Kind, never_binds
from ..core.flintq import fraction_of
from ..core.intervals import IntervalUnion
from .families import ELLIPSOIDS
from .problem import ValidSetProblem
from .results import EllipsoidLargestThreshold, EllipsoidValidSteplengths
from .route import Route, RouteConditions

__all__ = ["EllipsoidRoute"]

_H = flint.fmpq_poly([0, 1])


class EllipsoidRoute(Route):
    """The coefficient polynomials of the congruent matrix condition, as conditions h q_k(h) >= 0."""

    name = "ellipsoid"

    def accepts(self, problem: ValidSetProblem) -> bool:
        """An ellipsoid.

        >>> import exactinv as ei
        >>> from exactinv.validset.problem import ValidSetProblem
        >>> e = ValidSetProblem(ei.LinearSystem([[-1]]), ei.Ellipsoid([[1]]), ei.methods.taylor(2))
        >>> EllipsoidRoute().accepts(e)
        True
        """
        return problem.family is ELLIPSOIDS

    def refusal(self, problem: ValidSetProblem) -> str:
        """Not an ellipsoid.

        >>> import exactinv as ei
        >>> from exactinv.validset.problem import ValidSetProblem
        >>> p = ValidSetProblem(ei.LinearSystem([[-1]]), ei.Polyhedron.box([-1], [1]), ei.methods.taylor(1))
        >>> EllipsoidRoute().refusal(p)
        'the ellipsoid route handles ellipsoids, not a polyhedron'
        """
        return f"the ellipsoid route handles ellipsoids, not a {problem.family.name}"

    def estimate(self, problem: ValidSetProblem) -> float:
        """n: the number of coefficient polynomials.

        >>> import exactinv as ei
        >>> from exactinv.validset.problem import ValidSetProblem
        >>> e = ValidSetProblem(ei.LinearSystem([[-1]]), ei.Ellipsoid([[1]]), ei.methods.taylor(2))
        >>> EllipsoidRoute().estimate(e)
        1
        """
        return problem.invariant_set.n

    def apply(self, problem: ValidSetProblem, first_end: bool) -> RouteConditions:
        """The conditions h q_k(h) >= 0 that can bind.

        Taylor(2) on x' = -x, Q = 1: 1 - r(-h)^2 = h (1 - h/2)(2 - h + h^2/2), so
        q_1 = (1 - h/2)(2 - h + h^2/2) = 2 - 2h + h^2 - h^3/4, and the condition is h q_1.

        >>> import exactinv as ei
        >>> from exactinv.validset.problem import ValidSetProblem
        >>> e = ValidSetProblem(ei.LinearSystem([[-1]]), ei.Ellipsoid([[1]]), ei.methods.taylor(2))
        >>> [c.poly for c in EllipsoidRoute().apply(e, False).inequalities]
        [(Fraction(0, 1), Fraction(2, 1), Fraction(-2, 1), Fraction(1, 1), Fraction(-1, 4))]
        """
        qs, _ = problem.coefficient_polynomials
        out = [Condition(Kind.COEFFICIENT, k, 0, _H * q) for k, q in enumerate(qs, start=1)
               if not never_binds(q.coeffs())]
        return RouteConditions(self.name, tuple(out), (), tuple(c for c in out if c.generator == 1))

    def valid_result(self, problem: ValidSetProblem, found: RouteConditions, union: IntervalUnion,
                     singular: tuple, distinct: int) -> EllipsoidValidSteplengths:
        """An :class:`EllipsoidValidSteplengths` with the q_k.

        >>> import exactinv as ei
        >>> from exactinv.validset.problem import ValidSetProblem
        >>> e = ValidSetProblem(ei.LinearSystem([[-1]]), ei.Ellipsoid([[1]]), ei.methods.taylor(2))
        >>> from exactinv.validset.engine import valid_set
        >>> valid_set(e)
        EllipsoidValidSteplengths([0, 2], method=taylor(2))
        """
        qs, _ = problem.coefficient_polynomials
        return EllipsoidValidSteplengths(union, problem.method, singular, len(qs), len(qs), system=problem.system,
                                         polyhedron=problem.invariant_set, determinant=tuple(problem.Dcoeffs),
                                         route=self.name,
                                         polynomials=tuple(tuple(fraction_of(c) for c in q.coeffs()) for q in qs))

    def largest_result(self, problem: ValidSetProblem, found: RouteConditions, value: Any, attained: bool,
                       binding: Condition | None, singular: Any, checked: tuple[Condition, ...]) -> EllipsoidLargestThreshold:
        """An :class:`EllipsoidLargestThreshold`; ``coefficient`` the k of the binding h q_k.

        >>> import exactinv as ei
        >>> from exactinv.validset.problem import ValidSetProblem
        >>> e = ValidSetProblem(ei.LinearSystem([[-1]]), ei.Ellipsoid([[1]]), ei.methods.taylor(2))
        >>> from exactinv.validset.engine import largest
        >>> L = largest(e)
        >>> L.value, L.coefficient
        (Fraction(2, 1), 1)
        """
        return EllipsoidLargestThreshold(value, attained, problem.method, None, singular, system=problem.system,
                                         polyhedron=problem.invariant_set, determinant=tuple(problem.Dcoeffs),
                                         route=self.name, coefficient=None if binding is None else binding.generator)
