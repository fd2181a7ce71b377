"""The engine's own tags, as ``StrEnum``s: the steps of the paper's bisection and the kinds of
an oracle counterexample.

The tags a certificate carries -- claim types, radius reasons, generator kinds -- belong to
the certificate format and are defined once, in :mod:`exactinv_check.format` (``ClaimType``,
``RadiusReason``, ``GeneratorKind``); the engine imports them from there.  A ``StrEnum``
member is its string, and a :class:`Tag` also prints as its string.  (The LP engine's own
tags are :class:`exactinv.lp.hint.LPStatus` and :class:`exactinv.lp.solver.LPPath`; the
oracle's verdicts are :class:`exactinv.interfaces.oracle.Status`; the generator kinds of the
valid sets are :class:`exactinv.conditions.polyhedron.Kind`.)

>>> BisectionStep.STEP_2 == "step 2", repr(CounterexampleKind.INFEASIBLE)
(True, "'infeasible'")
"""

from __future__ import annotations

import warnings

from exactinv_check import format as _format
from exactinv_check.format import Tag

__all__ = ["Tag", "BisectionStep", "CounterexampleKind"]

_MOVED = ("ClaimType", "RadiusReason")


def __getattr__(name: str):
    """``ClaimType`` and ``RadiusReason`` moved to :mod:`exactinv_check.format` (deprecated here)."""
    if name in _MOVED:
        warnings.warn(f"exactinv.core.tags.{name} is deprecated: import it from exactinv_check.format",
                      DeprecationWarning, stacklevel=2)
        return getattr(_format, name)
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")


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
