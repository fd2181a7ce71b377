"""The paper's valid steplength threshold for any method (Section 3): the
polynomial theorems (:mod:`.polynomial`) or the rational one (:mod:`.rational`)."""

from __future__ import annotations

from ..errors import NotInvariant
from ..invariance.gamma_star import OptimalGamma, optimal_gamma
from ..model import LinearSystem, Method, Polyhedron
from ..model.validate import check_method
from .polynomial import SteplengthThreshold, polynomial_threshold
from .rational import rational_threshold

__all__ = ["steplength_threshold"]


def steplength_threshold(system: LinearSystem, polyhedron: Polyhedron, method: Method) -> SteplengthThreshold:
    """The paper's valid threshold for ``method`` on P, with gamma = gamma*.

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
    return steplength_threshold_from_gamma(method, optimal_gamma(system, polyhedron))


def steplength_threshold_from_gamma(method: Method, gamma: OptimalGamma) -> SteplengthThreshold:
    """:func:`steplength_threshold` with gamma* already solved by
    :func:`~exactinv.invariance.gamma_star.optimal_gamma` (exactinv.certify solves it once for all claims).

    >>> import exactinv as ei
    >>> S, P = ei.LinearSystem([[-1]]), ei.Polyhedron.box([-1], [1])
    >>> steplength_threshold_from_gamma(ei.methods.taylor(2), ei.optimal_gamma(S, P)).value
    Fraction(2, 1)
    """
    if gamma.witness is not None:
        raise NotInvariant("P is not invariant for x' = Ax (gamma* = +oo); no threshold exists", gamma.witness)
    if method.is_polynomial:
        return polynomial_threshold(method, gamma)
    return rational_threshold(method, gamma)
