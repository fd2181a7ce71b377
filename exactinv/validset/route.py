"""The route protocol: how the verified conditions of a valid set are found (docs/design.md, "The route protocol").

A *route* turns one valid-set problem (a system, an invariant set and a
method, :class:`~exactinv.validset.problem.ValidSetProblem`) into exact
polynomial conditions whose common nonnegative set, with the poles of
r(hA) removed, IS the valid set {h >= 0 : A_d(h) S subset of S} -- as
cvxpy's ``Reduction``: :meth:`Route.accepts` says (cheaply: no vertex, no
LP) whether the route handles the problem, :meth:`Route.apply` produces the
conditions, each proved by the route's own theorem (vertex-facet pairs with
certified pruning, the box cells, the parametric LP's pieces, the ellipsoid's
coefficient polynomials).  One engine (:mod:`exactinv.validset.engine`)
turns any route's conditions into the valid set, the largest threshold and
the forward-Euler step; every route that accepts a problem gives the same
exact set, end by end and flag by flag (tests/validset/test_route.py).
"""

from __future__ import annotations

from abc import ABC, abstractmethod
from dataclasses import dataclass, field
from typing import TYPE_CHECKING, Any

from ..conditions.polyhedron import Condition
from ..core.intervals import IntervalUnion
from ..errors import ExactinvException

if TYPE_CHECKING:
    from .problem import ValidSetProblem

__all__ = ["Route", "RouteConditions", "RouteDeclined"]


class RouteDeclined(ExactinvException):
    """A route that accepted a problem found, while applying it, that it cannot finish
    (e.g. the LP route on an unbounded P): ``route="auto"`` takes the next route,
    a forced route reports it as :class:`~exactinv.InvalidInput`."""


@dataclass(frozen=True)
class RouteConditions:
    """What a route proves: the exact conditions of the valid set.

    ``inequalities`` (c(h) >= 0 each) and ``equalities`` (e(h) = 0, lines of P)
    are :class:`~exactinv.conditions.polyhedron.Condition` objects; ``leading`` are the
    conditions the engine intersects first (vertex 0, the trace q_1: they usually
    bound the set, so later conditions are skipped when Descartes shows them
    positive up to that bound); ``leading_set``, when the route already computed
    it, is the nonnegative set of ``leading``.  ``details`` are the route's own
    statistics and certificate records (``pruning``, ``box``, ``lp``; None when
    not used)."""

    route: str
    inequalities: tuple[Condition, ...]
    equalities: tuple[Condition, ...] = ()
    leading: tuple[Condition, ...] = ()
    leading_set: IntervalUnion | None = field(default=None, repr=False)
    details: dict[str, Any] = field(default_factory=dict, repr=False, compare=False)


class Route(ABC):
    """One way to the conditions of a valid set.  Subclasses set ``name`` and implement
    :meth:`accepts` (cheap), :meth:`refusal` (why not, for the error of a forced route),
    :meth:`estimate` (a cheap cost figure: ``route="auto"`` takes the least) and :meth:`apply`.
    The results of the engine are built by :meth:`valid_result` and :meth:`largest_result`,
    so the result types of a set type live with its routes, not in an ``isinstance`` chain."""

    name: str = ""

    @abstractmethod
    def accepts(self, problem: "ValidSetProblem") -> bool:
        """True if this route handles ``problem``; cheap (no vertex enumeration, no LP).

        >>> import exactinv as ei
        >>> from exactinv.validset.problem import ValidSetProblem
        >>> p = ValidSetProblem(ei.LinearSystem([[-1]]), ei.Polyhedron.box([-1], [1]), ei.methods.taylor(1))
        >>> from exactinv.validset.engine import ROUTES
        >>> [name for name, r in ROUTES.items() if r.accepts(p)]     # [-1, 1] is a box with rank G = 1
        ['vertex', 'box', 'lp']
        """

    @abstractmethod
    def refusal(self, problem: "ValidSetProblem") -> str:
        """Why :meth:`accepts` is False, in words for an error message.

        >>> import exactinv as ei
        >>> from exactinv.validset.problem import ValidSetProblem
        >>> p = ValidSetProblem(ei.LinearSystem([[-1]]), ei.Polyhedron.box([-1], [1]), ei.methods.taylor(1))
        >>> from exactinv.validset.engine import ROUTES
        >>> ROUTES["ellipsoid"].refusal(p)
        'the ellipsoid route handles ellipsoids, not a polyhedron'
        """

    @abstractmethod
    def estimate(self, problem: "ValidSetProblem") -> float:
        """A cheap cost figure for the route choice (smaller runs first).

        >>> import exactinv as ei
        >>> from exactinv.validset.problem import ValidSetProblem
        >>> p = ValidSetProblem(ei.LinearSystem([[-1]]), ei.Polyhedron.box([-1], [1]), ei.methods.taylor(1))
        >>> from exactinv.validset.engine import ROUTES
        >>> ROUTES["box"].estimate(p) < ROUTES["vertex"].estimate(p) < ROUTES["lp"].estimate(p)
        True
        """

    @abstractmethod
    def apply(self, problem: "ValidSetProblem", first_end: bool) -> RouteConditions:
        """The route's proved conditions; ``first_end``: only the first interval's end is wanted
        (a route may then prune more).  May raise :class:`RouteDeclined`.

        x' = -x on [-1, 1], forward Euler: the vertex -1 on the facet x <= 1 gives 2 - h >= 0.

        >>> import exactinv as ei
        >>> from exactinv.validset.problem import ValidSetProblem
        >>> p = ValidSetProblem(ei.LinearSystem([[-1]]), ei.Polyhedron.box([-1], [1]), ei.methods.taylor(1))
        >>> from exactinv.validset.engine import ROUTES
        >>> found = ROUTES["vertex"].apply(p, False)
        >>> found.route, [c.poly for c in found.inequalities]
        ('vertex', [(Fraction(2, 1), Fraction(-1, 1)), (Fraction(2, 1), Fraction(-1, 1))])
        """

    @abstractmethod
    def valid_result(self, problem: "ValidSetProblem", found: RouteConditions, union: IntervalUnion,
                     singular: tuple, distinct: int) -> Any:
        """The valid-set result object of this route's set type (the engine calls it).

        >>> import exactinv as ei
        >>> from exactinv.validset.problem import ValidSetProblem
        >>> p = ValidSetProblem(ei.LinearSystem([[-1]]), ei.Polyhedron.box([-1], [1]), ei.methods.taylor(1))
        >>> from exactinv.validset.engine import ROUTES, valid_set
        >>> type(valid_set(p, "box")).__name__
        'ValidSteplengths'
        """

    @abstractmethod
    def largest_result(self, problem: "ValidSetProblem", found: RouteConditions, value: Any, attained: bool,
                       binding: Condition | None, singular: Any, checked: tuple[Condition, ...]) -> Any:
        """The largest-threshold result object of this route's set type (the engine calls it).

        >>> import exactinv as ei
        >>> from exactinv.validset.problem import ValidSetProblem
        >>> e = ValidSetProblem(ei.LinearSystem([[-1]]), ei.Ellipsoid([[1]]), ei.methods.taylor(1))
        >>> from exactinv.validset.engine import largest
        >>> type(largest(e)).__name__
        'EllipsoidLargestThreshold'
        """

    def __repr__(self) -> str:
        return f"{type(self).__name__}()"
