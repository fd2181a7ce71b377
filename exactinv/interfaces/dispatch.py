"""The public invariance and threshold functions, dispatched on the invariant set.

A :class:`~exactinv.Polyhedron` goes to the paper's and the polyhedral
functions (:mod:`exactinv.paper`, :mod:`exactinv.beyond.largest`); an
:class:`~exactinv.Ellipsoid` to :mod:`exactinv.beyond.ellipsoid_invariance`
and :mod:`exactinv.beyond.ellipsoid_thresholds`.  Same names, same argument
order, result types with the same attributes.  (The dispatch lives here
because ``paper`` and ``beyond`` never import each other.)
"""

from __future__ import annotations

from typing import Any

from ..beyond import largest as polyhedral
from ..beyond.ellipsoid_invariance import (
    EllipsoidInvariance,
    ellipsoid_continuous_invariance,
    ellipsoid_discrete_invariance,
)
from ..beyond.ellipsoid_thresholds import (
    EllipsoidForwardEulerThreshold,
    ellipsoid_forward_euler_threshold,
    ellipsoid_largest_threshold,
    ellipsoid_valid_steplengths,
)
from ..beyond.largest import ConditionSet, LargestThreshold, ValidSteplengths
from ..model import Ellipsoid
from ..paper import forward_euler as paper_fe, invariance as paper_inv
from ..paper.forward_euler import ForwardEulerThreshold
from ..paper.invariance import ContinuousInvariance, DiscreteInvariance

__all__ = ["continuous_invariance", "discrete_invariance", "forward_euler_threshold", "valid_steplengths",
           "largest_threshold"]


def continuous_invariance(system: Any, invariant_set: Any) -> ContinuousInvariance | EllipsoidInvariance:
    """Is the set (a Polyhedron or an Ellipsoid) invariant for x' = Ax?  Exact, with a certificate.

    >>> from exactinv import LinearSystem, Ellipsoid
    >>> continuous_invariance(LinearSystem([[-1, 0], [0, -2]]), Ellipsoid([[1, 0], [0, 1]])).holds
    True
    """
    if isinstance(invariant_set, Ellipsoid):
        return ellipsoid_continuous_invariance(system, invariant_set)
    return paper_inv.continuous_invariance(system, invariant_set)


def discrete_invariance(Ad: Any, invariant_set: Any, method: Any = None, dt: Any = None, *,
                        allow_float: bool = False) -> DiscreteInvariance | EllipsoidInvariance:
    """Is the set mapped into itself by x+ = A_d x (A_d a matrix, or r(dt A) from a system, a method and dt)?

    >>> from exactinv import Ellipsoid
    >>> discrete_invariance([[0, 1], [-1, 0]], Ellipsoid([[1, 0], [0, 1]])).holds
    True
    """
    if isinstance(invariant_set, Ellipsoid):
        return ellipsoid_discrete_invariance(Ad, invariant_set, method, dt, allow_float=allow_float)
    return paper_inv.discrete_invariance(Ad, invariant_set, method, dt, allow_float=allow_float)


def forward_euler_threshold(system: Any, invariant_set: Any) -> ForwardEulerThreshold | EllipsoidForwardEulerThreshold:
    """The largest forward-Euler step, exact and cross-checked two ways.

    >>> from exactinv import LinearSystem, Ellipsoid
    >>> forward_euler_threshold(LinearSystem([[-1, -2], [2, -1]]), Ellipsoid([[1, 0], [0, 1]])).value
    Fraction(2, 5)
    """
    if isinstance(invariant_set, Ellipsoid):
        return ellipsoid_forward_euler_threshold(system, invariant_set)
    return paper_fe.forward_euler_threshold(system, invariant_set)


def valid_steplengths(system: Any, invariant_set: Any, method: Any, *, prune: bool = True,
                      conditions: ConditionSet | None = None, box: bool = True, route: str = "auto") -> ValidSteplengths:
    """The exact set of valid steplengths h >= 0, a union of intervals with exact ends.
    On a polyhedron, ``prune``, ``conditions`` (a :class:`ConditionSet` of the
    same problem, shared with :func:`largest_threshold`) and ``box`` (the box
    route on a box; False: every vertex-facet pair) and ``route`` ("auto", "vertex", "box"
    or "lp": how the conditions are found, the set is the same; the result's ``route``
    says which ran) are passed on.

    >>> from exactinv import LinearSystem, Ellipsoid, methods
    >>> valid_steplengths(LinearSystem([[-1]]), Ellipsoid([[1]]), methods.taylor(2))
    EllipsoidValidSteplengths([0, 2], method=taylor(2))
    """
    if isinstance(invariant_set, Ellipsoid):
        return ellipsoid_valid_steplengths(system, invariant_set, method)
    return polyhedral.valid_steplengths(system, invariant_set, method, prune=prune, conditions=conditions, box=box,
                                 route=route)


def largest_threshold(system: Any, invariant_set: Any, method: Any, *, prune: bool = True,
                      conditions: ConditionSet | None = None, box: bool = True, route: str = "auto") -> LargestThreshold:
    """The exact largest threshold: the end of the first interval of the valid set
    (``prune``, ``conditions``, ``box``, ``route`` as for :func:`valid_steplengths`).

    >>> from exactinv import LinearSystem, Ellipsoid, methods
    >>> largest_threshold(LinearSystem([[-1]]), Ellipsoid([[1]]), methods.backward_euler()).value
    INF
    """
    if isinstance(invariant_set, Ellipsoid):
        return ellipsoid_largest_threshold(system, invariant_set, method)
    return polyhedral.largest_threshold(system, invariant_set, method, prune=prune, conditions=conditions, box=box,
                                 route=route)
