"""The paper's valid steplength threshold for any method (Section 3): the
polynomial theorems (:mod:`.polynomial`) or the rational one (:mod:`.rational`)."""

from __future__ import annotations

from ..errors import NotInvariant
from ..model import LinearSystem, Method, Polyhedron
from ..model.validate import check_method
from .gamma_star import OptimalGamma, gamma_for
from .polynomial import SteplengthThreshold, polynomial_threshold
from .rational import rational_threshold

__all__ = ["steplength_threshold"]


def steplength_threshold(system: LinearSystem, polyhedron: Polyhedron, method: Method, *,
                         gamma: OptimalGamma | None = None) -> SteplengthThreshold:
    """The paper's valid threshold for ``method`` on P, with gamma = gamma* (``gamma``: gamma* of
    this pair if already computed, :func:`~exactinv.paper.gamma_star.gamma_for`).

    Polynomial methods: Theorem 3.4 (tau = min_i tau_i); rational methods:
    Theorem 3.12, corrected by errata E2 and E2'.  Raises
    :class:`~exactinv.NotInvariant` (carrying the witness) when P is not
    invariant for x' = Ax: the paper's theorems then give nothing.

    >>> import exactinv as ei
    >>> S, P = ei.LinearSystem([[-1, 1], [-1, -1]]), ei.Polyhedron.box([-1, -1], [1, 1])
    >>> steplength_threshold(S, P, ei.methods.taylor(2)).value
    Fraction(1, 1)
    """
    check_method(method)
    gamma = gamma_for(system, polyhedron, gamma)
    if gamma.witness is not None:
        raise NotInvariant("P is not invariant for x' = Ax (gamma* = +oo); no threshold exists", gamma.witness)
    if method.is_polynomial:
        return polynomial_threshold(method, gamma)
    return rational_threshold(method, gamma)
