"""The trusted kernel's price of a radius certificate, checked by the engine before it returns one (issue 22).

The rule: every certificate the engine writes is verified by the kernel within the kernel's budget
(exactinv_check.budget: CERTIFICATE_BUDGET word operations, about 40 s), or the engine says Undecided instead.  The
kernel refuses some work up front by its own cost model, before running it; the engine asks the same model (the
kernel's public estimates, imported from exactinv_check -- the engine may read the kernel, never the reverse):

* the coefficient polynomials d_0 .. d_(N-1) of a claim with a tail index N (reasons coefficient, tie, termwise):
  exactinv_check.claims_radius.scan_cost against exactinv_check.budget.SCAN_BUDGET.

A result over a gate becomes :class:`exactinv.errors.Undecided` naming the gate ("over the kernel's budget").  What
the kernel charges as it runs (isolations, products) is not predicted here; tests/kernel/test_genuine_fuzz.py runs
the engine's radius on the fuzz families and asserts that no certificate is over the budget.
"""

from __future__ import annotations

from exactinv_check.budget import SCAN_BUDGET
from exactinv_check.claims_radius import scan_cost

from ..errors import Undecided
from .result import AbsoluteMonotonicityRadius

__all__ = ["priced"]


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
