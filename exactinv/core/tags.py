"""The tags that results and certificates carry, as ``StrEnum``s.

A ``StrEnum`` member is its string (``ClaimType.GAMMA_STAR == "gamma_star"``,
``json.dumps`` writes ``"gamma_star"``), so certificates and tests read the
same as with plain strings, while the code names each tag once.  (The LP
engine's own tags are :class:`exactinv.lp.hint.LPStatus` and
:class:`exactinv.lp.solver.LPPath`; the oracle's verdicts are
:class:`exactinv.interfaces.oracle.Status`; the generator kinds of the valid
sets are :class:`exactinv.beyond.conditions.Kind`.)

>>> import json
>>> ClaimType.GAMMA_STAR == "gamma_star", json.dumps({"type": ClaimType.GAMMA_STAR})
(True, '{"type": "gamma_star"}')
"""

from __future__ import annotations

from enum import StrEnum

__all__ = ["Tag", "ClaimType", "RadiusReason", "BisectionStep", "CounterexampleKind"]


class Tag(StrEnum):
    """A tag that also *prints* as its string, so that claims and result reprs
    read as the certificate does.

    >>> repr(ClaimType.GAMMA_STAR), {"type": ClaimType.GAMMA_STAR}
    ("'gamma_star'", {'type': 'gamma_star'})
    """

    def __repr__(self) -> str:
        return repr(self.value)


class ClaimType(Tag):
    """The ``"type"`` of a claim in a certificate (docs/certificate-format.md)."""

    GAMMA_STAR = "gamma_star"
    CONTINUOUS_INVARIANCE = "continuous_invariance"
    DISCRETE_INVARIANCE = "discrete_invariance"
    POLYNOMIAL_THRESHOLD = "polynomial_threshold"
    RATIONAL_THRESHOLD = "rational_threshold"
    FORWARD_EULER_THRESHOLD = "forward_euler_threshold"
    ABSOLUTE_MONOTONICITY_RADIUS = "absolute_monotonicity_radius"
    VALID_STEPLENGTHS = "valid_steplengths"
    LARGEST_THRESHOLD = "largest_threshold"
    ELLIPSOID_CONTINUOUS_INVARIANCE = "ellipsoid_continuous_invariance"
    ELLIPSOID_DISCRETE_INVARIANCE = "ellipsoid_discrete_invariance"
    ELLIPSOID_VALID_STEPLENGTHS = "ellipsoid_valid_steplengths"
    ELLIPSOID_LARGEST_THRESHOLD = "ellipsoid_largest_threshold"
    ELLIPSOID_FORWARD_EULER_THRESHOLD = "ellipsoid_forward_euler_threshold"
    OPTIMAL_GAIN = "optimal_gain"
    ROBUST_THRESHOLD = "robust_threshold"


class RadiusReason(Tag):
    """Why the absolute monotonicity radius rho (Def. 3.11) has its value."""

    COEFFICIENT = "coefficient"  # c_binding changes sign at rho
    ALL_COEFFICIENTS = "all-coefficients"  # every coefficient stays >= 0: rho = INF
    NO_POSITIVE_POLE = "no-positive-pole"
    PRINCIPAL_PART_SIGN = "principal-part-sign"
    DOMINANCE_AT_0 = "dominance-at-0"
    NEGATIVE_AT_0 = "negative-at-0"  # rho = 0: the scan found c_j(0) < 0 (a witness needs no tail)
    TIE = "tie"  # p* wins the equal-modulus tie at rho = kappa_A (exact root of the tie polynomial)
    PRODUCT = "product"  # rho = INF: r is a product of absolutely monotonic factors
    TERMWISE = "termwise"  # rho = INF: every partial-fraction term is absolutely monotonic
    BALANCED_TIE = "balanced-tie"  # two simple real poles whose residues balance exactly: rho = kappa* (closed form)
    BERNSTEIN = "bernstein"  # rho = INF: r(-x) = c + Laplace transform of f >= 0 (Bernstein's theorem)
    BERNSTEIN_ROOT = "bernstein-root"  # c < 0, f >= 0: rho = the one positive root of g(-kappa), attained


class BisectionStep(Tag):
    """The step of the paper's bisection (Section 3.1.2) that returned."""

    STEP_2 = "step 2"
    STEP_3 = "step 3"
    STEP_4 = "step 4 (termination 3)"
    STEP_5 = "step 5"


class CounterexampleKind(Tag):
    """The ``"kind"`` of an oracle counterexample to a claimed LP value."""

    INFEASIBLE = "infeasible"  # a Farkas vector: the exact LP has no feasible point
    UNBOUNDED = "unbounded"  # a feasible point beating the claim, and a ray
    BETTER_POINT = "better_point"  # a feasible point beating the claimed optimum
    DUAL_BOUND = "dual_bound"  # a dual vector proving the claim unattainable
