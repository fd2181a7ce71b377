"""The trusted kernel's price of a radius certificate, checked by the engine before it returns one (issue 22).

The rule: every certificate the engine writes is verified by the kernel within the kernel's budget
(exactinv_check.budget: CERTIFICATE_BUDGET word operations, about 40 s), or the engine says Undecided instead.  The
kernel refuses some work up front by its own cost model, before running it; the engine asks the same model (the
kernel's public estimates, imported from exactinv_check -- the engine may read the kernel, never the reverse):

* the coefficient polynomials d_0 .. d_(N-1) of a claim with a tail index N (reasons coefficient, tie, termwise):
  exactinv_check.claims_radius.scan_cost against exactinv_check.budget.SCAN_BUDGET.

A result over a gate becomes :class:`exactinv.errors.Undecided` naming the gate ("over the kernel's budget").  What
the kernel charges as it runs (isolations, products) is not predicted by the gates: a random polynomial of degree 64
with 100-bit coefficients passes them, and the kernel then spends its whole budget isolating.  So a result whose
engine run took longer than TRIAL_SECONDS of CPU is checked by the kernel itself (:func:`kernel_tried`) before it
is returned; the kernel's work runs some 1-8x the engine's on genuine certificates, so a faster engine run is far
inside the budget.  tests/kernel/test_genuine_fuzz.py runs the engine's radius on the fuzz families and asserts
that no certificate is over the budget.
"""

from __future__ import annotations

import exactinv_check
from exactinv_check.budget import SCAN_BUDGET
from exactinv_check.claims_radius import scan_cost
from exactinv_check.format import Verdict

from ..errors import Undecided, VerificationFailed
from .result import AbsoluteMonotonicityRadius

__all__ = ["priced", "kernel_tried", "TRIAL_SECONDS"]

TRIAL_SECONDS = 0.25  # engine CPU seconds past which the kernel checks a radius certificate before it is returned


def priced(result: AbsoluteMonotonicityRadius) -> AbsoluteMonotonicityRadius:
    """``result`` itself when the kernel's up-front gates admit its claim, else Undecided (module docstring).

    Pade(1,3) (tail index 78, deg h = 3) is far inside the gate:

    >>> from exactinv.model import methods
    >>> from exactinv.monotonicity.radius import absolute_monotonicity_radius
    >>> priced(absolute_monotonicity_radius(methods.pade(1, 3))).tail_index
    78
    """
    num, den = list(result.method.numerator), list(result.method.denominator)
    count = max(result.tail_index or 0, len(num), len(den), 1)
    estimate = scan_cost(num, den, count)
    if estimate > SCAN_BUDGET:
        raise Undecided(f"absolute monotonicity of {result.method.name}: rho = {result.value} ({result.reason}, tail index "
                        f"{result.tail_index}) is decided, but its certificate is over the kernel's budget: the "
                        f"coefficient polynomials d_0 .. d_{count - 1} are estimated at {estimate:.2e} word operations "
                        f"> {SCAN_BUDGET:.0e} (exactinv_check.budget.SCAN_BUDGET), so the kernel would refuse it")
    return result


def kernel_tried(result: AbsoluteMonotonicityRadius, engine_seconds: float) -> AbsoluteMonotonicityRadius:
    """``result`` itself if the engine took at most TRIAL_SECONDS or the kernel accepts its certificate; Undecided if
    the kernel refuses it as over its budget; VerificationFailed (an engine bug) if the kernel rejects it otherwise.

    >>> from exactinv.model import methods
    >>> from exactinv.monotonicity.radius import absolute_monotonicity_radius
    >>> kernel_tried(absolute_monotonicity_radius(methods.taylor(4)), engine_seconds=1.0).value
    Fraction(1, 1)
    """
    if engine_seconds <= TRIAL_SECONDS:
        return result
    report = exactinv_check.check(result.certificate)
    if report.ok:
        return result
    if report.kind == Verdict.OVER_BUDGET:
        raise Undecided(f"absolute monotonicity of {result.method.name}: rho = {result.value} ({result.reason}) is "
                        f"decided, but the trusted kernel refuses its certificate as over its budget: {report}")
    raise VerificationFailed(f"absolute monotonicity of {result.method.name}: the trusted kernel rejects the engine's "
                             f"certificate of rho = {result.value} ({result.reason}): {report}")
