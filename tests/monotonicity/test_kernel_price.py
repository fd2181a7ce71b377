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


def _random_degree_64(seed):
    """1 + sum_k c_k z^k, k = 1..64, c_k = p/q with p, q uniform in [1, 2^100]: inside every up-front gate."""
    import random
    from fractions import Fraction
    rng = random.Random(seed)
    return ei.methods.polynomial([Fraction(1)] + [Fraction(rng.randint(1, 2**100), rng.randint(1, 2**100))
                                                  for _ in range(64)])


@pytest.mark.heavy
@pytest.mark.workload  # the kernel spends its whole budget (about 8 s): stage 2 of CI only
def test_a_certificate_past_the_gates_but_over_the_kernels_budget_is_undecided():
    """Session 5's residual: the engine answered this polynomial (rho from a coefficient) in about 1.5 s and the
    kernel refused the certificate after about 8 s of isolation, over its budget.  Now the engine, having spent
    more than TRIAL_SECONDS, asks the kernel first and says Undecided, naming the kernel's refusal."""
    method = _random_degree_64(1)
    num = list(method.numerator)
    assert scan_cost(num, [1], len(num)) <= SCAN_BUDGET  # the up-front gate admits it
    with pytest.raises(ei.Undecided, match="refuses its certificate as over its budget"):
        absolute_monotonicity_radius(method)


def test_a_kernel_rejection_of_an_engine_certificate_is_an_engine_bug_not_undecided():
    """A slow result whose claim the kernel rejects (a wrong rho) raises VerificationFailed: never returned, never
    hidden as Undecided."""
    from exactinv.monotonicity.kernel_price import TRIAL_SECONDS, kernel_tried
    good = absolute_monotonicity_radius(ei.methods.taylor(4))
    assert kernel_tried(good, TRIAL_SECONDS * 2) is good
    wrong = replace(good, value=good.value + 1)
    assert kernel_tried(wrong, TRIAL_SECONDS / 2) is wrong  # a fast result is not tried (the rule, stated)
    with pytest.raises(ei.VerificationFailed, match="rejects the engine's certificate"):
        kernel_tried(wrong, TRIAL_SECONDS * 2)


def test_a_slow_result_the_kernel_refuses_over_budget_is_undecided_naming_the_refusal():
    """The rule of kernel_tried without the kernel's whole budget: Pade(1,3)'s result with its tail index raised
    past the scan gate, as if the engine had spent long on it -- the kernel refuses it over budget at once."""
    from exactinv.monotonicity.kernel_price import TRIAL_SECONDS, kernel_tried
    over = replace(absolute_monotonicity_radius(ei.methods.pade(1, 3)), tail_index=2000)
    with pytest.raises(ei.Undecided, match="refuses its certificate as over its budget"):
        kernel_tried(over, TRIAL_SECONDS * 2)
