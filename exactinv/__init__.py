"""exactinv: exact steplength thresholds for invariance preserving discretizations.

A symbolic-exact verifier for Horvath, Song and Terlaky, "Steplength
thresholds for invariance preserving of discretization methods of dynamical
systems on a polyhedron".  Every reported number is a Fraction, an exact
real algebraic number with a certified rational enclosure, or infinity, and
comes with a certificate that the standard-library checker
(:mod:`exactinv.check`) re-verifies.

>>> import exactinv as ei
>>> S = ei.LinearSystem([[-1, 1], [-1, -1]])
>>> P = ei.Polyhedron.box([-1, -1], [1, 1])
>>> ei.optimal_gamma(S, P).value
Fraction(1, 1)
>>> ei.steplength_threshold(S, P, ei.methods.taylor(4)).value
Fraction(1, 1)
"""

from . import display, methods, oracle
from .algebraic import RealAlgebraic
from .check import check
from .errors import EmptyPolyhedron, ExactinvError, InvalidInput, NotInvariant, Undecided, VerificationFailed
from .invariance import (
    ContinuousInvariance,
    DiscreteInvariance,
    FacetWitness,
    OptimalGamma,
    continuous_invariance,
    discrete_invariance,
    optimal_gamma,
)
from .largest import (
    ForwardEulerThreshold,
    LargestThreshold,
    ThresholdComparison,
    ValidSteplengths,
    compare_thresholds,
    forward_euler_threshold,
    largest_threshold,
    valid_steplengths,
)
from .methods import Method
from .model import LinearSystem, Polyhedron
from .monotonicity import AbsoluteMonotonicityRadius, absolute_monotonicity_radius
from .numbers import INF, Infinity, exact_from_float, nearest_rational
from .roots import first_sign_change, nonnegative_until, real_roots
from .thresholds import SteplengthThreshold, steplength_threshold

__version__ = "0.1.0"

__all__ = [
    "AbsoluteMonotonicityRadius",
    "absolute_monotonicity_radius",
    "INF",
    "Infinity",
    "ContinuousInvariance",
    "DiscreteInvariance",
    "EmptyPolyhedron",
    "ExactinvError",
    "FacetWitness",
    "ForwardEulerThreshold",
    "LargestThreshold",
    "ThresholdComparison",
    "ValidSteplengths",
    "compare_thresholds",
    "forward_euler_threshold",
    "largest_threshold",
    "valid_steplengths",
    "InvalidInput",
    "LinearSystem",
    "Method",
    "NotInvariant",
    "OptimalGamma",
    "Polyhedron",
    "RealAlgebraic",
    "SteplengthThreshold",
    "Undecided",
    "VerificationFailed",
    "check",
    "continuous_invariance",
    "discrete_invariance",
    "exact_from_float",
    "first_sign_change",
    "display",
    "methods",
    "oracle",
    "nearest_rational",
    "nonnegative_until",
    "optimal_gamma",
    "real_roots",
    "steplength_threshold",
]
