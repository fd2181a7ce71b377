"""exactinv_check.resultants (quotient polynomials of algebraic numbers) and long-coefficient roots, attacked.

Each test builds a certificate that the kernel mishandles and asserts the
CORRECT behaviour: a false claim must be rejected, a genuine certificate
accepted, and no input may make ``check`` raise or run (practically) forever.
These tests fail until the kernel is fixed.
"""


import random

import pytest
from test_kernel_attacks import _cert, _check_in_subprocess  # shared helpers

pytestmark = pytest.mark.workload  # the kernel's own workload: left out at the lowest versions (.ci/run stage 3)


E2_PROBLEM = {"A": [["0", "1/3"], ["1/3", "1/3"]], "G": [["-1", "0"], ["0", "-1"]], "b": ["0", "0"],
              "method": {"name": "rational", "numerator": ["1"], "denominator": ["1", "-1", "1/5"]}}


E2_CLAIMS = [  # written by the engine (optimal_gamma, absolute_monotonicity_radius); both verify
    {"type": "gamma_star", "value": "0", "paths": {"float-rounded": 2}, "H": [["0", "1/3"], ["1/3", "1/3"]],
     "binding_row": 0, "dual": {"y": ["-1", "0"], "lambda": "0"}},
    {"type": "absolute_monotonicity_radius", "value": "oo", "reason": "product", "attained": True,
     "pole": {"poly": ["5", "-5", "1"], "interval": ["1105572809/800000000", "1381966011251/1000000000000"]}},
]


def _e2_cert(threshold_claim):
    return {"format": "exactinv-certificate", "version": 2, "problem": E2_PROBLEM,
            "claims": E2_CLAIMS + [threshold_claim]}


# ------------------------------------------------------------------ soundness

def test_a_false_rational_threshold_from_a_wrong_quotient_is_rejected():
    # tau = 2.5020... (the kernel's wrong z_p/alpha) instead of 2.5623...: the
    # kernel VERIFIES this false claim.
    from exactinv_check import check

    cert = _e2_cert({"type": "rational_threshold",
                     "value": {"poly": ["75", "10475", "-9020", "2545", "-247"], "interval": ["1", "4"]},
                     "attained": False, "rho": "oo"})
    assert not check(cert).ok


def test_the_true_rational_threshold_z_p_over_alpha_is_accepted():
    # The true tau = root of x^2 + 15x - 45 in (2.562305898749, 2.5623058987...)
    # is rejected ("tau is not min(...) = root of [75, 10475, ...]").
    from exactinv_check import check

    cert = _e2_cert({"type": "rational_threshold",
                     "value": {"poly": ["-45", "15", "1"],
                               "interval": ["2562305898749/1000000000000", "2049844719/800000000"]},
                     "attained": False, "rho": "oo"})
    assert check(cert).ok


# ------------------------------------------------------------------ resource

def test_a_bounded_degree_algebraic_number_with_long_coefficients_is_rejected_quickly():
    rng = random.Random(1)
    poly = [str(rng.randint(-10**30, 10**30)) for _ in range(200)] + ["1"]  # degree 200, ~6 KB
    cert = _cert([{"type": "absolute_monotonicity_radius", "value": {"poly": poly, "interval": ["0", "2"]},
                   "reason": "coefficient", "attained": True}],
                 method=(["1", "1"], ["1"]))
    assert _check_in_subprocess(cert, 60) == "REJECTED"


def test_a_forged_threshold_with_long_coefficients_is_rejected_quickly():
    # The same cost reached through a valid_steplengths claim: a forged end
    # (degree 60, 1000-digit coefficients, ~60 KB) about a trivial problem.
    # x' = -x, P = [-1, 1], forward Euler: the valid set is [0, 2].
    rng = random.Random(2)
    poly = [str(rng.randint(-10**1000, 10**1000)) for _ in range(60)] + ["1"]
    cert = _cert([{"type": "valid_steplengths",
                   "intervals": [{"lo": "0", "hi": {"poly": poly, "interval": ["1", "3"]},
                                  "lo_closed": True, "hi_closed": True}],
                   "vertices": [["-1"], ["1"]], "rays": [], "lines": []}],
                 method=(["1", "1"], ["1"]), A=[["-1"]], G=[["1"], ["-1"]], b=["1", "1"])
    assert _check_in_subprocess(cert, 60) == "REJECTED"


def test_quotient_of_two_cubic_irrationals_does_not_hang():
    # dp*dq odd: the T = 0 sample has the wrong sign.  Orthant, A with
    # characteristic polynomial x^3 - x - 1 (alpha = 1.3247..., plastic number),
    # r = 1/(1 - 3z + 2z^2 - z^3/3) with three positive poles (rho = oo, the
    # smallest z_p = 0.4679..., a root of x^3 - 6x^2 + 9x - 3).  True tau =
    # z_p/alpha = 0.3532... (not attained); the claimed "1" is false, but the
    # kernel never gets to compare: quotient() bisects without end (> 90 s
    # measured; the true value hangs the same way).
    cert = {"format": "exactinv-certificate", "version": 2,
            "problem": {"A": [["0", "1", "0"], ["0", "0", "1"], ["1", "1", "0"]],
                        "G": [["-1", "0", "0"], ["0", "-1", "0"], ["0", "0", "-1"]], "b": ["0", "0", "0"],
                        "method": {"name": "rational", "numerator": ["1"], "denominator": ["1", "-3", "2", "-1/3"]}},
            "claims": [{"type": "gamma_star", "value": "0", "paths": {"float-rounded": 3},
                        "H": [["0", "1", "0"], ["0", "0", "1"], ["1", "1", "0"]], "binding_row": 0,
                        "dual": {"y": ["-1", "0", "0"], "lambda": "0"}},
                       {"type": "absolute_monotonicity_radius", "value": "oo", "reason": "product", "attained": True,
                        "pole": {"poly": ["-3", "9", "-6", "1"],
                                 "interval": ["233955556881/500000000000", "467911113763/1000000000000"]}},
                       {"type": "rational_threshold", "value": "1", "attained": False, "rho": "oo"}]}
    assert _check_in_subprocess(cert, 60) == "REJECTED"
