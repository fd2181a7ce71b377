"""The set types a valid set is computed on: polyhedra and ellipsoids (docs/design.md, "The route protocol").

A :class:`SetFamily` holds what depends on the type of the invariant set
and is not a route: the exact continuous and discrete invariance tests, the
check of the problem's arguments, and the second, independent derivation of
the largest forward-Euler step that the engine's valid set must agree with
(1/gamma* by Lemma 3.14 on a polyhedron; a generalised eigenvalue on an
ellipsoid).  :func:`family_of` is the one place that chooses by the type of
the set (its ``family``: :func:`exactinv.model.sets.set_family`); every other
decision goes through a family or a route.
"""

from __future__ import annotations

from abc import ABC, abstractmethod
from fractions import Fraction
from typing import Any

from ..conditions.polyhedron import ConditionSet
from ..core.scalars import INF, Infinity
from ..errors import InvalidInput, VerificationFailed
from ..invariance import polyhedra as paper_invariance
from ..invariance.ellipsoids import (
    check_ellipsoid_pair,
    ellipsoid_continuous_invariance,
    ellipsoid_discrete_invariance,
)
from ..invariance.gamma_star import OptimalGamma, optimal_gamma
from ..model.sets import set_family
from ..model.validate import check_method
from ..thresholds.ellipsoid_forward_euler import generalised_eigenvalue_step
from ..thresholds.forward_euler import ForwardEulerThreshold
from .results import EllipsoidForwardEulerThreshold

__all__ = ["SetFamily", "POLYHEDRA", "ELLIPSOIDS", "family_of"]


class SetFamily(ABC):
    """A type of invariant set.  ``name`` for messages; ``paper_applies``: the paper's theorems
    (gamma*, its thresholds) are about this type."""

    name: str = ""
    paper_applies: bool = False

    @abstractmethod
    def checked(self, system: Any, invariant_set: Any, method: Any, conditions: Any) -> tuple:
        """(system, set, method, ConditionSet or None), each checked (else InvalidInput).

        >>> import exactinv as ei
        >>> S, P = ei.LinearSystem([[-1]]), ei.Polyhedron.box([-1], [1])
        >>> family_of(P).checked(S, P, "taylor", None)
        Traceback (most recent call last):
        ...
        exactinv.errors.InvalidInput: method: expected an exactinv method (exactinv.methods.*), got str
        """

    @abstractmethod
    def continuous_invariance(self, system: Any, invariant_set: Any) -> Any:
        """Is the set invariant for x' = Ax?  Exact, with a certificate.

        >>> import exactinv as ei
        >>> S, E = ei.LinearSystem([[-1, -2], [2, -1]]), ei.Ellipsoid([[1, 0], [0, 1]])
        >>> family_of(E).continuous_invariance(S, E).holds
        True
        """

    @abstractmethod
    def discrete_invariance(self, Ad: Any, invariant_set: Any, method: Any, dt: Any, allow_float: bool) -> Any:
        """Is the set mapped into itself by x+ = A_d x?  Exact, with a certificate.

        >>> import exactinv as ei
        >>> S, P = ei.LinearSystem([[-1]]), ei.Polyhedron.box([-1], [1])
        >>> family_of(P).discrete_invariance([[3]], P, None, None, False).holds     # 3 [-1, 1] is not in [-1, 1]
        False
        """

    @abstractmethod
    def forward_euler(self, system: Any, invariant_set: Any, by_valid_set: Any, gamma: Any = None) -> Any:
        """The forward-Euler result: the engine's largest threshold ``by_valid_set`` for r(z) = 1 + z,
        cross-checked against this family's own derivation (VerificationFailed if they differ).

        >>> import exactinv as ei
        >>> S, E = ei.LinearSystem([[-1, -2], [2, -1]]), ei.Ellipsoid([[1, 0], [0, 1]])
        >>> from exactinv.validset.engine import largest_threshold
        >>> family_of(E).forward_euler(S, E, largest_threshold(S, E, ei.methods.forward_euler())).value
        Fraction(2, 5)
        """


class Polyhedra(SetFamily):
    """P = {x : Gx <= b} (:class:`~exactinv.Polyhedron`): the paper's sets."""

    name = "polyhedron"
    paper_applies = True

    def checked(self, system, invariant_set, method, conditions):
        """The checked arguments and the ConditionSet (``conditions``, if of this very problem).

        >>> import exactinv as ei
        >>> S, P = ei.LinearSystem([[-1]]), ei.Polyhedron.box([-1], [1])
        >>> POLYHEDRA.checked(S, P, ei.methods.taylor(2), None)[3]
        <exactinv.conditions.polyhedron.ConditionSet object at ...>
        """
        if conditions is None:
            cs = ConditionSet(system, invariant_set, method)  # checks the three arguments
        elif not isinstance(conditions, ConditionSet):
            raise InvalidInput(f"conditions: expected a ConditionSet or None, got {type(conditions).__name__}")
        elif not all(a is b or a == b for a, b in ((conditions.system, system), (conditions.polyhedron, invariant_set),
                                                   (conditions.method, method))):
            raise InvalidInput("conditions: a ConditionSet of another (system, polyhedron, method)")
        else:
            cs = conditions
        return cs.system, cs.polyhedron, cs.method, cs

    def continuous_invariance(self, system, invariant_set):
        """The paper's test (gamma*, an exact H or a facet witness).

        >>> import exactinv as ei
        >>> S, P = ei.LinearSystem([[-1]]), ei.Polyhedron.box([-1], [1])
        >>> POLYHEDRA.continuous_invariance(S, P).holds
        True
        """
        return paper_invariance.continuous_invariance(system, invariant_set)

    def discrete_invariance(self, Ad, invariant_set, method, dt, allow_float):
        """The paper's discrete test (an exact H~ or a witness vertex).

        >>> import exactinv as ei
        >>> S, P = ei.LinearSystem([[-1]]), ei.Polyhedron.box([-1], [1])
        >>> POLYHEDRA.discrete_invariance(S, P, ei.methods.forward_euler(), 2, False).holds   # 1 - 2 = -1
        True
        """
        return paper_invariance.discrete_invariance(Ad, invariant_set, method, dt, allow_float=allow_float)

    def forward_euler(self, system, invariant_set, by_valid_set, gamma: OptimalGamma | None = None) -> ForwardEulerThreshold:
        """1/gamma* (Lemma 3.14; ``gamma``: gamma* already solved for this very pair) against the valid set.

        >>> import exactinv as ei
        >>> S, P = ei.LinearSystem([[-1]]), ei.Polyhedron.box([-1], [1])
        >>> from exactinv.validset.engine import largest_threshold
        >>> fe = POLYHEDRA.forward_euler(S, P, largest_threshold(S, P, ei.methods.forward_euler()))
        >>> fe.value, fe.by_gamma, fe.route
        (Fraction(2, 1), Fraction(2, 1), 'box')
        """
        if gamma is None:
            gamma = optimal_gamma(system, invariant_set)
        g = gamma.value
        by_gamma = Fraction(0) if g == INF else (INF if isinstance(g, Infinity) or g <= 0 else 1 / g)
        value = by_valid_set.value
        if value != by_gamma:
            raise VerificationFailed(f"forward Euler: 1/gamma* = {by_gamma} but the valid set ({by_valid_set.route} "
                                     f"route) gives {value}")
        c = by_valid_set.binding
        binding = None if c is None else (str(c.kind), c.generator, c.facet)
        return ForwardEulerThreshold(value, by_gamma, value, binding, gamma, route=by_valid_set.route)


class Ellipsoids(SetFamily):
    """E = {x : x^T Q x <= 1} (:class:`~exactinv.Ellipsoid`, docs/ellipsoids.md)."""

    name = "ellipsoid"

    def checked(self, system, invariant_set, method, conditions):
        """The checked arguments; no ConditionSet (that is of a polyhedron).

        >>> import exactinv as ei
        >>> S, E = ei.LinearSystem([[-1, -2], [2, -1]]), ei.Ellipsoid([[1, 0], [0, 1]])
        >>> ELLIPSOIDS.checked(S, E, ei.methods.taylor(2), None)[3] is None
        True
        """
        if conditions is not None:
            raise InvalidInput("conditions: a ConditionSet is of a polyhedron; pass None on an ellipsoid")
        S, E = check_ellipsoid_pair(system, invariant_set)
        return S, E, check_method(method), None

    def continuous_invariance(self, system, invariant_set):
        """-(A^T Q + Q A) >= 0, by an exact LDL^T (or a witness direction).

        >>> import exactinv as ei
        >>> S, E = ei.LinearSystem([[-1, -2], [2, -1]]), ei.Ellipsoid([[1, 0], [0, 1]])
        >>> ELLIPSOIDS.continuous_invariance(S, E).holds
        True
        """
        return ellipsoid_continuous_invariance(system, invariant_set)

    def discrete_invariance(self, Ad, invariant_set, method, dt, allow_float):
        """Q - A_d^T Q A_d >= 0, exactly.

        >>> import exactinv as ei
        >>> S, E = ei.LinearSystem([[-1, -2], [2, -1]]), ei.Ellipsoid([[1, 0], [0, 1]])
        >>> ELLIPSOIDS.discrete_invariance([[0, 1], [-1, 0]], E, None, None, False).holds    # a rotation
        True
        """
        return ellipsoid_discrete_invariance(Ad, invariant_set, method, dt, allow_float=allow_float)

    def forward_euler(self, system, invariant_set, by_valid_set, gamma: Any = None) -> EllipsoidForwardEulerThreshold:
        """The generalised eigenvalue (:mod:`exactinv.thresholds.ellipsoid_forward_euler`) against the valid set.

        >>> import exactinv as ei
        >>> S, E = ei.LinearSystem([[-1, -2], [2, -1]]), ei.Ellipsoid([[1, 0], [0, 1]])
        >>> from exactinv.validset.engine import largest_threshold
        >>> fe = ELLIPSOIDS.forward_euler(S, E, largest_threshold(S, E, ei.methods.forward_euler()))
        >>> fe.by_eigenvalue, fe.by_valid_set
        (Fraction(2, 5), Fraction(2, 5))
        """
        by_eigenvalue = generalised_eigenvalue_step(system.A_flint, invariant_set.Q_flint)
        by_set = by_valid_set.value
        if by_set != by_eigenvalue:
            raise VerificationFailed(f"forward Euler on E: the eigenvalue route gives {by_eigenvalue}, "
                                     f"the valid set {by_set}")
        return EllipsoidForwardEulerThreshold(by_set, by_eigenvalue, by_set, system, invariant_set)


POLYHEDRA = Polyhedra()
ELLIPSOIDS = Ellipsoids()


def family_of(invariant_set: Any) -> SetFamily:
    """The family of ``invariant_set``: ELLIPSOIDS for an :class:`~exactinv.Ellipsoid`, else POLYHEDRA
    (whose argument check then names what is wrong with anything that is not a Polyhedron).

    >>> from exactinv.model import Ellipsoid, Polyhedron
    >>> family_of(Ellipsoid([[1]])).name, family_of(Polyhedron.box([0], [1])).name
    ('ellipsoid', 'polyhedron')
    """
    return ELLIPSOIDS if set_family(invariant_set) == "ellipsoid" else POLYHEDRA
