"""One valid-set problem: a system x' = Ax, an invariant set and a method, checked once (docs/design.md,
"The route protocol").

What every route needs is computed here once: the set's family
(:mod:`.families`), D(h) = det h(hA) (the poles of r(hA)), and -- built
lazily -- a polyhedron's :class:`~exactinv.conditions.polyhedron.ConditionSet`
(shared by the routes, and between the valid set and the largest threshold
when a caller passes one) or an ellipsoid's coefficient polynomials.
"""

from __future__ import annotations

from fractions import Fraction
from functools import cached_property
from typing import Any

import flint

from ..conditions.ellipsoid import psd_polynomials
from ..conditions.polyhedron import ConditionSet
from ..core.flintq import fraction_of
from ..errors import InvalidInput
from .families import SetFamily, family_of

__all__ = ["ValidSetProblem"]


class ValidSetProblem:
    """(system, invariant set, method), checked; ``prune`` and ``box`` are the vertex route's
    pruning and whether ``route="auto"`` may take the box route; ``conditions`` a shared
    :class:`ConditionSet` of the same polyhedral problem (None: built here).

    >>> import exactinv as ei
    >>> p = ValidSetProblem(ei.LinearSystem([[-1]]), ei.Polyhedron.box([-1], [1]), ei.methods.backward_euler())
    >>> p.family.name, p.Dcoeffs
    ('polyhedron', [Fraction(1, 1), Fraction(1, 1)])
    """

    def __init__(self, system: Any, invariant_set: Any, method: Any, *, conditions: ConditionSet | None = None,
                 prune: bool = True, box: bool = True):
        for name, flag in (("prune", prune), ("box", box)):
            if not isinstance(flag, bool):
                raise InvalidInput(f"{name}: expected True or False, got {flag!r}")
        self.family: SetFamily = family_of(invariant_set)
        self.system, self.invariant_set, self.method, self._conditions = self.family.checked(
            system, invariant_set, method, conditions)
        self.prune, self.box = prune, box

    @property
    def conditions(self) -> ConditionSet:
        """The polyhedron's ConditionSet (the routes of a polyhedron only)."""
        if self._conditions is None:
            raise InvalidInput(f"conditions: a {self.family.name} has no vertex-facet conditions")
        return self._conditions

    @cached_property
    def coefficient_polynomials(self) -> tuple[list[flint.fmpq_poly], flint.fmpq_poly]:
        """An ellipsoid's ([q_1, .., q_n], D) (:func:`~exactinv.conditions.ellipsoid.psd_polynomials`)."""
        return psd_polynomials(self.system, self.invariant_set.Q_flint, self.method)

    @property
    def D(self) -> flint.fmpq_poly:
        """D(h) = det h(hA): r(hA) is singular exactly at its roots."""
        if self._conditions is not None:
            return self._conditions.D
        return self.coefficient_polynomials[1]

    @property
    def Dcoeffs(self) -> list[Fraction]:
        return [fraction_of(c) for c in self.D.coeffs()]

    def __repr__(self) -> str:
        return f"ValidSetProblem({self.family.name}, n = {self.system.n}, method={self.method.name})"
