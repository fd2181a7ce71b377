"""exactinv.monotonicity.kernel_price: the engine asks the kernel's own cost model before it returns a radius, and
says Undecided exactly where the kernel's up-front gate on the coefficient polynomials would refuse the claim."""

from dataclasses import replace

import pytest

import exactinv as ei
from exactinv.monotonicity.kernel_price import priced
from exactinv.monotonicity.radius import absolute_monotonicity_radius
from exactinv_check import check
from exactinv_check.budget import SCAN_BUDGET
from exactinv_check.claims_radius import scan_cost


@pytest.mark.parametrize("tail_index", [78, 400, 900, 2000])
def test_the_engine_refuses_what_the_kernels_scan_gate_refuses(tail_index):
    """Pade(1,3) (rho ~ 1.1955, tail index 78) with its tail index raised: under the gate the result is returned
    as it is; over it, Undecided naming the kernel's budget -- and the kernel, given that claim, refuses it over
    budget by the same gate."""
    method = ei.methods.pade(1, 3)
    result = replace(absolute_monotonicity_radius(method), tail_index=tail_index)
    over = scan_cost(list(method.numerator), list(method.denominator), tail_index) > SCAN_BUDGET
    if not over:
        assert priced(result) is result
        return
    with pytest.raises(ei.Undecided, match="over the kernel's budget"):
        priced(result)
    report = check(result.certificate)
    assert report.kind == "over-budget" and "coefficient polynomials" in str(report)


def test_both_outcomes_are_reached():
    """The parametrisation above is not vacuous: 78 is under the gate and 2000 over it."""
    method = ei.methods.pade(1, 3)
    num, den = list(method.numerator), list(method.denominator)
    assert scan_cost(num, den, 78) <= SCAN_BUDGET < scan_cost(num, den, 2000)
