"""Control (issue 25): the gain that minimizes gamma* (so maximizes every method's
certified threshold) and robust thresholds over a polytope of matrices.

This room sits above ``thresholds`` and beside ``validset`` (it joins them: the closed
loop's thresholds and valid sets), below ``interfaces``.
"""

from .optimal_gain import OptimalGain, optimal_gain
from .robust import RobustThreshold, robust_threshold

__all__ = ["OptimalGain", "optimal_gain", "RobustThreshold", "robust_threshold"]
