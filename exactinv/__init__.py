"""exactinv: exact steplength thresholds for invariance preserving discretizations.

A symbolic-exact verifier for Horvath, Song and Terlaky, "Steplength
thresholds for invariance preserving of discretization methods of dynamical
systems on a polyhedron".  Every reported number is a Fraction, an exact
real algebraic number with a certified rational enclosure, or infinity, and
comes with a certificate that the trusted kernel -- the separate,
standard-library-only package :mod:`exactinv_check` -- re-verifies
(``exactinv.check`` is ``exactinv_check.check``).

The package is layered; imports point one way only (tests/test_layering.py):
errors <- core <- lp <- model <- {invariance, monotonicity, conditions} <- thresholds
<- {validset, control, certificates} <- interfaces.

>>> import exactinv as ei
>>> S = ei.LinearSystem([[-1, 1], [-1, -1]])
>>> P = ei.Polyhedron.box([-1, -1], [1, 1])
>>> ei.optimal_gamma(S, P).value
Fraction(1, 1)
>>> ei.steplength_threshold(S, P, ei.methods.taylor(4)).value
Fraction(1, 1)
>>> ei.largest_threshold(S, ei.Ellipsoid([[1, 0], [0, 1]]), ei.methods.forward_euler()).value
Fraction(1, 1)
"""

from exactinv_check import check  # the trusted kernel: a separate, standard-library-only package

from .conditions.polyhedron import ConditionSet
from .control import OptimalGain, RobustThreshold, optimal_gain, robust_threshold
from .core import scalars as numbers  # noqa: F401 (ei.numbers: the exact input conversions)
from .core.moved import install_moved_modules
from .core.real_algebraic import RealAlgebraic
from .core.roots import first_sign_change, nonnegative_until, real_roots
from .core.scalars import INF, Infinity, exact_from_float, nearest_rational
from .errors import EmptyPolyhedron, ExactinvError, InvalidInput, NotInvariant, Undecided, VerificationFailed
from .interfaces import display, oracle
from .interfaces.batch import BatchSummary, run_batch
from .interfaces.compare import ThresholdComparison, compare_thresholds
from .invariance.ellipsoids import EllipsoidInvariance, QuadraticWitness
from .invariance.polyhedra import (
    ContinuousInvariance,
    DiscreteInvariance,
    FacetWitness,
    OptimalGamma,
    optimal_gamma,
)
from .model import Ellipsoid, LinearSystem, Method, Polyhedron, methods
from .monotonicity.radius import AbsoluteMonotonicityRadius, absolute_monotonicity_radius
from .thresholds.forward_euler import ForwardEulerThreshold
from .thresholds.polynomial import SteplengthThreshold
from .thresholds.steplength import steplength_threshold
from .validset.engine import (
    continuous_invariance,
    discrete_invariance,
    forward_euler_threshold,
    largest_threshold,
    valid_steplengths,
)
from .validset.results import (
    EllipsoidForwardEulerThreshold,
    EllipsoidLargestThreshold,
    EllipsoidValidSteplengths,
    LargestThreshold,
    ValidSteplengths,
)

__version__ = "0.1.0"

install_moved_modules()  # exactinv.paper.* and exactinv.beyond.* (issue 26) still import, with a warning

__all__ = [
    "AbsoluteMonotonicityRadius",
    "absolute_monotonicity_radius",
    "BatchSummary",
    "run_batch",
    "INF",
    "Infinity",
    "ContinuousInvariance",
    "DiscreteInvariance",
    "Ellipsoid",
    "EllipsoidForwardEulerThreshold",
    "EllipsoidInvariance",
    "EllipsoidLargestThreshold",
    "EllipsoidValidSteplengths",
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
    "ConditionSet",
    "InvalidInput",
    "LinearSystem",
    "Method",
    "NotInvariant",
    "OptimalGamma",
    "Polyhedron",
    "QuadraticWitness",
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
    "optimal_gain",
    "OptimalGain",
    "robust_threshold",
    "RobustThreshold",
    "real_roots",
    "steplength_threshold",
]
